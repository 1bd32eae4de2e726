#include "mfs_classify.h"
#include "mfs_alloc.h"

#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The kappa of sample i on a ray with kappa_max km. */
static double sample(const mfs_sampling *smp, double km, size_t i)
{
  return smp->kappa ? smp->kappa[i] : km * (double)i / (double)(smp->npoints - 1);
}

static size_t nsamples(const mfs_sampling *smp)
{
  return smp->kappa ? smp->nkappa : (size_t)smp->npoints;
}

/* Smallest real part of omega^2 over the sampled kappa of all rays
 * (npts uniform samples in (0, kappa_max]). */
static double min_omega2(const mfs_disp_plan *pl, double sbar, const mfs_sampling *smp, int npts,
                         double complex *buf)
{
  double m = INFINITY;
  int nb = mfs_disp_branches(pl);
  for (size_t t = 0; t < smp->ntheta; t++) {
    double km = mfs_disp_kappa_max(pl, smp->theta[t]);
    for (int i = 1; i <= npts; i++) {
      double kap = km * i / npts;
      if (mfs_disp_omega2(pl, sbar, kap, smp->theta[t], buf) != MFS_OK)
        continue;
      for (int b = 0; b < nb; b++)
        m = creal(buf[b]) < m ? creal(buf[b]) : m;
    }
  }
  return m;
}

/* Smallest |sbar| in the direction sign (+1 tension, -1 compression) at
 * which some omega^2 < -tol; NAN if none up to the limit. */
static double onset(const mfs_disp_plan *pl, int sign, const mfs_sampling *smp, int npts,
                    double tol, double complex *buf)
{
  double lo = 0.0, hi = sign > 0 ? 10.0 : 1.0 + 1e-9;
  mfs_plane_state ps;
  if (mfs_disp_plan_spec(pl)->disc.material.physics == MFS_PHYS_PLANE_STRAIN &&
      mfs_disp_state(pl, sign * hi, &ps) != MFS_OK)
    return NAN; /* a finite material: the state is the plan's */
  if (min_omega2(pl, sign * hi, smp, npts, buf) >= -tol)
    return NAN;
  if (min_omega2(pl, 0.0, smp, npts, buf) < -tol)
    return 0.0;
  for (int it = 0; it < 50; it++) {
    double mid = 0.5 * (lo + hi);
    if (min_omega2(pl, sign * mid, smp, npts, buf) < -tol)
      hi = mid;
    else
      lo = mid;
  }
  return sign * hi;
}

/* The wave vector of (kappa, theta) in 1/dx. */
static void wave_vector(const mfs_disp_plan *pl, double kap, double th, double *kv)
{
  kv[0] = kap * M_PI * cos(th);
  kv[1] = kap * M_PI * sin(th);
  if (mfs_disp_plan_spec(pl)->disc.dim == 1)
    kv[1] = 0.0;
}

unsigned mfs_class_labels(int unstable, const mfs_ellipticity *pde, double sigma_nn,
                          double sigma_mean, int spurious_zeros)
{
  unsigned l = 0;
  int continuum = !mfs_pde_stable(pde);
  if (unstable && continuum)
    l |= MFS_LABEL_MATERIAL;
  if (unstable && !continuum) {
    double s = sigma_nn != 0.0 ? sigma_nn : sigma_mean;
    l |= s < 0.0 ? MFS_LABEL_COMPRESSIVE : MFS_LABEL_TENSILE;
  }
  if (spurious_zeros > 0)
    l |= MFS_LABEL_RANK_DEFICIENCY;
  return l;
}

/* The normal stress along the current direction of the frame's wave vector
 * (kappa, theta), and the mean stress, at sbar. */
