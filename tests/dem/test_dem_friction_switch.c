/* dem_bridge_scale_friction: a sphere on a plate under gravity tilted by theta slides without
 * friction and rolls once the friction is switched back on.
 *
 * Reference (rigid-body mechanics of a sphere on an incline, e.g. Goldstein, or any text on
 * rolling): with no friction the contact force is normal, so the sphere slides with
 *   a = g sin(theta)   and no spin;
 * with Coulomb friction mu >= (2/7) tan(theta) it ends up rolling without slip, where the
 * friction force f = m g sin(theta) - m a and the spin I alpha = f R with I = 2/5 m R^2 and
 * alpha = a / R give
 *   a = 5/7 g sin(theta).
 * Here theta = 10 deg and mu = 0.3 (rolling needs mu >= 0.050). The accelerations are measured
 * as velocity differences over windows of 0.04 s after the normal bounce and the slide-to-roll
 * transition (both last well under 0.01 s) and checked to 1 %. The tangential Mindlin spring
 * makes the rolling sphere's speed ripple slightly, which is what the window averages out. */
#include "dem_test_util.h"

static double vx(DemBridge *b) {
  double v[3];
  T_CHECK(dem_bridge_particles(b, NULL, v, NULL, NULL));
  return v[0];
}

/* mean x-acceleration over n steps of length dt */
static double accel(DemBridge *b, int n, double dt) {
  double v0 = vx(b);
  T_CHECK(dem_bridge_run(b, n));
  return (vx(b) - v0) / (n * dt);
}

int main(void) {
  DemParams p;
  t_params(&p);
  p.friction = p.friction_wall = p.friction_piston = 0.3;
  const double theta = 10 * M_PI / 180, g = 9.81;
  p.gravity[0] = g * sin(theta), p.gravity[1] = 0, p.gravity[2] = -g * cos(theta);
  const double R = 0.5 * p.diameter;

  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  T_CHECK(dem_bridge_setup(b, &p));
  t_true("a friction scale outside [0, 1] is refused",
         dem_bridge_scale_friction(b, 1.5) == SA_ERR_INPUT);
  sa_error_clear();
  T_CHECK(dem_bridge_scale_friction(b, 0));
  double xyz[12];
  int tri[6], id, ins;
  t_square(0, 0, 0, 0.045, xyz, tri);
  T_CHECK(dem_bridge_add_mesh(b, "plate", 4, xyz, 2, tri, DEM_WALL_STEEL, &id));
  T_CHECK(dem_bridge_insert_cylinder(b, -0.04, 0, 1.01 * R, 0.01e-3, 0.01e-3 + p.diameter, 1,
                                     &ins));
  t_true("one sphere inserted", ins == 1);

  const int win = (int)(0.04 / p.dt);
  T_CHECK(dem_bridge_run(b, (int)(0.01 / p.dt))); /* the drop of 0.01 mm and its bounce */
  double a_slide = accel(b, win, p.dt);
  T_CHECK(dem_bridge_scale_friction(b, 1));
  T_CHECK(dem_bridge_run(b, (int)(0.01 / p.dt))); /* slip until rolling */
  double a_roll = accel(b, win, p.dt);
  if (t_verbose())
    printf("a/(g sin theta): frictionless %.6f (1), after the switch %.6f (5/7 = %.6f)\n",
           a_slide / (g * sin(theta)), a_roll / (g * sin(theta)), 5.0 / 7.0);
  t_close("frictionless slide a = g sin(theta)", a_slide, g * sin(theta), 0, 0.01);
  t_close("rolling after the switch a = 5/7 g sin(theta)", a_roll, 5.0 / 7.0 * g * sin(theta), 0,
          0.01);
  dem_bridge_destroy(&b);
  return t_failures ? 1 : 0;
}
