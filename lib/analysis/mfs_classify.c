#include "mfs_classify.h"
#include "mfs_alloc.h"
#include "mfs_omp.h"

#include <complex.h>
#undef I
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The sweeps run in parallel (OpenMP) over fixed chunks of CHUNK samples of
 * every ray; each sample is computed on its own (mfs_disp_ray) and the
 * chunks' minima and maxima are combined in chunk order, so the results are
 * the same bits for any number of threads. */

enum { CHUNK = 64 };

/* The kappa of sample i on a ray with kappa_max km. */
static double sample(const mfs_sampling *smp, double km, size_t i)
{
  return smp->kappa ? smp->kappa[i] : km * (double)i / (double)(smp->npoints - 1);
}

static size_t nsamples(const mfs_sampling *smp)
{
  return smp->kappa ? smp->nkappa : (size_t)smp->npoints;
}

/* The smallest real part (want_max 0) or the largest modulus (1) of omega^2
 * at sbar over the rays of smp, at kappa_max * i / npts for i = i0 .. npts,
 * points that fail skipped (their values are NaN).  red holds a value per
 * chunk (ntheta ceil((npts - i0 + 1) / CHUNK)). */
static double extreme(const mfs_disp_plan *pl, double sbar, const mfs_sampling *smp, int i0,
                      int npts, int want_max, double *red)
{
  const int nb = mfs_disp_branches(pl);
  const long nper = (long)(npts - i0 + 1), nch = (nper + CHUNK - 1) / CHUNK;
  const long ntask = (long)smp->ntheta * nch;
  MFS_OMP("omp parallel for schedule(static) if (ntask > 1)")
  for (long task = 0; task < ntask; task++) {
    const size_t t = (size_t)(task / nch);
    const long c0 = (task % nch) * CHUNK, len = nper - c0 < CHUNK ? nper - c0 : CHUNK;
    const double km = mfs_disp_kappa_max(pl, smp->theta[t]);
    double kap[CHUNK], m = want_max ? 0.0 : INFINITY;
    double complex buf[CHUNK * 4];
    for (long i = 0; i < len; i++)
      kap[i] = km * (double)(i0 + c0 + i) / npts;
    if (mfs_disp_ray(pl, &sbar, 1, smp->theta[t], kap, (size_t)len, buf, 0) != MFS_EINVAL)
      for (long i = 0; i < len * nb; i++) {
        double v = want_max ? cabs(buf[i]) : creal(buf[i]);
        if (want_max ? v > m : v < m)
          m = v;
      }
    red[task] = m;
  }
  double m = want_max ? 0.0 : INFINITY;
  for (long task = 0; task < ntask; task++)
    if (want_max ? red[task] > m : red[task] < m)
      m = red[task];
  return m;
}

/* Smallest real part of omega^2 over the sampled kappa of all rays
 * (npts uniform samples in (0, kappa_max]). */
static double min_omega2(const mfs_disp_plan *pl, double sbar, const mfs_sampling *smp, int npts,
                         double *red)
{
  return extreme(pl, sbar, smp, 1, npts, 0, red);
}

/* Smallest |sbar| in the direction sign (+1 tension, -1 compression) at
 * which some omega^2 < -tol; NAN if none up to the limit. */
static double onset(const mfs_disp_plan *pl, int sign, const mfs_sampling *smp, int npts,
                    double tol, double *red)
{
  double lo = 0.0, hi = sign > 0 ? 10.0 : 1.0 + 1e-9;
  mfs_plane_state ps;
  if (mfs_disp_plan_spec(pl)->disc.material.physics == MFS_PHYS_PLANE_STRAIN &&
      mfs_disp_state(pl, sign * hi, &ps) != MFS_OK)
    return NAN; /* a finite material: the state is the plan's */
  if (min_omega2(pl, sign * hi, smp, npts, red) >= -tol)
    return NAN;
  if (min_omega2(pl, 0.0, smp, npts, red) < -tol)
    return 0.0;
  for (int it = 0; it < 50; it++) {
    double mid = 0.5 * (lo + hi);
    if (min_omega2(pl, sign * mid, smp, npts, red) < -tol)
      hi = mid;
    else
      lo = mid;
  }
  return sign * hi;
}

