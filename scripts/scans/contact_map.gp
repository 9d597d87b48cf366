# The contact map of scripts/scans/contact_map.sh: two panels over (varpi, pulse
# amplitude A), one cell per scan point. Left: max u(1,t)/g; right: total contact time
# (grey: no contact). In both, the contact boundary max u(1,t) = g (the contour at 1 of
# the left panel's values, interpolated in log10(varpi) and A) and the paper's two data
# points of experiment 2 (varpi = 0.1: A = 20 contact, A = 5 no contact).
#
#   gnuplot -e "datadir='runs/contact_map'; out='figures/contact_map.png'; res='h = 1/500, Δt = 10^{-4}'" \
#       scripts/scans/contact_map.gp
#
# datadir holds what scripts/scans/contact_map_grid.py writes; res describes the
# discretisation for the title.
set encoding utf8
set terminal pngcairo enhanced size 1500, 720 font 'DejaVu Sans,16' linewidth 1.5
set output out
load datadir.'/contact_map.params.gp'
cells = datadir.'/contact_map.cells.dat'

# the contour max u(1,t)/g = 1, computed on the grid in (log10 varpi, A)
set table datadir.'/contact_map.contour.dat'
set contour base
set cntrparam linear
set cntrparam levels discrete 1.0
unset surface
set view map
splot datadir.'/contact_map.grid.dat' using 1:2:3 with lines
unset table
unset contour
set surface

it(s) = '{/:Italic '.s.'}'
set multiplot
if (!exists('res')) res = 'h = 1/500, Δt = 10^{-4}'
set label 1000 sprintf('Contact map of experiment 2 (%d runs, %s, t ≤ 2.5): where does the rod reach the obstacle %s = 0.1?', n_points, res, it('g')) at screen 0.01, screen 0.96 left font ',18'
set logscale x
set xrange [varpi_min:varpi_max]
set yrange [amp_min:amp_max]
set xtics ('0.01' 0.01, '0.02' 0.02, '0.05' 0.05, '0.1' 0.1, '0.2' 0.2, '0.5' 0.5, '1' 1) out nomirror
set ytics 5 out nomirror
set mytics 2
set xlabel 'viscosity ϖ (model.varpi)'
set ylabel 'pulse amplitude '.it('A').' (θ_0 = '.it('P').'_0 = '.it('A').' on [0, 0.1])'
set style fill solid 1.0 noborder
# one legend row under the title for both panels
unset key
ly = 0.895
set arrow 900 from screen 0.09, screen ly to screen 0.125, screen ly nohead lw 3.5 lc rgb '#e8000b' front
set label 900 'contact boundary: max '.it('u').'(1,'.it('t').') = '.it('g') at screen 0.132, screen ly left
set object 903 circle at screen 0.41, screen ly size screen 0.0065 fc rgb 'black' fs solid 1.0 front
set label 903 'paper: contact (ϖ = 0.1, '.it('A').' = 20)' at screen 0.421, screen ly left
set object 904 circle at screen 0.675, screen ly size screen 0.0065 fc rgb 'white' fs solid 1.0 border lc rgb 'black' lw 2.5 front
set label 904 'paper: no contact (ϖ = 0.1, '.it('A').' = 5)' at screen 0.686, screen ly left
set colorbox vertical user origin graph 1.03, graph 0 size character 1.5, graph 1
set tmargin at screen 0.79
set bmargin at screen 0.14

boundary = 'datadir."/contact_map.contour.dat" using (10**$1):2 with lines lw 3.5 lc rgb "#e8000b" notitle'
paper_marks = 'set object 901 circle at first 0.1, first 20 size screen 0.008 fc rgb "black" fs solid 1.0 front; set object 902 circle at first 0.1, first 5 size screen 0.008 fc rgb "white" fs solid 1.0 border lc rgb "black" lw 2.5 front'

# --- left: max u(1,t)/g
set lmargin at screen 0.065
set rmargin at screen 0.405
set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 '#fde725')
set cbrange [0:1.02]
set cbtics 0.2
set cblabel 'max '.it('u').'(1,'.it('t').') / '.it('g') offset 0.5, 0
set title 'largest displacement of the contact point'
@paper_marks
plot cells using 1:2:3:4:5:6:7 with boxxyerror fc palette notitle, \
     @boundary

# --- right: contact time
set ylabel ''
set lmargin at screen 0.575
set rmargin at screen 0.915
set palette defined (0 '#fff5eb', 0.3 '#fdae6b', 0.65 '#e6550d', 1 '#7f2704')
set cbrange [0:*]
set cbtics auto
set cblabel 'total contact time' offset 0.5, 0
set title 'time in contact (grey: no contact)'
plot cells using 1:(($9 == 1) ? $2 : NaN):3:4:5:6:8 with boxxyerror fc palette notitle, \
     cells using 1:(($9 == 0 && $10 == 1) ? $2 : NaN):3:4:5:6 with boxxyerror fc rgb '#d9d9d9' notitle, \
     @boundary
unset multiplot
