#!/usr/bin/env bash
# Short differential fuzzing run of every fuzz target (default 5 s each), as part of the test
# script. It builds the targets with the same coverage instrumentation `cargo fuzz` uses (plus
# debug assertions and overflow checks), but with plain `cargo build`, so CI does not have to
# install cargo-fuzz. Long runs, with AddressSanitizer:
#   cargo install cargo-fuzz --locked
#   cd fuzz && RUSTC_BOOTSTRAP=1 cargo fuzz run -O <target> corpus/<target> -- -max_len=65536
# The committed seed corpus is copied first so a smoke run never rewrites it.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
secs=${1:-5}
target=$(rustc -vV | sed -n 's/^host: //p')
export CARGO_TARGET_DIR=${FUZZ_TARGET_DIR:-$PWD/target}
# --target keeps the instrumentation out of build scripts, as cargo fuzz does. Unoptimised
# (FUZZ_OPT_LEVEL, default 0): a smoke run replays the committed corpus and then fuzzes a few
# seconds, which needs coverage, not speed. Measured 2026-12-03 on two cores, 3 s a target: level
# 0 builds in 95 s (190 CPU-seconds), level 1 in 253 s (510), and level 1 runs 10-20x more inputs
# in the same seconds (FUZZ_OPT_LEVEL=1 for a smoke run that explores more; long runs: cargo fuzz
# run -O, above).
CARGO_PROFILE_RELEASE_OPT_LEVEL=${FUZZ_OPT_LEVEL:-0} \
RUSTFLAGS="-Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 \
-Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table \
-Cllvm-args=-sanitizer-coverage-trace-compares --cfg fuzzing -Cdebug-assertions -Coverflow-checks" \
  cargo build --release --locked --target "$target" --bins
echo "== fuzz targets built, ${SECONDS}s after the smoke run started"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Each target is one single-threaded process: FUZZ_JOBS (default: the number of cores) run at once.
jobs=${FUZZ_JOBS:-$(nproc)}
run() {
  local t=$1
  # TMPDIR: the CLI target writes its fixtures and outputs in a scratch directory under it.
  if TMPDIR="$work/tmp-$t" "$CARGO_TARGET_DIR/$target/release/$t" "$work/$t" -max_total_time="$secs" \
      -rss_limit_mb=2048 -max_len=8192 -artifact_prefix=artifacts/"$t"/ >"$work/$t.log" 2>&1; then
    echo ok >"$work/$t.status"
  fi
}
targets=()
for src in fuzz_targets/*.rs; do
  t=$(basename "$src" .rs)
  targets+=("$t")
  mkdir -p "$work/$t" "$work/tmp-$t" artifacts/"$t"
  cp -r corpus/"$t"/. "$work/$t"/
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run "$t" &
done
wait
echo "== every target run, ${SECONDS}s after the smoke run started"
for t in "${targets[@]}"; do
  echo "== fuzz $t (${secs}s)"
  if [ ! -f "$work/$t.status" ]; then
    tail -40 "$work/$t.log"
    echo "fuzz target $t failed (reproducer under fuzz/artifacts/$t)"
    exit 1
  fi
  grep -E "^Done" "$work/$t.log" || true
done
