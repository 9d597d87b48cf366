#!/usr/bin/env bash
# Parameter scans with rodcontact: the Cartesian product of value lists, run in parallel by
# GNU parallel, resumable, every point accounted for in one CSV. Documentation: docs/scans.md.
#
#   scripts/scan.sh INPUT --set AXIS [--set AXIS ...] --out DIR [-j N]   run the scan
#   scripts/scan.sh INPUT --set AXIS ... --list                          print the points
#   scripts/scan.sh INPUT --set AXIS ... --out DIR [--batch B] --task T  run task T only
#   scripts/scan.sh INPUT --set AXIS ... --out DIR [--batch B] --array   print task indices
#   scripts/scan.sh INPUT --set AXIS ... --out DIR --collect             write DIR/summary.csv
#   scripts/scan.sh INPUT --set AXIS ... --out DIR [--batch B] --slurm [SBATCH OPTIONS] [%N]
#                            submit the Slurm array and a collect job after it; print both ids
#
# AXIS is TARGET=VALUES:
#   TARGET   group.variable or 'group.variable(i)' (element i of an array; quote it for the
#            shell), or several joined by '+', which then take the same value at every point
#            ('initial.theta0_step(1)+initial.p0_step(1)=2:30:15').
#   VALUES   a:b:n        n values from a to b, evenly spaced, both ends included
#            a:b:n:log    n values from a to b, evenly spaced in log (a, b > 0)
#            v1,v2,...    a list
#            x1;x2;...    a list whose items may hold commas or colons: whole arrays,
#                         'theta0_step=5,0.1;10,0.1'
#            v            one value: the same at every point
# The points are numbered 0..N-1, the last --set varying fastest. Point K runs
#   rodcontact DIR/input.nml --set TARGET=value ... --set output.prefix=DIR/point_K --set output.quiet=.true.
# and leaves DIR/point_K.h5 (when the run got that far), DIR/point_K.err (its stderr) and
# DIR/point_K.status (line 1: exit status, line 2: its error message, if any).
#
# Before any point runs, every axis is checked: each target a group.variable, each range
# well formed, and every point to run read and validated by 'rodcontact --check' (no file
# written); a scan that fails a check exits 2 naming the axis (or the point) and runs nothing.
#
# Options: -j N / --jobs N   points run at once (default: the number of cores, nproc; with
#                            --task: $SLURM_CPUS_PER_TASK, else 1)
#          --batch B         points per task of --task and --array (default 1): task T runs
#                            points T*B .. T*B+B-1
#          --exe PATH        the rodcontact executable (default: $RODCONTACT, else build/rodcontact
#                            in a source tree, PREFIX/bin/rodcontact installed: scripts/lib/find_rodcontact.sh)
#          --nondimensional  summary.csv in the files' own nondimensional values (default: the
#                            input's units: SI with &material, each column's unit in its name)
# The points run under GNU parallel (Debian package 'parallel'); DIR/joblog is its job log
# of the latest run. A rerun of the same command skips the points whose .h5 has status
# 'complete' and runs the others (failed, never run, or interrupted); an interrupted point
# continues from the checkpoint its run wrote when it was stopped (DIR/point_K.h5.part).
# On SIGTERM or SIGINT the scan stops its runs (each finishes its step and writes its
# checkpoint) and exits once they have ended. One scan at a time in DIR: another one started
# there while it runs is refused (exit 2, naming it; DIR/.scan.lock).
# --slurm: the words after it go to sbatch (e.g. --partition=P --account=A --time=1:00:00),
# a word %N throttles the array to N tasks at once; logs in DIR/slurm/. DIR keeps a copy of
# INPUT (input.nml) and the point list (points.txt): a rerun with another input or other
# axes is refused. --array prints the Slurm array indices of the tasks that still have
# points to run ('0-9', '2,5-7'; nothing when every point is complete).
# Exit status: 0 every point run is complete; 1 some point failed (recorded, see the CSV);
# 2 usage error, a scan that fails its checks, or another scan running in DIR; 5 a point's run
# was stopped by a signal (not the scan; rerun to resume it); 130/143 interrupted (rerun to
# resume).

