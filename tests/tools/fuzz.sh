#!/usr/bin/env bash
# Fuzz the namelist reader (and validation) through the real program: a bounded loop of
# random mutations of the shipped inputs (byte flips, deletions, duplicated and swapped
# lines, random, huge and special numbers, NaN/Inf, empty and unterminated strings, very
# long lines, binary junk, stray tokens, truncation), each run with a time limit.
#
# Every input keeps rodcontact's work small and its output in the scratch directory: the
# &mesh, &time and &output groups of the seed are removed before mutating, and fixed ones
# are appended after it on lines of their own (a quoted string never continues onto the
# next line, so the mutated text cannot swallow them; if it repeats one of these groups
# or leaves a group open, the input is rejected, which is fine).
#
# Allowed outcomes:
#   exit 0  valid input: <prefix>.h5 written, no .part left
#   exit 2  bad input: one line 'rodcontact: error in <where>: ...' on stderr, no output file
#   exit 3  a valid input that is numerically bad (e.g. varpi mutated to 0 with
#           method = 'paper'): one 'rodcontact: error in solver: step ...' line and <prefix>.h5
# Findings (reported, input kept under <scratch>/findings/): a signal (crash), exit 1 or a
# gfortran 'Fortran runtime error', a timeout (hang), any other status, a message that is
# not one line, a file left behind by bad input. In a build with floating-point traps
# (Debug) a SIGFPE raised inside gfortran's namelist read (strtod, reading a literal
# beyond the double range such as 1e400) is counted separately as 'trap in read', and
# gfortran's -fcheck runtime warnings ('Namelist object ... truncated on read') are counted
# apart from the message: both are known findings in config_m (docs/robustness.md).
#
#   tests/tools/fuzz.sh                                 # build, 3000 cases
#   tests/tools/fuzz.sh --count 300 --seed 7 --program build/rodcontact --scratch /tmp/fuzz
# Options: --program <rodcontact> (default: scripts/setup.sh, then build/rodcontact),
# --count N (3000), --seed S (12345), --scratch DIR (a new temporary directory),
# --timeout SECONDS (5), --quiet (only the summary).
# Exit status: 0 no finding, 1 findings, 2 usage error.
set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
program=""
count=3000
seed=12345
scratch=""
time_limit=5
quiet=no
while (($# > 0)); do
    case $1 in
        --program) program=$2; shift 2 ;;
        --count) count=$2; shift 2 ;;
        --seed) seed=$2; shift 2 ;;
        --scratch) scratch=$2; shift 2 ;;
        --timeout) time_limit=$2; shift 2 ;;
        --quiet) quiet=yes; shift ;;
        -h|--help) sed -n '2,34p' "${BASH_SOURCE[0]}"; exit 0 ;;
        *) echo "fuzz.sh: unknown argument '$1' (try --help)" >&2; exit 2 ;;
    esac
done
if [[ -z "$program" ]]; then
    "$repo_root/scripts/setup.sh" || exit 2
    program="$repo_root/build/rodcontact"
fi
[[ -x "$program" ]] || { echo "fuzz.sh: no program at '$program'" >&2; exit 2; }
[[ -n "$scratch" ]] || scratch=$(mktemp -d)
mkdir -p "$scratch/seeds" "$scratch/findings" || exit 2

traps=no
cache="$(dirname "$program")/CMakeCache.txt"
if [[ -f "$cache" ]] && grep -q '^CMAKE_BUILD_TYPE:[A-Z]*=Debug$' "$cache"; then
    traps=yes
fi

