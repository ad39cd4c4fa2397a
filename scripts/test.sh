#!/usr/bin/env bash
# The whole test suite, as CI runs it (.ci/run calls exactly this). Installs what it needs on a
# fresh Debian machine (while the Rust workspace builds), then: lint gates (fmt, clippy, rustdoc,
# missing_docs), Rust tests (unit, property, real data when ../shared/data exists), Miri and the
# fuzz smoke, CLI smoke checks, the Python package, the CMake package install and the C/C++
# cross-checks (plain and under AddressSanitizer + UndefinedBehaviorSanitizer).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage says when it starts, so a slow stage shows in the log (CI has 30 minutes for all).
stage() { echo "== $* [${SECONDS}s]"; }

# The Python extension is built as an extension module in every cargo build below (no libpython
# linked, as maturin builds it), so the Python stage imports the cdylib of the workspace build
# instead of compiling the core again (scripts/py-tests.sh says why that compile would differ).
export PYO3_BUILD_EXTENSION_MODULE=1

# What the suite installs comes from the network and dpkg, mostly waiting: it runs while the lint
# gates and the workspace build below use the cores, and its log is printed before the first
# stage that needs it (the tests). Nothing of it is needed to build the Rust workspace.
install_all() {
  scripts/install-deps.sh cmake ninja-build pkg-config valgrind libopenmesh-dev libcgal-dev \
    libgudhi-dev libgtest-dev libcgal-demo libbenchmark-dev
  # PETSc 3.18 + OpenMPI for the optional DMPlex bridge (Topoplex::dmplex) and its MPI tests
  # (cpp_tests/dmplex, run by scripts/cpp-tests.sh in the uninstrumented pass).
  scripts/install-deps.sh libpetsc-real-dev openmpi-bin
  # Python meshio and gmsh: meshio is the independent reader and writer of tests/it/interop.rs;
  # gmsh (the PyPI wheel: Gmsh's own Python API) meshes the labelled geometry of
  # tests/it/gmsh_real.rs. Each test is skipped without its module. Never installed into the
  # user's Python: when the system's python3 lacks one, they go into a venv of the suite's own
  # under the target directory, put first on PATH for the tests. The gmsh wheel links X11 and
  # OpenGL libraries even when nothing is displayed: those Debian packages first.
  scripts/install-deps.sh libglu1-mesa libgl1 libopengl0 libxcursor1 libxft2 libxinerama1 \
    libxrender1 libfontconfig1 libgomp1
  if [ -n "$test_venv_used" ]; then
    for module in meshio gmsh; do
      "$test_venv/bin/python3" -c "import $module" 2>/dev/null ||
        "$test_venv/bin/python3" -m pip install --quiet "$module" ||
        echo "$module not installed: the tests that use it will skip their checks"
    done
  fi
  # The Python stage's own venv and test dependencies (scripts/py-tests.sh).
  scripts/py-tests.sh --deps
}
test_venv=${CARGO_TARGET_DIR:-target}/test-venv
mkdir -p "${CARGO_TARGET_DIR:-target}"
# The venv is made and put first on PATH now, before any cargo build: PyO3's build script finds
# its Python on PATH and reruns when PATH changes, so a PATH changed between the workspace build
# and the tests would rebuild PyO3 and the extension.
test_venv_used=
if ! python3 -c "import meshio, gmsh" 2>/dev/null; then
  if [ -x "$test_venv/bin/python3" ] || python3 -m venv "$test_venv"; then
    test_venv_used=1
    PATH="$(cd "$test_venv/bin" && pwd):$PATH"
    export PATH
  else
    echo "no venv for meshio and gmsh: the tests use python3 as it is (skipping what it lacks)"
  fi
fi
install_log=$(mktemp "${TMPDIR:-/tmp}/topoplex-install.XXXXXX")
install_all >"$install_log" 2>&1 &
installing=$!

stage "lint gates: formatting, clippy, docs (missing_docs is denied on the public API; the installs run meanwhile)"
# Each crate's lib.rs has #![warn(missing_docs)]; -D warnings turns it (and every clippy lint)
# into an error here, as rustls-ffi's and petgraph's CI do.
cargo fmt --all --check
cargo clippy --workspace --all-targets -- -D warnings
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --workspace

