# bench/dem/stiff_bed_plot.gp - the stiff bed's stroke (softening 30, rigid band 5 mm) past
# 8 mm (docs/dem.md, stop 42): bending angle and piston force against piston displacement.
#   gnuplot -e "band='results/s40_band30/bending.csv'; cap='results/s42_cap10/bending.csv'; \
#     ind='results/s42_ind45/bending.csv'; out='docs/img/dem_stiff_bed_trust_region.png'" \
#     bench/dem/stiff_bed_plot.gp
# band: stop 40's run to 8 mm (no trust region); cap: resumed at 7.75 mm with
# [coupling] max_trial_change = 0.1; ind: cap's run resumed after 10.75 mm with max_indentation 0.45.
set datafile separator ","
set terminal pngcairo size 1000,420 font ",10"
set output out
set multiplot layout 1,2
set key top left Left reverse
set grid
set xlabel "piston displacement [mm]"
set ylabel "bending angle [deg]"
plot band u ($1*1e3):2 every ::1 w lp pt 7 ps 0.5 lc rgb "#888888" t "stop 40 (to 8 mm)", \
     cap u ($1*1e3 >= 7.74 ? $1*1e3 : 1/0):2 every ::1 w lp pt 7 ps 0.6 lc rgb "#1f77b4" t "trust region 0.1 d", \
     ind u ($1*1e3 >= 10.99 ? $1*1e3 : 1/0):2 every ::1 w lp pt 5 ps 0.6 lc rgb "#d62728" t "max indentation 0.45 (from 10.75 mm)"
set ylabel "piston force [N]"
plot band u ($1*1e3):3 every ::1 w lp pt 7 ps 0.5 lc rgb "#888888" t "stop 40 (to 8 mm)", \
     cap u ($1*1e3 >= 7.74 ? $1*1e3 : 1/0):3 every ::1 w lp pt 7 ps 0.6 lc rgb "#1f77b4" t "trust region 0.1 d", \
     ind u ($1*1e3 >= 10.99 ? $1*1e3 : 1/0):3 every ::1 w lp pt 5 ps 0.6 lc rgb "#d62728" t "max indentation 0.45"
unset multiplot
