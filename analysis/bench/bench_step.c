/* Benchmark of the step rules of the reference solvers (issue 14 item 5):
 * the time to choose the stable step dt_crit with each rule of mfs_dt_rule
 * (mfs_explicit.h) on a solver already built, side by side: in each of the
 * repetitions the three rules run one after the other (power, gershgorin,
 * certified), so that a change of the machine's load falls on all three.
 *
 * Scenes: the rod (mfs_solver.h: 1D, MLS quartic, D = 2, nodal, Lagrangian,
 * fixed ends, E = rho = 1, S0 = 0.3) and the plane-strain plate
 * (mfs_solver2d.h: periodic square lattice, MLS cubic, D = 2, nodal, mu = 1,
 * nu = 0.25) at the particle counts given.
 *
 * Columns: scene, rule (the one used), particles, dofs, reps, seconds_min,
 * seconds_median, seconds_max (wall time of mfs_solver[2d]_choose_step with
 * nothing cached), lambda_per_s2 (the lambda dt_crit uses), lambda_ratio (to
 * the ARPACK lambda_max of the certified run, at MFS_DT_ARPACK_TOL), proven,
 * time_ratio_power (median / the power rule's median), arpack_tol (certified
 * only), load_1min (the 1-minute load average of /proc/loadavg, the largest
 * seen during the scene's rows: the machine is shared), peak_rss_mb, nnz_K
 * (the stored entries of K on the free degrees of freedom, the operator the
 * rules bound: the plate's model->K; the rod's rules work from the plan
 * without K, so its K(Cbar) is assembled once outside the timing, by an
 * mfs_model of the same discretization with the ends fixed, only to count
 * them: analysis/bench/limits.py's limit of the row).  Not a test: nothing
 * here asserts a time.
 *
 * The certified rule on the rod is slow: its top eigenvalues cluster (the
 * sawtooth's neighbours lie within (pi/N)^2 of it) and ARPACK needs many
 * restarts to reach MFS_DT_ARPACK_TOL; above --certified-max particles (default
 * 20000) the rod's certified row is not run (no row written).
 *
 * Usage: bench_step [-o FILE] [--reps R] [--certified-max N] N...
 * (default N: 10000 100000; R 5) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "mfs_solver.h"
#include "mfs_solver2d.h"
#include "mfstab.h"

enum { NRULE = 3, MAXREP = 50 };
static const mfs_dt_rule order[NRULE] = {MFS_DT_POWER, MFS_DT_GERSHGORIN, MFS_DT_CERTIFIED};

/* One solver of either kind. */
typedef struct {
  mfs_solver *rod;
  mfs_solver2d *plate;
} solver;

/* Choose the step by rule with nothing cached (the cache of s->step is
 * cleared: a benchmark-only reach into the read-only field, so that each
 * repetition does the whole work). */
static mfs_status choose(solver *s, mfs_dt_rule r, mfs_dt_info *info)
{
  mfs_dt_info *step = s->rod ? &s->rod->step : &s->plate->step;
  *step = mfs_dt_info_init(r);
  step->requested = (mfs_dt_rule)-1;
  mfs_status st = s->rod ? mfs_solver_choose_step(s->rod, r) : mfs_solver2d_choose_step(s->plate, r);
  *info = *step;
  return st;
}

static int certified_max = 20000;

/* The stored entries of the rod's K(Cbar) on the free particles: an
 * mfs_model of the same discretization, ends fixed (0 on failure). */
static size_t rod_nnz(const mfs_disc *d)
{
  mfs_model_spec ms = mfs_model_spec_default();
  ms.disc = *d;
  ms.disc.material.modulus += ms.disc.material.initial_stress;
  ms.disc.material.initial_stress = 0.0;
  ms.fixed = MFS_FIX_ENDS;
  mfs_status st;
  mfs_model *md = mfs_model_alloc(&ms, &st, NULL);
  size_t nnz = md ? md->K->ptr[md->K->nrow] : 0;
  mfs_model_free(md);
  return nnz;
}

