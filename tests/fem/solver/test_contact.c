/* test_contact - frictional penalty contact (fem_contact.h): sliding, stick/slip, the contact
 * tangent against finite differences, a rigid cylinder wall against a closed form, and a
 * failed contact (too deep) as a recoverable failure.
 *
 * 1. Sliding block on a rigid plane. A 10 mm cube (E = 1 MPa, nu = 0.3, tet4 3x3x3) rests on
 *    the plane z = 0 (mu = 0.3, eps_N = eps_T = 10 E / h); its top face is pressed down by
 *    0.1 mm and pushed along x by s.
 *    - stick (s = 5 um; slip would need ~80 um, G A / a * s = mu N): no node slips, the
 *      tangential contact force is below mu N and balances the top reaction (equilibrium, to
 *      the Newton tolerance: 1e-6 of the force);
 *    - slip (s = 1 mm): every bottom node slips and the tangential force equals mu times the
 *      normal force (each slipping node carries mu t_N exactly, so the ratio is exact to
 *      round-off: 1e-9), and the top reactions have the same ratio (equilibrium: 1e-6).
 *    - tangent: fem_solver_check_tangent (central differences, h = 1e-9 m on 1e-2 m) at the
 *      converged stick and slip states: relative error <= 1e-5 (the analytic contact tangent;
 *      the FD error of the check itself is ~1e-8).
 * 2. The same block on a second, deformable block (non-matching meshes 4x4 on 3x3; master =
 *    the lower block's top, node-to-surface, large sliding: s = 3 mm crosses master faces of
 *    3.3 mm): stick and slip as in 1 (slip ratio on the slave side exact, on the master side
 *    by the reactions of the lower block: equilibrium 1e-6), tangent by finite differences
 *    (its blocks are themselves local central differences: 1e-5).
 *    Both again with tet10 (tri6 faces: slave areas and master triangles from the 4 flat
 *    corner/mid-node sub-triangles).
 * 3. Rigid cylinder wall: a cylinder of radius R = 6 mm, height 10 mm (E = 1 MPa, nu = 0.3)
 *    inside a frictionless rigid wall of radius R, compressed axially by eps_z = -1e-4 between
 *    rollers. Closed form (linear elasticity, uniform radial strain e, the wall's penalty
 *    compliance u_R = p_w / eps_N): lambda (2 e + eps_z) + 2 G e = -eps_N R e, so
 *    e = -lambda eps_z / (2 lambda + 2 G + eps_N R); wall pressure p_w = eps_N R e; total
 *    wall normal force p_w 2 pi R H. Checked to 2 % (faceted wall: tributary areas of the
 *    16-segment polygon vs the circle, O(h^2) ~ 1 %; finite strain O(1e-4)); tangent by FD,
 *    with friction mu = 0.3 in stick and in slip (the cylinder pushed along its axis).
 * 4. A penetration deeper than max_penetration: the solve fails recoverably (> 0), the state
 *    is the last converged one.
 * 5. Augmented Lagrangian: the cylinder of 3 with a soft penalty (eps_N R = 2 E), which alone
 *    carries only eps_N R / (2 lambda + 2 G + eps_N R) = 51 % of the rigid wall's force. Uzawa
 *    updates (fem_contact_augment, then a solve at the same loads) must reach the rigid-wall
 *    closed form, no radial strain and wall pressure -lambda eps_z, to 2 % (the faceting of 3),
 *    and cut the largest penetration below 1e-2 of the penalty-only one, in 12 updates. Closed
 *    form of the rate: with multiplier L the wall carries p = L + eps_N u and the cylinder
 *    p = p0 - K u (K = (2 lambda + 2 G) / R), so the error p0 - L of the uniform mode contracts
 *    by K / (K + eps_N) = 0.49 per update; the mean ratio over the first 3 updates must match it
 *    to 5 % (measured 0.50). Later the largest penetration sits at single nodes whose local
 *    stiffness is far above eps_N and contracts by ~0.95 per update (measured): the Uzawa rate
 *    of a mode is K / (K + eps_N), so a penalty far below the stiffness of the structure
 *    converges slowly there. With half updates (fem_contact_augment_damp, omega = 0.5) the
 *    uniform mode contracts by 1 - omega eps_N / (K + eps_N) = 0.745 per update: checked to 5 %
 *    over 3 updates. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cutil.h"
#include "fem.h"
#include "fem_contact.h"
#include "sa_log.h"
#include "tutil.h"

static const double E = 1e6, NU = 0.3, A = 0.01, MU = 0.3;
/* sliding tests: nu = 0, so pressing makes no lateral expansion and a small push sticks
 * everywhere (with nu = 0.3 the rim of the flat punch slips outward under the pressure alone) */
