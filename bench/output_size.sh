#!/usr/bin/env bash
# Benchmark (NOT a test) of the output file: its size and the run's wall time for
# &output compression = 0, 1, 4, 9, written as the section "Output: chunks and compression"
# of docs/performance.md (replaced in place, or appended when the page has none).
# scripts/bench.sh calls it after writing the rest of the page.
#
#   bench/output_size.sh            # about 2-3 minutes on 2 (shared) cores
#   bench/output_size.sh --quick    # 1 run each, no long run, page in out/bench-quick/
#
# Cases (input/exp1.nml, s = 500, dt = 1e-4, default output settings otherwise):
#   short  t_end = 0.01: 100 steps, 2 snapshots (the file a large scan pays for per point)
#   exp1   t_end = 3: 30,000 steps, 301 snapshots (the paper's experiment 1)
#   long   t_end = 30: 300,000 steps, 3001 snapshots (skipped with --quick)
# Wall time: median of RUNS runs (default 3) of the whole process; peak RSS from
# /usr/bin/time when it exists. Every compressed file is checked to hold the same data as
# the uncompressed one (tests/tools/regression.py same).
#
# Environment: BUILD_DIR (as scripts/setup.sh), EXE (the rodcontact to time; default
# $BUILD_DIR/rodcontact, built by scripts/setup.sh if missing), RUNS (3), BENCH_OUT (raw data and
# files, default out/bench; --quick: out/bench-quick), DOC (the page to write).
# Exit status: 0 written; 1 a run failed or the data differ; 2 usage.

set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
. "$repo_root/bench/quick_option.sh" bench_output "$@"

runs="${RUNS:-3}"
levels=(0 1 4 9)
cases=("short 0.01" "exp1 3" "long 30")
if ((quick)); then
    runs=1
    cases=("short 0.01" "exp1 3")
    out="${BENCH_OUT:-$repo_root/out/bench-quick}"
    doc="${DOC:-$out/performance-quick.md}"
else
    out="${BENCH_OUT:-$repo_root/out/bench}"
    doc="${DOC:-$repo_root/docs/performance.md}"
