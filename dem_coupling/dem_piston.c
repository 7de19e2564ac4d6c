/* dem_piston.c - piston kinematics of the FEM-DEM scene (dem_piston.h). */
#include "dem_piston.h"
#include <math.h>

void dem_piston_step(double stroke, double interval, double speed, int ramp_steps, int k,
                     double *s0, double *s1, double *v0, double *v1, double *T) {
  double s_ramp = ramp_steps * interval;
  *s0 = (k - 1) * interval, *s1 = fmin(k * interval, stroke);
  *v0 = *s0 < s_ramp ? speed * sqrt(*s0 / s_ramp) : speed;
  *v1 = *s1 < s_ramp ? speed * sqrt(*s1 / s_ramp) : speed;
  *T = 2 * (*s1 - *s0) / (*v0 + *v1);
}

void dem_piston_at(double s0, double v0, double v1, double T, double t, double *s, double *v) {
  double a = (v1 - v0) / T;
  *s = s0 + (v0 + 0.5 * a * t) * t;
  *v = v0 + a * t;
}