static const double NU_SLIDE = 0.0;

/* FD step of the tangent checks [m] (positions ~1e-2 m). The tet10 block on block after 3 mm
 * of sliding has slave nodes within ~1e-9 m of a sub-triangle edge of the master (a kink of
 * the closest-point map, which the frozen-state pair tangent takes one-sided): the measured
 * error grows with h, 1.5e-7 / 1e-5 / 6e-5 / 1.8e-4 at h = 1e-11 / 1e-10 / 1e-9 / 1e-8, the
 * signature of a crossed kink, not of a wrong tangent (which would not depend on h); that
 * case is checked with h = 1e-11. */
static double g_fd_h = 1e-9;

static int fd_check(FemSolver *s, const char *what, double tol) {
  double err;
  TU_CHECK(fem_solver_check_tangent(s, getenv("CONTACT_FD_H") ? atof(getenv("CONTACT_FD_H")) : g_fd_h, &err));
  if (getenv("CONTACT_VERBOSE")) fprintf(stderr, "%s: FD tangent rel err %.3e\n", what, err);
  if (!(err <= tol)) {
    fprintf(stderr, "%s: tangent vs finite differences: rel err %.3e > %.1e\n", what, err, tol);
    return 1;
  }
  return 0;
}

/* At a committed state a slipping node sits exactly on the slip surface (its anchor was just
 * moved there), where the force is not differentiable. The check is made off it: with mu
 * raised by 1 % every node is strictly in stick, with mu lowered by 1 % the nodes that slipped
 * are strictly in slip (a trial state of the next step). */
static int fd_both(FemSolver *s, FemContact **c, int nc, double mu, const char *what, double tol) {
  int fail = 0;
  char w[160];
  for (int k = 0; k < 2; k++) {
    for (int i = 0; i < nc; i++) TU_CHECK(fem_contact_set_friction(c[i], mu * (k ? 0.99 : 1.01)));
    snprintf(w, sizeof w, "%s, %s", what, k ? "slip (mu - 1 %)" : "stick (mu + 1 %)");
    fail |= fd_check(s, w, tol);
  }
  for (int i = 0; i < nc; i++) TU_CHECK(fem_contact_set_friction(c[i], mu));
  return fail;
}

/* Sum of the reactions over surface S [out] R 3. */
static int surface_reaction(FemSolver *s, const FemMesh *m, const char *surf, double R[3]) {
  double *r = malloc(sizeof(double) * 3 * m->nnodes);
  TU_CHECK(fem_solver_reactions(s, r));
  const FemSurface *S = fem_mesh_find_surface(m, surf);
  R[0] = R[1] = R[2] = 0;
  for (int k = 0; k < S->nnodes; k++)
    for (int i = 0; i < 3; i++) R[i] += r[3 * S->nodes[k] + i];
  free(r);
  return 0;
}

/* Block pushed along x on a plane (lower == NULL) or on the lower block of m. krylov: Newton
 * directions by GMRES on the last LU factors (the frictional tangent is unsymmetric), which
 * must meet every check of the direct path and be taken at least once. */
