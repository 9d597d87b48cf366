# Figure 4: energy (log scale) and u(1,t) for varpi = 0.1, 0.5, 1 (experiment 1), with the
# obstacle g and the contact interval of varpi = 0.1.
load 'common.gp'
runs = 'exp1 exp1_varpi05 exp1_varpi1'
rc = '#440154 #21918c #e08a00'
rdt = '1 2 4'
varpi(k) = value('varpi_'.word(runs, k))
set multiplot
eval figtitle('Figure 4: experiment 1 — energy and displacement of the end '.it('x').' = 1 for three viscosities ϖ')
key_plot = 'for [k=1:3] NaN with lines lw 2.2 dt int(word(rdt, k)) lc rgb word(rc, k) title sprintf("ϖ = %g", varpi(k)), NaN with lines lw 1.5 dt (8,5) lc rgb "#c00000" title "obstacle "."{/:Italic g}".sprintf(" = %g", g), NaN with boxes fs solid 1.0 lc rgb "#e6e6e6" title sprintf("contact, ϖ = %g", varpi_exp1)'
key_y0 = 0.84; key_y1 = 0.93; key_samplen = 4
set style fill solid 1.0 noborder
@keyrow
unset label 1000
pnr = 1; pnc = 2; pr = 0
px0 = 0.08; pgx = 0.10
set xlabel it('t')
set xrange [0:t_end_series]
if (t_on_exp1 == t_on_exp1) {   # not NaN: shade the contact interval
    set object 1 rect from t_on_exp1, graph 0 to t_off_exp1, graph 1 behind fc rgb '#e6e6e6' fs solid 1.0 noborder
}
pc = 0
@place
set logscale y
set format y '10^{%L}'
set ylabel it('E').'('.it('t').')'
plot for [k=1:3] datadir.'/'.word(runs, k).'.series.dat' skip 1 using 1:2 with lines lw 2.2 dt int(word(rdt, k)) lc rgb word(rc, k)
unset logscale y
set format y '%g'
pc = 1
@place
set ylabel it('u').'(1, '.it('t').')'
set yrange [0:*]
set arrow 1 from graph 0, first g to graph 1, first g nohead lw 1.5 dt (8,5) lc rgb '#c00000' front
plot for [k=1:3] datadir.'/'.word(runs, k).'.series.dat' skip 1 using 1:3 with lines lw 2.2 dt int(word(rdt, k)) lc rgb word(rc, k)
unset multiplot
