#!/usr/bin/env bash
# The Python package's tests (crates/topoplex-py): a venv of the suite's own under the target
# directory (never the user's Python), the test dependencies from PyPI when missing, the
# extension built with `maturin develop` in the `ci` profile into the workspace's target
# directory (so the core library compiled by `cargo build --profile ci --workspace` is reused:
# only pyo3 and the binding recompile, for maturin's PYO3_BUILD_EXTENSION_MODULE), then pytest
# over the tests and the docstring examples of the package and of the README's Python section,
# and mypy over the package: every function annotated, every body checked against its annotations.
set -euo pipefail
cd "$(dirname "$0")/.."
target=${CARGO_TARGET_DIR:-target}
mkdir -p "$target"
venv=$(cd "$target" && pwd)/py-venv
# Without a venv or PyPI (as tests/it/interop.rs does without meshio) the stage says so loudly and
# is skipped; a build or test failure fails it.
skip() { echo "PYTHON TESTS NOT RUN: $*"; exit 0; }
if [ ! -x "$venv/bin/python3" ]; then
  python3 -m venv "$venv" || skip "python3 -m venv failed (install python3-venv)"
fi
py="$venv/bin/python3"
if ! "$py" -c "import maturin, numpy, pytest, hypothesis, gudhi, meshio, trimesh, scipy, mypy" 2>/dev/null; then
  "$py" -m pip install --quiet --disable-pip-version-check \
    'maturin>=1.9.4,<2' numpy pytest hypothesis gudhi meshio trimesh scipy 'mypy>=1.18' ||
    skip "the test dependencies could not be installed from PyPI"
fi
# maturin's and pip's chatter goes to a log, shown only when the build fails.
log="$venv/maturin.log"
if ! VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" \
  maturin develop --profile ci -m crates/topoplex-py/Cargo.toml >"$log" 2>&1; then
  cat "$log"
  exit 1
fi
cd crates/topoplex-py
# -p no:cacheprovider: no .pytest_cache in the source tree.
"$py" -m pytest -q -p no:cacheprovider --doctest-modules python/topoplex tests
"$py" -m doctest ../../README.md && echo "README Python examples: passed"
# The package's annotations are its only type declarations (no stubs beside them): mypy checks
# each body against them under pyproject.toml's [tool.mypy] (the extension module and the
# optional peers have no type information). Run from the venv, where mypy leaves its cache,
# not in the source tree.
config=$(pwd)/pyproject.toml
(cd "$venv" && "$py" -m mypy --config-file "$config" -p topoplex)
