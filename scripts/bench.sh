#!/usr/bin/env bash
# Benchmark (NOT a test): the speed of rodcontact, written to docs/performance.md.
#
#   scripts/bench.sh            # everything, about 10-12 minutes on 2 (shared) cores
#   scripts/bench.sh --quick    # 1 run of small cases, no long run: checks the pipeline and
#                               # writes out/bench-quick/performance-quick.md, not docs/
#
# What it measures (every case RUNS = 5 times, medians printed and written):
#  1. per-step cost against the mesh size s in SIZES (default 100 500 2000 10000 100000):
#     bench/bench_kernels.f90 assembles the monolithic matrix (kl = ku = 7) of exp1 at
#     dt = 1e-4, factors it with dgbtrf and times, in one process, one dgbtrs (the floor),
#     the own band substitution, the block-tridiagonal substitution, and one full time step
#     stepper%advance for 'monolithic' (Euler, BDF2) and 'paper' (Euler); us per step, ns
#     per unknown, ratio to one dgbtrs of the same run; the growth with s is checked;
#  2. the same with the reference BLAS/LAPACK and with OpenBLAS, selected per run with
#     LD_LIBRARY_PATH (reference: /usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack,
#     OpenBLAS: /usr/lib/x86_64-linux-gnu/openblas-pthread), checked with ldd;
#  3. experiment 1 as the paper ran it (h = 1/500, dt = 1e-4) to t_end = 10 (100,000
#     steps, default output): wall time (target <= 2.5 s) and peak RSS (/usr/bin/time);
#     one run to t_end = 100 (1,000,000 steps): the RSS must not grow (target < 50 MB);
#  4. where a step's time goes (valgrind callgrind: instructions per step by function, the
#     difference of a 1000- and a 2000-step run) and heap allocations per step and per
#     snapshot (valgrind memcheck's heap summary, same difference);
#  5. the work-precision diagram, bench/work_precision.sh (figures/work_precision.png), and
#     the work-precision of Euler, BDF2 and the midpoint rule on exp1 and the impact case,
#     bench/work_precision_schemes.sh (figures/work_precision_schemes.png, ~2.5 minutes).
#  5b. adaptive against fixed time steps on exp1 to t = 60 (issue 12),
#     bench/adaptive_steps.sh (figures/work_precision_adaptive.png, about 5 minutes), and the
#     instructions per adaptive and per fixed step, bench/step_cost.sh (issue 24, ~3 minutes).
#  5c. the adaptive mesh on exp2 against the exact solution (issue 13),
#     bench/adaptive_mesh.sh (figures/work_precision_mesh.png, 20-40 minutes),
#  5d. the error budget of exp2 (mesh size against time step, where the error sits),
#     bench/error_budget.sh (about 8 minutes).
#  6. output file size and wall time against &output compression (bench/output_size.sh).
#
# OpenBLAS: if libopenblas0-pthread is not installed, it is installed with apt-get (needs
# root or sudo; without them the OpenBLAS runs are skipped and the page says so). Installing
# it would make Debian switch the system-wide alternatives libblas.so.3 and liblapack.so.3 to
# OpenBLAS (higher priority), which would slow every other program on the machine (OpenBLAS
# is several times slower for our kl = 7 band solves). So this script first records the two
# alternatives (update-alternatives --query), pins them to their current value with
# `update-alternatives --set` (manual mode: the package's post-install script then leaves
# them alone), installs, and sets them again to the recorded values right after, checking
# that they are unchanged (also on an error exit). The groups stay in manual mode ('auto'
# would now select OpenBLAS); `update-alternatives --auto <name>` would hand them back.
#
# Environment: BUILD_DIR (as scripts/setup.sh; Release is forced), RUNS (5), SIZES,
# BENCH_OUT (raw data, default out/bench; --quick: out/bench-quick), SKIP_WP=1 (reuse out/bench/work_precision.md),
# SKIP_WPS=1 (reuse out/bench/work_precision_schemes.md),
# SKIP_WPA=1 (reuse out/bench/work_precision_adaptive.md),
# SKIP_WPM=1 (reuse out/bench/work_precision_mesh.md),
# SKIP_EB=1 (reuse out/bench/error_budget.md),
# NO_OPENBLAS=1 (reference BLAS only, no installation).
# Exit status: 0 done (whether or not the targets are met: see the page); 1 build or run
# failure, or a BLAS/LAPACK library that does not resolve as intended; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" bench "$@"
t_start="$(date +%s)"

