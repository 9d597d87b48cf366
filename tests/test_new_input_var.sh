#!/usr/bin/env bash
# A new input variable is one line in config_m (src/input/generate_input_vars.py writes the
# rest): a copy of config_m.f90 with one new component of &time, `knob`, is run through the
# generator, and the input layer is compiled from it with a small program that reads an
# input and prints what it got. The new variable must be read from the text and from
# --set, keep its default, be recorded with the inputs (input_items, after t_end), be named
# in the messages of a bad value and of an unknown name, and the generator must refuse a
# component it cannot read, naming the line.
#
#   bash tests/test_new_input_var.sh <path to rodcontact (unused)> <source dir> <scratch dir>
# Exit status: 0 passed, 1 failed, 77 skipped (no Fortran compiler or python3).
set -u

src=${2:-}
scratch=${3:-$(mktemp -d)}
fc=${FC:-gfortran}
if [[ -z "$src" || ! -f "$src/src/input/config_m.f90" ]]; then
    echo "usage: bash test_new_input_var.sh <rodcontact> <source dir> <scratch dir>"
    exit 1
fi
command -v "$fc" > /dev/null && command -v python3 > /dev/null || { echo "SKIP: no $fc or python3"; exit 77; }
rm -rf "$scratch/work"
mkdir -p "$scratch/work/gen" "$scratch/work/mod" || exit 1
cd "$scratch/work" || exit 1

n_failed=0
fail() { echo "FAIL: $*"; n_failed=$((n_failed + 1)); }
pass() { echo "PASS: $*"; }

# --- the one edit ------------------------------------------------------------------------
for f in base/kinds_m base/errors_m base/reals_m base/strings_m input/config_m input/input_vars_m input/namelist_text_m \
         input/material_m input/config_reader_m; do
    cp "$src/src/$f.f90" . || exit 1
done
sed -i 's|^\( *\)real(dp) :: t_end = 1.0_dp$|&\n\1real(dp) :: knob = 2.5_dp   !< added by test_new_input_var|' config_m.f90
grep -q ':: knob = 2.5_dp' config_m.f90 || { echo "FAIL: could not add knob after t_end in config_m.f90"; exit 1; }

python3 "$src/src/input/generate_input_vars.py" config_m.f90 gen || { echo "FAIL: generator failed"; exit 1; }
cat > knob.f90 << 'EOF'
program knob
    use config_m, only: config_t
    use config_reader_m, only: read_config
    use namelist_text_m, only: string_t
    use input_vars_m, only: input_item_t, input_items
    implicit none
    type(config_t) :: cfg
    type(input_item_t), allocatable :: items(:)
    character(len=256) :: source, set
    integer :: k

    call get_command_argument(1, source)
    call get_command_argument(2, set)
    if (set == '') then
        call read_config(trim(source), cfg)
    else
        call read_config(trim(source), cfg, [string_t(set)])
    end if
    write (*, '(a, es10.3)') 'knob ', cfg%time%knob
    items = input_items(cfg)
    write (*, '(a)', advance='no') 'items'
    do k = 1, size(items)
        if (items(k)%name(1:5) == 'time.') write (*, '(1x, a)', advance='no') items(k)%name
    end do
    write (*, '(a)') ''
end program knob
EOF
if ! "$fc" -std=f2018 -fimplicit-none -Igen -Jmod kinds_m.f90 errors_m.f90 reals_m.f90 strings_m.f90 config_m.f90 \
        input_vars_m.f90 namelist_text_m.f90 material_m.f90 config_reader_m.f90 knob.f90 \
        -o knob > compile.log 2>&1; then
    echo "FAIL: the input layer does not compile with the new variable:"
    head -20 compile.log
    exit 1
fi

# --- what the new variable gets ----------------------------------------------------------
# check_run <name> <expected status> <expected text in stdout+stderr> <input text> [--set value]
check_run() {
    local name=$1 want_status=$2 want=$3 text=$4 set=${5:-}
    printf '%s\n' "$text" > "$name.nml"
    ./knob "$name.nml" "$set" > "$name.out" 2>&1
    local status=$?
    if [[ $status -ne $want_status ]]; then
        fail "$name: exit status $status, expected $want_status: $(head -c 300 "$name.out")"
    elif ! grep -qF -- "$want" "$name.out"; then
        fail "$name: expected '$want' in: $(head -c 300 "$name.out")"
    else
        pass "$name: $want"
    fi
}
check_run default 0 'knob  2.500E+00' '&time dt = 0.1 /'
check_run text 0 'knob  3.500E+00' '&time knob = 3.5 /'
check_run set 0 'knob  4.500E+00' '&time knob = 3.5 /' 'time.knob=4.5'
check_run recorded 0 'items time.dt time.t_end time.knob time.scheme' '&time /'
check_run bad_value 2 "rodcontact: error in time.knob: got 'x'; must be a real number" "&time knob = 'x' /"
check_run unknown_name 2 'allowed: dt, t_end, knob, scheme,' '&time knobs = 1.0 /'

# --- a component the generator cannot read -----------------------------------------------
sed -i 's|^\( *\)real(dp) :: knob = 2.5_dp .*$|\1real(dp) :: knob = 2.5_dp, other = 1.0_dp|' config_m.f90
line=$(grep -n ':: knob = 2.5_dp, other' config_m.f90 | cut -d: -f1)
if python3 "$src/src/input/generate_input_vars.py" config_m.f90 gen > generator.out 2>&1; then
    fail "the generator accepted two components on one line"
elif ! grep -q "config_m.f90:$line: .*cannot read this component of &time" generator.out; then
    fail "the generator's message does not name line $line: $(cat generator.out)"
else
    pass "two components on one line: $(cat generator.out)"
fi

if [[ $n_failed -gt 0 ]]; then
    echo "test_new_input_var: $n_failed check(s) failed"
    exit 1
fi
echo "test_new_input_var: all passed"