static int sliding(int on_block, int order, int krylov) {
  int fail = 0;
  FemMesh *mb[2] = {NULL, NULL}, *m = NULL;
  CuBox up = {{0, 0, 0}, {A, A, A}}, lo = {{0, -0.5 * A, -A}, {2 * A, 1.5 * A, 0}};
  /* tet10 block on block: half the cells (the same node spacing, a quarter of the cost) */
  int nu = on_block ? 4 / order : 3, nz = order == 2 && on_block ? 2 : 3;
  SmeshBlock bu = {{nu, nu, nz}, cu_map_box, &up,
                   {"xu0", "xu1", "yu0", "yu1", "bottom", "top"}};
  SmeshBlock bl = {{6 / order, 6 / order, 2 / order}, cu_map_box, &lo, {"xl0", "xl1", "yl0", "yl1", "base", "ltop"}};
  TU_CHECK(smesh_build(1, &bu, order, 1e-12, &mb[0]));
  if (on_block) TU_CHECK(smesh_build(1, &bl, order, 1e-12, &mb[1]));
  const char *names[2] = {"upper", "lower"};
  TU_CHECK(cu_concat(on_block ? 2 : 1, mb, names, &m));
  /* lower block 100 times stiffer: its top stays flat to ~1e-4, so the global reactions have
   * the ratio mu to that accuracy */
  FemMaterial mats[2] = {fem_material_from_e_nu(E, NU_SLIDE, 1000),
                         fem_material_from_e_nu(100 * E, NU_SLIDE, 1000)};
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = 1e-10;
  if (krylov) {
    prm.krylov_max = 30;
    prm.krylov_rtol = 1e-2;
  }
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, mats, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "top", FEM_XYZ));
  if (on_block) TU_CHECK(fem_solver_fix_surface(s, "base", FEM_XYZ));
  double h = A / 3;
  FemContactParams cp = fem_contact_params_default();
  cp.penalty = 10 * E / h;
  cp.friction = MU;
  cp.search_radius = 0.5 * h;
  g_fd_h = on_block && order == 2 ? 1e-11 : 1e-9;
  FemContact *c;
  TU_CHECK(fem_contact_create(m, "bottom", &cp, &c));
  if (on_block) TU_CHECK(fem_contact_set_master(c, "ltop"));
  else TU_CHECK(fem_contact_set_plane(c, (double[3]){0, 0, 0}, (double[3]){0, 0, 1}));
  TU_CHECK(fem_contact_attach(c, s));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *top = fem_mesh_find_surface(m, "top");
  const char *tag = krylov     ? "block on block, GMRES"
                    : on_block ? (order == 2 ? "block on block tet10" : "block on block")
                               : (order == 2 ? "block on plane tet10" : "block on plane");
  double press = 1e-4, push[2] = {5e-6, on_block ? 3e-3 : 1e-3};
  TU_CHECK(fem_solver_set_prescribed(s, top->nnodes, top->nodes, 2, -press));
  TU_CHECK(fem_solver_solve(s));
  for (int phase = 0; phase < 2; phase++) {
    TU_CHECK(fem_solver_set_prescribed(s, top->nnodes, top->nodes, 0, push[phase]));
    TU_CHECK(fem_solver_solve(s));
    FemContactStats st;
    fem_contact_stats(c, &st);
    double Rt[3];
    TU_CHECK(surface_reaction(s, m, "top", Rt));
    char what[128];
    if (getenv("CONTACT_VERBOSE") && phase)
      fprintf(stderr, "%s slip: T / (mu N) - 1 = %.3e, |Rxy| / (mu |Rz|) - 1 = %.3e\n", tag,
              st.tangent_force / (MU * st.normal_force) - 1, hypot(Rt[0], Rt[1]) / (MU * fabs(Rt[2])) - 1);
    if (getenv("CONTACT_VERBOSE"))
      fprintf(stderr, "%s %s: active %d slip %d/%d N %.6g T %.6g F %.6g %.6g %.6g Rtop %.6g %.6g "
              "%.6g pen %.3g\n", tag, phase ? "slip" : "stick", st.n_active, st.n_slip,
              st.n_active, st.normal_force, st.tangent_force, st.force[0], st.force[1],
              st.force[2], Rt[0], Rt[1], Rt[2], st.max_penetration);
    /* equilibrium: the contact force on the block balances the top's reaction */
    for (int i = 0; i < 3; i++) {
      snprintf(what, sizeof what, "%s %s: contact force[%d] + top reaction", tag,
               phase ? "slip" : "stick", i);
      fail |= tu_close(what, st.force[i] + Rt[i], 0, 1e-6 * st.normal_force, 0);
    }
    if (st.n_active == 0) {
      fprintf(stderr, "%s: no contact\n", tag);
      fail = 1;
    }
    if (phase == 0) {
      if (st.n_slip != 0 || !(st.tangent_force < MU * st.normal_force)) {
        fprintf(stderr, "%s stick: %d nodes slip, T/N = %.4g (mu %.2g)\n", tag, st.n_slip,
                st.tangent_force / st.normal_force, MU);
        fail = 1;
      }
      fail |= fd_both(s, &c, 1, MU, tag, 1e-5);
    } else {
      if (st.n_slip != st.n_active) {
        fprintf(stderr, "%s slip: only %d of %d nodes slip\n", tag, st.n_slip, st.n_active);
        fail = 1;
      }
      /* per node |t_T| = mu t_N exactly (the return map); the resultant ratio falls short of
       * mu by the spread of the slip directions (the block yaws slightly: measured 1e-7) */
      const double *tn, *tt;
      int nsl = fem_contact_slaves(c, NULL, NULL, NULL, &tn, &tt, NULL);
      double worst = 0;
      for (int k = 0; k < nsl; k++)
        if (tn[k] > 0) {
          double r = fabs(sqrt(tt[3 * k] * tt[3 * k] + tt[3 * k + 1] * tt[3 * k + 1] +
                               tt[3 * k + 2] * tt[3 * k + 2]) / (MU * tn[k]) - 1);
          if (r > worst) worst = r;
        }
      snprintf(what, sizeof what, "%s slip: max over nodes of | |t_T| / (mu t_N) - 1 |", tag);
      fail |= tu_close(what, worst, 0, 1e-12, 0);
      snprintf(what, sizeof what, "%s slip: T / (mu N)", tag);
      fail |= tu_close(what, st.tangent_force / (MU * st.normal_force), 1.0, 1e-6, 0);
      snprintf(what, sizeof what, "%s slip: top reaction |Rxy| / (mu |Rz|)", tag);
      fail |= tu_close(what, hypot(Rt[0], Rt[1]) / (MU * fabs(Rt[2])), 1.0, on_block ? 1e-3 : 1e-6, 0);
      if (on_block) {
        double Rb[3];
        TU_CHECK(surface_reaction(s, m, "base", Rb));
        snprintf(what, sizeof what, "%s slip: base reaction |Rx| / (mu Rz)", tag);
        fail |= tu_close(what, hypot(Rb[0], Rb[1]) / (MU * fabs(Rb[2])), 1.0, 1e-3, 0);
      }
      fail |= fd_both(s, &c, 1, MU, tag, 1e-5);
    }
  }
  FemSolverStats fs;
  fem_solver_stats(s, &fs);
  if (getenv("CONTACT_VERBOSE"))
    fprintf(stderr, "%s: pattern rebuilds %d, LU %d, Cholesky %d, GMRES %d (%d iterations, %d "
            "abandoned)\n", tag, fs.n_pattern_rebuilds, fs.n_lu, fs.n_chol, fs.n_gmres,
            fs.n_krylov_it, fs.n_krylov_fail);
  if (krylov && (fs.n_gmres == 0 || fs.n_krylov == 0)) {
    fprintf(stderr, "%s: no Newton direction from GMRES (the test should exercise it)\n", tag);
    fail = 1;
  }
  fem_solver_destroy(&s);
  fem_contact_destroy(&c);
  smesh_free(&m);
  smesh_free(&mb[0]);
  smesh_free(&mb[1]);
  return fail;
}

