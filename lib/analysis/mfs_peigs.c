#include "mfs_peigs.h"
#include "mfs_alloc.h"

#ifndef MFS_HAVE_MPI

/* Built without MPI: every entry point says so. */
int mfs_peigs_available(void)
{
  return 0;
}

mfs_pmodel *mfs_pmodel_alloc(const mfs_model_spec *spec, int comm, int assemble,
                             mfs_status *status, size_t *bad)
{
  (void)spec;
  (void)comm;
  (void)assemble;
  (void)bad;
  if (status)
    *status = MFS_ENOTSUP;
  return NULL;
}

void mfs_pmodel_free(mfs_pmodel *pm)
{
  (void)pm;
}

void mfs_pmodel_release_plan(mfs_pmodel *pm)
{
  (void)pm;
}

void mfs_pmodel_sizes(const mfs_pmodel *pm, mfs_pmodel_info *info)
{
  (void)pm;
  *info = (mfs_pmodel_info){.size = 1};
}

mfs_status mfs_pmodel_particle_x(const mfs_pmodel *pm, size_t particle, double *xy)
{
  (void)pm;
  (void)particle;
  (void)xy;
  return MFS_ENOTSUP;
}

mfs_status mfs_pmodel_gershgorin(const mfs_pmodel *pm, mfs_gershgorin_result *r)
{
  (void)pm;
  (void)r;
  return MFS_ENOTSUP;
}

mfs_status mfs_pmodel_bound(const mfs_pmodel *pm, mfs_bound_result *r)
{
  (void)pm;
  (void)r;
  return MFS_ENOTSUP;
}

mfs_status mfs_peig_max(const mfs_pmodel *pm, const mfs_eig_opts *opts, double *lambda,
                        mfs_eig_info *info)
{
  (void)pm;
  (void)opts;
  (void)lambda;
  (void)info;
  return MFS_ENOTSUP;
}

mfs_status mfs_pmodel_matvec(const mfs_pmodel *pm, const double *x, double *y)
{
  (void)pm;
  (void)x;
  (void)y;
  return MFS_ENOTSUP;
}

long mfs_pmodel_row_dof(const mfs_pmodel *pm, size_t i)
{
  (void)pm;
  (void)i;
  return -1;
}

#else /* MFS_HAVE_MPI */

#include <limits.h>
#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_assemble.h"
#include "mfs_lapack.h"
#include "mfs_neighbor.h"
#include "mfs_plan.h"

/* PARPACK (arpack-ng, gfortran, 32-bit integers): the Fortran symbols, the
 * communicator as a Fortran handle, the hidden string lengths last. */
extern void pdsaupd_(const MPI_Fint *comm, int *ido, const char *bmat, const int *n,
                     const char *which, const int *nev, const double *tol, double *resid,
                     const int *ncv, double *v, const int *ldv, int *iparam, int *ipntr,
                     double *workd, double *workl, const int *lworkl, int *info,
                     size_t bmat_len, size_t which_len);
extern void pdseupd_(const MPI_Fint *comm, const int *rvec, const char *howmny, int *select,
                     double *d, double *z, const int *ldz, const double *sigma, const char *bmat,
                     const int *n, const char *which, const int *nev, const double *tol,
                     double *resid, const int *ncv, double *v, const int *ldv, int *iparam,
                     int *ipntr, double *workd, double *workl, const int *lworkl, int *info,
                     size_t howmny_len, size_t bmat_len, size_t which_len);

int mfs_peigs_available(void)
{
  return 1;
}

struct mfs_pmodel {
  MPI_Comm comm;
  MPI_Fint fcomm;
  int rank, size;
  int dim, ndof, assembled, lumped;
  mfs_material mat;
  size_t np, nq, ndofs;   /* the whole model: particles, points, free dofs */
  size_t nown;            /* owned particles */
  size_t nlq, plan_nnz;   /* sizes of the local plan, kept when it is released */
  /* the local part: particles and points in the global order */
  mfs_particles *p;
  mfs_quad *q;
  mfs_plan *pl;
  size_t *pg;             /* local particle -> global particle */
  size_t *qg;             /* local point -> global point */
  int *powner;            /* owner rank of each local particle */
  unsigned char *fixed;   /* local particle is fixed */
  int any_fixed;
  double *ml;             /* lumped mass of every local dof (particle * ndof + k), or NULL */
  /* rows: the owned free dofs, in the global order */
  size_t nrow;
  size_t *rlocal;         /* local dof (particle * ndof + k) of each row */
  long *rdof;             /* global free dof of each row */
  mfs_csr *K;             /* nrow x (nrow + nhalo): columns in the extended vector, entries
                             in the order of the global dofs (NULL when not assembled) */
  /* the halo exchange: values of nhalo dofs received in blocks by owner */
  size_t nhalo;
  int nnb;                /* neighbour ranks */
  int *nb;                /* their ranks */
  size_t *rptr;           /* nnb + 1: block k of the halo part of the extended vector */
  size_t *sptr;           /* nnb + 1: block k of the send list */
  size_t *sidx;           /* rows whose values go to neighbour k */
};

/* ------------------------------------------------------------------ */
/* agreement over the ranks                                            */

/* The largest status of all ranks (MFS_OK = 0 only if every rank is OK). */
static mfs_status agree(MPI_Comm c, mfs_status st)
{
  int s = (int)st, r = 0;
  MPI_Allreduce(&s, &r, 1, MPI_INT, MPI_MAX, c);
  return (mfs_status)r;
}

/* ------------------------------------------------------------------ */
/* partition                                                            */

/* owner[I] for every particle: contiguous blocks of the cell order of a
 * grid of side a little over a/2 (mfs_grid), cut at the cell boundary
 * nearest to r n / size. */
