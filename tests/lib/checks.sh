# Shell helpers shared by the shell tests (source it: . "$src/tests/lib/checks.sh").
# check <description> <command ...>: the command must succeed; counts into n_checks/n_failed.
# equals <expected> <got>: succeeds when equal, else prints both.
# wait_in_time_loop <file.h5.part>: see below.
n_checks=0
n_failed=0
check() {
    local what=$1
    shift
    n_checks=$((n_checks + 1))
    if "$@"; then
        echo "PASS $what"
    else
        n_failed=$((n_failed + 1))
        echo "FAIL $what"
    fi
}
equals() {
    [[ "$1" == "$2" ]] && return 0
    echo "  expected: $1"
    echo "  got:      $2"
    return 1
}
# wait_in_time_loop FILE: until the run's FILE (.h5.part) has grown after its first flush
# (the run is then in its time loop, where a signal stops it cleanly), at most 15 s;
# fails if it never does. rodcontact installs its stop handlers before it creates the .part,
# so from then on SIGTERM/SIGINT/SIGUSR1 stop it cleanly.
wait_in_time_loop() {
    local size size0="" i
    for ((i = 0; i < 1500; i++)); do
        size=$(stat -c %s "$1" 2> /dev/null)
        if [[ -n $size ]] && ((size > 1000)); then
            [[ -z $size0 ]] && size0=$size
            ((size > size0)) && return 0
        fi
        sleep 0.01
    done
    return 1
}