static mfs_status scene(FILE *f, int plate, int n, int reps)
{
  solver s = {0};
  mfs_status st;
  size_t dofs, nnz;
  if (plate) {
    int m = (int)lround(sqrt((double)n));
    mfs_model_spec sp = mfs_model_spec_default();
    mfs_disc *d = &sp.disc;
    d->dim = 2;
    d->source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .nx = m, .ny = m, .lx = 0.01 * m,
                             .ly = 0.01 * m, .periodic = 1};
    d->kernel = &mfs_kernel_cubic;
    d->shape = &mfs_shape_mls;
    d->dilation = 2.0;
    d->quadrature = mfs_quad_find("nodal");
    d->material = (mfs_material){.physics = MFS_PHYS_PLANE_STRAIN, .modulus = 1.0, .density = 1.0,
                                 .poisson = 0.25};
    if (!(s.plate = mfs_solver2d_alloc(&sp, &st, NULL)))
      return st;
    n = m * m;
    dofs = s.plate->n;
    nnz = s.plate->model->K->ptr[s.plate->model->K->nrow];
  } else {
    mfs_disc d = mfs_disc_default();
    d.source = (mfs_source){.lattice = MFS_LATTICE_LINE, .nx = n, .lx = 1.0};
    d.kernel = &mfs_kernel_quartic;
    d.dilation = 2.0;
    d.material = (mfs_material){.physics = MFS_PHYS_SCALAR, .modulus = 1.0, .density = 1.0,
                                .initial_stress = 0.3};
    mfs_solver_spec sp = {.disc = d,
                          .bc = {MFS_BC_FIXED, MFS_BC_FIXED},
                          .bc_until = {INFINITY, INFINITY},
                          .equilibrate = 1};
    if (!(s.rod = mfs_solver_alloc(&sp, &st, NULL)))
      return st;
    dofs = s.rod->n - 2;
    nnz = rod_nnz(&d);
  }
  double sec[NRULE][MAXREP], load = bench_load1();
  mfs_dt_info info[NRULE];
  int nrule = !plate && n > certified_max ? NRULE - 1 : NRULE; /* the certified rule last */
  st = MFS_OK;
  for (int k = 0; k < reps && st == MFS_OK; k++)
    for (int r = 0; r < nrule && st == MFS_OK; r++) {
      double t0 = bench_now();
      st = choose(&s, order[r], &info[r]);
      sec[r][k] = bench_now() - t0;
      load = fmax(load, bench_load1());
    }
  if (st == MFS_OK) {
    double med[NRULE];
    for (int r = 0; r < nrule; r++) {
      qsort(sec[r], (size_t)reps, sizeof sec[r][0], bench_cmp_double);
      med[r] = reps % 2 ? sec[r][reps / 2] : 0.5 * (sec[r][reps / 2 - 1] + sec[r][reps / 2]);
    }
    /* the reference lambda_max: the certified run's ARPACK value, or without one the
     * Gershgorin bound's own (the ratio column is then empty) */
    double lref = nrule == NRULE ? info[2].lambda_arpack : NAN;
    for (int r = 0; r < nrule; r++) {
      fprintf(f, "%s,%s,%d,%zu,%d,%.6g,%.6g,%.6g,%.10g,", plate ? "plate" : "rod",
              mfs_dt_rule_name(info[r].used), n, dofs, reps, sec[r][0], med[r], sec[r][reps - 1],
              info[r].lambda);
      if (!isnan(lref))
        fprintf(f, "%.7f", info[r].lambda / lref);
      fprintf(f, ",%d,%.4g,", info[r].proven, med[r] / med[0]);
      if (info[r].arpack_tol > 0.0)
        fprintf(f, "%g", info[r].arpack_tol);
      fprintf(f, ",%.2f,%.1f,", load, bench_peak_mb());
      if (nnz)
        fprintf(f, "%zu", nnz);
      fputc('\n', f);
    }
    fflush(f);
  }
  mfs_solver_free(s.rod);
  mfs_solver2d_free(s.plate);
  return st;
}

int main(int argc, char **argv)
{
  const char *out = NULL;
  int reps = 5, ns[16], nn = 0;
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "-o") && i + 1 < argc)
      out = argv[++i];
    else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = atoi(argv[++i]);
    else if (!strcmp(argv[i], "--certified-max") && i + 1 < argc)
      certified_max = atoi(argv[++i]);
    else if (nn < 16)
      ns[nn++] = atoi(argv[i]);
  }
  if (nn == 0) {
    ns[nn++] = 10000;
    ns[nn++] = 100000;
  }
  if (reps < 1 || reps > MAXREP) {
    fprintf(stderr, "bench_step: --reps %d: allowed 1 to %d\n", reps, MAXREP);
    return 2;
  }
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!f) {
    perror(out);
    return 1;
  }
  fputs("scene,rule,particles,dofs,reps,seconds_min,seconds_median,seconds_max,lambda_per_s2,"
        "lambda_ratio,proven,time_ratio_power,arpack_tol,load_1min,peak_rss_mb,nnz_K\n",
        f);
  mfs_status st = MFS_OK;
  for (int plate = 0; plate < 2 && st == MFS_OK; plate++)
    for (int i = 0; i < nn && st == MFS_OK; i++)
      st = scene(f, plate, ns[i], reps);
  if (out)
    fclose(f);
  if (st != MFS_OK) {
    fprintf(stderr, "bench_step: %s\n", mfs_strerror(st));
    return 1;
  }
  return 0;
}
