#!/usr/bin/env bash
# Short differential fuzzing run of every target (default 10 s each). Long runs:
#   cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz run -O <target> corpus/<target> -- -max_len=65536
# The committed seed corpus is copied first so a smoke run never rewrites it.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
secs=${1:-10}
export RUSTC_BOOTSTRAP=1  # cargo fuzz needs nightly flags; the machine has one stable toolchain
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked --version 0.13.2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for t in $(cargo fuzz list); do
  mkdir -p "$work/$t"
  cp -r corpus/"$t"/. "$work/$t"/
  echo "== fuzz $t (${secs}s)"
  if ! cargo fuzz run -O "$t" "$work/$t" -- -max_total_time="$secs" -rss_limit_mb=2048 -max_len=8192 >"$work/$t.log" 2>&1; then
    tail -40 "$work/$t.log"
    echo "fuzz target $t failed (reproducer under fuzz/artifacts/$t)"
    exit 1
  fi
  grep -E "^Done" "$work/$t.log" || true
done
