#include "mfs_dispersion.h"
#include "mfs_alloc.h"

#include <complex.h>
#undef I /* particle indices are called I here */
#ifndef CMPLX /* C11's; clang 14 with glibc 2.36 does not define it */
#define CMPLX(x, y) mfs_cmplx((x), (y))
static inline double complex mfs_cmplx(double re, double im)
{
  double complex z;
  ((double *)&z)[0] = re; /* a complex is an array of two reals (C11 6.2.5) */
  ((double *)&z)[1] = im;
  return z;
}
#endif
#include <lapacke.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_lapack.h"
#include "mfs_status.h"

#define P4(i, j, k, l) ((((i)*2 + (j)) * 2 + (k)) * 2 + (l))

/* Raw components of the folded sums: at most 2 x 2 blocks of 9. */
enum { MFS_DISP_NC = 36 };

typedef struct {
  int row, col;  /* branch indices: unit-cell particle * ndof + dof (plane: the particles) */
  double d[2];   /* x_K - x_I */
  double A, G, M;
  double A2[4], G2[4]; /* plane strain: A^{jl}, G^{jk} */
  int ij[2];           /* plane strain: d = i a1 + j a2 */
} disp_term;

struct mfs_disp_plan {
  mfs_disp_spec spec;
  int nb, ndof, nbr;
  int plane;            /* 2D plane strain: tensor terms contracted with a state */
  int euler2;           /* ... with an Eulerian kernel (current geometry) */
  int finite;           /* the state is the finite material's at the plan's stretch */
  mfs_plane_state st0;  /* that state */
  double R[2][2];  /* primitive translations of the unit cell */
  double a1[2], a2[2];
  int mij;         /* the largest |i|, |j| of the terms' offsets */
  size_t nterm;
  disp_term *t;
  /* The lattice sums folded over pairs of opposite offsets (fold_build), for
   * the evaluators: the raw values of every block (row, col) of particles,
   * nraw per block (scalar: A, G, M; plane strain: A^{jl}, G^{jk}, M), nc in
   * all; their sums over all terms (k = 0), and per offset of the half plane
   * their symmetric and antisymmetric parts, kept for the components that
   * are not zero everywhere. */
  int nraw, nc;
  int upper;              /* Hermitian symbols: the blocks row <= col only (the rest is their adjoint) */
  double c0[MFS_DISP_NC], corig[MFS_DISP_NC]; /* sums over all terms, over those at d = 0 */
  size_t no;
  int *oi, *oj;           /* the offsets d = i a1 + j a2: i > 0, or i = 0 and j > 0 */
  int nsym, nanti;        /* components kept */
  int csym[MFS_DISP_NC], canti[MFS_DISP_NC];
  double *sym, *anti;     /* no x nsym, no x nanti */
};

static int hermitian(const mfs_disp_plan *dp);

static const char *const support_names[] = {"volume", "reference"};

const char *mfs_support_rule_name(mfs_support_rule r)
{
  return (unsigned)r < 2 ? support_names[r] : "?";
}

