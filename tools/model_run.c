#include "model_run.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* Die with a clear line for a failed eigenvalue computation. */
static _Noreturn void die_eig(int st, const mfs_eig_info *info, const char *what)
{
  if (st == MFS_ENOCONV)
    cli_die(1,
            "%s: ARPACK %s did not converge (info %d) after %d iterations, %d Ritz values "
            "converged; raise --maxiter or --ncv, or loosen --arpack-tol",
            what, info->routine, info->info, info->iterations, info->nconv);
  if (st == MFS_EARPACK)
    cli_die(1, "%s: ARPACK %s failed with info %d", what, info->routine, info->info);
  if (st == MFS_EDOMAIN && strcmp(info->routine, "cholmod") == 0)
    cli_die(1, "%s: CHOLMOD: the matrix to factor is not positive definite (status %d)", what,
            info->cholmod_status);
  cli_die(1, "%s: %s", what, mfs_strerror(st));
}

void model_rules(const model_cmd *c, double *dt)
{
  const mfs_disc *d = &c->s.disc;
  double a = mfs_disc_support(d);
  const mfs_convention *cv = c->m.convention;
  for (int k = 0; mfs_step_rules[k] && k < RUN_MAX_RULES; k++) {
    const mfs_step_rule *rule = mfs_step_rules[k];
    mfs_rule_args args = {.dim = d->dim,
                          .h = mfs_rule_h(rule, cv, a),
                          .young = c->young,
                          .poisson = c->poisson,
                          .density = d->material.density};
    /* --rule-factor: the convention's own rule (not the peer's variants) */
    double f = cv && rule == cv->rule && c->m.rule_factor > 0.0 ? c->m.rule_factor : 0.0;
    dt[k] = mfs_rule_dt(rule, &args, f);
  }
}

void rules_header(FILE *f)
{
  for (int k = 0; mfs_step_rules[k]; k++)
    fprintf(f, ",dt_rule_%s_s,dt_rule_%s_unsafe", mfs_step_rules[k]->name, mfs_step_rules[k]->name);
}

void rules_row(FILE *f, const double *dt, double safe_below, double unsafe_above, int last)
{
  for (int k = 0; mfs_step_rules[k]; k++) {
    eigs_put(f, dt[k], 0);
    int end = last && !mfs_step_rules[k + 1];
    if (!isnan(dt[k]) && !isnan(unsafe_above) && dt[k] > unsafe_above)
      fputc('1', f);
    else if (!isnan(dt[k]) && !isnan(safe_below) && dt[k] <= safe_below)
      fputc('0', f);
    fputc(end ? '\n' : ',', f);
  }
}

void run_take_lambda(run_result *r, const mfs_eig_info *info)
{
  if (!(r->lambda > 0.0))
    cli_die(1, "lambda_max = %g: the stiffness has no positive eigenvalue", r->lambda);
  r->have_lambda = 1;
  r->iters = info->iterations;
  r->matvecs = info->matvecs;
  r->resid = info->residual;
}

