# Work-precision diagram (bench/work_precision.sh): error at the final time against the
# wall time of the time stepping, one point per (h, dt), one line per pairing.
# Expects: datadir (with work_precision_{mms,exp2}.dat and work_precision_params.gp), out.
set encoding utf8
set terminal pngcairo enhanced size 1950, 1150 font 'DejaVu Sans,16' linewidth 1.5
set output out
load datadir.'/work_precision_params.gp'

set logscale xy
set format x '10^{%T}'
set format y '10^{%T}'
set grid lc rgb '#d8d8d8' lw 0.8
set tics out nomirror
set border lw 1
set key bottom left spacing 1.15 box opaque samplen 2.5 width -2 font ',14'
set xlabel 'wall time of the time stepping [s]'

mms = datadir.'/work_precision_mms.dat'
exp2 = datadir.'/work_precision_exp2.dat'

set multiplot layout 2, 3 title "{/:Bold Work-precision: implicit Euler (6.1) and BDF2}" font ',19'

# --- (a) manufactured solution --------------------------------------------------------------
set arrow 1 from graph 0, first 1e-4 to graph 1, first 1e-4 nohead dt (8, 5) lw 1.2 lc rgb '#555555' back
set title "(a) manufactured solution: {/:Italic L}^2 error of {/:Italic θ}"
set ylabel 'error at t = 1'
plot for [i=1:mms_n] mms index (i-1) using 4:5 with linespoints lc rgb mms_colour[i] pt mms_pt[i] ps 1.4 \
     dt mms_dash[i] lw 1.6 title mms_title[i]

set title "(a) manufactured solution: {/:Italic H}^1 error of {/:Italic u}"
plot for [i=1:mms_n] mms index (i-1) using 4:6 with linespoints lc rgb mms_colour[i] pt mms_pt[i] ps 1.4 \
     dt mms_dash[i] lw 1.6 title mms_title[i]

set title "(a) manufactured solution: {/:Italic L}^2 error of {/:Italic P}"
plot for [i=1:mms_n] mms index (i-1) using 4:8 with linespoints lc rgb mms_colour[i] pt mms_pt[i] ps 1.4 \
     dt mms_dash[i] lw 1.6 title mms_title[i]
unset arrow 1

# --- (b) experiment 2 against the reference -----------------------------------------------
set title "(b) experiment 2: relative {/:Italic L}^2 error of {/:Italic θ}"
set ylabel 'relative error at t = '.exp2_tend
plot for [i=1:exp2_n] exp2 index (i-1) using 4:5 with linespoints lc rgb exp2_colour[i] pt exp2_pt[i] ps 1.4 \
     dt exp2_dash[i] lw 1.6 title exp2_title[i]

set title "(b) experiment 2: relative {/:Italic H}^1 error of {/:Italic u}"
plot for [i=1:exp2_n] exp2 index (i-1) using 4:6 with linespoints lc rgb exp2_colour[i] pt exp2_pt[i] ps 1.4 \
     dt exp2_dash[i] lw 1.6 title exp2_title[i]

set title "(b) experiment 2: relative {/:Italic L}^2 error of {/:Italic P} (pulse front)"
# the reference's own accuracy in P: errors below this line are not resolved
if (exists('exp2_refcheck_P')) {
    set arrow 2 from graph 0, first exp2_refcheck_P to graph 1, first exp2_refcheck_P nohead dt (3, 4) lw 1.2 \
        lc rgb '#555555' back
    set label 2 'reference check (s/2, 2dt)' at graph 0.03, first exp2_refcheck_P/1.3 left font ',13' tc rgb '#555555'
}
set key top right
plot for [i=1:exp2_n] exp2 index (i-1) using 4:8 with linespoints lc rgb exp2_colour[i] pt exp2_pt[i] ps 1.4 \
     dt exp2_dash[i] lw 1.6 title exp2_title[i]
unset multiplot