static void stress_along(const mfs_disp_plan *pl, double sbar, double kap, double th, double *snn,
                         double *smean)
{
  mfs_plane_state ps;
  if (mfs_disp_state(pl, sbar, &ps) != MFS_OK) { /* 1D, anti-plane (equibiaxial) */
    *snn = *smean = sbar;
    return;
  }
  double k[2] = {kap * M_PI * cos(th), kap * M_PI * sin(th)}, kc[2];
  mfs_disp_current_k(pl, k, kc);
  double nk = hypot(kc[0], kc[1]), n[2] = {nk > 0 ? kc[0] / nk : 1.0, nk > 0 ? kc[1] / nk : 0.0};
  const double *s = ps.sigma;
  *snn = n[0] * n[0] * s[0] + n[0] * n[1] * (s[1] + s[2]) + n[1] * n[1] * s[3];
  *smean = 0.5 * (s[0] + s[3]);
}

/* max over the rays of the relative deviation of the acoustic branches'
 * omega^2 / kappa^2 from the continuum's (Richardson from kappa dx = 1e-3, 2e-3) */
static double longwave_dev(const mfs_disp_plan *pl, double sbar, const mfs_sampling *smp,
                           double complex *buf)
{
  const int nd = mfs_physics_ndof(mfs_disp_plan_spec(pl)->disc.material.physics);
  double dev = 0.0;
  for (size_t t = 0; t < smp->ntheta; t++) {
    double q[2], w[2][2];
    if (mfs_disp_longwave(pl, sbar, smp->theta[t], q) != MFS_OK)
      return NAN;
    for (int r = 0; r < 2; r++) {
      double h = r ? 2e-3 : 1e-3;
      if (mfs_disp_omega2(pl, sbar, h / M_PI, smp->theta[t], buf) != MFS_OK)
        return NAN;
      for (int b = 0; b < nd; b++)
        w[r][b] = creal(buf[b]) / (h * h);
    }
    double sc = 0.0;
    for (int b = 0; b < nd; b++)
      sc = fmax(sc, fabs(q[b]));
    for (int b = 0; b < nd; b++) {
      double rich = (4.0 * w[0][b] - w[1][b]) / 3.0;
      dev = fmax(dev, fabs(rich - q[b]) / (sc > 0.0 ? sc : 1.0));
    }
  }
  return dev;
}