mfs_status mfs_support_rule_parse(const char *name, mfs_support_rule *r)
{
  for (int i = 0; name && i < 2; i++)
    if (strcmp(name, support_names[i]) == 0) {
      *r = (mfs_support_rule)i;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

void mfs_disp_plan_free(mfs_disp_plan *pl)
{
  if (!pl)
    return;
  mfs_free(pl->t);
  mfs_free(pl->oi);
  mfs_free(pl->oj);
  mfs_free(pl->sym);
  mfs_free(pl->anti);
  mfs_free(pl);
}

int mfs_disp_branches(const mfs_disp_plan *pl)
{
  return pl->nbr;
}

const mfs_disp_spec *mfs_disp_plan_spec(const mfs_disp_plan *pl)
{
  return &pl->spec;
}

/* Unit-cell class of particle I: the star pattern (cells cut by alternating
 * diagonals) has two particles per cell. */
static int node_class(const mfs_particles *p, size_t I)
{
  if (p->dim == 2 && p->lattice == MFS_LATTICE_SQUARE && p->cells == MFS_CELLS_STAR)
    return (p->ij[2 * I] + p->ij[2 * I + 1]) & 1;
  return 0;
}

/* A new term at the end of dp->t (grown by doubling); NULL when out of memory. */
static disp_term *push_term(mfs_disp_plan *dp, size_t *cap)
{
  if (dp->nterm == *cap) {
    size_t ncap = 2 * *cap + 64;
    disp_term *t = mfs_realloc(dp->t, ncap * sizeof *t);
    if (!t)
      return NULL;
    dp->t = t;
    *cap = ncap;
  }
  return dp->t + dp->nterm++;
}

/* The terms of the assembled row of unit-cell particle I (columns sorted by
 * particle), with the lattice offset x_K - x_I of every coupling. */
static int add_terms(mfs_disp_plan *dp, const mfs_particles *p, const mfs_row *r, size_t I,
                     size_t *cap, double mscale)
{
  const mfs_disc *d = &dp->spec.disc;
  int nd = dp->ndof, cls = node_class(p, I);
  double msum[2] = {0.0, 0.0};
  if (dp->plane) { /* one term per particle pair: A^{jl}, G^{jk}, M */
    double ms = 0.0;
    for (size_t s = 0; s < r->len; s++) {
      size_t K = (size_t)r->col[s];
      double dd[3] = {0.0, 0.0, 0.0};
      mfs_box_delta(&p->box, p->x + I * p->dim, p->x + K * p->dim, dd);
      disp_term *t = push_term(dp, cap);
      if (!t)
        return MFS_ENOMEM;
      *t = (disp_term){.row = cls, .col = node_class(p, K), .d = {dd[0], dd[1]},
                       .M = d->consistent_mass ? mscale * r->M[s] : 0.0};
      memcpy(t->A2, r->K + s * 4, sizeof t->A2);
      if (r->G)
        memcpy(t->G2, r->G + s * 4, sizeof t->G2);
      ms += r->M[s];
    }
    if (!d->shape->partition_of_unity)
      ms = p->vol[I];
    if (d->node_volume_mass) /* eq. 119's node volume */
      ms = mfs_particles_node_volume(p);
    if (!d->consistent_mass) {
      disp_term *t = push_term(dp, cap);
      if (!t)
        return MFS_ENOMEM;
      *t = (disp_term){.row = cls, .col = cls, .M = mscale * ms};
    }
    return MFS_OK;
  }
  for (size_t s = 0; s < r->len; s++) {
    size_t K = (size_t)r->col[s];
    double dd[3] = {0.0, 0.0, 0.0};
    mfs_box_delta(&p->box, p->x + I * p->dim, p->x + K * p->dim, dd);
    int ck = node_class(p, K);
    for (int a = 0; a < nd; a++) {
      msum[a] += r->M[s];
      for (int c = 0; c < nd; c++) {
        disp_term *t = push_term(dp, cap);
        if (!t)
          return MFS_ENOMEM;
        *t = (disp_term){.row = cls * nd + a,
                         .col = ck * nd + c,
                         .d = {dd[0], dd[1]},
                         .A = r->K[s * nd * nd + a * nd + c],
                         .G = nd == 1 && r->G ? r->G[s] : 0.0,
                         .M = (d->consistent_mass && a == c) ? r->M[s] : 0.0};
      }
    }
  }
  if (!d->shape->partition_of_unity) /* sph: particle mass rho V (eq. 51) */
    msum[0] = msum[1] = p->vol[I];
  if (d->node_volume_mass) /* eq. 119's node volume */
    msum[0] = msum[1] = mfs_particles_node_volume(p);
  if (!d->consistent_mass) /* lumped: row sums on the diagonal */
    for (int a = 0; a < nd; a++) {
      disp_term *t = push_term(dp, cap);
      if (!t)
        return MFS_ENOMEM;
      *t = (disp_term){.row = cls * nd + a, .col = cls * nd + a, .M = msum[a]};
    }
  return MFS_OK;
}

/* The raw values of term t (scalar: A, G, M; plane strain: A^{jl}, G^{jk}, M). */
static void term_raw(const mfs_disp_plan *dp, const disp_term *t, double *r)
{
  if (dp->plane) {
    memcpy(r, t->A2, 4 * sizeof *r);
    memcpy(r + 4, t->G2, 4 * sizeof *r);
    r[8] = t->M;
  } else {
    r[0] = t->A;
    r[1] = t->G;
    r[2] = t->M;
  }
}

typedef struct {
  int i, j, sign; /* the offset in the half plane, and +1 or -1 for the term's own */
  size_t t;
} fold_key;

static int cmp_key(const void *a, const void *b)
{
  const fold_key *x = a, *y = b;
  if (x->i != y->i)
    return (x->i > y->i) - (x->i < y->i);
  if (x->j != y->j)
    return (x->j > y->j) - (x->j < y->j);
  return (x->t > y->t) - (x->t < y->t);
}

/* Fold the terms over pairs of opposite offsets:
 *   sum_t c_t e^{ik.d_t} = c(0) + sum_o (c_o + c_-o) cos k.d_o + i sum_o (c_o - c_-o) sin k.d_o
 *                        = sum_t c_t - sum_o (c_o + c_-o) (1 - cos k.d_o) + i ...
 * over the offsets o of the half plane (c_o the value at d_o, c_-o at -d_o,
 * c(0) at d = 0).  Long waves take the second form: the versine keeps them
 * exact to rounding, where cosines near 1 would cancel against c(0) (the
 * stiffness has sum_t c_t ~ 0, a rigid translation); shorter ones the first,
 * whose cosines carry half the rounding of a versine near 2. */
static mfs_status fold_build(mfs_disp_plan *dp)
{
  dp->nraw = dp->plane ? 9 : 3;
  dp->nc = dp->nb * dp->nb * dp->nraw;
  mfs_status st = MFS_ENOMEM;
  fold_key *key = mfs_malloc((dp->nterm + 1) * sizeof *key);
  double *pm = NULL; /* per offset: the c_o (nc) then the c_-o (nc) */
  if (!key)
    goto done;
  size_t nk = 0;
  memset(dp->c0, 0, sizeof dp->c0);
  memset(dp->corig, 0, sizeof dp->corig);
  for (size_t t = 0; t < dp->nterm; t++) {
    const disp_term *tt = dp->t + t;
    double r[9];
    term_raw(dp, tt, r);
    int blk = (tt->row * dp->nb + tt->col) * dp->nraw;
    for (int q = 0; q < dp->nraw; q++)
      dp->c0[blk + q] += r[q];
    int i = tt->ij[0], j = tt->ij[1];
    if (i == 0 && j == 0) {
      for (int q = 0; q < dp->nraw; q++)
        dp->corig[blk + q] += r[q];
      continue;
    }
    int pos = i > 0 || (i == 0 && j > 0);
    key[nk++] = (fold_key){.i = pos ? i : -i, .j = pos ? j : -j, .sign = pos ? 1 : -1, .t = t};
  }
  qsort(key, nk, sizeof *key, cmp_key);
  size_t no = 0;
  for (size_t q = 0; q < nk; q++)
    no += q == 0 || key[q].i != key[q - 1].i || key[q].j != key[q - 1].j;
  const int nc = dp->nc;
  dp->no = no;
  dp->oi = mfs_malloc((no + 1) * sizeof *dp->oi);
  dp->oj = mfs_malloc((no + 1) * sizeof *dp->oj);
  pm = mfs_calloc(2 * (no + 1) * (size_t)nc, sizeof *pm);
  if (!dp->oi || !dp->oj || !pm)
    goto done;
  size_t o = 0;
  for (size_t q = 0; q < nk; q++) {
    if (q > 0 && (key[q].i != key[q - 1].i || key[q].j != key[q - 1].j))
      o++;
    dp->oi[o] = key[q].i;
    dp->oj[o] = key[q].j;
    const disp_term *tt = dp->t + key[q].t;
    double r[9];
    term_raw(dp, tt, r);
    double *c = pm + (2 * o + (key[q].sign > 0 ? 0 : 1)) * (size_t)nc +
                (size_t)((tt->row * dp->nb + tt->col) * dp->nraw);
    for (int k = 0; k < dp->nraw; k++)
      c[k] += r[k];
  }
  /* keep the components that are not zero at every offset; of Hermitian
   * symbols only the blocks on and above the diagonal (every solve reads
   * that triangle: the contractions fill the rest as its adjoint) */
  dp->nsym = dp->nanti = 0;
  dp->upper = hermitian(dp);
  for (int c = 0; c < nc; c++) {
    const int blk = c / dp->nraw;
    if (dp->upper && blk / dp->nb > blk % dp->nb)
      continue;
    int s = 0, a = 0;
    for (o = 0; o < no; o++) {
      double p = pm[2 * o * (size_t)nc + c], m = pm[(2 * o + 1) * (size_t)nc + c];
      s |= p + m != 0.0;
      a |= p - m != 0.0;
    }
    if (s)
      dp->csym[dp->nsym++] = c;
    if (a)
      dp->canti[dp->nanti++] = c;
  }
  dp->sym = mfs_malloc((no * (size_t)dp->nsym + 1) * sizeof *dp->sym);
  dp->anti = mfs_malloc((no * (size_t)dp->nanti + 1) * sizeof *dp->anti);
  if (!dp->sym || !dp->anti)
    goto done;
  for (o = 0; o < no; o++) {
    const double *p = pm + 2 * o * (size_t)nc, *m = p + nc;
    for (int c = 0; c < dp->nsym; c++)
      dp->sym[o * (size_t)dp->nsym + c] = p[dp->csym[c]] + m[dp->csym[c]];
    for (int c = 0; c < dp->nanti; c++)
      dp->anti[o * (size_t)dp->nanti + c] = p[dp->canti[c]] - m[dp->canti[c]];
  }
  st = MFS_OK;
done:
  mfs_free(key);
  mfs_free(pm);
  return st;
}

/* MFS_OK or MFS_ENOTSUP for what the analysis does not cover. */
static int covered(const mfs_disp_spec *s)
{
  const mfs_disc *d = &s->disc;
  int plane = d->material.physics == MFS_PHYS_PLANE_STRAIN;
  int stretched = (s->stretch > 0.0 && s->stretch != 1.0) ||
                  (d->dim == 2 && s->stretch_y > 0.0 && s->stretch_y != 1.0);
  int finite = s->material.type != NULL;
  if (plane && (d->dim != 2 || s->ls_beta > 0.0))
    return MFS_ENOTSUP;
  if (d->dim == 2 && stretched && !(plane && finite))
    return MFS_ENOTSUP;
  if ((s->stress_yy != 0.0 || s->stress_xy != 0.0) && (!plane || finite))
    return MFS_ENOTSUP;
  if (finite && !plane)
    return MFS_ENOTSUP;
  /* the consistent frame: shapes with position derivatives; a pre-stretch
   * moves interpolated points exactly with sum_K phi_K u~_K only for
   * linearly complete shapes */
  if (d->frame == MFS_FRAME_EULERIAN_CONSISTENT &&
      ((d->dim == 1 && !d->shape->dpos_1d) || (d->dim == 2 && !plane) ||
       (d->dim == 2 && !d->shape->dpos) ||
       (d->dim == 1 && stretched && !d->shape->linear_complete)))
    return MFS_ENOTSUP;
  return MFS_OK;
}

static int star_cell(const mfs_disc *d)
{
  return d->dim == 2 && d->quadrature->cells == MFS_CELLS_STAR;
}

/* Keep the quadrature points that see one of the unit-cell particles
 * 0 .. nb-1 (within a): the rows of the unit cell need no other, and the
 * per-state plans of an Eulerian map tabulate only these. */
static void keep_near(mfs_quad *q, const mfs_particles *p, int nb, double a)
{
  size_t m = 0;
  for (size_t Q = 0; Q < q->n; Q++) {
    int near = 0;
    for (int b = 0; b < nb && !near; b++) {
      double dd[3];
      mfs_box_delta(&p->box, q->x + 2 * Q, p->x + 2 * (size_t)b, dd);
      near = dd[0] * dd[0] + dd[1] * dd[1] < a * a * (1.0 + 1e-12);
    }
    if (!near)
      continue;
    q->x[2 * m] = q->x[2 * Q];
    q->x[2 * m + 1] = q->x[2 * Q + 1];
    q->w[m] = q->w[Q];
    q->node[m] = q->node[Q];
    m++;
  }
  q->n = m;
}

/* Map a periodic box of the reference lattice to the current one, x = F X
 * with F = diag(l1, l2): positions, box, lattice vectors, cells, volumes and
 * weights (times J). */
static void stretch_box(mfs_particles *p, mfs_quad *q, double l1, double l2)
{
  const double l[2] = {l1, l2}, J = l1 * l2;
  for (size_t i = 0; i < p->n; i++) {
    p->x[2 * i] *= l1;
    p->x[2 * i + 1] *= l2;
    p->vol[i] *= J;
  }
  for (int k = 0; k < 2; k++) {
    p->box.lo[k] *= l[k];
    p->box.hi[k] *= l[k];
    p->a1[k] *= l[k];
    p->a2[k] *= l[k];
  }
  p->dx *= l1;
  p->dy *= l2;
  for (size_t i = 0; i < p->ncell * (size_t)p->nvert; i++) {
    p->cellx[2 * i] *= l1;
    p->cellx[2 * i + 1] *= l2;
  }
  for (size_t Q = 0; Q < q->n; Q++) {
    q->x[2 * Q] *= l1;
    q->x[2 * Q + 1] *= l2;
    q->w[Q] *= J;
  }
}

mfs_disp_plan *mfs_disp_plan_alloc(const mfs_disp_spec *s, mfs_status *status)
{
  mfs_status st = MFS_EINVAL;
  mfs_disp_plan *dp = NULL;
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_plan *pl = NULL;
  mfs_row r = {0};
  if (!s || s->ls_beta < 0.0 || !(s->stretch >= 0.0) || !isfinite(s->ls_beta) ||
      !(s->stretch_y >= 0.0) || !isfinite(s->stretch) || !isfinite(s->stretch_y) ||
      !isfinite(s->stress_yy) || !isfinite(s->stress_xy) || !s->disc.kernel || !s->disc.shape ||
      (unsigned)s->support > MFS_SUPPORT_REFERENCE || (s->material.type && !s->material.type->finite))
    goto done;
  if ((st = covered(s)) != MFS_OK)
    goto done;
  st = MFS_EINVAL;
  mfs_disc d = s->disc; /* normalized: dx = 1, C = rho = 1 */
  d.source.spacing = 1.0;
  d.material.modulus = d.material.density = 1.0;
  if (mfs_disc_check(&d, NULL) != MFS_OK || !mfs_disc_infinite(&d))
    goto done;
  st = MFS_ENOMEM;
  dp = mfs_calloc(1, sizeof *dp);
  if (!dp)
    goto done;
  dp->spec = *s;
  dp->spec.disc = d;
  dp->ndof = mfs_physics_ndof(d.material.physics);
  dp->plane = d.material.physics == MFS_PHYS_PLANE_STRAIN;
  dp->euler2 = dp->plane && d.frame != MFS_FRAME_LAGRANGIAN;
  dp->finite = dp->plane && s->material.type != NULL;
  double l1 = 1.0, l2 = 1.0;
  if (dp->plane) {
    l1 = s->stretch > 0.0 ? s->stretch : 1.0;
    l2 = s->stretch_y > 0.0 ? s->stretch_y : 1.0;
    dp->spec.stretch = l1;
    dp->spec.stretch_y = l2;
    st = dp->finite ? mfs_plane_state_stretch(&s->material, l1, l2, &dp->st0) : MFS_OK;
    if (st != MFS_OK)
      goto done;
  }
  /* the Eulerian lattice of a plane-strain analysis is the current one,
   * with the kernel radius of the support rule */
  double gl1 = dp->euler2 ? l1 : 1.0, gl2 = dp->euler2 ? l2 : 1.0;
  double a = d.dilation * (dp->euler2 && s->support == MFS_SUPPORT_VOLUME ? sqrt(gl1 * gl2) : 1.0);

  double gamma = d.source.gamma > 0.0 ? d.source.gamma : 1.0;
  double hy = d.source.lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 : gamma;
  int nx = 2 * (int)ceil(2.0 * a / gl1) + 4;
  int ny = 2 * (int)ceil(2.0 * a / (hy * gl2)) + 4;
  st = mfs_disc_periodic_box(&d, nx, ny, &p, &q);
  if (st != MFS_OK)
    goto done;
  if (dp->euler2) {
    stretch_box(p, q, gl1, gl2);
    keep_near(q, p, star_cell(&d) ? 2 : 1, a);
  }
  int euler = d.frame != MFS_FRAME_LAGRANGIAN &&
              ((d.dim == 1 && d.material.physics == MFS_PHYS_SCALAR) || dp->euler2);
  mfs_disc dplan = d;
  dplan.dilation = a / p->dx; /* the plan's radius is dilation * p->dx */
  pl = mfs_plan_alloc(&dplan, p, q, &st);
  if (!pl)
    goto done;
  st = mfs_plan_tabulate(pl, euler || s->ls_beta > 0.0 ? 2 : 1, NULL);
  if (st != MFS_OK)
    goto done;

  int star = star_cell(&d);
  dp->nb = star ? 2 : 1;
  dp->nbr = dp->nb * dp->ndof;
  memcpy(dp->a1, p->a1, sizeof dp->a1);
  memcpy(dp->a2, p->a2, sizeof dp->a2);
  if (star) {
    dp->R[0][0] = p->a1[0] + p->a2[0];
    dp->R[0][1] = p->a1[1] + p->a2[1];
    dp->R[1][0] = p->a1[0] - p->a2[0];
    dp->R[1][1] = p->a1[1] - p->a2[1];
  } else {
    memcpy(dp->R[0], p->a1, sizeof dp->R[0]);
    memcpy(dp->R[1], p->a2, sizeof dp->R[1]);
  }
  /* stiffness with C = 1 (plane strain: mu = 1, lambda from nu), the mass
   * with rho = 1 (the lumped mass is its row sum), the Eulerian and
   * least-squares terms */
  mfs_forms f = mfs_forms_stiffness(&d.material);
  f.density = 1.0;
  f.euler = !euler ? MFS_EULER_NONE
            : d.frame == MFS_FRAME_EULERIAN_CONSISTENT ? MFS_EULER_CONSISTENT
                                                       : MFS_EULER_PAPER;
  f.stretch = s->stretch > 0.0 ? s->stretch : 1.0;
  f.stretch_y = l2;
  f.ls_beta = s->ls_beta;
  f.outer = dp->plane;
  /* the mass is rho0 V0: the current volumes J V0 times rho = rho0 / J */
  double mscale = dp->euler2 ? 1.0 / (gl1 * gl2) : 1.0;
  if ((st = mfs_row_init(&r, pl, &f)) != MFS_OK)
    goto done;
  size_t cap = 0;
  for (int b = 0; b < dp->nb; b++) {
    size_t I = (size_t)b; /* particles 0 and 1: (0,0) and (1,0) of the lattice */
    if ((st = mfs_row_assemble(&r, pl, &f, I)) != MFS_OK)
      goto done;
    mfs_row_sort(&r);
    if ((st = add_terms(dp, p, &r, I, &cap, mscale)) != MFS_OK)
      goto done;
  }
  { /* the lattice coordinates of every offset, for the phase tables */
    double det = dp->a1[0] * dp->a2[1] - dp->a1[1] * dp->a2[0];
    for (size_t i = 0; i < dp->nterm; i++) {
      disp_term *t = dp->t + i;
      double u = d.dim == 1 ? t->d[0] / dp->a1[0]
                            : (t->d[0] * dp->a2[1] - t->d[1] * dp->a2[0]) / det;
      double v = d.dim == 1 ? 0.0 : (dp->a1[0] * t->d[1] - dp->a1[1] * t->d[0]) / det;
      t->ij[0] = (int)lround(u);
      t->ij[1] = (int)lround(v);
      int m = abs(t->ij[0]) > abs(t->ij[1]) ? abs(t->ij[0]) : abs(t->ij[1]);
      dp->mij = m > dp->mij ? m : dp->mij;
    }
  }
  if ((st = fold_build(dp)) != MFS_OK)
    goto done;
  st = MFS_OK;
done:
  mfs_row_free(&r);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  if (st != MFS_OK) {
    mfs_disp_plan_free(dp);
    dp = NULL;
  }
  if (status)
    *status = st;
  return dp;
}

mfs_status mfs_disp_state(const mfs_disp_plan *dp, double sbar, mfs_plane_state *s)
{
  if (!dp->plane)
    return MFS_EINVAL;
  if (dp->finite) {
    if (sbar != 0.0)
      return MFS_EINVAL;
    *s = dp->st0;
    return MFS_OK;
  }
  return mfs_plane_state_linear(dp->spec.disc.material.poisson, sbar, dp->spec.stress_yy,
                                dp->spec.stress_xy, s);
}

/* The lattice sums of the raw components at one wave vector: s[(row nb +
 * col) nraw + q] (plane strain: q < 4 A^{jl}, q < 8 G^{jk}, q = 8 the mass). */
typedef struct {
  double complex s[MFS_DISP_NC];
} raw_sums;

enum { MAX_MIJ = 256 };

/* The direct sums, term by term (the reference for the folded sums): e^{ik.d}
 * = e^{i i k.a1} e^{i j k.a2} from tables of powers, sincos of each power. */
static void plane_sum(const mfs_disp_plan *dp, const double *k, raw_sums *ps)
{
  memset(ps, 0, sizeof *ps);
  int M = dp->mij < MAX_MIJ ? dp->mij : MAX_MIJ;
  double complex p1[2 * MAX_MIJ + 1], p2[2 * MAX_MIJ + 1];
  double ph1 = k[0] * dp->a1[0] + k[1] * dp->a1[1], ph2 = k[0] * dp->a2[0] + k[1] * dp->a2[1];
  p1[M] = p2[M] = 1.0;
  for (int m = 1; m <= M; m++) {
    p1[M + m] = cos(m * ph1) + _Complex_I * sin(m * ph1);
    p2[M + m] = cos(m * ph2) + _Complex_I * sin(m * ph2);
    p1[M - m] = conj(p1[M + m]);
    p2[M - m] = conj(p2[M + m]);
  }
  for (size_t i = 0; i < dp->nterm; i++) {
    const disp_term *t = dp->t + i;
    double complex e;
    if (abs(t->ij[0]) <= M && abs(t->ij[1]) <= M) {
      e = p1[M + t->ij[0]] * p2[M + t->ij[1]];
    } else {
      double ph = k[0] * t->d[0] + k[1] * t->d[1];
      e = cos(ph) + _Complex_I * sin(ph);
    }
    double complex *s = ps->s + (t->row * dp->nb + t->col) * 9;
    for (int q = 0; q < 4; q++)
      s[q] += t->A2[q] * e;
    if (dp->euler2)
      for (int q = 0; q < 4; q++)
        s[4 + q] += t->G2[q] * e;
    s[8] += t->M * e;
  }
}

/* The blocks below the diagonal of K and M (n x n, blocks of bs) as the
 * adjoints of those above. */
static void lower_adjoint(int n, int bs, double complex *K, double complex *M)
{
  for (int r = bs; r < n; r++)
    for (int c = 0; c < r / bs * bs; c++) {
      K[r * n + c] = conj(K[c * n + r]);
      M[r * n + c] = conj(M[c * n + r]);
    }
}

/* K and M (nbr x nbr) of a state from the sums: Lagrangian K_ik = A_ijkl SA^{jl};
 * Eulerian K_ik = a_ijkl SA^{jl} + sigma_im SA^{km} + sigma_ij SG^{jk} (eq. C6);
 * upper: the sums of the blocks row <= col only, the rest their adjoints. */
static void plane_contract(const mfs_disp_plan *dp, const raw_sums *ps, const mfs_plane_state *st,
                           int upper, double complex *K, double complex *M)
{
  const int n = dp->nbr;
  const double *t = dp->euler2 ? st->a : st->A, *sg = st->sigma;
  for (int rb = 0; rb < dp->nb; rb++)
    for (int cb = upper ? rb : 0; cb < dp->nb; cb++) {
      const double complex *A = ps->s + (rb * dp->nb + cb) * 9, *G = A + 4;
      for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
          double complex v = 0.0;
          for (int j = 0; j < 2; j++)
            for (int l = 0; l < 2; l++)
              v += t[P4(i, j, k, l)] * A[j * 2 + l];
          if (dp->euler2)
            for (int m = 0; m < 2; m++)
              v += sg[i * 2 + m] * A[k * 2 + m] + sg[i * 2 + m] * G[m * 2 + k];
          K[(rb * 2 + i) * n + cb * 2 + k] = v;
          M[(rb * 2 + i) * n + cb * 2 + k] = i == k ? A[8] : 0.0;
        }
    }
  if (upper)
    lower_adjoint(n, 2, K, M);
}

/* The scalar operator's coefficients at stress sbar: K = ca A + cg G. */
static void scalar_coef(const mfs_disp_plan *dp, double sbar, double *ca, double *cg)
{
  const mfs_disc *s = &dp->spec.disc;
  double F = dp->spec.stretch > 0.0 ? dp->spec.stretch : 1.0;
  if (s->dim == 1 && s->frame != MFS_FRAME_LAGRANGIAN) {
    *ca = 1.0 + 2.0 * sbar; /* C~ + sigma, eq. 75 */
    *cg = sbar;
  } else if (s->dim == 1) {
    *ca = F * F + sbar; /* C-bar = C F^2 + S, eq. 81 */
    *cg = 0.0;
  } else {
    *ca = 1.0 + sbar;
    *cg = 0.0;
  }
}

/* K and M (nbr x nbr) of the scalar operator from the sums (upper: as
 * plane_contract). */
static void scalar_contract(const mfs_disp_plan *dp, const raw_sums *ps, double ca, double cg,
                            int upper, double complex *K, double complex *M)
{
  const int nb = dp->nb;
  for (int b = 0; b < nb * nb; b++) {
    if (upper && b / nb > b % nb)
      continue;
    const double complex *s = ps->s + b * 3;
    K[b] = CMPLX(ca * creal(s[0]) + cg * creal(s[1]), ca * cimag(s[0]) + cg * cimag(s[1]));
    M[b] = s[2];
  }
  if (upper)
    lower_adjoint(nb, 1, K, M);
}

static int same_stretch(const mfs_disp_plan *dp, const mfs_plane_state *s)
{
  return !dp->euler2 || (fabs(s->l[0] - dp->spec.stretch) <= 1e-14 * dp->spec.stretch &&
                         fabs(s->l[1] - dp->spec.stretch_y) <= 1e-14 * dp->spec.stretch_y);
}

mfs_status mfs_disp_symbols_state(const mfs_disp_plan *dp, const mfs_plane_state *s,
                                  const double *k, double complex *K, double complex *M)
{
  if (!dp->plane || !s || !same_stretch(dp, s))
    return MFS_EINVAL;
  raw_sums ps;
  plane_sum(dp, k, &ps);
  plane_contract(dp, &ps, s, 0, K, M);
  return MFS_OK;
}

mfs_status mfs_disp_symbols(const mfs_disp_plan *dp, double sbar, const double *k,
                            double complex *K, double complex *M)
{
  const mfs_disc *s = &dp->spec.disc;
  int n = dp->nbr;
  if (dp->plane) {
    mfs_plane_state st;
    mfs_status e = mfs_disp_state(dp, sbar, &st);
    return e != MFS_OK ? e : mfs_disp_symbols_state(dp, &st, k, K, M);
  }
  double ca, cg;
  scalar_coef(dp, sbar, &ca, &cg);
  for (int i = 0; i < n * n; i++)
    K[i] = M[i] = 0.0;
  for (size_t i = 0; i < dp->nterm; i++) {
    const disp_term *t = dp->t + i;
    double ph = k[0] * t->d[0] + (s->dim > 1 ? k[1] * t->d[1] : 0.0);
    double complex e = cos(ph) + _Complex_I * sin(ph);
    K[t->row * n + t->col] += (ca * t->A + cg * t->G) * e;
    M[t->row * n + t->col] += t->M * e;
  }
  return MFS_OK;
}

static int cmp_re(const void *a, const void *b)
{
  double x = creal(*(const double complex *)a), y = creal(*(const double complex *)b);
  return (x > y) - (x < y);
}

/* x / y; by a real y without the complex division (the lumped masses). */
static inline double complex cdiv(double complex x, double complex y)
{
  return cimag(y) == 0.0 ? CMPLX(creal(x) / creal(y), cimag(x) / creal(y)) : x / y;
}

/* omega^2 = K / M of one branch. */
static inline mfs_status solve1(double complex K, double complex M, int herm, double complex *omega2)
{
  if (M == 0.0)
    return MFS_EDOMAIN;
  if (herm)
    *omega2 = creal(K) / creal(M);
  else
    *omega2 = cdiv(K, M);
  return isfinite(creal(*omega2)) && isfinite(cimag(*omega2)) ? MFS_OK : MFS_EDOMAIN;
}

/* The eigenvalues of Hermitian n x n matrices, n <= 4, ascending, given by
 * their real and imaginary parts (row-major; the triangle c >= r is read):
 * each reduced by Householder reflections to a real symmetric tridiagonal one
 * (the moduli of the complex subdiagonal: a diagonal unitary similarity),
 * then the implicit QL iteration with Wilkinson's shift (EISPACK's tql1;
 * LAPACK's zhegv does the same two steps, zhetrd and dsterf).  Fixed-size
 * kernels in real arithmetic: no call, no workspace, no threads (zhegv's calls
 * into the threaded BLAS cost 20 times the arithmetic at this size), no
 * complex multiplication (C's has a NaN-recovery branch per product), no
 * hypot (the entries are neither huge nor tiny: the symbols are O(1) to
 * O(1e4)). */
#if defined(__GNUC__)
#define HERM_INLINE __attribute__((always_inline)) inline /* n a constant where called */
#else
#define HERM_INLINE inline
#endif

static HERM_INLINE void herm_tridiag(int n, const double *Ar, const double *Ai, double *d,
                                     double *e)
{
  double br[16], bi[16];
  for (int i = 0; i < 4; i++)
    e[i] = 0.0;
  for (int r = 0; r < n; r++) {
    br[r * n + r] = Ar[r * n + r];
    bi[r * n + r] = 0.0;
    for (int c = r + 1; c < n; c++) {
      br[r * n + c] = br[c * n + r] = Ar[r * n + c];
      bi[r * n + c] = Ai[r * n + c];
      bi[c * n + r] = -Ai[r * n + c];
    }
  }
  for (int k = 0; k + 2 < n; k++) {
    /* x = B[k+1..n)[k]; H = I - tau v v^H maps it to alpha e_1, |alpha| = |x| */
    double tail = 0.0;
    for (int i = k + 2; i < n; i++)
      tail += br[i * n + k] * br[i * n + k] + bi[i * n + k] * bi[i * n + k];
    const double x0r = br[(k + 1) * n + k], x0i = bi[(k + 1) * n + k];
    const double a2 = x0r * x0r + x0i * x0i, ax0 = sqrt(a2), xn = sqrt(a2 + tail);
    e[k] = xn;
    if (tail == 0.0) /* already tridiagonal in this column */
      continue;
    double vr[4], vi[4], pr[4], pi[4];
    const double phr = ax0 > 0.0 ? x0r / ax0 : 1.0, phi = ax0 > 0.0 ? x0i / ax0 : 0.0;
    vr[k + 1] = phr * (ax0 + xn);
    vi[k + 1] = phi * (ax0 + xn);
    for (int i = k + 2; i < n; i++) {
      vr[i] = br[i * n + k];
      vi[i] = bi[i * n + k];
    }
    const double tau = 1.0 / (xn * (xn + ax0)); /* 2 / |v|^2 */
    /* B <- H B H on the trailing block: p = tau B v, q = p - (tau/2)(v^H p) v,
     * B -= v q^H + q v^H */
    double vp = 0.0;
    for (int i = k + 1; i < n; i++) {
      double tr = 0.0, ti = 0.0;
      for (int j = k + 1; j < n; j++) {
        tr += br[i * n + j] * vr[j] - bi[i * n + j] * vi[j];
        ti += br[i * n + j] * vi[j] + bi[i * n + j] * vr[j];
      }
      pr[i] = tau * tr;
      pi[i] = tau * ti;
      vp += vr[i] * pr[i] + vi[i] * pi[i];
    }
    const double half = 0.5 * tau * vp;
    for (int i = k + 1; i < n; i++) {
      pr[i] -= half * vr[i];
      pi[i] -= half * vi[i];
    }
    for (int i = k + 1; i < n; i++)
      for (int j = k + 1; j < n; j++) {
        br[i * n + j] -= (vr[i] * pr[j] + vi[i] * pi[j]) + (pr[i] * vr[j] + pi[i] * vi[j]);
        bi[i * n + j] -= (vi[i] * pr[j] - vr[i] * pi[j]) + (pi[i] * vr[j] - pr[i] * vi[j]);
      }
  }
  for (int i = 0; i < n; i++)
    d[i] = br[i * n + i];
  if (n >= 2) {
    const double xr = br[(n - 1) * n + n - 2], xi = bi[(n - 1) * n + n - 2];
    e[n - 2] = sqrt(xr * xr + xi * xi);
  }
  e[n - 1] = 0.0;
}

enum { HERM_LANES = 8 }; /* matrices per call of herm_small_eigvals */

/* QL on the tridiagonal d[4 p ..], e[4 p ..] of np <= HERM_LANES matrices in
 * turn, one iteration of each at a time: the iterations of different
 * matrices are independent (their square roots and divisions overlap, where
 * one matrix's chain of them waits on each), and each matrix sees the same
 * operations in the same order as alone.  bad[p]: an eigenvalue took more
 * than 30 iterations (not seen: the iteration converges cubically). */
static HERM_INLINE void tql_lanes(int n, int np, double *D, double *E, int *bad)
{
  int L[HERM_LANES], it[HERM_LANES], live = np;
  for (int p = 0; p < np; p++) {
    L[p] = it[p] = bad[p] = 0;
    E[4 * p + n - 1] = 0.0;
  }
  while (live > 0) {
    live = 0;
    for (int p = 0; p < np; p++) {
      const int l = L[p];
      if (l >= n)
        continue;
      double *d = D + 4 * p, *e = E + 4 * p; /* e[i] couples d[i] and d[i + 1] */
      int m;
      for (m = l; m < n - 1; m++)
        if (fabs(e[m]) <= DBL_EPSILON * (fabs(d[m]) + fabs(d[m + 1])))
          break;
      live++;
      if (m == l) { /* d[l] has converged */
        L[p]++;
        it[p] = 0;
        continue;
      }
      if (m == l + 1) { /* a 2 x 2 block: its eigenvalues in closed form (LAPACK's dlae2) */
        const double sm = d[l] + d[m], df = d[l] - d[m], tb = 2.0 * e[l];
        const double rt = sqrt(df * df + tb * tb), big = fabs(d[l]) > fabs(d[m]) ? d[l] : d[m];
        const double sml = fabs(d[l]) > fabs(d[m]) ? d[m] : d[l];
        double r1 = 0.5 * (sm < 0.0 ? sm - rt : sm + rt), r2;
        if (sm == 0.0) {
          r1 = 0.5 * rt;
          r2 = -0.5 * rt;
        } else {
          r2 = (big / r1) * sml - (e[l] / r1) * e[l];
        }
        d[l] = r1;
        d[m] = r2;
        e[l] = 0.0;
        continue;
      }
      if (it[p]++ == 30) {
        bad[p] = 1;
        L[p] = n;
        continue;
      }
      /* Wilkinson's shift d[l] - e^2 / (h + sign(h) sqrt(h^2 + e^2)), h = (d[l + 1] - d[l]) / 2 */
      const double h = 0.5 * (d[l + 1] - d[l]), el = e[l];
      double g = d[m] - d[l] + el * el / (h + copysign(sqrt(h * h + el * el), h)), r;
      double s = 1.0, c = 1.0, q = 0.0;
      int i;
      for (i = m - 1; i >= l; i--) {
        double f = s * e[i], b = c * e[i];
        e[i + 1] = r = sqrt(f * f + g * g); /* no hypot: the symbols are O(1) to O(1e4) */
        if (r == 0.0) { /* split: deflate and start again */
          d[i + 1] -= q;
          e[m] = 0.0;
          break;
        }
        const double ir = 1.0 / r;
        s = f * ir;
        c = g * ir;
        g = d[i + 1] - q;
        r = (d[i] - g) * s + 2.0 * c * b;
        q = s * r;
        d[i + 1] = g + q;
        g = c * r - b;
      }
      if (r == 0.0 && i >= l)
        continue;
      d[l] -= q;
      e[l] = g;
      e[m] = 0.0;
    }
  }
}

/* The block kernels are compiled three times where the compiler can dispatch
 * at run time (GCC on x86-64 Linux: ifunc), for SSE2, AVX2 and x86-64-v4
 * (AVX-512): the same additions and multiplications, each rounded the same
 * way (-ffp-contract=off, meson.build: no FMA even where the processor has
 * it), so all give the same bits, the wider ones with more lanes per
 * instruction.  The AVX-512 build took 0.87-0.94 of the AVX2 build's time on
 * the 1D rays and 0.8-0.9 on the 2D ones (an AMD EPYC with AVX-512, the two
 * libraries alternating in one process). */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
  !defined(MFS_NO_CLONES)
#if __GNUC__ >= 11 /* the x86-64-v4 level is known from GCC 11 on */
#define MFS_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define MFS_CLONES __attribute__((target_clones("avx2", "default")))
#endif
#define MFS_INLINE __attribute__((always_inline)) inline /* into each clone */
#else
#define MFS_CLONES
#define MFS_INLINE inline
#endif

/* The eigenvalues of 4 x 4 Hermitian matrices, HERM_LANES at a time, in
 * GCC's and Clang's vector types of four lanes (plain C compilers: the QL
 * kernel above, matrix by matrix): the same Householder reduction to a real
 * tridiagonal as herm_tridiag, without branches (a column already reduced:
 * tau = 0), then cyclic Jacobi rotations (Rutishauser's; Golub and Van Loan
 * 8.5) in the parallel order {(0,1),(2,3)}, {(0,2),(1,3)}, {(0,3),(1,2)},
 * until the off-diagonal part is below eps/3 of the Frobenius norm: the
 * eigenvalues to a few eps of the norm (backward stable; double roots, the
 * crossings and kappa = 0 included), every lane the same operations (QL's
 * shifts, splits and deflations branch per matrix: 65% of the ray's time
 * went to mispredictions and to the chain of its square roots).  A lane
 * whose test passed does no more rotations (t = 0: the identity exactly),
 * so a matrix gets the same bits whatever the other lanes hold. */
#if defined(__GNUC__)
#define HERM4_VEC 1
/* v4d only in functions inlined into each clone: no ABI crosses (GCC warns at
 * the end of the file, so to its end) */
#pragma GCC diagnostic ignored "-Wpsabi"
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

static HERM_INLINE v4d v4_sqrt(v4d x)
{
#if defined(__SSE2__) /* the SSE2 instruction on each half (the base version) */
  union {
    v4d v;
    __m128d h[2];
  } u = {.v = x};
  u.h[0] = _mm_sqrt_pd(u.h[0]);
  u.h[1] = _mm_sqrt_pd(u.h[1]);
  return u.v;
#else
  return (v4d){sqrt(x[0]), sqrt(x[1]), sqrt(x[2]), sqrt(x[3])};
#endif
}

/* AVX's square root where the kernel is compiled for AVX2 (herm4_eigvals'
 * two versions): one costs about half of the two SSE2 ones here (measured:
 * 3.2 against 5.9 ns of throughput for four lanes); target_clones cannot
 * choose an intrinsic per clone, hence the two versions by hand */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__) && \
  !defined(MFS_NO_CLONES)
