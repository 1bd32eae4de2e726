#include "mfs_model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mfs_status.h"

void mfs_model_spec_default(mfs_model_spec *s)
{
  *s = (mfs_model_spec){.dim = 1,
                        .nx = 41,
                        .ny = 1,
                        .lx = 1.0,
                        .ly = 1.0,
                        .periodic = 0,
                        .fixed = MFS_FIX_NONE,
                        .kernel = &mfs_kernel_cubic,
                        .shape = &mfs_shape_mls,
                        .dilation = 2.0,
                        .quadrature = "gauss2",
                        .consistent_mass = 0,
                        .physics = MFS_PHYS_SCALAR,
                        .modulus = 1.0,
                        .density = 1.0,
                        .poisson = 0.25,
                        .rcond_min = 0.0};
}

/* Spacings of the lattice of a spec (checked). */
static void spacing(const mfs_model_spec *s, double *dx, double *dy)
{
  *dx = s->periodic ? s->lx / s->nx : s->lx / (s->nx - 1);
  *dy = s->dim == 1 ? 0.0 : (s->periodic ? s->ly / s->ny : s->ly / (s->ny - 1));
}

int mfs_model_spec_check(const mfs_model_spec *s)
{
  if (s->dim != 1 && s->dim != 2)
    return MFS_EINVAL;
  if (s->nx < 2 || (s->dim == 2 && s->ny < 2))
    return MFS_EINVAL;
  if (!(s->lx > 0.0) || (s->dim == 2 && !(s->ly > 0.0)) || !isfinite(s->lx) ||
      (s->dim == 2 && !isfinite(s->ly)))
    return MFS_EINVAL;
  if (!s->kernel || !s->shape || !(s->dilation > 0.0) || !s->quadrature)
    return MFS_EINVAL;
  if (!(s->modulus > 0.0) || !(s->density > 0.0) || !isfinite(s->modulus) ||
      !isfinite(s->density))
    return MFS_EINVAL;
  if (s->fixed != MFS_FIX_NONE && s->fixed != MFS_FIX_ENDS && s->fixed != MFS_FIX_BOUNDARY)
    return MFS_EINVAL;
  if (s->periodic && s->fixed != MFS_FIX_NONE)
    return MFS_EINVAL;
  if (s->dim == 2 && s->fixed == MFS_FIX_ENDS)
    return MFS_EINVAL;
  if (s->physics == MFS_PHYS_PLANE_STRAIN && (s->dim != 2 || !(s->poisson > -1.0 && s->poisson < 0.5)))
    return MFS_EINVAL;
  if (s->physics != MFS_PHYS_SCALAR && s->physics != MFS_PHYS_PLANE_STRAIN)
    return MFS_EINVAL;
  /* fixing the boundary must leave free particles */
  if (s->fixed != MFS_FIX_NONE && (s->nx < 3 || (s->dim == 2 && s->ny < 3)))
    return MFS_EINVAL;
  mfs_quad_rule rule;
  mfs_lattice_kind lat = s->dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE;
  if (mfs_quad_rule_parse(s->quadrature, &rule) != MFS_OK ||
      mfs_quad_rule_check(&rule, s->dim, lat) != MFS_OK)
    return MFS_EINVAL;
  if (rule.kind == MFS_QK_VORONOI && s->periodic && ((s->nx & 1) || (s->ny & 1)))
    return MFS_EINVAL; /* the star pattern tiles a periodic box only with even counts */
  if (s->periodic) {
    double dx, dy;
    spacing(s, &dx, &dy);
    double a = s->dilation * dx;
    if (!(s->nx * dx > 2.0 * a) || (s->dim == 2 && !(s->ny * dy > 2.0 * a)))
      return MFS_ETOOSMALL;
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
  free(m->fixed);
  free(m->dof);
  mfs_csr_free(m->K);
  mfs_csr_free(m->M);
  free(m->m);
  free(m);
}

void mfs_model_release_plan(mfs_model *m)
{
  mfs_plan_free(m->pl);
  mfs_quad_free(m->q);
  m->pl = NULL;
  m->q = NULL;
}

/* Sort the column indices of every row (insertion sort: rows are short and
 * come out of the assembly nearly sorted).  Sorted rows make the products
 * K x of the Lanczos iterations read x in order, which is markedly faster
 * on large models. */
static void sort_rows(mfs_csr *A)
{
  for (size_t r = 0; r < A->nrow; r++) {
    int *ix = A->idx;
    double *v = A->val;
    for (size_t e = A->ptr[r] + 1; e < A->ptr[r + 1]; e++) {
      int c = ix[e];
      double x = v[e];
      size_t k = e;
      for (; k > A->ptr[r] && ix[k - 1] > c; k--) {
        ix[k] = ix[k - 1];
        v[k] = v[k - 1];
      }
      ix[k] = c;
      v[k] = x;
    }
  }
}

/* Rows and columns `keep` (full index -> reduced index, or -1) of A. */
static mfs_csr *reduce(const mfs_csr *A, const long *keep, const size_t *dof, size_t n)
{
  size_t nnz = 0;
  for (size_t r = 0; r < n; r++)
    for (size_t e = A->ptr[dof[r]]; e < A->ptr[dof[r] + 1]; e++)
      nnz += keep[A->idx[e]] >= 0;
  mfs_csr *B = mfs_csr_alloc(n, n, nnz);
  if (!B)
    return NULL;
  size_t pos = 0;
  for (size_t r = 0; r < n; r++) {
    for (size_t e = A->ptr[dof[r]]; e < A->ptr[dof[r] + 1]; e++) {
      long c = keep[A->idx[e]];
      if (c < 0)
        continue;
      B->idx[pos] = (int)c;
      B->val[pos] = A->val[e];
      pos++;
    }
    B->ptr[r + 1] = pos;
  }
  return B;
}

int mfs_model_geometry(const mfs_model_spec *spec, mfs_particles **p, mfs_quad **q)
{
  *p = NULL;
  *q = NULL;
  int st = mfs_model_spec_check(spec);
  if (st != MFS_OK)
    return st;
  double dx, dy;
  spacing(spec, &dx, &dy);
  mfs_quad_rule rule;
  mfs_quad_rule_parse(spec->quadrature, &rule);
  mfs_lattice_spec ls = {spec->dim,
                         spec->dim == 1 ? MFS_LATTICE_LINE : MFS_LATTICE_SQUARE,
                         spec->nx,
                         spec->dim == 1 ? 1 : spec->ny,
                         dx,
                         spec->dim == 1 ? 1.0 : dy / dx,
                         spec->periodic,
                         rule.cells,
                         0.0,
                         0};
  *p = mfs_lattice_alloc(&ls, &st);
  if (!*p)
    return st;
  *q = mfs_quad_alloc(&rule, *p, &st);
  if (!*q) {
    mfs_particles_free(*p);
    *p = NULL;
  }
  return st;
}

mfs_model *mfs_model_alloc(const mfs_model_spec *spec, int *status, size_t *bad)
{
  int st = mfs_model_spec_check(spec);
  mfs_model *m = NULL;
  mfs_csr *K = NULL, *M = NULL;
  double *ml = NULL;
  long *keep = NULL;
  if (st != MFS_OK)
    goto done;
  st = MFS_ENOMEM;
  m = calloc(1, sizeof *m);
  if (!m)
    goto done;
  m->spec = *spec;
  spacing(spec, &m->dx, &m->dy);
  m->a = spec->dilation * m->dx;
  m->c = sqrt(spec->modulus / spec->density);
  m->ndof = mfs_physics_ndof(spec->physics);
  m->mat.kind = spec->physics;
  m->mat.modulus = spec->modulus;
  m->mat.density = spec->density;
  m->mat.lambda = spec->physics == MFS_PHYS_PLANE_STRAIN
                    ? 2.0 * spec->modulus * spec->poisson / (1.0 - 2.0 * spec->poisson)
                    : 0.0;

  st = mfs_model_geometry(spec, &m->p, &m->q);
  if (st != MFS_OK)
    goto done;
  mfs_plan_spec ps = {spec->kernel, spec->shape, spec->dilation, 1,
                      spec->rcond_min > 0.0 ? spec->rcond_min : 1e-12};
  m->pl = mfs_plan_alloc(&ps, m->p, m->q, &st, bad);
  if (!m->pl)
    goto done;

  size_t np = m->p->n, nfull = np * (size_t)m->ndof;
  st = MFS_ENOMEM;
  m->fixed = calloc(np, 1);
  keep = malloc(nfull * sizeof *keep);
  m->dof = malloc(nfull * sizeof *m->dof);
  if (!m->fixed || !keep || !m->dof)
    goto done;
  if (spec->fixed != MFS_FIX_NONE)
    for (size_t I = 0; I < np; I++)
      m->fixed[I] = m->p->flags[I] != 0; /* 1D: the ends; 2D: the boundary */
  m->n = 0;
  for (size_t I = 0; I < np; I++)
    for (int k = 0; k < m->ndof; k++) {
      size_t f = I * (size_t)m->ndof + (size_t)k;
      keep[f] = m->fixed[I] ? -1 : (long)m->n;
      if (!m->fixed[I])
        m->dof[m->n++] = f;
    }
  st = MFS_EINVAL;
  if (m->n < 1)
    goto done;

  st = mfs_assemble_stiffness(m->pl, &m->mat, &K);
  if (st != MFS_OK)
    goto done;
  if (spec->consistent_mass) {
    st = mfs_assemble_mass_consistent(m->pl, &m->mat, &M);
    if (st != MFS_OK)
      goto done;
  } else {
    st = MFS_ENOMEM;
    ml = malloc(nfull * sizeof *ml);
    if (!ml)
      goto done;
    st = mfs_assemble_mass_lumped(m->pl, &m->mat, ml);
    if (st != MFS_OK)
      goto done;
  }
  sort_rows(K);
  if (M)
    sort_rows(M);
  st = MFS_ENOMEM;
  if (m->n == nfull) { /* nothing fixed: keep the assembled matrices */
    m->K = K;
    K = NULL;
    m->M = M;
    M = NULL;
    m->m = ml;
    ml = NULL;
  } else {
    m->K = reduce(K, keep, m->dof, m->n);
    if (!m->K)
      goto done;
    if (M) {
      m->M = reduce(M, keep, m->dof, m->n);
      if (!m->M)
        goto done;
    } else {
      m->m = malloc(m->n * sizeof *m->m);
      if (!m->m)
        goto done;
      for (size_t r = 0; r < m->n; r++)
        m->m[r] = ml[m->dof[r]];
    }
  }
  st = MFS_OK;
done:
  free(keep);
  free(ml);
  mfs_csr_free(K);
  mfs_csr_free(M);
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
  if (m->spec.fixed != MFS_FIX_NONE)
    return 0;
  size_t n = m->n;
  if (m->ndof == 1) {
    if (r)
      for (size_t i = 0; i < n; i++)
        r[i] = 1.0;
    return 1;
  }
  int nr = m->spec.periodic ? 2 : 3; /* a rotation is not periodic */
  if (r) {
    double cx = 0.5 * m->spec.lx, cy = 0.5 * m->spec.ly;
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

int mfs_model_write_mtx(const mfs_model *m, FILE *fK, FILE *fM)
{
  if (fK) {
    int st = mfs_csr_write_mtx(m->K, fK);
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
