# Figure 3: q and eta for experiment 1 (varpi = 0.1), profiles at marked times.
load 'common.gp'
n = n_exp1_all; times = times_exp1_all; colours = colours_exp1_all
set multiplot
eval figtitle('Figure 3: experiment 1, ϖ = '.sprintf('%g', varpi_exp1).' — heat flux and diffusion flux')
key_plot = 'for [k=1:n] NaN with lines lw 2 lc rgb word(colours, k) title "t = ".word(times, k)'
key_y0 = 0.84; key_y1 = 0.93
@keyrow
unset label 1000
pnr = 1; pnc = 2; pr = 0
px0 = 0.08; pgx = 0.09
set xlabel it('x')
set xrange [0:1]
set xtics 0.2
do for [pc=0:1] {
    @place
    fld = word('q eta', pc + 1)
    set ylabel field_label(word('q η', pc + 1))
    plot for [k=1:n] datadir.'/exp1.all.'.fld.'.dat' skip 1 using 1:k+1 with lines lw 1.6 lc rgb word(colours, k)
}
unset multiplot
