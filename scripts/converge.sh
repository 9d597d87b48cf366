#!/usr/bin/env bash
# Is my run converged? Run a ladder of refinements of one input and report, for each quantity,
# the observed order, the Richardson extrapolate and the Grid Convergence Index (GCI) of the
# finest level. Documentation: docs/verification.md, "Checking convergence with
# scripts/converge.sh".
#
#   scripts/converge.sh INPUT [--set group.variable=value ...] [--refine space|time|both]
#                       [--levels N] [--ratio R] [--out DIR] [-j J] [--nondimensional]
#
# Level k = 0 .. N-1 is INPUT (with the --set values) with
#   space:  mesh.n_elements = n * R^k (rounded)
#   time:   time.dt = dt / R^k (the snapshots kept at the same times: output.snapshot_every
#           times R^k when that is an integer, else output.snapshot_dt = snapshot_every * dt)
#   both:   the two together (default)
# where n and dt are those of INPUT: level 0 is the input itself, the coarsest; the finest
# level costs about R^(N-1) (space or time) or R^(2(N-1)) (both) times the input. Every
# level writes its series at every step (output.series_every = 1).
# Adaptive steps and adaptive meshes are refused (time.adaptive, mesh.adaptive): the ladder
# refines a fixed step on a uniform mesh (the built-in &output error_estimate also takes
# adaptive steps and meshes: docs/scheme.md).
#
# Options: --refine WHAT   space, time or both (default both)
#          --levels N      levels, >= 2 (default 3; with 2 no order can be observed)
#          --ratio R       refinement ratio, > 1 (default 2)
#          --out DIR       where the levels and the results go (default out/converge_<input>)
#          -j J            runs at once (default: the number of cores)
#          --nondimensional  the table and figure in the files' own nondimensional values
#                          (default: the input's units, SI with &material, named in each row)
#          --exe PATH      the rodcontact executable (default: $RODCONTACT, else build/rodcontact
#                          in a source tree, PREFIX/bin/rodcontact installed: scripts/lib/find_rodcontact.sh)
# Each level is a one-point scan of scripts/scan.sh in DIR/level_<k>/ (its file
# point_0000.h5); a rerun of the same command reuses the levels that are complete.
# Writes DIR/converge.csv (quantity,fine,extrapolated,observed_order,gci_abs,gci_rel,status,units)
# and DIR/converge.png, and prints the table (scalars, and each field's largest band).
# Exit status: 0 done; 1 a level failed (see DIR/level_<k>/); 2 bad usage or input; 130/143
# interrupted by INT/TERM (the running levels are stopped; rerun the same command to resume).

set -uo pipefail

script="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$(basename "${BASH_SOURCE[0]}")"
repo_root="$(cd "$(dirname "$script")/.." && pwd)"

die() {
    echo "converge: error: $*" >&2
    exit 2
}

usage() {
    sed -n '2,/^$/s/^# \{0,1\}//p' "$script"
}

