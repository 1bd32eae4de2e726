#include "mfs_model.h"
#include "mfs_alloc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"

mfs_model_spec mfs_model_spec_default(void)
{
  mfs_disc d = mfs_disc_default();
  d.source = (mfs_source){.lattice = MFS_LATTICE_LINE, .nx = 41, .ny = 1, .lx = 1.0, .ly = 1.0};
  d.quadrature = &mfs_quad_gauss[1];
  return (mfs_model_spec){.disc = d, .fixed = MFS_FIX_NONE};
}

mfs_status mfs_model_spec_check(const mfs_model_spec *s, const char **field)
{
  static char name[64];
  const char *f = "";
  if (field)
    *field = "";
  mfs_status st = mfs_disc_check(&s->disc, &f);
  if (st != MFS_OK) {
    snprintf(name, sizeof name, "disc.%s", f);
    if (field)
      *field = name;
    return st;
  }
  const mfs_disc *d = &s->disc;
  if (mfs_disc_infinite(d)) {
    if (field)
      *field = "disc.source";
    return MFS_EINVAL;
  }
  int pts = mfs_disc_points(d);
  int bad = s->fixed != MFS_FIX_NONE && s->fixed != MFS_FIX_ENDS &&
            s->fixed != MFS_FIX_BOUNDARY && s->fixed != MFS_FIX_MASK;
  bad |= !pts && d->source.periodic && s->fixed != MFS_FIX_NONE;
  bad |= d->dim == 2 && s->fixed == MFS_FIX_ENDS;
  bad |= s->fixed == MFS_FIX_MASK && !s->fix_mask;
  /* fixing the boundary must leave free particles */
  bad |= !pts && s->fixed != MFS_FIX_NONE && s->fixed != MFS_FIX_MASK &&
         (d->source.nx < 3 || (d->dim == 2 && d->source.ny < 3));
  if (bad) {
    if (field)
      *field = "fixed";
    return MFS_EINVAL;
  }
  return MFS_OK;
}

void mfs_model_free(mfs_model *m)
{
  if (!m)
    return;
  mfs_plan_free(m->pl);
  mfs_quad_free(m->q);
  mfs_particles_free(m->p);
  mfs_free(m->fixed);
  mfs_free(m->dof);
  mfs_csr_free(m->K);
  mfs_csr_free(m->M);
  mfs_free(m->m);
  mfs_free(m);
}

void mfs_model_release_plan(mfs_model *m)
{
  mfs_plan_free(m->pl);
  mfs_quad_free(m->q);
  m->pl = NULL;
  m->q = NULL;
}

double *mfs_model_coords(const mfs_model *m)
{
  const int dim = m->p->dim, nd = m->ndof;
  double *x = mfs_malloc((m->n ? m->n : 1) * (size_t)dim * sizeof *x);
  if (!x)
    return NULL;
  for (size_t i = 0; i < m->n; i++) {
    size_t I = m->dof[i] / (size_t)nd;
    for (int k = 0; k < dim; k++)
      x[i * (size_t)dim + (size_t)k] = m->p->x[I * (size_t)dim + (size_t)k];
  }
  return x;
}

