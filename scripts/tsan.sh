#!/usr/bin/env bash
# ThreadSanitizer over the concurrency test: every structure queried from 8 threads at once on
# fixtures and (when present) real data, with the standard library rebuilt under TSan so that
# every access is instrumented. Needs the nightly toolchain with rust-src
# (`rustup component add rust-src --toolchain nightly`). Not part of scripts/test.sh: the
# instrumented rebuild of std and all dependencies takes about 3 minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
host=$(rustc -vV | sed -n 's/^host: //p')
RUSTFLAGS="-Zsanitizer=thread" CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-target}/tsan \
  cargo +nightly test -Zbuild-std --target "$host" --profile ci --test it structures::eight_threads
