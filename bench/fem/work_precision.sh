#!/bin/sh
# The work-precision plot of docs/fem_time_to_accuracy.md from the committed raw outputs
# (bench/fem/results_rings); the reference angles are the converged estimate of the ring series
# (h = h_band = 2 mm, h_ring = 2, 1, 0.5, 0.25 mm: Richardson at order 1.089 times the wall
# correction) in that document's section "The fourth ring size". Four panels: the error at
# 30, 60, 90 and 120 kPa; the C3D20R run stopped at 109 kPa and appears in the first three only.
set -eu
cd "$(dirname "$0")/../.."
R=bench/fem/results_rings
A="previous recipe (5592fe2), h then all sizes refined"
B="new recipe, rings refined at h 2 mm"
C="new recipe, 4/2/1 ring zone 1 mm"
python3 bench/fem/work_precision.py --ref 16.82,36.66,59.32,84.20 \
  --out docs/img/fem_work_precision --time cpu \
  "$A:4/2/2@nw=$R/prev_4_2_2.out" "$A:3/2/2@-=$R/prev_3_2_2.out" "$A:2/2/2@ne=$R/prev_2_2_2.out" \
  "$A:1.5/1.5/1.5@ne=$R/prev_1.5_1.5_1.5.out" "$A:1.25/1.25/1.25@ne=$R/prev_1.25_1.25_1.25.out" \
  "$B:4/2/2@n=$R/new_4_2_2.out" "$B:2/2/1@sw=$R/new_2_2_1.out" "$B:2/2/0.5@sw=$R/new_2_2_0.5.out" \
  "$B:2/2/0.25@e=$R/new_2_2_0.25.out" \
  "$C:4/2/1@sw=$R/new_4_2_1_tg1.out" \
  "CalculiX C3D10 (locks), same mesh:4/2/2@e=$R/ccx/c3d10_4_2_2.out" \
  "swept grid (mesh kind swept), stop 41:3/2/2/0.125@s=$R/swept_3_2_2_0.125_g2.out" \
  "CalculiX C3D20R, ring-aligned hex (stopped at 109 kPa):h 2 mm@w=$R/ccx/c3d20r_h2.out" \
  "CalculiX C3D20R h 4 mm, idle (stop 44; stopped at 116 kPa):h 4 mm@w=$R/ccx/c3d20r_h4.out" \
  "AMD Zen, idle (stop 44), Gmsh default and swept grid:Gmsh 4/2/2@s=$R/zen/gmsh_4_2_2.out" \
  "AMD Zen, idle (stop 44), Gmsh default and swept grid:swept 4/2/2/0.5@n=$R/zen/swept_4_2_2_0.5.out"