# ---------------------------------------------------------------- seeds
# The shipped inputs without &mesh, &time, &output, plus two that reach other readers
# (&solver and &contact with strings, &material).
n_seed=0
for file in "$repo_root"/input/*.nml; do
    awk '
        skipping { if (index($0, "/")) skipping = 0; next }
        /^[ \t]*&(mesh|time|output)([ \t]|$)/ { if (!index($0, "/")) skipping = 1; next }
        { print }' "$file" > "$scratch/seeds/$n_seed.nml"
    n_seed=$((n_seed + 1))
done
cat > "$scratch/seeds/$n_seed.nml" <<'EOF'
&solver method='paper' tol=1e-7 max_iter=50 /
&contact g=0.1 eps=0.01 law='penalty' /
&initial theta0_poly(1) = 40  theta0_poly(2:3) = -80, 40
         u1_poly = 0, 10  p0_step = 20, 0.1 /
EOF
n_seed=$((n_seed + 1))
cat > "$scratch/seeds/$n_seed.nml" <<'EOF'
&material units='SI' T0=293 rho0=8954 cE=383.1 kappa=386 lambda=7.76e10 mu=3.86e10 alpha_t=1.78e-5
          alpha_c=1.98e-4 D=0.85e-8 nu=1.2e4 varrho=0.9e6 ell=1 tau0=177.7 tau=1777 /
&contact eps=1.0d-2 /
&initial theta0_step = 5, 0.1 /
EOF
n_seed=$((n_seed + 1))

# ---------------------------------------------------------------- mutations
# rand N: R = a pseudo-random integer in 0 .. N-1. A 64-bit linear congruential generator
# whose state lives in this shell (bash reseeds $RANDOM in every $(...) subshell, so it
# cannot reproduce a run); call it as a command, never inside $(...).
STATE=$seed
rand() {
    STATE=$(( (STATE * 6364136223846793005 + 1442695040888963407) & 0x7fffffffffffffff ))
    R=$(( (STATE >> 24) % $1 ))
}
size_of() { stat -c %s "$1"; }

# splice <file> <pos> <n_delete> <insert file>: bytes [0,pos) + insert + bytes [pos+n_delete, end)
splice() {
    local file=$1 pos=$2 n_delete=$3 insert=$4
    { head -c "$pos" "$file"; cat "$insert"; tail -c +"$((pos + n_delete + 1))" "$file"; } > "$file.new"
    mv "$file.new" "$file"
}

# random_number: NUM = a random number in one of several Fortran forms
random_number() {
    local a b sign
    rand 8
    case $R in
        0) rand 2000000; NUM=$(( R - 1000000 )) ;;
        1) rand 1000; a=$R; rand 1000; NUM="$a.$R" ;;
        2) rand 2; sign=-; ((R)) && sign=+
           rand 10; a=$R; rand 100000; b=$R; rand 400; NUM="$a.${b}e$sign$R" ;;
        3) rand 10; a=$R; rand 1000; b=$R; rand 80; NUM="$a.${b}d$(( R - 40 ))" ;;
        4) rand 10; a=$R; rand 10; b=$R; rand 330; NUM="-$a.${b}E-$R" ;;
        5) rand 1000000000; a=$R; rand 1000000000; b=$R; rand 1000000000; NUM="$a$b$R" ;;
        6) rand 100; NUM=".$R" ;;
        *) rand 100; NUM="$R." ;;
    esac
}
SPECIALS=(NaN nan -NaN Inf -Inf Infinity -infinity +Inf 1e308 1.7976931348623157e308 1e309 1e400 -1e400
          1e-400 4.9e-324 2.2250738585072014e-308 0 -0 0.0 2147483647 2147483648 -2147483649
          99999999999999999999 1e 1e+ --1 1.2.3 0x10 1,2 3*1.0 '*' .e5 1e-30 1e30 1e31 1e-31)
TOKENS=('&' '/' '=' ',' "'" '"' '&end' '&model' '&bogus' '&material' 'rho' '(3)' '(0)' '(-1)' '(100)'
        '(1:2)' '3*' ';' '!' $'\r' $'\t' 'é' '$' '%' 'rho=1' "law='x'" '&mesh n_elements=7 /'
        '&output prefix="x" /' "'''" 'theta0_poly(9)=1' 'theta0_poly(10)=1' 'u1_poly(0:3)=1,2,3,4'
        '.true.' 'T' "prefix=''" 'method=' '=1')

# random_bytes <n>: n bytes of any value (NUL included), from rand so that a seed
# reproduces the run
random_bytes() {
    local k escapes=""
    local hex
    for ((k = 0; k < $1; k++)); do rand 256; printf -v hex %02x "$R"; escapes+="\\x$hex"; done
    printf "$escapes"
}

# mutate <file>: apply one random mutation in place
mutate() {
    local file=$1 size n pos len line other piece
    size=$(size_of "$file")
    rand 16
    case $R in
        0)  # flip one byte to a random value (NUL and high bytes included)
            ((size > 0)) || return
            rand "$size"; pos=$R
            random_bytes 1 > "$file.ins"
            splice "$file" "$pos" 1 "$file.ins" ;;
        1)  # delete a range of bytes
            ((size > 0)) || return
            rand "$size"; pos=$R; rand 20; len=$(( R + 1 ))
            : > "$file.ins"; splice "$file" "$pos" "$len" "$file.ins" ;;
        2)  # duplicate a line
            n=$(wc -l < "$file"); ((n > 0)) || return
            rand "$n"; line=$(( R + 1 ))
            awk -v l="$line" '{ print } NR == l { print }' "$file" > "$file.new" && mv "$file.new" "$file" ;;
        3)  # swap two lines (moves groups, splits multi-line groups)
            n=$(wc -l < "$file"); ((n > 1)) || return
            rand "$n"; line=$(( R + 1 )); rand "$n"; other=$(( R + 1 ))
            awk -v a="$line" -v b="$other" '{ l[NR] = $0 } END { t = l[a]; l[a] = l[b]; l[b] = t;
                for (i = 1; i <= NR; i++) print l[i] }' "$file" > "$file.new" && mv "$file.new" "$file" ;;
        4|5)  # replace a number by a random one
            random_number
            replace_number "$file" "$NUM" ;;
        6|7)  # replace a number by a special value
            rand ${#SPECIALS[@]}
            replace_number "$file" "${SPECIALS[$R]}" ;;
        8)  # empty a quoted string
            sed -i "0,/'[^']*'/s//''/" "$file" ;;
        9)  # remove the closing quote of a quoted string
            sed -i "0,/'\([^']*\)'/s//'\1/" "$file" ;;
        10) # a very long line
            rand 200000; n=$(( R + 5000 ))
            rand 5
            case $R in
                0) { printf '! '; head -c "$n" /dev/zero | tr '\0' 'x'; echo; } > "$file.ins" ;;
                1) { head -c "$n" /dev/zero | tr '\0' 'x'; echo; } > "$file.ins" ;;
                2) { printf '&model rho = 1'; head -c "$n" /dev/zero | tr '\0' '0'; echo ' /'; } > "$file.ins" ;;
                3) { printf '&initial u1_poly = '; head -c "$n" /dev/zero | tr '\0' '1' | sed 's/1/0, /g'; echo '/'; } > "$file.ins" ;;
                *) { printf "&solver method = '"; head -c "$n" /dev/zero | tr '\0' 'm'; echo "' /"; } > "$file.ins" ;;
            esac
            rand $((size + 1)); pos=$R
            splice "$file" "$pos" 0 "$file.ins" ;;
        11) # binary junk
            rand 64; random_bytes $(( R + 1 )) > "$file.ins"
            rand $((size + 1)); splice "$file" "$R" 0 "$file.ins" ;;
        12|13) # a stray token
            rand ${#TOKENS[@]}; printf '%s' "${TOKENS[$R]}" > "$file.ins"
            rand $((size + 1)); splice "$file" "$R" 0 "$file.ins" ;;
        14) # truncate
            ((size > 0)) || return
            rand "$size"; head -c "$R" "$file" > "$file.new" && mv "$file.new" "$file" ;;
        *)  # replace a group name by another (or a misspelt one)
            local names=(model contact initial solver material mesh time output modle '')
            rand ${#names[@]}; piece=${names[$R]}
            sed -i "0,/&[a-z]*/s//\&$piece/" "$file" ;;
    esac
    rm -f "$file.ins"
}