void model_run(const model_cmd *c, const run_opts *o, run_result *r)
{
  if (o->distributed) {
    model_prun(c, o, r);
    return;
  }
  memset(r, 0, sizeof *r);
  const mfs_model_spec *s = &c->s;
  const mfs_disc *d = &s->disc;
  eigs_derive(s, &r->dv);
  mfs_status st;
  size_t bad = 0;
  mfs_model *m = mfs_model_alloc(s, &st, &bad);
  if (!m) {
    if (st == MFS_EINVAL && s->fixed != MFS_FIX_NONE)
      cli_die(2, "--fix%s: every particle is fixed; nothing is left to move",
              s->fixed == MFS_FIX_MASK ? "" : "ed");
    model_die_status(c, st, bad, "at a quadrature point of the model");
  }
  r->m = m;
  r->particles = m->p->n;
  r->dofs = m->n;
  st = mfs_bound_of_model(m, &r->br);
  if (st != MFS_OK)
    cli_die(1, "element bound: %s", mfs_strerror(st));
  mfs_model_release_plan(m);
  r->bound_valid = !d->consistent_mass && r->br.negative_phi == 0;
  if (m->n < 2)
    cli_die(2, "the model has %zu free degree of freedom; use more particles", m->n);

  /* lumped masses and the Gershgorin bound */
  r->min_mass = NAN;
  r->masses_ok = 1;
  if (m->m) {
    mfs_gershgorin_csr(m->K, m->m, m->dof, &r->g);
    r->nonpositive = r->g.nonpositive;
    r->min_mass = r->g.min_mass;
    r->min_mass_particle = r->g.argmin_mass / (size_t)m->ndof;
    r->min_mass_x[0] = m->p->x[r->min_mass_particle * (size_t)m->p->dim];
    r->min_mass_x[1] = m->p->dim == 2 ? m->p->x[r->min_mass_particle * 2 + 1] : NAN;
    r->masses_ok = r->nonpositive == 0;
  } else {
    r->g = (mfs_gershgorin_result){.lambda = NAN};
  }
  st = mfs_bound_fourier(s, (int)c->m.fourier_points, (int)c->m.fourier_angles, &r->lf, &r->kf,
                         &r->tf);
  if (st != MFS_OK)
    model_die_status(c, st, 0, "Fourier estimate on the uniform lattice");
  model_rules(c, r->dt_rule);
  if (!r->masses_ok)
    goto done; /* nothing that needs positive masses applies */

  mfs_pencil P = {m->K, m->M, m->m};
  mfs_eig_opts eo = {(int)o->ncv, (int)o->maxiter, o->arpack_tol};
  mfs_eig_info info;
  if (o->keep) {
    r->vmax = mfs_malloc(m->n * sizeof *r->vmax);
    if (!r->vmax)
      cli_die(1, "out of memory");
  }
  mfs_eig_opts emax = eo;
  if (o->lambda_tol > 0.0)
    emax.tol = o->lambda_tol;
  st = mfs_eig_max(&P, &emax, &r->lambda, r->vmax, &info);
  if (st != MFS_OK)
    die_eig(st, &info, "lambda_max");
  run_take_lambda(r, &info);

  if (o->zero_modes) {
    mfs_zero_opts zo = {o->tol, (int)o->nev, 0, o->keep};
    mfs_eig_info zinfo = {0};
    st = mfs_eig_zero_modes(&P, r->lambda, &zo, &eo, &r->z, &zinfo);
    if (st != MFS_OK)
      die_eig(st, &zinfo, "zero-energy modes");
    r->have_zero = 1;
    r->zero_runs = zinfo.runs;
    int nr = mfs_model_rigid_fields(m, NULL);
    if (nr > 0) {
      double *rf = mfs_malloc((size_t)nr * m->n * sizeof *rf);
      if (!rf)
        cli_die(1, "out of memory");
      mfs_model_rigid_fields(m, rf);
      for (int k = 0; k < nr; k++) {
        int null;
        if (mfs_eig_is_null(&P, rf + (size_t)k * m->n, r->lambda, o->tol, &null) != MFS_OK) {
          mfs_free(rf);
          cli_die(1, "zero-energy modes: out of memory");
        }
        r->rigid += null;
      }
      mfs_free(rf);
    }
  }
  if (o->certify) {
    /* from the Lanczos value: it lies below lambda_max by about the ARPACK tolerance */
    double tol = o->lambda_tol > 0.0 ? o->lambda_tol : o->arpack_tol > 0.0 ? o->arpack_tol : 1e-15;
    double *x = mfs_model_coords(m); /* the factorization ordered by the particles' positions */
    if (!x)
      cli_die(1, "certification: out of memory");
    mfs_certify_opts co = {.lambda_est = r->lambda, .gap = fmax(1e-6, 4.0 * tol), .coord = x,
                           .coord_dim = m->p->dim};
    st = mfs_eig_certify_search(&P, &co, &r->cr);
    mfs_free(x);
    if (st != MFS_OK)
      cli_die(1, "certification: %s", mfs_strerror(st));
    r->have_cert = 1;
  }
done:
  if (!o->keep) {
    mfs_model_free(m);
    r->m = NULL;
  }
}

