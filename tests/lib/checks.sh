# Shell helpers shared by the shell tests (source it: . "$src/tests/lib/checks.sh").
# check <description> <command ...>: the command must succeed; counts into n_checks/n_failed.
# equals <expected> <got>: succeeds when equal, else prints both.
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
