/* Momentum balance of the run check (dem_momentum_residual, dem_checks.h) on one sphere
 * dropped onto a triangulated plate under gravity, through the bridge's per-triangle wall
 * forces sampled every DEM step, as the scene samples them.
 *
 * Reference: Newton's second law for the sphere over a window of N steps of dt,
 *   m (v_end - v_start) = -sum_n F_wall,n dt - m g N dt,
 * exact for velocity Verlet when the window starts and ends out of contact (the sum of the
 * step forces then equals the trapezoidal impulse). The window holds the whole bounce
 * (restitution 0.5): the static balance |F_wall + W| misses by the momentum rate, which is
 * of the order of the mean contact force, while the momentum balance closes to round-off.
 * A second window with the sphere at rest on the plate checks the static limit. */
#include "dem_checks.h"
#include "dem_test_util.h"

int main(void) {
  DemParams p;
  t_params(&p);
  const double R = 0.5 * p.diameter, v_in = 0.3, gap = 0.2e-3;
  DemBridge *b = NULL;
  int id;
  t_sphere_on_plate(&p, 0.002, -0.003, gap, &b, &id);
  char cmd[128];
  snprintf(cmd, sizeof cmd, "velocity all set 0 0 %.17g", -v_in);
  T_CHECK(dem_bridge_command(b, cmd));
  T_CHECK(dem_bridge_run(b, 1)); /* the first force evaluation happens in the first run */

  const double m = p.density * 4.0 / 3.0 * M_PI * R * R * R, W = m * 9.81;
  double x[3], v0[3], v1[3], f[6];
  /* window 1: from the approach through the bounce until the contact has ended */
  T_CHECK(dem_bridge_particles(b, x, v0, NULL, NULL));
  double F[3] = {0, 0, 0}, fpeak = 0;
  int n = 0, touched = 0;
  for (; n < 200000; n++) {
    T_CHECK(dem_bridge_run(b, 1));
    T_CHECK(dem_bridge_mesh_forces(b, id, f));
    double fz = f[2] + f[5];
    for (int d = 0; d < 3; d++) F[d] += f[d] + f[3 + d];
    fpeak = fmax(fpeak, -fz);
    if (fz != 0) touched = 1;
    if (touched && fz == 0) break;
  }
  T_CHECK(dem_bridge_particles(b, x, v1, NULL, NULL));
  n++;
  double T = n * p.dt, Fm[3] = {F[0] / n, F[1] / n, F[2] / n};
  double dp[3] = {m * (v1[0] - v0[0]), m * (v1[1] - v0[1]), m * (v1[2] - v0[2])};
  double res = dem_momentum_residual(Fm, W, dp, T), rate = fabs(dp[2]) / T;
  double stat = fabs(Fm[2] + W);
  t_true("the sphere bounced (contact seen, rebounding)", touched && v1[2] > 0);
  t_close("bounce: momentum residual / momentum rate (Newton, round-off)", res / rate, 0, 1e-6, 0);
  t_true("bounce: the static balance misses by the momentum rate (> 50 %)", stat > 0.5 * rate);
  if (t_verbose())
    printf("bounce: %d steps, peak force %.4g N, mean wall force %.6g N, weight %.6g N, "
           "momentum rate %.6g N, residual %.3g N (static %.3g N)\n",
           n, fpeak, Fm[2], W, rate, res, stat);

  /* window 2: at rest on the plate (let the bounces die out first) */
  T_CHECK(dem_bridge_run(b, 100000));
  T_CHECK(dem_bridge_particles(b, x, v0, NULL, NULL));
  F[0] = F[1] = F[2] = 0;
  int nr = 2000;
  for (int k = 0; k < nr; k++) {
    T_CHECK(dem_bridge_run(b, 1));
    T_CHECK(dem_bridge_mesh_forces(b, id, f));
    for (int d = 0; d < 3; d++) F[d] += (f[d] + f[3 + d]) / nr;
  }
  T_CHECK(dem_bridge_particles(b, x, v1, NULL, NULL));
  for (int d = 0; d < 3; d++) dp[d] = m * (v1[d] - v0[d]);
  res = dem_momentum_residual(F, W, dp, nr * p.dt);
  t_close("at rest: wall force carries the weight [N]", -F[2], W, 0, 1e-3);
  t_close("at rest: momentum residual / weight", res / W, 0, 1e-3, 0);
  dem_bridge_destroy(&b);
  return t_failures ? 1 : 0;
}
