#!/usr/bin/env bash
# Bad input: every case must exit with status 2, name group.variable on stderr (and print
# nothing on stdout that looks like an error), and leave no <prefix>.h5 nor <prefix>.h5.part.
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

# check_result <form> <expected where> <extra expected text or ''> <dir> <input text>
check_result() {
    local form=$1 where=$2 extra=$3 dir=$4 text=$5
    local problems=()
    [[ $status -eq 2 ]] || problems+=("exit status: expected 2, got $status")
    grep -qF "rodcontact: error in $where:" "$dir/stderr" ||
        problems+=("stderr: expected 'rodcontact: error in $where:', got '$(head -c 300 "$dir/stderr")'")
    if [[ -n "$extra" ]]; then
        grep -qF -- "$extra" "$dir/stderr" || problems+=("stderr: expected to contain '$extra'")
    fi
    if grep -qi "error" "$dir/stdout"; then
        problems+=("stdout: an error message went to stdout: '$(head -c 200 "$dir/stdout")'")
    fi
    for leftover in "$dir/run.h5" "$dir/run.h5.part"; do
        [[ -e "$leftover" ]] && problems+=("output: expected no file, found $leftover")
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
run_case stdin material.kappa  "got -386"          "&material kappa = -386 /"

# --- validation: &model
run_case file  model.rho       "got -1.2298e-17"   "&model rho = -1.2298e-17 /"
run_case stdin model.alpha     "got NaN"           "&model alpha = NaN /"
run_case file  model.d         "(2.16)"            "&model d = 0.1 /"
run_case stdin model.hbar      "must be > 0"       "&model hbar = 0 /"
run_case file  model.tau0      "must be >= 0"      "&model tau0 = -0.02 /"
# --- &contact
run_case stdin contact.g       "must be > 0"       "&contact g = 0 /"
run_case file  contact.law     "not supported yet" "&contact law = 'signorini' /"
# --- &mesh
run_case stdin mesh.n_elements "must be an integer >= 2" "&mesh n_elements = 1 /"
run_case file  mesh.n_elements "GiB"               "&mesh n_elements = 2000000000 /"
# --- &time
run_case stdin time.dt         "got Inf"           "&time dt = Inf /"
run_case file  time.t_end      "must be >= dt"     "&time dt = 1e-3, t_end = 1e-4 /"
run_case stdin time.scheme     "not supported yet" "&time scheme = 'bdf2' /"
run_case file  time.restart_from "not supported yet" "&time restart_from = 'old.h5' /"
run_case stdin time.dt         "steps"             "&time dt = 1e-12, t_end = 1 /"
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
run_case file  solver.tol      "must be > 0"       "&solver tol = 0 /"
run_case stdin solver.max_iter ">= 1"              "&solver max_iter = 0 /"
# --- &output
run_case file  output.snapshot_every ">= 1"        "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. snapshot_every = 0 /"
run_case stdin output.checkpoint_every "not supported yet" "&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. checkpoint_every = 10 /"
run_case file  output.prefix   "non-empty"         "&output prefix = '' /"
run_case stdin output.snapshot_every "GiB"         "&mesh n_elements = 100000 /
&time dt = 1e-6, t_end = 1 /
&output prefix='$scratch/case$((n_case + 1))/run' quiet=.true. snapshot_every = 1 /"

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