/* The cylinder of 3 (radius R, height H) in its frictionless rigid wall with penalty eps,
 * compressed axially by eps_z = ez and solved once. */
static const double CYL_R = 6e-3, CYL_H = 1e-2, CYL_EZ = -1e-4;
static int cylinder_solved(double eps, FemMesh **mo, FemSolver **so, FemContact *c[4]) {
  const double R = CYL_R, H = CYL_H;
  double cc[3] = {R, H, 0};
  SmeshBlock b = {{8, 8, 4}, cu_map_cyl, cc, {"s0", "s1", "s2", "s3", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &b, 1, 1e-12, &m));
  *mo = m;
  FemMaterial mat = fem_material_from_e_nu(E, NU, 1000);
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = 1e-10;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  *so = s;
  TU_CHECK(fem_solver_fix_surface(s, "bottom", FEM_Z));
  TU_CHECK(fem_solver_fix_surface(s, "top", FEM_Z));
  /* in-plane rigid motions: the centre line (x = y = 0 nodes) fixed in x, y; the +x radius
   * in y (rotation) */
  for (int A2 = 0; A2 < m->nnodes; A2++) {
    const double *X = m->xyz + 3 * A2;
    if (fabs(X[0]) < 1e-9 && fabs(X[1]) < 1e-9) TU_CHECK(fem_solver_fix_nodes(s, 1, &A2, FEM_X | FEM_Y));
    else if (fabs(X[1]) < 1e-9 && X[0] > 0) TU_CHECK(fem_solver_fix_nodes(s, 1, &A2, FEM_Y));
  }
  FemContactParams cp = fem_contact_params_default();
  cp.penalty = eps;
  const char *sides[4] = {"s0", "s1", "s2", "s3"};
  for (int k = 0; k < 4; k++) {
    TU_CHECK(fem_contact_create(m, sides[k], &cp, &c[k]));
    TU_CHECK(fem_contact_set_cylinder(c[k], (double[3]){0, 0, 0}, (double[3]){0, 0, 1}, R, -1, 1));
    TU_CHECK(fem_contact_attach(c[k], s));
  }
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *top = fem_mesh_find_surface(m, "top");
  TU_CHECK(fem_solver_set_prescribed(s, top->nnodes, top->nodes, 2, CYL_EZ * H));
  TU_CHECK(fem_solver_solve(s));
  return 0;
}

