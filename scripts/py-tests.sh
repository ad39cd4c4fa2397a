#!/usr/bin/env bash
# The Python package's tests (crates/topoplex-py): a venv of the suite's own under the target
# directory (never the user's Python), the test dependencies from PyPI when missing, the
# extension module installed in development mode (the package's sources on the venv's path, the
# module beside them, as `maturin develop` does), then pytest over the tests and the docstring
# examples of the package and of the README's Python section, and mypy over the package: every
# function annotated, every body checked against its annotations.
#
# The module is built with `maturin develop --profile ci` into the workspace's target directory,
# or, when TOPOPLEX_PY_PREBUILT names one, taken as built: scripts/test.sh passes the cdylib of
# its `cargo build --profile ci --workspace`, built with PYO3_BUILD_EXTENSION_MODULE=1 as maturin
# builds it. maturin builds one package, so cargo unifies the dependencies' features differently
# from the workspace build (the test targets' dev-dependencies turn on more of serde, syn and
# either) and compiles the core and a dozen dependencies a second time: two of CI's minutes.
#
# usage: scripts/py-tests.sh            build (or take TOPOPLEX_PY_PREBUILT), install, test
#        scripts/py-tests.sh --deps     only the venv and the test dependencies
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
[ "${1:-}" = --deps ] && exit 0
package=crates/topoplex-py/python
if [ -n "${TOPOPLEX_PY_PREBUILT:-}" ]; then
  # What `maturin develop` leaves for a package with python-source (pyproject.toml): the module
  # beside the package's sources (ignored by git), and the sources' directory on the venv's path.
  cp "$TOPOPLEX_PY_PREBUILT" "$package/topoplex/_core.abi3.so"
  site=$("$py" -c 'import sysconfig; print(sysconfig.get_path("purelib"))')
  (cd "$package" && pwd) >"$site/topoplex.pth"
  echo "extension module: $TOPOPLEX_PY_PREBUILT (prebuilt)"
else
  # maturin's and pip's chatter goes to a log, shown only when the build fails.
  log="$venv/maturin.log"
  if ! VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" \
    maturin develop --profile ci -m crates/topoplex-py/Cargo.toml >"$log" 2>&1; then
    cat "$log"
    exit 1
  fi
fi
# Whichever way it came, the module must be an extension module: no libpython of its own (the
# manylinux rule, and a second interpreter's symbols in the process otherwise).
if readelf -d "$package/topoplex/_core.abi3.so" 2>/dev/null | grep -q 'NEEDED.*libpython'; then
  echo "$package/topoplex/_core.abi3.so links libpython: build it with PYO3_BUILD_EXTENSION_MODULE=1" >&2
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
