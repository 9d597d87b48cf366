# Option handling shared by the benchmark scripts (bench.sh, output_size.sh,
# work_precision_schemes.sh, adaptive_steps.sh). Source it right after
# `set -euo pipefail` with the script's name and its arguments:
#   . "$repo_root/bench/quick_option.sh" <name> "$@"
# It accepts at most the one option --quick (quick=1; without it quick=0); -h or --help
# prints the calling script's header comment (from line 2 up to `set -euo`) and exits 0;
# anything else exits 2 naming it. It defines say(): a message on stderr prefixed by <name>.
script_name=$1
shift
say() { echo "$script_name: $*" >&2; }
quick=0
case "${1:-}" in
    --quick) quick=1 ;;
    "") ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[1]}" | sed -e '$d' -e 's/^# \{0,1\}//'; exit 0 ;;
    *) say "unknown option '$1' (--quick, --help)"; exit 2 ;;
esac