runs="${RUNS:-5}"
read -r -a sizes <<<"${SIZES:-100 500 2000 10000 100000}"
exp1_tend=10
long_tend=100
if ((quick)); then
    runs=1
    read -r -a sizes <<<"${SIZES:-100 500}"
    exp1_tend=1
    long_tend=""
fi
if ((quick)); then out="${BENCH_OUT:-$repo_root/out/bench-quick}"; else out="${BENCH_OUT:-$repo_root/out/bench}"; fi
mkdir -p "$out"
if ((quick)); then doc="$out/performance-quick.md"; else doc="$repo_root/docs/performance.md"; fi
python="$(command -v python3 || echo /usr/bin/python3)"
load_start="$(cut -d' ' -f1-3 /proc/loadavg)"

# --- 0. build -----------------------------------------------------------------------------
BUILD_TYPE=Release "$repo_root/scripts/setup.sh"
build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
exe="$build_dir/rodcontact"
kernels="$build_dir/bench/rodcontact_bench_kernels"
for f in "$exe" "$kernels" "$build_dir/bench/rodcontact_work_precision"; do
    [[ -x "$f" ]] || { say "$f was not built"; exit 1; }
done
input="$repo_root/input/exp1.nml"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/rodcontact-bench.XXXXXX")"

# --- 1. BLAS / LAPACK: OpenBLAS installed without touching the system's choice --------------
ref_path="/usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack"
openblas_path="/usr/lib/x86_64-linux-gnu/openblas-pthread"
alternatives=(libblas.so.3-x86_64-linux-gnu liblapack.so.3-x86_64-linux-gnu)
alt_value() { update-alternatives --query "$1" 2>/dev/null | sed -n 's/^Value: //p'; }
alt_status() { update-alternatives --query "$1" 2>/dev/null | sed -n 's/^Status: //p'; }
meta="$out/meta.txt"
: >"$meta"
record() { printf '%s=%s\n' "$1" "$2" >>"$meta"; }
for alt in "${alternatives[@]}"; do
    record "alternative_before.$alt" "$(alt_value "$alt") ($(alt_status "$alt"))"
done

declare -A saved_value=()
restore_alternatives() {   # set the recorded values again; say if anything differs
    local alt
    for alt in "${!saved_value[@]}"; do
        "${sudo_cmd[@]}" update-alternatives --set "$alt" "${saved_value[$alt]}" >/dev/null 2>&1 || true
        if [[ "$(alt_value "$alt")" != "${saved_value[$alt]}" ]]; then
            say "WARNING: could not restore $alt to ${saved_value[$alt]}; it is $(alt_value "$alt"). Run:"
            say "    update-alternatives --set $alt ${saved_value[$alt]}"
        fi
    done
}
cleanup() {
    restore_alternatives
    rm -rf "$tmp"
}
trap cleanup EXIT

