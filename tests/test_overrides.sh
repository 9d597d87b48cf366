#!/usr/bin/env bash
# Command-line overrides (--set group.variable=value) and rodcontact --summary.
#
# Good cases: a run with --set must be the same run as one from a namelist file that holds
# the overridden values (their --summary rows agree in every column but file and wall
# seconds), for a scalar, an array element, a whole array, a group the file lacks, a
# string without quotes, stdin input, the --set=... form, and a variable given twice (the
# later value wins).
# Bad cases: exit status 2, 'rodcontact: error in <where>:' on stderr with the expected
# text, and no output file.
#
#   bash tests/test_overrides.sh <path to rodcontact> <source dir> <scratch dir>
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
cd "$scratch" || exit 1
rm -rf good bad
mkdir -p good bad

n_case=0
n_failed=0

fail() {
    n_failed=$((n_failed + 1))
    echo "FAIL case $n_case: $1"
    shift
    printf '  %s\n' "$@"
}

# A coarse, fast experiment 2 (pulses of amplitude 20, contact at t ~ 0.3).
base_text="&model varpi = 0.1 /
&mesh n_elements = 40 /
&time dt = 2e-3 t_end = 0.5 /
&initial theta0_step = 20, 0.1
         p0_step = 20, 0.1
         u1_poly = 0, 10 /
&output prefix = 'good/base' quiet = .true. snapshot_every = 1000 /"
printf '%s\n' "$base_text" > base.nml

# summary_without_file_and_wall FILE.h5: its --summary row minus the file and wall_seconds
summary_core() {
    "$prog" --summary "$1" | awk -F, '{ $1 = ""; $17 = ""; print }'
}

# same_run <name> <namelist text of the reference> <command ...>: the command writes
# good/<name>.h5 (its --set output.prefix), the reference text writes good/<name>_ref.h5
same_run() {
    local name=$1 ref_text=$2
    shift 2
    n_case=$((n_case + 1))
    printf '%s\n' "$ref_text" | sed "s|prefix = 'good/base'|prefix = 'good/${name}_ref'|" > "good/${name}_ref.nml"
    "$prog" "good/${name}_ref.nml" > /dev/null 2> "good/${name}_ref.err" ||
        { fail "$name: the reference run failed" "$(cat "good/${name}_ref.err")"; return; }
    "$@" > "good/$name.out" 2> "good/$name.err"
    local status=$?
    if ((status != 0)); then
        fail "$name: expected exit status 0, got $status" "command: $*" "stderr: $(head -c 300 "good/$name.err")"
        return
    fi
    if [[ ! -f good/$name.h5 ]]; then
        fail "$name: expected good/$name.h5" "command: $*"
        return
    fi
    local got expected
    got=$(summary_core "good/$name.h5")
    expected=$(summary_core "good/${name}_ref.h5")
    if [[ "$got" != "$expected" ]]; then
        fail "$name: the --set run differs from the run of the file with those values" \
             "command:  $*" "expected: $expected" "got:      $got"
        return
    fi
    echo "PASS case $n_case $name"
}

# the reference texts: base.nml with one thing changed
with() { printf '%s\n' "$base_text" | sed "$1"; }

same_run scalar "$(with 's/varpi = 0.1/varpi = 0.3/')" \
    "$prog" base.nml --set model.varpi=0.3 --set output.prefix=good/scalar
same_run element "$(with 's/theta0_step = 20, 0.1/theta0_step = 5, 0.1/')" \
    "$prog" base.nml --set 'initial.theta0_step(1)=5' --set output.prefix=good/element
same_run element_x_end "$(with 's/p0_step = 20, 0.1/p0_step = 20, 0.2/')" \
    "$prog" base.nml --set 'initial.p0_step( 2 )=0.2' --set output.prefix=good/element_x_end
same_run whole_array "$(with 's/p0_step = 20, 0.1/p0_step = 7.5, 0.05/')" \
    "$prog" base.nml --set initial.p0_step=7.5,0.05 --set output.prefix=good/whole_array
same_run new_group "$(with 's|^&model varpi = 0.1 /|\&model varpi = 0.1 /\n\&contact eps = 0.02 g = 0.09 /|')" \
    "$prog" base.nml --set contact.eps=0.02 --set CONTACT.G=0.09 --set output.prefix=good/new_group
same_run stdin "$(with 's/varpi = 0.1/varpi = 0.3/')" \
    "$prog" --set model.varpi=0.3 --set output.prefix=good/stdin < base.nml
same_run dash "$(with 's/varpi = 0.1/varpi = 0.3/')" \
    "$prog" - --set=model.varpi=0.3 --set=output.prefix=good/dash < base.nml