static mfs_status partition(const mfs_particles *p, double a, int size, int *owner)
{
  mfs_status st;
  mfs_grid *g = mfs_grid_alloc(p->dim, p->n, p->x, &p->box, a, &st);
  if (!g)
    return st;
  size_t ncell = 1;
  for (int k = 0; k < p->dim; k++)
    ncell *= (size_t)g->nc[k];
  size_t c0 = 0;
  for (int r = 0; r < size; r++) {
    size_t c1 = ncell;
    if (r + 1 < size) {
      size_t target = (size_t)((double)p->n * (double)(r + 1) / (double)size);
      size_t lo = c0, hi = ncell; /* the first boundary c with start[c] >= target */
      while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (g->start[mid] >= target)
          hi = mid;
        else
          lo = mid + 1;
      }
      c1 = lo;
      if (c1 > c0 && target - g->start[c1 - 1] < g->start[c1] - target)
        c1--;
    }
    for (size_t c = c0; c < c1; c++)
      for (size_t e = g->start[c]; e < g->start[c + 1]; e++)
        owner[g->item[e]] = r;
    c0 = c1;
  }
  mfs_grid_free(g);
  return MFS_OK;
}

/* ------------------------------------------------------------------ */
/* the local part                                                       */

void mfs_pmodel_free(mfs_pmodel *pm)
{
  if (!pm)
    return;
  mfs_plan_free(pm->pl);
  mfs_quad_free(pm->q);
  mfs_particles_free(pm->p);
  mfs_free(pm->pg);
  mfs_free(pm->qg);
  mfs_free(pm->powner);
  mfs_free(pm->fixed);
  mfs_free(pm->ml);
  mfs_free(pm->rlocal);
  mfs_free(pm->rdof);
  mfs_csr_free(pm->K);
  mfs_free(pm->nb);
  mfs_free(pm->rptr);
  mfs_free(pm->sptr);
  mfs_free(pm->sidx);
  mfs_free(pm);
}

/* Whether x lies in [lo - r, hi + r] in every direction. */
static int in_box(int dim, const double *x, const double *lo, const double *hi, double r)
{
  for (int k = 0; k < dim; k++)
    if (x[k] < lo[k] - r || x[k] > hi[k] + r)
      return 0;
  return 1;
}

/* The points within a of an owned particle and the particles within a of
 * those points: lmark[I] = 1 for the local particles, qkeep[Q] = 1 for the
 * local points.  Neighbour lists over the candidate particles (within 2a
 * of the owned ones' bounding box), in chunks of points. */
static mfs_status select_local(const mfs_particles *p, const mfs_quad *q, double a,
                               const int *owner, int rank, unsigned char *lmark,
                               unsigned char *qkeep)
{
  const int dim = p->dim;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t I = 0; I < p->n; I++)
    if (owner[I] == rank)
      for (int k = 0; k < dim; k++) {
        double x = p->x[I * (size_t)dim + (size_t)k];
        lo[k] = x < lo[k] ? x : lo[k];
        hi[k] = x > hi[k] ? x : hi[k];
      }
  const int all = p->box.periodic; /* minimum images: no pruning by the box */
  size_t nc = 0;
  for (size_t I = 0; I < p->n; I++)
    nc += all || in_box(dim, p->x + I * (size_t)dim, lo, hi, 2.0 * a);
  enum { CHUNK = 8192 };
  mfs_status st = MFS_ENOMEM;
  mfs_grid *g = NULL;
  mfs_nlist *nl = NULL;
  size_t *cand = mfs_malloc((nc ? nc : 1) * sizeof *cand), *qi = NULL;
  double *cx = mfs_malloc((nc ? nc : 1) * (size_t)dim * sizeof *cx), *xq = NULL;
  if (!cand || !cx)
    goto done;
  nc = 0;
  for (size_t I = 0; I < p->n; I++)
    if (all || in_box(dim, p->x + I * (size_t)dim, lo, hi, 2.0 * a)) {
      memcpy(cx + nc * (size_t)dim, p->x + I * (size_t)dim, (size_t)dim * sizeof *cx);
      cand[nc++] = I;
    }
  g = mfs_grid_alloc(dim, nc, cx, &p->box, a, &st);
  if (!g)
    goto done;
  st = MFS_ENOMEM;
  qi = mfs_malloc(CHUNK * sizeof *qi);
  xq = mfs_malloc(CHUNK * (size_t)dim * sizeof *xq);
  if (!qi || !xq)
    goto done;
  size_t Q = 0;
  while (Q < q->n) {
    size_t m = 0;
    for (; Q < q->n && m < CHUNK; Q++)
      if (all || in_box(dim, q->x + Q * (size_t)dim, lo, hi, a)) {
        memcpy(xq + m * (size_t)dim, q->x + Q * (size_t)dim, (size_t)dim * sizeof *xq);
        qi[m++] = Q;
      }
    if (m == 0)
      continue;
    nl = mfs_nlist_build(g, m, xq, a, &st);
    if (!nl)
      goto done;
    for (size_t t = 0; t < m; t++) {
      int mine = 0;
      for (size_t e = nl->ptr[t]; e < nl->ptr[t + 1] && !mine; e++)
        mine = owner[cand[nl->idx[e]]] == rank;
      if (!mine)
        continue;
      qkeep[qi[t]] = 1;
      for (size_t e = nl->ptr[t]; e < nl->ptr[t + 1]; e++)
        lmark[cand[nl->idx[e]]] = 1;
    }
    mfs_nlist_free(nl);
    nl = NULL;
  }
  st = MFS_OK;
done:
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  mfs_free(cand);
  mfs_free(cx);
  mfs_free(qi);
  mfs_free(xq);
  return st;
}

/* The particles lmark of p, in order, as a particle set of their own
 * (no background cells: the points are given). */
static mfs_particles *sub_particles(const mfs_particles *p, const unsigned char *lmark, size_t nl)
{
  mfs_particles *s = mfs_calloc(1, sizeof *s);
  if (!s)
    return NULL;
  *s = *p;
  s->x = mfs_malloc((nl ? nl : 1) * (size_t)p->dim * sizeof *s->x);
  s->vol = mfs_malloc((nl ? nl : 1) * sizeof *s->vol);
  s->flags = mfs_malloc(nl ? nl : 1);
  s->ij = p->ij ? mfs_malloc((nl ? nl : 1) * 2 * sizeof *s->ij) : NULL;
  s->conn = NULL;
  s->cellx = NULL;
  s->ncell = 0;
  s->n = nl;
  if (!s->x || !s->vol || !s->flags || (p->ij && !s->ij)) {
    mfs_particles_free(s);
    return NULL;
  }
  size_t k = 0;
  for (size_t I = 0; I < p->n; I++) {
    if (!lmark[I])
      continue;
    memcpy(s->x + k * (size_t)p->dim, p->x + I * (size_t)p->dim, (size_t)p->dim * sizeof *s->x);
    s->vol[k] = p->vol[I];
    s->flags[k] = p->flags[I];
    if (s->ij)
      memcpy(s->ij + 2 * k, p->ij + 2 * I, 2 * sizeof *s->ij);
    k++;
  }
  return s;
}

