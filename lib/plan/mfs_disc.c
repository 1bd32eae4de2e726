#include "mfs_disc.h"

#include <math.h>
#include <string.h>

#include "mfs_status.h"

static const char *const frame_names[] = {"lagrangian", "eulerian", "eulerian-consistent"};

const char *mfs_frame_name(mfs_frame f)
{
  return (unsigned)f < 3 ? frame_names[f] : "?";
}

mfs_status mfs_frame_parse(const char *name, mfs_frame *f)
{
  for (int i = 0; name && i < 3; i++)
    if (strcmp(name, frame_names[i]) == 0) {
      *f = (mfs_frame)i;
      return MFS_OK;
    }
  return MFS_EINVAL;
}

mfs_disc mfs_disc_default(void)
{
  return (mfs_disc){.dim = 1,
                    .source = {.lattice = MFS_LATTICE_LINE, .spacing = 1.0, .gamma = 1.0},
                    .kernel = &mfs_kernel_cubic,
                    .dilation = 2.0,
                    .shape = &mfs_shape_mls,
                    .quadrature = &mfs_quad_nodal,
                    .frame = MFS_FRAME_LAGRANGIAN,
                    .consistent_mass = 0,
                    .node_volume_mass = 0,
                    .material = {.physics = MFS_PHYS_SCALAR,
                                 .modulus = 1.0,
                                 .poisson = 0.25,
                                 .density = 1.0},
                    .rcond_min = 0.0};
}

/* The spacing of a particle set (mfs_disc_dx). */
static double set_spacing(const mfs_point_set *ps)
{
  int dim = ps->dim;
  if (ps->spacing > 0.0)
    return ps->spacing;
  if (ps->n < 2 || (dim != 1 && dim != 2))
    return NAN;
  double lo[2], hi[2];
  for (int k = 0; k < dim; k++) {
    lo[k] = hi[k] = ps->x[k];
    for (size_t i = 1; i < ps->n; i++) {
      double v = ps->x[i * dim + k];
      lo[k] = v < lo[k] ? v : lo[k];
      hi[k] = v > hi[k] ? v : hi[k];
    }
  }
  if (dim == 1)
    return (hi[0] - lo[0]) / (double)(ps->n - 1);
  double A = 0.0;
  if (ps->vol)
    for (size_t i = 0; i < ps->n; i++)
      A += ps->vol[i];
  else
    A = (hi[0] - lo[0]) * (hi[1] - lo[1]);
  return sqrt(A / (double)ps->n);
}

double mfs_disc_dx(const mfs_disc *d)
{
  const mfs_source *s = &d->source;
  if (s->points)
    return set_spacing(s->points);
  if (s->nx == 0)
    return s->spacing > 0.0 ? s->spacing : 1.0;
  return s->periodic ? s->lx / s->nx : s->lx / (s->nx - 1);
}

double mfs_disc_dy(const mfs_disc *d)
{
  const mfs_source *s = &d->source;
  if (d->dim == 1)
    return 0.0;
  if (s->points)
    return set_spacing(s->points);
  if (s->nx == 0) {
    double dx = mfs_disc_dx(d);
    if (s->lattice == MFS_LATTICE_HEX)
      return sqrt(3.0) / 2.0 * dx;
    return (s->gamma > 0.0 ? s->gamma : 1.0) * dx;
  }
  return s->periodic ? s->ly / s->ny : s->ly / (s->ny - 1);
}

double mfs_disc_support(const mfs_disc *d)
{
  return d->support > 0.0 ? d->support : d->dilation * mfs_disc_dx(d);
}

double mfs_disc_rcond(const mfs_disc *d)
{
  return d->rcond_min > 0.0 ? d->rcond_min : 1e-12;
}

#define BAD(name)                                                                            \
  do {                                                                                       \
    if (field)                                                                               \
      *field = name;                                                                         \
    return MFS_EINVAL;                                                                       \
  } while (0)

