/* A monolayer of grains at rest pressed by a floor raised into it: every wall force the bridge
 * returns is a static Hertz force known in closed form, triangle by triangle. Run on one rank
 * (dem_static_load) and on two MPI ranks (dem_static_load_mpi: the floor and the layer cut by
 * the plane y = 0, so triangles under one rank's grains belong to the other rank and their
 * forces reach their owner through LIGGGHTS' reverse communication; the floor's nodes are moved
 * on both ranks, ghost copies included).
 *
 * Set-up: grains inserted in a cylinder exactly one diameter high, so every centre lies at
 * z_c = z_lo + R; no gravity, zero velocities; the flat floor (a disk of triangles) is then
 * moved from z = 0 to z = z_lo + delta (dem_bridge_set_mesh_nodes), which overlaps every grain
 * by delta. One DEM step: the grains have not moved (zero velocity and force before it), so the
 * contact force is the elastic Hertz force with no damping (zero normal velocity) and no
 * tangential part (Johnson, Contact Mechanics, 1985, eq. 4.23):
 *   F = 4/3 E* sqrt(R) delta^1.5,  1/E* = (1 - nu^2)/E + (1 - nu_w^2)/E_w.
 * Checks (to 1e-9 of F): the floor's total force = N F (down); on each triangle, F times the
 * grains whose centre projects inside it (a coplanar neighbour takes no edge contact); no
 * horizontal force; the grains' count N (gathered); the largest overlap delta / d (the bridge's
 * own search over the gathered grains); the running force sums (dem_bridge_mesh_forces_add,
 * _take) equal the forces read directly. */
#include "dem_test_util.h"

/* Is (x, y) inside triangle (a, b, c) (z ignored), with margin eps? */
static int inside2(double x, double y, const double *a, const double *b, const double *c,
                   double eps) {
  double d = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
  double l1 = ((b[1] - c[1]) * (x - c[0]) + (c[0] - b[0]) * (y - c[1])) / d;
  double l2 = ((c[1] - a[1]) * (x - c[0]) + (a[0] - c[0]) * (y - c[1])) / d;
  return l1 >= -eps && l2 >= -eps && 1 - l1 - l2 >= -eps;
}

int main(void) {
  t_mpi_begin();
  DemParams p;
  t_params(&p);
  p.gravity[2] = 0;
  p.young = 5e6, p.poisson = 0.3;
  p.wall_young = 2e7, p.wall_poisson = 0.25;
  for (int k = 0; k < 2; k++) p.box_lo[k] = -0.02, p.box_hi[k] = 0.02;
  p.box_lo[2] = -0.005, p.box_hi[2] = 0.01;
  const double d = p.diameter, R = 0.5 * d, z_lo = 0.1e-3, delta = 0.02 * d, Rf = 0.012;

  DemBridge *b = NULL;
  T_CHECK(dem_bridge_create(t_log(), &b));
  if (dem_par_size() > 1) T_CHECK(dem_bridge_set_processors(b, 1, dem_par_size(), 1));
  T_CHECK(dem_bridge_setup(b, &p));
  double *fxyz;
  int *ftri, fnv, fnt, floor_id, ins;
  /* 23 sectors: triangles straddle the cut y = 0, so some grains of one rank press on a triangle
   * the other rank owns (its force reaches the owner through LIGGGHTS' reverse communication) */
  t_disk(0, 0, Rf, 0, 23, 5, &fxyz, &ftri, &fnv, &fnt);
  T_CHECK(dem_bridge_add_mesh(b, "floor", fnv, fxyz, fnt, ftri, DEM_WALL_STEEL, &floor_id));
  T_CHECK(dem_bridge_insert_cylinder(b, 0, 0, Rf - 0.5e-3, z_lo, z_lo + d, 60, &ins));
  T_CHECK(dem_bridge_finalize_walls(b));
  int n = dem_bridge_count(b);
  t_true("grains inserted and counted over the ranks", n == ins && n > 20);

  /* the floor up into the layer (every node, velocity zero) */
  for (int i = 0; i < fnv; i++) fxyz[3 * i + 2] = z_lo + delta;
  T_CHECK(dem_bridge_set_mesh_nodes(b, floor_id, fxyz, NULL));
  T_CHECK(dem_bridge_run(b, 1));
  double *f = calloc(3 * (size_t)fnt, sizeof *f), *acc = calloc(3 * (size_t)fnt, sizeof *acc);
  double *x = malloc(3 * (size_t)n * sizeof *x);
  T_CHECK(dem_bridge_mesh_forces(b, floor_id, f));
  T_CHECK(dem_bridge_mesh_forces_add(b));
  T_CHECK(dem_bridge_mesh_forces_take(b, floor_id, acc));
  T_CHECK(dem_bridge_particles(b, x, NULL, NULL, NULL));
  double ov = dem_bridge_max_overlap(b);

  double Es = 1 / ((1 - p.poisson * p.poisson) / p.young +
                   (1 - p.wall_poisson * p.wall_poisson) / p.wall_young);
  double FH = 4.0 / 3.0 * Es * sqrt(R) * pow(delta, 1.5);
  double *expect = calloc((size_t)fnt, sizeof *expect), Fz = 0, Fh = 0, e_tri = 0, e_acc = 0;
  int unplaced = 0;
  for (int i = 0; i < n; i++) {
    int found = -1;
    for (int t = 0; t < fnt && found < 0; t++)
      if (inside2(x[3 * i], x[3 * i + 1], fxyz + 3 * ftri[3 * t], fxyz + 3 * ftri[3 * t + 1],
                  fxyz + 3 * ftri[3 * t + 2], 0))
        found = t;
    if (found < 0) unplaced++;
    else expect[found] += FH;
    t_close("grain centre height [m]", x[3 * i + 2], z_lo + R, 1e-15, 0);
  }
  for (int t = 0; t < fnt; t++) {
    Fz -= f[3 * t + 2];
    Fh += fabs(f[3 * t]) + fabs(f[3 * t + 1]);
    e_tri = fmax(e_tri, fabs(-f[3 * t + 2] - expect[t]));
    for (int k = 0; k < 3; k++) e_acc = fmax(e_acc, fabs(acc[3 * t + k] - f[3 * t + k]));
  }
  t_true("every grain above one floor triangle", unplaced == 0);
  t_close("floor force / (N x Hertz force)", Fz / (n * FH), 1, 1e-9, 0);
  t_close("largest per-triangle miss / Hertz force", e_tri / FH, 0, 1e-9, 0);
  t_close("horizontal force / Hertz force", Fh / FH, 0, 1e-9, 0);
  t_close("largest overlap / d", ov, delta / d, 1e-9, 0);
  t_close("running sum - direct forces / Hertz force", e_acc / FH, 0, 1e-12, 0);
  if (t_verbose())
    printf("static load on %d rank(s): %d grains, Hertz force %.6g N each, floor %.9g N "
           "(%.3g of N F), worst triangle %.3g of F, overlap %.6g of d\n",
           dem_par_size(), n, FH, Fz, Fz / (n * FH) - 1, e_tri / FH, ov);
  free(f), free(acc), free(x), free(expect), free(fxyz), free(ftri);
  dem_bridge_destroy(&b);
  t_mpi_end();
  return t_failures ? 1 : 0;
}
