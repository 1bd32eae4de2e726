/* Internals of mfs_static shared by its two files (mfs_static.c: assembly,
 * solution, errors; mfs_static_problems.c: the problems' geometry and closed
 * forms).  Not installed. */
#ifndef MFS_STATIC_IMPL_H
#define MFS_STATIC_IMPL_H

#include "mfs_neighbor.h"
#include "mfs_static.h"

enum { SEG_TRACTION, SEG_FREE }; /* exact traction sigma n, or none (the patch test: all sigma n) */

typedef struct {
  int a, b;       /* nodes, counter-clockwise along the boundary */
  int kind;       /* SEG_TRACTION, SEG_FREE */
  unsigned fixed; /* essential components: bit 0 u_x, bit 1 u_y */
  double n[2];    /* outward unit normal */
  double len;
} segment;

/* A boundary quadrature point. */
typedef struct {
  double x[2], n[2], w;
  int node;      /* the node at the point (nodal rule), or -1 */
  size_t seg;    /* its segment */
  double t;      /* position along the segment, 0 at a, 1 at b */
} bpoint;

struct mfs_static {
  mfs_static_spec s;
  const mfs_quad_type *qt; /* the rule in use */
  mfs_particles *p;        /* owned */
  mfs_quad *gq;            /* background cells, 5 x 5 Gauss */
  mfs_quad *eq;            /* the points of the error norms: gq, or its cells in the domain */
  double *evol;            /* node weights of the nodal errors (the volume in the domain) */
  unsigned char *pinned;   /* nodes whose parameters are prescribed (spec.ghost) */
  mfs_quad *q;             /* the assembly rule (owned, or gq) */
  size_t gq_block, q_block; /* points per block (cell), 1 for nodal */
  segment *seg;
  size_t nseg, seg_cap;
  bpoint *bp;
  size_t nbp;
  double h, a;
  double D[9], Dinv[9];
  mfs_grid *grid;
  double patch_c[2], patch_G[4];
  /* assembly */
  mfs_csr *K;
  double *f;
  size_t m;                /* multipliers */
  mfs_csr *Ctr, *Cte;      /* m x 2n, scaled by cscale */
  double *g;
  double cscale;
  int assembled, eliminated, solved;
  size_t max_nn;
  double *u;               /* 2n nodal parameters */
  mfs_spsolve_info sinfo;
  const mfs_spsolve_type *solver;
};

/* Append the boundary segment from node a to node b (counter-clockwise). */
int mfs_static_impl_add_segment(mfs_static *m, int a, int b, int kind, unsigned fixed);

/* Gauss-Legendre points and weights on [0, 1]; MFS_OK or MFS_ENOMEM. */
int mfs_static_impl_gauss01(int n, double *t, double *w);

#endif
