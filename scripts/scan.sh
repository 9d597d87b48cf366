#!/usr/bin/env bash
# Parameter scans with rodcontact: the Cartesian product of value lists, run in parallel,
# resumable, every point accounted for in one CSV. Documentation: docs/scans.md.
#
#   scripts/scan.sh INPUT --set AXIS [--set AXIS ...] --out DIR [-j N]   run the scan
#   scripts/scan.sh INPUT --set AXIS ... --list                          print the points
#   scripts/scan.sh INPUT --set AXIS ... --out DIR --task K              run point K only
#   scripts/scan.sh INPUT --set AXIS ... --out DIR --collect             write DIR/summary.csv
#
# AXIS is TARGET=VALUES:
#   TARGET   group.variable or 'group.variable(i)' (element i of an array; quote it for the
#            shell), or several joined by '+', which then take the same value at every point
#            ('initial.theta0_step(1)+initial.p0_step(1)=2:30:15').
#   VALUES   a:b:n        n values from a to b, evenly spaced, both ends included
#            a:b:n:log    n values from a to b, evenly spaced in log (a, b > 0)
#            v1,v2,...    a list
#            x1;x2;...    a list whose items may hold commas: whole arrays, 'theta0_step=5,0.1;10,0.1'
#            v            one value: the same at every point
# The points are numbered 0..N-1, the last --set varying fastest. Point K runs
#   rodcontact DIR/input.nml --set TARGET=value ... --set output.prefix=DIR/point_K --set output.quiet=.true.
# and leaves DIR/point_K.h5 (when the run got that far), DIR/point_K.err (its stderr) and
# DIR/point_K.status (line 1: exit status, line 2: its error message, if any).
#
# Options: -j N / --jobs N   points run at once (default: the number of cores, nproc)
#          --exe PATH        the rodcontact executable (default: $RODCONTACT, else build/rodcontact)
# A rerun of the same command skips the points whose .h5 has status 'complete' and runs the
# others (failed, never run, or interrupted). DIR keeps a copy of INPUT (input.nml) and the
# point list (points.txt): a rerun with another input or other axes is refused.
# Exit status: 0 every point run is complete; 1 some point failed (recorded, see the CSV);
# 2 usage error; 130/143 interrupted (rerun the same command to resume).

set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

die() {
    echo "scan: error: $*" >&2
    exit 2
}

usage() {
    sed -n '2,/^$/s/^# \{0,1\}//p' "${BASH_SOURCE[0]}"
}

