#include "mfs_dispersion.h"

#include <complex.h>
#undef I /* particle indices are called I here */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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

/* Unit-cell class of particle I: the star pattern has two particles per cell. */
static int node_class(const mfs_disp_spec *s, const mfs_particles *p, size_t I)
{
  if (s->dim == 2 && s->lattice == MFS_LATTICE_SQUARE && p->nvert == 3 && strcmp(s->quadrature, "stress-star") == 0)
    return (p->ij[2 * I] + p->ij[2 * I + 1]) & 1;
  return 0;
}

/* Accumulators of one row, indexed by particle. */
typedef struct {
  double A[4], G, M;
  int used;
} row_acc;

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

static int add_terms(mfs_disp_plan *dp, const mfs_plan *pl, size_t I, int cls, row_acc *acc,
                     size_t *cap)
{
  const mfs_particles *p = pl->p;
  int nd = dp->ndof;
  double msum[2] = {0.0, 0.0};
  for (size_t K = 0; K < p->n; K++) {
    if (!acc[K].used)
      continue;
    double d[3] = {0.0, 0.0, 0.0};
    mfs_box_delta(&p->box, p->x + I * p->dim, p->x + K * p->dim, d);
    int ck = node_class(&dp->spec, p, K);
    for (int r = 0; r < nd; r++) {
      msum[r] += acc[K].M;
      for (int c = 0; c < nd; c++) {
        disp_term *t = push_term(dp, cap);
        if (!t)
          return MFS_ENOMEM;
        t->row = cls * nd + r;
        t->col = ck * nd + c;
        t->d[0] = d[0];
        t->d[1] = d[1];
        t->A = acc[K].A[r * nd + c];
        t->G = nd == 1 ? acc[K].G : 0.0;
        t->M = (dp->spec.consistent_mass && r == c) ? acc[K].M : 0.0;
      }
    }
  }
  if (!dp->spec.shape->partition_of_unity) /* sph: particle mass rho V (eq. 51) */
    msum[0] = msum[1] = p->vol[I];
  if (!dp->spec.consistent_mass) /* lumped: row sums on the diagonal */
    for (int r = 0; r < nd; r++) {
      disp_term *t = push_term(dp, cap);
      if (!t)
        return MFS_ENOMEM;
      *t = (disp_term){cls * nd + r, cls * nd + r, {0.0, 0.0}, 0.0, 0.0, msum[r]};
    }
  return MFS_OK;
}