sudo_cmd=()
blas_list=(reference)
openblas_action="not requested (NO_OPENBLAS=1)"
if [[ "${NO_OPENBLAS:-0}" != 1 ]]; then
    if [[ "$(dpkg-query -W -f='${Status}' libopenblas0-pthread 2>/dev/null || true)" == "install ok installed" ]]; then
        openblas_action="libopenblas0-pthread was already installed; alternatives not touched"
        blas_list+=(openblas)
        for alt in "${alternatives[@]}"; do
            if [[ "$(alt_value "$alt")" == *openblas* ]]; then
                say "WARNING: the system-wide $alt is OpenBLAS ($(alt_value "$alt")): every program on this machine"
                say "  uses it. To go back to the reference implementation (not done here):"
                say "    update-alternatives --set $alt $(update-alternatives --list "$alt" | grep -v openblas | head -n 1)"
                openblas_action="$openblas_action (WARNING: the system-wide $alt points to OpenBLAS)"
            fi
        done
    else
        can_install=1
        if [[ "$(id -u)" -ne 0 ]]; then
            if command -v sudo >/dev/null 2>&1; then sudo_cmd=(sudo); else can_install=0; fi
        fi
        if ((can_install)); then
            say "installing libopenblas0-pthread; the system alternatives are pinned first and restored after:"
            for alt in "${alternatives[@]}"; do
                saved_value[$alt]="$(alt_value "$alt")"
                say "  $alt = ${saved_value[$alt]} ($(alt_status "$alt"))"
                [[ -n "${saved_value[$alt]}" ]] && "${sudo_cmd[@]}" update-alternatives --set "$alt" "${saved_value[$alt]}" >/dev/null
            done
            apt_install() {
                "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
                    libopenblas0-pthread >"$out/apt.log" 2>&1
            }
            if apt_install || { "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q >>"$out/apt.log" 2>&1 &&
                                apt_install; }; then
                restore_alternatives
                openblas_action="libopenblas0-pthread installed by this run; alternatives pinned before and restored after"
                blas_list+=(openblas)
            else
                restore_alternatives
                openblas_action="installing libopenblas0-pthread failed (see out/bench/apt.log): OpenBLAS not measured"
                say "$openblas_action"
            fi
        else
            openblas_action="libopenblas0-pthread missing and no root/sudo to install it: OpenBLAS not measured"
            say "$openblas_action"
        fi
    fi
fi
for alt in "${alternatives[@]}"; do
    record "alternative_after.$alt" "$(alt_value "$alt") ($(alt_status "$alt"))"
done
record openblas_action "$openblas_action"

blas_dir() { if [[ "$1" == reference ]]; then echo "$ref_path"; else echo "$openblas_path"; fi; }
# What a binary resolves under LD_LIBRARY_PATH=$1: "name -> real file" per BLAS/LAPACK library.
resolved() {
    env LD_LIBRARY_PATH="$1" ldd "$2" | awk '$1 ~ /^lib(blas|lapack|openblas|gfortran)/ && $3 ~ /^\// { print $1, $3 }' |
        while read -r name path; do echo "$name -> $path ($(readlink -f "$path"))"; done
}
# The binaries NEED liblapack.so.3 only; the BLAS comes with it: the reference liblapack.so.3
# needs libblas.so.3, OpenBLAS's needs libopenblas.so.0 (BLAS and LAPACK kernels in one).
blas_ok() {   # blas_ok <blas> <ldd lines>
    case "$1" in
        reference) grep -q "^liblapack.so.3 -> /usr/lib/x86_64-linux-gnu/lapack/" <<<"$2" &&
                   grep -q "^libblas.so.3 -> /usr/lib/x86_64-linux-gnu/blas/" <<<"$2" &&
                   ! grep -q "^libopenblas" <<<"$2" ;;
        openblas) grep -q "^liblapack.so.3 -> $openblas_path/" <<<"$2" &&
                  grep -q "^libopenblas.so.0 -> $openblas_path/" <<<"$2" &&
                  ! grep -q "^libblas.so.3 -> /usr/lib/x86_64-linux-gnu/blas/" <<<"$2" ;;
    esac
}
for blas in "${blas_list[@]}"; do
    dir="$(blas_dir "$blas")"
    for bin in "$exe" "$kernels"; do
        libs="$(resolved "$dir" "$bin")"
        if ! blas_ok "$blas" "$libs"; then
            say "with LD_LIBRARY_PATH=$dir, $(basename "$bin") does not resolve $blas BLAS/LAPACK from there:"
            echo "$libs" >&2
            exit 1
        fi
    done
    record "ld_library_path.$blas" "$dir"
    record "resolved.$blas" "$(resolved "$dir" "$kernels" | tr '\n' ';')"
