/* dem_piston.h - the piston's kinematics in the FEM-DEM scene (private to dem_coupling/): the
 * stroke in coupling steps of equal travel, with an optional start from rest at uniform
 * acceleration ([piston] ramp_steps). Pure arithmetic, so that it is tested on its own. */
#ifndef DEM_PISTON_H
#define DEM_PISTON_H

/* Stroke step k >= 1 of a stroke of `stroke` [m] in steps of `interval` [m] at `speed` [m/s],
 * reached after ramp_steps steps of uniform acceleration from rest: piston displacements s0 ->
 * s1 [m], speeds v0 -> v1 [m/s] (v(s) = speed sqrt(s / s_ramp) on the ramp) and the step's
 * duration T [s] = 2 (s1 - s0) / (v0 + v1) (the speed is linear in time within a step). */
void dem_piston_step(double stroke, double interval, double speed, int ramp_steps, int k,
                     double *s0, double *s1, double *v0, double *v1, double *T);
/* Displacement [m] and speed [m/s] a time t in [0, T] into a step that starts at s0 with speed
 * v0 and ends with v1 after T (constant acceleration within the step). */
void dem_piston_at(double s0, double v0, double v1, double T, double t, double *s, double *v);

#endif
