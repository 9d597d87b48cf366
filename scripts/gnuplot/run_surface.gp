# Fields of one run as surfaces over (x, t), one panel per field, up to three per row, in the
# order given (the paper's panel layout when figures.sh passes its fields). Called by
# scripts/plot.sh and scripts/paper/figures.sh with the data of scripts/lib/plotdata.py.
# Expects: datadir, out, fmt, W, H (see common.gp), fig_title; optional: with_uend = 1 adds
# a last panel with u(1, t), the obstacle and the contact interval (Figure 6).
load 'common.gp'
if (!exists('with_uend')) { with_uend = 0 }
n_panels = n_fields + with_uend
pnc = (n_panels < 3) ? n_panels : 3
pnr = int(ceil(n_panels/3.0))
set multiplot
st = failed ? sprintf('   [%s]', status) : ''
# literal = 1 (scripts/plot.sh): the title as it is, no enhanced-text markup (run names)
if (exists('literal') && literal) {
    eval figtitle_literal(fig_title.st.(units_note eq '' ? '' : '   ('.units_note.')'))
} else {
    eval figtitle(fig_title.st.(units_note eq '' ? '' : '   ('.units_note.')'))
}
# colour maps: sequential (dark blue - teal - yellow) for one-signed fields, diverging
# (blue - white - red, centred on 0) for fields that change sign
seq_palette = "set palette defined (0 '#30123b', 0.25 '#3e6fd8', 0.5 '#1bbc8f', 0.75 '#b8d22a', 1 '#f0e442')"
div_palette = "set palette defined (0 '#2140a0', 0.25 '#6f9bd9', 0.5 '#f7f7f7', 0.75 '#e9845f', 1 '#a01818')"
# panel (pr, pc) occupies the box [ox, ox + sx] x [oy, oy + sy] of the screen below the title
top = 0.93
sx = 1.0/pnc; sy = top/pnr
# the short labels of plotdata.py (x_short, t_short, short_<field>): without SI units the
# figure's title says 'nondimensional' once, the axes and panels name the variable and the
# power of ten drawn (the long '(nondimensional)' ran into the tick labels)
do for [i=0:n_fields-1] {
    pr = int(i/3); pc = i - 3*pr
    fld = word(fields, i + 1)
    set origin pc*sx + 0.005, top - (pr + 1)*sy - 0.03*sy
    set size sx*0.78, sy*1.1
    set lmargin 0; set rmargin 0; set tmargin 0; set bmargin 0
    set view 56, 38, 1.05, 1.0
    set xyplane 0
    set border 31 lw 0.8 lc rgb '#606060'
    unset grid
    # about four ticks on each axis: the t axis, foreshortened by the view, ran its labels together
    set xtics xs_step offset 0, -0.2 nomirror
    set ytics t_step offset 0.5, -0.2 nomirror
    unset ztics   # the colour bar beside the panel gives the values
    unset mxtics; unset mytics
    set xlabel it('x').x_short offset 0, -0.3
    set ylabel it('t').t_short offset 0, 0
    set zlabel ''
    set format z '%g'
    tmin = value('t_min_'.fld)
    # tmin > 0: the field at t = 0 is off the colour scale, drawn from t = tmin
    set title field_label(word(symbols, i + 1)).value('short_'.fld).(tmin > 0 ? sprintf('   (from {/:Italic t} = %.3g%s)', tmin, t_plain eq '' ? '' : ' '.t_plain) : '') offset 0, -1
    set xrange [0:x_max]
    set yrange [0:t_max]
    lo = value('cb_lo_'.fld); hi = value('cb_hi_'.fld)
    set zrange [value('z_lo_'.fld):value('z_hi_'.fld)]
    set cbrange [lo:hi]
    if (value('signed_'.fld)) { eval div_palette } else { eval seq_palette }
    set colorbox vertical user origin screen (pc + 0.78)*sx, screen top - (pr + 1)*sy + 0.22*sy size screen 0.012, screen 0.55*sy
    set cbtics auto
    set format cb '%g'
    set pm3d depthorder border lw 0.2 lc rgb '#90303030'
    set pm3d lighting primary 0.65 specular 0.1
    splot datadir.'/surf.'.fld.'.dat' using 1:2:3 with pm3d notitle
    unset label 1000
    unset title
    unset colorbox
}
if (with_uend) {
    i = n_fields
    pr = int(i/3); pc = i - 3*pr
    set origin 0, 0; set size 1, 1
    set lmargin at screen pc*sx + 0.07; set rmargin at screen (pc + 0.95)*sx
    set bmargin at screen top - (pr + 1)*sy + 0.2*sy; set tmargin at screen top - pr*sy - 0.1*sy
    unset pm3d
    set border 3 lw 1 lc rgb 'black'
    set xtics auto out nomirror offset 0, 0
    set ytics auto out nomirror offset 0, 0
    set grid xtics ytics
    set xrange [0:t_end_series]
    set yrange [0:*]
    set xlabel it('t').ts_unit offset 0, 0
    set ylabel it('u').'(1, '.it('t').')'.u_unit offset 0, 0
    @shade_contact
    set arrow 1 from graph 0, first g to graph 1, first g nohead lw 1.5 dt (8,5) lc rgb '#c00000' front
    set key inside right bottom reverse Left samplen 2.5 box opaque width 1
    set style fill solid 1.0 noborder
    plot datadir.'/series.dat' skip 1 using 1:3 with lines lw 2.2 lc rgb '#30123b' title it('u').'(1, '.it('t').')', \
         NaN with lines lw 1.5 dt (8,5) lc rgb '#c00000' title 'obstacle '.it('g').sprintf(' = %g', g), \
         NaN with boxes lc rgb '#e6e6e6' title 'in contact'
}
unset multiplot
