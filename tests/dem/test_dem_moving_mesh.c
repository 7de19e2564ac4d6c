/* A wall moved node by node (dem_bridge_set_mesh_nodes) pushes a resting sphere.
 *
 * The wall is a square that starts horizontal, far below the sphere; the first update turns
 * it into a plane tilted by 20 degrees (every node moves, by more than the skin: LIGGGHTS must
 * recompute normals and rebuild its neighbour lists), which then advances along its normal n
 * at speed w, its nodes set every step with velocity w n. Frictionless, no gravity.
 * Reference (Galilean invariance): the same sphere striking the same wall at rest with speed w
 * rebounds with e' w (e' is LIGGGHTS' restitution for this impact, measured in the run); the
 * pushed sphere must leave with (1 + e') w along n, since the contact model sees the wall's
 * node velocities. Tolerance 1 %: the two runs differ only in the time discretisation of the
 * wall position (exact at every step) and the contact history. Without the wall velocity in
 * the damping (e' = 0.5) the result would be off by ~ 30 %.
 * Also: LIGGGHTS' node copies equal what was set (exactly), a coarser update (every 10 steps,
 * positions jump) still pushes the sphere along n, and the mesh forces balance the sphere's
 * momentum change (impulse = m dv to 2 %, force sampled every step).
 * The cheap placements (dem_bridge_set_mesh_path + dem_bridge_place_on_path, and
 * dem_bridge_place_flat_mesh for a flat wall) must give LIGGGHTS the same bits as
 * dem_bridge_set_mesh_nodes with the same positions: the same push done both ways ends with the
 * sphere's position and velocity identical to the last bit (and passes the physics check), and
 * a tilted wall is refused as a flat one. */
#include "dem_test_util.h"

static const double TILT = 20 * M_PI / 180, W = 0.2, E_REST = 0.5;

static void params(DemParams *p) {
  t_params(p);
  p->friction = p->friction_wall = p->friction_piston = 0;
  p->rolling_friction = 0;
  p->restitution = E_REST;
  p->gravity[2] = 0;
}

/* Plane through c - s n (n tilted by TILT about x), square of half-size h: 4 vertices. */
static void tilted(const double *c, double s, double h, double *xyz) {
  double n[3] = {0, -sin(TILT), cos(TILT)}, u[3] = {1, 0, 0}, t[3] = {0, cos(TILT), sin(TILT)};
  double o[3] = {c[0] - s * n[0], c[1] - s * n[1], c[2] - s * n[2]};
  double a[4] = {-1, 1, 1, -1}, bb[4] = {-1, -1, 1, 1};
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 3; k++) xyz[3 * i + k] = o[k] + h * (a[i] * u[k] + bb[i] * t[k]);
}

/* Sphere at c pushed by the wall, nodes set every `every` steps; returns its final velocity
 * and the wall impulse along n. */
/* The push's set-up: bridge *b with the pusher (mesh *id, horizontal at z = 0 until the first
 * update) and the sphere at C; node velocities vn [out] 12 (W along n). Returns the steps of
 * the push. */
static const double C[3] = {0, 0, 0.02}, HALF = 8e-3;
static double s_start(const DemParams *p) { return 0.5 * p->diameter + 3e-3; }
static int start_push(const DemParams *p, DemBridge **b, int *id, double vn[12]) {
  const double R = 0.5 * p->diameter, n[3] = {0, -sin(TILT), cos(TILT)};
  double xyz[12];
  int tri[6], ins;
  T_CHECK(dem_bridge_create(t_log(), b));
  T_CHECK(dem_bridge_setup(*b, p));
  t_square(0, 0, 0, HALF, xyz, tri);
  T_CHECK(dem_bridge_add_mesh(*b, "pusher", 4, xyz, 2, tri, DEM_WALL_STEEL, id));
  T_CHECK(dem_bridge_insert_cylinder(*b, C[0], C[1], R, C[2] - R, C[2] + R, 1, &ins));
  t_true("sphere inserted", ins == 1);
  for (int i = 0; i < 4; i++)
    for (int k = 0; k < 3; k++) vn[3 * i + k] = W * n[k];
  return (int)((s_start(p) - R + 2e-3) / W / p->dt) + 300;
}

