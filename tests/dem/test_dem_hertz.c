/* Hertz impact of one sphere on a triangulated wall (two triangles, dem_bridge_add_mesh),
 * measured through the per-triangle wall forces (dem_bridge_mesh_forces).
 *
 * Reference (Johnson, Contact Mechanics, 1985, sec. 11.4), sphere of mass m and radius R
 * against a flat wall, normal speed v:
 *   1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w,  R* = R,  m* = m,
 *   delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5),  F_max = 4/3 E* sqrt(R*) delta_max^1.5,
 *   t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5)      (dem_hertz_wall_contact_time; 2.868 exactly).
 * The wall has its own E_w, nu_w, so the general E* is exercised.
 * The closed forms are elastic; LIGGGHTS' contact is damped to give restitution e = 0.99:
 * about 1 - e^2 = 2 % of the energy is dissipated over the whole contact, about half of it
 * before maximum compression, so delta_max drops by ~ 0.4 % and F_max by ~ 0.6 %; the viscous
 * force (~ 2 beta sqrt(k m) v, beta = ln e / sqrt(ln^2 e + pi^2) = -0.0032) shifts the force
 * zero crossings by ~ 0.3 % of t_c. With 1 step = 0.4 % of t_c, both are checked to 2 %.
 * Rebound: v_out / v_in against e; LIGGGHTS sets the damping from e with the linear-spring
 * relation, which for the Hertz spring is exact in the limit (Antypov & Elliott 2011 find a
 * few % of (1 - e) for moderate e): checked as (1 - v_out/v_in) against (1 - e) to 15 %.
 * Order map: the sphere strikes the second triangle; the first must carry no force.
 * Twice: on a steel wall (DEM_WALL_STEEL: wall_young, wall_poisson) and on a compliant silicone
 * wall (DEM_WALL_SILICONE with silicone_young > 0: silicone_young, silicone_poisson, 4x softer),
 * the two wall types' moduli set apart so that a mix-up shows. The largest overlap from the
 * positions (dem_bridge_max_overlap) must reach delta_max / d on the steel wall and leave the
 * silicone wall out, whose largest indentation (dem_bridge_max_indentation) reaches it instead. */
#include "dem_test_util.h"