same_run keyword_and_logical "$(with 's/^&model varpi = 0.1 \//\&model varpi = 0.1 \/\n\&solver method = "monolithic" tol = 1e-8 \//')" \
    "$prog" --set solver.method=MONOLITHIC --set solver.tol=1d-8 --set output.quiet=true base.nml \
    --set output.prefix=good/keyword_and_logical
same_run quoted_string "$base_text" "$prog" base.nml --set "output.prefix='good/quoted_string'"
# a later --set of a variable overrides an earlier one (also the output prefix, and an element
# after its whole array), so that a command can be repeated with one more --set appended
same_run later_wins "$(with 's/varpi = 0.1/varpi = 0.3/')" \
    "$prog" base.nml --set model.varpi=1 --set MODEL.VARPI=0.3 --set output.prefix=good/later_wins
same_run element_after_array "$(with 's/p0_step = 20, 0.1/p0_step = 5, 0.05/')" \
    "$prog" base.nml --set initial.p0_step=7.5,0.05 --set 'initial.p0_step(1)=5' --set output.prefix=good/element_after_array
same_run prefix_twice "$base_text" "$prog" base.nml --set output.prefix=good/first_prefix --set output.prefix=good/prefix_twice
n_case=$((n_case + 1))
if [[ -e good/first_prefix.h5 || -e good/first_prefix.h5.part ]]; then
    fail "prefix given twice: the earlier output.prefix was written (good/first_prefix.h5)"
else
    echo "PASS case $n_case: prefix given twice: only the later one written"
fi

# a string with a blank and a quote, into a directory that does not exist yet
n_case=$((n_case + 1))
"$prog" base.nml --set "output.prefix=good/it's new/run" > /dev/null 2> good/odd.err
if [[ $? -ne 0 || ! -f "good/it's new/run.h5" ]]; then
    fail "string with a blank and a quote: expected exit 0 and \"good/it's new/run.h5\"" "$(cat good/odd.err)"
else
    echo "PASS case $n_case string with a blank and a quote"
fi