/* omega^2 at every sample of ray t at sbar into w (nk nb), in parallel over
 * chunks; MFS_OK or the status of the first failing sample. */
static mfs_status ray_samples(const mfs_disp_plan *pl, double sbar, const mfs_sampling *smp,
                              size_t t, double complex *w, mfs_status *cst)
{
  const int nb = mfs_disp_branches(pl);
  const long nk = (long)nsamples(smp), nch = (nk + CHUNK - 1) / CHUNK;
  const double th = smp->theta[t], km = mfs_disp_kappa_max(pl, th);
  MFS_OMP("omp parallel for schedule(static) if (nch > 1)")
  for (long c = 0; c < nch; c++) {
    const long c0 = c * CHUNK, len = nk - c0 < CHUNK ? nk - c0 : CHUNK;
    double kap[CHUNK];
    for (long i = 0; i < len; i++)
      kap[i] = sample(smp, km, (size_t)(c0 + i));
    cst[c] = mfs_disp_ray(pl, &sbar, 1, th, kap, (size_t)len, w + c0 * nb, 0);
  }
  for (long c = 0; c < nch; c++)
    if (cst[c] != MFS_OK)
      return cst[c];
  return MFS_OK;
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
  /* a chunk's extreme per (ray, chunk) of the sweeps, the statuses of a ray's chunks */
  size_t nred = smp->ntheta * ((size_t)(nk > 201 ? nk : 201) / CHUNK + 1);
  double complex *w = mfs_malloc((size_t)nk * (size_t)nb * sizeof *w);
  double *red = mfs_malloc(nred * sizeof *red);
  mfs_status *cst = mfs_malloc(((size_t)nk / CHUNK + 1) * sizeof *cst);
  mfs_status st = MFS_ENOMEM;
  if (!w || !red || !cst)
    goto done;
  st = MFS_OK;
  /* the scale: the largest |omega^2| at sbar = 0 (201 samples per ray), for relative zero tests */
  double scale = extreme(pl, 0.0, &(mfs_sampling){.theta = smp->theta, .ntheta = smp->ntheta}, 0,
                         200, 1, red);
  const double tol = 1e-10 * scale;
  /* the worst samples' place: a later sample replaces the one kept only if
   * it is beyond it by more than 1e-12 of the scale, so that samples equal
   * but for rounding (mirror images, zeros of the rounding's size) give the
   * same place whatever the rounding of the machine and the build (the
   * extremes themselves are exact) */
  const double tie = 1e-12 * scale, tie_g = 1e-12 * sqrt(scale);
  double onset_t = onset(pl, +1, smp, nk, tol, red);
  double onset_c = onset(pl, -1, smp, nk, tol, red);
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
    double at_min = INFINITY, at_growth = 0.0; /* the values at the places kept */
    for (size_t t = 0; t < smp->ntheta && st == MFS_OK; t++) {
      double th = smp->theta[t], km = mfs_disp_kappa_max(pl, th);
      st = ray_samples(pl, sb, smp, t, w, cst);
      for (int i = 0; i < nk && st == MFS_OK; i++) {
        double kap = sample(smp, km, (size_t)i), kv[2];
        wave_vector(pl, kap, th, kv);
        for (int b = 0; b < nb; b++) {
          double complex w2 = w[(size_t)i * nb + b], wr = csqrt(w2);
          double re = creal(w2), g = fabs(cimag(wr));
          c.min_omega2 = re < c.min_omega2 ? re : c.min_omega2;
          if (re < at_min - tie) {
            at_min = re;
            c.kappa_at_min = kap;
            c.theta_at_min = (int)t;
          }
          if (re < -tol || g > sqrt(tol)) {
            c.unstable_kappa_from =
              isnan(c.unstable_kappa_from) || kap < c.unstable_kappa_from ? kap
                                                                          : c.unstable_kappa_from;
            c.unstable_kappa_to =
              isnan(c.unstable_kappa_to) || kap > c.unstable_kappa_to ? kap : c.unstable_kappa_to;
            c.max_growth = g > c.max_growth ? g : c.max_growth;
            if (g > at_growth + tie_g) {
              at_growth = g;
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
        st = ray_samples(pl, 0.0, smp, t, w, cst);
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
done:
  mfs_free(w);
  mfs_free(red);
  mfs_free(cst);
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
