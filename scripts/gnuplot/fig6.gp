# Figure 6: q, eta for experiment 2 (profiles at t = 0 ... 0.05 with the fronts of (7.4)
# marked, and at later times) and the displacement u(1,t) of the contact point x = 1.
load 'common.gp'
set multiplot
eval figtitle('Figure 6: experiment 2 — heat flux, diffusion flux and the contact point {/:Italic x} = 1')
run = 'exp2'; fields = 'q eta'; symbols = 'q η'; pnc = 2; with_fronts = 1
rows_x1 = 0.66; fronts_split = 0.62; fronts_x1 = 1.0
px0 = 0.075; px1 = 0.635; pgx = 0.085
load 'profile_rows.gp'
# u(1, t) with the obstacle and the contact interval, spanning both rows
set lmargin at screen 0.735; set rmargin at screen 0.985
set tmargin at screen 0.875; set bmargin at screen 0.095
set offsets 0, 0, 0, 0
set xrange [0:t_end_exp2]
set xtics auto
set yrange [0:*]
set xlabel it('t')
set ylabel it('u').'(1, '.it('t').')'
if (t_on_exp2 == t_on_exp2) {   # not NaN: shade the contact interval
    set object 1 rect from t_on_exp2, graph 0 to t_off_exp2, graph 1 behind fc rgb '#e6e6e6' fs solid 1.0 noborder
}
set arrow 1 from graph 0, first g to graph 1, first g nohead lw 1.5 dt (8,5) lc rgb '#c00000' front
set key inside right bottom reverse Left samplen 2.5 box opaque width 1
set style fill solid 1.0 noborder
plot datadir.'/exp2.series.dat' skip 1 using 1:3 with lines lw 2.2 lc rgb '#440154' title it('u').'(1, '.it('t').')', \
     NaN with lines lw 1.5 dt (8,5) lc rgb '#c00000' title 'obstacle '.it('g').sprintf(' = %g', g), \
     NaN with boxes lc rgb '#e6e6e6' title 'contact'
unset multiplot