input=""
out=""
jobs=""
refine=both
levels=3
ratio=2
exe=$("$repo_root/scripts/lib/find_rodcontact.sh")
user_sets=()
nondimensional=()
while (($# > 0)); do
    case $1 in
        --set) (($# >= 2)) || die "--set needs group.variable=value"; user_sets+=("$2"); shift 2 ;;
        --set=*) user_sets+=("${1#--set=}"); shift ;;
        --refine) (($# >= 2)) || die "--refine needs space, time or both"; refine=$2; shift 2 ;;
        --refine=*) refine=${1#--refine=}; shift ;;
        --levels) (($# >= 2)) || die "--levels needs a number"; levels=$2; shift 2 ;;
        --levels=*) levels=${1#--levels=}; shift ;;
        --ratio) (($# >= 2)) || die "--ratio needs a number"; ratio=$2; shift 2 ;;
        --ratio=*) ratio=${1#--ratio=}; shift ;;
        --out) (($# >= 2)) || die "--out needs a directory"; out=$2; shift 2 ;;
        --out=*) out=${1#--out=}; shift ;;
        -j|--jobs) (($# >= 2)) || die "$1 needs a number"; jobs=$2; shift 2 ;;
        -j*) jobs=${1#-j}; shift ;;
        --jobs=*) jobs=${1#--jobs=}; shift ;;
        --exe) (($# >= 2)) || die "--exe needs a path"; exe=$2; shift 2 ;;
        --exe=*) exe=${1#--exe=}; shift ;;
        --nondimensional) nondimensional=(--nondimensional); shift ;;
        -h|--help) usage; exit 0 ;;
        -*) die "unknown option '$1'; see scripts/converge.sh --help" ;;
        *) [[ -z $input ]] || die "a second input file '$1' after '$input'"
           input=$1; shift ;;
    esac
done
[[ -n $input ]] || die "no input file; usage: scripts/converge.sh INPUT [--refine space|time|both] [--levels N] [--ratio R] [--out DIR]"
[[ -f $input && -r $input ]] || die "cannot read input file '$input'"
case $refine in
    space|time|both) ;;
    *) die "--refine: expected space, time or both, got '$refine'" ;;
esac
[[ $levels =~ ^[0-9]+$ ]] || die "--levels: expected an integer >= 2, got '$levels'"
levels=$((10#$levels))
((levels >= 2)) || die "--levels: at least 2 levels are needed (3 or more to observe the order), got $levels"
number='^[+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?$'
[[ $ratio =~ $number ]] || die "--ratio: expected a number > 1, got '$ratio'"
awk -v r="$ratio" 'BEGIN { exit !(r > 1) }' || die "--ratio: the refinement ratio must be > 1, got $ratio"
[[ -z $jobs ]] && jobs=$(nproc 2> /dev/null || echo 1)
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-j: expected a positive integer, got '$jobs'"
[[ -x $exe ]] || die "rodcontact not found at '$exe': build it with scripts/setup.sh, or pass --exe PATH (or set RODCONTACT)"
exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
export RODCONTACT=$exe
PY=$("$repo_root/scripts/lib/find_python.sh") || exit 2
stem=$(basename "$input")
[[ -n $out ]] || out=out/converge_${stem%.*}

# ---------------------------------------------------------------- the --set values
# converge.sh sets these itself at every level but 0 (where the user's values stand);
# output.series_every = 1 at every level
owned="output.series_every"
[[ $refine != time ]] && owned+=" mesh.n_elements"
[[ $refine != space ]] && owned+=" time.dt output.snapshot_every output.snapshot_dt"
for s in "${user_sets[@]}"; do
    [[ $s == *=* ]] || die "--set '$s': expected group.variable=value"
    target=${s%%=*}
    target=${target,,}
    case $target in
        output.prefix|output.quiet) die "--set '$s': converge.sh sets $target itself (DIR/level_<k>/point_0000)" ;;
        time.adaptive|mesh.adaptive)
            [[ ${s#*=} =~ ^[[:space:]]*\.?[fF] ]] ||
                die "--set '$s': converge.sh refines fixed steps on uniform meshes; adaptive steps and meshes are refused" ;;
    esac
    [[ $s != *';'* ]] || die "--set '$s': a value may not hold ';'"
done
# The early check of adaptivity in INPUT (the exact one reads level 0's file)
if grep -v '^[[:space:]]*!' "$input" | grep -qiE '(^|[[:space:],&])adaptive[[:space:]]*=[[:space:]]*\.?t'; then
    adaptive_off=0
    for s in "${user_sets[@]}"; do
        [[ ${s,,} =~ ^(time|mesh)\.adaptive=[[:space:]]*\.?f ]] && adaptive_off=$((adaptive_off + 1))
    done
    ((adaptive_off >= 1)) ||
        die "'$input' asks for adaptive steps or an adaptive mesh: converge.sh refines fixed steps on uniform meshes (--set time.adaptive=.false. --set mesh.adaptive=.false. to check the fixed-step run)"
fi

# scan_axis SET: the --set of scan.sh that gives SET's value as one point (a value holding
# ',' or ':' goes in a one-item ';' list)
scan_axis() {
    local s=$1
    if [[ ${s#*=} == *[,:]* ]]; then
        printf '%s;' "$s"
    else
        printf '%s' "$s"
    fi
}

# level_args K: ARGS = scan.sh's --set arguments of level K (after level 0 is known)
level_args() {
    local k=$1 s target keep
    ARGS=()
    for s in "${user_sets[@]}"; do
        target=${s%%=*}
        target=${target,,}
        keep=1
        [[ $target == output.series_every ]] && keep=0
        ((k > 0)) && [[ " $owned " == *" $target "* ]] && keep=0
        ((keep)) && ARGS+=(--set "$(scan_axis "$s")")
    done
    ARGS+=(--set output.series_every=1)
    ((k == 0)) && return
    [[ $refine != time ]] && ARGS+=(--set "mesh.n_elements=$(awk -v n="$n0" -v r="$ratio" -v k="$k" 'BEGIN { printf "%d", n * r^k + 0.5 }')")
    if [[ $refine != space ]]; then
        ARGS+=(--set "time.dt=$(awk -v d="$dt0" -v r="$ratio" -v k="$k" 'BEGIN { printf "%.17g", d / r^k }')")
        if awk -v s="$snap_dt0" 'BEGIN { exit !(s > 0) }'; then
            ARGS+=(--set "output.snapshot_dt=$snap_dt0")
        else
            local m
            m=$(awk -v r="$ratio" -v k="$k" -v e="$snap_every0" 'BEGIN { m = e * r^k; printf (m == int(m)) ? "%d" : "", m }')
            if [[ -n $m ]]; then
                ARGS+=(--set "output.snapshot_every=$m")
            else
                ARGS+=(--set "output.snapshot_dt=$(awk -v d="$dt0" -v e="$snap_every0" 'BEGIN { printf "%.17g", d * e }')")
            fi
        fi
    fi
}

# run_level K: the one-point scan of level K in DIR/level_K (its log: DIR/level_K.log); in a
# background subshell the scan replaces it (exec), so that the signal trap below reaches it
run_level() {
    local k=$1
    level_args "$k"
    exec bash "$repo_root/scripts/scan.sh" "$input" "${ARGS[@]}" --out "$out/level_$k" -j 1 --exe "$exe" \
        > "$out/level_$k.log" 2>&1
}

mkdir -p "$out" || die "cannot create '$out'"
file0=$out/level_0/point_0000.h5

# ---------------------------------------------------------------- level 0, the input itself
pids=()
on_signal() {
    local sig=$1
    trap '' INT TERM
    for pid in "${pids[@]}"; do
        kill -TERM "$pid" 2> /dev/null
    done
    wait
    echo "converge: interrupted (signal $sig); rerun the same command to resume (complete levels are kept)" >&2
    exit $((sig == 2 ? 130 : 143))
}
trap 'on_signal 2' INT
trap 'on_signal 15' TERM
echo "converge: level 0 (the input) in $out/level_0/" >&2
run_level 0 &
pids=($!)
wait "${pids[0]}"
rc=$?
if ((rc != 0)); then
    echo "converge: level 0 failed (exit $rc):" >&2
    grep -h 'scan: \(error\|point\)' "$out/level_0.log" >&2 || tail -n 3 "$out/level_0.log" >&2
    ((rc == 2)) && exit 2
    exit 1
fi
attr() { "$PY" "$repo_root/scripts/lib/rodrun.py" attr "$file0" "$@"; }
n0=$(attr mesh.n_elements) && dt0=$(attr time.dt) && snap_every0=$(attr output.snapshot_every) &&
    snap_dt0=$(attr output.snapshot_dt 0) && time_adaptive=$(attr time.adaptive 0) &&
    mesh_adaptive=$(attr mesh.adaptive 0) || die "cannot read the input values from $file0"
# the file records the nondimensional values run; an SI input (root attribute units) takes
# its times in s: dt0 and snap_dt0 back in the input's units for the --set of the levels
if [[ $(attr units nondimensional) == SI ]]; then
    t_scale=$(attr scale.time) || die "cannot read scale.time from $file0"
    dt0=$(awk -v d="$dt0" -v s="$t_scale" 'BEGIN { printf "%.17g", d * s }')
    snap_dt0=$(awk -v d="$snap_dt0" -v s="$t_scale" 'BEGIN { printf "%.17g", d * s }')
fi
[[ $time_adaptive == 0 && $mesh_adaptive == 0 ]] ||
    die "the input asks for adaptive steps or an adaptive mesh: converge.sh refines fixed steps on uniform meshes (--set time.adaptive=.false. --set mesh.adaptive=.false.)"

# ---------------------------------------------------------------- the finer levels, finest first
echo "converge: levels 1..$((levels - 1)) ($refine refined by $ratio each) with -j $jobs: logs in $out/level_<k>.log" >&2
running=0
for ((k = levels - 1; k >= 1; k--)); do
    if ((running >= jobs)); then
        wait -n
        running=$((running - 1))
    fi
    run_level "$k" &
    pids+=($!)
    running=$((running + 1))
done
wait
trap - INT TERM
failed=0
for ((k = 1; k < levels; k++)); do
    rc=""
    [[ -f $out/level_$k/point_0000.status ]] && read -r rc < "$out/level_$k/point_0000.status"
    [[ $rc == 0 && -f $out/level_$k/point_0000.h5 ]] && continue
    echo "converge: level $k failed: $(grep -h -m 1 'scan: \(error\|point\)' "$out/level_$k.log" || tail -n 1 "$out/level_$k.log")" >&2
    failed=1
done
((failed == 0)) || exit 1

# ---------------------------------------------------------------- the analysis
files=()
for ((k = 0; k < levels; k++)); do
    files+=("$out/level_$k/point_0000.h5")
done
"$PY" "$repo_root/scripts/lib/converge.py" "$out" --refine "$refine" "${nondimensional[@]}" "${files[@]}"
