#!/usr/bin/env bash
# Bad input: every case must exit with status 2 (4 for an output location that cannot be
# created), write exactly one line to stderr, 'rodcontact: error in <group.variable>: ...',
# saying what is allowed (and no gfortran runtime error or backtrace), print nothing on
# stdout that looks like an error, and leave no <prefix>.h5 nor <prefix>.h5.part.
# A valid control run checks that the harness would see an output file if there were one.
#
#   bash tests/test_bad_input.sh <path to rodcontact> <source dir> <scratch dir>
# Exit status: 0 all passed, 1 a case failed, 77 skipped (no program).
set -u

prog=${1:-}
scratch=${3:-}
if [[ -z "$prog" || ! -x "$prog" ]]; then
    echo "SKIP: rodcontact not found at '$prog'"
    exit 77
fi
if [[ -z "$scratch" ]]; then
    scratch=$(mktemp -d)
fi
mkdir -p "$scratch" || exit 1

n_case=0
n_failed=0

# run_case <form> <expected where> <extra expected text or ''> <namelist text>
#   form: stdin (rodcontact < file), file (rodcontact file), dash (rodcontact - < file)
#   Unless the text has its own &output, '&output prefix=<scratch>/caseN/run quiet=.true. /'
#   is appended.
run_case() {
    local form=$1 where=$2 extra=$3 text=$4
    n_case=$((n_case + 1))
    local dir="$scratch/case$n_case"
    rm -rf "$dir"
    mkdir -p "$dir"
    local input="$dir/input.nml"
    printf '%s\n' "$text" > "$input"
    if [[ "$text" != *"&output"* ]]; then
        printf "&output prefix='%s/run' quiet=.true. /\n" "$dir" >> "$input"
    fi
    run_input "$form" "$input" "$dir"
    check_result "$form" "$where" "$extra" "$dir" "$text"
}

# run_input <form> <input path> <dir>: run the program, keep status, stdout, stderr
run_input() {
    local form=$1 input=$2 dir=$3
    case $form in
        stdin) "$prog" < "$input" > "$dir/stdout" 2> "$dir/stderr" ;;
        file) "$prog" "$input" > "$dir/stdout" 2> "$dir/stderr" < /dev/null ;;
        dash) "$prog" - < "$input" > "$dir/stdout" 2> "$dir/stderr" ;;
    esac
    status=$?
}

# Words by which a message says what is allowed (or, for a broken text, what is wrong
# with its structure).
ALLOWED_WORDS="must|allowed|need|at most|at least|give one|only|use law|every group|not closed|cannot open|given twice"

