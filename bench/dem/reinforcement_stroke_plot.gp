# bench/dem/reinforcement_stroke_plot.gp - the stiff bed (softening 30, rigid band 5 mm, trust
# region 0.1 d) with and without the rings over the long stroke (docs/dem.md, stop 43): bending
# angle, piston force and cavity growth against piston displacement.
#   gnuplot -e "rings='results/s42_cap10/bending.csv'; ind='results/s42_ind45/bending.csv'; \
#     norings='results/s43_norings30/bending.csv'; out='docs/img/dem_reinforcement_stroke.png'" \
#     bench/dem/reinforcement_stroke_plot.gp
# rings: stop 40's run to 7.75 mm continued by stop 42 to 11.25 mm (its bending.csv holds both);
# ind: the same resumed after 10.75 mm with max_indentation 0.45; norings: mesh.rings = 0.
set datafile separator ","
set terminal pngcairo size 1400,420 font ",10"
set output out
set multiplot layout 1,3
set key top left Left reverse
set grid
set xlabel "piston displacement [mm]"
set ylabel "bending angle [deg]"
plot rings u ($1*1e3):2 every ::1 w lp pt 7 ps 0.5 lc rgb "#1f77b4" t "rings", \
     ind u ($1*1e3 >= 10.99 ? $1*1e3 : 1/0):2 every ::1 w lp pt 5 ps 0.5 lc rgb "#9ecae1" t "rings, max indentation 0.45", \
     norings u ($1*1e3):2 every ::1 w lp pt 7 ps 0.5 lc rgb "#d62728" t "no rings"
set ylabel "piston force [N]"
plot rings u ($1*1e3):3 every ::1 w lp pt 7 ps 0.5 lc rgb "#1f77b4" t "rings", \
     ind u ($1*1e3 >= 10.99 ? $1*1e3 : 1/0):3 every ::1 w lp pt 5 ps 0.5 lc rgb "#9ecae1" t "rings, max indentation 0.45", \
     norings u ($1*1e3):3 every ::1 w lp pt 7 ps 0.5 lc rgb "#d62728" t "no rings"
set ylabel "cavity volume change [% of V0]"
plot rings u ($1*1e3):($5*100) every ::1 w lp pt 7 ps 0.5 lc rgb "#1f77b4" t "rings", \
     ind u ($1*1e3 >= 10.99 ? $1*1e3 : 1/0):($5*100) every ::1 w lp pt 5 ps 0.5 lc rgb "#9ecae1" t "rings, max indentation 0.45", \
     norings u ($1*1e3):($5*100) every ::1 w lp pt 7 ps 0.5 lc rgb "#d62728" t "no rings"
unset multiplot