mfs_status mfs_classify(const mfs_disp_plan *pl, const mfs_sampling *smp, const double *sbar,
                        size_t nsbar, mfs_class *out)
{
  if (!pl || !smp || !smp->theta || smp->ntheta < 1 || (!smp->kappa && smp->npoints < 2) ||
      (smp->kappa && smp->nkappa < 1) || (!sbar && nsbar))
    return MFS_EINVAL;
  const int nb = mfs_disp_branches(pl), nk = (int)nsamples(smp);
  double complex buf[4];
  double complex *w = mfs_malloc((size_t)nk * (size_t)nb * sizeof *w);
  if (!w)
    return MFS_ENOMEM;
  mfs_status st = MFS_OK;
  /* the scale: the largest |omega^2| at sbar = 0, for relative zero tests */
  double scale = 0.0;
  for (size_t t = 0; t < smp->ntheta; t++) {
    double km = mfs_disp_kappa_max(pl, smp->theta[t]);
    for (int i = 0; i <= 200; i++) {
      if (mfs_disp_omega2(pl, 0.0, km * i / 200, smp->theta[t], buf) != MFS_OK)
        continue;
      for (int b = 0; b < nb; b++)
        scale = cabs(buf[b]) > scale ? cabs(buf[b]) : scale;
    }
  }
  const double tol = 1e-10 * scale;
  double onset_t = onset(pl, +1, smp, nk, tol, buf);
  double onset_c = onset(pl, -1, smp, nk, tol, buf);
  for (size_t si = 0; si < nsbar && st == MFS_OK; si++) {
    double sb = sbar[si];
    mfs_class c = {.sbar = sb,
                   .min_omega2 = INFINITY,
                   .theta_at_min = 0,
                   .unstable_kappa_from = NAN,
                   .unstable_kappa_to = NAN,
                   .max_growth = 0.0,
                   .kappa_at_max_growth = NAN,
                   .theta_at_max_growth = -1,
                   .zero_kappa = NAN,
                   .zero_theta = -1,
                   .onset_tension = onset_t,
                   .onset_compression = onset_c};
    int nzero0 = 0;
    for (size_t t = 0; t < smp->ntheta && st == MFS_OK; t++) {
      double th = smp->theta[t], km = mfs_disp_kappa_max(pl, th);
      for (int i = 0; i < nk && st == MFS_OK; i++)
        st = mfs_disp_omega2(pl, sb, sample(smp, km, (size_t)i), th, w + (size_t)i * nb);
      for (int i = 0; i < nk && st == MFS_OK; i++) {
        double kap = sample(smp, km, (size_t)i), kv[2];
        wave_vector(pl, kap, th, kv);
        for (int b = 0; b < nb; b++) {
          double complex w2 = w[(size_t)i * nb + b], wr = csqrt(w2);
          double re = creal(w2), g = fabs(cimag(wr));
          if (re < c.min_omega2) {
            c.min_omega2 = re;
            c.kappa_at_min = kap;
            c.theta_at_min = (int)t;
          }
          if (re < -tol || g > sqrt(tol)) {
            c.unstable_kappa_from =
              isnan(c.unstable_kappa_from) || kap < c.unstable_kappa_from ? kap
                                                                          : c.unstable_kappa_from;
            c.unstable_kappa_to =
              isnan(c.unstable_kappa_to) || kap > c.unstable_kappa_to ? kap : c.unstable_kappa_to;
            if (g > c.max_growth) {
              c.max_growth = g;
              c.kappa_at_max_growth = kap;
              c.theta_at_max_growth = (int)t;
            }
          }
          if (fabs(re) <= tol && !mfs_disp_is_reciprocal(pl, kv, 1e-9)) {
            c.spurious_zeros++;
            c.zero_kappa = kap;
            c.zero_theta = (int)t;
          }
        }
      }
      if (sb != 0.0 && st == MFS_OK) { /* rank deficiency: zeros at sbar = 0 */
        for (int i = 0; i < nk && st == MFS_OK; i++)
          st = mfs_disp_omega2(pl, 0.0, sample(smp, km, (size_t)i), th, w + (size_t)i * nb);
        for (int i = 0; i < nk && st == MFS_OK; i++) {
          double kv[2];
          wave_vector(pl, sample(smp, km, (size_t)i), th, kv);
          for (int b = 0; b < nb; b++)
            if (fabs(creal(w[(size_t)i * nb + b])) <= tol && !mfs_disp_is_reciprocal(pl, kv, 1e-9))
              nzero0++;
        }
      }
    }
    if (sb == 0.0)
      nzero0 = c.spurious_zeros;
    if (st != MFS_OK)
      break;
    c.unstable = c.min_omega2 < -tol || c.max_growth > 0.0;
    if ((st = mfs_disp_pde(pl, sb, &c.pde)) != MFS_OK)
      break;
    double smean = NAN;
    c.sigma_nn = NAN;
    if (c.unstable) { /* the worst mode: the most negative omega^2, else the fastest growth */
      int by_min = c.min_omega2 < -tol;
      stress_along(pl, sb, by_min ? c.kappa_at_min : c.kappa_at_max_growth,
                   smp->theta[by_min ? c.theta_at_min : c.theta_at_max_growth], &c.sigma_nn, &smean);
    }
    c.longwave_deviation = longwave_dev(pl, sb, smp, buf);
    c.labels = mfs_class_labels(c.unstable, &c.pde, c.sigma_nn, smean, nzero0);
    out[si] = c;
  }
  mfs_free(w);
  return st;
}

const char *mfs_class_label(unsigned labels, char *buf, size_t len)
{
  static const struct {
    unsigned bit;
    const char *name;
  } names[] = {{MFS_LABEL_MATERIAL, "material"},
               {MFS_LABEL_TENSILE, "tensile"},
               {MFS_LABEL_COMPRESSIVE, "compressive"},
               {MFS_LABEL_RANK_DEFICIENCY, "rank-deficiency"}};
  if (len == 0)
    return buf;
  buf[0] = '\0';
  for (int k = 0; k < 4; k++)
    if (labels & names[k].bit) {
      if (buf[0])
        strncat(buf, "+", len - strlen(buf) - 1);
      strncat(buf, names[k].name, len - strlen(buf) - 1);
    }
  if (!buf[0])
    strncat(buf, "stable", len - 1);
  return buf;
}