# check_result <form> <expected where> <extra expected text or ''> <dir> <input text> [<prefix>]
#   Expects exit status $expect_status (2 unless the caller sets it) and no <prefix>.h5 nor
#   <prefix>.h5.part (prefix <dir>/run by default).
expect_status=2
check_result() {
    local form=$1 where=$2 extra=$3 dir=$4 text=$5 prefix=${6:-$4/run}
    local problems=()
    [[ $status -eq $expect_status ]] || problems+=("exit status: expected $expect_status, got $status")
    grep -qF "rodcontact: error in $where:" "$dir/stderr" ||
        problems+=("stderr: expected 'rodcontact: error in $where:', got '$(head -c 300 "$dir/stderr")'")
    if [[ -n "$extra" ]]; then
        grep -qF -- "$extra" "$dir/stderr" || problems+=("stderr: expected to contain '$extra'")
    fi
    # gfortran's runtime warnings of a -fcheck build (Debug: 'Namelist object truncated on
    # read') are not the program's messages: noted, not counted
    local n_lines n_warnings
    n_warnings=$(grep -c 'Fortran runtime warning' "$dir/stderr")
    n_lines=$(grep -v -c -E '^At line [0-9]+ of file |^Fortran runtime warning' "$dir/stderr")
    [[ $n_lines -eq 1 ]] || problems+=("stderr: expected exactly 1 line, got $n_lines: '$(head -c 400 "$dir/stderr")'")
    [[ $n_warnings -eq 0 ]] ||
        echo "NOTE case $n_case: $n_warnings gfortran runtime warning(s): $(grep -m 1 'Fortran runtime warning' "$dir/stderr")"
    grep -qE "$ALLOWED_WORDS" "$dir/stderr" ||
        problems+=("stderr: expected the message to say what is allowed (one of: $ALLOWED_WORDS)")
    if grep -qE 'Fortran runtime error|Backtrace|Program received signal' "$dir/stderr"; then
        problems+=("stderr: a runtime error or backtrace instead of a message")
    fi
    if grep -qi "error" "$dir/stdout"; then
        problems+=("stdout: an error message went to stdout: '$(head -c 200 "$dir/stdout")'")
    fi
    for leftover in "$prefix.h5" "$prefix.h5.part"; do
        if [[ "$leftover" == "${keep_dir:-}" ]]; then
            # made a directory by the case itself: must be left as it was, empty
            [[ -d "$leftover" && -z "$(ls -A "$leftover")" ]] ||
                problems+=("output: expected $leftover to stay an empty directory")
        elif [[ -e "$leftover" ]]; then
            problems+=("output: expected no file, found $leftover")
        fi
    done
    local label="case $n_case ($form) $where"
    if [[ ${#problems[@]} -eq 0 ]]; then
        echo "PASS $label: $(head -n 1 "$dir/stderr")"
    else
        n_failed=$((n_failed + 1))
        echo "FAIL $label"
        echo "  input: $(printf '%s' "$text" | tr '\n' ' ')"
        printf '  %s\n' "${problems[@]}"
    fi
}

# --- reader: text, syntax, names, types
run_case stdin model.rho       "Equal sign"        "&model rho = 1.0 alpha 0.5 /"
run_case file  model           "not closed"        "&model rho = 1.0"
run_case dash  model.beta      "unknown variable 'beta'"  "&model beta = 3 /"
run_case stdin model.rho       "must be a real number"    "&model rho = 'abc' /"
run_case file  mesh.n_elements "must be an integer"       "&mesh n_elements = 1.5 /"
run_case stdin input           "unknown namelist group '&modle'" "&modle rho = 1 /"
run_case file  mesh            "given twice"       "&mesh n_elements = 10 /
&mesh n_elements = 20 /"
run_case stdin input           "outside a namelist group" "n_elements = 10"
run_case file  contact.law     "quoted string"     "&contact law = penalty /"
run_case stdin initial.theta0_poly "at most 9"     "&initial theta0_poly = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10 /"
run_case file  material        "both given"        "&material /
&model rho = 1.0 /"
run_case stdin material.kappa  "got -386"          "&material units = 'SI' kappa = -386 /"
run_case stdin material.units  "say so with units = 'SI'" "&material ell = 0.01 /"

# --- validation: &model
run_case file  model.rho       "got -1.2298e-17"   "&model rho = -1.2298e-17 /"
run_case file  model.d         "(2.16)"            "&model d = 0.1 /"
run_case file  model.tau0      "must be >= 0"      "&model tau0 = -0.02 /"
# --- &contact
run_case file  contact.law     "'penalty', 'signorini'" "&contact law = 'hertz' /"
run_case stdin solver.method   "no Signorini form" "&contact law = 'signorini' / &solver method = 'paper' /"
# --- &mesh
run_case stdin mesh.n_elements "must be an integer >= 2" "&mesh n_elements = 1 /"
run_case file  mesh.n_elements "GiB"               "&mesh n_elements = 2000000000 /"
# --- &time
run_case file  time.t_end      "must be >= dt"     "&time dt = 1e-3, t_end = 1e-4 /"
run_case stdin time.scheme     "'euler', 'bdf2'" "&time scheme = 'bdf3' /"
run_case stdin solver.method   "implicit Euler" "&time scheme = 'bdf2' / &solver method = 'paper' /"
run_case file  time.restart_from "no such file" "&time restart_from = 'old.h5' /"
run_case stdin time.dt         "steps"             "&time dt = 1e-12, t_end = 1 /"
run_case file  time.error_tol  "must be > 0"       "&time adaptive = .true., error_tol = 0 /"
run_case stdin time.error_tol  "must be > 0"       "&time adaptive = .true., error_tol = -1e-5 /"
run_case file  time.error_tol  "must be in (0, 1)" "&time adaptive = .true., error_tol = 2 /"
run_case stdin time.dt_min     "must be <= dt_max" "&time adaptive = .true., dt_min = 1e-2, dt_max = 1e-3 /"
run_case file  time.dt_min     "must be > 0"       "&time adaptive = .true., dt_min = 0 /"
run_case stdin time.dt         "[dt_min, dt_max]"  "&time adaptive = .true., dt = 1e-4, dt_min = 1e-3 /"
run_case file  time.adaptive   ".true. or .false." "&time adaptive = 'yes' /"
run_case stdin solver.method   "adaptive steps"    "&time adaptive = .true. / &solver method = 'paper' /"
run_case file  output.snapshot_dt "must be >= 0"   "&output snapshot_dt = -0.1 /"
# --- &initial
run_case file  initial.u0_poly "u0(1) <= g"        "&initial u0_poly = 0, 0.2 /"
run_case stdin initial.theta0_poly "must be 0 at x = 1" "&initial theta0_poly = 0, 40, -80 /"
run_case file  initial.q0_poly "must be 0 at x = 0" "&initial q0_poly = 1 /"
run_case stdin initial.u1_poly "must be 0 at x = 0" "&initial u1_poly = 0.5, 10 /"
run_case file  initial.theta0_step "must be 0 at x = 1" "&initial theta0_step = 20, 1.0 /"
run_case stdin initial.p0_step "x_end"             "&initial p0_step = 20, 1.5 /"
run_case file  initial.eta0_poly "finite"          "&initial eta0_poly = 0, -Inf /"
# --- &solver
run_case stdin solver.method   "'monolithic', 'paper'" "&solver method = 'foo' /"
run_case stdin solver.max_iter ">= 1"              "&solver max_iter = 0 /"
# --- &output
run_case file  output.snapshot_every ">= 1"        "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. snapshot_every = 0 /"
run_case stdin output.checkpoint_every ">= 0" "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. checkpoint_every = -10 /"
run_case stdin output.compression "from 0 (no compression) to 9" "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. compression = 10 /"
run_case stdin output.compression "from 0 (no compression) to 9" "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. compression = -1 /"
run_case file  output.prefix   "non-empty"         "&output prefix = '' /"
run_case stdin output.snapshot_every "GiB"         "&mesh n_elements = 100000 /
&time dt = 1e-6, t_end = 1 /
&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. snapshot_every = 1 /"

# --- more reader cases: types, values, structure
run_case file  output.quiet    "must be .true. or .false." "&output prefix='$scratch/case$((n_case + 1))/run' quiet = 'yes' /"
run_case stdin solver.max_iter "must be an integer" "&solver max_iter = .true. /"
run_case file  mesh.n_elements "must be an integer" "&mesh n_elements = NaN /"
run_case stdin mesh.n_elements "Integer overflow"  "&mesh n_elements = 3000000000 /"
run_case file  model.rho       "given twice"       "&model rho = 1.0 rho = 2.0 /"
run_case stdin model.rho       "no value"          "&model rho = /"
run_case file  contact         "not closed"        "&contact law = 'penalty /"
run_case stdin input           "without a group name" "& /"

# --- every checked real: zero, negative, NaN, Inf, too large (and too small where the
# scheme divides by it). Variables that must be > 0 and are divided by:
m=0
for where in model.rho model.alpha model.c model.r model.hbar contact.eps time.dt; do
    group=${where%%.*} var=${where#*.}
    for value in 0 -1 NaN Inf 1e31 1e-31; do
        case $value in
            0|-1) expected="must be > 0" ;;
            NaN|Inf) expected="must be a finite real number" ;;
            1e31) expected="at most 1e30" ;;
            1e-31) expected="must be >= 1e-30" ;;
        esac
        forms=(stdin file dash); form=${forms[$((m % 3))]}; m=$((m + 1))
        run_case "$form" "$where" "$expected" "&$group $var = $value /"
    done
