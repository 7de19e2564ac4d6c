/* fem_fill.c - the [fill] case table (Mohr-Coulomb granular fill, issue 13 key names) and its
 * material (fem_fill.h). Defaults are the reference actuator's fill (/work/shared/ACTUATOR.md):
 * glass beads as a continuum, friction angle 28 deg, a numerical cohesion of 0.1 kPa, dilation
 * angle 3 deg, E = 20 MPa, nu = 0.3, bulk density 1550 kg/m^3. */
#include "fem_fill.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fem_element.h"
#include "fem_law.h"
#include "sa_error.h"

#define P(f) offsetof(FemFillParams, f)
static const SaParam fill_params[] = {
    {"friction_angle", SA_PARAM_REAL, P(friction_angle), "deg", "28", 0, 90, SA_MAX_OPEN, NULL,
     "Mohr-Coulomb friction angle phi"},
    {"cohesion", SA_PARAM_REAL, P(cohesion), "Pa", "100", 0, INFINITY, 0, NULL,
     "cohesion c (> 0 when friction_angle = 0; a small value regularises a cohesionless fill)"},
    {"dilation_angle", SA_PARAM_REAL, P(dilation_angle), "deg", "3", 0, 90, SA_MAX_OPEN, NULL,
     "dilation angle psi <= friction_angle (psi < phi: non-associated flow, unsymmetric "
     "tangent, UMFPACK)"},
    {"young", SA_PARAM_REAL, P(young), "Pa", "20e6", 0, INFINITY, SA_MIN_OPEN, NULL,
     "Young's modulus (linear in Hencky strain / Kirchhoff stress)"},
    {"poisson", SA_PARAM_REAL, P(poisson), "-", "0.3", -1, 0.5, SA_MIN_OPEN | SA_MAX_OPEN, NULL,
     "Poisson's ratio"},
    {"density", SA_PARAM_REAL, P(density), "kg/m^3", "1550", 0, INFINITY, 0, NULL,
     "bulk density (gravity; the verification scenes are weightless)"},
    {"friction_wall", SA_PARAM_REAL, P(friction_wall), "-", "0.6", 0, 10, 0, NULL,
     "Coulomb friction fill - silicone cavity wall and floor (actuator scene [mc_bending]; "
     "the bead-silicone friction)"},
    {"friction_piston", SA_PARAM_REAL, P(friction_piston), "-", "0.3", 0, 10, 0, NULL,
     "Coulomb friction fill - rigid barrel and piston (actuator scene [mc_bending]; the "
     "bead-piston friction)"},
};
#undef P

const SaParamTable fem_fill_table = {"fill", "fem",
                                     "Mohr-Coulomb granular fill (law mohr_coulomb)", fill_params,
                                     SA_NPARAMS(fill_params)};

int fem_fill_load(const SaCase *c, FemFillParams *p) {
  SA_CHECK(sa_params_load(&fem_fill_table, c, p));
  char w[SA_STR_MAX];
  SA_REQUIRE(p->dilation_angle <= p->friction_angle, SA_ERR_INPUT,
             "%s: [fill] dilation_angle = %g deg (%s): expected a value in [0, friction_angle = "
             "%g deg]", sa_case_path(c), p->dilation_angle,
             sa_case_origin(c, "fill", "dilation_angle", w), p->friction_angle);
  SA_REQUIRE(p->friction_angle > 0 || p->cohesion > 0, SA_ERR_INPUT,
             "%s: [fill] cohesion = 0 with friction_angle = 0: the material has no strength; "
             "expected cohesion > 0 when friction_angle = 0", sa_case_path(c));
  return 0;
}

int fem_fill_material(const FemFillParams *p, FemMaterial *mat) {
  const char *nm[] = {"young", "poisson", "friction_angle", "cohesion", "dilation_angle"};
  double v[] = {p->young, p->poisson, p->friction_angle, p->cohesion, p->dilation_angle};
  SA_CHECK(fem_material_from_law("mohr_coulomb", 5, nm, v, p->density, mat));
  SA_CHECK(fem_material_check(mat));
  return 0;
}

void fem_fill_history_mean(const FemSolver *s, int k, double *out) {
  const FemMesh *m = fem_solver_mesh(s);
  for (int e = 0; e < m->nelem; e++) {
    int nh = 0;
    const double *h = fem_solver_history(s, e, &nh);
    double X[30];
    for (int a = 0; a < m->nen; a++)
      for (int i = 0; i < 3; i++) X[3 * a + i] = m->xyz[3 * m->conn[(size_t)e * m->nen + a] + i];
    int nq = fem_element_nqp_used(m->etype, X);
    double sum = 0;
    for (int q = 0; h && k < nh && q < nq; q++) sum += h[q * nh + k];
    out[e] = h && k < nh ? sum / nq : 0.0;
  }
}