void run_result_free(run_result *r)
{
  mfs_model_free(r->m);
  mfs_free(r->vmax);
  mfs_free(r->z.modes);
  memset(r, 0, sizeof *r);
}

/* ------------------------------------------------------------------ */
/* modes                                                                */

unsigned char *model_boundary_layer(const mfs_model *m)
{
  const mfs_particles *p = m->p;
  size_t n = p->n, nb = 0;
  unsigned char *layer = mfs_calloc(n ? n : 1, 1);
  if (!layer)
    cli_die(1, "out of memory");
  for (size_t I = 0; I < n; I++)
    nb += p->flags[I] != 0;
  if (nb == 0 || p->box.periodic)
    return layer;
  double *xb = mfs_malloc(nb * (size_t)p->dim * sizeof *xb);
  if (!xb)
    cli_die(1, "out of memory");
  size_t k = 0;
  for (size_t I = 0; I < n; I++)
    if (p->flags[I])
      memcpy(xb + (k++) * (size_t)p->dim, p->x + I * (size_t)p->dim, (size_t)p->dim * sizeof *xb);
  /* the particles within a of a boundary particle: cell lists over the boundary particles */
  mfs_status st;
  mfs_box box = p->box;
  mfs_grid *g = mfs_grid_alloc(p->dim, nb, xb, &box, m->a, &st);
  mfs_nlist *nl = g ? mfs_nlist_build(g, n, p->x, m->a, &st) : NULL;
  if (!nl)
    cli_die(1, "boundary layer: %s", mfs_strerror(st));
  for (size_t I = 0; I < n; I++)
    layer[I] = nl->ptr[I + 1] > nl->ptr[I];
  mfs_nlist_free(nl);
  mfs_grid_free(g);
  mfs_free(xb);
  return layer;
}

void mode_describe(const mfs_model *m, const unsigned char *layer, const double *u, mode_info *mi)
{
  const mfs_particles *p = m->p;
  size_t np = p->n;
  double *a2 = mfs_calloc(np ? np : 1, sizeof *a2);
  if (!a2)
    cli_die(1, "out of memory");
  for (size_t i = 0; i < m->n; i++)
    a2[m->dof[i] / (size_t)m->ndof] += u[i] * u[i];
  double s2 = 0.0, s4 = 0.0, e = 0.0, eb = 0.0, v = 0.0, vb = 0.0, peak = -1.0;
  size_t nfree = 0;
  mi->peak_particle = 0;
  for (size_t I = 0; I < np; I++) {
    if (m->fixed[I])
      continue;
    nfree++;
    s2 += a2[I];
    s4 += a2[I] * a2[I];
    e += p->vol[I] * a2[I];
    v += p->vol[I];
    if (layer[I]) {
      eb += p->vol[I] * a2[I];
      vb += p->vol[I];
    }
    if (a2[I] > peak) {
      peak = a2[I];
      mi->peak_particle = I;
    }
  }
  mfs_free(a2);
  mi->participation = s4 > 0.0 ? s2 * s2 / ((double)nfree * s4) : NAN;
  mi->boundary_share = e > 0.0 ? eb / e : NAN;
  mi->layer_share = v > 0.0 ? vb / v : NAN;
  mi->location = mi->boundary_share > 0.5 && mi->boundary_share > mi->layer_share ? "boundary"
                                                                                   : "interior";
}

static void mass_apply(const mfs_model *m, const double *x, double *y)
{
  if (m->M)
    mfs_csr_matvec(m->M, x, y);
  else
    for (size_t i = 0; i < m->n; i++)
      y[i] = m->m[i] * x[i];
}

static double dotn(size_t n, const double *a, const double *b)
{
  double s = 0.0;
  for (size_t i = 0; i < n; i++)
    s += a[i] * b[i];
  return s;
}

/* M-orthogonalize b against the k vectors B (with MB = M B), twice, and
 * normalize; 0 if b lies in their span (its norm drops below 1e-6 of what it was). */