static mfs_quad *sub_points(const mfs_quad *q, const unsigned char *qkeep, size_t nl,
                            const int *g2l)
{
  mfs_quad *s = mfs_quad_empty(q->dim, nl);
  if (!s)
    return NULL;
  s->n = nl;
  size_t k = 0;
  for (size_t Q = 0; Q < q->n; Q++) {
    if (!qkeep[Q])
      continue;
    memcpy(s->x + k * (size_t)q->dim, q->x + Q * (size_t)q->dim, (size_t)q->dim * sizeof *s->x);
    s->w[k] = q->w[Q];
    s->node[k] = q->node[Q] >= 0 ? g2l[q->node[Q]] : -1; /* at distance 0: local */
    k++;
  }
  return s;
}

static int cmp_long(const void *a, const void *b)
{
  long x = *(const long *)a, y = *(const long *)b;
  return (x > y) - (x < y);
}

/* The row of global free dof g, or -1. */
static long row_of(const mfs_pmodel *pm, long g)
{
  const long *r = bsearch(&g, pm->rdof, pm->nrow, sizeof *pm->rdof, cmp_long);
  return r ? (long)(r - pm->rdof) : -1;
}

/* Assemble the rows (CSR, columns as local dofs for now) of the owned free
 * particles; sorted rows, free columns only. */
static mfs_status assemble_rows(mfs_pmodel *pm, const long *lfree, long *colmap)
{
  const int ndof = pm->ndof, nd2 = ndof * ndof;
  mfs_forms f = mfs_forms_stiffness(&pm->mat);
  mfs_row row;
  mfs_status st = mfs_row_init(&row, pm->pl, &f);
  if (st != MFS_OK)
    return st;
  size_t cap = 8 * pm->nrow * (size_t)nd2 + 16;
  mfs_csr *A = mfs_csr_alloc(pm->nrow, pm->nrow, cap);
  st = A ? MFS_OK : MFS_ENOMEM;
  size_t pos = 0, r = 0;
  for (size_t I = 0; I < pm->p->n && st == MFS_OK; I++) {
    if (pm->powner[I] != pm->rank || pm->fixed[I])
      continue;
    st = mfs_row_assemble(&row, pm->pl, &f, I);
    if (st != MFS_OK)
      break;
    mfs_row_sort(&row); /* by particle: local order is the global order */
    size_t len = row.len;
    if (pos + len * (size_t)nd2 > cap) {
      size_t ncap = 2 * cap + len * (size_t)nd2;
      int *ti = mfs_realloc(A->idx, ncap * sizeof *ti);
      if (ti)
        A->idx = ti;
      double *tv = ti ? mfs_realloc(A->val, ncap * sizeof *tv) : NULL;
      if (!tv) {
        st = MFS_ENOMEM;
        break;
      }
      A->val = tv;
      cap = ncap;
    }
    for (int a = 0; a < ndof; a++, r++) {
      for (size_t s = 0; s < len; s++) {
        int J = row.col[s];
        if (pm->fixed[J])
          continue;
        for (int b = 0; b < ndof; b++) {
          long ld = (long)J * ndof + b;
          A->idx[pos] = (int)ld;
          A->val[pos] = row.K[s * (size_t)nd2 + (size_t)a * ndof + (size_t)b];
          colmap[ld] = lfree[ld]; /* mark: a column of some row */
          pos++;
        }
      }
      A->ptr[r + 1] = pos;
    }
  }
  mfs_row_free(&row);
  if (st != MFS_OK) {
    mfs_csr_free(A);
    return st;
  }
  pm->K = A;
  return MFS_OK;
}

/* The halo: the columns of other ranks' particles, in blocks by owner (in
 * the global order within a block); the send lists from the owners' side.
 * colmap[ld] >= 0 marks the local dofs used as columns; on return it holds
 * each column's position in the extended vector. */
