# Fields of one run as families of profiles x -> f(x, t) at the times of plotdata.py (at most
# nine, coloured from dark blue (early) to dark red (late)), one panel per field, up to three
# per row, and one key of the times. A state at t = 0 off the scale of the later ones
# (clip0_<field>) does not set the y range: it is clipped at the frame, and the panel says so.
# The axes carry plotdata.py's short labels: without SI units the title says 'nondimensional'
# once. Called by scripts/plot.sh. Expects: datadir, out, fmt, W, H (see common.gp), fig_title.
load 'common.gp'
pnc = (n_fields < 3) ? n_fields : 3
pnr = int(ceil(n_fields/3.0))
set multiplot
st = failed ? sprintf('   [%s]', status) : ''
eval figtitle_literal(fig_title.st.'   ('.units_note.')')
key_plot = 'for [k=1:n_prof] NaN with lines lw 2.5 lc rgb word(prof_colours, k) title "t = ".word(prof_times, k).(t_plain eq "" ? "" : " ".t_plain)'
# bands in pixels of the H-pixel figure (one row of panels is 600 px high, two are 1000): the
# title, the key (two rows), the panels, the x label at the bottom
key_y1 = 1 - 65./H; key_y0 = key_y1 - 75./H
@keyrow
unset label 1000
py1 = key_y0 - 55./H; py0 = 100./H; pgy = 120./H
px0 = 0.09; px1 = 0.985; pgx = 0.10
set xlabel it('x').x_short
set xrange [0:x_max]
set xtics x_step
do for [i=0:n_fields-1] {
    pr = int(i/3); pc = i - 3*pr
    @place
    fld = word(fields, i + 1)
    set ylabel field_label(word(symbols, i + 1)).value('short_'.fld)
    k0 = value('clip0_'.fld) ? 2 : 1
    flat = value('flat_'.fld)
    if (flat == flat) { set yrange [flat - (flat == 0 ? 1 : abs(flat)):flat + (flat == 0 ? 1 : abs(flat))] } else { set autoscale y }
    if (k0 == 2) {
        set label 1 it('t').' = 0: off scale' at graph 1, graph 1.03 right font ','.sprintf('%.2f', (font_px - 3)*font_scale) textcolor rgb word(prof_colours, 1)
    } else {
        unset label 1
    }
    plot for [k=1:k0-1] datadir.'/prof.'.fld.'.dat' skip 1 using 1:k+1 with lines lw 1.8 lc rgb word(prof_colours, k) noautoscale, \
         for [k=k0:n_prof] datadir.'/prof.'.fld.'.dat' skip 1 using 1:k+1 with lines lw 1.8 lc rgb word(prof_colours, k)
}
unset multiplot
