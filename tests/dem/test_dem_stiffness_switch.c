/* dem_bridge_set_young: a grain resting on a flat wall under gravity has the static Hertz
 * overlap of its modulus before and after the modulus is changed mid-run.
 *
 * Reference (Hertz, Johnson 1985 sec. 4.2): a sphere of weight W = m g on a flat wall,
 *   W = 4/3 E* sqrt(R) delta^(3/2),  1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w
 *   => delta = (3 W / (4 E* sqrt(R)))^(2/3).
 * With restitution 0.3 the bounce dies out within the settle time; the remaining oscillation
 * and the contact's viscous term at rest are zero, so the overlap matches to the round-off of
 * the integration (checked to 1 %). The modulus is changed by 10x: the overlap must follow
 * (a factor 10^(2/3) = 4.64), which also shows the walls' modulus was switched; and the
 * force read back from the wall carries the grain's weight m g before and after. */
#include "dem_test_util.h"

static double settle_overlap(DemBridge *b, int steps) {
  T_CHECK(dem_bridge_run(b, steps));
  return dem_bridge_max_overlap(b);
}

int main(void) {
  DemParams p;
  t_params(&p);
  p.diameter = 4e-3;
  p.young = 5e6;
  p.poisson = 0.3;
  p.wall_young = 5e6;
  p.wall_poisson = 0.3;
  p.restitution = 0.3;
  p.friction = p.friction_wall = p.friction_piston = 0.3;
  p.rolling_friction = 0;
  p.gravity[0] = p.gravity[1] = 0, p.gravity[2] = -9.81;
  p.dt = 0.1 * dem_rayleigh_dt(p.diameter, p.density, p.young, p.poisson);
  p.skin = 0.5e-3;
  const double R = 0.5 * p.diameter, m = p.density * 4.0 / 3.0 * M_PI * R * R * R;

  DemBridge *b = NULL;
  int id;
  t_sphere_on_plate(&p, -0.004, 0.004, 0.01e-3, &b, &id);

  double E[2] = {p.young, 10 * p.young};
  for (int k = 0; k < 2; k++) {
    if (k == 1) {
      double dt = 0.1 * dem_rayleigh_dt(p.diameter, p.density, E[1], p.poisson);
      /* an unsafe step for the stiffer grains is refused */
      t_true("a time step above the Rayleigh limit of the new modulus is refused",
             dem_bridge_set_young(b, E[1], 10 * dt) == SA_ERR_INPUT);
      sa_error_clear();
      T_CHECK(dem_bridge_set_young(b, E[1], dt));
    }
    double estar = 1.0 / (2 * (1 - p.poisson * p.poisson) / E[k]);
    double ref = pow(3 * m * 9.81 / (4 * estar * sqrt(R)), 2.0 / 3.0) / p.diameter;
    double got = settle_overlap(b, 40000);
    if (getenv("DEM_TEST_VERBOSE"))
      printf("E = %g Pa: overlap/d %.6g, Hertz %.6g\n", E[k], got, ref);
    t_close(k ? "overlap after the switch" : "overlap before the switch", got, ref, 0, 0.01);
    /* the overlap check names its contact: the plate, at the grain's centre */
    double at[3], x[3];
    const char *site = dem_bridge_overlap_site(b, at);
    T_CHECK(dem_bridge_particles(b, x, NULL, NULL, NULL));
    t_true("the largest overlap is named as the plate's", strcmp(site, "mesh_plate") == 0);
    t_close("the largest overlap's grain position (z)", at[2], x[2], 1e-15, 0);
    /* the wall force read back carries the weight (the stress module survives the switch) */
    double f[6];
    T_CHECK(dem_bridge_mesh_forces(b, id, f));
    t_close(k ? "wall force after the switch" : "wall force before the switch", -(f[2] + f[5]),
            m * 9.81, 0, 1e-3);
  }
  dem_bridge_destroy(&b);
  return t_failures ? 1 : 0;
}