/* Accumulate row I of A, G and M over all quadrature points that see I. */
static void row_accumulate(const mfs_disp_plan *dp, const mfs_plan *pl, size_t I, row_acc *acc,
                           double *mu, int *status)
{
  *status = MFS_OK;
  const mfs_disp_spec *s = &dp->spec;
  const mfs_nlist *nl = pl->nl;
  const mfs_quad *q = pl->q;
  int dim = pl->dim, nc = pl->ncomp;
  int euler = s->frame != MFS_FRAME_LAGRANGIAN && s->dim == 1 && s->physics == MFS_PHYS_SCALAR;
  int consistent = s->frame == MFS_FRAME_EULERIAN_CONSISTENT;
  double F = s->stretch > 0.0 ? s->stretch : 1.0, beta = s->ls_beta;
  for (size_t Q = 0; Q < nl->nq; Q++) {
    size_t e0 = nl->ptr[Q], e1 = nl->ptr[Q + 1], eI = e1;
    for (size_t e = e0; e < e1; e++)
      if ((size_t)nl->idx[e] == I)
        eI = e;
    if (eI == e1)
      continue;
    double w = q->w[Q];
    const double *fi = pl->tab + eI * nc;
    double lapI = 0.0;
    if (pl->order >= 2)
      for (int k = 0; k < dim; k++)
        lapI += fi[1 + dim + k * dim + k];
    for (size_t e = e0; e < e1; e++) {
      int K = nl->idx[e];
      const double *fk = pl->tab + e * nc;
      row_acc *a = acc + K;
      a->used = 1;
      if (s->physics == MFS_PHYS_PLANE_STRAIN) {
        double ix = fi[1], iy = fi[2], jx = fk[1], jy = fk[2];
        double c0 = mu[0] + 2.0 * mu[1], c1 = mu[0], c2 = mu[1];
        a->A[0] += w * (c0 * ix * jx + c2 * iy * jy);
        a->A[1] += w * (c1 * ix * jy + c2 * iy * jx);
        a->A[2] += w * (c1 * iy * jx + c2 * ix * jy);
        a->A[3] += w * (c0 * iy * jy + c2 * ix * jx);
      } else {
        double g = 0.0;
        for (int k = 0; k < dim; k++)
          g += fi[1 + k] * fk[1 + k];
        a->A[0] += w * g;
      }
      a->M += w * fi[0] * fk[0];
      if (beta > 0.0) {
        double lapK = 0.0;
        for (int k = 0; k < dim; k++)
          lapK += fk[1 + dim + k * dim + k];
        a->A[0] += beta * w * lapI * lapK;
        a->M -= beta * w * lapI * fk[0];
      }
      if (euler && consistent) {
        /* phi_I''(Q) u~_Q with u~_Q = u~_node or sum_K phi_K(Q) u~_K; the
         * position derivatives d phi_I'(Q)/d x_K are added per point below */
        if (q->node[Q] >= 0) {
          if (K == q->node[Q])
            a->G += w * lapI;
        } else {
          a->G += w * lapI * fk[0];
        }
      } else if (euler) {
        /* kernel motion, phi_I''(Q) (u~_Q - u~_I): eqs 71, 89-92 */
        if (q->node[Q] >= 0) {
          if (K == q->node[Q])
            a->G += w * lapI;
        } else {
          double dQK[3], dQI[3]; /* x_K - x_I through the point, minimum image */
          mfs_box_delta(&pl->p->box, q->x + Q * dim, pl->p->x + (size_t)K * dim, dQK);
          mfs_box_delta(&pl->p->box, q->x + Q * dim, pl->p->x + I * dim, dQI);
          double uK = (1.0 - 1.0 / F) * (dQK[0] - dQI[0]); /* eq. 92 */
          a->G += w * lapI * F * (fk[0] - fk[1] * uK);
        }
      }
    }
    if (euler && !consistent)
      acc[I].G -= w * lapI, acc[I].used = 1;
    if (euler && consistent) {
      int nn = (int)(e1 - e0), iI = (int)(eI - e0);
      double dq[64], vq[64], dphi[64], dgrad[64];
      if (nn > 64) {
        *status = MFS_ENOTSUP;
        return;
      }
      for (int j = 0; j < nn; j++) {
        double dd[3];
        mfs_box_delta(&pl->p->box, q->x + Q * dim, pl->p->x + (size_t)nl->idx[e0 + j] * dim, dd);
        dq[j] = dd[0];
        vq[j] = pl->p->vol[nl->idx[e0 + j]];
      }
      for (int k = 0; k < nn; k++) {
        int st = mfs_shape_dpos_1d(s->shape, &pl->ctx, nn, dq, vq, k, dphi, dgrad);
        if (st != MFS_OK) {
          *status = st;
          return;
        }
        acc[nl->idx[e0 + k]].G += w * dgrad[iI];
        acc[nl->idx[e0 + k]].used = 1;
      }
    }
  }
}