static mfs_status build_halo(mfs_pmodel *pm, long *colmap)
{
  const int P = pm->size, ndof = pm->ndof;
  size_t nld = pm->p->n * (size_t)ndof;
  mfs_status st = MFS_ENOMEM;
  int *rc = mfs_calloc((size_t)P, sizeof *rc), *sc = mfs_calloc((size_t)P, sizeof *sc);
  int *rd = mfs_calloc((size_t)P + 1, sizeof *rd), *sd = mfs_calloc((size_t)P + 1, sizeof *sd);
  long *req = NULL, *got = NULL;
  size_t *fill = mfs_calloc((size_t)P, sizeof *fill);
  st = agree(pm->comm, rc && sc && rd && sd && fill ? MFS_OK : MFS_ENOMEM); /* before a collective */
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  for (size_t r = 0; r < pm->nrow; r++)
    colmap[pm->rlocal[r]] = -2; /* owned: not halo */
  for (size_t ld = 0; ld < nld; ld++)
    if (colmap[ld] >= 0)
      rc[pm->powner[ld / (size_t)ndof]]++;
  MPI_Alltoall(rc, 1, MPI_INT, sc, 1, MPI_INT, pm->comm);
  for (int k = 0; k < P; k++) {
    rd[k + 1] = rd[k] + rc[k];
    sd[k + 1] = sd[k] + sc[k];
  }
  pm->nhalo = (size_t)rd[P];
  req = mfs_malloc((pm->nhalo ? pm->nhalo : 1) * sizeof *req);
  got = mfs_malloc((sd[P] ? (size_t)sd[P] : 1) * sizeof *got);
  st = agree(pm->comm, req && got ? MFS_OK : MFS_ENOMEM);
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  for (size_t ld = 0; ld < nld; ld++) {
    if (colmap[ld] < 0)
      continue;
    int o = pm->powner[ld / (size_t)ndof];
    size_t h = (size_t)rd[o] + fill[o]++;
    req[h] = colmap[ld]; /* its global free dof */
    colmap[ld] = (long)(pm->nrow + h);
  }
  for (size_t r = 0; r < pm->nrow; r++)
    colmap[pm->rlocal[r]] = (long)r;
  MPI_Alltoallv(req, rc, rd, MPI_LONG, got, sc, sd, MPI_LONG, pm->comm);
  int nnb = 0;
  for (int k = 0; k < P; k++)
    nnb += rc[k] > 0 || sc[k] > 0;
  pm->nnb = nnb;
  pm->nb = mfs_malloc((size_t)(nnb ? nnb : 1) * sizeof *pm->nb);
  pm->rptr = mfs_malloc((size_t)(nnb + 1) * sizeof *pm->rptr);
  pm->sptr = mfs_malloc((size_t)(nnb + 1) * sizeof *pm->sptr);
  pm->sidx = mfs_malloc((sd[P] ? (size_t)sd[P] : 1) * sizeof *pm->sidx);
  if (!pm->nb || !pm->rptr || !pm->sptr || !pm->sidx)
    goto done;
  int t = 0;
  pm->rptr[0] = pm->sptr[0] = 0;
  for (int k = 0; k < P; k++) {
    if (!(rc[k] > 0 || sc[k] > 0))
      continue;
    pm->nb[t] = k;
    pm->rptr[t + 1] = pm->rptr[t] + (size_t)rc[k];
    pm->sptr[t + 1] = pm->sptr[t] + (size_t)sc[k];
    t++;
  }
  st = MFS_OK;
  for (int s = 0; s < sd[P]; s++) {
    long r = row_of(pm, got[s]);
    if (r < 0) {
      st = MFS_EINVAL; /* cannot happen: the owner holds every dof it owns */
      break;
    }
    pm->sidx[s] = (size_t)r;
  }
done:
  mfs_free(rc);
  mfs_free(sc);
  mfs_free(rd);
  mfs_free(sd);
  mfs_free(fill);
  mfs_free(req);
  mfs_free(got);
  return st;
}

