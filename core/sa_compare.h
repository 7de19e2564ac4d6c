/* sa_compare.h - the comparison scene ([compare], cases/compare_bending.ini): bending angle
 * against piston displacement of the FEM-DEM run, the FEM run with a Mohr-Coulomb fill and the
 * pressure baseline, read from the results folders of earlier runs, on one plot and in one
 * table. It computes no mechanics; it reads CSV tables and interpolates.
 *
 * Inputs ([compare] keys, at least two of dem, mc, pressure; relative folders are resolved
 * against the case file's folder, like every path in a case file):
 *   dem, mc    results folder of cases/granular_bending_dem.ini / granular_bending_mc.ini; their
 *              bending.csv must have piston_displacement [m], bending_angle [deg],
 *              piston_force [N], displaced_volume [m^3] (volume_change_rel [-] is used if present)
 *   pressure   results folder of cases/pressure_bending.ini; its bending.csv must have
 *              pressure [Pa], bending_angle [deg], volume_change [m^3] (volume_change_rel used
 *              if present)
 *   bore_radius  r of the barrel: the piston displaces V_d = pi r^2 x at displacement x; checked
 *              against the granular runs' displaced_volume column
 *
 * The pressure baseline enters through volume (the hydrostatic limit of an incompressible
 * fill): at displacement x its state is the one of the pressure run whose cavity volume change
 * equals V_d = pi r^2 x, interpolated linearly in the volume change (which must increase
 * strictly along the run); its piston force is p pi r^2. Past the pressure run's largest volume
 * change the baseline ends (logged and in summary.ini).
 *
 * Outputs: comparison.csv (every sample displacement of the inputs at which at least two
 * curves exist; each curve interpolated linearly in x there; differences MC - DEM,
 * pressure - DEM, pressure - MC in deg and relative to the second; an empty field where a
 * curve does not reach), curve_dem.csv / curve_mc.csv / curve_pressure.csv (each curve at its
 * own sample points, in mm: the plotted data; the pressure curve is cut at the granular runs'
 * largest displacement, its interpolated end marked run_state = 0), bending_comparison.png,
 * piston_force_comparison.png (+ .gp), summary.ini, the table in softact.log. */
#ifndef SA_COMPARE_H
#define SA_COMPARE_H

#include "sa_module.h"

extern const SaModule sa_compare_module;

#endif