set -uo pipefail

script="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$(basename "${BASH_SOURCE[0]}")"
command_line="$0 $*"
repo_root="$(cd "$(dirname "$script")/.." && pwd)"

die() {
    echo "scan: error: $*" >&2
    exit 2
}

usage() {
    sed -n '2,/^$/s/^# \{0,1\}//p' "$script"
}

# ---------------------------------------------------------------- one point (GNU parallel's job)
# scan.sh --point-run DIR K ARGS...    run point K of the scan in DIR (K zero-padded) with the
#                                      --set arguments ARGS, record its exit status
# scan.sh --points-check INPUT        rodcontact --check of INPUT for each point on stdin (one
#                                      per line: K and its --set arguments, tab-separated); at
#                                      the first failure prints 'K<TAB>message' on stdout, stops
# Both use $RODCONTACT, exported by the scan.

# record_status STEM RC: STEM.status = exit status and the run's error message
record_status() {
    local stem=$1 rc=$2 message
    if ((rc == 5)); then
        message="$(grep -m 1 '^rodcontact: stopped by' "$stem.err" | sed 's/; continue it with.*//'); checkpoint in $stem.h5.part: rerun the scan to resume the point from it"
    elif ((rc > 128)); then
        message="killed by signal $((rc - 128)) before its first checkpoint: a rerun of the scan runs the point again"
    else
        message=$(grep -m 1 '^rodcontact: error' "$stem.err" || tail -n 1 "$stem.err")
    fi
    printf '%s\n%s\n' "$rc" "$message" > "$stem.status.tmp" && mv -f "$stem.status.tmp" "$stem.status"
    [[ -s $stem.out ]] || rm -f "$stem.out"
}

