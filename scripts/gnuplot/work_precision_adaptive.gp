# Work-precision of adaptive against fixed time steps on experiment 1
# (bench/adaptive_steps.sh): error against wall time, one line per scheme and mode.
# Expects: datadir (with work_precision_adaptive.dat and work_precision_adaptive_params.gp), out.
set encoding utf8
set terminal pngcairo enhanced size 1950, 700 font 'DejaVu Sans,16' linewidth 1.5
set output out
load datadir.'/work_precision_adaptive_params.gp'
dat = datadir.'/work_precision_adaptive.dat'

set logscale xy
set format x '10^{%T}'
set format y '10^{%T}'
set grid lc rgb '#d8d8d8' lw 0.8
set tics out nomirror
set border lw 1
set key top right spacing 1.1 box opaque samplen 2.5 width -1 font ',13'
set xlabel 'wall time [s] (wall\_seconds)'
set bmargin 4
# the x range from the data (not the next decade), with room for the labels
set autoscale xfix
set offsets graph 0.06, graph 0.12, 0, 0

# error_tol next to the adaptive points, dt next to the fixed ones (column 6)

set multiplot layout 1, 3 title "{/:Bold Experiment 1 (h = 1/500): fixed and adaptive time steps against a BDF2 reference (dt = ".wpa_ref_dt.")}" font ',18'

set arrow 1 from graph 0, first wpa_target_a to graph 1, first wpa_target_a nohead dt (8, 5) lw 1.2 lc rgb '#555555' back
set label 1 'target 10^{-5}' at graph 0.30, first wpa_target_a/1.6 left font ',12' tc rgb '#555555'
set arrow 2 from graph 0, first wpa_ref_error to graph 1, first wpa_ref_error nohead dt (3, 4) lw 1.2 lc rgb '#999999' back
set label 2 'reference error (check/3)' at graph 0.98, first wpa_ref_error*1.35 right font ',12' tc rgb '#999999'
set title 'max_t |{/:Italic u}(1,{/:Italic t}) - reference|, {/:Italic t} ≤ '.wpa_t_long
set ylabel 'error'
set yrange [wpa_ymin_u:wpa_ymax_u]
plot for [i=1:wpa_n] dat index (i-1) using 2:3 with linespoints lc rgb wpa_colour[i] pt wpa_pt[i] ps 1.5 \
         dt wpa_dash[i] lw 1.8 title wpa_title[i], \
     for [i=1:wpa_n] dat index (i-1) using 2:3:6 with labels offset char wpa_lx[i], char wpa_ly[i] left \
         font ',10' tc rgb wpa_colour[i] notitle
unset arrow 2
unset label 2

set title 'contact onset and release: larger time error, {/:Italic t} ≤ '.wpa_t_long
set ylabel 'max(|onset error|, |release error|)'
set label 1 at graph 0.30, first wpa_target_a*1.35
if (exists('wpa_ymin_ev')) { set yrange [wpa_ymin_ev:wpa_ymax_ev] } else { set yrange [*:*] }
if (exists('wpa_ref_ev_error')) {
    set arrow 2 from graph 0, first wpa_ref_ev_error to graph 1, first wpa_ref_ev_error nohead dt (3, 4) lw 1.2 \
        lc rgb '#999999' back
    set label 2 'reference error (check/3)' at graph 0.98, first wpa_ref_ev_error*1.35 right font ',12' tc rgb '#999999'
}
plot for [i=1:wpa_n] dat index (i-1) using 2:4 with linespoints lc rgb wpa_colour[i] pt wpa_pt[i] ps 1.5 \
         dt wpa_dash[i] lw 1.8 title wpa_title[i], \
     for [i=1:wpa_n] dat index (i-1) using 2:4:6 with labels offset char wpa_lx[i], char wpa_ly[i] left \
         font ',10' tc rgb wpa_colour[i] notitle
unset arrow 1
unset label 1
unset arrow 2
unset label 2
set yrange [*:*]

set title 'max |{/:Italic u}(1,{/:Italic t}) - reference|, {/:Italic t} ≤ '.wpa_t_short
set ylabel 'error'
if (exists('wpa_base_short_error')) {
    set arrow 3 from graph 0, first wpa_base_short_error to graph 1, first wpa_base_short_error nohead dt (8, 5) \
        lw 1.2 lc rgb '#555555' back
    set label 3 'fixed Euler dt = 10^{-4}' at graph 0.02, first wpa_base_short_error/1.6 left font ',12' tc rgb '#555555'
}
plot for [i=1:wpa_n] dat index (wpa_n+i-1) using 2:3 with linespoints lc rgb wpa_colour[i] pt wpa_pt[i] ps 1.5 \
         dt wpa_dash[i] lw 1.8 title wpa_title[i], \
     for [i=1:wpa_n] dat index (wpa_n+i-1) using 2:3:6 with labels offset char wpa_lx[i], char wpa_ly[i] left \
         font ',10' tc rgb wpa_colour[i] notitle
unset multiplot