static void push(int every, double *vel, double *impulse, int check_nodes) {
  DemParams p;
  params(&p);
  const double s0 = s_start(&p), *c = C, h = HALF;
  double n[3] = {0, -sin(TILT), cos(TILT)};
  DemBridge *b = NULL;
  double xyz[12], vn[12];
  int id;
  int nsteps = start_push(&p, &b, &id, vn);
  double J = 0, f[6];
  for (int step = 0; step < nsteps; step += every) {
    double s = s0 - W * step * p.dt;
    tilted(c, s, h, xyz);
    T_CHECK(dem_bridge_set_mesh_nodes(b, id, xyz, vn));
    if (check_nodes && step % 200 == 0) {
      double got[12];
      T_CHECK(dem_bridge_mesh_nodes(b, id, got));
      for (int i = 0; i < 12; i++)
        if (got[i] != xyz[i]) {
          printf("step %d: LIGGGHTS node coordinate %d = %.17g, set %.17g\n", step, i, got[i],
                 xyz[i]);
          t_failures++;
          break;
        }
    }
    for (int k = 0; k < every; k++) {
      T_CHECK(dem_bridge_run(b, 1));
      T_CHECK(dem_bridge_mesh_forces(b, id, f));
      /* force on the wall is minus the force on the sphere */
      J -= p.dt * ((f[0] + f[3]) * n[0] + (f[1] + f[4]) * n[1] + (f[2] + f[5]) * n[2]);
    }
  }
  T_CHECK(dem_bridge_particles(b, NULL, vel, NULL, NULL));
  *impulse = J;
  dem_bridge_destroy(&b);
}

/* The tilted push with the wall on one straight path from s0 to s0 - W T: placed at fraction
 * a = step / nsteps every step, either by dem_bridge_place_on_path (cheap = 1) or by
 * dem_bridge_set_mesh_nodes at x0 + a (x1 - x0) computed here. Sphere position x, velocity v. */
static void push_path(int cheap, double *x, double *vel) {
  DemParams p;
  params(&p);
  const double s0 = s_start(&p), *c = C, h = HALF;
  DemBridge *b = NULL;
  double xyz[12], x0[12], x1[12], vn[12];
  int id;
  int nsteps = start_push(&p, &b, &id, vn);
  tilted(c, s0, h, x0);
  tilted(c, s0 - W * nsteps * p.dt, h, x1);
  if (cheap) T_CHECK(dem_bridge_set_mesh_path(b, id, x0, x1, vn));
  for (int step = 0; step < nsteps; step++) {
    double a = (double)step / nsteps;
    if (cheap) {
      T_CHECK(dem_bridge_place_on_path(b, id, a));
    } else {
      for (int k = 0; k < 12; k++) xyz[k] = x0[k] + a * (x1[k] - x0[k]);
      T_CHECK(dem_bridge_set_mesh_nodes(b, id, xyz, vn));
    }
    T_CHECK(dem_bridge_run(b, 1));
  }
  T_CHECK(dem_bridge_particles(b, x, vel, NULL, NULL));
  dem_bridge_destroy(&b);
}

/* A horizontal plate below the sphere lifted at speed W, placed every step by
 * dem_bridge_place_flat_mesh (cheap = 1) or dem_bridge_set_mesh_nodes. */
static void lift(int cheap, double *x, double *vel) {
  DemParams p;
  params(&p);
  const double R = 0.5 * p.diameter, c[3] = {0, 0, 0.02}, z0 = c[2] - R - 2e-3, h = 8e-3;
  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  T_CHECK(dem_bridge_setup(b, &p));
  double xyz[12], v[12] = {0};
  int tri[6], id, ins;
  t_square(0, 0, z0, h, xyz, tri);
  T_CHECK(dem_bridge_add_mesh(b, "lifter", 4, xyz, 2, tri, DEM_WALL_STEEL, &id));
  T_CHECK(dem_bridge_insert_cylinder(b, c[0], c[1], R, c[2] - R, c[2] + R, 1, &ins));
  for (int i = 0; i < 4; i++) v[3 * i + 2] = W;
  int nsteps = (int)(4e-3 / W / p.dt) + 300;
  for (int step = 0; step < nsteps; step++) {
    double z = z0 + W * step * p.dt;
    if (cheap) {
      T_CHECK(dem_bridge_place_flat_mesh(b, id, z, W));
    } else {
      for (int i = 0; i < 4; i++) xyz[3 * i + 2] = z;
      T_CHECK(dem_bridge_set_mesh_nodes(b, id, xyz, v));
    }
    T_CHECK(dem_bridge_run(b, 1));
  }
  T_CHECK(dem_bridge_particles(b, x, vel, NULL, NULL));
  dem_bridge_destroy(&b);
}