#define HERM4_AVX2 1
#include <immintrin.h>
static __attribute__((target("avx2"))) inline v4d v4_sqrt_avx(v4d x)
{
  return (v4d)_mm256_sqrt_pd((__m256d)x);
}
#endif

static HERM_INLINE v4d v4_sqrtv(v4d x, const int avx)
{
#ifdef HERM4_AVX2
  if (avx)
    return v4_sqrt_avx(x);
#else
  (void)avx;
#endif
  return v4_sqrt(x);
}

static HERM_INLINE v4d v4_sel(v4i m, v4d a, v4d b) /* m ? a : b, lane by lane */
{
  return (v4d)(((v4i)a & m) | ((v4i)b & ~m));
}

static HERM_INLINE v4d v4_abs(v4d x)
{
  const v4i sign = (v4i)(v4d){-0.0, -0.0, -0.0, -0.0};
  return (v4d)((v4i)x & ~sign);
}

/* One Jacobi rotation in the plane (p, q) of lanes whose mask f is clear:
 * B = J^T A J with J = [c s; -s c] on rows and columns p, q, which zeroes
 * a_pq; r, s the two other indices (a_rp, a_rq, a_sp, a_sq). */
static HERM_INLINE void v4_rot(v4d *app, v4d *aqq, v4d *apq, v4d *arp, v4d *arq, v4d *asp,
                              v4d *asq, v4i f, const int avx)
{
  const v4d one = {1.0, 1.0, 1.0, 1.0}, zero = {0.0, 0.0, 0.0, 0.0};
  const v4d h = *aqq - *app, a = *apq;
  const v4d rho = v4_sqrtv(h * h + 4.0 * a * a, avx), den = v4_abs(h) + rho;
  const v4i sg = (v4i)(v4d){-0.0, -0.0, -0.0, -0.0}, live = (den > zero) & ~f;
  /* t = tan theta = 2 a sign(h) / (|h| + rho), c = cos theta = sqrt((|h| + rho) / (2 rho))
   * (1 / sqrt(1 + t^2), by one square root after the division instead of
   * two operations), s = t c; the identity where den = 0 (a = h = 0) or frozen */
  const v4d t = v4_sel(live, (v4d)((v4i)(2.0 * a) ^ ((v4i)h & sg)) / den, zero);
  const v4d c = v4_sel(live, v4_sqrtv(den / (2.0 * rho), avx), one), s = t * c;
  *app -= t * a;
  *aqq += t * a;
  *apq = v4_sel(f, a, zero);
  const v4d rp = *arp, rq = *arq, sp = *asp, sq = *asq;
  *arp = c * rp - s * rq;
  *arq = s * rp + c * rq;
  *asp = c * sp - s * sq;
  *asq = s * sp + c * sq;
}

