/* The finite-model analyses of `mfstab eigs` and `mfstab bound` over the MPI
 * ranks (`mpirun -np N mfstab eigs|bound ...`): the hooks of model_run() and
 * cmd_bound() when tools/par.h says MPI runs.  The numbers come from
 * lib/analysis/mfs_peigs.h; every rank calls the same functions in the same
 * order, and every failure there is agreed over the ranks, so every rank
 * dies with the same line (rank 0's is the one shown). */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "model_run.h"
#include "par.h"

/* The model of c over the ranks, or die with the line the one-process
 * commands give. */
static mfs_pmodel *pmodel_build(const model_cmd *c, int assemble)
{
  mfs_status st;
  size_t bad = 0;
  mfs_pmodel *pm = mfs_pmodel_alloc(&c->s, par_comm(), assemble, &st, &bad);
  if (pm)
    return pm;
  if (st == MFS_EINVAL && c->s.fixed != MFS_FIX_NONE)
    cli_die(2, "--fix%s: every particle is fixed; nothing is left to move",
            c->s.fixed == MFS_FIX_MASK ? "" : "ed");
  if (st == MFS_ETOOSMALL) /* the spec, checked before, fits the support radius */
    cli_die(2, "mpirun -np %d: some rank has no free degree of freedom (the model has too few "
               "cells of the support radius for %d ranks); use fewer ranks or more particles",
            par_size(), par_size());
  model_die_status(c, st, bad, "at a quadrature point of the model");
}

/* Die with a clear line for a failed distributed eigenvalue computation. */
static _Noreturn void die_peig(mfs_status st, const mfs_eig_info *info)
{
  if (st == MFS_ENOCONV)
    cli_die(1,
            "lambda_max: PARPACK %s did not converge (info %d) after %d iterations, %d Ritz "
            "values converged; raise --maxiter or --ncv, or loosen --arpack-tol",
            info->routine, info->info, info->iterations, info->nconv);
  if (st == MFS_EARPACK)
    cli_die(1, "lambda_max: PARPACK %s failed with info %d", info->routine, info->info);
  cli_die(1, "lambda_max: %s", mfs_strerror(st));
}

static void particle_x(const mfs_pmodel *pm, size_t I, int dim, double *xy)
{
  if (mfs_pmodel_particle_x(pm, I, xy) != MFS_OK)
    cli_die(1, "out of memory");
  if (dim == 1)
    xy[1] = NAN;
}

void model_prun(const model_cmd *c, const run_opts *o, run_result *r)
{
  memset(r, 0, sizeof *r);
  const mfs_model_spec *s = &c->s;
  const mfs_disc *d = &s->disc;
  eigs_derive(s, &r->dv);
  mfs_pmodel *pm = pmodel_build(c, 1);
  mfs_pmodel_info in;
  mfs_pmodel_sizes(pm, &in);
  r->particles = in.particles;
  r->dofs = in.dofs;
  mfs_status st = mfs_pmodel_bound(pm, &r->br);
  if (st != MFS_OK)
    cli_die(1, "element bound: %s", mfs_strerror(st));
  mfs_pmodel_release_plan(pm); /* as model_run: the rows stay */
  r->bound_valid = !d->consistent_mass && r->br.negative_phi == 0;
  if (in.dofs < 2)
    cli_die(2, "the model has %zu free degree of freedom; use more particles", in.dofs);

  /* lumped masses and the Gershgorin bound (eigs refuses a consistent mass on more ranks) */
  r->min_mass = NAN;
  r->masses_ok = 1;
  r->g = (mfs_gershgorin_result){.lambda = NAN};
  if (!d->consistent_mass) {
    st = mfs_pmodel_gershgorin(pm, &r->g);
    if (st != MFS_OK)
      cli_die(1, "Gershgorin bound: %s", mfs_strerror(st));
    int ndof = mfs_physics_ndof(d->material.physics);
    r->nonpositive = r->g.nonpositive;
    r->min_mass = r->g.min_mass;
    r->min_mass_particle = r->g.argmin_mass / (size_t)ndof;
    particle_x(pm, r->min_mass_particle, d->dim, r->min_mass_x);
    r->masses_ok = r->nonpositive == 0;
  }
  st = mfs_bound_fourier(s, (int)c->m.fourier_points, (int)c->m.fourier_angles, &r->lf, &r->kf,
                         &r->tf);
  if (st != MFS_OK)
    model_die_status(c, st, 0, "Fourier estimate on the uniform lattice");
  model_rules(c, r->dt_rule);
  if (r->masses_ok && !d->consistent_mass) {
    mfs_eig_opts eo = {(int)o->ncv, (int)o->maxiter, o->arpack_tol};
    mfs_eig_info info;
    st = mfs_peig_max(pm, &eo, &r->lambda, &info);
    if (st != MFS_OK)
      die_peig(st, &info);
    run_take_lambda(r, &info);
  }
  mfs_pmodel_free(pm);
}

void bound_prun(const model_cmd *c, mfs_bound_result *br, mfs_gershgorin_result *gr, double *gx,
                size_t *mI, size_t *np, size_t *npts)
{
  const mfs_disc *d = &c->s.disc;
  int ndof = mfs_physics_ndof(d->material.physics);
  mfs_pmodel *pm = pmodel_build(c, 0);
  mfs_pmodel_info in;
  mfs_pmodel_sizes(pm, &in);
  *np = in.particles;
  *npts = in.points;
  mfs_status st;
  int lattice = !mfs_disc_points(d) && !(d->source.perturb > 0.0);
  if (!lattice) { /* the element bound over the ranks' points */
    st = mfs_pmodel_bound(pm, br);
    if (st != MFS_OK)
      cli_die(1, "element bound: %s", mfs_strerror(st));
  }
  if (!d->consistent_mass) {
    st = mfs_pmodel_gershgorin(pm, gr);
    if (st != MFS_OK)
      cli_die(1, "Gershgorin bound: %s", mfs_strerror(st));
    double xy[2];
    if (isfinite(gr->lambda)) {
      particle_x(pm, gr->argmax / (size_t)ndof, d->dim, xy);
      gx[0] = xy[0];
      gx[1] = d->dim == 2 ? xy[1] : NAN;
    }
  }
  *mI = gr->argmin_mass / (size_t)ndof;
  mfs_pmodel_free(pm);
  if (lattice) { /* the streaming bound (equivalent points once), as one process computes it */
    size_t bad = 0;
    st = mfs_bound_model(&c->s, br, &bad);
    if (st != MFS_OK)
      model_die_status(c, st, bad, "at a quadrature point of the model");
  }
  if (!(br->lambda > 0.0))
    cli_die(1, "the element bound is %g: no quadrature point with a positive lambda^Q", br->lambda);
}
