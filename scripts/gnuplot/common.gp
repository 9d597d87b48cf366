# Shared set-up of the figure scripts fig2.gp ... fig7.gp (called by scripts/paper/figures.sh).
# Expects: datadir (h5extract.py output), out (file to write), fmt ('png' or 'pdf'),
# W, H (size in pixels of the PNG; the PDF has the same proportions, 100 px = 1 inch).
set encoding utf8
font_px = 17
if (fmt eq 'png') {
    font_scale = 1.0
    set terminal pngcairo enhanced size W, H font 'DejaVu Sans,'.font_px linewidth 1.5
} else {
    # W x H pixels -> W/200 x H/200 inches (7.5 in wide for the 1500 px figures); the
    # same fonts and lines relative to the page as in the PNG
    font_scale = 0.72
    set terminal pdfcairo enhanced size W/200., H/200. font 'DejaVu Sans,'.sprintf('%.2f', font_px*font_scale) linewidth 0.75
}
set output out
load datadir.'/params.gp'

set grid lc rgb '#d8d8d8' lw 0.8
set border lw 1
set tics out nomirror
set mxtics 2
set mytics 2
set key noautotitle
set format y '%g'
set datafile commentschars '#'

# Italic symbols in enhanced text.
it(s) = '{/:Italic '.s.'}'
field_label(f) = it(f).'('.it('x').', '.it('t').')'

# 'x = 0.1 + t v' markers: vertical dashed lines in the colour of the curve of time t.
# Usage: @fronts with fr_times, fr_colours, fr_n, fr_v set.
fronts = 'do for [k=1:fr_n] { xf = pulse_end + fr_v*word(fr_times, k); if (word(fr_times, k) > 0 && xf <= 1.0) { set arrow from xf, graph 0 to xf, graph 1 nohead dt (6,4) lw 1.5 lc rgb word(fr_colours, k) back } }'

# The contact intervals of scripts/lib/plotdata.py (n_contact, contact_on, contact_off: word
# lists in the time axis' units) shaded grey behind the next plot. Usage: @shade_contact
shade_contact = 'do for [k=1:n_contact] { set object 100 + k rect from real(word(contact_on, k)), graph 0 to real(word(contact_off, k)), graph 1 behind fc rgb "#e6e6e6" fs solid 1.0 noborder }'

# Panel placement in screen coordinates: columns c = 0..nc-1 between x0 and x1 with gap
# gx; rows r = 0..nr-1 (0 at the top) between y1 (top) and y0 (bottom) with gap gy.
px0 = 0.09; px1 = 0.985; pgx = 0.085
py0 = 0.16; py1 = 0.82; pgy = 0.14
place = 'set lmargin at screen px0 + pc*((px1 - px0 + pgx)/pnc); set rmargin at screen px0 + pc*((px1 - px0 + pgx)/pnc) + (px1 - px0 + pgx)/pnc - pgx; set tmargin at screen py1 - pr*((py1 - py0 + pgy)/pnr); set bmargin at screen py1 - pr*((py1 - py0 + pgy)/pnr) - (py1 - py0 + pgy)/pnr + pgy'
# Figure title at the top left. figtitle_literal: the text as it is, no enhanced-text markup
# (run names: 'point_0001' would draw 0001 as a subscript); no double quote in s.
figtitle(s) = sprintf('set label 1000 "%s" at screen 0.01, screen 0.965 left font ",%.2f"', s, (font_px + 3)*font_scale)
figtitle_literal(s) = figtitle(s).' noenhanced'

# A key of its own across the whole width, between the title and the panels: an empty
# plot whose curves are never drawn (NaN) but are listed in its key. Usage: set
# key_plot to the plot command's curve list, key_y0/key_y1 (and key_x0/key_x1) to its
# screen band (key_spacing: more room between its rows, for subscripts), then @keyrow
# (key_plot is read when the line runs).
key_x0 = 0.0; key_x1 = 1.0; key_samplen = 2.5; key_spacing = 1.0
keyrow = 'set lmargin at screen key_x0; set rmargin at screen key_x1; set tmargin at screen key_y1; set bmargin at screen key_y0; unset border; unset xtics; unset ytics; unset mxtics; unset mytics; unset xlabel; unset ylabel; unset grid; set xrange [0:1]; set yrange [0:1]; set key inside center center horizontal reverse Left samplen key_samplen spacing key_spacing width 0; eval "plot ".key_plot; unset key; set border; set xtics out nomirror; set ytics out nomirror; set mxtics 2; set mytics 2; set grid; set autoscale'