enum { JACOBI_SWEEPS = 12 }; /* the test passes after 3 to 5 sweeps (quadratic convergence) */

/* Four matrices: upper triangles ar[(r 4 + c) stride + p], ai likewise, lanes
 * p0 .. p0 + 3, to real symmetric tridiagonals a[] = a00 a11 a22 a33 a01 a02
 * a03 a12 a13 a23 (a02 = a03 = a13 = 0). */
static HERM_INLINE void herm4_tridiag(const double *ar, const double *ai, int p0, int stride,
                                     v4d *a, const int avx)
{
  v4d br[16], bi[16];
  for (int r = 0; r < 4; r++)
    for (int c = r; c < 4; c++) {
      v4d x, y;
      memcpy(&x, ar + (r * 4 + c) * stride + p0, sizeof x);
      memcpy(&y, ai + (r * 4 + c) * stride + p0, sizeof y);
      br[r * 4 + c] = br[c * 4 + r] = x;
      bi[r * 4 + c] = y;
      bi[c * 4 + r] = -y;
    }
  const v4d zero = {0.0, 0.0, 0.0, 0.0}, one = {1.0, 1.0, 1.0, 1.0};
  v4d e[3];
  for (int k = 0; k < 2; k++) { /* herm_tridiag's reflections, tau = 0 where tail = 0 */
    v4d tail = zero;
    for (int i = k + 2; i < 4; i++)
      tail += br[i * 4 + k] * br[i * 4 + k] + bi[i * 4 + k] * bi[i * 4 + k];
    const v4d x0r = br[(k + 1) * 4 + k], x0i = bi[(k + 1) * 4 + k];
    const v4d a2 = x0r * x0r + x0i * x0i, ax0 = v4_sqrtv(a2, avx), xn = v4_sqrtv(a2 + tail, avx);
    e[k] = xn;
    const v4i nz = ax0 > zero;
    const v4d phr = v4_sel(nz, x0r / ax0, one), phi = v4_sel(nz, x0i / ax0, zero);
    const v4d tau = v4_sel(tail > zero, one / (xn * (xn + ax0)), zero);
    v4d vr[4], vi[4], pr[4], pi[4];
    vr[k + 1] = phr * (ax0 + xn);
    vi[k + 1] = phi * (ax0 + xn);
    for (int i = k + 2; i < 4; i++) {
      vr[i] = br[i * 4 + k];
      vi[i] = bi[i * 4 + k];
    }
    v4d vp = zero;
    for (int i = k + 1; i < 4; i++) {
      v4d tr = zero, ti = zero;
      for (int j = k + 1; j < 4; j++) {
        tr += br[i * 4 + j] * vr[j] - bi[i * 4 + j] * vi[j];
        ti += br[i * 4 + j] * vi[j] + bi[i * 4 + j] * vr[j];
      }
      pr[i] = tau * tr;
      pi[i] = tau * ti;
      vp += vr[i] * pr[i] + vi[i] * pi[i];
    }
    const v4d half = 0.5 * tau * vp;
    for (int i = k + 1; i < 4; i++) {
      pr[i] -= half * vr[i];
      pi[i] -= half * vi[i];
    }
    for (int i = k + 1; i < 4; i++)
      for (int j = k + 1; j < 4; j++) {
        br[i * 4 + j] -= (vr[i] * pr[j] + vi[i] * pi[j]) + (pr[i] * vr[j] + pi[i] * vi[j]);
        bi[i * 4 + j] -= (vi[i] * pr[j] - vr[i] * pi[j]) + (pi[i] * vr[j] - pr[i] * vi[j]);
      }
  }
  e[2] = v4_sqrtv(br[3 * 4 + 2] * br[3 * 4 + 2] + bi[3 * 4 + 2] * bi[3 * 4 + 2], avx);
  const v4d zero4 = zero;
  a[0] = br[0], a[1] = br[5], a[2] = br[10], a[3] = br[15];
  a[4] = e[0], a[5] = zero4, a[6] = zero4, a[7] = e[1], a[8] = zero4, a[9] = e[2];
}

/* Jacobi on the two groups of four lanes at once (their chains of square
 * roots and divisions overlap): a[g][] as herm4_tridiag's; the diagonals
 * converge to the eigenvalues (unsorted); done[g] the lanes whose test passed. */
static HERM_INLINE void herm4_jacobi(v4d (*a)[10], v4i *done, const int avx)
{
  const double tol2 = DBL_EPSILON * DBL_EPSILON / 9.0;
  for (int sweep = 0;; sweep++) {
    int all = 1;
    for (int g = 0; g < 2; g++) {
      const v4d *x = a[g];
      const v4d off = (x[4] * x[4] + x[5] * x[5]) + (x[6] * x[6] + x[7] * x[7]) +
                      (x[8] * x[8] + x[9] * x[9]);
      const v4d fro = (x[0] * x[0] + x[1] * x[1]) + (x[2] * x[2] + x[3] * x[3]) + 2.0 * off;
      done[g] = off <= tol2 * fro;
      all = all && (done[g][0] & done[g][1] & done[g][2] & done[g][3]);
    }
    if (sweep == JACOBI_SWEEPS || all)
      break;
    /* a[] = a00 a11 a22 a33 a01 a02 a03 a12 a13 a23 */
    for (int g = 0; g < 2; g++) {
      v4d *x = a[g];
      v4_rot(x + 0, x + 1, x + 4, x + 5, x + 7, x + 6, x + 8, done[g], avx); /* (0,1): rows 2, 3 */
      v4_rot(x + 2, x + 3, x + 9, x + 5, x + 6, x + 7, x + 8, done[g], avx); /* (2,3): rows 0, 1 */
    }
    for (int g = 0; g < 2; g++) {
      v4d *x = a[g];
      v4_rot(x + 0, x + 2, x + 5, x + 4, x + 7, x + 6, x + 9, done[g], avx); /* (0,2): rows 1, 3 */
      v4_rot(x + 1, x + 3, x + 8, x + 4, x + 6, x + 7, x + 9, done[g], avx); /* (1,3): rows 0, 2 */
    }
    for (int g = 0; g < 2; g++) {
      v4d *x = a[g];
      v4_rot(x + 0, x + 3, x + 6, x + 4, x + 8, x + 5, x + 9, done[g], avx); /* (0,3): rows 1, 2 */
      v4_rot(x + 1, x + 2, x + 7, x + 4, x + 5, x + 8, x + 9, done[g], avx); /* (1,2): rows 0, 3 */
    }
  }
}

static HERM_INLINE void herm4_body(const double *ar, const double *ai, double *w, int *bad,
                                  const int avx)
{
  v4d a[2][10];
  v4i done[2];
  herm4_tridiag(ar, ai, 0, HERM_LANES, a[0], avx);
  herm4_tridiag(ar, ai, 4, HERM_LANES, a[1], avx);
  herm4_jacobi(a, done, avx);
  for (int g = 0; g < 2; g++) {
    for (int i = 0; i < 4; i++)
      memcpy(w + i * HERM_LANES + 4 * g, a[g] + i, sizeof a[g][i]);
    for (int l = 0; l < 4; l++)
      bad[4 * g + l] = !done[g][l];
  }
  for (int p = 0; p < HERM_LANES; p++) { /* a sorting network: min and max, no branch */
    double x[4] = {w[p], w[HERM_LANES + p], w[2 * HERM_LANES + p], w[3 * HERM_LANES + p]};
    static const int cmp[5][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}, {1, 2}};
    for (int q = 0; q < 5; q++) {
      const double u = x[cmp[q][0]], v = x[cmp[q][1]];
      x[cmp[q][0]] = u < v ? u : v;
      x[cmp[q][1]] = u < v ? v : u;
    }
    for (int i = 0; i < 4; i++)
      w[i * HERM_LANES + p] = x[i];
  }
}

