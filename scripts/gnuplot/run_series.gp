# Time series of one run: the energy E(t) (log scale) with its parts when the file has them
# (/series/energy_<part>), and u at the end of the rod with the obstacle g and the contact
# intervals shaded (scripts/lib/plotdata.py: from /events, else from the penetration or the
# contact stress, which is the one that Signorini's law makes non-zero).
# The axes carry plotdata.py's short labels (the title says 'nondimensional' once).
# Called by scripts/plot.sh. Expects: datadir, out, fmt, W, H (see common.gp), fig_title.
load 'common.gp'
set multiplot
st = failed ? sprintf('   [%s]', status) : ''
eval figtitle_literal(fig_title.st.'   ('.units_note.')')
part_colours = '#4145ab #1bbc8f #d9a800 #f36a00 #d0190f #7a0403 #2d9bd6 #67b51e'
# the parts are named E_<part>, the shading 'in contact' (one part is named 'contact')
key_plot = 'NaN with lines lw 2.5 lc rgb "#30123b" title "'.it('E').' (total)"'.(n_parts > 0 ? ', for [k=1:n_parts] NaN with lines lw 2 dt 2 lc rgb word(part_colours, k) title "'.it('E').'_{".word(part_names, k)."}"' : '').', NaN with lines lw 1.5 dt (8,5) lc rgb "#c00000" title "obstacle '.it('g').'", NaN with boxes fs solid 1.0 lc rgb "#e6e6e6" title "in contact"'
key_y0 = 0.82; key_y1 = 0.93; key_samplen = 4; key_spacing = 1.3
set style fill solid 1.0 noborder
@keyrow
unset label 1000
pnr = 1; pnc = 2; pr = 0; py1 = 0.77; py0 = 0.19
px0 = 0.095; px1 = 0.975; pgx = 0.10
set xlabel it('t').ts_short
set xrange [0:t_end_series]
@shade_contact
pc = 0
@place
# a log scale when some E > 0 (a run at rest has E = 0 throughout: a linear axis)
if (!exists('e_positive') || e_positive) { set logscale y; set format y '10^{%L}' }
set ylabel it('E').'('.it('t').')'.e_short
# parts: columns 6, 7, ... of series.dat; zero values are left out of the log plot
if (!exists('e_positive') || e_positive) {
    plot datadir.'/series.dat' skip 1 using 1:($2 > 0 ? $2 : NaN) with lines lw 2.5 lc rgb '#30123b', \
         for [k=1:n_parts] datadir.'/series.dat' skip 1 using 1:(column(5 + k) > 0 ? column(5 + k) : NaN) with lines lw 2 dt 2 lc rgb word(part_colours, k)
} else {
    set yrange [-1:1]
    plot datadir.'/series.dat' skip 1 using 1:2 with lines lw 2.5 lc rgb '#30123b', \
         for [k=1:n_parts] datadir.'/series.dat' skip 1 using 1:(column(5 + k)) with lines lw 2 dt 2 lc rgb word(part_colours, k)
    set autoscale y
}
unset logscale y
set format y '%g'
pc = 1
@place
set ylabel it('u').'('.(x_end eq '1' ? '1' : it(x_end)).', '.it('t').')'.u_short
ylo = (u_end_min < 0) ? 1.08*u_end_min : 0; yhi = 1.08*((g == g && g > u_end_max) ? g : u_end_max)
set yrange [ylo:(yhi > ylo ? yhi : ylo + 1)]
if (g == g) { set arrow 1 from graph 0, first g to graph 1, first g nohead lw 1.5 dt (8,5) lc rgb '#c00000' front }
plot datadir.'/series.dat' skip 1 using 1:3 with lines lw 2.5 lc rgb '#30123b'
unset multiplot
