#include "mfs_dispersion.h"
#include "mfs_alloc.h"

#include <complex.h>
#undef I /* particle indices are called I here */
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_lapack.h"
#include "mfs_status.h"

#define P4(i, j, k, l) ((((i)*2 + (j)) * 2 + (k)) * 2 + (l))

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
  int mij;         /* plane strain: the largest |i|, |j| of the terms' offsets */
  size_t nterm;
  disp_term *t;
};

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
  if (dp->plane) { /* the lattice coordinates of every offset, for the phase tables */
    double det = dp->a1[0] * dp->a2[1] - dp->a1[1] * dp->a2[0];
    for (size_t i = 0; i < dp->nterm; i++) {
      disp_term *t = dp->t + i;
      double u = (t->d[0] * dp->a2[1] - t->d[1] * dp->a2[0]) / det;
      double v = (dp->a1[0] * t->d[1] - dp->a1[1] * t->d[0]) / det;
      t->ij[0] = (int)lround(u);
      t->ij[1] = (int)lround(v);
      int m = abs(t->ij[0]) > abs(t->ij[1]) ? abs(t->ij[0]) : abs(t->ij[1]);
      dp->mij = m > dp->mij ? m : dp->mij;
    }
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

/* The lattice sums of the plane-strain terms at k: per branch pair (row,
 * col) of particles, SA[.][4] = sum A^{jl} e^{ik.d}, SG likewise, SM the mass. */
typedef struct {
  double complex SA[2][2][4], SG[2][2][4], SM[2][2];
} plane_sums;

enum { MAX_MIJ = 256 };

static void plane_sum(const mfs_disp_plan *dp, const double *k, plane_sums *ps)
{
  memset(ps, 0, sizeof *ps);
  /* e^{ik.d} = e^{i i k.a1} e^{i j k.a2} from tables of powers (no sincos per term) */
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
    double complex *sa = ps->SA[t->row][t->col], *sg = ps->SG[t->row][t->col];
    for (int q = 0; q < 4; q++)
      sa[q] += t->A2[q] * e;
    if (dp->euler2)
      for (int q = 0; q < 4; q++)
        sg[q] += t->G2[q] * e;
    ps->SM[t->row][t->col] += t->M * e;
  }
}

/* K and M (nbr x nbr) of a state from the sums: Lagrangian K_ik = A_ijkl SA^{jl};
 * Eulerian K_ik = a_ijkl SA^{jl} + sigma_im SA^{km} + sigma_ij SG^{jk} (eq. C6). */
static void plane_contract(const mfs_disp_plan *dp, const plane_sums *ps, const mfs_plane_state *st,
                           double complex *K, double complex *M)
{
  const int n = dp->nbr;
  const double *t = dp->euler2 ? st->a : st->A, *sg = st->sigma;
  for (int rb = 0; rb < dp->nb; rb++)
    for (int cb = 0; cb < dp->nb; cb++) {
      const double complex *A = ps->SA[rb][cb], *G = ps->SG[rb][cb];
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
          M[(rb * 2 + i) * n + cb * 2 + k] = i == k ? ps->SM[rb][cb] : 0.0;
        }
    }
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
  plane_sums ps;
  plane_sum(dp, k, &ps);
  plane_contract(dp, &ps, s, K, M);
  return MFS_OK;
}

mfs_status mfs_disp_symbols(const mfs_disp_plan *dp, double sbar, const double *k,
                            double complex *K, double complex *M)
{
  const mfs_disp_spec *sp = &dp->spec;
  const mfs_disc *s = &sp->disc;
  int n = dp->nbr;
  if (dp->plane) {
    mfs_plane_state st;
    mfs_status e = mfs_disp_state(dp, sbar, &st);
    return e != MFS_OK ? e : mfs_disp_symbols_state(dp, &st, k, K, M);
  }
  double F = sp->stretch > 0.0 ? sp->stretch : 1.0;
  double ca, cg;
  if (s->dim == 1 && s->frame != MFS_FRAME_LAGRANGIAN) {
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

/* The generalized eigenvalues of K v = omega^2 M v (n x n), sorted by real
 * part; herm: K and M Hermitian.  A 2 x 2 problem with M = m I (one particle,
 * lumped mass) in closed form. */
static mfs_status eig_solve(int n, double complex *K, double complex *M, int herm,
                            double complex *omega2)
{
  if (n == 1) {
    if (cabs(M[0]) == 0.0)
      return MFS_EDOMAIN;
    omega2[0] = herm ? creal(K[0]) / creal(M[0]) : K[0] / M[0];
    return isfinite(creal(omega2[0])) && isfinite(cimag(omega2[0])) ? MFS_OK : MFS_EDOMAIN;
  }
  if (n == 2 && M[1] == 0.0 && M[2] == 0.0 && M[0] == M[3]) {
    if (cabs(M[0]) == 0.0)
      return MFS_EDOMAIN;
    double complex m = M[0];
    if (herm) {
      double a = creal(K[0]) / creal(m), d = creal(K[3]) / creal(m);
      double b = cabs(K[1]) / creal(m), r = hypot(0.5 * (a - d), b);
      omega2[0] = 0.5 * (a + d) - r;
      omega2[1] = 0.5 * (a + d) + r;
      return isfinite(r) && isfinite(a + d) ? MFS_OK : MFS_EDOMAIN;
    }
    double complex a = K[0] / m, b = K[1] / m, c = K[2] / m, d = K[3] / m;
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

mfs_status mfs_disp_omega2_state(const mfs_disp_plan *dp, const mfs_plane_state *s,
                                 const double *k, double complex *omega2)
{
  double complex K[16], M[16];
  mfs_status st = mfs_disp_symbols_state(dp, s, k, K, M);
  return st != MFS_OK ? st : eig_solve(dp->nbr, K, M, hermitian(dp), omega2);
}

mfs_status mfs_disp_omega2(const mfs_disp_plan *dp, double sbar, double kappa, double theta,
                           double complex *omega2)
{
  int n = dp->nbr;
  double k[2] = {kappa * M_PI * cos(theta), kappa * M_PI * sin(theta)};
  if (dp->spec.disc.dim == 1)
    k[0] = kappa * M_PI, k[1] = 0.0;
  double complex K[16], M[16];
  mfs_status st = mfs_disp_symbols(dp, sbar, k, K, M);
  if (st != MFS_OK)
    return st;
  return eig_solve(n, K, M, hermitian(dp), omega2);
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
  plane_sums *s;
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
  for (size_t i = 0; i < nk; i++)
    plane_sum(pl, k + 2 * i, s->s + i);
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
  plane_contract(s->pl, s->s + i, st, K, M);
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
