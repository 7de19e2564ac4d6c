/* fem_fill.c - the [fill] case table (Mohr-Coulomb granular fill, issue 13 key names) and its
 * material (fem_fill.h). Defaults are the reference actuator's fill (/work/shared/ACTUATOR.md):
 * glass beads as a continuum, friction angle 28 deg, a numerical cohesion of 0.1 kPa, dilation
 * angle 3 deg, E = 20 MPa, nu = 0.3, bulk density 1550 kg/m^3. */
#include "fem_fill.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "fem_element.h"
#include "fem_law.h"
#include "fem_mohr_coulomb.h"
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
    {"apex_stiffness", SA_PARAM_REAL, P(apex_stiffness), "-", "0", 0, 1, 0, NULL,
     "tangent at the yield surface's apex (the fill at zero confinement) as this fraction of "
     "the elastic one, instead of the consistent zero that leaves such a region without "
     "stiffness in Newton's system; the stress is the apex's either way (0 = consistent; "
     "docs/mohr_coulomb.md)"},
    {"relaxation_time", SA_PARAM_REAL, P(relaxation_time), "s", "0", 0, INFINITY, 0, NULL,
     "Duvaut-Lions viscoplasticity: the stress above the yield surface relaxes onto it as "
     "exp(-t / relaxation_time); each step's stress is (inviscid + (tau/dt) trial) / (1 + "
     "tau/dt), so the tangent keeps a share of the elastic one (a regularisation of the "
     "perfectly plastic fill; 0 = rate-independent; the actuator scene's time is the piston "
     "displacement over [mc_bending] piston_speed; docs/mohr_coulomb.md)"},
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
  const char *nm[] = {"young",          "poisson",        "friction_angle",
                      "cohesion",       "dilation_angle", "apex_stiffness", "relaxation_time"};
  double v[] = {p->young,    p->poisson,        p->friction_angle,
                p->cohesion, p->dilation_angle, p->apex_stiffness, p->relaxation_time};
  SA_CHECK(fem_material_from_law("mohr_coulomb", 7, nm, v, p->density, mat));
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
    int nq = fem_element_nqp_used(m->etype, X,
                                  fem_solver_material(s, m->region ? m->region[e] : 0));
    double sum = 0;
    for (int q = 0; h && k < nh && q < nq; q++) sum += h[q * nh + k];
    out[e] = h && k < nh ? sum / nq : 0.0;
  }
}

double fem_fill_k0_jaky(double phi_deg) { return 1 - sin(phi_deg * M_PI / 180); }

void fem_fill_rankine(double phi_deg, double *k_active, double *k_passive) {
  double sp = sin(phi_deg * M_PI / 180);
  if (k_active) *k_active = (1 - sp) / (1 + sp);
  if (k_passive) *k_passive = (1 + sp) / (1 - sp);
}

/* Deformation gradient of a tet4 (corners 0..3 of X and x): F = [dx] [dX]^-1. */
static double tet4_F(const double *X, const double *x, double F[9]) {
  double dX[9], dx[9], dXi[9];
  for (int a = 0; a < 3; a++)
    for (int i = 0; i < 3; i++) {
      dX[3 * i + a] = X[3 * (a + 1) + i] - X[i];
      dx[3 * i + a] = x[3 * (a + 1) + i] - x[i];
    }
  double det = dX[0] * (dX[4] * dX[8] - dX[5] * dX[7]) - dX[1] * (dX[3] * dX[8] - dX[5] * dX[6]) +
               dX[2] * (dX[3] * dX[7] - dX[4] * dX[6]);
  dXi[0] = (dX[4] * dX[8] - dX[5] * dX[7]) / det, dXi[1] = (dX[2] * dX[7] - dX[1] * dX[8]) / det;
  dXi[2] = (dX[1] * dX[5] - dX[2] * dX[4]) / det, dXi[3] = (dX[5] * dX[6] - dX[3] * dX[8]) / det;
  dXi[4] = (dX[0] * dX[8] - dX[2] * dX[6]) / det, dXi[5] = (dX[2] * dX[3] - dX[0] * dX[5]) / det;
  dXi[6] = (dX[3] * dX[7] - dX[4] * dX[6]) / det, dXi[7] = (dX[1] * dX[6] - dX[0] * dX[7]) / det;
  dXi[8] = (dX[0] * dX[4] - dX[1] * dX[3]) / det;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double v = 0;
      for (int k = 0; k < 3; k++) v += dx[3 * i + k] * dXi[3 * k + j];
      F[3 * i + j] = v;
    }
  return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
         F[2] * (F[3] * F[7] - F[4] * F[6]);
}

