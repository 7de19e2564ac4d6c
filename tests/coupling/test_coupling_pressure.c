/* test_coupling_pressure - the coupling surface carries a pressure like the solver's own
 * follower pressure.
 *
 * The actuator (meshes/actuator.geo, coarse) under a small cavity pressure p, two ways:
 *  A. the solver's follower pressure on cavity_wall (reference: verified against CalculiX,
 *     docs/calculix.md);
 *  B. the same pressure as flat-triangle forces F_t = -p A_t n_t on the coupling surface's
 *     triangles at the reference configuration, scattered to the nodes (fem_coupling.h) and
 *     applied as dead nodal loads.
 * At a small load the follower and dead loads differ at second order in the displacement, and
 * the flat-triangle forces converge to the consistent tri6 load at first order in h, so the
 * cavity volume changes must agree to a few per cent (tolerance 10 %: p = 200 Pa gives a
 * volume change of ~0.06 %, where the follower correction is ~1e-3 relative; the flat-triangle
 * geometry error at this mesh size is the larger term, measured ~2 %). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fem.h"
#include "fem_actuator.h"
#include "fem_coupling.h"
#include "sa_log.h"
#include "tutil.h"

#ifndef ACTUATOR_GEO
#error "ACTUATOR_GEO must name meshes/actuator.geo"
#endif

static int build(FemMesh *m, const FemMaterial *mats, FemSolver **s) {
  FemSolverParams prm = fem_solver_params_default();
  prm.threads = 2;
  TU_CHECK(fem_solver_create(m, mats, &prm, s));
  TU_CHECK(fem_solver_fix_surface(*s, "fixed_end", FEM_XYZ));
  TU_CHECK(fem_solver_add_pressure_surface(*s, "cavity_wall"));
  TU_CHECK(fem_solver_setup(*s));
  return 0;
}

int main(void) {
  sa_log_set_level(SA_LOG_WARN);
  FemMesh *m = NULL;
  FemGeoParam gp[] = {{"rings", 1}, {"h_band", 3e-3}, {"h_ring", 3e-3}};
  TU_CHECK(fem_mesh_generate(ACTUATOR_GEO, 3, gp, 6e-3, 2, &m));
  FemMaterial *mats = calloc((size_t)m->nregions, sizeof *mats);
  FemActuatorCase ac;
  TU_CHECK(sa_params_defaults(&fem_actuator_mesh_table, &ac.mesh));
  TU_CHECK(sa_params_defaults(&fem_actuator_material_table, &ac.mat));
  TU_CHECK(sa_params_defaults(&fem_actuator_solver_table, &ac.solver));
  TU_CHECK(fem_actuator_materials(&ac, m, mats));
  const double p = 200;
  FemSolver *a = NULL, *b = NULL;
  if (build(m, mats, &a) || build(m, mats, &b)) return 1;
  double V0 = fem_solver_cavity_volume(a);
  TU_CHECK(fem_solver_set_pressure(a, p));
  TU_CHECK(fem_solver_solve(a));
  double dVa = fem_solver_cavity_volume(a) - V0;

  const char *wall[] = {"cavity_wall"};
  FemCouplingSurface *c = NULL;
  TU_CHECK(fem_coupling_surface_create(m, 1, wall, &c));
  int nv = fem_coupling_surface_nverts(c), nt = fem_coupling_surface_ntri(c);
  double *xw = malloc(sizeof(double) * 3 * nv), *ft = malloc(sizeof(double) * 3 * nt),
         *fn = malloc(sizeof(double) * 3 * nv);
  fem_coupling_surface_gather(c, m->xyz, xw);
  for (int t = 0; t < nt; t++) {
    double n[3], A = fem_coupling_surface_tri_area(c, xw, t, n);
    for (int d = 0; d < 3; d++) ft[3 * t + d] = -p * A * n[d];
  }
  fem_coupling_surface_scatter(c, ft, fn);
  TU_CHECK(fem_solver_set_nodal_forces(b, nv, fem_coupling_surface_nodes(c), fn));
  TU_CHECK(fem_solver_solve(b));
  double dVb = fem_solver_cavity_volume(b) - V0;
  double angA, angB;
  TU_CHECK(fem_bending_angle(m, "tip", fem_solver_positions(a), &angA));
  TU_CHECK(fem_bending_angle(m, "tip", fem_solver_positions(b), &angB));
  if (getenv("SA_TEST_VERBOSE"))
    printf("dV follower %.6g m^3, coupling %.6g m^3 (%.3f %%); angle %.5f vs %.5f deg\n", dVa,
           dVb, 100 * (dVb / dVa - 1), angA, angB);
  int fail = tu_close("cavity volume change through the coupling surface", dVb, dVa, 0, 0.10);
  fail |= tu_close("bending angle through the coupling surface", angB, angA, 0, 0.10);
  free(xw), free(ft), free(fn), free(mats);
  fem_coupling_surface_destroy(&c);
  fem_solver_destroy(&a);
  fem_solver_destroy(&b);
  fem_mesh_destroy(&m);
  return fail;
}
