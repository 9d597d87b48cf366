# Two rows of profile panels (early times on top, later times below) for one run; loaded
# by fig5.gp, fig6.gp and fig7.gp. Expects: run, fields and symbols (word lists, one word
# per column), pnc (number of profile columns), with_fronts (1: mark the fronts (7.4) in the
# early row), rows_x1 (right end of the keys, screen), fronts_split and fronts_x1 (where the
# key of the fronts starts and ends), px0/px1/pgx (horizontal placement of the profile columns).
# Screen bands (fractions of the height): key of row 1, row 1, key of row 2, row 2.
band_key = '0.885 0.94 0.445 0.51'
band_row = '0.575 0.875 0.095 0.435'
set offsets 0, 0, graph 0.04, 0
set xrange [0:1]
set xtics 0.2
set xlabel it('x')
do for [pr=0:1] {
    set_ = word('early late', pr + 1)
    n = value('n_'.run.'_'.set_); times = value('times_'.run.'_'.set_); colours = value('colours_'.run.'_'.set_)
    key_y0 = real(word(band_key, 2*pr + 1)); key_y1 = real(word(band_key, 2*pr + 2))
    key_plot = 'for [k=1:n] NaN with lines lw 2 lc rgb word(colours, k) title "t = ".word(times, k)'
    if (pr == 0 && with_fronts) {
        # the times on the left, the meaning of the dashed lines on the right
        key_x0 = 0.0; key_x1 = fronts_split
        @keyrow
        key_x0 = fronts_split; key_x1 = fronts_x1
        key_plot = 'NaN with lines lw 1.5 dt (6,4) lc rgb "#404040" title "fronts x = 0.1 + t v, (7.4)"'
        @keyrow
    } else {
        key_x0 = 0.0; key_x1 = rows_x1
        @keyrow
    }
    unset label 1000
    set xrange [0:1]
    set xtics 0.2
    # both rows share the x axis: its label only under the lower row, which leaves the
    # room between the rows to the key of the lower row
    if (pr == 0) { unset xlabel } else { set xlabel it('x') }
    py1 = real(word(band_row, 2*pr + 2)); py0 = real(word(band_row, 2*pr + 1)); pnr = 1
    do for [pc=0:pnc-1] {
        pr_save = pr; pr = 0
        @place
        pr = pr_save
        fld = word(fields, pc + 1)
        set ylabel field_label(word(symbols, pc + 1))
        unset arrow
        if (pr == 0 && with_fronts && (fld eq 'theta' || fld eq 'q' || fld eq 'P' || fld eq 'eta')) {
            fr_n = n; fr_times = times; fr_colours = colours
            fr_v = (fld eq 'theta' || fld eq 'q') ? v_theta : v_P
            @fronts
        }
        # the initial pulse (t = 0) does not set the y range: at t > 0 the fields are much
        # smaller in experiment 3, and would be flattened against the axis
        k0 = (real(word(times, 1)) == 0.0) ? 2 : 1
        plot for [k=1:k0-1] datadir.'/'.run.'.'.set_.'.'.fld.'.dat' skip 1 using 1:k+1 with lines lw 1.1 lc rgb word(colours, k) noautoscale, \
             for [k=k0:n] datadir.'/'.run.'.'.set_.'.'.fld.'.dat' skip 1 using 1:k+1 with lines lw 1.1 lc rgb word(colours, k)
    }
    unset arrow
}
