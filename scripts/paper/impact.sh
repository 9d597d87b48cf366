#!/usr/bin/env bash
# The impact case (input/impact.nml: an elastic bar, no dissipation, hitting the obstacle)
# with the three time schemes and both contact laws: E(t)/E(0) for each run drawn as
# figures/impact_energy.png, and a Markdown table on stdout (used by scripts/paper/verify.sh):
# the energy change by t = 4, the largest rise of E^n in one step, the first contact step
# against the exact onset 1 - sqrt(0.9), and the energy lost in the first impact step.
#
#   scripts/paper/impact.sh            # ~5 s after the build
# Environment: BUILD_DIR (as scripts/setup.sh), IMPACT_OUT (run files, default out/impact).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build_dir="${BUILD_DIR:-build}"; [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
out="${IMPACT_OUT:-$repo_root/out/impact}"
py=$("$repo_root/scripts/lib/find_python.sh")
"$repo_root/scripts/setup.sh" >&2
mkdir -p "$out" "$repo_root/figures"
for scheme in euler bdf2 midpoint; do
    for law in penalty signorini; do
        "$build_dir/rodcontact" "$repo_root/input/impact.nml" --set time.scheme="'$scheme'" \
            --set contact.law="'$law'" --set output.prefix="$out/${scheme}_$law" --set output.quiet=.true. >/dev/null
    done
done
"$py" - "$out" <<'PY'
import sys, math
import h5py, numpy as np
out = sys.argv[1]
exact_onset = 1 - math.sqrt(0.9)
print("| scheme | law | E(4)/E(0) - 1 | largest one-step rise of E^n (rel.) | first contact step ends at | energy lost in the first contact step (rel.) | wall s |")
print("|---|---|---:|---:|---:|---:|---:|")
for scheme in ("euler", "bdf2", "midpoint"):
    for law in ("penalty", "signorini"):
        with h5py.File(f"{out}/{scheme}_{law}.h5", "r") as f:
            t, e, cs = f["series/t"][:], f["series/energy"][:], f["series/contact_stress"][:]
            wall = f.attrs["wall_seconds"]
        k = int(np.argmax(cs < 0))
        np.savetxt(f"{out}/{scheme}_{law}.dat", np.column_stack([t, e / e[0]]))
        print(f"| {scheme} | {law} | {e[-1] / e[0] - 1:+.3e} | {np.max(np.diff(e) / e[:-1]):+.1e} | "
              f"{t[k]:.5f} (exact onset {exact_onset:.5f}) | {(e[k - 1] - e[k]) / e[0]:.2e} | {wall:.2f} |")
PY
gnuplot <<GP
set terminal pngcairo size 1000,600 font 'DejaVu Sans,11'
set output '$repo_root/figures/impact_energy.png'
set title 'Elastic bar hitting the obstacle (input/impact.nml): E(t)/E(0)'
set xlabel 't'; set ylabel 'E(t) / E(0)'
set key bottom left; set grid
set yrange [0.88:1.005]
plot '$out/euler_penalty.dat' w l lw 2 t 'Euler, penalty', '$out/euler_signorini.dat' w l lw 2 dt 2 t 'Euler, Signorini', \
     '$out/bdf2_penalty.dat' w l lw 2 t 'BDF2, penalty', '$out/bdf2_signorini.dat' w l lw 2 dt 2 t 'BDF2, Signorini', \
     '$out/midpoint_penalty.dat' w l lw 3 t 'midpoint, penalty', '$out/midpoint_signorini.dat' w l lw 2 dt 2 t 'midpoint, Signorini'
GP
echo "impact: wrote figures/impact_energy.png" >&2
