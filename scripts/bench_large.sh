#!/usr/bin/env bash
# The large benchmark of issue 17 (`scripts/bench.sh --large`): generated datasets of ~10^7
# (and, with --huge, ~10^8) simplices, each timed phase by phase by examples/scale.rs in its own
# process: parse, complex normalisation, build with 1 and with 2 threads, save (.tpx), open +
# one query, 10^5 vertex-star walks on the opened structure, with the process's peak memory
# after each phase. Datasets are generated into $TOPOPLEX_BENCH_DATA (default
# <target dir>/bench-data/large) and never committed; results go to RESULTS_DIR/large.tsv.
#
# usage: scripts/bench_large.sh [--huge] [RESULTS_DIR]
set -euo pipefail

. "$(dirname "$0")/bench_common.sh"
huge=0
bench_option() {
  case "$1" in
    --large) ;;
    --huge) huge=1 ;;
    *) return 1 ;;
  esac
}
bench_args 10 "$@"
bench_dirs /large large-

nice -n 10 cargo build --release --example scale --manifest-path "$root/Cargo.toml"
scale=$target/release/examples/scale

# name, generator arguments, file, structures
datasets=(
  "grid-73|grid 73|grid-73.mesh|ia sig"
  "loop-9|loop 9|loop-9.off|ia sig"
  "rips-200k|rips 200000 3|rips-200k.simplices|sig"
)
if [ "$huge" = 1 ]; then
  datasets=("grid-156|grid 156|grid-156.mesh|ia")
fi

{
  echo "date: $(date -u +'%Y-%m-%d %H:%M UTC')"
  echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  echo "cpu: $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1) ($(nproc) cores)"
  echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
} | tee "$results/machine.txt"

out=$results/large.tsv
printf 'dataset\tstructure\tthreads\tphase\tseconds\tpeak_mib\n' > "$out"
for entry in "${datasets[@]}"; do
  IFS='|' read -r name gen file kinds <<< "$entry"
  if [ ! -s "$data/$file" ]; then
    echo "== generating $name"
    # shellcheck disable=SC2086
    nice -n 10 "$scale" $gen "$data/$file"
  fi
  for kind in $kinds; do
    for threads in 1 2; do
      echo "== $name $kind threads=$threads"
      "$scale" phases "$data/$file" "$kind" "$threads" "$data/$name-$kind.tpx" |
        while read -r phase secs peak rest; do
          printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$kind" "$threads" "$phase" "$secs" "$peak" | tee -a "$out"
        done
    done
    rm -f "$data/$name-$kind.tpx"
  done
done
echo "results: $out"