mfs_pmodel *mfs_pmodel_alloc(const mfs_model_spec *spec, int comm, int assemble,
                             mfs_status *status, size_t *bad)
{
  mfs_status st = mfs_model_spec_check(spec, NULL);
  MPI_Comm c = MPI_Comm_f2c((MPI_Fint)comm);
  mfs_pmodel *pm = NULL;
  mfs_particles *gp = NULL;
  mfs_quad *gq = NULL;
  int *owner = NULL, *g2l = NULL;
  unsigned char *lmark = NULL, *qkeep = NULL;
  long *lfree = NULL, *colmap = NULL;
  unsigned long long badq = ULLONG_MAX;
  if (st != MFS_OK) /* the same spec on every rank: the same verdict */
    goto done;
  const mfs_disc *d = &spec->disc;
  st = MFS_ENOMEM;
  pm = mfs_calloc(1, sizeof *pm);
  if (pm) {
    pm->comm = c;
    pm->fcomm = (MPI_Fint)comm;
    MPI_Comm_rank(c, &pm->rank);
    MPI_Comm_size(c, &pm->size);
    pm->dim = d->dim;
    pm->ndof = mfs_physics_ndof(d->material.physics);
    pm->mat = d->material;
    pm->assembled = assemble != 0;
    pm->lumped = !d->consistent_mass;
    st = mfs_disc_geometry(d, &gp, &gq);
  }
  st = agree(c, st);
  if (st != MFS_OK)
    goto done;
  const int ndof = pm->ndof;
  pm->np = gp->n;
  pm->nq = gq->n;
  double a = d->support > 0.0 ? d->support : d->dilation * gp->dx; /* as mfs_plan_alloc */
  st = MFS_ENOMEM;
  owner = mfs_malloc(gp->n * sizeof *owner);
  g2l = mfs_malloc(gp->n * sizeof *g2l);
  lmark = mfs_calloc(gp->n, 1);
  qkeep = mfs_calloc(gq->n ? gq->n : 1, 1);
  if (owner && g2l && lmark && qkeep)
    st = partition(gp, a, pm->size, owner);
  if (st == MFS_OK)
    st = select_local(gp, gq, a, owner, pm->rank, lmark, qkeep);
  st = agree(c, st);
  if (st != MFS_OK)
    goto done;

  /* the local particles and points, the global free dof numbering */
  size_t nl = 0, nlq = 0, nfree = 0;
  for (size_t I = 0; I < gp->n; I++) {
    if (owner[I] == pm->rank)
      lmark[I] = 1, pm->nown++;
    g2l[I] = lmark[I] ? (int)nl++ : -1;
  }
  for (size_t Q = 0; Q < gq->n; Q++)
    nlq += qkeep[Q];
  st = MFS_ENOMEM;
  pm->p = sub_particles(gp, lmark, nl);
  pm->q = pm->p ? sub_points(gq, qkeep, nlq, g2l) : NULL;
  pm->pg = mfs_malloc((nl ? nl : 1) * sizeof *pm->pg);
  pm->qg = mfs_malloc((nlq ? nlq : 1) * sizeof *pm->qg);
  pm->powner = mfs_malloc((nl ? nl : 1) * sizeof *pm->powner);
  pm->fixed = mfs_calloc(nl ? nl : 1, 1);
  lfree = mfs_malloc((nl ? nl : 1) * (size_t)ndof * sizeof *lfree);
  if (!pm->q || !pm->pg || !pm->qg || !pm->powner || !pm->fixed || !lfree)
    goto fail;
  for (size_t I = 0, k = 0; I < gp->n; I++) {
    int fx = spec->fixed == MFS_FIX_MASK  ? spec->fix_mask[I] != 0
             : spec->fixed != MFS_FIX_NONE ? gp->flags[I] != 0
                                           : 0;
    if (lmark[I]) {
      pm->pg[k] = I;
      pm->powner[k] = owner[I];
      pm->fixed[k] = (unsigned char)fx;
      pm->any_fixed |= fx;
      for (int b = 0; b < ndof; b++)
        lfree[k * (size_t)ndof + (size_t)b] = fx ? -1 : (long)(nfree + (size_t)b);
      if (owner[I] == pm->rank && !fx)
        pm->nrow += (size_t)ndof;
      k++;
    }
    if (!fx)
      nfree += (size_t)ndof;
  }
  for (size_t Q = 0, k = 0; Q < gq->n; Q++)
    if (qkeep[Q])
      pm->qg[k++] = Q;
  pm->ndofs = nfree;
  st = MFS_OK;
fail:
  /* the whole geometry is not needed any more */
  mfs_particles_free(gp);
  mfs_quad_free(gq);
  gp = NULL;
  gq = NULL;
  mfs_free(owner);
  mfs_free(g2l);
  mfs_free(lmark);
  mfs_free(qkeep);
  owner = g2l = NULL;
  lmark = qkeep = NULL;
  st = agree(c, st);
  if (st != MFS_OK)
    goto done;
  /* every particle fixed: mfs_model_alloc's MFS_EINVAL; a rank without rows:
   * more ranks than the model has room for */
  unsigned long long mine = pm->nrow, least = 0;
  MPI_Allreduce(&mine, &least, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, c);
  st = pm->ndofs < 1 ? MFS_EINVAL : least == 0 ? MFS_ETOOSMALL : MFS_OK;
  if (st != MFS_OK)
    goto done;

  /* the plan of the local part: the whole model's points, neighbours and table */
  pm->pl = mfs_plan_alloc(d, pm->p, pm->q, &st);
  st = agree(c, st);
  if (st != MFS_OK)
    goto done;
  size_t lbad = 0;
  st = mfs_plan_tabulate(pm->pl, 1, &lbad);
  if (st == MFS_ESINGULAR)
    badq = pm->qg[lbad];
  {
    unsigned long long b = badq;
    MPI_Allreduce(&b, &badq, 1, MPI_UNSIGNED_LONG_LONG, MPI_MIN, c);
  }
  st = agree(c, st);
  if (st != MFS_OK)
    goto done;

  st = MFS_ENOMEM;
  pm->rlocal = mfs_malloc((pm->nrow ? pm->nrow : 1) * sizeof *pm->rlocal);
  pm->rdof = mfs_malloc((pm->nrow ? pm->nrow : 1) * sizeof *pm->rdof);
  if (pm->lumped)
    pm->ml = mfs_malloc(pm->p->n * (size_t)ndof * sizeof *pm->ml);
  if (pm->rlocal && pm->rdof && (!pm->lumped || pm->ml)) {
    size_t r = 0;
    for (size_t I = 0; I < pm->p->n; I++)
      if (pm->powner[I] == pm->rank && !pm->fixed[I])
        for (int b = 0; b < ndof; b++, r++) {
          pm->rlocal[r] = I * (size_t)ndof + (size_t)b;
          pm->rdof[r] = lfree[pm->rlocal[r]];
        }
    st = pm->lumped ? mfs_assemble_mass_lumped(pm->pl, &pm->mat, pm->ml) : MFS_OK;
  }
  if (st == MFS_OK && pm->assembled) {
    size_t nld = pm->p->n * (size_t)ndof;
    colmap = mfs_malloc((nld ? nld : 1) * sizeof *colmap);
    st = colmap ? MFS_OK : MFS_ENOMEM;
    if (st == MFS_OK) {
      for (size_t i = 0; i < nld; i++)
        colmap[i] = -1;
      st = assemble_rows(pm, lfree, colmap);
    }
  }
  st = agree(c, st);
  if (st != MFS_OK || !pm->assembled)
    goto done;
  st = build_halo(pm, colmap);
  if (st == MFS_OK) {
    mfs_csr *A = pm->K;
    for (size_t e = 0; e < A->ptr[A->nrow]; e++)
      A->idx[e] = (int)colmap[A->idx[e]];
    A->ncol = pm->nrow + pm->nhalo;
  }
  st = agree(c, st);
done:
  mfs_particles_free(gp);
  mfs_quad_free(gq);
  mfs_free(owner);
  mfs_free(g2l);
  mfs_free(lmark);
  mfs_free(qkeep);
  mfs_free(lfree);
  mfs_free(colmap);
  if (st != MFS_OK) {
    mfs_pmodel_free(pm);
    pm = NULL;
  }
  if (bad && badq != ULLONG_MAX)
    *bad = (size_t)badq;
  if (status)
    *status = st;
  return pm;
}

void mfs_pmodel_release_plan(mfs_pmodel *pm)
{
  if (!pm)
    return;
  if (pm->pl)
    pm->plan_nnz = mfs_plan_nnz(pm->pl);
  if (pm->q)
    pm->nlq = pm->q->n;
  mfs_plan_free(pm->pl);
  mfs_quad_free(pm->q);
  pm->pl = NULL;
  pm->q = NULL;
}

void mfs_pmodel_sizes(const mfs_pmodel *pm, mfs_pmodel_info *info)
{
  size_t sent = pm->sptr ? pm->sptr[pm->nnb] : 0;
  *info = (mfs_pmodel_info){.rank = pm->rank,
                            .size = pm->size,
                            .particles = pm->np,
                            .points = pm->nq,
                            .dofs = pm->ndofs,
                            .own_particles = pm->nown,
                            .local_particles = pm->p->n,
                            .local_points = pm->q ? pm->q->n : pm->nlq,
                            .rows = pm->nrow,
                            .halo = pm->nhalo,
                            .sent = sent,
                            .neighbours = pm->nnb,
                            .nnz = pm->K ? pm->K->ptr[pm->K->nrow] : 0,
                            .plan_nnz = pm->pl ? mfs_plan_nnz(pm->pl) : pm->plan_nnz};
}

long mfs_pmodel_row_dof(const mfs_pmodel *pm, size_t i)
{
  return pm && i < pm->nrow ? pm->rdof[i] : -1;
}

