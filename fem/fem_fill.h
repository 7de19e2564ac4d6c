/* fem_fill.h - the Mohr-Coulomb granular fill as case keys ([fill], issue 13) and the
 * verification scenes built on it:
 *   [triaxial]  drained triaxial compression of a cube (fem_triaxial.c, cases/mc_triaxial.ini)
 *   [footing]   rigid strip footing on a weightless layer (fem_footing.c, cases/mc_footing.ini)
 * and the actuator's continuum scene:
 *   [mc_bending] the fill in the bore pushed by the piston (fem_mc_scene.c,
 *                cases/granular_bending_mc.ini)
 * The [fill] table is shared (listed once in `softact keys`); the actuator's continuum scene can
 * read the same section. The law is "mohr_coulomb" from the registry (fem_law.h,
 * fem_mohr_coulomb.h); docs/mohr_coulomb.md has the model and the measured results. */
#ifndef FEM_FILL_H
#define FEM_FILL_H

#include "fem.h"
#include "sa_module.h"
#include "sa_params.h"

typedef struct {
  double friction_angle; /* [deg] */
  double cohesion;       /* [Pa] */
  double dilation_angle; /* [deg] */
  double young;          /* [Pa] */
  double poisson;        /* [-] */
  double apex_stiffness; /* [-] the law's apex tangent (fem_mohr_coulomb.h) */
  double relaxation_time; /* [s] Duvaut-Lions relaxation time (0: rate-independent) */
  double density;        /* [kg/m^3] */
  double friction_wall;   /* [-] Coulomb coefficient fill - silicone cavity (actuator scene) */
  double friction_piston; /* [-] fill - rigid barrel and piston (actuator scene) */
} FemFillParams;

extern const SaParamTable fem_fill_table; /* [fill] */

/* Load [fill] of case c [in] into p [out] with the cross-key checks (dilation_angle <=
 * friction_angle; cohesion > 0 when friction_angle = 0): SA_ERR_INPUT naming file, keys and
 * the allowed range. */
int fem_fill_load(const SaCase *c, FemFillParams *p);
/* The region material of the fill: law mohr_coulomb with p [in]; mat [out]. */
int fem_fill_material(const FemFillParams *p, FemMaterial *mat);
/* Mean of history value k over the used quadrature points of every element of s: out [out]
 * nelem values (e.g. k = 6: equivalent plastic strain). */
void fem_fill_history_mean(const FemSolver *s, int k, double *out);

/* The settled (geostatic) stress of the fill, region `region` of s [in/out], at the current
 * positions (a K0 procedure: the stress is replaced, the shape kept): at each element's current
 * centroid, depth = z_surface - z (zero above the surface), vertical Cauchy stress
 * sv = -density g depth, lateral k0 sv (z up; k0 = 0: Jaky's 1 - sin phi), written as the
 * Mohr-Coulomb history at the element's F (fem_mc_hist_init_at) at every quadrature point, so
 * the field is piecewise constant per element. Before any solve (F = I) for tet4 and tet10;
 * in a deformed state tet4 only (a tet10's F varies over it). A k0 outside the Rankine range
 * (the state outside the yield surface) is SA_ERR_INPUT naming the allowed range. The solver
 * then has to balance it (a solve at the same loads). n_set [out, may be NULL]: elements given
 * a nonzero stress. */
int fem_fill_k0_stress(FemSolver *s, int region, const FemFillParams *p, double z_surface,
                       double k0, double g, int *n_set);
/* Jaky's K0 = 1 - sin phi and the Rankine active / passive ratios of cohesionless soil,
 * (1 -+ sin phi) / (1 +- sin phi), for friction angle phi_deg [deg]. */
double fem_fill_k0_jaky(double phi_deg);
void fem_fill_rankine(double phi_deg, double *k_active, double *k_passive);

extern const SaModule fem_triaxial_module; /* trigger [triaxial] */
extern const SaModule fem_footing_module;  /* trigger [footing] */
extern const SaModule fem_mc_bending_module; /* trigger [mc_bending] (extends [mesh]) */

#endif
