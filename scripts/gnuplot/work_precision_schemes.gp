# Work-precision of the time schemes (bench/work_precision_schemes.sh): error against the
# wall time of the time stepping, one point per dt, one line per scheme (and contact law).
# Expects: datadir (with wps_exp1.dat, wps_impact.dat and wps_params.gp), out.
set encoding utf8
set terminal pngcairo enhanced size 1950, 860 font 'DejaVu Sans,16' linewidth 1.5
set output out
load datadir.'/wps_params.gp'

set logscale xy
set format x '10^{%T}'
set format y '10^{%T}'
set grid lc rgb '#d8d8d8' lw 0.8
set tics out nomirror
set border lw 1
set key outside below center vertical maxrows 3 spacing 1.1 samplen 2.5 width 1 font ',13'
set xlabel 'wall time of the time stepping [s]' offset 0, 0.4
array colour[3] = ['#c0392b', '#1f5fa8', '#1e8449']
array name[3] = ['Euler', 'BDF2', 'midpoint']
array pt_full[3] = [7, 5, 9]
array pt_open[3] = [6, 4, 8]

exp1 = datadir.'/wps_exp1.dat'
impact = datadir.'/wps_impact.dat'

set multiplot layout 1, 3 title "{/:Bold Work-precision of the time schemes}" font ',19'

# --- (a) exp1: time error of u(1,t) ---------------------------------------------------------
set title "(a) exp1, h = 1/500: error of {/:Italic u}(1,{/:Italic t}) against a fine {/:Italic dt}"
set ylabel 'max error of u(1,t)'
set yrange [1e-10:1e-4]
set arrow 1 from graph 0, first exp1_refcheck to graph 1, first exp1_refcheck nohead dt (3, 4) lw 1.2 \
    lc rgb '#555555' back
set label 1 'reference check (2 dt_{ref})' at graph 0.97, first exp1_refcheck*1.8 right font ',12' tc rgb '#555555'
plot for [i=1:3] exp1 index (i-1) using 3:4 with linespoints lc rgb colour[i] pt pt_full[i] ps 1.4 lw 1.8 \
         title name[i].', t ≤ '.exp1_tend, \
     for [i=1:3] exp1 index (i-1) using 3:5 with linespoints lc rgb colour[i] pt pt_open[i] ps 1.4 dt 2 lw 1.4 \
         title name[i].', before contact'
unset arrow 1
unset label 1

# --- (b) impact: pre-contact error against the exact solution --------------------------------
set title "(b) impact, s = 1000: {/:Italic u}(1,{/:Italic t}) before contact, exact {/:Italic t} - {/:Italic t}^2/2"
set ylabel 'max error of u(1,t), t < 1 - √0.9'
set yrange [1e-8:1e-4]
set arrow 2 from graph 0, first impact_floor to graph 1, first impact_floor nohead dt (3, 4) lw 1.2 \
    lc rgb '#555555' back
set label 2 'space error of s = 1000' at graph 0.97, first impact_floor*1.6 right font ',12' tc rgb '#555555'
plot for [i=1:3] impact index (i-1) using 3:4 with linespoints lc rgb colour[i] pt pt_full[i] ps 1.4 lw 1.8 \
         title name[i]
unset arrow 2
unset label 2

# --- (c) impact: energy drift ----------------------------------------------------------------
set title "(c) impact: energy drift over [0, ".impact_tend."]"
set ylabel '|E(T)/E(0) - 1|'
set yrange [1e-8:1]
plot for [i=1:3] impact index (i-1) using 3:5 with linespoints lc rgb colour[i] pt pt_full[i] ps 1.4 lw 1.8 \
         title name[i].', penalty', \
     for [i=1:3] impact index (i+2) using 3:5 with linespoints lc rgb colour[i] pt pt_open[i] ps 1.4 dt 2 lw 1.4 \
         title name[i].', Signorini'
unset multiplot
