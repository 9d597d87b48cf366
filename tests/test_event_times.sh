#!/usr/bin/env bash
# Contact event times from the scheme's interpolant (dense_output_m, step_driver_m's event_time),
# on input/impact.nml, whose pre-contact solution is exact: u(1,t) = t - t^2/2, so contact starts
# at t* = 1 - sqrt(1 - 2 g) (g = 0.05: 0.0513167...). Adaptive midpoint and BDF2 runs with
# error_tol = 1e-3 (steps across the event up to 1e-3 long), every step in /series:
# the onset in /events (the root of the quadratic through the gap of the two levels before the
# step across it and the step's trial gap, the free motion) is within the step error of the
# exact crossing: |t_onset - t*| <= 2 max |u_k(1) - (t_k - t_k^2/2)| / u'(t*) over the two
# levels before the onset (u' = 1 - t*); measured 2.8e-8 (midpoint) and 1.4e-8 (BDF2) against
# bounds of 5.2e-8 and 2.8e-8. The straight line between the levels across the step (the
# events before issue 24) is 2.6e-4 and 1.9e-4 off (printed; the check also asserts it is
# outside the bound, so the runs do test the interpolant).
# Broken once: step_driver_m's event_time returning crossing_time (the straight line): both
# checks fail.
# Usage: bash test_event_times.sh <rodcontact> <source dir> <scratch dir>
set -u
exe=$1; src=$2; scratch=$3
py=$("$src/scripts/lib/find_python.sh") || { echo "SKIP: no Python with h5py"; exit 77; }
. "$src/tests/lib/checks.sh"
cd "$scratch" && rm -rf ./* || exit 1

for scheme in midpoint bdf2; do
    "$exe" "$src/input/impact.nml" --set time.scheme="'$scheme'" --set time.adaptive=.true. \
        --set time.error_tol=1e-3 --set time.t_end=0.1 --set output.quiet=.true. \
        --set output.snapshot_every=100000000 --set output.prefix="'impact_$scheme'" ||
        { echo "FAIL: impact run ($scheme)"; exit 1; }
    check "$scheme: the onset is within the step error of 1 - sqrt(1 - 2g) (the straight line is not)" \
        "$py" - "$src/scripts/lib" "impact_$scheme.h5" <<'PY'
import math
import sys
import numpy as np
sys.path.insert(0, sys.argv[1])
import rodrun
with rodrun.open_run(sys.argv[2]) as f:
    t, u = rodrun.series(f, "t"), rodrun.series(f, "u_end")
    ev_t, ev_kind = rodrun.events(f)
    g = rodrun.attr(f, "contact.g")
exact = 1 - math.sqrt(1 - 2 * g)
onset = float(ev_t[list(ev_kind).index(1)])
n = int(np.searchsorted(t, onset))          # t[n-1] < onset <= t[n]
ts, gaps = t[n - 2:n + 1], u[n - 2:n + 1] - g
line = ts[1] - gaps[1] * (ts[2] - ts[1]) / (gaps[2] - gaps[1])
level_error = max(abs(u[k] - (t[k] - t[k] ** 2 / 2)) for k in (n - 2, n - 1))
bound = 2 * level_error / (1 - exact)
print("  onset %.15f, straight line %.15f, exact %.15f" % (onset, line, exact))
print("  |onset - exact| = %.2e, bound (2 x level error / u') = %.2e, step across it %.2e"
      % (abs(onset - exact), bound, ts[2] - ts[1]))
ok = abs(onset - exact) <= bound < abs(line - exact)
sys.exit(0 if ok else 1)
PY
done
echo "test_event_times: $n_checks checks, $n_failed failed"
((n_failed == 0))
