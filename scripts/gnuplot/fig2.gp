# Figure 2: u, P, theta for experiment 1 (varpi = 0.1), profiles at marked times.
load 'common.gp'
n = n_exp1_all; times = times_exp1_all; colours = colours_exp1_all
set multiplot
eval figtitle('Figure 2: experiment 1, ϖ = '.sprintf('%g', varpi_exp1).' — profiles at the marked times')
key_plot = 'for [k=1:n] NaN with lines lw 2 lc rgb word(colours, k) title "t = ".word(times, k)'
key_y0 = 0.84; key_y1 = 0.93
@keyrow
unset label 1000
pnr = 1; pnc = 3; pr = 0
set xlabel it('x')
set xrange [0:1]
set yrange [*:*]
set xtics 0.2
do for [pc=0:2] {
    @place
    fld = word('u P theta', pc + 1)
    set ylabel field_label(word('u P θ', pc + 1))
    plot for [k=1:n] datadir.'/exp1.all.'.fld.'.dat' skip 1 using 1:k+1 with lines lw 1.6 lc rgb word(colours, k)
}
unset multiplot