int fem_fill_k0_stress(FemSolver *s, int region, const FemFillParams *p, double z_surface,
                       double k0, double g, int *n_set) {
  const FemMesh *m = fem_solver_mesh(s);
  const double *x = fem_solver_positions(s);
  SA_REQUIRE(m && x && p && k0 >= 0 && g >= 0, SA_ERR_INPUT, "fem_fill_k0_stress: bad arguments");
  if (k0 == 0) k0 = fem_fill_k0_jaky(p->friction_angle);
  const double deg = M_PI / 180;
  FemMohrCoulomb mc = {p->young, p->poisson, p->friction_angle * deg, p->cohesion,
                       p->dilation_angle * deg, p->apex_stiffness, 0};
  int nset = 0, nh = 0, nq = fem_element_nqp(m->etype);
  double *h = malloc(sizeof(double) * (size_t)nq * FEM_MC_NHIST);
  SA_REQUIRE(h, SA_ERR_MEMORY, "K0 initial stress");
  int rc = 0;
  for (int e = 0; e < m->nelem && !rc; e++) {
    if ((m->region ? m->region[e] : 0) != region) continue;
    const double *h_old = fem_solver_history(s, e, &nh);
    if (!h_old || nh != FEM_MC_NHIST) {
      rc = SA_ERROR(SA_ERR_INPUT, "fem_fill_k0_stress: element %d of region %d is not a "
                    "Mohr-Coulomb element", e, region);
      break;
    }
    const int *c = m->conn + (size_t)e * m->nen;
    double Xe[30], xe[30], F[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, J = 1, moved = 0, zc = 0;
    for (int a = 0; a < m->nen; a++)
      for (int i = 0; i < 3; i++) {
        Xe[3 * a + i] = m->xyz[3 * c[a] + i], xe[3 * a + i] = x[3 * c[a] + i];
        moved = fmax(moved, fabs(xe[3 * a + i] - Xe[3 * a + i]));
      }
    for (int a = 0; a < m->nen; a++) zc += xe[3 * a + 2] / m->nen;
    /* a tet4's F is constant; a tet10's varies over it, so only its reference state is taken */
    if (m->etype == FEM_TET4) J = tet4_F(Xe, xe, F);
    else if (moved > 0) {
      rc = SA_ERROR(SA_ERR_INPUT, "fem_fill_k0_stress: a deformed tet10 fill needs F per "
                    "quadrature point (give the stress before the first solve, or use tet4)");
      break;
    }
    if (!(J > 0)) {
      rc = SA_ERROR(SA_ERR_INPUT, "fem_fill_k0_stress: element %d is inverted (det F = %g)", e, J);
      break;
    }
    double sv = -p->density * g * fmax(z_surface - zc, 0); /* Cauchy; Kirchhoff = J sigma */
    double tau0[6] = {J * k0 * sv, J * k0 * sv, J * sv, 0, 0, 0};
    memcpy(h, h_old, sizeof(double) * (size_t)nq * nh);
    for (int q = 0; q < nq && !rc; q++) rc = fem_mc_hist_init_at(&mc, F, tau0, h + (size_t)q * nh);
    if (rc) {
      double ka, kp;
      fem_fill_rankine(p->friction_angle, &ka, &kp);
      sa_error_clear();
      rc = SA_ERROR(SA_ERR_INPUT, "K0 initial stress: lateral ratio %.4g at depth %.4g m is "
                    "outside the yield surface (friction angle %g deg, cohesion %g Pa: the "
                    "cohesionless Rankine range is %.4g .. %.4g)", k0, z_surface - zc,
                    p->friction_angle, p->cohesion, ka, kp);
      break;
    }
    rc = fem_solver_set_history(s, e, h);
    if (sv < 0) nset++;
  }
  free(h);
  if (n_set) *n_set = nset;
  return rc;
}