done
# must be > 0, not divided by (tiny values are fine)
for where in contact.g time.t_end solver.tol; do
    group=${where%%.*} var=${where#*.}
    for value in 0 -1 NaN -Inf 1e31; do
        case $value in
            0|-1) expected="must be > 0" ;;
            NaN|-Inf) expected="must be a finite real number" ;;
            1e31) expected="at most 1e30" ;;
        esac
        forms=(stdin file dash); form=${forms[$((m % 3))]}; m=$((m + 1))
        run_case "$form" "$where" "$expected" "&$group $var = $value /"
    done
done
# must be >= 0
for where in model.varpi model.gamma1 model.gamma2 model.d model.tau0 model.tau; do
    group=${where%%.*} var=${where#*.}
    for value in -1 NaN Inf 1e31; do
        case $value in
            -1) expected="must be >= 0" ;;
            NaN|Inf) expected="must be a finite real number" ;;
            1e31) expected="at most 1e30" ;;
        esac
        forms=(stdin file dash); form=${forms[$((m % 3))]}; m=$((m + 1))
        run_case "$form" "$where" "$expected" "&$group $var = $value /"
    done
done
# integers
run_case stdin mesh.n_elements "must be an integer >= 2" "&mesh n_elements = 0 /"
run_case file  mesh.n_elements "must be an integer >= 2" "&mesh n_elements = -5 /"
run_case stdin solver.max_iter ">= 1"              "&solver max_iter = -1 /"
run_case file  output.series_every ">= 1"          "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. series_every = 0 /"
run_case stdin output.snapshot_every ">= 1"        "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. snapshot_every = -3 /"
# (2.16) exactly on its boundary: c*r - d**2 = 0
run_case file  model.d         "(2.16)"            "&model c = 1, r = 1, d = 1 /"
# initial data: non-finite or too large coefficients, boundary values of the spaces
for var in u0_poly u1_poly theta0_poly p0_poly q0_poly eta0_poly; do
    forms=(stdin file dash); form=${forms[$((m % 3))]}; m=$((m + 1))
    run_case "$form" "initial.$var" "finite" "&initial $var = 0, NaN /"
    run_case "$form" "initial.$var" "at most 1e30" "&initial $var = 0, 1e300, -1e300 /"