static int same_bits(const double *a, const double *b, int n) {
  return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

/* Reference: the sphere strikes the same wall at rest with speed W along -n. */
static double rebound(void) {
  DemParams p;
  params(&p);
  const double R = 0.5 * p.diameter, c[3] = {0, 0, 0.02}, h = 8e-3;
  double n[3] = {0, -sin(TILT), cos(TILT)}, xyz[12];
  int tri[6] = {0, 1, 2, 0, 2, 3}, id, ins;
  tilted(c, R + 0.2e-3, h, xyz);
  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  T_CHECK(dem_bridge_setup(b, &p));
  T_CHECK(dem_bridge_add_mesh(b, "wall", 4, xyz, 2, tri, DEM_WALL_STEEL, &id));
  T_CHECK(dem_bridge_insert_cylinder(b, c[0], c[1], R, c[2] - R, c[2] + R, 1, &ins));
  char cmd[160];
  snprintf(cmd, sizeof cmd, "velocity all set %.17g %.17g %.17g", -W * n[0], -W * n[1], -W * n[2]);
  T_CHECK(dem_bridge_command(b, cmd));
  T_CHECK(dem_bridge_run(b, (int)(0.2e-3 / W / p.dt) + 300));
  double v[3];
  T_CHECK(dem_bridge_particles(b, NULL, v, NULL, NULL));
  dem_bridge_destroy(&b);
  return (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]) / W;
}

int main(void) {
  DemParams p;
  params(&p);
  double n[3] = {0, -sin(TILT), cos(TILT)};
  double R = 0.5 * p.diameter, m = p.density * 4.0 / 3.0 * M_PI * R * R * R;
  double e = rebound();
  t_close("restitution of the static-wall reference (LIGGGHTS' damping law, 10 %)", e, E_REST, 0,
          0.1);

  double v[3], J;
  push(1, v, &J, 1);
  double vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  double vt = sqrt(fmax(0, v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - vn * vn));
  t_close("pushed sphere speed along n [m/s] ((1 + e') w, Galilean invariance, 1 %)", vn,
          (1 + e) * W, 0, 0.01);
  t_close("pushed sphere speed across n [m/s] (frictionless: 0)", vt, 0, 1e-6 * W, 0);
  t_close("wall impulse along n [N s] (= m dv, 2 %)", J, m * vn, 0, 0.02);
  if (t_verbose())
    printf("moving mesh: e' %.5f, v_n %.6g (ref %.6g, rel %.3g), v_t %.3g, impulse %.6g "
           "(m dv %.6g)\n",
           e, vn, (1 + e) * W, vn / ((1 + e) * W) - 1, vt, J, m * vn);

  push(10, v, &J, 0);
  vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  vt = sqrt(fmax(0, v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - vn * vn));
  t_true("coarse updates (every 10 steps): the sphere leaves along n faster than the wall",
         vn > W && vn < 2.5 * W && vt < 1e-3 * vn);
  if (t_verbose()) printf("moving mesh, every 10 steps: v_n %.6g, v_t %.3g\n", vn, vt);

  /* the cheap placements: the same bits as node-by-node updates, and the same physics */
  double xa[3], va[3], xb[3], vb[3];
  push_path(0, xa, va);
  push_path(1, xb, vb);
  t_true("wall on a path (dem_bridge_place_on_path): sphere position and velocity identical "
         "to dem_bridge_set_mesh_nodes at the same positions",
         same_bits(xa, xb, 3) && same_bits(va, vb, 3));
  vn = vb[0] * n[0] + vb[1] * n[1] + vb[2] * n[2];
  t_close("path-placed wall: sphere speed along n ((1 + e') w, 1 %)", vn, (1 + e) * W, 0, 0.01);
  lift(0, xa, va);
  lift(1, xb, vb);
  t_true("flat wall (dem_bridge_place_flat_mesh): sphere position and velocity identical to "
         "dem_bridge_set_mesh_nodes at the same height",
         same_bits(xa, xb, 3) && same_bits(va, vb, 3));
  t_close("lifted sphere speed ((1 + e') w, 1 %)", vb[2], (1 + e) * W, 0, 0.01);
  if (t_verbose())
    printf("cheap placements: path v_n %.9g, flat v_z %.9g (ref %.9g)\n", vn, vb[2],
           (1 + e) * W);
  {
    DemBridge *b = NULL;
    double xyz[12];
    int tri[6], id;
    T_CHECK(dem_bridge_create(t_log(), &b));
    T_CHECK(dem_bridge_setup(b, &p));
    tilted((double[]){0, 0, 0.02}, 5e-3, 8e-3, xyz);
    t_square(0, 0, 0, 8e-3, (double[12]){0}, tri);
    T_CHECK(dem_bridge_add_mesh(b, "tilted", 4, xyz, 2, tri, DEM_WALL_STEEL, &id));
    t_true("a tilted wall is refused as a flat one (SA_ERR_INPUT)",
           dem_bridge_place_flat_mesh(b, id, 0.01, 0) == SA_ERR_INPUT);
    t_true("a path fraction outside [0, 1] is refused", 
           dem_bridge_set_mesh_path(b, id, xyz, xyz, NULL) == 0 &&
               dem_bridge_place_on_path(b, id, 1.5) == SA_ERR_INPUT);
    sa_error_clear();
    dem_bridge_destroy(&b);
  }
  return t_failures ? 1 : 0;
}