done
record "resolved.default" "$(resolved "" "$exe" | tr '\n' ';')"
record openblas_num_threads "${OPENBLAS_NUM_THREADS:-unset}"

# --- 2. per-step cost against s, both BLAS (kernels, one process per case) -------------------
: >"$out/kernels.raw"
say "per-step cost: ${#blas_list[@]} BLAS x ${#sizes[@]} sizes x $runs runs (round robin)"
for ((run = 1; run <= runs; run++)); do
    for blas in "${blas_list[@]}"; do
        for s in "${sizes[@]}"; do
            env LD_LIBRARY_PATH="$(blas_dir "$blas")" "$kernels" "$input" "$s" >"$tmp/k.txt"
            sed "s/^/blas=$blas run=$run /" "$tmp/k.txt" >>"$out/kernels.raw"
        done
    done
    say "  run $run/$runs done"
done

# --- 3. exp1 as the paper ran it: wall time and peak RSS ------------------------------------
run_exp1() {   # run_exp1 <blas> <t_end> <tag>: appends "blas= t_end= wall= rss_kb=" to $out/exp1.raw
    local prefix="$tmp/exp1_$3"
    rm -f "$prefix.h5"
    if ! env LD_LIBRARY_PATH="$(blas_dir "$1")" /usr/bin/time -f '%e %M' -o "$tmp/time.txt" \
        "$exe" "$input" --set time.t_end="$2" --set output.prefix="$prefix" --set output.quiet=.true. \
        >"$tmp/exp1.out" 2>"$tmp/exp1.err"; then
        say "exp1 run (t_end = $2, $1 BLAS) failed:"
        cat "$tmp/exp1.err" >&2
        exit 1
    fi
    read -r wall rss <"$tmp/time.txt"
    echo "blas=$1 t_end=$2 wall=$wall rss_kb=$rss h5_bytes=$(stat -c %s "$prefix.h5")" >>"$out/exp1.raw"
    rm -f "$prefix.h5"
}
: >"$out/exp1.raw"
say "exp1 to t_end = $exp1_tend: $runs runs per BLAS"
for ((run = 1; run <= runs; run++)); do
    for blas in "${blas_list[@]}"; do
        run_exp1 "$blas" "$exp1_tend" "r$run"
    done
done
if [[ -n "$long_tend" ]]; then
    say "exp1 to t_end = 30 and $long_tend (300,000 and 1,000,000 steps, once each): does the RSS grow?"
    run_exp1 reference 30 mid
    run_exp1 reference "$long_tend" long
fi
record exp1_command "$(basename "$exe") input/exp1.nml --set time.t_end=T --set output.prefix=<tmp> --set output.quiet=.true."

# --- 3b. the energy law with BDF2 during contact (src/numerics/energy_m.f90 points here) ------------
: >"$out/energy.raw"
if h5python="$("$repo_root/scripts/lib/find_python.sh" 2>/dev/null)"; then
    say "exp1 to t_end = 3 with Euler and BDF2: energy law through the contact phase"
    for scheme in euler bdf2; do
        env LD_LIBRARY_PATH="$ref_path" "$exe" "$input" --set time.t_end=3 --set time.scheme="$scheme" \
            --set output.snapshot_every=100000 --set output.prefix="$tmp/energy" --set output.quiet=.true. \
            >/dev/null 2>"$tmp/energy.err" || { cat "$tmp/energy.err" >&2; exit 1; }
        "$h5python" - "$tmp/energy.h5" "$scheme" "$repo_root/scripts/lib" >>"$out/energy.raw" <<'PY'
import sys
import numpy as np
sys.path.insert(0, sys.argv[3])
import rodrun
with rodrun.open_run(sys.argv[1]) as f:
    e = f["series/energy"][:]
    pen = f["series/penetration"][:]
    law_rise = float(f.attrs["energy_max_relative_rise"])
    law = rodrun.text(f.attrs["energy_law"])
