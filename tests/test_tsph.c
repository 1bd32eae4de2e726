/* lib/mfs_tsph (paper 001, the two-step Taylor SPH scheme): exact transport
 * at c dt = dx, second-order convergence, the fixed-end reflection, energy of
 * the elastic bar, and the error returns. */
#include <stdlib.h>

#include "check.h"
#include "mfstab.h"

static const double RHO = 2000.0, E = 8e7; /* paper 001 section 4.1.1: c = 200 m/s */

static mfs_tsph_spec elastic(int n, int linear)
{
  mfs_tsph_spec s = {0};
  s.n = n;
  s.length = 1.0;
  s.density = RHO;
  s.modulus = E;
  s.yield_stress = INFINITY;
  s.dilation = 2.0;
  s.scheme = MFS_TSPH_TAYLOR;
  s.linear_interpolation = linear;
  s.bc[0] = s.bc[1] = MFS_BC_FIXED;
  return s;
}

/* a right-going wave v = f(x - ct), sigma = -rho c v, away from the ends */
static double pulse(double x)
{
  return exp(-400.0 * (x - 0.3) * (x - 0.3));
}

/* max |v - exact| / max |v| after the pulse has moved by `shift` (m) */
static double transport_error(int n, int linear, double cfl, double shift, int *status)
{
  mfs_tsph_spec sp = elastic(n, linear);
  mfs_tsph *s = mfs_tsph_alloc(&sp, status);
  if (!s)
    return INFINITY;
  double c = sqrt(E / RHO), *sig = malloc(s->n * sizeof *sig), *v = malloc(s->n * sizeof *v);
  for (size_t I = 0; I < s->n; I++) {
    v[I] = pulse(s->X[I]);
    sig[I] = -RHO * c * v[I];
  }
  mfs_tsph_set_state(s, sig, v);
  mfs_tsph_set_dt(s, cfl * s->dx / c);
  long steps = lround(shift / (c * s->dt));
  for (long k = 0; k < steps && *status == MFS_OK; k++)
    *status = mfs_tsph_step(s);
  double err = 0.0;
  for (size_t I = 0; I < s->n; I++)
    err = fmax(err, fabs(s->v[I] - pulse(s->X[I] - c * s->t)));
  free(sig);
  free(v);
  mfs_tsph_free(s);
  return err;
}

int main(void)
{
  int st;
  /* Richtmyer's two-step Lax-Wendroff shifts the grid function by exactly one
   * particle per step at c dt = dx (both interpolations: the pulse stays away
   * from the ends, where they differ) */
  for (int lin = 0; lin < 2; lin++) {
    double e = transport_error(121, lin, 1.0, 0.35, &st);
    CHECK(st == MFS_OK && e < 1e-12, "exact transport at c dt = dx (interpolation %d): error %.3g", lin, e);
  }
  /* second order at c dt = 0.5 dx: halving dx divides the error by about 4 */
  double e1 = transport_error(201, 0, 0.5, 0.3, &st), e2 = transport_error(401, 0, 0.5, 0.3, &st);
  CHECK(st == MFS_OK && e1 / e2 > 3.5 && e1 / e2 < 4.5, "order 2: errors %.3g, %.3g, ratio %.3g", e1, e2,
        e1 / e2);

  /* the paper's bar: left end driven at 1 m/s for 2.5 ms, right end fixed;
   * after the reflection the fixed-end stress is -2 rho c v0 = -8e5 Pa */
  mfs_tsph_spec sp = elastic(50, 0);
  sp.bc[0] = MFS_BC_VELOCITY;
  sp.bc_velocity[0] = 1.0;
  sp.bc_until[0] = 2.5e-3;
  mfs_tsph *s = mfs_tsph_alloc(&sp, &st);
  CHECK(s != NULL, "alloc bar: %s", mfs_strerror(st));
  if (s) {
    mfs_tsph_set_dt(s, 9.9e-5);
    double plateau_min = INFINITY, plateau_max = -INFINITY;
    while (s->t < 7.3e-3 && mfs_tsph_step(s) == MFS_OK)
      if (s->t > 5.8e-3) {
        plateau_min = fmin(plateau_min, -s->sigma[s->n - 1]);
        plateau_max = fmax(plateau_max, -s->sigma[s->n - 1]);
      }
    CHECK(plateau_min > 0.98 * 8e5 && plateau_max < 1.02 * 8e5,
          "reflected plateau [%.6g, %.6g] Pa, want 8e5 within 2%%", plateau_min, plateau_max);
    mfs_tsph_free(s);
  }

  /* elastic energy of a free-free bar at c dt = dx: the exact shift keeps it */
  sp = elastic(101, 1);
  sp.bc[0] = sp.bc[1] = MFS_BC_FREE;
  s = mfs_tsph_alloc(&sp, &st);
  if (s) {
    double *v = malloc(s->n * sizeof *v);
    for (size_t I = 0; I < s->n; I++)
      v[I] = pulse(s->X[I] + 0.2);
    mfs_tsph_set_state(s, NULL, v);
    free(v);
    double k0, p0, k1, p1;
    mfs_tsph_energy(s, &k0, &p0);
    for (int i = 0; i < 30; i++)
      mfs_tsph_step(s);
    mfs_tsph_energy(s, &k1, &p1);
    CHECK_NEAR(k1 + p1, k0 + p0, 1e-9 * (k0 + p0), "energy of the split pulse (interior, before the ends)");
    mfs_tsph_free(s);
  }

  /* error returns */
  sp = elastic(2, 0);
  CHECK(mfs_tsph_alloc(&sp, &st) == NULL && st == MFS_EINVAL, "n = 2: status %d", st);
  sp = elastic(50, 0);
  sp.density = -1.0;
  CHECK(mfs_tsph_alloc(&sp, &st) == NULL && st == MFS_EINVAL, "negative density: status %d", st);
  sp = elastic(50, 0);
  sp.dilation = 0.5;
  CHECK(mfs_tsph_alloc(&sp, &st) == NULL && st == MFS_ESINGULAR, "support without neighbours: status %d", st);
  sp = elastic(50, 0);
  s = mfs_tsph_alloc(&sp, &st);
  if (s) {
    CHECK(mfs_tsph_set_dt(s, 0.0) == MFS_EINVAL, "dt = 0 refused");
    double bad[50] = {0};
    bad[7] = NAN;
    CHECK(mfs_tsph_set_state(s, NULL, bad) == MFS_EDOMAIN, "NaN state refused");
    mfs_tsph_scheme sc;
    CHECK(mfs_tsph_scheme_parse("lax", &sc) == MFS_EINVAL, "unknown scheme name");
    mfs_tsph_free(s);
  }
  return check_summary("test_tsph");
}