static void herm4_eigvals_base(const double *ar, const double *ai, double *w, int *bad)
{
  herm4_body(ar, ai, w, bad, 0);
}

#ifdef HERM4_AVX2
__attribute__((target("avx2"))) static void herm4_eigvals_avx2(const double *ar, const double *ai,
                                                               double *w, int *bad)
{
  herm4_body(ar, ai, w, bad, 1);
}
#endif

/* The eigenvalues w[i HERM_LANES + p] (ascending in i) of the HERM_LANES
 * matrices of upper triangles ar[(r 4 + c) HERM_LANES + p], ai likewise;
 * bad[p] the lanes whose iteration did not converge.  The AVX2 version where
 * the processor has it (the same operations: the same bits). */
static void herm4_eigvals(const double *ar, const double *ai, double *w, int *bad)
{
#ifdef HERM4_AVX2
  if (__builtin_cpu_supports("avx2")) {
    herm4_eigvals_avx2(ar, ai, w, bad);
    return;
  }
#endif
  herm4_eigvals_base(ar, ai, w, bad);
}
#endif

/* The eigenvalues w[4 p ..] of the np <= HERM_LANES matrices Ar[16 p ..],
 * Ai[16 p ..]; bad[p] as tql_lanes. */
static void herm_small_eigvals(int n, int np, const double *Ar, const double *Ai, double *w,
                               int *bad)
{
  double D[4 * HERM_LANES], E[4 * HERM_LANES];
#ifdef HERM4_VEC
  if (n == 4) { /* the four branches of two particles in plane strain: herm4_eigvals */
    double sr[16 * HERM_LANES] = {0.0}, si[16 * HERM_LANES] = {0.0}, sw[4 * HERM_LANES];
    int sb[HERM_LANES];
    for (int p = 0; p < np; p++)
      for (int r = 0; r < 4; r++)
        for (int c = r; c < 4; c++) {
          sr[(r * 4 + c) * HERM_LANES + p] = Ar[16 * p + r * 4 + c];
          si[(r * 4 + c) * HERM_LANES + p] = Ai[16 * p + r * 4 + c];
        }
    herm4_eigvals(sr, si, sw, sb);
    for (int p = 0; p < np; p++) {
      bad[p] = sb[p];
      for (int i = 0; i < 4; i++)
        w[4 * p + i] = sw[i * HERM_LANES + p];
    }
    return;
  }
#endif
  if (n == 4) { /* the four branches of two particles in plane strain: unrolled */
    for (int p = 0; p < np; p++)
      herm_tridiag(4, Ar + 16 * p, Ai + 16 * p, D + 4 * p, E + 4 * p);
    tql_lanes(4, np, D, E, bad);
  } else {
    for (int p = 0; p < np; p++)
      herm_tridiag(n, Ar + 16 * p, Ai + 16 * p, D + 4 * p, E + 4 * p);
    tql_lanes(n, np, D, E, bad);
  }
  for (int p = 0; p < np; p++) {
    double *d = D + 4 * p;
    for (int i = 1; i < n; i++) { /* insertion sort */
      double t = d[i];
      int j = i;
      for (; j > 0 && d[j - 1] > t; j--)
        d[j] = d[j - 1];
      d[j] = t;
    }
    for (int i = 0; i < n; i++)
      w[4 * p + i] = d[i];
  }
}

/* A diagonal mass with real positive entries (the lumped masses). */
static int diagonal_mass(int n, const double complex *M)
{
  for (int r = 0; r < n; r++)
    for (int c = 0; c < n; c++)
      if (r == c ? !(creal(M[r * n + c]) > 0.0) || cimag(M[r * n + c]) != 0.0
                 : M[r * n + c] != 0.0)
        return 0;
  return 1;
}

/* M^-1/2 K M^-1/2 of a diagonal mass M, Hermitian, into Ar, Ai: the
 * triangle zhegv reads below ('L' of the column-major array: c >= r here). */
static void herm_scaled(int n, const double complex *K, const double complex *M, double *Ar,
                        double *Ai)
{
  double is[4];
  for (int r = 0; r < n; r++)
    is[r] = 1.0 / sqrt(creal(M[r * n + r]));
  for (int r = 0; r < n; r++)
    for (int c = r; c < n; c++) {
      const double q = is[r] * is[c];
      Ar[r * n + c] = creal(K[r * n + c]) * q;
      Ai[r * n + c] = cimag(K[r * n + c]) * q;
    }
}

/* The generalized eigenvalues of K v = omega^2 M v (n x n), sorted by real
 * part; herm: K and M Hermitian.  A 2 x 2 problem with M = m I (one particle,
 * lumped mass) in closed form. */
static mfs_status eig_solve(int n, double complex *K, double complex *M, int herm,
                            double complex *omega2)
{
  if (n == 1)
    return solve1(K[0], M[0], herm, omega2);
  if (n == 2 && M[1] == 0.0 && M[2] == 0.0 &&
      (M[0] == M[3] || !herm || (creal(M[0]) > 0.0 && creal(M[3]) > 0.0))) {
    /* a diagonal mass (lumped): the eigenvalues of M^-1 K, or for Hermitian
     * symbols of M^-1/2 K M^-1/2 */
    if (M[0] == 0.0 || M[3] == 0.0)
      return MFS_EDOMAIN;
    double complex m = M[0], m1 = M[3];
    if (herm) {
      /* r = |((a - d) / 2, |K01| / sqrt(m0 m1))| by one square root (no hypot:
       * these are neither huge nor tiny) */
      double a = creal(K[0]) / creal(m), d = creal(K[3]) / creal(m1), h = 0.5 * (a - d);
      double k2 = creal(K[1]) * creal(K[1]) + cimag(K[1]) * cimag(K[1]);
      double r = sqrt(h * h + k2 / (creal(m) * creal(m1)));
      omega2[0] = 0.5 * (a + d) - r;
      omega2[1] = 0.5 * (a + d) + r;
      return isfinite(r) && isfinite(a + d) ? MFS_OK : MFS_EDOMAIN;
    }
    double complex a = cdiv(K[0], m), b = cdiv(K[1], m), c = cdiv(K[2], m1), d = cdiv(K[3], m1);
    double complex h = 0.5 * (a - d), r = csqrt(h * h + b * c);
    omega2[0] = 0.5 * (a + d) - r;
    omega2[1] = 0.5 * (a + d) + r;
    if (creal(omega2[1]) < creal(omega2[0])) {
      double complex t = omega2[0];
      omega2[0] = omega2[1];
      omega2[1] = t;
    }
    for (int i = 0; i < 2; i++)
      if (!isfinite(creal(omega2[i])) || !isfinite(cimag(omega2[i])))
        return MFS_EDOMAIN;
    return MFS_OK;
  }
  if (herm && n <= 4 && diagonal_mass(n, M)) {
    double Ar[16], Ai[16], wr[4]; /* M^-1/2 K M^-1/2; ray_block: the same over a block */
    int bad;
    herm_scaled(n, K, M, Ar, Ai);
    herm_small_eigvals(n, 1, Ar, Ai, wr, &bad);
    if (bad)
      return MFS_EDOMAIN;
    for (int i = 0; i < n; i++) {
      if (!isfinite(wr[i]))
        return MFS_EDOMAIN;
      omega2[i] = wr[i];
    }
    return MFS_OK;
  }
  /* The _work drivers on stack workspaces, column-major: no allocation (and
   * no LAPACKE message).  The row-major symbols read column-major are their
   * transposes: the same eigenvalues; 'L' reads the elements 'U' reads in
   * row-major. */
  double complex work[64];
  double rwork[32];
  mfs_lapack_reset();
  if (herm) {
    double wr[4];
    lapack_int info = LAPACKE_zhegv_work(LAPACK_COL_MAJOR, 1, 'N', 'L', n, K, n, M, n, wr, work,
                                         64, rwork);
    if (info != 0 || mfs_lapack_last()->count > 0)
      return info > n ? MFS_EDOMAIN : MFS_ELAPACK;
    for (int i = 0; i < n; i++) {
      if (!isfinite(wr[i]))
        return MFS_EDOMAIN;
      omega2[i] = wr[i];
    }
    return MFS_OK;
  }
  double complex al[4], be[4], vl[1], vr[1];
  lapack_int info = LAPACKE_zggev_work(LAPACK_COL_MAJOR, 'N', 'N', n, K, n, M, n, al, be, vl, 1,
                                       vr, 1, work, 64, rwork);
  if (info != 0 || mfs_lapack_last()->count > 0)
    return MFS_ELAPACK;
  for (int i = 0; i < n; i++) {
    if (cabs(be[i]) == 0.0)
      return MFS_EDOMAIN;
    omega2[i] = al[i] / be[i];
    if (!isfinite(creal(omega2[i])) || !isfinite(cimag(omega2[i])))
      return MFS_EDOMAIN;
  }
  qsort(omega2, (size_t)n, sizeof *omega2, cmp_re);
  return MFS_OK;
}

/* Hermitian symbols: Lagrangian, or 2D anti-plane (the frame does not enter),
 * without least squares (its mass term makes M indefinite in general). */
static int hermitian(const mfs_disp_plan *dp)
{
  const mfs_disc *d = &dp->spec.disc;
  int herm = d->frame == MFS_FRAME_LAGRANGIAN || (d->dim == 2 && !dp->euler2);
  return herm && dp->spec.ls_beta == 0.0;
}

/* Wave vectors are evaluated in blocks of up to BLK points, the innermost
 * loops over the points of a block (which the compiler vectorizes); every
 * operation is elementwise, so a point's value does not depend on the other
 * points of its block. */
enum { BLK = 8 };
/* The block's arrays on the stack at the vectors' alignment: a 32- or 64-byte
 * load from an array only 16-byte aligned (the ABI's stack alignment) splits
 * across cache lines, and the time then depended on where the stack happened
 * to start (up to 15 % in bench_dispersion_ab under setarch -R with the
 * environment 16 bytes longer or shorter). */
#define LANE_ALIGN _Alignas(64)
_Static_assert((int)BLK == (int)HERM_LANES, "a block's Hermitian problems go to herm_small_eigvals, herm4_eigvals at once");

/* cos x, 1 - cos x and sin x of x[0..BLK), each to about an ulp absolute and
 * the versine, near x = 0, also relative (1 - cos x computed as such loses
 * it; against long double sinl, cosl at 6e6 points: 0.21 ulp absolute for
 * cos and sin, 2.5 ulps relative for the versine): x reduced to |r| <= pi/4
 * by n = nearest(x 2/pi) with pi/2 in two parts (fdlibm's split: the first
 * 33 bits, so that n pi/2 is exact for |n| < 2^20, then the rest), Taylor
 * series of sin r and 1 - cos r to r^17 and r^18 (the next terms are below
 * 1e-19 at pi/4), then the quadrant, without branches.  libm beyond
 * |x| = 1e5 (far outside the Brillouin zone). */
MFS_CLONES static void sincos_v(const double *x, double *c, double *v, double *s)
{
  static const double two_pi = 6.36619772367581382433e-01, /* 2 / pi */
    pio2_1 = 1.57079632673412561417e+00,                   /* first 33 bits of pi / 2 */
    pio2_1t = 6.07710050650619224932e-11,                  /* pi / 2 - pio2_1 */
    shift = 6755399441055744.0;                            /* 1.5 * 2^52: rounds to an integer */
  for (int p = 0; p < BLK; p++) {
    double xp = x[p]; /* |x| >= 1e5, inf, NaN: garbage here, replaced below */
    double n = (xp * two_pi + shift) - shift;
    double r = (xp - n * pio2_1) - n * pio2_1t, z = r * r, z2 = z * z, z4 = z2 * z2;
    /* the polynomials in z by Estrin's scheme (pairs, then pairs of pairs:
     * a chain of 5 products instead of Horner's 9; the terms fall by 1 /
     * (4 n^2) <= 0.04 per power of z, so the sum is as accurate) */
    double ps = ((-1.0 / 6 + z * (1.0 / 120)) + z2 * (-1.0 / 5040 + z * (1.0 / 362880))) +
                z4 * ((-1.0 / 39916800 + z * (1.0 / 6227020800)) +
                      z2 * (-1.0 / 1307674368000 + z * (1.0 / 355687428096000)));
    double pv = ((0.5 + z * (-1.0 / 24)) + z2 * (1.0 / 720 + z * (-1.0 / 40320))) +
                z4 * ((1.0 / 3628800 + z * (-1.0 / 479001600)) +
                      z2 * (1.0 / 87178291200 + z * (-1.0 / 20922789888000)) +
                      z4 * (1.0 / 6402373705728000));
    double sr = r + r * z * ps, vr = z * pv;
    double cr = 1.0 - vr;
    /* the quadrant q = n mod 4 as n - 4 round(n / 4), in {-2, ..., 2}:
     * q = 0: (cos, sin) = (cr, sr); 1: (-sr, cr); +-2: (-cr, -sr); -1: (sr, -cr),
     * chosen by products with 0 / 1 indicators, polynomials in |q| exact on
     * these integers (no branch and no division, so the loop vectorizes) */
    double q = n - 4.0 * ((n * 0.25 + shift) - shift), aq = fabs(q);
    double e0 = 0.5 * (1.0 - aq) * (2.0 - aq), odd = aq * (2.0 - aq), e2 = 0.5 * aq * (aq - 1.0);
    double e1 = 0.5 * odd * (1.0 + q), em1 = 0.5 * odd * (1.0 - q);
    double cp = odd * sr + (1.0 - odd) * cr, sp = odd * cr + (1.0 - odd) * sr;
    double cq = cp * (1.0 - 2.0 * (e1 + e2)), sq = sp * (1.0 - 2.0 * (em1 + e2));
    c[p] = cq;
    s[p] = sq;
    v[p] = e0 * vr + (1.0 - e0) * (1.0 - cq);
  }
  int far = 0; /* one test over the lanes (it vectorizes), the lanes apart only if one is far */
  for (int p = 0; p < BLK; p++)
    far |= !(fabs(x[p]) < 1e5);
  if (far)
    for (int p = 0; p < BLK; p++)
      if (!(fabs(x[p]) < 1e5)) {
        s[p] = sin(x[p]);
        c[p] = cos(x[p]);
        v[p] = 1.0 - c[p];
      }
}