rel = np.diff(e) / np.maximum(e[:-1], 1e-300)          # relative change of E^n, step n-1 -> n
contact = (pen[1:] > 0) | (pen[:-1] > 0)
print("scheme=%s steps=%d contact_steps=%d law_max_rise=%.3e En_max_rise_contact=%.3e "
      "En_max_rise_free=%.3e En_rising_steps=%d law=%s" % (
          sys.argv[2], len(rel), int(contact.sum()), law_rise,
          rel[contact].max() if contact.any() else 0.0, rel[~contact][1:].max() if (~contact).sum() > 1 else 0.0,
          int((rel > 1e-12).sum()), law.replace(" ", "_")))
PY
        rm -f "$tmp/energy.h5"
    done
else
    say "no Python with h5py: the energy check is skipped"
fi

# --- 4. callgrind (instructions per step) and memcheck (allocations per step) ---------------
: >"$out/alloc.raw"
if command -v valgrind >/dev/null 2>&1; then
    say "valgrind: instructions and allocations per step (3 methods)"
    for method in euler bdf2 paper; do
        case "$method" in
            euler) sets=() ;;
            bdf2) sets=(--set time.scheme=bdf2) ;;
            paper) sets=(--set solver.method=paper) ;;
        esac
        for t in 0.1 0.2; do
            valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$exe" "$input" "${sets[@]}" \
                --set time.t_end="$t" --set output.prefix="$tmp/cg" --set output.quiet=.true. >/dev/null 2>&1
            callgrind_annotate --inclusive=yes --threshold=100 "$tmp/cg.out" >"$out/callgrind_${method}_$t.txt" 2>/dev/null
            rm -f "$tmp/cg.out" "$tmp/cg.h5"
        done
        for spec in "0.1 100000" "0.2 100000" "0.2 100"; do
            read -r t every <<<"$spec"
            heap="$(valgrind --tool=memcheck --leak-check=no --undef-value-errors=no "$exe" "$input" "${sets[@]}" \
                --set time.t_end="$t" --set output.snapshot_every="$every" --set output.prefix="$tmp/mc" \
                --set output.quiet=.true. 2>&1 >/dev/null | sed -n 's/.*total heap usage: \([0-9,]*\) allocs.*/\1/p' | tr -d ,)"
            echo "method=$method t_end=$t snapshot_every=$every allocs=${heap:-?}" >>"$out/alloc.raw"
            rm -f "$tmp/mc.h5"
        done
    done
    # instructions per step against s (monolithic Euler, no snapshots): is the work linear in s?
    : >"$out/ir_per_step.raw"
    say "valgrind: instructions per step for s = ${sizes[*]}"
    for s in "${sizes[@]}"; do
        n1=$((200000 / s)); ((n1 < 5)) && n1=5; ((n1 > 1000)) && n1=1000
        irs=()
        for n in "$n1" $((2 * n1)); do
            valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$exe" "$input" --set mesh.n_elements="$s" \
                --set time.t_end="$(awk -v n="$n" 'BEGIN { printf "%.6g", n * 1e-4 }')" --set output.snapshot_every=100000 \
                --set output.prefix="$tmp/cg" --set output.quiet=.true. >/dev/null 2>&1
            irs+=("$(callgrind_annotate "$tmp/cg.out" 2>/dev/null | sed -n 's/^ *\([0-9,]*\) .*PROGRAM TOTALS.*/\1/p' | tr -d ,)")
            rm -f "$tmp/cg.out" "$tmp/cg.h5"
        done
        echo "s=$s steps1=$n1 steps2=$((2 * n1)) ir1=${irs[0]} ir2=${irs[1]}" >>"$out/ir_per_step.raw"
    done
    record valgrind "$(valgrind --version)"
else
    record valgrind "not installed: no instruction counts"
fi

