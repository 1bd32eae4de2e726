/* Benchmark (not a test) of issue 15: a user's particle file, read, planned
 * and bounded; and the certified step against ARPACK.  One job per process,
 * so that the peak resident memory is that of the job:
 *
 *   bench_check gen SIDE FILE [--perturb F] [--novol]
 *       write a 2D particle file: a SIDE x SIDE lattice of the unit square,
 *       perturbed by F (default 0.2), with its volumes (the perturbed cells'
 *       dual) unless --novol
 *   bench_check gershgorin FILE A [--quadrature RULE] [--header]
 *       the phases of 'mfstab bound --particles FILE --support A' that the
 *       Gershgorin step needs, timed one by one: read (tools/particles_csv.c),
 *       geometry (mfs_particles_from_set, the quadrature; Qhull without
 *       volumes), plan (cell lists, shape table), dt_gershgorin (the rows of
 *       K streamed from the table); cubic MLS, nodal by default
 *       CSV: job,particles,quadrature,read_s,geometry_s,plan_s,gershgorin_s,total_s,
 *            total_cpu_s,lambda_gershgorin,dt_gershgorin,peak_rss_mb,read_cpu_s,
 *            geometry_cpu_s,plan_cpu_s,gershgorin_cpu_s (phases: wall clock, then the
 *            process's CPU time, user + system, the measure on a shared machine)
 *   bench_check certify SIDE [--perturb F] [--mass lumped|consistent] [--header]
 *                      [--certify-first]
 *       the perturbed SIDE x SIDE model (cubic MLS, D = 2, nodal, anti-plane,
 *       free): lambda_max by ARPACK at relative accuracy 1e-12 (what mfstab eigs
 *       does), against dt_certified the way mfstab bound --certify gets it
 *       (plain Lanczos at 1e-4 with a lumped mass, ARPACK at 1e-3 with a
 *       consistent one or with --arpack-estimate; then the factorizations of sigma M - K from
 *       sigma = lambda (1 + 4e-4), the gap 4 times larger after a failure;
 *       --est-tol T and --gap G change the two)
 *       (--quadrature RULE for another rule), ARPACK first unless --certify-first;
 *       the factorization ordered by the particles' coordinates as mfstab does
 *       (mfs_model_coords), or by CHOLMOD's AMD with --amd, or by the order
 *       --order default|geometric|amd|metis|nesdis asks for (mfs_certify_opts.order)
 *       CSV: job,particles,mass,quadrature,assembly_s,arpack_s,arpack_matvecs,lambda_max,
 *            certify_s,lanczos_s,factor_s,factorizations,factor_nnz,factor_gflops,
 *            sigma_certified,certified_fraction,time_ratio,cpu_ratio,peak_rss_mb
 *       time_ratio = certify_s / arpack_s (wall clock), cpu_ratio the same in CPU time;
 *       certified_fraction = sqrt(lambda_max / sigma) = dt_certified / dt_crit. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "cli.h"
#include "mfstab.h"
#include "particles_csv.h"

static double now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* CPU time of the process (user + system): the measure on a shared machine. */
static double cpu(void)
{
  struct timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double peak_mb(void)
{
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_maxrss / 1024.0;
}

static mfs_disc model_disc(int side, double perturb)
{
  mfs_disc d = mfs_disc_default();
  d.dim = 2;
  d.source = (mfs_source){.lattice = MFS_LATTICE_SQUARE, .nx = side, .ny = side, .lx = 1.0,
                          .ly = 1.0, .perturb = perturb, .seed = 1};
  return d;
}

static int gen(int side, const char *path, double perturb, int novol)
{
  mfs_disc d = model_disc(side, perturb);
  mfs_particles *p;
  mfs_quad *q;
  mfs_status st = mfs_disc_geometry(&d, &p, &q);
  if (st != MFS_OK) {
    fprintf(stderr, "bench_check gen: %s\n", mfs_strerror(st));
    return 1;
  }
  FILE *f = fopen(path, "w");
  if (!f)
    return 1;
  fputs(novol ? "x,y\n" : "x,y,volume\n", f);
  for (size_t I = 0; I < p->n; I++)
    if (novol)
      fprintf(f, "%.17g,%.17g\n", p->x[2 * I], p->x[2 * I + 1]);
    else
      fprintf(f, "%.17g,%.17g,%.17g\n", p->x[2 * I], p->x[2 * I + 1], p->vol[I]);
  fclose(f);
  mfs_quad_free(q);
  mfs_particles_free(p);
  return 0;
}

static int gershgorin(const char *path, double a, const char *rule, int header)
{
  double c0 = cpu(), t0 = now();
  particle_file pf;
  particle_file_read(&pf, path, 1e-10);
  double t1 = now(), c1 = cpu();
  int novol = pf.vol == NULL;
  particle_file_volumes(&pf); /* without volumes: Qhull, timed as geometry */
  mfs_disc d = mfs_disc_default();
  d.dim = pf.dim;
  d.source = (mfs_source){.lattice = MFS_LATTICE_POINTS, .points = &pf.set};
  d.support = a;
  d.quadrature = mfs_quad_find(rule);
  if (!d.quadrature)
    return 2;
  mfs_particles *p;
  mfs_quad *q;
  mfs_status st = mfs_disc_geometry(&d, &p, &q);
  if (st != MFS_OK) {
    fprintf(stderr, "bench_check: geometry: %s\n", mfs_strerror(st));
    return 1;
  }
  double t2 = now(), c2 = cpu();
  mfs_plan *pl = mfs_plan_alloc(&d, p, q, &st);
  if (!pl || mfs_plan_tabulate(pl, 1, NULL) != MFS_OK) {
    fprintf(stderr, "bench_check: plan: %s\n", mfs_strerror(st));
    return 1;
  }
  double t3 = now(), c3 = cpu();
  mfs_gershgorin_result g;
  st = mfs_gershgorin_plan(pl, &d.material, NULL, &g);
  double t4 = now(), c4 = cpu();
  if (st != MFS_OK)
    return 1;
  if (header)
    puts("job,particles,quadrature,read_s,geometry_s,plan_s,gershgorin_s,total_s,total_cpu_s,"
         "lambda_gershgorin,dt_gershgorin,peak_rss_mb,read_cpu_s,geometry_cpu_s,plan_cpu_s,"
         "gershgorin_cpu_s");
  printf("gershgorin%s,%zu,%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.10g,%.10g,%.1f,%.4f,%.4f,%.4f,%.4f\n",
         novol ? "_novol" : "", pf.n, rule, t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0, c4 - c0,
         g.lambda, mfs_dt_crit(g.lambda), peak_mb(), c1 - c0, c2 - c1, c3 - c2, c4 - c3);
  mfs_plan_free(pl);
  mfs_quad_free(q);
  mfs_particles_free(p);
  particle_file_free(&pf);
  return 0;
}

/* ARPACK's lambda_max at 1e-12: wall and CPU seconds into t[0], c[0]. */
static mfs_status arpack_full(const mfs_pencil *P, double *lam, int *mv, double *t, double *c)
{
  mfs_eig_info info;
  mfs_eig_opts full = {0, 0, 1e-12};
  double t0 = now(), c0 = cpu();
  mfs_status st = mfs_eig_max(P, &full, lam, NULL, &info);
  *t = now() - t0;
  *c = cpu() - c0;
  *mv = info.matvecs;
  return st;
}

static double est_tol = 1e-3, est_gap = 4e-4; /* mfstab bound --certify's */
static int arpack_est = 0;                      /* --arpack-estimate */

/* dt_certified as mfstab bound --certify gets it: the estimate by plain
 * Lanczos at 1e-4 with a lumped mass (ARPACK at est_tol with a consistent
 * one, or with --arpack-estimate), then the factorizations; t[0..2], c[0]:
 * total, estimate, factorizations (wall), total CPU. */

static mfs_status certified(const mfs_pencil *P, const double *x, int dim, int order,
                            mfs_certify_result *cr, double *t, double *c)
{
  double lan, t0 = now(), c0 = cpu();
  mfs_status st;
  if (P->m && !arpack_est) { /* a lumped mass: plain Lanczos at 1e-4 */
    mfs_lanczos_opts lo = {.tol = 1e-4};
    st = mfs_lanczos_max(P, &lo, &lan, NULL);
  } else {
    mfs_eig_info info;
    mfs_eig_opts quick = {0, 0, est_tol};
    st = mfs_eig_max(P, &quick, &lan, NULL, &info);
  }
  double t1 = now();
  mfs_certify_opts co = {.lambda_est = lan, .gap = est_gap, .growth = 4.0, .coord = x,
                         .coord_dim = x ? dim : 0, .order = order};
  if (st == MFS_OK)
    st = mfs_eig_certify_search(P, &co, cr);
  t[0] = now() - t0;
  t[1] = t1 - t0;
  t[2] = now() - t1;
  *c = cpu() - c0;
  return st;
}

static const char *const order_name[] = {"default", "geometric", "amd", "metis", "nesdis"};

static int certify(int side, double perturb, int consistent, const char *rule, int header,
                   int cert_first, int amd, int order)
{
  mfs_model_spec s = {.disc = model_disc(side, perturb)};
  s.disc.consistent_mass = consistent;
  s.disc.quadrature = mfs_quad_find(rule);
  if (!s.disc.quadrature)
    return 2;
  double t0 = now();
  mfs_status st;
  mfs_model *m = mfs_model_alloc(&s, &st, NULL);
  if (!m) {
    fprintf(stderr, "bench_check certify: %s\n", mfs_strerror(st));
    return 1;
  }
  mfs_model_release_plan(m);
  double t1 = now();
  mfs_pencil P = {m->K, m->M, m->m};
  mfs_certify_result cr;
  double *x = amd ? NULL : mfs_model_coords(m); /* mfstab bound --certify passes them */
  if (!amd && !x)
    return 1;
  double lam = 0.0, ta = 0.0, ca = 0.0, tc[3] = {0, 0, 0}, cc = 0.0;
  int mv = 0;
  /* both on the same model in one process, in the order asked (the script alternates it) */
  if (cert_first) {
    st = certified(&P, x, m->p->dim, order, &cr, tc, &cc);
    if (st == MFS_OK)
      st = arpack_full(&P, &lam, &mv, &ta, &ca);
  } else {
    st = arpack_full(&P, &lam, &mv, &ta, &ca);
    if (st == MFS_OK)
      st = certified(&P, x, m->p->dim, order, &cr, tc, &cc);
  }
  mfs_free(x);
  if (st != MFS_OK || !cr.ok)
    return 1;
  if (header)
    puts("job,particles,mass,quadrature,assembly_s,arpack_s,arpack_matvecs,lambda_max,certify_s,"
         "lanczos_s,factor_s,factorizations,factor_nnz,factor_gflops,sigma_certified,certified_fraction,"
         "time_ratio,cpu_ratio,peak_rss_mb,arpack_cpu_s,certify_cpu_s,certify_first,order_s,"
         "analyze_s,numeric_s,supernodes,order,threads");
  printf("certify,%zu,%s,%s,%.4f,%.4f,%d,%.12g,%.4f,%.4f,%.4f,%d,%.0f,%.3f,%.12g,%.8f,%.4f,%.4f,"
         "%.1f,%.4f,%.4f,%d,%.4f,%.4f,%.4f,%d,%s,%s\n",
         m->p->n, consistent ? "consistent" : "lumped", s.disc.quadrature->name, t1 - t0, ta, mv,
         lam, tc[0], tc[1], tc[2], cr.factorizations, cr.factor_nnz, cr.flops * 1e-9,
         cr.lambda_upper, sqrt(lam / cr.lambda_upper), tc[0] / ta, cc / ca, peak_mb(), ca, cc,
         cert_first, cr.order_s, cr.analyze_s, cr.numeric_s, cr.supernodes, order_name[order],
         getenv("OMP_NUM_THREADS") ? getenv("OMP_NUM_THREADS") : "");
  mfs_model_free(m);
  return 0;
}

int main(int argc, char **argv)
{
  cli_command = "bench_check";
  if (argc < 3) {
    fprintf(stderr, "usage: bench_check gen SIDE FILE | gershgorin FILE A | certify SIDE\n");
    return 2;
  }
  double perturb = 0.2;
  int novol = 0, header = 0, consistent = 0, cert_first = 0, amd = 0, order = 0;
  const char *rule = "nodal";
  for (int i = 3; i < argc; i++) {
    if (strcmp(argv[i], "--perturb") == 0 && i + 1 < argc)
      perturb = atof(argv[++i]);
    else if (strcmp(argv[i], "--novol") == 0)
      novol = 1;
    else if (strcmp(argv[i], "--header") == 0)
      header = 1;
    else if (strcmp(argv[i], "--certify-first") == 0)
      cert_first = 1;
    else if (strcmp(argv[i], "--amd") == 0)
      amd = 1;
    else if (strcmp(argv[i], "--arpack-estimate") == 0)
      arpack_est = 1;
    else if (strcmp(argv[i], "--est-tol") == 0 && i + 1 < argc)
      est_tol = atof(argv[++i]);
    else if (strcmp(argv[i], "--gap") == 0 && i + 1 < argc)
      est_gap = atof(argv[++i]);
    else if (strcmp(argv[i], "--order") == 0 && i + 1 < argc) {
      const char *o = argv[++i];
      order = -1;
      for (int k = 0; k < 5; k++)
        if (strcmp(o, order_name[k]) == 0)
          order = k;
      if (order < 0) {
        fprintf(stderr, "bench_check: --order %s: not default, geometric, amd, metis, nesdis\n", o);
        return 2;
      }
      amd = order >= MFS_CERT_ORDER_AMD;
    }
    else if (strcmp(argv[i], "--quadrature") == 0 && i + 1 < argc)
      rule = argv[++i];
    else if (strcmp(argv[i], "--mass") == 0 && i + 1 < argc)
      consistent = strcmp(argv[++i], "consistent") == 0;
  }
  if (strcmp(argv[1], "gen") == 0 && argc >= 4)
    return gen(atoi(argv[2]), argv[3], perturb, novol);
  if (strcmp(argv[1], "gershgorin") == 0 && argc >= 4)
    return gershgorin(argv[2], atof(argv[3]), rule, header);
  if (strcmp(argv[1], "certify") == 0)
    return certify(atoi(argv[2]), perturb, consistent, rule, header, cert_first, amd, order);
  fprintf(stderr, "bench_check: unknown job %s\n", argv[1]);
  return 2;
}
