#!/usr/bin/env bash
# Demo scan: where does the rod of experiment 2 touch the obstacle? A 15 x 15 map over the
# viscosity varpi (0.01 .. 1, log-spaced) and the amplitude of the initial pulses
# theta0 = P0 = A on [0, 0.1] (A = 2.5 .. 37.5, step 2.5; theta0_step and p0_step set
# equal, as in the paper's experiment 2). The paper's two data points (varpi = 0.1:
# A = 20 contact, A = 5 none) are grid points. Then figures/contact_map.png: max u(1,t)/g
# and the contact time, with the contact boundary max u(1,t) = g. See docs/scans.md.
#
#   scripts/scans/contact_map.sh [--out DIR] [-j N] [--figure PNG] [--quick]
#
# Default: the paper's discretisation (h = 1/500, dt = 1e-4), t_end = 2.5, into
# runs/contact_map/ (225 points, about 2.5 min with -j 2 on a 2-core machine), figure
# figures/contact_map.png. --quick: h = 1/100, dt = 5e-4 (about 25 times cheaper) into
# runs/contact_map_quick/ and figure runs/contact_map_quick/contact_map.png.
# Resumable like any scan: rerun the same command after an interruption.
# Environment: BUILD_TYPE, BUILD_DIR as for scripts/setup.sh; RODCONTACT (an executable
# to use instead of building one).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
out=""
figure=""
jobs=$(nproc 2>/dev/null || echo 1)
quick=0
while (($# > 0)); do
    case $1 in
        --out) out=$2; shift 2 ;;
        -j) jobs=$2; shift 2 ;;
        --figure) figure=$2; shift 2 ;;
        --quick) quick=1; shift ;;
        -h|--help) sed -n '2,/^set -euo/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}" | sed '$d'; exit 0 ;;
        *) echo "contact_map: unknown argument '$1' (see --help)" >&2; exit 2 ;;
    esac
done

cd "$repo_root"
if [[ -z ${RODCONTACT:-} ]]; then
    scripts/setup.sh
    build_dir="${BUILD_DIR:-build}"
    [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
    export RODCONTACT="$build_dir/rodcontact"
fi
command -v gnuplot > /dev/null || { echo "contact_map: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
python=$(scripts/lib/find_python.sh 2> /dev/null || command -v python3) ||
    { echo "contact_map: no python3 found" >&2; exit 1; }

# The axes (do not change them without a new --out: the scan directory remembers them).
axes=(--set 'model.varpi=0.01:1:15:log'
      --set 'initial.theta0_step(1)+initial.p0_step(1)=2.5:37.5:15')
# t_end = 2.5: without contact u(1,t) peaks at t ~ 1.2 (varpi = 0.1) .. 2.0 (varpi = 1),
# so the verdict needs the run to get past t = 2. Only the first and last snapshots.
fixed=(--set time.t_end=2.5 --set output.snapshot_every=1000000)
if ((quick)); then
    fixed+=(--set mesh.n_elements=100 --set time.dt=5e-4 --set output.series_every=2)
    out=${out:-runs/contact_map_quick}
    figure=${figure:-$out/contact_map.png}
    res='h = 1/100, Δt = 5·10^{-4}'
else
    fixed+=(--set output.series_every=10)
    out=${out:-runs/contact_map}
    figure=${figure:-figures/contact_map.png}
    res='h = 1/500, Δt = 10^{-4}'
fi

start=$SECONDS
status=0
scripts/scan.sh input/exp2.nml "${axes[@]}" "${fixed[@]}" --out "$out" -j "$jobs" || status=$?
if ((status != 0 && status != 1)); then
    exit "$status"
fi
echo "contact_map: scan finished in $((SECONDS - start)) s (this invocation)" >&2

"$python" scripts/scans/contact_map_grid.py "$out/summary.csv" "$out"
mkdir -p "$(dirname "$figure")"
gnuplot -e "datadir='$out'; out='$figure'; res='$res'" scripts/scans/contact_map.gp
echo "contact_map: figure written to $figure" >&2
exit "$status"
