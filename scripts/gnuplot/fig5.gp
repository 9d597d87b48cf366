# Figure 5: u, P, theta for experiment 2 (pulses theta0 = P0 = 20 on [0, 0.1]): profiles at
# t = 0 ... 0.05 with the fronts of (7.4) marked, and at later times.
load 'common.gp'
set multiplot
eval figtitle('Figure 5: experiment 2 (pulses {/:Italic θ}_0 = {/:Italic P}_0 = 20 on [0, 0.1]) — second sound')
run = 'exp2'; fields = 'u P theta'; symbols = 'u P θ'; pnc = 3; with_fronts = 1
rows_x1 = 1.0; fronts_split = 0.68; fronts_x1 = 1.0
load 'profile_rows.gp'
unset multiplot