mfs_model *mfs_model_alloc(const mfs_model_spec *spec, mfs_status *status, size_t *bad)
{
  mfs_status st = mfs_model_spec_check(spec, NULL);
  mfs_model *m = NULL;
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  m = mfs_calloc(1, sizeof *m);
  if (!m)
    goto done;
  m->spec = *spec;
  const mfs_disc *d = &spec->disc;
  m->dx = mfs_disc_dx(d);
  m->dy = mfs_disc_dy(d);
  m->a = mfs_disc_support(d);
  m->c = sqrt(d->material.modulus / d->material.density);
  m->ndof = mfs_physics_ndof(d->material.physics);
  m->mat = d->material;

  st = mfs_disc_geometry(d, &m->p, &m->q);
  if (st != MFS_OK)
    goto done;
  m->pl = mfs_plan_alloc(d, m->p, m->q, &st);
  if (!m->pl)
    goto done;

  size_t np = m->p->n, nfull = np * (size_t)m->ndof;
  st = MFS_ENOMEM;
  m->fixed = mfs_calloc(np, 1);
  m->dof = mfs_malloc(nfull * sizeof *m->dof);
  if (!m->fixed || !m->dof)
    goto done;
  if (spec->fixed == MFS_FIX_MASK)
    for (size_t I = 0; I < np; I++)
      m->fixed[I] = spec->fix_mask[I] != 0;
  else if (spec->fixed != MFS_FIX_NONE)
    for (size_t I = 0; I < np; I++)
      m->fixed[I] = m->p->flags[I] != 0; /* 1D: the ends; 2D: the boundary (a set: its hull) */
  m->n = 0;
  for (size_t I = 0; I < np; I++)
    for (int k = 0; k < m->ndof; k++)
      if (!m->fixed[I])
        m->dof[m->n++] = I * (size_t)m->ndof + (size_t)k;
  st = MFS_EINVAL;
  if (m->n < 1)
    goto done;

  /* symbolic and numeric in one sweep over the rows (mfs_assemble): the
   * pattern of the free dofs, rows sorted, and K (and M, or the lumped m);
   * the sweep evaluates the shape functions block by block: no table is
   * held (mfs_assemble.h) */
  const unsigned char *fx = spec->fixed != MFS_FIX_NONE ? m->fixed : NULL;
  st = MFS_ENOMEM;
  if (!d->consistent_mass && !(m->m = mfs_malloc(m->n * sizeof *m->m)))
    goto done;
  st = mfs_assemble(m->pl, &m->mat, fx, &m->K, d->consistent_mass ? &m->M : NULL, m->m, bad);
done:
  if (st != MFS_OK) {
    mfs_model_free(m);
    m = NULL;
  }
  if (status)
    *status = st;
  return m;
}

int mfs_model_rigid_fields(const mfs_model *m, double *r)
{
  for (size_t I = 0; I < m->p->n; I++)
    if (m->fixed[I])
      return 0;
  size_t n = m->n;
  if (m->ndof == 1) {
    if (r)
      for (size_t i = 0; i < n; i++)
        r[i] = 1.0;
    return 1;
  }
  int periodic = m->spec.disc.source.periodic && !mfs_disc_points(&m->spec.disc);
  int nr = periodic ? 2 : 3; /* a rotation is not periodic */
  if (r) {
    double cx = 0.0, cy = 0.0; /* the centroid: any centre spans the same fields */
    for (size_t I = 0; I < m->p->n; I++) {
      cx += m->p->x[2 * I] / (double)m->p->n;
      cy += m->p->x[2 * I + 1] / (double)m->p->n;
    }
    for (size_t i = 0; i < n; i++) {
      size_t f = m->dof[i], I = f / 2;
      int comp = (int)(f % 2);
      const double *x = m->p->x + 2 * I;
      r[i] = comp == 0 ? 1.0 : 0.0;
      r[n + i] = comp == 1 ? 1.0 : 0.0;
      if (nr == 3) /* u = (-(y - cy), x - cx) */
        r[2 * n + i] = comp == 0 ? -(x[1] - cy) : x[0] - cx;
    }
  }
  return nr;
}

mfs_status mfs_model_write_mtx(const mfs_model *m, FILE *fK, FILE *fM)
{
  if (fK) {
    mfs_status st = mfs_csr_write_mtx(m->K, fK);
    if (st != MFS_OK)
      return st;
  }
  if (!fM)
    return MFS_OK;
  if (m->M)
    return mfs_csr_write_mtx(m->M, fM);
  if (fprintf(fM, "%%%%MatrixMarket matrix coordinate real general\n%zu %zu %zu\n", m->n, m->n,
              m->n) < 0)
    return MFS_EIO;
  for (size_t i = 0; i < m->n; i++)
    if (fprintf(fM, "%zu %zu %.17g\n", i + 1, i + 1, m->m[i]) < 0)
      return MFS_EIO;
  return MFS_OK;
}