/* For the points of a block: x[m BLK + p] = 1 - cos(m ph_p) (vers) or
 * cos(m ph_p), s[m BLK + p] = sin(m ph_p), m = 0 .. mmax, by the addition
 * theorem (the versine form has no cancellation for small ph), restarted
 * from sincos_v every 8 steps so that rounding does not grow with m. */
MFS_CLONES static void phase_table(const double *ph, int mmax, int vers, double *restrict x,
                                   double *restrict s)
{
  LANE_ALIGN double c1[BLK], v1[BLK], s1[BLK], mp[BLK], cc[BLK], vv[BLK];
  for (int p = 0; p < BLK; p++) {
    x[p] = vers ? 0.0 : 1.0;
    s[p] = 0.0;
  }
  if (mmax < 1)
    return;
  /* m = 1 in arrays of its own, apart from the table (x and s restrict: the
   * loops below vectorize) */
  sincos_v(ph, c1, v1, s1);
  for (int p = 0; p < BLK; p++) {
    x[BLK + p] = vers ? v1[p] : c1[p];
    s[BLK + p] = s1[p];
  }
  for (int m = 2; m <= mmax; m++) {
    double *xm = x + m * BLK, *sm = s + m * BLK;
    const double *xa = xm - BLK, *sa = sm - BLK;
    if ((m & 7) == 0) {
      for (int p = 0; p < BLK; p++)
        mp[p] = m * ph[p];
      sincos_v(mp, cc, vv, sm);
      for (int p = 0; p < BLK; p++)
        xm[p] = vers ? vv[p] : cc[p];
    } else if (vers) {
      for (int p = 0; p < BLK; p++) {
        xm[p] = (xa[p] + v1[p]) - (xa[p] * v1[p] - sa[p] * s1[p]);
        sm[p] = (sa[p] + s1[p]) - (sa[p] * v1[p] + xa[p] * s1[p]);
      }
    } else {
      for (int p = 0; p < BLK; p++) {
        xm[p] = xa[p] * c1[p] - sa[p] * s1[p];
        sm[p] = sa[p] * c1[p] + xa[p] * s1[p];
      }
    }
  }
}

enum { FOLD_TAB = 64 }; /* phase tables on the stack up to |m| = 64; beyond, a sincos per offset */
enum { OCHUNK = 32 };   /* offsets whose phases are formed at a time */

/* acc[k BLK + p] += sum_q w[q ld + k] x[q][p] for k < K (a constant where
 * inlined: the K BLK accumulators stay in registers over the offsets), the
 * offsets q in order; first: acc starts at 0 (not read). */
static MFS_INLINE void acc_lanes(const int K, int no, const double *w, int ld,
                                 const double *const *x, double *acc, int first)
{
#ifdef HERM4_VEC /* in vectors (GCC keeps the arrays below in memory) */
  v4d a[4][BLK / 4];
  for (int k = 0; k < K; k++)
    for (int h = 0; h < BLK / 4; h++) {
      if (first)
        a[k][h] = (v4d){0.0, 0.0, 0.0, 0.0};
      else
        memcpy(&a[k][h], acc + k * BLK + 4 * h, sizeof a[k][h]);
    }
  for (int q = 0; q < no; q++) {
    const double *wq = w + q * ld;
    for (int h = 0; h < BLK / 4; h++) {
      v4d xh; /* one load of four lanes (a copy of the array goes by halves) */
      memcpy(&xh, x[q] + 4 * h, sizeof xh);
      for (int k = 0; k < K; k++)
        a[k][h] += wq[k] * xh;
    }
  }
  for (int k = 0; k < K; k++)
    for (int h = 0; h < BLK / 4; h++)
      memcpy(acc + k * BLK + 4 * h, &a[k][h], sizeof a[k][h]);
#else
  double a[4 * BLK];
  for (int k = 0; k < K; k++)
    for (int p = 0; p < BLK; p++)
      a[k * BLK + p] = first ? 0.0 : acc[k * BLK + p];
  for (int q = 0; q < no; q++) {
    const double *xq = x[q], *wq = w + q * ld;
    for (int k = 0; k < K; k++)
      for (int p = 0; p < BLK; p++)
        a[k * BLK + p] += wq[k] * xq[p];
  }
  for (int k = 0; k < K; k++)
    for (int p = 0; p < BLK; p++)
      acc[k * BLK + p] = a[k * BLK + p];
#endif
}

/* acc_lanes over n components, four at a time. */
static MFS_INLINE void acc_all(int n, int no, const double *w, int ld, const double *const *x,
                               double *acc, int first)
{
  int c = 0;
  for (; c + 4 <= n; c += 4)
    acc_lanes(4, no, w + c, ld, x, acc + c * BLK, first);
  if (n - c >= 2) {
    acc_lanes(2, no, w + c, ld, x, acc + c * BLK, first);
    c += 2;
  }
  if (n - c == 1)
    acc_lanes(1, no, w + c, ld, x, acc + c * BLK, first);
}

/* The folded sums of BLK wave vectors (every loop over the lanes of a
 * constant count, so that it vectorizes and the accumulators stay in
 * registers), of phases ph1 =
 * k.a1, ph2 = k.a2 (1D: ph2 = 0), all long waves (vers: every phase of the
 * terms within pi/2, the versine form) or none (the cosine form): re[c BLK +
 * p] + i im[c BLK + p] for the raw components c of the plan (imaginary parts
 * only if want_im; zero otherwise).  Reads the plan only; no allocation. */
static MFS_INLINE void fold_lanes(const mfs_disp_plan *dp, const double *ph1,
                                  const double *ph2, int vers, int want_im, double *restrict re,
                                  double *restrict im)
{
  LANE_ALIGN double x1[(FOLD_TAB + 1) * BLK], s1[(FOLD_TAB + 1) * BLK];
  LANE_ALIGN double x2[(2 * FOLD_TAB + 1) * BLK], s2[(2 * FOLD_TAB + 1) * BLK];
  LANE_ALIGN double X[OCHUNK * BLK], S[OCHUNK * BLK], t[BLK], cc[BLK], vv[BLK];
  LANE_ALIGN double accs[MFS_DISP_NC * BLK], acca[MFS_DISP_NC * BLK];
  const int two = dp->spec.disc.dim > 1, m = dp->mij < FOLD_TAB ? dp->mij : FOLD_TAB;
  const int ns = dp->nsym, na = want_im ? dp->nanti : 0;
  const int in_tab = dp->mij <= FOLD_TAB; /* every offset's |i|, |j| within the tables */
  phase_table(ph1, m, vers, x1, s1);
  if (two) {
    phase_table(ph2, m, vers, x2 + FOLD_TAB * BLK, s2 + FOLD_TAB * BLK);
    for (int q = 1; q <= m; q++)
      for (int p = 0; p < BLK; p++) {
        x2[(FOLD_TAB - q) * BLK + p] = x2[(FOLD_TAB + q) * BLK + p];
        s2[(FOLD_TAB - q) * BLK + p] = -s2[(FOLD_TAB + q) * BLK + p];
      }
  }
  if (dp->no == 0) { /* else the first chunk starts the sums */
    for (int c = 0; c < ns * BLK; c++)
      accs[c] = 0.0;
    for (int c = 0; c < na * BLK; c++)
      acca[c] = 0.0;
  }
  for (size_t o0 = 0; o0 < dp->no; o0 += OCHUNK) {
    const int no = dp->no - o0 < OCHUNK ? (int)(dp->no - o0) : OCHUNK;
    const double *Xp[OCHUNK], *Sp[OCHUNK]; /* the phase factors of the chunk's offsets */
    for (int q = 0; q < no; q++) {
      const int i = dp->oi[o0 + q], j = dp->oj[o0 + q];
      double *Xq = X + q * BLK, *Sq = S + q * BLK;
      Xp[q] = Xq;
      Sp[q] = Sq;
      if (!in_tab && (i > m || j > m || j < -m)) {
        for (int p = 0; p < BLK; p++)
          t[p] = i * ph1[p] + j * ph2[p];
        sincos_v(t, cc, vv, Sq);
        for (int p = 0; p < BLK; p++)
          Xq[p] = vers ? vv[p] : cc[p];
      } else if (!two) { /* the tables themselves */
        Xp[q] = x1 + i * BLK;
        Sp[q] = s1 + i * BLK;
      } else { /* the angle sum i ph1 + j ph2 */
        const double *a = x1 + i * BLK, *sa = s1 + i * BLK;
        const double *b = x2 + (FOLD_TAB + j) * BLK, *sb = s2 + (FOLD_TAB + j) * BLK;
        if (vers)
          for (int p = 0; p < BLK; p++)
            Xq[p] = (a[p] + b[p]) - (a[p] * b[p] - sa[p] * sb[p]);
        else
          for (int p = 0; p < BLK; p++)
            Xq[p] = a[p] * b[p] - sa[p] * sb[p];
        if (na > 0 && vers) /* the sines only where imaginary parts are kept */
          for (int p = 0; p < BLK; p++)
            Sq[p] = (sa[p] + sb[p]) - (sa[p] * b[p] + a[p] * sb[p]);
        else if (na > 0)
          for (int p = 0; p < BLK; p++)
            Sq[p] = sa[p] * b[p] + a[p] * sb[p];
      }
    }
    /* the sums over the chunk's offsets in order, BLK lanes an offset at a
     * time (vectors over the lanes) */
    const double *sy = dp->sym + o0 * (size_t)ns, *an = dp->anti + o0 * (size_t)dp->nanti;
    acc_all(ns, no, sy, ns, Xp, accs, o0 == 0);
    acc_all(na, no, an, dp->nanti, Sp, acca, o0 == 0);
  }
  /* Re = c0 - sum sym vers (long waves) or c(0) + sum sym cos; the
   * components not kept: their sums at k = 0; imaginary parts not kept: 0 */
  const double *base = vers ? dp->c0 : dp->corig;
  const double sg = vers ? -1.0 : 1.0; /* b + (-1) a is b - a exactly: one loop that vectorizes */
  for (int k = 0; k < dp->nc; k++) {
    const double b = base[k];
    for (int p = 0; p < BLK; p++) {
      re[k * BLK + p] = b;
      im[k * BLK + p] = 0.0;
    }
  }
  for (int c = 0; c < ns; c++) {
    const int k = dp->csym[c];
    const double b = base[k];
    for (int p = 0; p < BLK; p++)
      re[k * BLK + p] = b + sg * accs[c * BLK + p];
  }
  for (int c = 0; c < na; c++) {
    const int k = dp->canti[c];
    for (int p = 0; p < BLK; p++)
      im[k * BLK + p] = acca[c * BLK + p];
  }
}

/* A block of np <= BLK wave vectors: all BLK lanes computed (the unused ones
 * at phase 0; a single point costs a block, which the vector loops make
 * cheaper than one lane in scalar loops of a count not known in advance). */
MFS_CLONES static void fold_block(const mfs_disp_plan *dp, int np, const double *ph1,
                                  const double *ph2, int vers, int want_im, double *re,
                                  double *im)
{
  LANE_ALIGN double p1[BLK], p2[BLK];
  for (int p = 0; p < BLK; p++) {
    p1[p] = p < np ? ph1[p] : 0.0;
    p2[p] = p < np ? ph2[p] : 0.0;
  }
  fold_lanes(dp, p1, p2, vers, want_im, re, im);
}

/* Long waves (the versine form): every phase of the terms within pi/2. */
static inline int long_wave(const mfs_disp_plan *dp, double ph1, double ph2)
{
  return dp->mij * (fabs(ph1) + fabs(ph2)) <= M_PI_2;
}

/* The sums of point p of a block. */
static void block_sums(const mfs_disp_plan *dp, const double *re, const double *im, int p,
                       raw_sums *ps)
{
  for (int c = 0; c < dp->nc; c++)
    ps->s[c] = CMPLX(re[c * BLK + p], im[c * BLK + p]);
}

/* The folded sums at one wave vector. */
static void fold_eval(const mfs_disp_plan *dp, double ph1, double ph2, int want_im, raw_sums *ps)
{
  LANE_ALIGN double re[MFS_DISP_NC * BLK], im[MFS_DISP_NC * BLK];
  fold_block(dp, 1, &ph1, &ph2, long_wave(dp, ph1, ph2), want_im, re, im);
  block_sums(dp, re, im, 0, ps);
}

/* The phases ph1 = k.a1, ph2 = k.a2 of np wave vectors k = (kx, ky) (1/dx;
 * 1D: ph2 = 0, ky not read), a loop over the lanes. */
static inline void phases_lanes(const mfs_disp_plan *dp, int np, const double *kx,
                                const double *ky, double *ph1, double *ph2)
{
  const double a10 = dp->a1[0], a11 = dp->a1[1], a20 = dp->a2[0], a21 = dp->a2[1]; /* not reloaded after each store */
  if (dp->spec.disc.dim == 1)
    for (int p = 0; p < np; p++) {
      ph1[p] = kx[p] * a10;
      ph2[p] = 0.0;
    }
  else
    for (int p = 0; p < np; p++) {
      ph1[p] = kx[p] * a10 + ky[p] * a11;
      ph2[p] = kx[p] * a20 + ky[p] * a21;
    }
}