static int orth_append(const mfs_model *m, double *B, double *MB, int k, const double *b)
{
  size_t n = m->n;
  double *x = B + (size_t)k * n, *mx = MB + (size_t)k * n;
  memcpy(x, b, n * sizeof *x);
  mass_apply(m, x, mx);
  double n0 = sqrt(fabs(dotn(n, x, mx)));
  for (int pass = 0; pass < 2; pass++)
    for (int q = 0; q < k; q++) {
      double c = dotn(n, MB + (size_t)q * n, x);
      for (size_t i = 0; i < n; i++)
        x[i] -= c * B[(size_t)q * n + i];
    }
  mass_apply(m, x, mx);
  double nrm = sqrt(fabs(dotn(n, x, mx)));
  if (!(nrm > 1e-6 * n0))
    return 0;
  for (size_t i = 0; i < n; i++) {
    x[i] /= nrm;
    mx[i] /= nrm;
  }
  return 1;
}

double *model_spurious_modes(const mfs_model *m, const run_result *r, int *count)
{
  *count = 0;
  if (!r->have_zero || r->z.count <= r->rigid || !r->z.modes)
    return NULL;
  size_t n = m->n;
  int nz = r->z.count, nr = mfs_model_rigid_fields(m, NULL);
  double *B = mfs_malloc((size_t)(nr + nz) * n * sizeof *B), *MB = mfs_malloc((size_t)(nr + nz) * n * sizeof *MB);
  double *R = nr ? mfs_malloc((size_t)nr * n * sizeof *R) : NULL;
  if (!B || !MB || (nr && !R))
    cli_die(1, "out of memory");
  mfs_pencil P = {m->K, m->M, m->m};
  int k = 0;
  if (nr > 0) { /* the rigid fields that are null vectors first */
    mfs_model_rigid_fields(m, R);
    for (int t = 0; t < nr; t++) {
      int null;
      if (mfs_eig_is_null(&P, R + (size_t)t * n, r->lambda, 1e-8, &null) != MFS_OK)
        cli_die(1, "zero-energy modes: out of memory");
      if (null)
        k += orth_append(m, B, MB, k, R + (size_t)t * n);
    }
  }
  int k0 = k;
  for (int t = 0; t < nz; t++)
    k += orth_append(m, B, MB, k, r->z.modes + (size_t)t * n);
  mfs_free(R);
  mfs_free(MB);
  *count = k - k0;
  if (*count == 0) {
    mfs_free(B);
    return NULL;
  }
  memmove(B, B + (size_t)k0 * n, (size_t)*count * n * sizeof *B);
  return B;
}

/* The displacement of particle I in mode u (the fixed ones: 0). */
static void particle_u(const mfs_model *m, const long *where, const double *u, size_t I,
                       double *ui)
{
  for (int k = 0; k < m->ndof; k++) {
    long f = where[I * (size_t)m->ndof + (size_t)k];
    ui[k] = f >= 0 ? u[f] : 0.0;
  }
}