mfs_status mfs_disc_check(const mfs_disc *d, const char **field)
{
  if (field)
    *field = "";
  if (!d || (d->dim != 1 && d->dim != 2))
    BAD("dim");
  const mfs_source *s = &d->source;
  if (s->points) {
    if (s->lattice != MFS_LATTICE_POINTS)
      BAD("source.lattice");
    if (s->points->dim != d->dim || !s->points->x || s->points->n < (size_t)d->dim + 1)
      BAD("source.points");
    if (!(d->support > 0.0)) /* a set has no spacing to scale a dilation with */
      BAD("support");
  } else if ((unsigned)s->lattice > MFS_LATTICE_HEX ||
             (d->dim == 1) != (s->lattice == MFS_LATTICE_LINE)) {
    BAD("source.lattice");
  } else if (s->nx == 0) { /* the infinite lattice */
    if (!(s->spacing >= 0.0) || !isfinite(s->spacing))
      BAD("source.spacing");
    if (!(s->gamma >= 0.0) || !isfinite(s->gamma))
      BAD("source.gamma");
  } else {
    if (s->nx < 2)
      BAD("source.nx");
    if (d->dim == 2 && s->ny < 2)
      BAD("source.ny");
    if (!(s->lx > 0.0) || !isfinite(s->lx))
      BAD("source.lx");
    if (d->dim == 2 && (!(s->ly > 0.0) || !isfinite(s->ly)))
      BAD("source.ly");
    if (d->dim == 2 && s->lattice != MFS_LATTICE_SQUARE)
      BAD("source.lattice"); /* finite boxes are square lattices */
    if (!(s->perturb >= 0.0 && s->perturb < 0.5))
      BAD("source.perturb");
  }
  if (!(d->support >= 0.0) || !isfinite(d->support))
    BAD("support");
  if (!d->kernel)
    BAD("kernel");
  if (!(d->dilation > 0.0) || !isfinite(d->dilation))
    BAD("dilation");
  if (!d->shape)
    BAD("shape");
  if (!d->quadrature || !mfs_quad_applies(d->quadrature, d->dim, s->lattice))
    BAD("quadrature");
  if ((unsigned)d->frame > MFS_FRAME_EULERIAN_CONSISTENT)
    BAD("frame");
  /* the Eulerian terms need second derivatives, which a cusp lacks at r = 0 */
  if (d->kernel->cusp && d->frame != MFS_FRAME_LAGRANGIAN)
    BAD("frame");
  const mfs_material *m = &d->material;
  if (m->physics != MFS_PHYS_SCALAR && m->physics != MFS_PHYS_PLANE_STRAIN)
    BAD("material.physics");
  if (m->physics == MFS_PHYS_PLANE_STRAIN && d->dim != 2)
    BAD("material.physics");
  if (!(m->modulus > 0.0) || !isfinite(m->modulus))
    BAD("material.modulus");
  if (!(m->density > 0.0) || !isfinite(m->density))
    BAD("material.density");
  if (m->physics == MFS_PHYS_PLANE_STRAIN && !(m->poisson > -1.0 && m->poisson < 0.5))
    BAD("material.poisson");
  if (!isfinite(m->initial_stress))
    BAD("material.initial_stress");
  if (!(d->rcond_min >= 0.0) || !(d->rcond_min < 1.0))
    BAD("rcond_min");
  if (d->node_volume_mass && d->consistent_mass)
    BAD("node_volume_mass");
  if (s->nx > 0 && s->periodic && !s->points) {
    /* the star pattern tiles a periodic box only with even counts */
    if (d->quadrature->cells == MFS_CELLS_STAR && d->dim == 2 && ((s->nx & 1) || (s->ny & 1)))
      BAD((s->nx & 1) ? "source.nx" : "source.ny");
    double a = mfs_disc_support(d);
    if (!(s->nx * mfs_disc_dx(d) > 2.0 * a)) {
      if (field)
        *field = "source.nx";
      return MFS_ETOOSMALL;
    }
    if (d->dim == 2 && !(s->ny * mfs_disc_dy(d) > 2.0 * a)) {
      if (field)
        *field = "source.ny";
      return MFS_ETOOSMALL;
    }
  }
  return MFS_OK;
}

static int build(const mfs_disc *d, const mfs_lattice_spec *ls, mfs_particles **p, mfs_quad **q)
{
  mfs_status st;
  *p = mfs_lattice_alloc(ls, &st);
  if (!*p)
    return st;
  *q = mfs_quad_alloc(d->quadrature, *p, &st);
  if (!*q) {
    mfs_particles_free(*p);
    *p = NULL;
  }
  return st;
}

