#include "mfs_material.h"

int mfs_physics_ndof(mfs_physics_kind kind)
{
  return kind == MFS_PHYS_PLANE_STRAIN ? 2 : 1;
}

double mfs_material_lambda(const mfs_material *m)
{
  if (m->physics != MFS_PHYS_PLANE_STRAIN)
    return 0.0;
  return 2.0 * m->modulus * m->poisson / (1.0 - 2.0 * m->poisson);
}