# replace_number <file> <text>: the k-th numeric token (k random) becomes <text>. Lines
# of 10000 characters or more (the very long lines above) are left alone: scanning them
# token by token would be quadratic in awk.
replace_number() {
    local file=$1 text=$2
    rand 1000000007
    awk -v r="$R" -v text="$text" '
        function scan(line, replace,    out, piece) {
            out = ""
            while (match(line, /[-+]?[0-9]*\.?[0-9]+([eEdD][-+]?[0-9]+)?/)) {
                count++
                piece = substr(line, RSTART, RLENGTH)
                if (replace && count == k) piece = text
                out = out substr(line, 1, RSTART - 1) piece
                line = substr(line, RSTART + RLENGTH)
            }
            return out line
        }
        NR == FNR { if (length($0) < 10000) scan($0, 0); next }
        FNR == 1 { k = (count > 0) ? r % count + 1 : 0; count = 0 }
        { if (length($0) < 10000) print scan($0, 1); else print }' "$file" "$file" > "$file.new" &&
        mv "$file.new" "$file"
}

# ---------------------------------------------------------------- the loop
declare -A outcome=()
n_finding=0
run_dir="$scratch/run"
mkdir -p "$run_dir"
start_time=$SECONDS
for ((i = 1; i <= count; i++)); do
    input="$run_dir/input.nml"
    rand "$n_seed"; cp "$scratch/seeds/$R.nml" "$input"
    rand 3; n_mut=$(( R + 1 ))
    for ((m = 0; m < n_mut; m++)); do mutate "$input"; done
    printf '\n&mesh n_elements = 20 /\n&time dt = 1e-3, t_end = 2e-3 /\n' >> "$input"
    printf "&output prefix = '%s/out' quiet = .true. /\n" "$run_dir" >> "$input"
    rm -f "$run_dir/out.h5" "$run_dir/out.h5.part"

    timeout -k 2 "$time_limit" "$program" "$input" > "$run_dir/stdout" 2> "$run_dir/stderr" < /dev/null
    status=$?
    # gfortran's runtime warnings of a -fcheck build ('Namelist object truncated on read')
    # are not the program's messages: counted apart, not as lines of the message
    n_warnings=$(grep -ac 'Fortran runtime warning' "$run_dir/stderr")
    n_lines=$(grep -av -c -E '^At line [0-9]+ of file |^Fortran runtime warning' "$run_dir/stderr")
    first=$(grep -av -E '^At line [0-9]+ of file |^Fortran runtime warning' "$run_dir/stderr" | head -n 1 |
            tr -d '\000')
    ((n_warnings > 0)) && outcome["gfortran runtime warning (-fcheck)"]=$(( ${outcome["gfortran runtime warning (-fcheck)"]:-0} + 1 ))
    verdict=""
    kind=""
    if grep -qaE 'Fortran runtime error|Backtrace|Program received signal|Segmentation|Aborted' "$run_dir/stderr"; then
        if [[ $traps == yes && $status -eq 136 ]] && grep -qa 'strtod' "$run_dir/stderr" &&
           grep -qa 'config_m' "$run_dir/stderr"; then
            kind="trap in read (Debug, known)"
        else
            verdict="runtime error / signal (exit $status)"
        fi
    elif [[ $status -eq 124 || $status -eq 137 ]]; then
        verdict="timeout after ${time_limit}s (hang?)"
    else
        case $status in
            0)  kind="exit 0"
                [[ -f "$run_dir/out.h5" && ! -e "$run_dir/out.h5.part" ]] ||
                    verdict="exit 0 without $run_dir/out.h5 (or with a .part left)" ;;
            2)  kind="exit 2"
                [[ $n_lines -eq 1 && "$first" == "rodcontact: error in "* ]] ||
                    verdict="exit 2 without a one-line message ($n_lines lines)"
                [[ -e "$run_dir/out.h5" || -e "$run_dir/out.h5.part" ]] && verdict="exit 2 but an output file was left" ;;
            3)  kind="exit 3"
                [[ $n_lines -eq 1 && "$first" == "rodcontact: error in solver: "* && -f "$run_dir/out.h5" ]] ||
                    verdict="exit 3 without its message or file"
                # allowed, but worth a look: keep the input
                mkdir -p "$scratch/exit3/case$i" && cp "$input" "$run_dir/stderr" "$scratch/exit3/case$i/" ;;
            *)  verdict="exit status $status" ;;
        esac
    fi
    if [[ -n "$verdict" ]]; then
        n_finding=$((n_finding + 1))
        kind="FINDING"
        keep="$scratch/findings/case$i"
        mkdir -p "$keep"
        cp "$input" "$run_dir/stderr" "$keep/"
        echo "fuzz: FINDING case $i: $verdict; input kept in $keep/input.nml; stderr: $(head -c 300 "$run_dir/stderr" | tr '\n' ' ')" >&2
    fi
    outcome[$kind]=$(( ${outcome[$kind]:-0} + 1 ))
    if [[ $quiet == no ]] && ((i % 100 == 0)); then
        echo "fuzz: $i / $count cases, $n_finding findings, $((SECONDS - start_time)) s" >&2
    fi
done

summary="fuzz: $count cases (seed $seed, $n_seed seeds, $((SECONDS - start_time)) s):"
for kind in "exit 0" "exit 2" "exit 3" "trap in read (Debug, known)" "gfortran runtime warning (-fcheck)" FINDING; do
    [[ -n "${outcome[$kind]:-}" ]] && summary+=" $kind: ${outcome[$kind]};"
done
echo "$summary"
[[ $n_finding -eq 0 ]]