done
run_case stdin initial.theta0_step "finite"        "&initial theta0_step = Inf, 0.5 /"
run_case file  initial.p0_step "at most 1e30"      "&initial p0_step = 1e31, 0.5 /"
run_case stdin initial.theta0_step "need 0 <= x_end <= 1" "&initial theta0_step = 1, -0.1 /"
run_case file  initial.u0_poly "must be 0 at x = 0" "&initial u0_poly = 1 /"
run_case stdin initial.p0_poly "must be 0 at x = 1" "&initial p0_poly = 1 /"
run_case file  initial.eta0_poly "must be 0 at x = 0" "&initial eta0_poly = -2, 1 /"
run_case stdin initial.u0_poly "u0(1) <= g"        "&contact g = 0.01 /
&initial u0_poly = 0, 0, 0.02 /"
# tables of &initial (*_file): the file, each line, the rows, the rod covered, the values,
# the boundary values of the profile they add to (docs/input.md, "Tables")
tables="$scratch/tables"
mkdir -p "$tables"
printf '0 1\nabc 2\n1 0\n' > "$tables/word.txt"
printf '# x value\n0 1 2\n1 0\n' > "$tables/three.txt"
printf '0 1\n0.5 1\n\n0.5 2   # again\n1 0\n' > "$tables/repeat.txt"
printf '# one row\n0 0\n' > "$tables/one.txt"
printf '0.1 1\n1 0\n' > "$tables/short.txt"
printf '0 1\n1 1\n' > "$tables/one_at_1.txt"
printf '0 0\n1 0.2\n' > "$tables/u0.txt"
printf '0 nan\n1 0\n' > "$tables/nan.txt"
printf '0 1e31\n1 0\n' > "$tables/big.txt"
run_case file  initial.theta0_file "cannot open"   "&initial theta0_file = '$tables/none.txt' /"
run_case stdin initial.p0_file "directory"         "&initial p0_file = '$tables' /"
run_case file  initial.theta0_file "word.txt' line 2: got 'abc 2'" "&initial theta0_file = '$tables/word.txt' /"
run_case dash  initial.eta0_file "three.txt' line 2" "&initial eta0_file = '$tables/three.txt' /"
run_case file  initial.q0_file "repeat.txt' line 4: position 0.5 after 0.5 (line 2)" \
    "&initial q0_file = '$tables/repeat.txt' /"
run_case stdin initial.u1_file "at least two rows" "&initial u1_file = '$tables/one.txt' /"
run_case file  initial.theta0_file "must cover the rod" "&initial theta0_file = '$tables/short.txt' /"
run_case stdin initial.theta0_file "must be 0 at x = 1" "&initial theta0_file = '$tables/one_at_1.txt' /"
run_case file  initial.q0_file "must be 0 at x = 0" "&initial q0_file = '$tables/one_at_1.txt' /"
run_case dash  initial.u0_file "u0(1) <= g"        "&initial u0_file = '$tables/u0.txt' /"
run_case file  initial.p0_file "nan.txt' line 1"   "&initial p0_file = '$tables/nan.txt' /"
run_case stdin initial.p0_file "at most 1e30"      "&initial p0_file = '$tables/big.txt' /"
# prefixes that do not name a file (input errors, exit 2)
run_case file  output.prefix   "names a directory" "&output prefix = '$scratch/case$((n_case + 1))/' /"
run_case stdin output.prefix   "names a directory" "&output prefix = '.' /"
run_case file  output.prefix   "control character" "&output prefix = '$scratch/case$((n_case + 1))/r$(printf '\001')un' /"
run_case stdin output.prefix   "at most 1023"      "&output prefix = '$scratch/case$((n_case + 1))/$(printf 'x%.0s' {1..1100})' /"

