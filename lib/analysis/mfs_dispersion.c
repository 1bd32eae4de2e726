#include "mfs_dispersion.h"

#include <complex.h>
#undef I /* particle indices are called I here */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_lapack.h"
#include "mfs_status.h"

typedef struct {
  int row, col;  /* branch indices: unit-cell particle * ndof + dof */
  double d[2];   /* x_K - x_I */
  double A, G, M;
} disp_term;

struct mfs_disp_plan {
  mfs_disp_spec spec;
  int nb, ndof, nbr;
  double R[2][2];  /* primitive translations of the unit cell */
  double a1[2], a2[2];
  size_t nterm;
  disp_term *t;
};

void mfs_disp_plan_free(mfs_disp_plan *pl)
{
  if (!pl)
    return;
  free(pl->t);
  free(pl);
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
    disp_term *t = realloc(dp->t, ncap * sizeof *t);
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
                     size_t *cap)
{
  const mfs_disc *d = &dp->spec.disc;
  int nd = dp->ndof, cls = node_class(p, I);
  double msum[2] = {0.0, 0.0};
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
  if (!d->consistent_mass) /* lumped: row sums on the diagonal */
    for (int a = 0; a < nd; a++) {
      disp_term *t = push_term(dp, cap);
      if (!t)
        return MFS_ENOMEM;
      *t = (disp_term){.row = cls * nd + a, .col = cls * nd + a, .M = msum[a]};
    }
  return MFS_OK;
}

/* MFS_OK or MFS_ENOTSUP for what the analysis does not cover. */
static int covered(const mfs_disp_spec *s)
{
  const mfs_disc *d = &s->disc;
  int stretched = s->stretch > 0.0 && s->stretch != 1.0;
  if (d->material.physics == MFS_PHYS_PLANE_STRAIN && (d->dim != 2 || s->ls_beta > 0.0))
    return MFS_ENOTSUP;
  if (d->dim == 2 && stretched)
    return MFS_ENOTSUP;
  /* the consistent frame: 1D, shapes with position derivatives; a
   * pre-stretch moves interpolated points exactly with sum_K phi_K u~_K only
   * for linearly complete shapes */
  if (d->frame == MFS_FRAME_EULERIAN_CONSISTENT &&
      (d->dim != 1 || !d->shape->dpos_1d || (stretched && !d->shape->linear_complete)))
    return MFS_ENOTSUP;
  return MFS_OK;
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
      !s->disc.kernel || !s->disc.shape)
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
  dp = calloc(1, sizeof *dp);
  if (!dp)
    goto done;
  dp->spec = *s;
  dp->spec.disc = d;
  dp->ndof = mfs_physics_ndof(d.material.physics);

  double gamma = d.source.gamma > 0.0 ? d.source.gamma : 1.0;
  double hy = d.source.lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 : gamma;
  int nx = 2 * (int)ceil(2.0 * d.dilation) + 4;
  int ny = 2 * (int)ceil(2.0 * d.dilation / hy) + 4;
  st = mfs_disc_periodic_box(&d, nx, ny, &p, &q);
  if (st != MFS_OK)
    goto done;
  int euler = d.frame != MFS_FRAME_LAGRANGIAN && d.dim == 1 &&
              d.material.physics == MFS_PHYS_SCALAR;
  pl = mfs_plan_alloc(&d, p, q, &st);
  if (!pl)
    goto done;
  st = mfs_plan_tabulate(pl, euler || s->ls_beta > 0.0 ? 2 : 1, NULL);
  if (st != MFS_OK)
    goto done;

  int star = d.dim == 2 && d.quadrature->cells == MFS_CELLS_STAR;
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
  f.ls_beta = s->ls_beta;
  if ((st = mfs_row_init(&r, pl, &f)) != MFS_OK)
    goto done;
  size_t cap = 0;
  for (int b = 0; b < dp->nb; b++) {
    size_t I = (size_t)b; /* particles 0 and 1: (0,0) and (1,0) of the lattice */
    if ((st = mfs_row_assemble(&r, pl, &f, I)) != MFS_OK)
      goto done;
    mfs_row_sort(&r);
    if ((st = add_terms(dp, p, &r, I, &cap)) != MFS_OK)
      goto done;
  }
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

mfs_status mfs_disp_symbols(const mfs_disp_plan *dp, double sbar, const double *k,
                            double complex *K, double complex *M)
{
  const mfs_disp_spec *sp = &dp->spec;
  const mfs_disc *s = &sp->disc;
  int n = dp->nbr;
  double F = sp->stretch > 0.0 ? sp->stretch : 1.0;
  double ca, cg;
  if (s->material.physics == MFS_PHYS_PLANE_STRAIN) {
    ca = 1.0;
    cg = 0.0;
  } else if (s->dim == 1 && s->frame != MFS_FRAME_LAGRANGIAN) {
    ca = 1.0 + 2.0 * sbar; /* C~ + sigma, eq. 75 */
    cg = sbar;
  } else if (s->dim == 1) {
    ca = F * F + sbar; /* C-bar = C F^2 + S, eq. 81 */
    cg = 0.0;
  } else {
    ca = 1.0 + sbar;
    cg = 0.0;
  }
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

mfs_status mfs_disp_omega2(const mfs_disp_plan *dp, double sbar, double kappa, double theta,
                           double complex *omega2)
{
  int n = dp->nbr;
  double k[2] = {kappa * M_PI * cos(theta), kappa * M_PI * sin(theta)};
  if (dp->spec.disc.dim == 1)
    k[0] = kappa * M_PI, k[1] = 0.0;
  double complex K[16], M[16];
  mfs_disp_symbols(dp, sbar, k, K, M);
  /* Hermitian symbols (Lagrangian kernels and the 2D operators, without the
   * least-squares mass) are solved as Hermitian: omega^2 is exactly real */
  int herm = dp->spec.disc.frame == MFS_FRAME_LAGRANGIAN || dp->spec.disc.dim == 2;
  herm = herm && dp->spec.ls_beta == 0.0;
  if (n == 1) {
    if (cabs(M[0]) == 0.0)
      return MFS_EDOMAIN;
    omega2[0] = herm ? creal(K[0]) / creal(M[0]) : K[0] / M[0];
    return isfinite(creal(omega2[0])) && isfinite(cimag(omega2[0])) ? MFS_OK : MFS_EDOMAIN;
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