mfs_status mfs_disc_geometry(const mfs_disc *d, mfs_particles **p, mfs_quad **q)
{
  *p = NULL;
  *q = NULL;
  mfs_status st = mfs_disc_check(d, NULL);
  if (st != MFS_OK)
    return st;
  if (mfs_disc_infinite(d))
    return MFS_EINVAL;
  if (mfs_disc_points(d)) {
    const mfs_quad_type *t = d->quadrature;
    *p = mfs_particles_from_set(d->source.points, mfs_quad_has_stress_points(t), &st);
    if (!*p)
      return st;
    *q = mfs_quad_alloc(t, *p, &st);
    if (!*q) {
      mfs_particles_free(*p);
      *p = NULL;
    }
    return st;
  }
  double dx = mfs_disc_dx(d), dy = mfs_disc_dy(d);
  mfs_lattice_spec ls = {.dim = d->dim,
                         .lattice = d->source.lattice,
                         .nx = d->source.nx,
                         .ny = d->dim == 1 ? 1 : d->source.ny,
                         .dx = dx,
                         .gamma = d->dim == 1 ? 1.0 : dy / dx,
                         .periodic = d->source.periodic,
                         .cells = d->quadrature->cells,
                         .perturb = d->source.perturb,
                         .seed = d->source.seed};
  return build(d, &ls, p, q);
}

mfs_status mfs_disc_periodic_box(const mfs_disc *d, int nx, int ny, mfs_particles **p, mfs_quad **q)
{
  *p = NULL;
  *q = NULL;
  if (!d->quadrature)
    return MFS_EINVAL;
  double gamma = d->source.gamma > 0.0 ? d->source.gamma : 1.0;
  mfs_lattice_spec ls = {.dim = d->dim,
                         .lattice = d->source.lattice,
                         .nx = nx,
                         .ny = d->dim == 1 ? 1 : ny,
                         .dx = mfs_disc_dx(d),
                         .gamma = gamma,
                         .periodic = 1,
                         .cells = d->quadrature->cells};
  return build(d, &ls, p, q);
}

double mfs_disc_model_bytes(const mfs_disc *d, double n)
{
  double points, entries = mfs_disc_plan_entries(d, n, &points);
  int dim = d->dim, ncomp = d->material.physics == MFS_PHYS_PLANE_STRAIN ? 2 : 1;
  /* the plan: an index and the values and gradients per entry */
  double plan = entries * (4.0 + 8.0 * (1 + dim));
  /* K (and a consistent M): the particles within 2a of each, ncomp^2 each, 12 bytes a nonzero */
  double D2 = 2.0 * d->dilation, gamma = d->source.gamma > 0.0 ? d->source.gamma : 1.0;
  double row = dim == 1 ? 2.0 * D2 + 1.0 : M_PI * D2 * D2 / gamma + 1.0;
  if (row > n)
    row = n;
  double nnz = n * ncomp * ncomp * row;
  double mats = 12.0 * nnz * (d->consistent_mass ? 2.0 : 1.0);
  return plan + mats + 64.0 * n * ncomp; /* and a few vectors */
}

double mfs_disc_plan_entries(const mfs_disc *d, double n, double *points)
{
  const mfs_quad_type *t = d->quadrature;
  int dim = d->dim, tri = dim == 2 && (t->cells != MFS_CELLS_QUAD ||
                                       d->source.lattice == MFS_LATTICE_HEX);
  double cells = dim == 1 ? 1.0 : (tri ? 2.0 : 1.0); /* background cells per particle */
  double per = t->node_share > 0.0 ? 1.0 : 0.0;      /* quadrature points per particle */
  if (t->centres)
    per += cells;
  if (t->gauss_n > 0)
    per += cells * (dim == 1 ? t->gauss_n : (tri && t->gauss_n == 1 ? 1 : t->gauss_n * t->gauss_n));
  /* neighbours: the particles within a = D dx, area (length) per particle */
  double D = d->dilation, nb;
  if (dim == 1) {
    nb = 2.0 * D + 1.0;
  } else {
    double gamma = d->source.gamma > 0.0 ? d->source.gamma : 1.0;
    double cell = d->source.lattice == MFS_LATTICE_HEX ? sqrt(3.0) / 2.0 : gamma;
    if (!mfs_disc_infinite(d) && d->source.nx > 1 && d->source.ny > 1)
      cell = mfs_disc_dy(d) / mfs_disc_dx(d);
    nb = M_PI * D * D / cell + 1.0;
  }
  if (nb > n)
    nb = n; /* a support wider than the body holds every particle */
  if (points)
    *points = n * per;
  return n * per * nb;
}
