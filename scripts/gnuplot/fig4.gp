# Figure 4: energy (log scale) and u(1,t) for varpi = 0.1, 0.5, 1 (experiment 1), with the
# obstacle g and the contact interval of varpi = 0.1; when exp1.h5 holds the parts of the
# energy (/series/energy_<part>, n_parts > 0 in params.gp) a third panel shows their
# magnitudes for varpi = 0.1 (kinetic, strain, thermal, ... as the file names them).
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
if (!exists('n_parts')) { n_parts = 0 }
pnr = 1; pnc = (n_parts > 0) ? 3 : 2; pr = 0
px0 = 0.08; pgx = (n_parts > 0) ? 0.11 : 0.10
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
if (n_parts > 0) {
    pc = 2
    @place
    unset arrow 1
    # |part|: the theta-P coupling term changes sign (c r > d^2 keeps its sum with the
    # thermal and chemical parts positive); zeros (a contact term out of contact) are left
    # out. The top decades are left free for the key.
    set yrange [*:1e8]
    set logscale y
    set format y '10^{%L}'
    set ylabel '|parts of '.it('E').'|, ϖ = '.sprintf('%g', varpi_exp1) offset 1.5, 0
    pcol = '#30123b #4145ab #2d9bd6 #1bbc8f #d9a800 #f36a00 #d0190f #7a0403'
    set key inside right top reverse Left samplen 2 box opaque width 1 font ',13' maxrows 4
    plot for [k=1:n_parts] datadir.'/exp1.series.dat' skip 1 using 1:(column(3 + k) != 0 ? abs(column(3 + k)) : NaN) with lines lw 2 lc rgb word(pcol, k) title word(part_names, k) noenhanced
}
unset multiplot