static int cylinder(void) {
  int fail = 0;
  const double R = CYL_R, H = CYL_H, ez = CYL_EZ;
  double h = R / 4, eps = 10 * E / h;
  FemMesh *m = NULL;
  FemSolver *s = NULL;
  FemContact *c[4] = {NULL, NULL, NULL, NULL};
  TU_CHECK(cylinder_solved(eps, &m, &s, c));
  double lam = E * NU / ((1 + NU) * (1 - 2 * NU)), G = E / (2 * (1 + NU));
  double e = -lam * ez / (2 * lam + 2 * G + eps * R), pw = eps * R * e;
  double Fn = 0;
  for (int k = 0; k < 4; k++) {
    FemContactStats st;
    fem_contact_stats(c[k], &st);
    Fn += st.normal_force;
  }
  if (getenv("CONTACT_VERBOSE"))
    fprintf(stderr, "cylinder: wall force %.6g N, closed form %.6g N (p_w %.4g Pa, e %.4g)\n", Fn,
            pw * 2 * M_PI * R * H, pw, e);
  fail |= tu_close("cylinder: wall normal force", Fn, pw * 2 * M_PI * R * H, 0, 0.02);
  fail |= fd_check(s, "cylinder frictionless", 1e-5);
  fem_solver_destroy(&s);
  for (int k = 0; k < 4; k++) fem_contact_destroy(&c[k]);
  smesh_free(&m);
  return fail;
}

/* Cylinder with wall friction, pressed against the wall by axial compression, then pushed
 * along the axis: tangent by FD in stick and in slip. */