# --- 5. work-precision diagram --------------------------------------------------------------
if [[ "${SKIP_WP:-0}" != 1 ]]; then
    if ((quick)); then
        WP_SKIP_BUILD=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/work_precision.sh" --quick
    else
        WP_SKIP_BUILD=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/work_precision.sh"
    fi
fi
if [[ "${SKIP_WPS:-0}" != 1 ]]; then
    if ((quick)); then
        WP_SKIP_BUILD=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/work_precision_schemes.sh" --quick
    else
        WP_SKIP_BUILD=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/work_precision_schemes.sh"
    fi
fi

# --- 5b. adaptive time steps: work and precision on exp1 (issue 12) ---------------------------
if [[ "${SKIP_WPA:-0}" != 1 ]]; then
    wpa_args=()
    ((quick)) && wpa_args=(--quick)
    WP_SKIP_BUILD=1 WPA_NO_SPLICE=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/adaptive_steps.sh" "${wpa_args[@]}"
    # the cost of an adaptive step against a fixed one (issue 24; callgrind, a few minutes)
    WP_SKIP_BUILD=1 WP_OUT="$out" BUILD_DIR="$build_dir" STEP_COST_DOC='' "$repo_root/bench/step_cost.sh" "${wpa_args[@]}"
fi

# --- 5c. the adaptive mesh: work and precision on exp2 against the exact solution (issue 13) ----
if [[ "${SKIP_WPM:-0}" != 1 ]]; then
    wpm_args=()
    ((quick)) && wpm_args=(--quick)
    WP_SKIP_BUILD=1 WPM_NO_SPLICE=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/adaptive_mesh.sh" "${wpm_args[@]}"
fi

# --- 5d. the error budget of exp2: mesh size against time step (issue 13) ----------------------
if [[ "${SKIP_EB:-0}" != 1 ]]; then
    eb_args=()
    ((quick)) && eb_args=(--quick)
    WP_SKIP_BUILD=1 EB_NO_SPLICE=1 WP_OUT="$out" BUILD_DIR="$build_dir" "$repo_root/bench/error_budget.sh" "${eb_args[@]}"
fi

# --- 6. what the numbers depend on, and the page ---------------------------------------------
fc="$(sed -n 's/^CMAKE_Fortran_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt")"
record cpu "$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -n 1)"
record cores "$(nproc)"
record caches "$(lscpu 2>/dev/null | sed -n 's/^\(L[123][di]* cache\):[[:space:]]*/\1 /p' | tr '\n' ';')"
record kernel "$(uname -srm)"
record compiler "${fc:-?}: $("${fc:-gfortran}" --version 2>/dev/null | head -n 1)"
record flags "$(sed -n 's/^Fortran_FLAGS = *//p' "$build_dir/CMakeFiles/rodcontact_lib.dir/flags.make" 2>/dev/null || echo unknown)"
commit="$(git -C "$repo_root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [[ "$commit" != unknown && -n "$(git -C "$repo_root" --no-optional-locks status --porcelain --untracked-files=no 2>/dev/null)" ]]; then
    commit="$commit (with uncommitted changes in the working tree)"
fi
record commit "$commit"
record date "$(date -u +%Y-%m-%dT%H:%M:%SZ)"
record load_start "$load_start"
record load_end "$(cut -d' ' -f1-3 /proc/loadavg)"
record runs "$runs"
record sizes "${sizes[*]}"
record quick "$quick"
record exp1_tend "$exp1_tend"
record long_tend "${long_tend:-none}"
record bench_seconds "$(($(date +%s) - t_start))"
"$python" "$repo_root/bench/report.py" "$out" "$doc"
# the section "Output: chunks and compression" (file size and wall time against &output compression)
EXE="$exe" BENCH_OUT="$out" DOC="$doc" RUNS="$(( runs < 3 ? runs : 3 ))" "$repo_root/bench/output_size.sh" $( ((quick)) && echo --quick )
say "wrote $doc (raw data in $out); took $(($(date +%s) - t_start)) s"
