#include "mfs_integrator.h"

#include <math.h>

/* ---- the rod ---- */

static mfs_status rod_set_state(void *s, const double *u, const double *v)
{
  return mfs_solver_set_state(s, u, v);
}

static double rod_stable_dt(void *s)
{
  return ((mfs_solver *)s)->dt_crit;
}

static mfs_status rod_set_dt(void *s, double dt, int force)
{
  return mfs_solver_set_dt(s, dt, force);
}

static mfs_status rod_choose_step(void *s, mfs_dt_rule rule)
{
  return mfs_solver_choose_step(s, rule);
}

static const mfs_dt_info *rod_step_info(const void *s)
{
  return &((const mfs_solver *)s)->step;
}

static mfs_status rod_step(void *s, mfs_scheme scheme)
{
  return mfs_solver_step(s, scheme);
}

static mfs_status rod_fields(void *s)
{
  return mfs_solver_fields(s);
}

static mfs_status rod_energy(void *s, double *kin, double *pot, double *mod)
{
  *mod = NAN;
  return mfs_solver_energy(s, kin, pot);
}

static void rod_state(const void *sv, mfs_state *st)
{
  const mfs_solver *s = sv;
  *st = (mfs_state){.dim = 1,
                    .n = s->n,
                    .ncomp = 1,
                    .X = s->X,
                    .u = s->u,
                    .v = s->v,
                    .nq = s->nq,
                    .xq = s->xq0,
                    .sigma = s->sigma,
                    .dx = s->dX,
                    .t = s->t,
                    .dt = s->dt};
}

static size_t rod_nearest(const void *s, double x, double y, int comp)
{
  (void)y;
  (void)comp;
  return mfs_solver_nearest(s, x);
}

static void rod_free(void *s)
{
  mfs_solver_free(s);
}

const mfs_integrator_type mfs_integrator_rod = {.name = "rod",
                                                .step_rule = "central-difference",
                                                .set_state = rod_set_state,
                                                .stable_dt = rod_stable_dt,
                                                .set_dt = rod_set_dt,
                                                .choose_step = rod_choose_step,
                                                .step_info = rod_step_info,
                                                .step = rod_step,
                                                .fields = rod_fields,
                                                .energy = rod_energy,
                                                .state = rod_state,
                                                .nearest = rod_nearest,
                                                .free = rod_free};

/* ---- the linear plate ---- */

static mfs_status plate_set_state(void *s, const double *u, const double *v)
{
  return mfs_solver2d_set_state(s, u, v);
}

static double plate_stable_dt(void *s)
{
  return ((mfs_solver2d *)s)->dt_crit;
}

static mfs_status plate_set_dt(void *s, double dt, int force)
{
  return mfs_solver2d_set_dt(s, dt, force);
}

static mfs_status plate_choose_step(void *s, mfs_dt_rule rule)
{
  return mfs_solver2d_choose_step(s, rule);
}

static const mfs_dt_info *plate_step_info(const void *s)
{
  return &((const mfs_solver2d *)s)->step;
}

static mfs_status plate_step(void *s, mfs_scheme scheme)
{
  return mfs_solver2d_step(s, scheme);
}

static mfs_status plate_energy(void *s, double *kin, double *pot, double *mod)
{
  mfs_solver2d_energy(s, kin, pot, mod);
  return MFS_OK;
}

static void plate_state(const void *sv, mfs_state *st)
{
  const mfs_solver2d *s = sv;
  const mfs_model *m = s->model;
  *st = (mfs_state){.dim = m->spec.disc.dim,
                    .n = s->n,
                    .ncomp = m->ndof,
                    .X = s->X,
                    .Y = m->spec.disc.dim > 1 ? s->Y : NULL,
                    .comp = s->comp,
                    .u = s->u,
                    .v = s->v,
                    .dx = m->dx,
                    .t = s->t,
                    .dt = s->dt};
}

static size_t plate_nearest(const void *s, double x, double y, int comp)
{
  long d = mfs_solver2d_dof(s, mfs_solver2d_nearest(s, x, y), comp);
  return d < 0 ? (size_t)-1 : (size_t)d;
}

static void plate_free(void *s)
{
  mfs_solver2d_free(s);
}

const mfs_integrator_type mfs_integrator_plate = {.name = "plate",
                                                  .step_rule = "central-difference",
                                                  .set_state = plate_set_state,
                                                  .stable_dt = plate_stable_dt,
                                                  .set_dt = plate_set_dt,
                                                  .choose_step = plate_choose_step,
                                                  .step_info = plate_step_info,
                                                  .step = plate_step,
                                                  .energy = plate_energy,
                                                  .state = plate_state,
                                                  .nearest = plate_nearest,
                                                  .free = plate_free};

/* ---- the TSPH bar ---- */

static mfs_status tsph_set_state(void *s, const double *u, const double *v)
{
  if (u)
    return MFS_EINVAL; /* no displacement in the stress-velocity form */
  return mfs_tsph_set_state(s, NULL, v);
}

static double tsph_stable_dt(void *s)
{
  return mfs_tsph_dt_stable(s);
}

static mfs_status tsph_set_dt(void *s, double dt, int force)
{
  if (!force && dt > mfs_tsph_dt_stable(s) * (1.0 + 1e-9))
    return MFS_EINVAL;
  return mfs_tsph_set_dt(s, dt);
}

static mfs_status tsph_step(void *s, mfs_scheme scheme)
{
  (void)scheme; /* spec.scheme */
  return mfs_tsph_step(s);
}

static mfs_status tsph_energy(void *s, double *kin, double *pot, double *mod)
{
  mfs_tsph_energy(s, kin, pot);
  *mod = NAN;
  return MFS_OK;
}

static void tsph_state(const void *sv, mfs_state *st)
{
  const mfs_tsph *s = sv;
  *st = (mfs_state){.dim = 1,
                    .n = s->n,
                    .ncomp = 1,
                    .X = s->X,
                    .v = s->v,
                    .nq = s->n,
                    .xq = s->X,
                    .sigma = s->sigma,
                    .dx = s->dx,
                    .t = s->t,
                    .dt = s->dt};
}

static size_t tsph_nearest(const void *sv, double x, double y, int comp)
{
  (void)y;
  (void)comp;
  const mfs_tsph *s = sv;
  size_t ic = 0; /* the first of the nearest */
  for (size_t I = 0; I < s->n; I++)
    if (fabs(s->X[I] - x) < fabs(s->X[ic] - x))
      ic = I;
  return ic;
}

static void tsph_free(void *s)
{
  mfs_tsph_free(s);
}

const mfs_integrator_type mfs_integrator_tsph = {.name = "tsph",
                                                 .step_rule = "von Neumann",
                                                 .set_state = tsph_set_state,
                                                 .stable_dt = tsph_stable_dt,
                                                 .set_dt = tsph_set_dt,
                                                 .step = tsph_step,
                                                 .energy = tsph_energy,
                                                 .state = tsph_state,
                                                 .nearest = tsph_nearest,
                                                 .free = tsph_free};