static int cylinder_friction(void) {
  int fail = 0;
  const double R = 6e-3, H = 1e-2;
  double cc[3] = {R, H, 0};
  SmeshBlock b = {{4, 4, 2}, cu_map_cyl, cc, {"s0", "s1", "s2", "s3", "bottom", "top"}};
  FemMesh *m;
  TU_CHECK(smesh_build(1, &b, 1, 1e-12, &m));
  FemMaterial mat = fem_material_from_e_nu(E, NU, 1000);
  FemSolverParams prm = fem_solver_params_default();
  prm.rtol = 1e-10;
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "top", FEM_XYZ));
  FemContactParams cp = fem_contact_params_default();
  cp.penalty = 10 * E / (R / 2);
  cp.friction = MU;
  const char *sides[4] = {"s0", "s1", "s2", "s3"};
  FemContact *c[4];
  for (int k = 0; k < 4; k++) {
    TU_CHECK(fem_contact_create(m, sides[k], &cp, &c[k]));
    TU_CHECK(fem_contact_set_cylinder(c[k], (double[3]){0, 0, 0}, (double[3]){0, 0, 1}, R, -1, 1));
    TU_CHECK(fem_contact_attach(c[k], s));
  }
  /* a frictionless floor plane so the cylinder is compressed, and slides on it */
  FemContactParams fp = cp;
  fp.friction = 0;
  FemContact *fl;
  TU_CHECK(fem_contact_create(m, "bottom", &fp, &fl));
  TU_CHECK(fem_contact_set_plane(fl, (double[3]){0, 0, 0}, (double[3]){0, 0, 1}));
  TU_CHECK(fem_contact_attach(fl, s));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *top = fem_mesh_find_surface(m, "top");
  TU_CHECK(fem_solver_set_prescribed(s, top->nnodes, top->nodes, 2, -2e-4));
  TU_CHECK(fem_solver_solve(s));
  fail |= fd_both(s, c, 4, MU, "cylinder wall friction, step 1", 1e-5);
  int nslip = 0;
  for (int k = 0; k < 4; k++) {
    FemContactStats st;
    fem_contact_stats(c[k], &st);
    nslip += st.n_slip;
  }
  /* more axial compression: the wall nodes slide down the wall */
  TU_CHECK(fem_solver_set_prescribed(s, top->nnodes, top->nodes, 2, -4e-4));
  TU_CHECK(fem_solver_solve(s));
  int nslip2 = 0, nact = 0;
  for (int k = 0; k < 4; k++) {
    FemContactStats st;
    fem_contact_stats(c[k], &st);
    nslip2 += st.n_slip;
    nact += st.n_active;
  }
  if (getenv("CONTACT_VERBOSE"))
    fprintf(stderr, "cylinder friction: slipping nodes %d after the first step, %d of %d after "
            "the second\n", nslip, nslip2, nact);
  if (nslip2 == 0) {
    fprintf(stderr, "cylinder friction: no wall node slips in the second step\n");
    fail = 1;
  }
  fail |= fd_both(s, c, 4, MU, "cylinder wall friction, step 2", 1e-5);
  fem_solver_destroy(&s);
  for (int k = 0; k < 4; k++) fem_contact_destroy(&c[k]);
  fem_contact_destroy(&fl);
  smesh_free(&m);
  return fail;
}

/* A penetration limit far below the one the load makes: recoverable failure. */
static int too_deep(void) {
  FemMesh *m;
  CuBox up = {{0, 0, 0}, {A, A, A}};
  SmeshBlock b = {{2, 2, 2}, cu_map_box, &up, {"x0", "x1", "y0", "y1", "bottom", "top"}};
  TU_CHECK(smesh_build(1, &b, 1, 1e-12, &m));
  FemMaterial mat = fem_material_from_e_nu(E, NU, 1000);
  FemSolverParams prm = fem_solver_params_default();
  FemSolver *s;
  TU_CHECK(fem_solver_create(m, &mat, &prm, &s));
  TU_CHECK(fem_solver_fix_surface(s, "top", FEM_XYZ));
  FemContactParams cp = fem_contact_params_default();
  cp.penalty = 10 * E / (A / 2);
  cp.max_penetration = 1e-9;
  FemContact *c;
  TU_CHECK(fem_contact_create(m, "bottom", &cp, &c));
  TU_CHECK(fem_contact_set_plane(c, (double[3]){0, 0, 0}, (double[3]){0, 0, 1}));
  TU_CHECK(fem_contact_attach(c, s));
  TU_CHECK(fem_solver_setup(s));
  const FemSurface *top = fem_mesh_find_surface(m, "top");
  TU_CHECK(fem_solver_set_prescribed(s, top->nnodes, top->nodes, 2, -1e-4));
  sa_log_set_level(SA_LOG_ERROR);
  int rc = fem_solver_solve(s);
  sa_error_clear();
  int fail = 0;
  if (rc <= 0) {
    fprintf(stderr, "too deep: solve returned %d, expected a recoverable failure (> 0)\n", rc);
    fail = 1;
  }
  fem_solver_destroy(&s);
  fem_contact_destroy(&c);
  smesh_free(&m);
  return fail;
}

