#include "mfs_classify.h"

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

mfs_status mfs_classify(const mfs_disp_plan *pl, const mfs_sampling *smp, const double *sbar,
                        size_t nsbar, mfs_class *out)
{
  if (!pl || !smp || !smp->theta || smp->ntheta < 1 || (!smp->kappa && smp->npoints < 2) ||
      (smp->kappa && smp->nkappa < 1) || (!sbar && nsbar))
    return MFS_EINVAL;
  const mfs_disp_spec *sp = mfs_disp_plan_spec(pl);
  const int nb = mfs_disp_branches(pl), nk = (int)nsamples(smp);
  double complex buf[4];
  double complex *w = malloc((size_t)nk * (size_t)nb * sizeof *w);
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
    c.unstable = c.min_omega2 < -tol || c.max_growth > 0.0;
    double F = sp->stretch > 0.0 ? sp->stretch : 1.0;
    double cbar = (sp->disc.dim == 1 && sp->disc.frame == MFS_FRAME_LAGRANGIAN) ? F * F + sb
                                                                                : 1.0 + sb;
    if (cbar <= 0.0)
      c.labels |= MFS_LABEL_MATERIAL;
    if (c.unstable && cbar > 0.0)
      c.labels |= MFS_LABEL_TENSILE;
    if (nzero0 > 0)
      c.labels |= MFS_LABEL_RANK_DEFICIENCY;
    out[si] = c;
  }
  free(w);
  return st;
}

const char *mfs_class_label(unsigned labels, char *buf, size_t len)
{
  static const char *const names[] = {"material", "tensile", "rank-deficiency"};
  if (len == 0)
    return buf;
  buf[0] = '\0';
  for (int k = 0; k < 3; k++)
    if (labels & (1u << k)) {
      if (buf[0])
        strncat(buf, "+", len - strlen(buf) - 1);
      strncat(buf, names[k], len - strlen(buf) - 1);
    }
  if (!buf[0])
    strncat(buf, "stable", len - 1);
  return buf;
}