mfs_disp_plan *mfs_disp_plan_alloc(const mfs_disp_spec *s, int *status)
{
  int st = MFS_EINVAL;
  mfs_disp_plan *dp = NULL;
  mfs_particles *p = NULL;
  mfs_quad *q = NULL;
  mfs_plan *pl = NULL;
  row_acc *acc = NULL;
  mfs_quad_rule rule;
  if (!s->kernel || !s->shape || !(s->dilation > 0.0) || s->ls_beta < 0.0)
    goto done;
  if (mfs_quad_rule_parse(s->quadrature, &rule) != MFS_OK ||
      mfs_quad_rule_check(&rule, s->dim, s->lattice) != MFS_OK)
    goto done;
  st = MFS_ENOTSUP;
  if (s->physics == MFS_PHYS_PLANE_STRAIN && (s->dim != 2 || s->ls_beta > 0.0))
    goto done;
  if (s->dim == 2 && s->stretch > 0.0 && s->stretch != 1.0)
    goto done;
  /* the consistent frame: 1D; a pre-stretch moves interpolated points exactly
   * with sum_K phi_K u~_K only for linearly complete shapes */
  if (s->frame == MFS_FRAME_EULERIAN_CONSISTENT &&
      (s->dim != 1 || (s->stretch > 0.0 && s->stretch != 1.0 && s->shape != &mfs_shape_mls) ||
       (s->shape != &mfs_shape_mls && s->shape != &mfs_shape_shepard && s->shape != &mfs_shape_sph)))
    goto done;
  st = MFS_ENOMEM;
  dp = calloc(1, sizeof *dp);
  if (!dp)
    goto done;
  dp->spec = *s;
  dp->ndof = mfs_physics_ndof(s->physics);

  double gamma = s->gamma > 0.0 ? s->gamma : 1.0;
  double hy = s->lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 : gamma;
  int nx = 2 * (int)ceil(2.0 * s->dilation) + 4;
  int ny = 2 * (int)ceil(2.0 * s->dilation / hy) + 4;
  mfs_lattice_spec ls = {s->dim, s->lattice, nx, s->dim == 1 ? 1 : ny, 1.0, gamma, 1,
                         rule.cells, 0.0, 0};
  p = mfs_lattice_alloc(&ls, &st);
  if (!p)
    goto done;
  q = mfs_quad_alloc(&rule, p, &st);
  if (!q)
    goto done;
  int need2 = (s->frame != MFS_FRAME_LAGRANGIAN && s->dim == 1) || s->ls_beta > 0.0;
  mfs_plan_spec ps = {s->kernel, s->shape, s->dilation, need2 ? 2 : 1, 1e-12};
  pl = mfs_plan_alloc(&ps, p, q, &st, NULL);
  if (!pl)
    goto done;

  int star = s->dim == 2 && rule.kind == MFS_QK_VORONOI;
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
  st = MFS_ENOMEM;
  acc = malloc(p->n * sizeof *acc);
  if (!acc)
    goto done;
  double nu = s->poisson;
  double mu[2] = {2.0 * nu / (1.0 - 2.0 * nu), 1.0}; /* lambda, mu with mu = 1 */
  size_t cap = 0;
  for (int b = 0; b < dp->nb; b++) {
    size_t I = (size_t)b; /* particles 0 and 1: (0,0) and (1,0) of the lattice */
    memset(acc, 0, p->n * sizeof *acc);
    row_accumulate(dp, pl, I, acc, mu, &st);
    if (st != MFS_OK)
      goto done;
    st = add_terms(dp, pl, I, node_class(s, p, I), acc, &cap);
    if (st != MFS_OK)
      goto done;
  }
  st = MFS_OK;
done:
  free(acc);
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

int mfs_disp_symbols(const mfs_disp_plan *dp, double sbar, const double *k, double complex *K,
                     double complex *M)
{
  const mfs_disp_spec *s = &dp->spec;
  int n = dp->nbr;
  double F = s->stretch > 0.0 ? s->stretch : 1.0;
  double ca, cg;
  if (s->physics == MFS_PHYS_PLANE_STRAIN) {
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

int mfs_disp_omega2(const mfs_disp_plan *dp, double sbar, double kappa, double theta,
                    double complex *omega2)
{
  int n = dp->nbr;
  double k[2] = {kappa * M_PI * cos(theta), kappa * M_PI * sin(theta)};
  if (dp->spec.dim == 1)
    k[0] = kappa * M_PI, k[1] = 0.0;
  double complex K[16], M[16];
  mfs_disp_symbols(dp, sbar, k, K, M);
  if (n == 1) {
    if (cabs(M[0]) == 0.0)
      return MFS_EDOMAIN;
    omega2[0] = K[0] / M[0];
    return MFS_OK;
  }
  int herm = dp->spec.frame == MFS_FRAME_LAGRANGIAN || dp->spec.dim == 2;
  /* (1D Eulerian symbols are 1 x 1) */
  herm = herm && dp->spec.ls_beta == 0.0;
  if (herm) {
    double wr[4];
    lapack_int info = LAPACKE_zhegv(LAPACK_ROW_MAJOR, 1, 'N', 'U', n, K, n, M, n, wr);
    if (info != 0)
      return info > n ? MFS_EDOMAIN : MFS_ELAPACK;
    for (int i = 0; i < n; i++)
      omega2[i] = wr[i];
    return MFS_OK;
  }
  double complex al[4], be[4], vl[1], vr[1];
  lapack_int info = LAPACKE_zggev(LAPACK_ROW_MAJOR, 'N', 'N', n, K, n, M, n, al, be, vl, 1, vr, 1);
  if (info != 0)
    return MFS_ELAPACK;
  for (int i = 0; i < n; i++) {
    if (cabs(be[i]) == 0.0)
      return MFS_EDOMAIN;
    omega2[i] = al[i] / be[i];
  }
  qsort(omega2, (size_t)n, sizeof *omega2, cmp_re);
  return MFS_OK;
}

int mfs_disp_is_reciprocal(const mfs_disp_plan *dp, const double *k, double tol)
{
  int dim = dp->spec.dim;
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
  if (dp->spec.dim == 1)
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