/* omega: the Uzawa step (fem_contact_augment_damp); 1 = the whole update. */
static int cylinder_augmented(double omega) {
  int fail = 0;
  const double R = CYL_R, H = CYL_H, ez = CYL_EZ;
  double eps = 2 * E / R;
  FemMesh *m = NULL;
  FemSolver *s = NULL;
  FemContact *c[4] = {NULL, NULL, NULL, NULL};
  TU_CHECK(cylinder_solved(eps, &m, &s, c));
  double lam = E * NU / ((1 + NU) * (1 - 2 * NU)), G = E / (2 * (1 + NU));
  double F_rigid = -lam * ez * 2 * M_PI * R * H;
  double pen0 = 0, pen = 0, rate = 0, Fn = 0;
  int upd = 0;
  for (;; upd++) {
    Fn = 0;
    pen = 0;
    for (int k = 0; k < 4; k++) {
      FemContactStats st;
      fem_contact_stats(c[k], &st);
      Fn += st.normal_force;
      pen = fmax(pen, st.max_penetration);
    }
    if (upd == 0) {
      pen0 = pen;
      if (getenv("CONTACT_VERBOSE"))
        fprintf(stderr, "augmented cylinder: penalty only %.6g N = %.3f of the rigid wall "
                "(closed form %.3f)\n", Fn, Fn / F_rigid, eps * R / (2 * lam + 2 * G + eps * R));
    }
    if (upd == 3) rate = cbrt(pen / pen0); /* the uniform mode, before the local ones dominate */
    if (getenv("CONTACT_VERBOSE")) fprintf(stderr, "  update %d: penetration %.4g m, force %.6g N\n", upd, pen, Fn);
    if (upd == (omega < 1 ? 3 : 12)) break;
    for (int k = 0; k < 4; k++) {
      TU_CHECK(fem_contact_augment(c[k], NULL, NULL));
      if (omega < 1) TU_CHECK(fem_contact_augment_damp(c[k], omega));
    }
    TU_CHECK(fem_solver_solve(s));
  }
  /* a step omega of the update: e -> e (1 - omega eps_N / (K + eps_N)) */
  double rate_cf = 1 - omega * eps * R / (2 * lam + 2 * G + eps * R);
  if (getenv("CONTACT_VERBOSE"))
    fprintf(stderr, "augmented cylinder: %d updates, wall force %.6g N, rigid closed form %.6g N, "
            "penetration %.3g m (penalty only %.3g m), rate %.4f (closed form %.4f)\n", upd, Fn,
            F_rigid, pen, pen0, rate, rate_cf);
  if (omega < 1) { /* three damped updates: only their rate */
    fail |= tu_close("augmented cylinder, half updates: contraction per update", rate, rate_cf, 0,
                     0.05);
    goto done;
  }
  fail |= tu_close("augmented cylinder: wall normal force vs rigid wall", Fn, F_rigid, 0, 0.02);
  fail |= tu_close("augmented cylinder: contraction per update", rate, rate_cf, 0, 0.05);
  if (!(pen <= 1e-2 * pen0)) {
    fprintf(stderr, "augmented cylinder: penetration %.3g m after %d updates, not below 1e-2 of "
            "the penalty's %.3g m\n", pen, upd, pen0);
    fail = 1;
  }
done:
  fem_solver_destroy(&s);
  for (int k = 0; k < 4; k++) fem_contact_destroy(&c[k]);
  smesh_free(&m);
  return fail;
}

int main(void) {
  sa_log_set_level(getenv("CONTACT_VERBOSE") ? SA_LOG_INFO : SA_LOG_WARN);
  int fail = 0;
  fail |= sliding(0, 1, 0);
  fail |= sliding(1, 1, 0);
  fail |= sliding(0, 2, 0);
  fail |= sliding(1, 2, 0);
  fail |= sliding(1, 1, 1);
  fail |= cylinder();
  fail |= cylinder_friction();
  fail |= too_deep();
  fail |= cylinder_augmented(1.0);
  fail |= cylinder_augmented(0.5);
  return fail;
}