/* The phases of one wave vector k[0..1]. */
static void phases(const mfs_disp_plan *dp, const double *k, double *ph1, double *ph2)
{
  phases_lanes(dp, 1, k, k + 1, ph1, ph2);
}

/* What one stress needs: the scalar coefficients, or the plane-strain state. */
typedef struct {
  double ca, cg;
  mfs_plane_state ps;
} disp_stress;

static mfs_status stress_at(const mfs_disp_plan *dp, double sbar, disp_stress *s)
{
  if (dp->plane)
    return mfs_disp_state(dp, sbar, &s->ps);
  scalar_coef(dp, sbar, &s->ca, &s->cg);
  return MFS_OK;
}

/* K and M from the sums at one stress. */
static void contract_at(const mfs_disp_plan *dp, const raw_sums *ps, const disp_stress *s,
                        double complex *K, double complex *M)
{
  if (dp->plane)
    plane_contract(dp, ps, &s->ps, dp->upper, K, M);
  else
    scalar_contract(dp, ps, s->ca, s->cg, dp->upper, K, M);
}

/* Imaginary parts are needed unless the problem is one Hermitian branch. */
static int want_im(const mfs_disp_plan *dp)
{
  return !(hermitian(dp) && dp->nbr == 1);
}

void mfs_disp_plan_work(const mfs_disp_plan *pl, size_t *offsets, int *components)
{
  *offsets = pl->no;
  *components = pl->nsym + (want_im(pl) ? pl->nanti : 0);
}

mfs_status mfs_disp_omega2_state(const mfs_disp_plan *dp, const mfs_plane_state *s,
                                 const double *k, double complex *omega2)
{
  return mfs_disp_omega2_states(dp, s, 1, k, omega2);
}

mfs_status mfs_disp_omega2(const mfs_disp_plan *dp, double sbar, double kappa, double theta,
                           double complex *omega2)
{
  return mfs_disp_ray(dp, &sbar, 1, theta, &kappa, 1, omega2, 0);
}

enum { RAY_STRESSES = 16 }; /* stresses per pass over a ray */

/* The status of the first failure in the order (stress, point). */
typedef struct {
  mfs_status st;
  size_t s, i;
} first_fail;

static void note_fail(first_fail *f, mfs_status st, size_t s, size_t i)
{
  if (f->st == MFS_OK || s < f->s || (s == f->s && i < f->i))
    *f = (first_fail){.st = st, .s = s, .i = i};
}

/* 1 / m of the lanes of a block (m = re[2 BLK + p], the real part of the
 * scalar mass), once for all its stresses: scalar_lanes multiplies by it. */
MFS_CLONES static void recip_lanes(const double *restrict re, double *restrict rm)
{
  for (int p = 0; p < BLK; p++)
    rm[p] = 1.0 / re[2 * BLK + p];
}

/* One scalar branch over the lanes of a block: omega^2 = K / m for a real m
 * (the lumped mass) as K (1 / m), with rm = 1 / m of recip_lanes shared by
 * the stresses of the block (one division per lane and block instead of two
 * per lane and stress; within an ulp or two of K / m, and the same bits for a
 * point whatever block it is in).  A point whose K (1 / m) is not finite, or
 * whose m is zero or not real: solve1 of scalar_contract (K / m, or the
 * complex division).  The points idx[0..np) into w[idx[p]]. */
MFS_CLONES static void scalar_lanes(int np, const size_t *idx,
                                    const double *restrict re, const double *restrict im,
                                    const double *restrict rm, const disp_stress *s, size_t si,
                                    int herm, double complex *w, first_fail *first)
{
  LANE_ALIGN double wr[BLK], wi[BLK], odd[BLK];
  const double ca = s->ca, cg = s->cg, hz = herm ? 0.0 : 1.0;
  /* all BLK lanes (fold_block fills them), in loops that vectorize (the
   * imaginary part computed and then zeroed where Hermitian) */
  for (int p = 0; p < BLK; p++) {
    wr[p] = (ca * re[p] + cg * re[BLK + p]) * rm[p];
    wi[p] = hz * ((ca * im[p] + cg * im[BLK + p]) * rm[p]);
  }
  /* the tests below at once: x - x is 0 for a finite x and NaN otherwise
   * (a zero mass gives an infinite 1 / m); |Im m| is 0 for a real mass.  All
   * zero (a lane past np too): every point as the loop below */
  for (int p = 0; p < BLK; p++)
    odd[p] = (wr[p] - wr[p]) + (wi[p] - wi[p]) + fabs(im[2 * BLK + p]);
  LANE_ALIGN double h[BLK / 2]; /* their sum by halves (a chain of 3 additions, not BLK) */
  for (int p = 0; p < BLK / 2; p++)
    h[p] = odd[p] + odd[p + BLK / 2];
  for (int p = 0; p < BLK / 4; p++)
    h[p] += h[p + BLK / 4];
  _Static_assert(BLK == 8, "the halving above stops at two lanes");
  if (h[0] + h[1] == 0.0) {
    if (np == BLK && idx[BLK - 1] == idx[0] + BLK - 1) { /* consecutive: interleaved in a loop that vectorizes */
      double *restrict o = (double *)(w + idx[0]); /* C11 6.2.5: an array of two doubles */
      for (int p = 0; p < BLK; p++) {
        o[2 * p] = wr[p];
        o[2 * p + 1] = wi[p];
      }
    } else {
      for (int p = 0; p < np; p++)
        w[idx[p]] = CMPLX(wr[p], wi[p]);
    }
    return;
  }
  for (int p = 0; p < np; p++) {
    double complex *wp = w + idx[p];
    mfs_status e = MFS_OK;
    if (isfinite(wr[p]) && isfinite(wi[p]) && im[2 * BLK + p] == 0.0 && re[2 * BLK + p] != 0.0) {
      *wp = CMPLX(wr[p], wi[p]);
    } else { /* the general case: K / m by division (1 / m may overflow where K / m does not) */
      double complex K = CMPLX(ca * re[p] + cg * re[BLK + p], ca * im[p] + cg * im[BLK + p]);
      e = solve1(K, CMPLX(re[2 * BLK + p], im[2 * BLK + p]), herm, wp);
    }
    if (e != MFS_OK) {
      *wp = CMPLX(NAN, NAN);
      note_fail(first, e, si, idx[p]);
    }
  }
}

/* Two Hermitian branches with a diagonal mass (one particle in plane strain,
 * two anti-plane), over the lanes of a block: plane_contract or
 * scalar_contract and eig_solve's closed form, the same operations in the
 * same order on each point, without the copies and the general paths.  0 if
 * a point of the block needs them (a mass not real and positive, a coupling
 * mass): then the caller takes the block point by point. */
MFS_CLONES static int herm2_lanes(const mfs_disp_plan *dp, int np, const size_t *idx,
                                  const double *re, const double *im, const disp_stress *s,
                                  size_t si, double complex *w, first_fail *first)
{
  LANE_ALIGN double a[BLK], d[BLK], kr[BLK], ki[BLK], m0[BLK], m1[BLK];
  int ok = 1;
  if (dp->plane) { /* K_ik = A_ijkl SA^{jl} (Lagrangian: hermitian()), M = SM I */
    if (dp->nb != 1 || dp->euler2)
      return 0;
    const double *t = s->ps.A;
    for (int p = 0; p < np; p++) {
      double k00 = 0.0, k11 = 0.0, r01 = 0.0, i01 = 0.0;
      for (int j = 0; j < 2; j++)
        for (int l = 0; l < 2; l++) {
          const double ar = re[(j * 2 + l) * BLK + p], ai = im[(j * 2 + l) * BLK + p];
          k00 += t[P4(0, j, 0, l)] * ar;
          k11 += t[P4(1, j, 1, l)] * ar;
          r01 += t[P4(0, j, 1, l)] * ar;
          i01 += t[P4(0, j, 1, l)] * ai;
        }
      m0[p] = m1[p] = re[8 * BLK + p];
      ok = ok && im[8 * BLK + p] == 0.0 && m0[p] > 0.0;
      a[p] = k00;
      d[p] = k11;
      kr[p] = r01;
      ki[p] = i01;
    }
  } else { /* K = ca SA + cg SG, M = SM, of the blocks (0,0), (0,1), (1,1) */
    if (dp->nb != 2)
      return 0;
    const double ca = s->ca, cg = s->cg;
    for (int p = 0; p < np; p++) {
      a[p] = ca * re[0 * BLK + p] + cg * re[1 * BLK + p];
      kr[p] = ca * re[3 * BLK + p] + cg * re[4 * BLK + p];
      ki[p] = ca * im[3 * BLK + p] + cg * im[4 * BLK + p];
      d[p] = ca * re[9 * BLK + p] + cg * re[10 * BLK + p];
      m0[p] = re[2 * BLK + p];
      m1[p] = re[11 * BLK + p];
      ok = ok && im[2 * BLK + p] == 0.0 && im[11 * BLK + p] == 0.0 && re[5 * BLK + p] == 0.0 &&
           im[5 * BLK + p] == 0.0 && m0[p] > 0.0 && m1[p] > 0.0;
    }
  }
  if (!ok)
    return 0;
  for (int p = 0; p < np; p++) { /* eig_solve's closed form */
    const double ap = a[p] / m0[p], dp2 = d[p] / m1[p], h = 0.5 * (ap - dp2);
    const double k2 = kr[p] * kr[p] + ki[p] * ki[p];
    const double r = sqrt(h * h + k2 / (m0[p] * m1[p]));
    double complex *wp = w + idx[p] * 2;
    if (isfinite(r) && isfinite(ap + dp2)) {
      wp[0] = 0.5 * (ap + dp2) - r;
      wp[1] = 0.5 * (ap + dp2) + r;
    } else {
      wp[0] = wp[1] = CMPLX(NAN, NAN);
      note_fail(first, MFS_EDOMAIN, si, idx[p]);
    }
  }
  return 1;
}

/* Four Hermitian branches with a diagonal mass (two particles in plane
 * strain), over the lanes of a block: plane_contract's triangle c >= r, scaled
 * as herm_scaled, the same operations in the same order on each point, then
 * herm4_eigvals on them all (plain C: herm_small_eigvals).  0 if a point of
 * the block needs the general path (a mass not real and positive, a coupling
 * mass).  Compiled for SSE2 and AVX2 as the sums (the same bits). */
MFS_CLONES static int herm4_lanes(const mfs_disp_plan *dp, int np, const size_t *idx,
                                  const double *re, const double *im, const disp_stress *s,
                                  size_t si, double complex *w, first_fail *first)
{
  if (!dp->plane || dp->nb != 2 || dp->euler2)
    return 0;
  LANE_ALIGN double Ar[16 * HERM_LANES], Ai[16 * HERM_LANES], wb[4 * HERM_LANES];
  int bad[HERM_LANES], ok = 1;
  const double *t = s->ps.A;
  for (int p = 0; p < np; p++) { /* the masses: blocks (0,0), (1,1) real positive, (0,1) zero */
    const double ma = re[8 * BLK + p], mb = re[(3 * 9 + 8) * BLK + p];
    ok = ok && ma > 0.0 && mb > 0.0 && im[8 * BLK + p] == 0.0 && im[(3 * 9 + 8) * BLK + p] == 0.0 &&
         re[(9 + 8) * BLK + p] == 0.0 && im[(9 + 8) * BLK + p] == 0.0;
  }
  if (!ok)
    return 0;
  /* the triangle in the layout of the kernel: herm4_eigvals' entry-major (as
   * re and im) or herm_small_eigvals' point-major; the lanes past np zero */
#ifdef HERM4_VEC
#define AT4(e, p) ((e) * HERM_LANES + (p))
#define W4(k, p) ((k) * HERM_LANES + (p))
#else
#define AT4(e, p) (16 * (p) + (e))
#define W4(k, p) (4 * (p) + (k))
#endif
  LANE_ALIGN double is0[BLK], is1[BLK];
  for (int p = 0; p < BLK; p++) {
    is0[p] = p < np ? 1.0 / sqrt(re[8 * BLK + p]) : 0.0;
    is1[p] = p < np ? 1.0 / sqrt(re[(3 * 9 + 8) * BLK + p]) : 0.0;
  }
  for (int r = 0; r < 4; r++)
    for (int c = r; c < 4; c++) {
      const int i = r & 1, k = c & 1, c0 = ((r >> 1) * 2 + (c >> 1)) * 9;
      const double *isr = r < 2 ? is0 : is1, *isc = c < 2 ? is0 : is1;
      for (int p = 0; p < BLK; p++) {
        double vr = 0.0, vi = 0.0;
        for (int j = 0; j < 2; j++)
          for (int l = 0; l < 2; l++) {
            vr += t[P4(i, j, k, l)] * re[(c0 + j * 2 + l) * BLK + p];
            vi += t[P4(i, j, k, l)] * im[(c0 + j * 2 + l) * BLK + p];
          }
        const double q = isr[p] * isc[p];
        Ar[AT4(r * 4 + c, p)] = vr * q;
        Ai[AT4(r * 4 + c, p)] = vi * q;
      }
    }
#ifdef HERM4_VEC
  herm4_eigvals(Ar, Ai, wb, bad);
#else
  herm_small_eigvals(4, np, Ar, Ai, wb, bad);
#endif
  for (int p = 0; p < np; p++) {
    double complex *wp = w + idx[p] * 4;
    int fin = !bad[p];
    for (int k = 0; k < 4; k++)
      fin = fin && isfinite(wb[W4(k, p)]);
    for (int k = 0; k < 4; k++)
      wp[k] = fin ? CMPLX(wb[W4(k, p)], 0.0) : CMPLX(NAN, NAN);
    if (!fin)
      note_fail(first, MFS_EDOMAIN, si, idx[p]);
  }
#undef AT4
#undef W4
  return 1;
}

