/* Materials of the linearized models: the physics (which field moves) and
 * the elastic constants, in SI units.
 *
 *   scalar        one displacement per particle: the 1D bar (u_x, modulus
 *                 E) or 2D anti-plane shear (u_z, shear modulus mu; paper
 *                 003 eq. 113)
 *   plane strain  (u_x, u_y) per particle, shear modulus mu and Poisson's
 *                 ratio nu: Lame lambda = 2 mu nu / (1 - 2 nu) */
#ifndef MFS_MATERIAL_H
#define MFS_MATERIAL_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { MFS_PHYS_SCALAR, MFS_PHYS_PLANE_STRAIN } mfs_physics_kind;

typedef struct {
  mfs_physics_kind physics;
  double modulus;        /* E of the 1D bar, shear modulus mu in 2D (Pa); > 0 */
  double poisson;        /* nu of plane strain, in (-1, 0.5) */
  double density;        /* rho (kg/m^3); > 0 */
  double initial_stress; /* uniform initial stress S0 of the 1D rod (Pa) */
} mfs_material;

/* Degrees of freedom per particle: 1 (scalar) or 2 (plane strain). */
int mfs_physics_ndof(mfs_physics_kind kind);

/* Lame lambda of plane strain, 2 mu nu / (1 - 2 nu); 0 for scalar physics. */
double mfs_material_lambda(const mfs_material *m);

#ifdef __cplusplus
}
#endif

#endif
