#!/usr/bin/env bash
# Every structure's `topoplex relation` dump equals the IG's, line by line, for every P,Q on
# every file of a data folder (default ../shared/data). Structures that refuse a file are listed
# with their reason. The test suite does the same on moderate files (tests/it/cli.rs); this is the
# full run over all of the real data.
#   usage: scripts/compare-cli.sh [DATA_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
data=${1:-$root/../shared/data}
cargo build --release --quiet --manifest-path "$root/Cargo.toml" --bin topoplex
bin=$root/target/release/topoplex
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
for f in "$data"/*/*; do
  d=$("$bin" report "$f" --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["dimension"])' 2>/dev/null) || {
    echo "skip $(basename "$f"): $("$bin" report "$f" 2>&1 | head -1)"; continue; }
  checked=()
  for s in sig ia iqm nmia ts pe le de; do
    if ! "$bin" relation "$f" --structure "$s" --relation 0,0 --simplex 0 >/dev/null 2>"$work/err"; then
      continue
    fi
    for p in $(seq 0 "$d"); do
      for q in $(seq 0 "$d"); do
        [ -f "$work/ig-$p-$q" ] || "$bin" relation "$f" --structure ig --relation "$p,$q" >"$work/ig-$p-$q"
        "$bin" relation "$f" --structure "$s" --relation "$p,$q" >"$work/out"
        if ! cmp -s "$work/ig-$p-$q" "$work/out"; then
          echo "DIFFERS: $(basename "$f") $s R_{$p,$q}"; fail=1
        fi
      done
    done
    checked+=("$s")
  done
  rm -f "$work"/ig-*
  echo "$(basename "$f") (dimension $d): equal to ig for every P,Q: ${checked[*]:-none}"
done
exit $fail