/* Evaluate the points idx[0..np) of phases ph1, ph2, all of one form (vers),
 * at the stresses at[0..ns) (of stress index s0 on), into omega2 (the ray's
 * layout, stresses ld apart); failures noted in *first. */
static void ray_block(const mfs_disp_plan *dp, int np, const size_t *idx, const double *ph1,
                      const double *ph2, int vers, const disp_stress *at, size_t s0, size_t ns,
                      size_t ld, double complex *omega2, first_fail *first)
{
  LANE_ALIGN double re[MFS_DISP_NC * BLK], im[MFS_DISP_NC * BLK];
  const int nb = dp->nbr, herm = hermitian(dp);
  LANE_ALIGN double rm[BLK];
  fold_block(dp, np, ph1, ph2, vers, want_im(dp), re, im);
  if (nb == 1 && !dp->plane)
    recip_lanes(re, rm);
  for (size_t q = 0; q < ns; q++) {
    if (nb == 1 && !dp->plane) {
      scalar_lanes(np, idx, re, im, rm, at + q, s0 + q, herm, omega2 + (s0 + q) * ld, first);
      continue;
    }
    if (herm && nb == 2 && herm2_lanes(dp, np, idx, re, im, at + q, s0 + q,
                                       omega2 + (s0 + q) * ld, first))
      continue;
    if (herm && nb == 4 && herm4_lanes(dp, np, idx, re, im, at + q, s0 + q,
                                       omega2 + (s0 + q) * ld, first))
      continue;
    /* eig_solve point by point, but the Hermitian problems of more than two
     * branches with a diagonal mass (its herm_small_eigvals) together */
    LANE_ALIGN double Ar[16 * HERM_LANES], Ai[16 * HERM_LANES], wb[4 * HERM_LANES];
    int lane[HERM_LANES], bad[HERM_LANES], nl = 0;
    for (int p = 0; p < np; p++) {
      double complex *w = omega2 + (s0 + q) * ld + idx[p] * (size_t)nb, K[16], M[16];
      raw_sums ps;
      block_sums(dp, re, im, p, &ps);
      contract_at(dp, &ps, at + q, K, M);
      mfs_status e = MFS_OK;
      if (herm && nb > 2 && diagonal_mass(nb, M)) {
        herm_scaled(nb, K, M, Ar + 16 * nl, Ai + 16 * nl);
        lane[nl++] = p;
      } else {
        e = eig_solve(nb, K, M, herm, w);
      }
      if (e != MFS_OK) {
        for (int k = 0; k < nb; k++)
          w[k] = CMPLX(NAN, NAN);
        note_fail(first, e, s0 + q, idx[p]);
      }
    }
    if (nl > 0)
      herm_small_eigvals(nb, nl, Ar, Ai, wb, bad);
    for (int b = 0; b < nl; b++) {
      double complex *w = omega2 + (s0 + q) * ld + idx[lane[b]] * (size_t)nb;
      int fin = !bad[b];
      for (int k = 0; k < nb; k++)
        fin = fin && isfinite(wb[4 * b + k]);
      for (int k = 0; k < nb; k++)
        w[k] = fin ? CMPLX(wb[4 * b + k], 0.0) : CMPLX(NAN, NAN);
      if (!fin)
        note_fail(first, MFS_EDOMAIN, s0 + q, idx[lane[b]]);
    }
  }
}

/* omega^2 at n points at the stresses at[0..ns) (stress index s0 on): the
 * wave vectors k[2 i .. 2 i + 1], or kappa[i] along (c, s) = (cos, sin)
 * theta; BLK consecutive points at a time, split by form (long or short
 * waves) where a block has both. */
static void eval_points(const mfs_disp_plan *dp, const disp_stress *at, size_t s0, size_t ns,
                        size_t n, const double *k, const double *kappa, double c, double s,
                        double complex *omega2, size_t ld, first_fail *first)
{
  for (size_t i0 = 0; i0 < n; i0 += BLK) {
    const int np = n - i0 < BLK ? (int)(n - i0) : BLK;
    LANE_ALIGN double ph1[BLK], ph2[BLK], kx[BLK], ky[BLK], k0[BLK] = {0.0}, k1[BLK] = {0.0};
    size_t idx[BLK];
    LANE_ALIGN double lw[BLK]; /* 1: long wave, 0: short (doubles: the test vectorizes) */
    int nlw = 0;
    /* the wave vectors k (1/dx), or kappa pi (cos theta, sin theta) of a ray
     * (1D: kappa pi), and their phases: the lanes past np at k = 0, every
     * loop over all BLK lanes (so that it vectorizes) */
    if (k)
      for (int p = 0; p < np; p++) {
        k0[p] = k[2 * (i0 + p)];
        k1[p] = k[2 * (i0 + p) + 1];
      }
    else if (np == BLK) /* a loop of a known count, not a call of memcpy */
      for (int p = 0; p < BLK; p++)
        k0[p] = kappa[i0 + p];
    else
      for (int p = 0; p < np; p++)
        k0[p] = kappa[i0 + p];
    if (k)
      for (int p = 0; p < BLK; p++) {
        kx[p] = k0[p];
        ky[p] = k1[p];
      }
    else if (dp->spec.disc.dim == 1)
      for (int p = 0; p < BLK; p++) {
        kx[p] = k0[p] * M_PI;
        ky[p] = 0.0;
      }
    else
      for (int p = 0; p < BLK; p++) {
        kx[p] = k0[p] * M_PI * c;
        ky[p] = k0[p] * M_PI * s;
      }
    phases_lanes(dp, BLK, kx, ky, ph1, ph2);
    for (int p = 0; p < BLK; p++) { /* every lane, in a loop that vectorizes */
      lw[p] = long_wave(dp, ph1[p], ph2[p]) ? 1.0 : 0.0;
      idx[p] = i0 + (size_t)p;
    }
    for (int p = 0; p < np; p++)
      nlw += lw[p] != 0.0;
    if (nlw == 0 || nlw == np) {
      ray_block(dp, np, idx, ph1, ph2, nlw > 0, at, s0, ns, ld, omega2, first);
      continue;
    }
    for (int form = 0; form < 2; form++) { /* a block with both forms: each on its own */
      LANE_ALIGN double q1[BLK], q2[BLK];
      size_t qi[BLK];
      int nq = 0;
      for (int p = 0; p < np; p++)
        if (lw[p] == (double)form) {
          q1[nq] = ph1[p];
          q2[nq] = ph2[p];
          qi[nq++] = idx[p];
        }
      ray_block(dp, nq, qi, q1, q2, form, at, s0, ns, ld, omega2, first);
    }
  }
}

mfs_status mfs_disp_ray(const mfs_disp_plan *dp, const double *sbar, size_t nsbar, double theta,
                        const double *kappa, size_t n, double complex *omega2, size_t ld)
{
  const double c = cos(theta), s = sin(theta);
  if (ld == 0)
    ld = n * (size_t)dp->nbr;
  first_fail first = {.st = MFS_OK};
  for (size_t s0 = 0; s0 < nsbar; s0 += RAY_STRESSES) {
    size_t ns = nsbar - s0 < RAY_STRESSES ? nsbar - s0 : RAY_STRESSES;
    disp_stress at[RAY_STRESSES];
    for (size_t q = 0; q < ns; q++) {
      mfs_status e = stress_at(dp, sbar[s0 + q], at + q);
      if (e != MFS_OK)
        return e;
    }
    eval_points(dp, at, s0, ns, n, NULL, kappa, c, s, omega2, ld, &first);
  }
  return first.st;
}

mfs_status mfs_disp_omega2_states(const mfs_disp_plan *dp, const mfs_plane_state *s, size_t n,
                                  const double *k, double complex *omega2)
{
  if (!dp->plane || !s || !same_stretch(dp, s))
    return MFS_EINVAL;
  disp_stress at = {.ps = *s};
  first_fail first = {.st = MFS_OK};
  eval_points(dp, &at, 0, 1, n, k, NULL, 0.0, 0.0, omega2, n * (size_t)dp->nbr, &first);
  return first.st;
}

mfs_status mfs_disp_longwave(const mfs_disp_plan *dp, double sbar, double theta, double *q)
{
  const mfs_disc *d = &dp->spec.disc;
  if (!dp->plane) {
    double F = dp->spec.stretch > 0.0 ? dp->spec.stretch : 1.0;
    q[0] = d->dim == 1 && d->frame == MFS_FRAME_LAGRANGIAN ? F * F + sbar : 1.0 + sbar;
    return MFS_OK;
  }
  mfs_plane_state s;
  mfs_status st = mfs_disp_state(dp, sbar, &s);
  if (st != MFS_OK)
    return st;
  double Q[4];
  mfs_acoustic_tensor(dp->euler2 ? s.a : s.A, theta, Q);
  double f = dp->euler2 ? s.J : 1.0; /* rho = rho0 / J */
  double a = Q[0], dd = Q[3], b = 0.5 * (Q[1] + Q[2]), r = hypot(0.5 * (a - dd), b);
  q[0] = f * (0.5 * (a + dd) - r);
  q[1] = f * (0.5 * (a + dd) + r);
  return MFS_OK;
}

mfs_status mfs_disp_pde(const mfs_disp_plan *dp, double sbar, mfs_ellipticity *e)
{
  if (!dp->plane) {
    double q;
    mfs_disp_longwave(dp, sbar, 0.0, &q);
    *e = (mfs_ellipticity){.stable = q > 0.0, .q_min = q, .theta = 0.0};
    return MFS_OK;
  }
  mfs_plane_state s;
  mfs_status st = mfs_disp_state(dp, sbar, &s);
  return st != MFS_OK ? st : mfs_ellipticity_check(s.a, 0, e);
}

void mfs_disp_current_k(const mfs_disp_plan *dp, const double *k, double *kc)
{
  kc[0] = k[0];
  kc[1] = dp->spec.disc.dim > 1 ? k[1] : 0.0;
  if (dp->plane && !dp->euler2) { /* k = F^-T k0 */
    kc[0] /= dp->spec.stretch;
    kc[1] /= dp->spec.stretch_y;
  }
}

struct mfs_disp_sample {
  const mfs_disp_plan *pl;
  size_t nk;
  raw_sums *s;
};

mfs_disp_sample *mfs_disp_sample_alloc(const mfs_disp_plan *pl, size_t nk, const double *k,
                                       mfs_status *status)
{
  mfs_disp_sample *s = NULL;
  mfs_status st = MFS_EINVAL;
  if (!pl || !pl->plane || !k || nk == 0)
    goto done;
  st = MFS_ENOMEM;
  s = mfs_calloc(1, sizeof *s);
  if (!s || !(s->s = mfs_malloc(nk * sizeof *s->s)))
    goto done;
  s->pl = pl;
  s->nk = nk;
  for (size_t i = 0; i < nk; i++) { /* the folded sums, as mfs_disp_omega2_state */
    double ph1, ph2;
    phases(pl, k + 2 * i, &ph1, &ph2);
    fold_eval(pl, ph1, ph2, want_im(pl), s->s + i);
  }
  st = MFS_OK;
done:
  if (st != MFS_OK) {
    mfs_disp_sample_free(s);
    s = NULL;
  }
  if (status)
    *status = st;
  return s;
}

void mfs_disp_sample_free(mfs_disp_sample *s)
{
  if (!s)
    return;
  mfs_free(s->s);
  mfs_free(s);
}

mfs_status mfs_disp_sample_omega2(const mfs_disp_sample *s, size_t i, const mfs_plane_state *st,
                                  double complex *omega2)
{
  if (i >= s->nk || !same_stretch(s->pl, st))
    return MFS_EINVAL;
  double complex K[16], M[16];
  plane_contract(s->pl, s->s + i, st, s->pl->upper, K, M);
  return eig_solve(s->pl->nbr, K, M, hermitian(s->pl), omega2);
}

int mfs_disp_is_reciprocal(const mfs_disp_plan *dp, const double *k, double tol)
{
  int dim = dp->spec.disc.dim;
  for (int r = 0; r < dim; r++) {
    double ph = k[0] * dp->R[r][0] + (dim > 1 ? k[1] * dp->R[r][1] : 0.0);
    double m = ph / (2.0 * M_PI);
    if (fabs(m - nearbyint(m)) > tol)
      return 0;
  }
  return 1;
}

double mfs_disp_kappa_max(const mfs_disp_plan *dp, double theta)
{
  if (dp->spec.disc.dim == 1)
    return 1.0;
  /* reciprocal vectors of the particle lattice a1, a2 */
  const double *a1 = dp->a1, *a2 = dp->a2;
  double det = a1[0] * a2[1] - a1[1] * a2[0];
  double b1[2] = {2.0 * M_PI * a2[1] / det, -2.0 * M_PI * a2[0] / det};
  double b2[2] = {-2.0 * M_PI * a1[1] / det, 2.0 * M_PI * a1[0] / det};
  double n[2] = {cos(theta), sin(theta)}, best = INFINITY;
  for (int i = -2; i <= 2; i++)
    for (int j = -2; j <= 2; j++) {
      if (!i && !j)
        continue;
      double G[2] = {i * b1[0] + j * b2[0], i * b1[1] + j * b2[1]};
      double ng = n[0] * G[0] + n[1] * G[1];
      if (ng <= 1e-12)
        continue;
      double t = 0.5 * (G[0] * G[0] + G[1] * G[1]) / ng;
      best = t < best ? t : best;
    }
  return best / M_PI;
}
