# Figure 7: u, P, theta for experiment 3 (tau = tau0 = 0: Fourier and Fick laws) with the data
# of experiment 2, profiles at the same times as Figure 5.
load 'common.gp'
set multiplot
eval figtitle('Figure 7: experiment 3 (pulses {/:Italic θ}_0 = {/:Italic P}_0 = 20 on [0, 0.1], {/:Italic τ} = {/:Italic τ}_0 = 0) — no second sound')
run = 'exp3'; fields = 'u P theta'; symbols = 'u P θ'; pnc = 3; with_fronts = 0
rows_x1 = 1.0; fronts_split = 0.68
load 'profile_rows.gp'
unset multiplot
