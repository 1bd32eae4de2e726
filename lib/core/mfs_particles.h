/* Particle sets: lattices in 1D and 2D, finite or periodic boxes, seeded
 * random perturbation, particle volumes, and the background cells (intervals,
 * quadrilaterals, triangles) that quadrature rules are built on; and sets
 * given as arrays (a user's file), with their volumes or the dual areas of
 * their Delaunay triangulation (mfs_delaunay.h). */
#ifndef MFS_PARTICLES_H
#define MFS_PARTICLES_H

#include <math.h>
#include <stddef.h>
#include "mfs_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* MFS_LATTICE_POINTS: no lattice, a particle set given as arrays (1D or 2D). */
typedef enum {
  MFS_LATTICE_LINE,
  MFS_LATTICE_SQUARE,
  MFS_LATTICE_HEX,
  MFS_LATTICE_POINTS
} mfs_lattice_kind;

/* How square cells are split: kept as quadrilaterals, cut by one diagonal
 * (paper 003 Fig. 12b), or by alternating diagonals (the star, Fig. 12c). */
typedef enum { MFS_CELLS_QUAD, MFS_CELLS_TRI, MFS_CELLS_STAR } mfs_cell_kind;

/* Boundary flags of a particle of a finite box; of a particle set: the ends
 * (1D, XLO and XHI) or the vertices of the convex hull (2D, HULL). */
enum { MFS_BND_XLO = 1, MFS_BND_XHI = 2, MFS_BND_YLO = 4, MFS_BND_YHI = 8, MFS_BND_HULL = 16 };

/* A box: [lo, hi] per direction, periodic (all directions) or not. */
typedef struct {
  int dim;
  double lo[3], hi[3];
  int periodic;
} mfs_box;

/* Displacement b - a, with the minimum image when the box is periodic.
 * Inline: it is called once per neighbour in every table build. */
static inline void mfs_box_delta(const mfs_box *box, const double *a, const double *b, double *d)
{
  for (int k = 0; k < box->dim; k++) {
    double t = b[k] - a[k];
    if (box->periodic) {
      double L = box->hi[k] - box->lo[k];
      t -= L * nearbyint(t / L);
    }
    d[k] = t;
  }
}

/* The same in 1D, b - a with the minimum image: equal to mfs_box_delta for
 * |b - a| < 1.5 L, without its division and nearbyint (hot loops). */
static inline double mfs_box_delta1(const mfs_box *box, double a, double b)
{
  double t = b - a;
  if (box->periodic) {
    double L = box->hi[0] - box->lo[0];
    if (fabs(t) >= 1.5 * L)
      t -= L * nearbyint(t / L);
    else if (t > 0.5 * L)
      t -= L;
    else if (t < -0.5 * L)
      t += L;
  }
  return t;
}

/* What to build. */
typedef struct {
  int dim;                  /* 1 or 2 */
  mfs_lattice_kind lattice; /* line (dim 1), square or hex (dim 2) */
  int nx, ny;               /* nodes per direction; ny unused in 1D */
  double dx;                /* nearest-neighbour spacing */
  double gamma;             /* dy/dx of the square lattice (1 if 0) */
  int periodic;             /* periodic box: nx*dx by ny*dy, ny even for hex */
  mfs_cell_kind cells;      /* square lattice only; hex is always triangles */
  double perturb;           /* random shift per coordinate in [-p, p]*dx */
  unsigned long seed;       /* GSL mt19937 seed of the perturbation */
} mfs_lattice_spec;

typedef struct {
  int dim;
  size_t n;
  double *x;             /* n*dim coordinates */
  double *vol;           /* n volumes: the cell dual (each cell's measure shared equally by its vertices) */
  unsigned char *flags;  /* n boundary flags (MFS_BND_*), 0 in a periodic box */
  int *ij;               /* n*2 integer lattice coordinates in the basis a1, a2 */
  mfs_box box;           /* the domain */
  mfs_lattice_kind lattice;
  double dx, dy;         /* spacing; dy = gamma*dx (square) or sqrt(3)/2 dx (hex row spacing) */
  double a1[2], a2[2];   /* lattice vectors */
  int nx, ny;            /* as in the spec */
  /* background cells */
  mfs_cell_kind cells;   /* how the cells were cut (hex and 1D: MFS_CELLS_TRI / MFS_CELLS_QUAD) */
  int nvert;             /* 2 (interval), 3 (triangle), 4 (quadrilateral, counter-clockwise) */
  size_t ncell;
  int *conn;             /* ncell*nvert node indices */
  double *cellx;         /* ncell*nvert*dim vertex coordinates, unwrapped across periodic edges */
} mfs_particles;