# --- output locations that cannot be created: exit 4, naming output.prefix
# run_output_case <label> <prefix> <extra expected text>: <prefix> must not get a file
run_output_case() {
    local label=$1 prefix=$2 extra=$3
    n_case=$((n_case + 1))
    local dir="$scratch/case$n_case"
    local input="$dir/input.nml"
    printf '%s\n' "&mesh n_elements = 4 /" "&time dt = 1e-3, t_end = 2e-3 /" \
        "&output prefix='$prefix' quiet=.true. /" > "$input"
    run_input file "$input" "$dir"
    expect_status=4
    check_result file output.prefix "$extra" "$dir" "($label) prefix '$prefix'" "$prefix"
    expect_status=2
}
prepare() { n_next=$((n_case + 1)); rm -rf "$scratch/case$n_next"; mkdir -p "$scratch/case$n_next"; }
prepare; touch "$scratch/case$n_next/regular-file"
run_output_case "under a regular file" "$scratch/case$n_next/regular-file/run" "is not a directory"
prepare; touch "$scratch/case$n_next/regular-file"
run_output_case "two levels under a regular file" "$scratch/case$n_next/regular-file/sub/run" "is not a directory"
prepare
run_output_case "directory cannot be created under /proc" "/proc/rodcontact-no-such-dir/run" "cannot create directory"
prepare
run_output_case "file cannot be created in /proc/self" "/proc/self/rodcontact-run" "cannot create"
prepare
run_output_case "read-only for root: /sys" "/sys/rodcontact-run" "Permission denied"
prepare; keep_dir="$scratch/case$n_next/run.h5"; mkdir -p "$keep_dir"
run_output_case "<prefix>.h5 is a directory" "$scratch/case$n_next/run" "is a directory"
prepare; keep_dir="$scratch/case$n_next/run.h5.part"; mkdir -p "$keep_dir"
run_output_case "<prefix>.h5.part is a directory" "$scratch/case$n_next/run" "Is a directory"
keep_dir=''
prepare
run_output_case "file name longer than NAME_MAX" "$scratch/case$n_next/$(printf 'n%.0s' {1..300})" "File name too long"

# --- a file that cannot be read
n_case=$((n_case + 1))
dir="$scratch/case$n_case"
rm -rf "$dir" && mkdir -p "$dir"
run_input file "$dir/does-not-exist.nml" "$dir"
check_result file input "cannot open" "$dir" "(missing file $dir/does-not-exist.nml)"
n_case=$((n_case + 1))
dir="$scratch/case$n_case"
rm -rf "$dir" && mkdir -p "$dir"
run_input file "$dir" "$dir"
check_result file input "directory" "$dir" "(a directory as input file)"

# --- no namelist group at all (an empty file, empty standard input, only comments): exit 2
# with a message saying how to run with the defaults; nothing written (default prefix out/run,
# relative to the working directory, which is the case's directory)
for entry in "stdin|" "file|" "dash|" "file|! only a comment"; do
    form=${entry%%|*} text=${entry#*|}
    n_case=$((n_case + 1))
    dir="$scratch/case$n_case"
    rm -rf "$dir" && mkdir -p "$dir"
    if [[ -n "$text" ]]; then printf '%s\n' "$text" > "$dir/input.nml"; else : > "$dir/input.nml"; fi
    pushd "$dir" > /dev/null && run_input "$form" "$dir/input.nml" "$dir" && popd > /dev/null
    check_result "$form" input "echo '&model /' | rodcontact" "$dir" "(no group: '$text')" "$dir/out/run"
    if [[ -e "$dir/out" ]]; then
        n_failed=$((n_failed + 1)); echo "FAIL case $n_case (no group, $form): $dir/out was created"
    fi
done

# --- control: a valid input does write <prefix>.h5 (so the checks above can fail)
dir="$scratch/control"
rm -rf "$dir" && mkdir -p "$dir"
printf '%s\n' "&mesh n_elements = 4 /" "&time dt = 1e-3, t_end = 2e-3 /" \
    "&output prefix='$dir/run' quiet=.true. /" > "$dir/input.nml"
run_input stdin "$dir/input.nml" "$dir"
if [[ $status -eq 0 && -e "$dir/run.h5" && ! -e "$dir/run.h5.part" ]]; then
    echo "PASS control (valid input): exit 0 and $dir/run.h5 written"
else
    n_failed=$((n_failed + 1))
    echo "FAIL control (valid input): expected exit 0 and $dir/run.h5, got exit $status," \
        "files: $(ls "$dir" | tr '\n' ' '), stderr: $(head -c 300 "$dir/stderr")"
fi

echo "test_bad_input: $((n_case + 1)) cases, $n_failed failed"
[[ $n_failed -eq 0 ]]