static void impact(DemWallType type) {
  const char *w = type == DEM_WALL_SILICONE ? "silicone wall: " : "steel wall: ";
  char what[200];
  DemParams p;
  t_params(&p);
  p.diameter = 4e-3;
  p.young = 1e7;
  p.poisson = 0.3;
  p.wall_young = 2e7;
  p.wall_poisson = 0.25;
  p.silicone_young = 5e6;
  p.silicone_poisson = 0.45;
  p.restitution = 0.99;
  p.friction = p.friction_wall = p.friction_piston = 0.3;
  p.gravity[2] = 0;
  p.dt = 2e-6;
  p.skin = 0.5e-3;
  const double v = 0.5, R = 0.5 * p.diameter, gap = 0.1e-3;
  const double cx = -0.004, cy = 0.004; /* above triangle 1 (y > x), away from its edges */

  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  T_CHECK(dem_bridge_setup(b, &p));
  double xyz[12];
  int tri[6], id;
  t_square(0, 0, 0, 0.01, xyz, tri);
  T_CHECK(dem_bridge_add_mesh(b, "plate", 4, xyz, 2, tri, type, &id));
  int ins;
  T_CHECK(dem_bridge_insert_cylinder(b, cx, cy, R, gap, gap + p.diameter, 1, &ins));
  t_true("one sphere inserted", ins == 1);
  char cmd[128];
  snprintf(cmd, sizeof cmd, "velocity all set 0 0 %.17g", -v);
  T_CHECK(dem_bridge_command(b, cmd));

  double f[6], fpeak = 0, f_other = 0, ov_max = 0, ind_max = 0, site[3] = {NAN, NAN, NAN};
  int nforce = 0, steps = 0, ended = 0;
  while (steps < 2000 && !ended) {
    T_CHECK(dem_bridge_run(b, 1));
    steps++;
    ov_max = fmax(ov_max, dem_bridge_max_overlap(b));
    double ind = dem_bridge_max_indentation(b);
    if (ind > ind_max) { /* where the deepest bead is: above the plate (z = 0) by R - delta */
      ind_max = ind;
      dem_bridge_indentation_site(b, site);
    }
    T_CHECK(dem_bridge_mesh_forces(b, id, f));
    double fz = -f[5]; /* the sphere pushes the wall down */
    f_other = fmax(f_other, fabs(f[0]) + fabs(f[1]) + fabs(f[2]));
    if (fz > 0 || fabs(f[3]) + fabs(f[4]) > 0) nforce++;
    if (fz > fpeak) fpeak = fz;
    if (nforce > 0 && f[5] == 0 && f[3] == 0 && f[4] == 0) ended = 1;
  }
  T_CHECK(dem_bridge_run(b, 10));
  double vel[3], x[3];
  T_CHECK(dem_bridge_particles(b, x, vel, NULL, NULL));

  double m = p.density * 4.0 / 3.0 * M_PI * R * R * R;
  int sil = type == DEM_WALL_SILICONE;
  double Ew = sil ? p.silicone_young : p.wall_young, nuw = sil ? p.silicone_poisson : p.wall_poisson;
  double es = 1.0 / ((1 - p.poisson * p.poisson) / p.young + (1 - nuw * nuw) / Ew);
  double dmax = pow(15 * m * v * v / (16 * es * sqrt(R)), 0.4);
  double fref = 4.0 / 3.0 * es * sqrt(R) * pow(dmax, 1.5);
  double tref = dem_hertz_wall_contact_time(p.diameter, p.density, p.young, p.poisson, Ew, nuw, v);
  double tc = nforce * p.dt;

  snprintf(what, sizeof what, "%scontact ended", w);
  t_true(what, ended);
  snprintf(what, sizeof what, "%speak wall force [N] (Hertz, 2 %%: damping e = 0.99, see header)", w);
  t_close(what, fpeak, fref, 0, 0.02);
  snprintf(what, sizeof what, "%scontact time [s] (Hertz, 2 %%: 1 step = 0.4 %%, damping 0.3 %%)", w);
  t_close(what, tc, tref, 0, 0.02);
  snprintf(what, sizeof what, "%sforce on triangle 0 [N] (the sphere hits triangle 1 only)", w);
  t_close(what, f_other, 0, 1e-12, 0);
  snprintf(what, sizeof what, "%s1 - rebound/impact speed (1 - e, 15 %%)", w);
  t_close(what, 1 - vel[2] / v, 1 - p.restitution, 0, 0.15);
  snprintf(what, sizeof what, "%srebound lateral speed [m/s]", w);
  t_close(what, fabs(vel[0]) + fabs(vel[1]), 0, 1e-9, 0);
  /* the largest overlap over the steps against delta_max / d (the damping's 0.4 %, and the
   * step: the peak lies between two steps, 1 step = 0.4 % of t_c, ~0.01 % of delta_max) */
  snprintf(what, sizeof what, "%slargest %s / d (Hertz delta_max, 1 %%)", w,
           sil ? "indentation" : "overlap");
  t_close(what, sil ? ind_max : ov_max, dmax / p.diameter, 0, 0.01);
  snprintf(what, sizeof what, "%slargest %s (none: the %s)", w, sil ? "overlap" : "indentation",
           sil ? "silicone wall's contact is an indentation" : "steel wall is not compliant");
  t_close(what, sil ? ov_max : ind_max, 0, 1e-15, 0);
  if (sil) { /* the sphere falls straight onto the plane z = 0: its centre is at (cx, cy),
               * R - delta above the plane */
    snprintf(what, sizeof what, "%sdeepest bead's centre x, y [m] (the sphere's path)", w);
    t_close(what, fabs(site[0] - cx) + fabs(site[1] - cy), 0, 1e-12, 0);
    snprintf(what, sizeof what, "%sdeepest bead's centre z [m] (R - indentation d)", w);
    t_close(what, site[2], R - ind_max * p.diameter, 1e-15, 0);
  }
  if (t_verbose())
    printf("hertz (%s): F_max %.6g N (ref %.6g, rel %.3g), t_c %.6g s (ref %.6g, rel %.3g), "
           "e_meas %.5f (input %.3f), %d contact steps, overlap %.5g / indentation %.5g of d "
           "(delta_max / d %.5g), deepest bead at (%.6g, %.6g, %.6g) m\n",
           sil ? "silicone" : "steel", fpeak, fref, fpeak / fref - 1, tc, tref, tc / tref - 1,
           vel[2] / v, p.restitution, nforce, ov_max, ind_max, dmax / p.diameter, site[0], site[1], site[2]);
  dem_bridge_destroy(&b);
}

int main(void) {
  impact(DEM_WALL_STEEL);
  impact(DEM_WALL_SILICONE);
  return t_failures ? 1 : 0;
}