/* Build a lattice.  Returns NULL and sets *status (MFS_EINVAL for a bad
 * spec, MFS_ENOMEM) on failure. */
mfs_particles *mfs_lattice_alloc(const mfs_lattice_spec *spec, mfs_status *status);
void mfs_particles_free(mfs_particles *p);

/* The lattice's area (1D: length) per node, dx dy (1D dx): the node volume
 * of eq. 119 of paper 003, the same for every node, where vol[] is each
 * node's share of its cells (unequal on the star pattern). */
static inline double mfs_particles_node_volume(const mfs_particles *p)
{
  return p->dim == 1 ? p->dx : p->dx * p->dy;
}

/* A particle set given as arrays, borrowed (a user's file). */
typedef struct {
  int dim;            /* 1 or 2 */
  size_t n;           /* particles, at least dim + 1 */
  const double *x;    /* n*dim coordinates (m) */
  const double *vol;  /* n volumes (> 0; length in 1D, area in 2D), or NULL: the dual
                         volumes of the set's cells (below) */
  double spacing;     /* the typical spacing (m), mfs_point_set_spacing; 0: not known */
} mfs_point_set;

/* The typical spacing of a set with volumes: the median volume in 1D, the
 * square root of the median volume in 2D (on a lattice: dx, or sqrt(dx dy);
 * the median leaves out the halved volumes at the boundary).  NAN without
 * volumes.  Allocates nothing (the median by bisection on the values), so
 * it cannot fail. */
double mfs_point_set_spacing(const mfs_point_set *s);

/* The particles of a set.  Cells: 1D the intervals between neighbouring
 * particles (the set sorted by x); 2D the Delaunay triangles (Qhull,
 * mfs_delaunay.h), built when cells != 0 or when the set has no volumes.
 * Volumes: the set's own, or the cell dual (1D: half of each adjacent
 * interval; 2D: mfs_dual_areas), which sum to the measure of the domain
 * (the interval [min x, max x], the convex hull).  flags: the ends (1D),
 * the convex hull vertices (2D, MFS_BND_HULL).  box: the bounding box (not
 * periodic).  dx = dy: s->spacing, or the typical spacing of the volumes
 * (mfs_point_set_spacing).  lattice MFS_LATTICE_POINTS, nx = n,
 * ny = 1, ij all 0.  NULL with *status: MFS_EINVAL (dimension, fewer than
 * dim + 1 particles, a coordinate not finite, a volume not positive and
 * finite, two particles at one place in 1D), MFS_EDOMAIN (2D: no
 * triangulation, all particles on a line), MFS_ENOMEM. */
mfs_particles *mfs_particles_from_set(const mfs_point_set *s, int cells, mfs_status *status);

/* The typical spacing of a set from its coordinates alone, robust to a few
 * far particles (a bounding box is not: one particle 10^8 spacings away
 * makes its spacing 10^4 times too large): the box between the quartiles of
 * each coordinate, its length over the particles in it less one (1D), the
 * square root of its area over the particles in it (2D).  NAN for fewer
 * than 4 particles, a coordinate not finite, or a flat box (half the
 * particles or more on one coordinate value).  Allocates nothing. */
double mfs_point_set_bulk_spacing(const mfs_point_set *s);

/* The pairs (i, j), i = j included, of particles closer than r > 0 (the
 * neighbour entries of a plan whose points are the particles), counted with
 * cell lists without storing them; the count stops once it exceeds limit
 * (*count then > limit): a bound on the work before a plan is built, where
 * a particle file's particles may cluster.  MFS_OK, MFS_EINVAL (also for a
 * coordinate not finite), MFS_ENOMEM. */
mfs_status mfs_point_set_neighbours(const mfs_point_set *s, double r, double limit, double *count);

/* Two particles of the set closer than r > 0, found with cell lists (O(n);
 * the cells over the bulk of the set, so that a few far particles do not
 * gather it into one cell): *found = 1 and *i < *j their indices (the pair
 * of least indices), or *found = 0.  MFS_OK, MFS_EINVAL (also for a
 * coordinate not finite), MFS_ENOMEM. */
mfs_status mfs_point_set_close_pair(const mfs_point_set *s, double r, int *found, size_t *i,
                                    size_t *j);

/* Measure (length or area) of cell c, from its vertex coordinates. */
double mfs_cell_measure(const mfs_particles *p, size_t c);

/* Domain volume: the sum of the cell measures. */
double mfs_particles_domain_volume(const mfs_particles *p);

#ifdef __cplusplus
}
#endif

#endif