fi
build_dir="${BUILD_DIR:-build}"
[[ "$build_dir" = /* ]] || build_dir="$repo_root/$build_dir"
exe="${EXE:-$build_dir/rodcontact}"
if [[ ! -x "$exe" ]]; then
    BUILD_TYPE=Release BUILD_DIR="$build_dir" "$repo_root/scripts/setup.sh" >&2
fi
[[ -x "$exe" ]] || { say "$exe was not built"; exit 1; }
py="$("$repo_root/scripts/lib/find_python.sh")" || exit 1
work="$out/output"
mkdir -p "$work"
raw="$work/output.tsv"
have_time=0
[[ -x /usr/bin/time ]] && have_time=1

# one run: prints "seconds peak_rss_kB"
timed_run() {
    local start end rss=""
    start=$EPOCHREALTIME
    if ((have_time)); then
        /usr/bin/time -f '%M' -o "$work/rss.txt" "$exe" "$@" >/dev/null
        rss="$(tail -n 1 "$work/rss.txt")"
    else
        "$exe" "$@" >/dev/null
    fi
    end=$EPOCHREALTIME
    echo "$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }') ${rss:--}"
}

median() { sort -g | awk '{ v[NR] = $1 } END { if (NR % 2) print v[(NR + 1) / 2]; else printf "%.3f\n", (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

printf 'case\tt_end\tcompression\tbytes\tseconds\trss_kB\n' > "$raw"
for c in "${cases[@]}"; do
    read -r name t_end <<<"$c"
    for level in "${levels[@]}"; do
        prefix="$work/${name}_c$level"
        times=() rss=()
        for ((k = 1; k <= runs; k++)); do
            rm -f "$prefix.h5"
            read -r sec kb < <(timed_run "$repo_root/input/exp1.nml" --set time.t_end="$t_end" \
                --set output.prefix="$prefix" --set output.quiet=.true. --set output.compression="$level") \
                || { say "$name, compression $level: run failed"; exit 1; }
            times+=("$sec") rss+=("$kb")
        done
        [[ -f "$prefix.h5" ]] || { say "$name, compression $level: no $prefix.h5"; exit 1; }
        bytes="$(stat -c %s "$prefix.h5")"
        sec="$(printf '%s\n' "${times[@]}" | median)"
        kb="$(printf '%s\n' "${rss[@]}" | sort -g | tail -n 1)"
        printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$t_end" "$level" "$bytes" "$sec" "$kb" >> "$raw"
        say "$name (t_end = $t_end), compression $level: $bytes bytes, $sec s (median of $runs), peak RSS $kb kB"
        if ((level > 0)); then
            "$py" "$repo_root/tests/tools/regression.py" same "$work/${name}_c0.h5" "$prefix.h5" >/dev/null \
                || { say "$name: compression $level changed the data"; exit 1; }
        fi
    done
    # the default: what a run without output.compression records
    if [[ "$name" == short ]]; then
        "$exe" "$repo_root/input/exp1.nml" --set time.t_end=0.01 --set output.prefix="$work/default" \
            --set output.quiet=.true. >/dev/null
        default="$("$py" -c "import h5py, sys; print(int(h5py.File(sys.argv[1], 'r').attrs['output.compression']))" "$work/default.h5")"
    fi
done

# the section, between markers so that a later run replaces it
machine="$(sed -n 's/^model name[[:space:]]*:[[:space:]]*//p' /proc/cpuinfo | head -n 1), $(nproc) cores"
commit="$(git -C "$repo_root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
if [[ "$commit" != unknown && -n "$(git -C "$repo_root" --no-optional-locks status --porcelain --untracked-files=no 2>/dev/null)" ]]; then
    commit="$commit (with uncommitted changes)"
fi
section="$work/section.md"
"$py" - "$raw" "$default" "$runs" "$machine" "$commit" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$quick" > "$section" <<'PY'
import csv, sys
raw, default, runs, machine, commit, date, quick = sys.argv[1:]
rows = list(csv.DictReader(open(raw), delimiter="\t"))
what = {"short": "2 snapshots (100 steps)", "exp1": "experiment 1 (30,000 steps, 301 snapshots)",
        "long": "t_end = 30 (300,000 steps, 3001 snapshots)"}
base = {r["case"]: r for r in rows if r["compression"] == "0"}
def size(b):
    b = int(b)
    return f"{b / 1e3:.1f} kB" if b < 1e6 else f"{b / 1e6:.2f} MB"
print("<!-- written by bench/output_size.sh (called by scripts/bench.sh); do not edit by hand -->")
print("## Output: chunks and compression\n")
print("File size and wall time of `input/exp1.nml` (s = 500, dt = 1e-4, `snapshot_every = 100`, "
      "`series_every = 1`) for each `&output compression` level. Produced by "
      f"`bench/output_size.sh{' --quick' if quick == '1' else ''}` (RUNS = {runs}: the wall time is the median "
      f"of {runs} runs of the whole process, output included); {machine}; commit {commit}; {date}.\n")
print("| run | compression | file size | vs. 0 | wall time | vs. 0 | peak RSS |")
print("|---|---|---|---|---|---|---|")
for r in rows:
    b = base[r["case"]]
    ratio = int(r["bytes"]) / int(b["bytes"])
    slow = float(r["seconds"]) / float(b["seconds"])
    rss = "—" if r["rss_kB"] in ("", "-") else f"{int(r['rss_kB']) / 1024:.1f} MB"
    print(f"| {what[r['case']]} | {r['compression']} | {size(r['bytes'])} | {ratio:.2f} | "
          f"{float(r['seconds']):.2f} s | {slow:.2f} | {rss} |")
# the rule the default follows: the level that saves most on experiment 1 while costing at
# most 10 % of its wall time
exp1 = [r for r in rows if r["case"] == "exp1"]
t0 = float(base["exp1"]["seconds"])
ok = [r for r in exp1 if float(r["seconds"]) <= 1.10 * t0]
best = min(ok, key=lambda r: (int(r["bytes"]), int(r["compression"])))
print()
print("Every compressed file holds the same data as the uncompressed one (`tests/tools/regression.py same`). "
      "Compression is the shuffle filter followed by deflate at the given level, on the snapshot fields "
      "(chunks of one row, 4 KiB at s = 500); `/series`, `/snapshots/t`, `/mesh/x` and `/checkpoint` are "
      "not compressed (docs/output.md, \"Chunks and compression\"). Doubles of a smooth solution compress little (their low "
      "mantissa bytes are noise); what shuffle + deflate finds is the exponent and sign bytes, the "
      "boundary zeros and the fields that stay zero or constant for a while.\n")
print(f"**Default: `compression = {default}`.** Rule: the level with the smallest experiment 1 file whose "
      f"wall time is at most 10 % above that of no compression; by this measurement that is level "
      f"{best['compression']}" + (" (the default agrees)." if best["compression"] == default else
      f" — the default ({default}, src/input/config_m.f90) disagrees with this measurement: look at the table "
      f"and update one of them.") + " Higher levels cost time for little more size; `compression = 0` "
      "gives the fastest writes (files another tool writes to in place, or a fast local disk and a "
      "short run).")
PY

mkdir -p "$(dirname "$doc")"
[[ -f "$doc" ]] || : > "$doc"
"$py" - "$doc" "$section" <<'PY'
import sys
doc, section = sys.argv[1:]
text = open(doc, encoding="utf-8").read()
new = open(section, encoding="utf-8").read().rstrip("\n") + "\n"
marker = "<!-- written by bench/output_size.sh"
begin = text.find(marker)
if begin >= 0:
    end = text.find("\n## ", text.find("## Output: chunks and compression", begin) + 3)
    text = text[:begin] + new + ("\n" + text[end + 1:] if end >= 0 else "")
else:
    text = text.rstrip("\n") + "\n\n" + new
open(doc, "w", encoding="utf-8").write(text)
PY
say "wrote the section 'Output: chunks and compression' of $doc (raw data in $raw)"