void write_modes(const model_cmd *c, const run_result *r, const char *prefix)
{
  const mfs_model *m = r->m;
  if (!m || !r->have_lambda) {
    fprintf(stderr, "mfstab %s: note: --write-modes %s: no modes (the lumped masses are not all "
                    "positive); nothing written\n",
            cli_command, prefix);
    return;
  }
  const mfs_particles *p = m->p;
  int nsp = 0;
  double *sp = model_spurious_modes(m, r, &nsp);
  int nm = nsp + 1;
  const double **U = mfs_malloc((size_t)nm * sizeof *U);
  mode_info *mi = mfs_malloc((size_t)nm * sizeof *mi);
  long *where = mfs_malloc(p->n * (size_t)m->ndof * sizeof *where);
  if (!U || !mi || !where)
    cli_die(1, "out of memory");
  for (size_t f = 0; f < p->n * (size_t)m->ndof; f++)
    where[f] = -1;
  for (size_t i = 0; i < m->n; i++)
    where[m->dof[i]] = (long)i;
  unsigned char *layer = model_boundary_layer(m);
  for (int k = 0; k < nsp; k++)
    U[k] = sp + (size_t)k * m->n;
  U[nsp] = r->vmax;
  for (int k = 0; k < nm; k++)
    mode_describe(m, layer, U[k], &mi[k]);
  int ps = m->ndof == 2;

  cli_out o;
  cli_out_open_fmt(&o, "%s_modes.csv", prefix);
  FILE *f = o.f;
  fprintf(f, "mode,kind,lambda_per_s2,participation_ratio,boundary_share,layer_share,location,"
             "particle,x_m,y_m,fixed,in_layer,%s\n",
          ps ? "u_x_norm,u_y_norm" : "u_norm");
  for (int k = 0; k < nm; k++)
    for (size_t I = 0; I < p->n; I++) {
      double ui[2];
      particle_u(m, where, U[k], I, ui);
      fprintf(f, "%d,%s,", k, k < nsp ? "spurious" : "max");
      eigs_put(f, k < nsp ? 0.0 : r->lambda, 0);
      eigs_put(f, mi[k].participation, 0);
      eigs_put(f, mi[k].boundary_share, 0);
      eigs_put(f, mi[k].layer_share, 0);
      fprintf(f, "%s,%zu,", mi[k].location, I);
      eigs_put(f, p->x[I * (size_t)p->dim], 0);
      eigs_put(f, p->dim == 2 ? p->x[I * (size_t)p->dim + 1] : 0.0, 0);
      fprintf(f, "%d,%d,", m->fixed[I] != 0, layer[I] != 0);
      eigs_put(f, ui[0], !ps);
      if (ps)
        eigs_put(f, ui[1], 1);
    }
  cli_out_commit(&o);

  /* legacy VTK polydata: the particles as vertices, the cells as lines or polygons */
  cli_out_open_fmt(&o, "%s_modes.vtk", prefix);
  f = o.f;
  fprintf(f, "# vtk DataFile Version 3.0\nmfstab modes: %d spurious zero-energy mode%s and the "
             "highest (lambda_max %.6g 1/s^2), %s\nASCII\nDATASET POLYDATA\nPOINTS %zu double\n",
          nsp, nsp == 1 ? "" : "s", r->lambda, c->s.disc.quadrature->name, p->n);
  for (size_t I = 0; I < p->n; I++)
    fprintf(f, "%.17g %.17g 0\n", p->x[I * (size_t)p->dim],
            p->dim == 2 ? p->x[I * (size_t)p->dim + 1] : 0.0);
  fprintf(f, "VERTICES %zu %zu\n", p->n, 2 * p->n);
  for (size_t I = 0; I < p->n; I++)
    fprintf(f, "1 %zu\n", I);
  if (p->ncell > 0 && !p->box.periodic) {
    fprintf(f, "%s %zu %zu\n", p->dim == 1 ? "LINES" : "POLYGONS", p->ncell,
            p->ncell * (size_t)(p->nvert + 1));
    for (size_t e = 0; e < p->ncell; e++) {
      fprintf(f, "%d", p->nvert);
      for (int v = 0; v < p->nvert; v++)
        fprintf(f, " %d", p->conn[e * (size_t)p->nvert + (size_t)v]);
      fputc('\n', f);
    }
  }
  fprintf(f, "POINT_DATA %zu\nSCALARS fixed int 1\nLOOKUP_TABLE default\n", p->n);
  for (size_t I = 0; I < p->n; I++)
    fprintf(f, "%d\n", m->fixed[I] != 0);
  fprintf(f, "SCALARS boundary_layer int 1\nLOOKUP_TABLE default\n");
  for (size_t I = 0; I < p->n; I++)
    fprintf(f, "%d\n", layer[I] != 0);
  for (int k = 0; k < nm; k++) {
    const char *kind = k < nsp ? "spurious" : "max";
    if (ps)
      fprintf(f, "VECTORS mode%d_%s double\n", k, kind);
    else
      fprintf(f, "SCALARS mode%d_%s double 1\nLOOKUP_TABLE default\n", k, kind);
    for (size_t I = 0; I < p->n; I++) {
      double ui[2];
      particle_u(m, where, U[k], I, ui);
      if (ps)
        fprintf(f, "%.17g %.17g 0\n", ui[0], ui[1]);
      else
        fprintf(f, "%.17g\n", ui[0]);
    }
  }
  cli_out_commit(&o);
  mfs_free(layer);
  mfs_free(where);
  mfs_free(mi);
  mfs_free(U);
  mfs_free(sp);
}
