/* Piston kinematics (dem_coupling/dem_piston.c) against the closed forms of a start from rest
 * at uniform acceleration a = speed^2 / (2 s_ramp), s_ramp = ramp_steps x interval:
 *   s(t) = a t^2 / 2 for t <= t_ramp = 2 s_ramp / speed, then s_ramp + speed (t - t_ramp),
 * sampled inside every step by dem_piston_at and summed step durations; without a ramp
 * s(t) = speed t. Also: continuity of s and v across steps, the last step cut at the stroke,
 * and a step halved into two (each half follows the whole step's motion). */
#include <math.h>
#include <stdio.h>

#include "dem_piston.h"

static int failures;
static void close_to(const char *what, double a, double b, double tol) {
  if (!(fabs(a - b) <= tol)) {
    printf("FAIL %s: %.17g against %.17g (tolerance %g)\n", what, a, b, tol);
    failures++;
  }
}

static void run(int ramp_steps) {
  const double stroke = 2.6e-3, ds = 0.25e-3, speed = 0.2;
  int nint = (int)ceil(stroke / ds - 1e-9);
  double s_ramp = ramp_steps * ds, acc = ramp_steps ? speed * speed / (2 * s_ramp) : 0;
  double t_ramp = ramp_steps ? 2 * s_ramp / speed : 0, t = 0, s_prev = 0, v_prev = 0;
  char what[128];
  for (int k = 1; k <= nint; k++) {
    double s0, s1, v0, v1, T;
    dem_piston_step(stroke, ds, speed, ramp_steps, k, &s0, &s1, &v0, &v1, &T);
    snprintf(what, sizeof what, "ramp %d step %d: start where the last step ended", ramp_steps, k);
    close_to(what, s0, s_prev, 1e-15);
    if (k > 1 || ramp_steps) close_to(what, v0, v_prev, 1e-12);
    for (int q = 0; q <= 8; q++) {
      double tau = T * q / 8, s, v, tt = t + tau;
      dem_piston_at(s0, v0, v1, T, tau, &s, &v);
      int on_ramp = ramp_steps && tt <= t_ramp;
      double s_ref = on_ramp ? 0.5 * acc * tt * tt : s_ramp + speed * (tt - t_ramp);
      double v_ref = on_ramp ? acc * tt : speed;
      snprintf(what, sizeof what, "ramp %d step %d: s(t) closed form", ramp_steps, k);
      close_to(what, s, s_ref, 1e-12);
      snprintf(what, sizeof what, "ramp %d step %d: v(t) closed form", ramp_steps, k);
      close_to(what, v, v_ref, 1e-9);
      if (q == 8) s_prev = s, v_prev = v;
    }
    /* a step halved (an iterated step that did not converge, dem_granular.c): the second half
     * starts at the middle of the whole step and follows the same closed form */
    double sm, vm;
    dem_piston_at(0, v0, v1, T, 0.5 * T, &sm, &vm);
    for (int q = 0; q <= 4; q++) {
      double tau = 0.5 * T * q / 4, s, v, s_whole, v_whole;
      dem_piston_at(s0 + sm, vm, v1, 0.5 * T, tau, &s, &v);
      dem_piston_at(s0, v0, v1, T, 0.5 * T + tau, &s_whole, &v_whole);
      snprintf(what, sizeof what, "ramp %d step %d: second half of the halved step", ramp_steps, k);
      close_to(what, s, s_whole, 1e-15);
      close_to(what, v, v_whole, 1e-12);
    }
    t += T;
  }
  close_to("the stroke ends at the stroke", s_prev, stroke, 1e-15);
}

int main(void) {
  run(0);
  run(1);
  run(4);
  run(20); /* longer than the stroke: never at speed */
  return failures ? 1 : 0;
}