/* The local index of global particle I, or -1. */
static long local_particle(const mfs_pmodel *pm, size_t I)
{
  size_t lo = 0, hi = pm->p->n;
  while (lo < hi) {
    size_t mid = lo + (hi - lo) / 2;
    if (pm->pg[mid] < I)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < pm->p->n && pm->pg[lo] == I ? (long)lo : -1;
}

mfs_status mfs_pmodel_particle_x(const mfs_pmodel *pm, size_t I, double *xy)
{
  if (!pm || I >= pm->np)
    return MFS_EINVAL;
  long l = local_particle(pm, I);
  double mine[3] = {0.0, 0.0, 0.0};
  if (l >= 0 && pm->powner[l] == pm->rank) {
    mine[0] = 1.0;
    for (int k = 0; k < pm->dim; k++)
      mine[1 + k] = pm->p->x[(size_t)l * (size_t)pm->dim + (size_t)k];
  }
  double *all = mfs_malloc((size_t)pm->size * 3 * sizeof *all);
  int ok = all != NULL, allok = 0;
  MPI_Allreduce(&ok, &allok, 1, MPI_INT, MPI_MIN, pm->comm);
  if (!allok) {
    mfs_free(all);
    return MFS_ENOMEM;
  }
  MPI_Allgather(mine, 3, MPI_DOUBLE, all, 3, MPI_DOUBLE, pm->comm);
  xy[0] = xy[1] = 0.0;
  for (int r = 0; r < pm->size; r++)
    if (all[3 * r] != 0.0) {
      xy[0] = all[3 * r + 1];
      xy[1] = all[3 * r + 2];
      break;
    }
  mfs_free(all);
  return MFS_OK;
}

/* ------------------------------------------------------------------ */
/* reductions: every rank's partial result gathered, then combined in rank
 * order with the serial loops' tie rules (the first index at the extreme) */

typedef struct {
  double lambda, min_mass;
  unsigned long long argmax, nonpositive, first_nonpositive, argmin_mass, rows;
} gersh_part;

static void gersh_add(gersh_part *g, double s, double mi, size_t f)
{ /* mfs_bound.c's gersh_row */
  g->rows++;
  if (mi < g->min_mass) {
    g->min_mass = mi;
    g->argmin_mass = f;
  }
  if (!(mi > 0.0)) {
    if (g->nonpositive++ == 0)
      g->first_nonpositive = f;
    return;
  }
  double lam = s / mi;
  if (lam > g->lambda) {
    g->lambda = lam;
    g->argmax = f;
  }
}

/* Gather a fixed-size part from every rank (MPI_BYTE: the same layout on
 * every rank of one program).  NULL when out of memory on some rank. */
static void *gather_parts(MPI_Comm c, int size, const void *mine, size_t len)
{
  void *all = mfs_malloc((size_t)size * len);
  int ok = all != NULL, allok = 0;
  MPI_Allreduce(&ok, &allok, 1, MPI_INT, MPI_MIN, c);
  if (!allok) {
    mfs_free(all);
    return NULL;
  }
  MPI_Allgather(mine, (int)len, MPI_BYTE, all, (int)len, MPI_BYTE, c);
  return all;
}

mfs_status mfs_pmodel_gershgorin(const mfs_pmodel *pm, mfs_gershgorin_result *r)
{
  *r = (mfs_gershgorin_result){.lambda = 0.0, .min_mass = INFINITY};
  if (!pm)
    return MFS_EINVAL;
  gersh_part g = {.lambda = 0.0, .min_mass = INFINITY};
  const int ndof = pm->ndof, nd2 = ndof * ndof;
  mfs_status st = pm->lumped ? MFS_OK : MFS_EINVAL;
  if (st == MFS_OK && pm->K) { /* as mfs_gershgorin_csr: the sorted rows */
    for (size_t i = 0; i < pm->nrow; i++) {
      double s = 0.0;
      for (size_t e = pm->K->ptr[i]; e < pm->K->ptr[i + 1]; e++)
        s += fabs(pm->K->val[e]);
      size_t ld = pm->rlocal[i];
      gersh_add(&g, s, pm->ml[ld], pm->pg[ld / (size_t)ndof] * (size_t)ndof + ld % (size_t)ndof);
    }
  } else if (st == MFS_OK && !pm->pl) {
    st = MFS_EINVAL; /* neither rows nor plan */
  } else if (st == MFS_OK) { /* as mfs_gershgorin_plan: streamed rows, first-appearance order */
    mfs_forms f = mfs_forms_stiffness(&pm->mat);
    mfs_row row;
    st = mfs_row_init(&row, pm->pl, &f);
    for (size_t I = 0; I < pm->p->n && st == MFS_OK; I++) {
      if (pm->powner[I] != pm->rank || pm->fixed[I])
        continue;
      st = mfs_row_assemble(&row, pm->pl, &f, I);
      for (int a = 0; a < ndof && st == MFS_OK; a++) {
        double s = 0.0;
        for (size_t k = 0; k < row.len; k++) {
          if (pm->any_fixed && pm->fixed[row.col[k]])
            continue;
          const double *blk = row.K + k * (size_t)nd2 + (size_t)a * ndof;
          for (int b = 0; b < ndof; b++)
            s += fabs(blk[b]);
        }
        size_t ld = I * (size_t)ndof + (size_t)a;
        gersh_add(&g, s, pm->ml[ld], pm->pg[I] * (size_t)ndof + (size_t)a);
      }
    }
    mfs_row_free(&row);
  }
  st = agree(pm->comm, st);
  if (st != MFS_OK)
    return st;
  gersh_part *all = gather_parts(pm->comm, pm->size, &g, sizeof g);
  if (!all)
    return MFS_ENOMEM;
  int seen = 0;
  for (int k = 0; k < pm->size; k++) {
    const gersh_part *x = &all[k];
    if (x->rows == 0)
      continue;
    if (x->min_mass < r->min_mass ||
        (x->min_mass == r->min_mass && seen && x->argmin_mass < r->argmin_mass)) {
      r->min_mass = x->min_mass;
      r->argmin_mass = (size_t)x->argmin_mass;
    }
    if (x->nonpositive > 0 && (r->nonpositive == 0 || x->first_nonpositive < r->first_nonpositive))
      r->first_nonpositive = (size_t)x->first_nonpositive;
    r->nonpositive += (size_t)x->nonpositive;
    if (x->lambda > r->lambda || (x->lambda == r->lambda && x->lambda > 0.0 && x->argmax < r->argmax)) {
      r->lambda = x->lambda;
      r->argmax = (size_t)x->argmax;
    }
    seen = 1;
  }
  mfs_free(all);
  if (r->nonpositive > 0)
    r->lambda = NAN;
  return MFS_OK;
}

typedef struct {
  double lambda, x[2];
  unsigned long long argmax, points, negative;
} bound_part;

mfs_status mfs_pmodel_bound(const mfs_pmodel *pm, mfs_bound_result *r)
{
  memset(r, 0, sizeof *r);
  if (!pm || !pm->pl || !(pm->mat.density > 0.0))
    return MFS_EINVAL;
  const int dim = pm->dim;
  if (mfs_plan_ncomp(pm->pl) < 1 + dim ||
      (pm->mat.physics == MFS_PHYS_PLANE_STRAIN && dim != 2))
    return MFS_EINVAL;
  bound_part b = {0};
  unsigned char *act = mfs_malloc(mfs_plan_max_neighbours(pm->pl));
  mfs_status st = agree(pm->comm, act ? MFS_OK : MFS_ENOMEM);
  if (st != MFS_OK) {
    mfs_free(act);
    return st;
  }
  for (size_t Q = 0; Q < pm->q->n; Q++) {
    mfs_point pt;
    mfs_plan_point(pm->pl, Q, &pt);
    /* counted by the owner of its first particle: once over the ranks */
    if (pt.nn == 0 || pm->powner[pt.idx[0]] != pm->rank)
      continue;
    for (size_t J = 0; J < pt.nn; J++)
      act[J] = !pm->fixed[pt.idx[J]];
    int neg;
    double lam = mfs_bound_point(dim, &pm->mat, (int)pt.nn, pt.phi, pt.ncomp,
                                 pm->any_fixed ? act : NULL, &neg);
    if (lam > b.lambda || b.points == 0) { /* mfs_bound.c's result_add */
      b.lambda = lam;
      b.argmax = pm->qg[Q];
      b.x[0] = pt.x[0];
      b.x[1] = dim > 1 ? pt.x[1] : 0.0;
    }
    b.points++;
    b.negative += neg != 0;
  }
  mfs_free(act);
  bound_part *all = gather_parts(pm->comm, pm->size, &b, sizeof b);
  if (!all)
    return MFS_ENOMEM;
  for (int k = 0; k < pm->size; k++) {
    const bound_part *x = &all[k];
    if (x->points == 0)
      continue;
    if (r->points == 0 || x->lambda > r->lambda ||
        (x->lambda == r->lambda && x->argmax < r->argmax)) {
      r->lambda = x->lambda;
      r->argmax = (size_t)x->argmax;
      r->xmax[0] = x->x[0];
      r->xmax[1] = x->x[1];
    }
    r->points += (size_t)x->points;
    r->negative_phi += (size_t)x->negative;
  }
  r->evaluated = r->points;
  mfs_free(all);
  return MFS_OK;
}

/* ------------------------------------------------------------------ */
/* products                                                             */

/* Buffers of the exchange, allocated once per solve. */
typedef struct {
  double *xe;        /* nrow + nhalo: the extended vector */
  double *sbuf;      /* the send lists' values */
  MPI_Request *req;  /* 2 nnb */
} halo_work;

static void work_free(halo_work *w)
{
  mfs_free(w->xe);
  mfs_free(w->sbuf);
  mfs_free(w->req);
  memset(w, 0, sizeof *w);
}

static mfs_status work_alloc(const mfs_pmodel *pm, halo_work *w)
{
  size_t ns = pm->sptr[pm->nnb];
  w->xe = mfs_malloc((pm->nrow + pm->nhalo) * sizeof *w->xe);
  w->sbuf = mfs_malloc((ns ? ns : 1) * sizeof *w->sbuf);
  w->req = mfs_malloc((size_t)(2 * pm->nnb + 1) * sizeof *w->req);
  mfs_status st = w->xe && w->sbuf && w->req ? MFS_OK : MFS_ENOMEM;
  st = agree(pm->comm, st);
  if (st != MFS_OK)
    work_free(w);
  return st;
}

/* The halo values of w->xe from their owners (w->xe[0 .. nrow) set). */
static void exchange(const mfs_pmodel *pm, halo_work *w)
{
  int nr = 0;
  for (int k = 0; k < pm->nnb; k++) {
    size_t n = pm->rptr[k + 1] - pm->rptr[k];
    if (n > 0)
      MPI_Irecv(w->xe + pm->nrow + pm->rptr[k], (int)n, MPI_DOUBLE, pm->nb[k], 17, pm->comm,
                &w->req[nr++]);
  }
  for (int k = 0; k < pm->nnb; k++) {
    size_t s0 = pm->sptr[k], n = pm->sptr[k + 1] - s0;
    if (n == 0)
      continue;
    for (size_t s = s0; s < s0 + n; s++)
      w->sbuf[s] = w->xe[pm->sidx[s]];
    MPI_Isend(w->sbuf + s0, (int)n, MPI_DOUBLE, pm->nb[k], 17, pm->comm, &w->req[nr++]);
  }
  MPI_Waitall(nr, w->req, MPI_STATUSES_IGNORE);
}

/* y = K xe (rows), after the exchange; entries in the order of the global dofs. */
static void local_rows(const mfs_csr *A, const double *restrict xe, double *restrict y)
{
  const size_t *restrict ptr = A->ptr;
  const int *restrict idx = A->idx;
  const double *restrict val = A->val;
  for (size_t i = 0; i < A->nrow; i++) {
    double s = 0.0;
    for (size_t e = ptr[i]; e < ptr[i + 1]; e++)
      s += val[e] * xe[idx[e]];
    y[i] = s;
  }
}

mfs_status mfs_pmodel_matvec(const mfs_pmodel *pm, const double *x, double *y)
{
  if (!pm || !pm->K)
    return MFS_EINVAL;
  halo_work w;
  mfs_status st = work_alloc(pm, &w);
  if (st != MFS_OK)
    return st;
  memcpy(w.xe, x, pm->nrow * sizeof *x);
  exchange(pm, &w);
  local_rows(pm->K, w.xe, y);
  work_free(&w);
  return MFS_OK;
}

/* mfs_eig_max's start vector (splitmix64), entry g of the global vector. */
static double start_entry(long g)
{
  uint64_t z = 0x9e3779b97f4a7c15ULL * ((uint64_t)g + 2u);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return 2.0 * ((double)(z >> 11) * 0x1.0p-53) - 1.0;
}

static double psum(MPI_Comm c, double v)
{
  double s = 0.0;
  MPI_Allreduce(&v, &s, 1, MPI_DOUBLE, MPI_SUM, c);
  return s;
}

mfs_status mfs_peig_max(const mfs_pmodel *pm, const mfs_eig_opts *opts, double *lambda,
                        mfs_eig_info *info)
{
  if (info)
    *info = (mfs_eig_info){.routine = ""};
  if (!pm || !pm->K || !pm->lumped || pm->ndofs < 2)
    return MFS_EINVAL;
  const size_t nr = pm->nrow;
  int okm = 1;
  for (size_t i = 0; i < nr; i++)
    okm &= pm->ml[pm->rlocal[i]] > 0.0 && isfinite(pm->ml[pm->rlocal[i]]);
  mfs_status st = agree(pm->comm, okm ? MFS_OK : MFS_EINVAL);
  if (st != MFS_OK)
    return st;
  int n = (int)nr, nev = 1, ldv = n;
  int ncv = opts && opts->ncv > 0 ? opts->ncv : 20;
  if (ncv <= nev)
    ncv = nev + 1;
  if ((size_t)ncv > pm->ndofs)
    ncv = (int)pm->ndofs;
  int lworkl = ncv * (ncv + 8), maxiter = opts && opts->maxiter > 0 ? opts->maxiter : 10000;
  double tol = opts && opts->tol > 0.0 ? opts->tol : 0.0, sigma = 0.0;
  int ido = 0, ainfo = 1, iparam[11] = {0}, ipntr[14] = {0};
  halo_work w = {0};
  double *s = mfs_malloc(nr * sizeof *s), *resid = mfs_malloc(nr * sizeof *resid);
  double *v = mfs_malloc(nr * (size_t)ncv * sizeof *v), *workd = mfs_malloc(3 * nr * sizeof *workd);
  double *workl = mfs_malloc((size_t)lworkl * sizeof *workl), *y = mfs_malloc(nr * sizeof *y);
  int *select = mfs_malloc((size_t)ncv * sizeof *select);
  double *d = mfs_malloc((size_t)ncv * 2 * sizeof *d);
  st = s && resid && v && workd && workl && y && select && d ? MFS_OK : MFS_ENOMEM;
  st = agree(pm->comm, st);
  if (st == MFS_OK)
    st = work_alloc(pm, &w);
  if (st != MFS_OK)
    goto done;
  for (size_t i = 0; i < nr; i++) {
    s[i] = 1.0 / sqrt(pm->ml[pm->rlocal[i]]);
    resid[i] = start_entry(pm->rdof[i]);
  }
  iparam[0] = 1; /* exact shifts */
  iparam[2] = maxiter;
  iparam[3] = 1;
  iparam[6] = 1; /* mode 1: M^-1/2 K M^-1/2 */
  mfs_lapack_reset();
  for (;;) {
    pdsaupd_(&pm->fcomm, &ido, "I", &n, "LA", &nev, &tol, resid, &ncv, v, &ldv, iparam, ipntr,
             workd, workl, &lworkl, &ainfo, 1, 2);
    if (mfs_lapack_last()->count > 0) { /* LAPACK inside, on the replicated small problem */
      st = mfs_eig_info_fail(info, MFS_EARPACK, "pdsaupd (LAPACK)", mfs_lapack_last()->info);
      goto done;
    }
    if (ido != -1 && ido != 1)
      break;
    const double *x = workd + ipntr[0] - 1;
    double *yy = workd + ipntr[1] - 1;
    for (size_t i = 0; i < nr; i++)
      w.xe[i] = s[i] * x[i];
    exchange(pm, &w);
    local_rows(pm->K, w.xe, yy);
    for (size_t i = 0; i < nr; i++)
      yy[i] *= s[i];
  }
  if (info) {
    info->iterations = iparam[2];
    info->matvecs = iparam[8];
    info->nconv = iparam[4];
    info->runs = 1;
  }
  if (ainfo != 0) {
    st = mfs_eig_info_fail(info, ainfo == 1 ? MFS_ENOCONV : MFS_EARPACK, "pdsaupd", ainfo);
    goto done;
  }
  int rvec = 1, einfo = 0;
  pdseupd_(&pm->fcomm, &rvec, "A", select, d, v, &ldv, &sigma, "I", &n, "LA", &nev, &tol, resid,
           &ncv, v, &ldv, iparam, ipntr, workd, workl, &lworkl, &einfo, 1, 1, 2);
  if (einfo == 0 && mfs_lapack_last()->count > 0)
    einfo = -1000 - mfs_lapack_last()->info;
  if (einfo != 0 || !isfinite(d[0])) {
    st = mfs_eig_info_fail(info, MFS_EARPACK, "pdseupd", einfo);
    goto done;
  }
  *lambda = d[0];
  /* the residual of the pencil's pair: v = M^-1/2 u */
  for (size_t i = 0; i < nr; i++)
    w.xe[i] = s[i] * v[i];
  exchange(pm, &w);
  local_rows(pm->K, w.xe, y);
  double r2 = 0.0, m2 = 0.0;
  for (size_t i = 0; i < nr; i++) {
    double mv = pm->ml[pm->rlocal[i]] * w.xe[i];
    r2 += (y[i] - d[0] * mv) * (y[i] - d[0] * mv);
    m2 += mv * mv;
  }
  r2 = psum(pm->comm, r2);
  m2 = psum(pm->comm, m2);
  if (info) {
    double res = sqrt(r2) / (fabs(d[0]) * sqrt(m2));
    info->residual = isfinite(res) ? res : INFINITY;
  }
  st = MFS_OK;
done:
  work_free(&w);
  mfs_free(s);
  mfs_free(resid);
  mfs_free(v);
  mfs_free(workd);
  mfs_free(workl);
  mfs_free(y);
  mfs_free(select);
  mfs_free(d);
  return st;
}

#endif /* MFS_HAVE_MPI */
