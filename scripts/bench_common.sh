# Sourced by scripts/bench.sh and scripts/bench_large.sh: the arguments and directories both take.

# bench_args HELP_END ARG...: prints lines 2..HELP_END of the script for -h/--help, sets
# `results` from the one positional argument and passes every other option to the caller's
# bench_option, which returns non-zero for one it does not know (exit 2).
bench_args() {
  local help_end=$1 arg
  shift
  results=""
  for arg in "$@"; do
    case "$arg" in
      -h|--help) sed -n "2,${help_end}p" "$0"; exit 0 ;;
      -*) bench_option "$arg" || { echo "unknown option $arg" >&2; exit 2; } ;;
      *) results=$arg ;;
    esac
  done
}

# bench_dirs DATA_SUFFIX RESULTS_PREFIX: sets `root`, `target` (CARGO_TARGET_DIR or
# <root>/target), `data` ($TOPOPLEX_BENCH_DATA or <target>/bench-data, then DATA_SUFFIX) and
# `results` (the argument, or <target>/bench-results/RESULTS_PREFIX<UTC date-time>), each
# created and made absolute.
bench_dirs() {
  root=$(cd "$(dirname "$0")/.." && pwd)
  target=${CARGO_TARGET_DIR:-$root/target}
  mkdir -p "$target"
  target=$(cd "$target" && pwd)
  data=${TOPOPLEX_BENCH_DATA:-$target/bench-data}$1
  results=${results:-$target/bench-results/$2$(date -u +%Y%m%dT%H%M%SZ)}
  mkdir -p "$data" "$results"
  data=$(cd "$data" && pwd)
  results=$(cd "$results" && pwd)
}