# run_point DIR K ARGS...: run the point in the foreground; record its exit status and message.
# A point interrupted before (its run stopped by a signal, exit 5) left DIR/point_K.h5.part with
# a checkpoint: the run continues it in place (rodcontact --resume, bit for bit the result of an
# uninterrupted run; docs/robustness.md); a .part without a usable checkpoint (a run killed
# before its first one) is dropped and the point runs from t = 0.
run_point() {
    local dir=$1 k=$2 stem rc resume=()
    shift 2
    stem=$dir/point_$k
    rm -f "$stem.h5" "$stem.status" "$stem.out"
    # (point_K.h5.resume: where scans before --resume moved the .part they continued)
    [[ -f $stem.h5.resume && ! -f $stem.h5.part ]] && mv -f "$stem.h5.resume" "$stem.h5.part"
    [[ -f $stem.h5.part ]] && resume=(--resume)
    # Signals. The scan stops its runs by sending SIGUSR1 to this shell (its pid in
    # DIR/.run.<scan>.K, <scan> = SCAN_ID, the scan's host and pid),
    # Ctrl-C's SIGINT and Slurm's SIGTERM (scancel) come to every process. rodcontact stops
    # cleanly on the first signal of each kind (a second one of the same kind ends it at once):
    # this shell passes one SIGUSR1 on, once, whatever came, and waits for the run to finish
    # its step, write its checkpoint and exit (5). A scan told to stop before this point started
    # (DIR/.stop.<scan>, checked after the pid file is written) runs nothing.
    local child="" stop_requested="" forwarded=""
    local run_file=$dir/.run.${SCAN_ID:-$$}.$k
    printf '%s\n' "$$" > "$run_file"
    if [[ -e $dir/.stop.${SCAN_ID:-$$} ]]; then
        rm -f "$run_file"
        return 143
    fi
    trap 'stop_requested=1; [[ -n $child && -z $forwarded ]] && { forwarded=1; kill -USR1 "$child" 2> /dev/null; }' TERM INT USR1
    while :; do
        child=""
        "$RODCONTACT" "$dir/input.nml" "$@" --set "output.prefix=$stem" \
            --set output.quiet=.true. "${resume[@]}" > "$stem.out" 2> "$stem.err" < /dev/null &
        child=$!
        [[ -n $stop_requested && -z $forwarded ]] && { forwarded=1; kill -USR1 "$child" 2> /dev/null; }
        while :; do
            wait "$child"
            rc=$?
            # a trap interrupted the wait while the run goes on (a zombie still counts)
            kill -0 "$child" 2> /dev/null || break
        done
        if ((rc == 2 && ${#resume[@]} > 0)) &&
                grep -q -F -e 'error in time.restart_from' -e "$stem.h5.part" "$stem.err"; then
            # no usable checkpoint in the file left behind: run the point from the start
            mv -f "$stem.err" "$stem.resume.err"
            rm -f "$stem.h5.part" "$stem.resume.h5.part" "$stem.h5.resume"
            resume=()
            [[ -z $stop_requested ]] && continue
            rc=143   # stopped meanwhile: the point counts as not run
        fi
        break
    done
    rm -f "$run_file"
    [[ -f $stem.h5 || -f $stem.h5.part ]] && rm -f "$stem.resume.err"
    if ((rc > 128)) && [[ ! -f $stem.h5 && ! -f $stem.h5.part ]]; then
        # killed by a signal before it wrote anything: not recorded, the point counts as not run
        rm -f "$stem.out"
        return "$rc"
    fi
    record_status "$stem" "$rc"
    if ((rc == 5 || rc > 128)); then
        echo "scan: point $k interrupted: $(sed -n 2p "$stem.status")" >&2
    elif ((rc != 0)); then
        echo "scan: point $k failed (exit $rc): $(sed -n 2p "$stem.status")" >&2
    fi
    return "$rc"
}

# check_point INPUT K ARGS...: the input checks of the point, nothing written
check_point() {
    local input=$1 k=$2 message rc
    shift 2
    message=$("$RODCONTACT" --check "$input" "$@" 2>&1 > /dev/null)
    rc=$?
    if ((rc != 0)); then
        message=$(grep -m 1 '^rodcontact: error' <<< "$message" || tail -n 1 <<< "$message")
        printf '%s\t%s\n' "$k" "${message:-rodcontact --check exited with status $rc}"
    fi
    return "$rc"
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

# complete_file FILE.h5: true when FILE.h5 exists with status 'complete'
complete_file() {
    local row
    [[ -f $1 ]] || return 1
    row=$("$RODCONTACT" --summary "$1" 2> /dev/null) || return 1
    parse_csv "$row" || return 1
    [[ ${CSV[1]:-} == complete ]]
}

case ${1:-} in
    --point-run)
        (($# >= 3)) || die "--point-run DIR K ARGS...: internal, run by GNU parallel"
        run_point "${@:2}"
        exit ;;
    --points-check)
        (($# == 2)) || die "--points-check INPUT: internal, run by GNU parallel"
        while IFS=$'\t' read -r -a words; do
            check_point "$2" "${words[@]}" || exit
        done
        exit 0 ;;
esac

# ---------------------------------------------------------------- command line
input=""
out=""
jobs=""
batch=1
exe=$("$repo_root/scripts/lib/find_rodcontact.sh")
mode=run
task=""
specs=()
sbatch_options=()
exe_given=""
nondimensional=()
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
        --batch) (($# >= 2)) || die "--batch needs a number of points per task"; batch=$2; shift 2 ;;
        --batch=*) batch=${1#--batch=}; shift ;;
        --exe) (($# >= 2)) || die "--exe needs a path"; exe=$2; exe_given=1; shift 2 ;;
        --exe=*) exe=${1#--exe=}; exe_given=1; shift ;;
        --list) mode=list; shift ;;
        --nondimensional) nondimensional=(--nondimensional); shift ;;
        --collect) mode=collect; shift ;;
        --array) mode=array; shift ;;
        --task) (($# >= 2)) || die "--task needs a task number"; mode=task; task=$2; shift 2 ;;
        --task=*) mode=task; task=${1#--task=}; shift ;;
        --slurm) mode=slurm; shift; sbatch_options=("$@"); break ;;
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
    if [[ $mode == task ]]; then
        jobs=${SLURM_CPUS_PER_TASK:-1}
    else
        jobs=$(nproc 2>/dev/null || echo 1)
    fi
fi
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-j: expected a positive integer, got '$jobs'"
[[ $batch =~ ^[1-9][0-9]*$ ]] || die "--batch: expected a positive integer, got '$batch'"
batch=$((10#$batch))

# ---------------------------------------------------------------- the axes
# Axis i: spec specs[i], targets axis_targets[i] ('+'-joined), values values[axis_first[i] ...]
# (axis_count[i]).
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

# expand_values AXIS SPEC: the values of SPEC, one per line (runs in a subshell: errors print
# their message and give no values)
expand_values() {
    local axis=$1 spec=$2
    if [[ $spec == *';'* ]]; then
        print_items ';' "$spec"
    elif [[ $spec == *:* ]]; then
        [[ $spec =~ ^($number):($number):([0-9]+)(:log)?$ ]] ||
            die "--set '$axis': '$spec' is not a range a:b:n or a:b:n:log (a, b numbers, n a count; a value that holds ':' goes in a ';' list: '$spec;')"
        local a=${BASH_REMATCH[1]} b=${BASH_REMATCH[4]} n=$((10#${BASH_REMATCH[7]})) log=${BASH_REMATCH[8]}
        a=${a//[dD]/e}
        b=${b//[dD]/e}
        ((n >= 1)) || die "--set '$axis': range '$spec': n must be >= 1"
        awk -v a="$a" -v b="$b" -v n="$n" -v log_spaced="${log:+1}" 'BEGIN {
            if (log_spaced && (a <= 0 || b <= 0)) exit 1
            for (i = 0; i < n; i++) {
                f = (n == 1) ? 0 : i / (n - 1)
                if (log_spaced) v = (i == n - 1 && n > 1) ? b : exp(log(a) + f * (log(b) - log(a)))
                else v = (i == n - 1 && n > 1) ? b : a + f * (b - a)
                printf "%.10g\n", v
            }
        }' || die "--set '$axis': range '$spec': log spacing needs a, b > 0"
    else
        print_items ',' "$spec"
    fi
}

for spec in "${specs[@]}"; do
    [[ $spec == *=* ]] || die "--set '$spec': expected TARGET=VALUES, e.g. model.varpi=0:1:11"
    lhs=${spec%%=*}
    rhs=${spec#*=}
    [[ $rhs != *[$'\t\n']* ]] || die "--set '$spec': a value may not hold a tab or a newline"
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
    axis_values=()
    expanded=$(expand_values "$spec" "$rhs") || exit 2
    [[ -n $expanded ]] && mapfile -t axis_values <<< "$expanded"
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
n_tasks=$(( (n_points + batch - 1) / batch ))

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
exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
export RODCONTACT=$exe
mkdir -p "$out" || die "cannot create '$out'"

# lock_scan -x|-s: one scan at a time in DIR. A run holds an exclusive lock on DIR/.scan.lock
# (flock(1); released by the kernel when the scan and every process it started have ended, so
# a scan that died leaves no stale lock); the tasks of a Slurm array share it (-s), so that
# they run side by side but a local run of the same DIR is refused while they run. The file
# names the holder: pid, host, start time and command.
lock_scan() {
    local holder
    command -v flock > /dev/null || return 0   # util-linux; without it no lock is taken
    exec 9>> "$out/.scan.lock" || die "cannot write '$out/.scan.lock'"
    if ! flock -n "$1" 9; then
        holder=$(tail -n 1 "$out/.scan.lock" 2> /dev/null)
        die "another scan is running in '$out' (${holder:-its lock file $out/.scan.lock is held}); wait for it to end or stop it, or use another --out"
    fi
    if [[ $1 == -x ]]; then
        : > "$out/.scan.lock"
    fi
    printf 'pid %s on %s since %s: %s\n' "$$" "$(hostname 2> /dev/null || echo '?')" \
        "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$command_line" >> "$out/.scan.lock"
}
case $mode in
    run) lock_scan -x ;;
    task) lock_scan -s ;;
esac

# same_or_new NEW DEST WHAT: a scan directory that holds another DEST is refused
same_or_new() {
    local new=$1 dest=$2 what=$3
    [[ ! -f $dest ]] || cmp -s "$new" "$dest" ||
        die "'$out' holds a scan with another $what ($dest differs); rerun with the same input and --set, or use another --out"
}
# install NEW DEST: DEST := NEW the first time (then NEW is removed)
install() {
    if [[ -f $2 ]]; then
        rm -f "$1"
    else
        mv -f "$1" "$2" || die "cannot write '$2'"
    fi
}
tmp_input=$(mktemp "$out/.input.XXXXXX") || die "cannot write in '$out'"
tmp_points=$(mktemp "$out/.points.XXXXXX") || die "cannot write in '$out'"
jobfile=$(mktemp "$out/.jobs.XXXXXX") || die "cannot write in '$out'"
checks=$(mktemp "$out/.checks.XXXXXX") || die "cannot write in '$out'"
trap 'rm -f "$tmp_input" "$tmp_points" "$jobfile" "$checks" "$out/.stop.${SCAN_ID:-}"' EXIT
# mktemp makes its files 0600: the scan's files get the mode of the umask, as any new file
file_mode=$(printf '%o' $((0666 & ~$(umask))))
chmod "$file_mode" "$tmp_input" "$tmp_points" || die "cannot change the mode of the files in '$out'"
cp "$input" "$tmp_input" || die "cannot copy '$input' into '$out'"
same_or_new "$tmp_input" "$out/input.nml" "input file"
for ((k = 0; k < n_points; k++)); do
    point_line "$k"
done > "$tmp_points"
same_or_new "$tmp_points" "$out/points.txt" "list of points"

# point_stem K: STEM = DIR/point_K (K zero-padded), the prefix of the point's files
point_stem() {
    printf -v STEM "%s/point_%0${width}d" "$out" "$1"
}

# point_complete K: true when point K is finished: DIR/point_K.h5 with status 'complete'.
# Fast path: the .status of a run that exited 0 (rodcontact exits 0 exactly when it wrote
# status 'complete'); else the file's own status attribute.
point_complete() {
    local rc=""
    point_stem "$1"
    [[ -f $STEM.h5 ]] || return 1
    [[ -f $STEM.status ]] && read -r rc < "$STEM.status"
    [[ $rc == 0 ]] && return 0
    complete_file "$STEM.h5"
}

# csv_escape TEXT: FIELD = TEXT as one CSV field (RFC 4180)
csv_escape() {
    if [[ $1 == *[,\"$'\n'$'\r']* ]]; then
        FIELD="\"${1//\"/\"\"}\""
    else
        FIELD=$1
    fi
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
    local n_complete=0 n_failed=0 n_missing=0 n_stopped=0
    # the header in the units of the points' files (the first one there is; SI with &material)
    local first_file=()
    for ((k = 0; k < n_points; k++)); do
        point_stem "$k"
        [[ -f $STEM.h5 ]] && "$exe" --summary "$STEM.h5" > /dev/null 2>&1 && { first_file=("$STEM.h5"); break; }
    done
    header=$("$exe" --summary-header "${first_file[@]}" "${nondimensional[@]}") && parse_csv "$header" ||
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
        if [[ -f $stem.h5 ]] && summary=$("$exe" --summary "$stem.h5" "${nondimensional[@]}" 2>&1) && parse_csv "$summary"; then
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
            elif [[ $exit_status == 5 || -f $stem.h5.part || -f $stem.h5.resume ]]; then
                status=interrupted
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
            interrupted) n_stopped=$((n_stopped + 1)) ;;
            *) n_failed=$((n_failed + 1)) ;;
        esac
        csv_escape "$status"
        printf '%s,%s,%s%s\n' "$row" "$FIELD" "$exit_status" "$rest"
    done >> "$tmp"
    chmod "$file_mode" "$tmp"
    mv -f "$tmp" "$csv" || die "cannot write '$csv'"
    echo "scan: $csv: $n_points points: $n_complete complete, $n_failed failed, $n_stopped interrupted, $n_missing missing" >&2
}

if [[ $mode == collect ]]; then
    install "$tmp_input" "$out/input.nml"
    install "$tmp_points" "$out/points.txt"
    collect
    exit 0
fi

# ---------------------------------------------------------------- the points to run
command -v parallel > /dev/null && parallel --version 2> /dev/null | grep -q '^GNU parallel' ||
    die "GNU parallel not found (the 'parallel' of moreutils is another program): apt-get install parallel (scripts/setup.sh installs it)"

if [[ $mode == task ]]; then
    [[ $task =~ ^[0-9]+$ ]] || die "--task: expected a task number 0..$((n_tasks - 1)), got '$task'"
    task=$((10#$task))
    ((task < n_tasks)) || die "--task $task: the scan has tasks 0..$((n_tasks - 1)) ($n_points points, --batch $batch)"
    first=$((task * batch))
    last=$(( first + batch - 1 < n_points - 1 ? first + batch - 1 : n_points - 1 ))
else
    first=0
    last=$((n_points - 1))
fi
pending=()
for ((k = first; k <= last; k++)); do
    point_complete "$k" || pending+=("$k")
done
n_run=${#pending[@]}
n_skipped=$((last - first + 1 - n_run))
# the points to run that continue from a checkpoint (an interrupted run's point_K.h5.part)
n_resumed=0
for k in "${pending[@]}"; do
    point_stem "$k"
    [[ -f $STEM.h5.part || -f $STEM.h5.resume ]] && n_resumed=$((n_resumed + 1))
done
resumed=""
((n_resumed > 0)) && resumed=" ($n_resumed of them continue from their checkpoints)"

# The jobs for GNU parallel, one line per point: K, then its --set arguments, tab-separated
# (--colsep); no value holds a tab (checked above).
for k in "${pending[@]}"; do
    point_args "$k"
    printf -v line "%0${width}d" "$k"
    for arg in "${POINT_ARGS[@]}"; do
        line+=$'\t'$arg
    done
    printf '%s\n' "$line"
done > "$jobfile"

# run_parallel WHAT INPUT ARGS...: GNU parallel with ARGS and INPUT as its standard input, in
# the background so that INT and TERM reach our trap at once; the trap stops it (GNU
# parallel sends TERM to its jobs and waits for them) and exits 130/143
parallel_pid=""
on_interrupt() {
    local sig=$1 run_file pid
    trap '' INT TERM
    [[ -n $parallel_pid ]] || parallel_pid=$(jobs -p)
    if [[ $what == "running the points" ]]; then
        # No new point starts (the stop file, and SIGHUP: GNU parallel starts no more jobs and
        # waits for the running ones); each running point's shell gets SIGUSR1 and passes it to
        # its run, which finishes its step, writes its checkpoint and exits. Then GNU parallel
        # exits, and this scan after it: no run is left behind.
        : > "$out/.stop.$SCAN_ID"
        [[ -n $parallel_pid ]] && kill -HUP $parallel_pid 2> /dev/null
        for run_file in "$out/.run.$SCAN_ID".*; do
            [[ -f $run_file ]] && read -r pid < "$run_file" && kill -USR1 "$pid" 2> /dev/null
        done
    else
        [[ -n $parallel_pid ]] && kill -TERM $parallel_pid 2> /dev/null
    fi
    wait 2> /dev/null
    echo "scan: interrupted (signal $sig) while $what; every point that ended is recorded, the runs stopped wrote their checkpoints (point_K.h5.part); rerun the same command to resume" >&2
    exit $((sig == 2 ? 130 : 143))
}
run_parallel() {
    what=$1
    local stdin=$2
    shift 2
    parallel_pid=""
    trap 'on_interrupt 2' INT
    trap 'on_interrupt 15' TERM
    parallel "$@" < "$stdin" &
    parallel_pid=$!
    wait "$parallel_pid"
    local rc=$?
    trap - INT TERM
    parallel_pid=""
    return "$rc"
}

# ---------------------------------------------------------------- checks before any run
# Every point to run, read and validated by rodcontact --check (nothing written; about 15 ms
# a point), in blocks of 100 points per job. The first failure stops the checks; its message
# names the variable, which names the axis.
if ((n_run > 0)); then
    if ! run_parallel "checking the points" "$jobfile" --jobs "$jobs" --pipe -N 100 --halt now,fail=1 \
            "$BASH" "$script" --points-check "$tmp_input" > "$checks" 2> /dev/null; then
        IFS=$'\t' read -r bad_point message < "$checks" ||
            die "the checks of the points failed without a message (GNU parallel: $(parallel --version | head -n 1))"
        bad=$((10#$bad_point))
        point_values "$bad"
        variable=""
        [[ $message =~ error\ in\ (--set\ )?([A-Za-z0-9_]+\.[A-Za-z0-9_]+) ]] && variable=${BASH_REMATCH[2],,}
        for ((i = 0; i < n_axes; i++)); do
            IFS='+' read -r -a targets <<< "${axis_targets[i]}"
            for target in "${targets[@]}"; do
                target=${target%%(*}
                if [[ -n $variable && ${target,,} == "$variable" ]]; then
                    die "axis --set '${specs[i]}': value '${POINT_VALUES[i]}' (point $bad) is not valid input: ${message#rodcontact: }; nothing was run"
                fi
            done
        done
        point_line "$bad" > "$checks"
        die "point $bad ($(cut -d' ' -f2- "$checks")) is not valid input: ${message#rodcontact: }; nothing was run"
    fi
fi
# the scan's definition, kept in DIR once its points passed the checks
install "$tmp_input" "$out/input.nml"
install "$tmp_points" "$out/points.txt"

# ---------------------------------------------------------------- --array
# The Slurm array indices of the tasks with a point to run, as ranges: '0-3,5,7-9'
task_ranges() {
    local k t range_first=-1 range_last=-1
    ranges=""
    for k in "${pending[@]}"; do
        t=$((k / batch))
        ((t == range_last)) && continue
        if ((range_first < 0)); then
            range_first=$t
        elif ((t != range_last + 1)); then
            ranges+=${ranges:+,}$range_first$( ((range_last > range_first)) && echo "-$range_last")
            range_first=$t
        fi
        range_last=$t
    done
    ((range_first >= 0)) && ranges+=${ranges:+,}$range_first$( ((range_last > range_first)) && echo "-$range_last")
    return 0
}
if [[ $mode == array ]]; then
    task_ranges
    [[ -n $ranges ]] && echo "$ranges"
    echo "scan: $n_points points in $n_tasks tasks of --batch $batch; $n_run points to run$resumed" >&2
    exit 0
fi

# ---------------------------------------------------------------- --slurm
# The array (scripts/slurm/scan_array.sbatch, one task per --batch points that has a point to
# run) and a collect job that runs after it (--dependency=afterany), in one go; the Slurm logs
# in DIR/slurm/. The words after --slurm go to both sbatch calls (partition, account, time
# limit, ...), but a word %N, which throttles the array (at most N tasks at once).
if [[ $mode == slurm ]]; then
    command -v sbatch > /dev/null || die "--slurm: sbatch not found (is this a Slurm login node?)"
    throttle=""
    sbatch_args=()
    for word in "${sbatch_options[@]}"; do
        if [[ $word =~ ^%[1-9][0-9]*$ ]]; then
            throttle=$word
        else
            sbatch_args+=("$word")
        fi
    done
    out_abs=$(cd "$out" && pwd)
    mkdir -p "$out_abs/slurm" || die "cannot create '$out/slurm'"
    # the scan's own arguments, for the tasks and the collector (relative paths are taken from
    # this directory, which is the jobs' working directory too)
    scan_argv=("$input")
    for spec in "${specs[@]}"; do
        scan_argv+=(--set "$spec")
    done
    scan_argv+=(--out "$out" --batch "$batch" --exe "$exe" "${nondimensional[@]}")
    export RODCONTACT_ROOT=$repo_root RODCONTACT=$exe
    if ((n_run > 0)); then
        task_ranges
        array_job=$(sbatch --parsable --array="$ranges$throttle" --output="$out_abs/slurm/%x-%A_%a.out" \
                    "${sbatch_args[@]}" "$repo_root/scripts/slurm/scan_array.sbatch" "${scan_argv[@]}") ||
            die "--slurm: sbatch of the array failed (above)"
        array_job=${array_job%%;*}
        echo "submitted the array: job $array_job, tasks $ranges$throttle ($n_run points to run), logs $out/slurm/rodcontact-scan-${array_job}_<task>.out"
        dependency=(--dependency="afterany:$array_job")
    else
        echo "every point is complete: no array to submit"
        dependency=()
    fi
    # the collector as a shell command line: every word in single quotes (sbatch --wrap runs it
    # with /bin/sh, where an unquoted 'initial.theta0_step(1)=...' is a syntax error)
    wrap="exec"
    for word in "$script" "${scan_argv[@]}" --collect; do
        wrap+=" '${word//\'/\'\\\'\'}'"
    done
    collect_job=$(sbatch --parsable "${dependency[@]}" --job-name=rodcontact-collect --ntasks=1 \
                  --output="$out_abs/slurm/%x-%j.out" "${sbatch_args[@]}" --wrap "$wrap") ||
        die "--slurm: sbatch of the collect job failed (above)"
    collect_job=${collect_job%%;*}
    echo "submitted the collect job: job $collect_job${array_job:+, after the array ends}: $out/summary.csv, log $out/slurm/rodcontact-collect-$collect_job.out"
    echo "watch: squeue --me; resume: the same command again" >&2
    exit 0
fi

# ---------------------------------------------------------------- run
if [[ $mode == task ]]; then
    echo "scan: task $task: points $first..$last of $n_points in $out/, $n_skipped already complete, $n_run to run$resumed with -j $jobs" >&2
else
    echo "scan: $n_points points in $out/, $n_skipped already complete, $n_run to run$resumed with -j $jobs" >&2
fi
start=$SECONDS
# --term-seq: when GNU parallel itself gets SIGTERM or SIGINT (scancel, Ctrl-C: every process
# gets it) it sends SIGCONT, which changes nothing, to the processes of each running point and
# waits up to 10 minutes for them to end (the points stop on the signal they got themselves,
# see run_point), before SIGKILL. Its default sequence TERM,200,TERM,... sent rodcontact a
# second SIGTERM that ended it before its checkpoint, and exited while runs were still going.
SCAN_ID="$(hostname 2> /dev/null || echo host).$$"
export SCAN_ID
rm -f "$out/.stop.$SCAN_ID"
parallel_args=(--jobs "$jobs" --colsep '\t' -a "$jobfile"
               --term-seq CONT,600000,KILL,25)
# GNU parallel's job log of a local run (one per scan directory; a task of an array leaves
# its log to Slurm)
[[ $mode == run ]] && parallel_args+=(--joblog "$out/joblog")
[[ -t 2 ]] && parallel_args+=(--eta)
if ((n_run > 0)); then
    run_parallel "running the points" /dev/null "${parallel_args[@]}" "$BASH" "$script" --point-run "$out"
fi
n_ok=0
n_bad=0
n_lost=0
n_stopped=0
for k in "${pending[@]}"; do
    point_stem "$k"
    rc=""
    [[ -f $STEM.status ]] && read -r rc < "$STEM.status"
    case $rc in
        0) n_ok=$((n_ok + 1)) ;;
        5 | 129 | 1[3-9][0-9]) n_stopped=$((n_stopped + 1)) ;;
        '') n_lost=$((n_lost + 1)) ;;
        *) n_bad=$((n_bad + 1)) ;;
    esac
done
lost=""
((n_lost > 0)) && lost=", $n_lost not run"
((n_stopped > 0)) && lost+=", $n_stopped interrupted (stopped by a signal: rerun the same command to resume them from their checkpoints)"
echo "scan: done in $(hms $((SECONDS - start))): $n_ok complete, $n_bad failed$lost (messages in $out/point_*.status, .err)" >&2
[[ $mode == run ]] && collect
# 5: a point's run was stopped by a signal (not the scan: e.g. the run killed directly);
# its checkpoint is kept and a rerun resumes it. Not a success, and not a recorded failure
# (a Slurm array task that ends so is FAILED, not COMPLETED).
((n_stopped > 0)) && exit 5
((n_bad == 0 && n_lost == 0)) || exit 1
exit 0