stage "cargo test (the workspace: core, C ABI, CLI; unit, property, layering, real data)"
# The C library first: the C ABI crate's header test holds libtopoplex_ffi.so's exported symbols
# to include/topoplex.h (cargo test links the tests against the rlib only).
# Every target but the criterion benches (clippy above checks them; built optimised they only
# cost time), in one build: the stages below take its binary and C library as they are. The
# test targets are in this build, not only in `cargo test`'s, because the dev-dependencies
# change the features of shared dependencies (serde, rayon, syn): a build without them and a
# test build after it compiled the core, the CLI and a dozen dependencies twice (about 3 of the
# stage's 16 minutes on two slow cores). A build of one package would differ again (the Python
# binding's macros turn on more of syn).
cargo build --profile ci --workspace --lib --bins --tests --examples
installed=0
wait "$installing" || installed=$?
stage "installs (Debian packages, Python venvs), run during the stages above"
cat "$install_log"
rm -f "$install_log"
[ "$installed" = 0 ] || { echo "installing the suite's dependencies failed (status $installed)" >&2; exit "$installed"; }
# The root package's integration tests are one binary (tests/it/, one link of the core) plus the
# few that need a process of their own (tests/*.rs: global allocator, RLIMIT_AS, RSS, thread count).
# Not --examples: they hold no tests, and in test mode they would compile a second time.
cargo test --profile ci --workspace --lib --bins --tests
cargo test --profile ci --workspace --doc

stage "Miri on the FFI layer's unit tests, the fuzz smoke beside it"
# Miri interprets the tests on one thread, so the fuzz smoke (its instrumented build, then a few
# seconds of every target) runs meanwhile on the other core; its log is printed after Miri's.
# Together about a minute and a half sooner than one after the other on two cores.
miri() {
  # Needs the nightly toolchain's miri component; rustup fetches it when it can.
  if rustup toolchain list 2>/dev/null | grep -q nightly &&
     { rustup component list --toolchain nightly --installed 2>/dev/null | grep -q '^miri' ||
       rustup component add miri rust-src --toolchain nightly >/dev/null 2>&1; }; then
    # Miri interprets a test thousands of times slower than it runs, so its time goes to
    # running, not building (about a minute). It runs the tests that go through the C ABI's
    # unsafe code (ownership helpers, every pointer-taking export, threads); two are left to the
    # plain run of the same tests above, where they still run, because they repeat code the
    # others already take through Miri: the relation sweep (every simplex, every q, two kinds;
    # alone about half of Miri's time) calls the same tpx_relation as lifecycle_*,
    # simplices_in_* and kinds_and_query_errors_*, on structures built and freed as in those,
    # and the row sort (sort_rows_in_place) is safe code.
    cargo +nightly miri test -p topoplex-ffi --lib -- \
      --skip tests::relation_matches_the_rust_api_for_every_simplex_and_q \
      --skip tests::answers_are_sorted_in_place_for_every_arity
  else
    echo "MIRI NOT RUN: no nightly toolchain with the miri component on this machine"
  fi
}
fuzz_log=$(mktemp "${TMPDIR:-/tmp}/topoplex-fuzz-smoke.XXXXXX")
scripts/fuzz-smoke.sh 3 >"$fuzz_log" 2>&1 &
fuzz=$!
miri_status=0
miri || miri_status=$?
echo "Miri done [${SECONDS}s]"
fuzz_status=0
wait "$fuzz" || fuzz_status=$?
stage "fuzz smoke (differential: readers, every structure vs the oracle, altered saved files)"
cat "$fuzz_log"
rm -f "$fuzz_log"
if [ "$miri_status" != 0 ]; then
  echo "Miri failed (status $miri_status)" >&2
  exit "$miri_status"
fi
if [ "$fuzz_status" != 0 ]; then
  echo "fuzz smoke failed (status $fuzz_status)" >&2
  exit "$fuzz_status"
fi

stage "CLI smoke"
# The binary `cargo build --profile ci --workspace` made above.
cli=${CARGO_TARGET_DIR:-target}/ci/topoplex
"$cli" report >/dev/null
"$cli" report --json | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["dimension"] == 3 and "ig" in d["structures"]'

stage "Python"
# The package `topoplex` (crates/topoplex-py): its venv under the target directory, the extension
# module the workspace build made, pytest + hypothesis against the oracle and GUDHI,
# meshio/trimesh/scipy round trips.
TOPOPLEX_PY_PREBUILT=${CARGO_TARGET_DIR:-target}/ci/lib_core.so scripts/py-tests.sh

if [ -x scripts/cpp-tests.sh ]; then
  stage "C/C++ package and cross-checks"
  # The C library `cargo build --profile ci --workspace` made above, as it is.
  TOPOPLEX_CARGO_PROFILE=ci TOPOPLEX_CARGO_PREBUILT=ON scripts/cpp-tests.sh
fi
stage "all tests passed"
