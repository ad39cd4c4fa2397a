#!/usr/bin/env bash
# The Python package's benchmarks (scripts/bench_py.py: build from a 10^7-triangle array against
# the Rust call, every vertex's star against GUDHI's get_star, face adjacency against trimesh,
# two threads against one, import time, wheel size), on release builds of both sides:
#   1. the venv of scripts/py-tests.sh (target/py-venv; made, and the test dependencies
#      installed, when missing);
#   2. `maturin develop --release` of crates/topoplex-py into it, and
#      `cargo build --release --example grid_build` (the Rust side of the build benchmark);
#   3. scripts/bench_py.py --wheel, its Markdown into OUT (default <target>/bench-results/python.md).
# Compiles run under `nice -n 10`, the benchmarks do not (take numbers to publish on a quiet
# machine). Extra arguments go to bench_py.py (e.g. --quick, --only stars,adjacency,
# --data DIR; default data: $TOPOPLEX_BENCH_DATA, else /work/bench-data).
#
# usage: scripts/bench_py.sh [OUT.md] [bench_py.py arguments...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
target=${CARGO_TARGET_DIR:-$root/target}
mkdir -p "$target"
target=$(cd "$target" && pwd)
out=$target/bench-results/python.md
if [ $# -gt 0 ] && [[ "$1" != -* ]]; then out=$1; shift; fi
mkdir -p "$(dirname "$out")"
venv=$target/py-venv
[ -x "$venv/bin/python3" ] || python3 -m venv "$venv"
py=$venv/bin/python3
"$py" -c "import maturin, numpy, gudhi, trimesh, scipy" 2>/dev/null ||
  "$py" -m pip install --quiet --disable-pip-version-check \
    'maturin>=1.9.4,<2' numpy pytest hypothesis gudhi meshio trimesh scipy
echo "== maturin develop --release (crates/topoplex-py), cargo build --release --example grid_build"
VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" nice -n 10 \
  maturin develop --release -m "$root/crates/topoplex-py/Cargo.toml" >"$venv/maturin-release.log" 2>&1 ||
  { cat "$venv/maturin-release.log"; exit 1; }
(cd "$root" && nice -n 10 cargo build --release --example grid_build)
echo "== scripts/bench_py.py"
PATH="$venv/bin:$PATH" "$py" "$root/scripts/bench_py.py" --wheel \
  --rust-bin "$target/release/examples/grid_build" \
  --data "${TOPOPLEX_BENCH_DATA:-/work/bench-data}" --out "$out" "$@"
echo "results: $out"
