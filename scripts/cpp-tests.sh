#!/usr/bin/env bash
# C/C++ tests of the installed package:
#   1. configure, build (one `cargo build -p topoplex-ffi --lib`, profile $TOPOPLEX_CARGO_PROFILE,
#      default release; none with TOPOPLEX_CARGO_PREBUILT=ON) and install Topoplex
#      into PREFIX_DIR
#      (default: a temporary directory), and check the installed SONAME;
#   2. configure, build and ctest cpp_tests/ against that prefix (the peer cross-checks left to
#      step 3);
#   3. the same with TOPOPLEX_SANITIZE=ON (ASan + UBSan, LeakSanitizer on) and the peer
#      cross-checks (CGAL, GUDHI, OpenMesh), built while the tests
#      of step 2 and valgrind run.
# When PETSc and MPI are installed, step 1 also installs the DMPlex bridge and step 2 runs its MPI
# tests (cpp_tests/dmplex, mpiexec -n 1, 2, 4); step 3 leaves them out (MPI under ASan is noise).
# Needs cmake, ninja-build, libgtest-dev, pkg-config and a C/C++ compiler (Debian packages:
# installed below when missing, so that the script also runs alone; scripts/test.sh installs
# them and the optional peers first).
# Cargo's target dir is $CARGO_TARGET_DIR or the repository's target/, so dependencies built by
# other cargo runs are reused.
#
# usage: scripts/cpp-tests.sh [PREFIX_DIR]
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh" cmake ninja-build pkg-config libgtest-dev g++
work=$(mktemp -d "${TMPDIR:-/tmp}/topoplex-cpp-tests.XXXXXX")
prefix=${1:-$work/prefix}
mkdir -p "$prefix"
prefix=$(cd "$prefix" && pwd)
cleanup() { rm -rf "$work"; }
trap cleanup EXIT

echo "== build and install Topoplex into $prefix [${SECONDS}s]"
cmake -S "$root" -B "$work/build" -G Ninja \
  -DTOPOPLEX_CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}" \
  -DTOPOPLEX_CARGO_PROFILE="${TOPOPLEX_CARGO_PROFILE:-release}" \
  -DTOPOPLEX_CARGO_PREBUILT="${TOPOPLEX_CARGO_PREBUILT:-OFF}"
cmake --build "$work/build"
cmake --install "$work/build" --prefix "$prefix"

soname=$(readelf -d "$prefix/lib/libtopoplex.so" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p')
if [[ "$soname" != libtopoplex.so.* ]]; then
  echo "installed libtopoplex.so has SONAME '$soname', expected libtopoplex.so.N" >&2
  exit 1
fi
echo "SONAME $soname"

# LeakSanitizer on; UBSan reports stop the test. Set here too (not only per test in CMake) for
# tests that gtest_discover_tests registers in cpp_tests/peers.
export ASAN_OPTIONS=detect_leaks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# Both configurations are configured first. The uninstrumented tests and valgrind (one process
# at a time, one core) run while the instrumented configuration builds on the others: the two
# share nothing but the installed prefix, which neither writes. Each check runs as before; only
# the order of the log changes (the uninstrumented pass's log is printed once it is done).
# The peer cross-checks (cpp_tests/peers, decompose: answers against CGAL, GUDHI and OpenMesh)
# are built and run in the uninstrumented pass, the adapters' tests (cpp_tests/adapters: the
# installed headers include/topoplex/*.hpp on CGAL, OpenMesh and GUDHI) in the sanitizer pass:
# each group's CGAL-heavy sources are compiled once. The peers compare answers; what they call of
# Topoplex's C and C++ API is also run under the sanitizers by cpp_wrapper and c_api. Under ASan
# and UBSan the peers took about 290 CPU-seconds to compile and 190 to run, against about 100 and
# 35 uninstrumented (2026-12-03, this machine). Everything else is built in both passes. The
# benchmark programs (uninstrumented pass only) run once each as smoke tests: built with -O0,
# which shortens their compilation; scripts/bench.sh builds them with -O2 for timing.
for sanitize in OFF ON; do
  peers=OFF adapters=ON
  [ "$sanitize" = ON ] || { peers=ON; adapters=OFF; }
  cmake -S "$root/cpp_tests" -B "$work/tests-$sanitize" -G Ninja \
    -DCMAKE_PREFIX_PATH="$prefix" -DTOPOPLEX_SANITIZE="$sanitize" -DTOPOPLEX_PEERS="$peers" \
    -DTOPOPLEX_ADAPTERS="$adapters" \
    -DTOPOPLEX_BENCH_OPT=-O0
done

echo "== cpp_tests (TOPOPLEX_SANITIZE=OFF): build [${SECONDS}s]"
cmake --build "$work/tests-OFF"

uninstrumented_checks() {
  local build="$work/tests-OFF"
  echo "== cpp_tests (TOPOPLEX_SANITIZE=OFF): ctest [${SECONDS}s]"
  ctest --test-dir "$build" --output-on-failure || return 1
  # valgrind memcheck on the uninstrumented build: zero errors, zero definite/indirect leaks.
  # In a directory of its own: test_c_api writes its files into the working directory.
  echo "== valgrind memcheck [${SECONDS}s]"
  mkdir -p "$work/valgrind"
  for t in c_api/test_c_api_shared c_api/test_threads; do
    (cd "$work/valgrind" && valgrind -q --error-exitcode=1 --leak-check=full \
      --errors-for-leak-kinds=definite,indirect "$build/$t") >"$work/valgrind.log" 2>&1 ||
      { cat "$work/valgrind.log"; echo "valgrind: $t failed" >&2; return 1; }
    echo "valgrind: $t clean"
  done
}
uninstrumented_checks >"$work/uninstrumented.log" 2>&1 &
checks=$!

echo "== cpp_tests (TOPOPLEX_SANITIZE=ON): build, then ctest (the uninstrumented tests run meanwhile) [${SECONDS}s]"
built=0
cmake --build "$work/tests-ON" || built=$?
# The instrumented tests start as soon as their build is done, beside whatever is left of the
# uninstrumented ones (one at a time; the two take about as long, 200-230 s here): one test per
# core (outputs have distinct names; fixtures order the tests that read another's output). Their
# log is printed after the uninstrumented pass's.
sanitized=0
if [ "$built" = 0 ]; then
  echo "== cpp_tests (TOPOPLEX_SANITIZE=ON): ctest [${SECONDS}s]" >"$work/sanitized.log"
  ctest --test-dir "$work/tests-ON" --output-on-failure -j "$(nproc)" >>"$work/sanitized.log" 2>&1 ||
    sanitized=$?
fi
passed=0
wait "$checks" || passed=$?
cat "$work/uninstrumented.log"
if [ "$passed" != 0 ]; then
  echo "cpp_tests (TOPOPLEX_SANITIZE=OFF) or valgrind failed" >&2
  exit 1
fi
[ "$built" = 0 ] || exit "$built"
cat "$work/sanitized.log"
echo "== cpp_tests done [${SECONDS}s]"
[ "$sanitized" = 0 ] || { echo "cpp_tests (TOPOPLEX_SANITIZE=ON) failed" >&2; exit "$sanitized"; }
