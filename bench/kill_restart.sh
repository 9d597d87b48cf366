#!/usr/bin/env bash
# Benchmark (not a test: it takes minutes and random kill times) of a killed run's .h5.part
# (docs/output.md, "A killed run"): KILLS times, start experiment 1 on 100 elements (implicit
# Euler, dt = 1e-4, t_end = 1000 so that it never ends, a checkpoint every 250 steps, a
# snapshot every 100) and SIGKILL it at a random time in 0.2-1.0 s; open the .h5.part as a
# SWMR reader and read its last checkpoint and every /series and /snapshots dataset. Every
# EVERY-th kill also restarts from the .h5.part to 5000 steps past its checkpoint, compares
# the result with an uninterrupted run (tests/tools/regression.py same) and checks that the
# .h5.part was left as it was.
#
#   bench/kill_restart.sh                 # 250 kills, a restart every 10th (about 6 minutes)
#   KILLS=50 EVERY=5 bench/kill_restart.sh
#
# Environment: EXE (the rodcontact to kill; default $BUILD_DIR/rodcontact, built by
# scripts/setup.sh), KILLS (250), EVERY (10), WORK (a scratch directory; default a new
# temporary one, removed at the end unless a file failed). Exit status: 0 every file
# readable and every restart equal; 1 otherwise (the failing files are kept in WORK).

set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
kills="${KILLS:-250}"
every="${EVERY:-10}"
if [[ -z "${EXE:-}" ]]; then
    "$repo_root/scripts/setup.sh" || exit 1
    build_dir="${BUILD_DIR:-build}"
    [[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
    EXE="$build_dir/rodcontact"
fi
py=$("$repo_root/scripts/lib/find_python.sh") || { echo "bench: no Python with h5py" >&2; exit 1; }
work="${WORK:-$(mktemp -d)}"
mkdir -p "$work" && cd "$work" || exit 1
run=("$EXE" "$repo_root/input/exp1.nml" --set mesh.n_elements=100
     --set output.checkpoint_every=250 --set output.snapshot_every=100 --set output.quiet=.true.)

unreadable=0; restarts=0; differ=0
for ((i = 1; i <= kills; i++)); do
    rm -f kill.h5.part
    wait_s=$(awk -v r=$RANDOM 'BEGIN { printf "%.3f", 0.2 + r / 32768 * 0.8 }')
    (timeout -s KILL "$wait_s" "${run[@]}" --set time.t_end=1000.0 --set output.prefix="'kill'"; :) 2> /dev/null   # ":": no exec, so the "Killed" note goes to /dev/null
    if ! step=$("$py" -c "
import h5py
f = h5py.File('kill.h5.part', 'r', swmr=True)
g = f['checkpoint/slot%d' % int(f['checkpoint/current'][0])]
g.visititems(lambda name, item: item[()] if isinstance(item, h5py.Dataset) else None)
for group in ('series', 'snapshots'):
    for name in f[group]:
        if isinstance(f[group][name], h5py.Dataset): f[group][name][()]
print(int(g['state/scalars']['step']))" 2> read.err); then
        unreadable=$((unreadable + 1))
        echo "kill $i at $wait_s s: unreadable: $(tail -n 1 read.err)"
        cp kill.h5.part "unreadable_$i.h5.part" 2> /dev/null
        continue
    fi
    ((i % every == 0)) || continue
    restarts=$((restarts + 1))
    sum=$(md5sum < kill.h5.part)
    t_end=$(awk -v n="$step" 'BEGIN { printf "%.4f", (n + 5000) * 1e-4 }')
    rm -f rest.h5 ref.h5
    "${run[@]}" --set time.t_end="$t_end" --set time.restart_from="'kill.h5.part'" --set output.prefix="'rest'" &&
        "${run[@]}" --set time.t_end="$t_end" --set output.prefix="'ref'" &&
        out=$("$py" "$repo_root/tests/tools/regression.py" same ref.h5 rest.h5) &&
        [[ "$(md5sum < kill.h5.part)" == "$sum" ]] ||
        { differ=$((differ + 1)); echo "kill $i: the restart from step $step failed or differs: ${out:-}"; cp kill.h5.part "differ_$i.h5.part"; }
done
echo "kill_restart: $kills kills of $EXE: $unreadable unreadable .h5.part; $restarts restarts, $differ failed or differ"
if ((unreadable + differ > 0)); then echo "kill_restart: the files are in $work"; exit 1; fi
[[ -z "${WORK:-}" ]] && rm -rf "$work"
exit 0