# ---------------------------------------------------------------- command line
input=""
out=""
jobs=""
exe="${RODCONTACT:-$repo_root/build/rodcontact}"
mode=run
task=""
specs=()
while (($# > 0)); do
    case $1 in
        --set) (($# >= 2)) || die "--set needs TARGET=VALUES, e.g. --set model.varpi=0:1:11"
               specs+=("$2"); shift 2 ;;
        --set=*) specs+=("${1#--set=}"); shift ;;
        --out) (($# >= 2)) || die "--out needs a directory"; out=$2; shift 2 ;;
        --out=*) out=${1#--out=}; shift ;;
        -j|--jobs) (($# >= 2)) || die "$1 needs a number"; jobs=$2; shift 2 ;;
        -j*) jobs=${1#-j}; shift ;;
        --jobs=*) jobs=${1#--jobs=}; shift ;;
        --exe) (($# >= 2)) || die "--exe needs a path"; exe=$2; shift 2 ;;
        --exe=*) exe=${1#--exe=}; shift ;;
        --list) mode=list; shift ;;
        --collect) mode=collect; shift ;;
        --task) (($# >= 2)) || die "--task needs a point number"; mode=task; task=$2; shift 2 ;;
        --task=*) mode=task; task=${1#--task=}; shift ;;
        -h|--help) usage; exit 0 ;;
        -*) die "unknown option '$1'; see scripts/scan.sh --help" ;;
        *) [[ -z $input ]] || die "a second input file '$1' after '$input'"
           input=$1; shift ;;
    esac
done
[[ -n $input ]] || die "no input file; usage: scripts/scan.sh INPUT --set TARGET=VALUES ... --out DIR"
[[ -f $input ]] || die "cannot read input file '$input'"
((${#specs[@]} > 0)) || die "no --set TARGET=VALUES: nothing to scan"
if [[ -z $jobs ]]; then
    jobs=$(nproc 2>/dev/null || echo 1)
fi
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-j: expected a positive integer, got '$jobs'"

# ---------------------------------------------------------------- the axes
# Axis i: targets axis_targets[i] ('+'-joined), values values[axis_first[i] ...] (axis_count[i]).
axis_targets=()
axis_first=()
axis_count=()
values=()
all_targets=()
number='[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eEdD][-+]?[0-9]+)?'

# print_items SEPARATOR SPEC: the items of SPEC, trimmed, one per line (empty ones dropped)
print_items() {
    local -a items
    local item
    IFS=$1 read -r -a items <<< "$2"
    for item in "${items[@]}"; do
        item=${item#"${item%%[![:space:]]*}"}
        item=${item%"${item##*[![:space:]]}"}
        [[ -n $item ]] && printf '%s\n' "$item"
    done
    return 0
}

# expand_values SPEC: the values of SPEC, one per line (runs in a subshell: errors print
# their message and give no values)
expand_values() {
    local spec=$1
    if [[ $spec == *';'* ]]; then
        print_items ';' "$spec"
    elif [[ $spec =~ ^($number):($number):([0-9]+)(:log)?$ ]]; then
        local a=${BASH_REMATCH[1]} b=${BASH_REMATCH[4]} n=$((10#${BASH_REMATCH[7]})) log=${BASH_REMATCH[8]}
        a=${a//[dD]/e}
        b=${b//[dD]/e}
        ((n >= 1)) || die "range '$spec': n must be >= 1"
        awk -v a="$a" -v b="$b" -v n="$n" -v log_spaced="${log:+1}" 'BEGIN {
            if (log_spaced && (a <= 0 || b <= 0)) { print "log range needs a, b > 0" > "/dev/stderr"; exit 1 }
            for (i = 0; i < n; i++) {
                f = (n == 1) ? 0 : i / (n - 1)
                if (log_spaced) v = (i == n - 1 && n > 1) ? b : exp(log(a) + f * (log(b) - log(a)))
                else v = (i == n - 1 && n > 1) ? b : a + f * (b - a)
                printf "%.10g\n", v
            }
        }' || die "range '$spec': log spacing needs a, b > 0"
    else
        print_items ',' "$spec"
    fi
}

for spec in "${specs[@]}"; do
    [[ $spec == *=* ]] || die "--set '$spec': expected TARGET=VALUES, e.g. model.varpi=0:1:11"
    lhs=${spec%%=*}
    rhs=${spec#*=}
    IFS='+' read -r -a targets <<< "$lhs"
    ((${#targets[@]} > 0)) || die "--set '$spec': no target before '='"
    for target in "${targets[@]}"; do
        [[ $target =~ ^[A-Za-z][A-Za-z0-9_]*\.[A-Za-z][A-Za-z0-9_]*(\([0-9]+\))?$ ]] ||
            die "--set '$spec': '$target' is not group.variable or group.variable(i)"
        case ${target,,} in
            output.prefix|output.quiet)
                die "--set '$spec': the scan sets $target itself (DIR/point_K, quiet)" ;;
        esac
        for seen in "${all_targets[@]}"; do
            [[ ${seen,,} == "${target,,}" ]] && die "--set '$spec': $target is scanned twice"
        done
        all_targets+=("$target")
    done
    mapfile -t axis_values < <(expand_values "$rhs")
    ((${#axis_values[@]} > 0)) || die "--set '$spec': no values after '='"
    axis_targets+=("$lhs")
    axis_first+=("${#values[@]}")
    axis_count+=("${#axis_values[@]}")
    values+=("${axis_values[@]}")
done
n_axes=${#axis_targets[@]}
n_points=1
for count in "${axis_count[@]}"; do
    n_points=$((n_points * count))
done
width=$(( ${#n_points} > 4 ? ${#n_points} : 4 ))

# point_values K: POINT_VALUES[i] = value of axis i at point K (last axis fastest)
point_values() {
    local rem=$1 i
    POINT_VALUES=()
    for ((i = n_axes - 1; i >= 0; i--)); do
        POINT_VALUES[i]=${values[axis_first[i] + rem % axis_count[i]]}
        rem=$((rem / axis_count[i]))
    done
}

# point_args K: POINT_ARGS = the --set arguments of point K
point_args() {
    local i target
    point_values "$1"
    POINT_ARGS=()
    for ((i = 0; i < n_axes; i++)); do
        IFS='+' read -r -a targets <<< "${axis_targets[i]}"
        for target in "${targets[@]}"; do
            POINT_ARGS+=(--set "$target=${POINT_VALUES[i]}")
        done
    done
}

# shell_word ARG: WORD = ARG quoted for a shell when it needs it
shell_word() {
    if [[ $1 =~ ^[A-Za-z0-9_.,:=+/@%-]+$ ]]; then
        WORD=$1
    else
        WORD="'${1//\'/\'\\\'\'}'"
    fi
}

# point_line K: 'K --set a=1 --set b=2', the line of --list and points.txt
point_line() {
    local arg line
    point_args "$1"
    printf -v line "%0${width}d" "$1"
    for arg in "${POINT_ARGS[@]}"; do
        shell_word "$arg"
        line+=" $WORD"
    done
    printf '%s\n' "$line"
}

if [[ $mode == list ]]; then
    for ((k = 0; k < n_points; k++)); do
        point_line "$k"
    done
    exit 0
fi

# ---------------------------------------------------------------- the scan directory
[[ -n $out ]] || die "no --out DIR: where the points' files go"
[[ -x $exe ]] || die "rodcontact not found at '$exe': build it with scripts/setup.sh, or pass --exe PATH (or set RODCONTACT)"
mkdir -p "$out" || die "cannot create '$out'"

# install_or_compare NEW DEST WHAT: DEST := NEW the first time; afterwards they must agree
install_or_compare() {
    local new=$1 dest=$2 what=$3
    if [[ -f $dest ]]; then
        cmp -s "$new" "$dest" || die "'$out' holds a scan with another $what ($dest differs); rerun with the same input and --set, or use another --out"
        rm -f "$new"
    else
        mv -f "$new" "$dest" || die "cannot write '$dest'"
    fi
}
tmp_input=$(mktemp "$out/.input.XXXXXX") || die "cannot write in '$out'"
cp "$input" "$tmp_input" || die "cannot copy '$input' into '$out'"
install_or_compare "$tmp_input" "$out/input.nml" "input file"
tmp_points=$(mktemp "$out/.points.XXXXXX") || die "cannot write in '$out'"
for ((k = 0; k < n_points; k++)); do
    point_line "$k"
done > "$tmp_points"
install_or_compare "$tmp_points" "$out/points.txt" "list of points"

# point_stem K: STEM = DIR/point_K (K zero-padded), the prefix of the point's files
point_stem() {
    printf -v STEM "%s/point_%0${width}d" "$out" "$1"
}

# parse_csv LINE: CSV = the fields of one RFC 4180 line
parse_csv() {
    local line=$1
    CSV=()
    while :; do
        if [[ $line == \"* ]]; then
            [[ $line =~ ^\"(([^\"]|\"\")*)\"(,|$) ]] || return 1
            CSV+=("${BASH_REMATCH[1]//\"\"/\"}")
            line=${line:${#BASH_REMATCH[0]}}
            [[ -n ${BASH_REMATCH[3]} ]] || break
        else
            CSV+=("${line%%,*}")
            [[ $line == *,* ]] || break
            line=${line#*,}
        fi
    done
}

# csv_escape TEXT: FIELD = TEXT as one CSV field (RFC 4180)
csv_escape() {
    if [[ $1 == *[,\"$'\n'$'\r']* ]]; then
        FIELD="\"${1//\"/\"\"}\""
    else
        FIELD=$1
    fi
}

# point_complete_file FILE.h5: true when FILE.h5 exists with status 'complete'
point_complete_file() {
    local row
    [[ -f $1 ]] || return 1
    row=$("$exe" --summary "$1" 2> /dev/null) || return 1
    parse_csv "$row" || return 1
    [[ ${CSV[1]:-} == complete ]]
}

# point_complete K: true when point K is finished: DIR/point_K.h5 with status 'complete'
point_complete() {
    point_stem "$1"
    point_complete_file "$STEM.h5"
}

# record_status STEM RC: DIR/point_K.status = exit status and the run's error message
record_status() {
    local stem=$1 rc=$2 message
    message=$(grep -m 1 '^rodcontact: error' "$stem.err" || tail -n 1 "$stem.err")
    printf '%s\n%s\n' "$rc" "$message" > "$stem.status.tmp" && mv -f "$stem.status.tmp" "$stem.status"
    [[ -s $stem.out ]] || rm -f "$stem.out"
}

# run_point K: run point K in the foreground; record its exit status and message
run_point() {
    local k=$1 stem child="" rc=""
    point_stem "$k"
    stem=$STEM
    point_args "$k"
    rm -f "$stem.h5" "$stem.h5.part" "$stem.status" "$stem.err" "$stem.out"
    # on TERM (from the scan's interrupt handler, or Slurm) or INT (Ctrl-C reaches the whole
    # process group; rodcontact, started with &, ignores it) on_point_term stops the run
    trap 'on_point_term' TERM INT
    "$exe" "$out/input.nml" "${POINT_ARGS[@]}" --set "output.prefix=$stem" --set output.quiet=.true. \
        > "$stem.out" 2> "$stem.err" < /dev/null &
    child=$!
    wait "$child"
    rc=$?
    record_status "$stem" "$rc"
    trap - TERM INT
    return "$rc"
}

# The TERM trap of run_point (it sees run_point's locals stem, child, rc). A run that had
# ended is recorded as usual; a run cut short is not recorded at all (its .part removed),
# so that the point counts as not run and the next rerun does it again.
on_point_term() {
    trap '' TERM INT
    if [[ -n $rc ]]; then
        record_status "$stem" "$rc"
        exit "$rc"
    fi
    if [[ -z $child ]]; then
        # TERM came between the start of the run and 'child=$!': the run is this
        # subshell's only job
        child=$(jobs -p)
        [[ -n $child ]] || exit 143
    fi
    kill -TERM "$child" 2> /dev/null
    wait "$child"
    rc=$?
    if [[ ! -f $stem.h5 ]]; then
        rm -f "$stem.h5.part" "$stem.out"
        exit 143
    fi
    # the run got to its end (the .h5 is renamed last) just before the signal; when the
    # interrupted wait lost its exit status, it follows from the file: rodcontact exits 0
    # exactly when it writes status 'complete', 3 after a numerical failure
    if ((rc != 0 && rc != 3)); then
        rc=3
        point_complete_file "$stem.h5" && rc=0
    fi
    record_status "$stem" "$rc"
    exit "$rc"
}

hms() {
    local s=$1
    if ((s >= 3600)); then
        printf '%dh%02dm%02ds' $((s / 3600)) $((s % 3600 / 60)) $((s % 60))
    elif ((s >= 60)); then
        printf '%dm%02ds' $((s / 60)) $((s % 60))
    else
        printf '%ds' "$s"
    fi
}

# ---------------------------------------------------------------- --collect
collect() {
    local csv="$out/summary.csv" tmp header k i stem status exit_status row rest n_rest
    local n_complete=0 n_failed=0 n_missing=0
    header=$("$exe" --summary-header) && parse_csv "$header" ||
        die "'$exe --summary-header' failed: is it an older rodcontact without --summary?"
    local -a summary_columns=("${CSV[@]}")
    n_rest=$((${#summary_columns[@]} - 2))
    tmp=$(mktemp "$out/.summary.XXXXXX") || die "cannot write in '$out'"
    header="point"
    for target in "${all_targets[@]}"; do
        csv_escape "$target"
        header+=",$FIELD"
    done
    header+=",status,exit_status,file"
    for ((i = 2; i < ${#summary_columns[@]}; i++)); do
        header+=",${summary_columns[i]}"
    done
    printf '%s\n' "$header" > "$tmp"
    for ((k = 0; k < n_points; k++)); do
        point_stem "$k"
        stem=$STEM
        point_values "$k"
        row="$k"
        for ((i = 0; i < n_axes; i++)); do
            IFS='+' read -r -a targets <<< "${axis_targets[i]}"
            for target in "${targets[@]}"; do
                csv_escape "${POINT_VALUES[i]}"
                row+=",$FIELD"
            done
        done
        exit_status=""
        message=""
        if [[ -f $stem.status ]]; then
            { IFS= read -r exit_status; IFS= read -r message; } < "$stem.status"
        fi
        rest=""
        if [[ -f $stem.h5 ]] && summary=$("$exe" --summary "$stem.h5" 2>&1) && parse_csv "$summary"; then
            status=${CSV[1]}
            csv_escape "${CSV[0]}"
            rest=",$FIELD"
            for ((i = 2; i < ${#CSV[@]}; i++)); do
                csv_escape "${CSV[i]}"
                rest+=",$FIELD"
            done
        else
            if [[ -f $stem.h5 ]]; then
                status="failed: cannot summarise $stem.h5: ${summary#rodcontact: }"
            elif [[ -n $exit_status && $exit_status != 0 ]]; then
                status="failed: exit $exit_status: ${message#rodcontact: }"
            else
                status=missing
            fi
            rest=","
            for ((i = 0; i < n_rest; i++)); do
                rest+=","
            done
        fi
        case $status in
            complete) n_complete=$((n_complete + 1)) ;;
            missing) n_missing=$((n_missing + 1)) ;;
            *) n_failed=$((n_failed + 1)) ;;
        esac
        csv_escape "$status"
        printf '%s,%s,%s%s\n' "$row" "$FIELD" "$exit_status" "$rest"
    done >> "$tmp"
    mv -f "$tmp" "$csv" || die "cannot write '$csv'"
    echo "scan: $csv: $n_points points: $n_complete complete, $n_failed failed, $n_missing missing" >&2
}

if [[ $mode == collect ]]; then
    collect
    exit 0
fi

# ---------------------------------------------------------------- --task K
if [[ $mode == task ]]; then
    [[ $task =~ ^[0-9]+$ ]] || die "--task: expected a point number 0..$((n_points - 1)), got '$task'"
    task=$((10#$task))
    ((task < n_points)) || die "--task $task: the scan has points 0..$((n_points - 1))"
    if point_complete "$task"; then
        point_stem "$task"
        echo "scan: point $task already complete ($STEM.h5), skipped" >&2
        exit 0
    fi
    run_point "$task"
    rc=$?
    if ((rc != 0)); then
        point_stem "$task"
        echo "scan: point $task failed (exit $rc): $(sed -n 2p "$STEM.status")" >&2
    fi
    exit "$rc"
fi

# ---------------------------------------------------------------- run: a pool of -j jobs
((BASH_VERSINFO[0] > 5 || (BASH_VERSINFO[0] == 5 && BASH_VERSINFO[1] >= 1))) ||
    die "running points in parallel needs bash >= 5.1 (wait -n -p); this is $BASH_VERSION: use --task K per point"

pending=()
for ((k = 0; k < n_points; k++)); do
    point_complete "$k" || pending+=("$k")
done
n_run=${#pending[@]}
n_skipped=$((n_points - n_run))
echo "scan: $n_points points in $out/, $n_skipped already complete, $n_run to run with -j $jobs" >&2

declare -A running=()
n_ok=0
n_bad=0
start=$SECONDS
tty=0
[[ -t 2 ]] && tty=1
last_decile=0

progress() {
    local done=$((n_ok + n_bad)) elapsed=$((SECONDS - start)) eta="?" line decile
    ((done > 0)) && eta=$(hms $((elapsed * (n_run - done) / done)))
    line="scan: $done/$n_run run ($n_ok complete, $n_bad failed), ${#running[@]} running, $((n_run - done)) remaining, $(hms "$elapsed") elapsed, ETA $eta"
    if ((tty)); then
        printf '\r\033[K%s' "$line" >&2
    else
        decile=$((n_run > 0 ? 10 * done / n_run : 10))
        if ((decile > last_decile || done == n_run)); then
            last_decile=$decile
            echo "$line" >&2
        fi
    fi
}

on_interrupt() {
    local sig=$1 pid
    trap '' INT TERM
    # every point running: the table, and any job started just before the signal but not
    # entered in the table yet
    for pid in "${!running[@]}" $(jobs -p); do
        kill -TERM "$pid" 2> /dev/null
    done
    wait 2> /dev/null
    ((tty)) && echo >&2
    echo "scan: interrupted ($sig): $n_ok complete, $n_bad failed, $((n_run - n_ok - n_bad)) not finished; rerun the same command to resume" >&2
    exit $((sig == 2 ? 130 : 143))
}
trap 'on_interrupt 2' INT
trap 'on_interrupt 15' TERM

reap_one() {
    local pid="" rc stem
    wait -n -p pid
    rc=$?
    [[ -n $pid ]] || return 0
    point_stem "${running[$pid]}"
    stem=$STEM
    if ((rc == 0)); then
        n_ok=$((n_ok + 1))
    else
        n_bad=$((n_bad + 1))
        ((tty)) && printf '\r\033[K' >&2
        echo "scan: point ${running[$pid]} failed (exit $rc): $(sed -n 2p "$stem.status" 2>/dev/null)" >&2
    fi
    unset "running[$pid]"
    progress
}

for k in "${pending[@]}"; do
    while ((${#running[@]} >= jobs)); do
        reap_one
    done
    run_point "$k" &
    running[$!]=$k
done
while ((${#running[@]} > 0)); do
    reap_one
done
((tty && n_run > 0)) && echo >&2
trap - INT TERM
echo "scan: done in $(hms $((SECONDS - start))): $n_ok complete, $n_bad failed (messages in $out/point_*.status, .err)" >&2
collect
((n_bad == 0))