# bad <where> <expected text> <how: file|stdin> <--set arguments ...>
bad() {
    local where=$1 extra=$2 how=$3
    shift 3
    n_case=$((n_case + 1))
    local dir="bad/case$n_case"
    mkdir -p "$dir"
    local status
    if [[ $how == stdin ]]; then
        "$prog" "$@" --set "output.prefix=$dir/run" < base.nml > "$dir/stdout" 2> "$dir/stderr"
    else
        "$prog" base.nml "$@" --set "output.prefix=$dir/run" < /dev/null > "$dir/stdout" 2> "$dir/stderr"
    fi
    status=$?
    local problems=()
    [[ $status -eq 2 ]] || problems+=("exit status: expected 2, got $status")
    grep -qF -- "rodcontact: error in $where:" "$dir/stderr" ||
        problems+=("stderr: expected 'rodcontact: error in $where:', got '$(head -c 300 "$dir/stderr")'")
    grep -qF -- "$extra" "$dir/stderr" || problems+=("stderr: expected to contain '$extra'")
    [[ -s "$dir/stdout" ]] && problems+=("stdout: expected nothing, got '$(head -c 200 "$dir/stdout")'")
    for leftover in "$dir/run.h5" "$dir/run.h5.part"; do
        [[ -e "$leftover" ]] && problems+=("output: expected no file, found $leftover")
    done
    if ((${#problems[@]} == 0)); then
        echo "PASS case $n_case: $(head -n 1 "$dir/stderr")"
    else
        fail "$where ($how): $*" "${problems[@]}"
    fi
}

bad "--set model.varpy"          "unknown variable 'varpy' in &model; allowed: rho, alpha, varpi" file --set model.varpy=1
bad "--set modl.varpi"           "unknown namelist group 'modl'; allowed groups: &model" file --set modl.varpi=1
bad "--set varpi=1"              "expected group.variable=value" file --set varpi=1
bad "--set model.varpi"          "expected group.variable=value" file --set model.varpi
bad "--set model.varpi"          "got 'abc'; must be a real number" file --set model.varpi=abc
bad "--set model.varpi"          "no value after 'varpi ='; must be a real number" file --set model.varpi=
bad "--set model.varpi"          "got '0.3/'; must be a real number" file --set model.varpi=0.3/
bad "--set time.t_end"           "got '1 dt=3'; must be a real number" file --set "time.t_end=1 dt=3"
bad "--set model.varpi"          "got '1,2'; must be a real number" file --set model.varpi=1,2
bad "--set mesh.n_elements"      "must be an integer" file --set mesh.n_elements=2.5
bad "--set output.quiet"         "must be .true. or .false." file --set output.quiet=maybe
bad "--set initial.theta0_step"  "must be two real numbers: amplitude, x_end" file --set initial.theta0_step=1,2,3
bad "--set initial.theta0_step"  "theta0_step(3) = 1" file --set 'initial.theta0_step(3)=1'
bad "--set initial.theta0_step(x)" "expected a subscript like 'theta0_step(1)'" file --set 'initial.theta0_step(x)=1'
bad "--set model.varpi(1)"       "'varpi' is not an array" file --set 'model.varpi(1)=1'
bad "--set material.t0"          "&material and &model are both given" file --set material.T0=300
bad "--set model.varpy"          "unknown variable 'varpy'" stdin --set model.varpy=1
bad "--set initial.u1_poly"      "at most 9 real coefficients" stdin --set initial.u1_poly=0,1,2,3,4,5,6,7,8,9
# value ranges are checked by validation, with the same message as for the file
bad "model.rho"                  "got -1; must be > 0" file --set model.rho=-1
bad "solver.method"              "got 'newton'; must be one of 'monolithic', 'paper'" stdin --set solver.method=newton
bad "initial.theta0_step"        "must be 0 at x = 1" file --set initial.theta0_step=20,1.0

# command-line errors
n_case=$((n_case + 1))
"$prog" base.nml --set > bad/noarg.out 2> bad/noarg.err
status=$?
if [[ $status -eq 2 ]] && grep -qF "rodcontact: error in command line: --set needs an argument" bad/noarg.err; then
    echo "PASS case $n_case: $(head -n 1 bad/noarg.err)"
else
    fail "--set without an argument: expected exit 2 and '--set needs an argument'" "got $status: $(cat bad/noarg.err)"
fi
n_case=$((n_case + 1))
"$prog" --summary bad/none.h5 > bad/summary.out 2> bad/summary.err
status=$?
if [[ $status -eq 2 ]] && grep -qF "'bad/none.h5': no such file" bad/summary.err; then
    echo "PASS case $n_case: $(head -n 1 bad/summary.err)"
else
    fail "--summary of a missing file: expected exit 2 and 'no such file'" "got $status: $(cat bad/summary.err)"
fi

# --summary-header and --summary of the base run agree on the number of columns
n_case=$((n_case + 1))
"$prog" base.nml > /dev/null 2>&1
header=$("$prog" --summary-header)
row=$("$prog" --summary good/base.h5)
if [[ $(awk -F, '{print NF}' <<< "$header") -eq $(awk -F, '{print NF}' <<< "$row") && "$row" == good/base.h5,complete,yes,* ]]; then
    echo "PASS case $n_case: --summary good/base.h5: $row"
else
    fail "--summary: expected a row of as many columns as the header, starting good/base.h5,complete,yes," \
         "header: $header" "row:    $row"
fi

# --summary of several files: one row each, in order; a file that is not a rodcontact
# output (missing, not HDF5, HDF5 without /series) exits 2 naming it, with no row at all
n_case=$((n_case + 1))
cp good/base.h5 good/copy.h5
rows=$("$prog" --summary good/base.h5 good/copy.h5)
if [[ $(wc -l <<< "$rows") -eq 2 && $(sed -n 1p <<< "$rows") == good/base.h5,complete,* \
      && $(sed -n 2p <<< "$rows") == good/copy.h5,complete,* ]]; then
    echo "PASS case $n_case: --summary of two files: two rows"
else
    fail "--summary of two files: expected a row for good/base.h5 then good/copy.h5" "got: $rows"
fi
head -c 100 /dev/urandom > bad/noise.h5
cp base.nml bad/input.h5
bad_summaries=("bad/noise.h5:not an HDF5 file" "bad/input.h5:not an HDF5 file" "bad/none.h5:no such file")
py=$("${2:-.}/scripts/lib/find_python.sh" 2>/dev/null) && "$py" -c "
import h5py; h5py.File('bad/other.h5', 'w').create_dataset('x', data=[1.0])" \
    && bad_summaries+=("bad/other.h5:not a rodcontact output file")
for entry in "${bad_summaries[@]}"; do
    n_case=$((n_case + 1))
    file=${entry%%:*}; text=${entry#*:}
    "$prog" --summary good/base.h5 "$file" > bad/summary.out 2> bad/summary.err
    status=$?
    if [[ $status -eq 2 && ! -s bad/summary.out ]] && grep -qF "'$file': $text" bad/summary.err; then
        echo "PASS case $n_case: $(head -n 1 bad/summary.err)"
    else
        fail "--summary with $file: expected exit 2, no row, and '$file': $text" \
             "got $status: $(cat bad/summary.err) / stdout: $(cat bad/summary.out)"
    fi
done

echo "test_overrides: $n_case cases, $n_failed failed"
((n_failed == 0))
