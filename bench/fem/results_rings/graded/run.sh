#!/bin/sh
# ring-corner graded meshes, 0 -> 30 kPa in one output step, the recipe of cases/pressure_bending.ini
R=/work/build2/bench/fem/fem_ramp
REC="merit=energy indefinite=modify krylov_max=10 krylov_rtol=1e-2 predictor=reuse ls_memory=4 rtol=1e-6 reuse_rate=0 ref=0 p_max=30e3 n_out=1"
for hc in "$@"; do
  cd /work/main && $R h=2e-3 hb=2e-3 hr=1e-3 hc=$hc gc=0.5 $REC > /work/runs/grade/ramp/hc_$hc.out 2> /work/runs/grade/ramp/hc_$hc.err
done
