#!/usr/bin/env bash
# Topoplex side by side with OpenMesh, CGAL and GUDHI, in one run (issue 9 part 2):
#   1. build and install Topoplex (release) into a prefix, as scripts/cpp-tests.sh does;
#   2. build the dataset maker (cpp_tests/bench_data) and make the datasets, cached in
#      $TOPOPLEX_BENCH_DATA (default: <target dir>/bench-data; existing files are reused);
#   3. build the Google Benchmark programs (cpp_tests/bench) against the prefix and run
#      topoplex_bench_surface and topoplex_bench_simplify (issue 14: quadric simplification to
#      1%) on surf-*.off, topoplex_bench_tets on tet-*.mesh, topoplex_bench_contract (issue 14:
#      link-checked contractions per second next to OpenMesh's collapses) on the 300×300
#      triangle grid and topoplex_bench_gudhi on every dataset, JSON into the results directory;
#      the application of issue 25 on OpenMesh and on the mesh (scripts/bench_app.py, app.md);
#      then peak RSS and time of whole simplify processes (simplify_rss.tsv, simplify_cli.tsv);
#   4. `cargo bench --bench structures` (criterion, Rust API), if that bench exists, and its
#      tables (benches/structures_table.py) into RESULTS/criterion.md; then `cargo bench --bench
#      live` (the live complex: link-checked contractions per second, storage vs the IA) into
#      RESULTS/live.log;
#   5. the Python package beside the Rust call, GUDHI and trimesh (scripts/bench_py.sh, its
#      table into RESULTS/python.md);
#   6. scripts/bench_table.py: one Markdown table of Topoplex / peer ratios and the aims of
#      issue 9 part 3, and the simplification table of issue 14, printed and written to
#      RESULTS/table.md.
#
# usage: scripts/bench.sh [--quick] [RESULTS_DIR]
#        scripts/bench.sh --large [--huge] [RESULTS_DIR]
#   --quick      only the ~10^4 and ~10^5 datasets, short minimum times (a smoke run)
#   --large      instead, the generated 10^7-simplex datasets of issue 17 (scripts/bench_large.sh:
#                parse, build with 1 and 2 threads, save, open, walks, peak memory); with
#                --huge, the 10^8-simplex tetrahedral grid
#   RESULTS_DIR  default <target dir>/bench-results/<UTC date-time>
# Environment: TOPOPLEX_BENCH_DATA (datasets), TOPOPLEX_BENCH_KINDS (ia,ts,...: restrict the
# Topoplex kinds; iastar, the live complex, is a kind of topoplex_bench_gudhi only),
# TOPOPLEX_BENCH_COFACES_STRIDE (topoplex_bench_gudhi's cofaces walks every k-th vertex and
# edge, for every library), TOPOPLEX_BENCH_MIN_TIME (seconds per benchmark; default Google Benchmark's
# own, 0.05 with --quick), TOPOPLEX_BENCH_GUDHI_COFACES_MAX (GUDHI cofaces only on datasets up
# to this many top simplices, default 25000: see run() below), TOPOPLEX_BENCH_SIMPLIFY_RATIO
# (fraction of the triangles topoplex_bench_simplify keeps, default 0.01), CARGO_TARGET_DIR.
# Installs, when missing (Debian): cmake ninja-build g++ libgtest-dev libbenchmark-dev
# libopenmesh-dev libcgal-dev libcgal-demo libgudhi-dev libboost-dev libeigen3-dev python3;
# needs cargo. Compiles and dataset
# generation run under `nice -n 10`; the benchmarks themselves do not (take final numbers on a
# quiet machine).
set -euo pipefail

case " $* " in
  *" --large "*) exec "$(dirname "$0")/bench_large.sh" "$@" ;;
esac
. "$(dirname "$0")/bench_common.sh"
quick=0
bench_option() {
  case "$1" in
    --quick) quick=1 ;;
    *) return 1 ;;
  esac
}
bench_args 30 "$@"
bench_dirs "" ""
# Build directories and the install prefix live in the target dir so that a second run
# recompiles nothing that did not change (the CGAL/GUDHI programs take minutes to compile).
prefix=$target/bench-prefix
build=$target/bench-cmake
min_time=${TOPOPLEX_BENCH_MIN_TIME:-}
if [ "$quick" = 1 ] && [ -z "$min_time" ]; then min_time=0.05; fi
failed=()

"$root/scripts/install-deps.sh" cmake ninja-build g++ libgtest-dev libbenchmark-dev \
  libopenmesh-dev libcgal-dev libcgal-demo libgudhi-dev libboost-dev libeigen3-dev python3

echo "== machine"
{
  echo "date: $(date -u +'%Y-%m-%d %H:%M UTC')"
  echo "commit: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$root" diff --quiet 2>/dev/null || echo ' (dirty)')"
  echo "cpu: $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1) ($(nproc) cores)"
  echo "memory: $(awk '/MemTotal/ {printf "%.1f GiB", $2 / 1048576}' /proc/meminfo)"
  echo "compilers: $(rustc --version), $(c++ --version | head -1)"
  echo "command: scripts/bench.sh $*"
} | tee "$results/machine.txt"

echo "== build and install Topoplex (release) into $prefix"
nice -n 10 cmake -S "$root" -B "$build/topoplex" -G Ninja \
  -DTOPOPLEX_CARGO_TARGET_DIR="$target" >/dev/null
nice -n 10 cmake --build "$build/topoplex"
cmake --install "$build/topoplex" --prefix "$prefix" >/dev/null

echo "== datasets into $data"
nice -n 10 cmake -S "$root/cpp_tests/bench_data" -B "$build/bench_data" -G Ninja \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
nice -n 10 cmake --build "$build/bench_data"
maker_args=()
if [ "$quick" = 1 ]; then maker_args+=(--quick); fi
nice -n 10 "$build/bench_data/topoplex_bench_data" "${maker_args[@]}" "$data" \
  || failed+=("dataset maker (some datasets missing)")
cp "$data/datasets.tsv" "$results/" 2>/dev/null || true

echo "== build the benchmark programs (cpp_tests/bench) against $prefix"
programs=(topoplex_bench_surface topoplex_bench_tets topoplex_bench_gudhi topoplex_bench_simplify
          topoplex_bench_contract topoplex_bench_app)
if [ ! -f "$root/cpp_tests/bench/CMakeLists.txt" ]; then
  echo "cpp_tests/bench is missing: no side-by-side runs" >&2
  failed+=("cpp_tests/bench missing")
  bench_bin=""
else
  # cpp_tests/bench is a subdirectory of cpp_tests (it uses the parent's Topoplex package and
  # CGAL sample data); configure the parent and build only the three programs.
  nice -n 10 cmake -S "$root/cpp_tests" -B "$build/cpp_tests" -G Ninja \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release -DTOPOPLEX_SANITIZE=OFF \
    -DTOPOPLEX_BENCH_OPT=-O2 >/dev/null
  built=()
  for p in "${programs[@]}"; do
    if nice -n 10 cmake --build "$build/cpp_tests" --target "$p"; then
      built+=("$p")
    else
      failed+=("$p did not build")
    fi
  done
  bench_bin=$build/cpp_tests/bench
fi

# Quick runs stay below ~5*10^5 top simplices (the number at the end of each file name).
datasets() {
  local f n
  for f in "$data"/$1; do
    [ -e "$f" ] || continue
    n=${f##*-}
    n=${n%%.*}
    if [ "$quick" = 1 ] && [ "$n" -ge 500000 ]; then continue; fi
    echo "$f"
  done
}

# GUDHI's cofaces_simplex_range walks the whole Simplex_tree for every query, so cofaces of
# every vertex / edge is quadratic in the complex (tet-bunny00-108212: ~2 min for the vertices
# and ~15 min for the edges on 2 busy cores; hours at 10^6). Above this many top simplices the
# GUDHI side of cofaces_v / cofaces_e is left out (Topoplex's still runs; the table shows —).
gudhi_cofaces_max=${TOPOPLEX_BENCH_GUDHI_COFACES_MAX:-25000}

run() { # program short-name file
  local exe=$bench_bin/$1 out="$results/$2__$(basename "$3").json"
  [ -x "$exe" ] || return 0
  echo "-- $2 $(basename "$3")"
  local args=(--benchmark_format=json --benchmark_out="$out")
  if [ -n "$min_time" ]; then args+=(--benchmark_min_time="$min_time"); fi
  local n=${3##*-}
  n=${n%%.*}
  if [ "$2" = gudhi ] && [ "$n" -gt "$gudhi_cofaces_max" ]; then
    args+=(--benchmark_filter='-cofaces_./gudhi')
  fi
  if ! "$exe" "${args[@]}" "$3" >"$results/$2__$(basename "$3").log" 2>&1; then
    tail -5 "$results/$2__$(basename "$3").log" >&2
    failed+=("$2 on $(basename "$3") (see $2__$(basename "$3").log)")
  fi
}

if [ -n "$bench_bin" ]; then
  echo "== side-by-side benchmarks into $results"
  for f in $(datasets 'surf-*.off'); do run topoplex_bench_surface surface "$f"; done
  for f in $(datasets 'tet-*.mesh'); do run topoplex_bench_tets tets "$f"; done
  # Issue 25: the whole application (load, smoothing, stats, face neighbours, write) on
  # OpenMesh and on the mesh (also indexed: facet adjacency and one-rings built in load, --kept), one process
  # per run, peak RSS per process; the surfaces and the
  # non-manifold meshes of ../shared/data when present. RESULTS/app.md.
  if [ -x "$bench_bin/topoplex_bench_app" ]; then
    echo "-- app"
    shared=$root/../shared/data
    python3 "$root/scripts/bench_app.py" "$bench_bin/topoplex_bench_app" \
      --runs "$([ "$quick" = 1 ] && echo 2 || echo 5)" --kept $(datasets 'surf-*.off') \
      $(ls "$shared"/nonmanifold/*.obj 2>/dev/null) | tee "$results/app.md" \
      || failed+=("bench_app.py")
  fi
  # Issue 14: simplification to 1% next to OpenMesh's Decimater and CGAL's SMS.
  for f in $(datasets 'surf-*.off'); do run topoplex_bench_simplify simplify "$f"; done
  # Peak RSS of the whole process, one library per process (same soup loaded first), into
  # RESULTS/simplify_rss.tsv: the peak heap counter above misses what the C library keeps
  # resident (docs/benchmarks.md, Simplification).
  if [ -x /usr/bin/time ] && [ -x "$bench_bin/topoplex_bench_simplify" ]; then
    printf 'dataset\tlib\tpeak_rss_kb\n' >"$results/simplify_rss.tsv"
    for f in $(datasets 'surf-*.off'); do
      for lib in openmesh cgal_sm tpx tpx_preserve; do
        kb=$(/usr/bin/time -f '%M' "$bench_bin/topoplex_bench_simplify" \
               --benchmark_filter="simplify/$lib\$" --benchmark_min_time=0 "$f" 2>&1 >/dev/null \
             | tail -1)
        printf '%s\t%s\t%s\n' "$(basename "$f")" "$lib" "$kb" >>"$results/simplify_rss.tsv"
      done
    done
    cat "$results/simplify_rss.tsv"
  fi
  # RESULTS/simplify_cli.tsv: whole processes reading the file, simplifying to 1% and writing
  # the result — the `topoplex simplify` CLI (which fixes glibc's mmap threshold, see
  # crates/topoplex/src/sys.rs) next to OpenMesh's and CGAL's readers + simplifiers + writers
  # (`--file-job`): peak RSS (KiB) and wall/user/sys seconds from /usr/bin/time.
  if [ -x /usr/bin/time ] && [ -x "$bench_bin/topoplex_bench_simplify" ] \
     && nice -n 10 cargo build --release --bin topoplex --manifest-path "$root/Cargo.toml" \
          --target-dir "$target" >/dev/null 2>&1; then
    plain=$(mktemp -d)
    printf 'dataset\tjob\tpeak_rss_kb\twall_s\tuser_s\tsys_s\n' >"$results/simplify_cli.tsv"
    for f in $(datasets 'surf-*.off'); do
      g="$plain/$(basename "$f")"
      grep -v '^#' "$f" >"$g"  # OpenMesh's OFF reader reads a comment line as an empty mesh
      ratio=${TOPOPLEX_BENCH_SIMPLIFY_RATIO:-0.01}
      for job in openmesh cgal_sm cli cli_preserve; do
        case $job in
          cli) cmd=("$target/release/topoplex" simplify "$g" --out "$plain/out.off" --ratio "$ratio") ;;
          cli_preserve) cmd=("$target/release/topoplex" simplify "$g" --out "$plain/out.off" --ratio "$ratio"
                             --preserve-topology) ;;
          *) cmd=("$bench_bin/topoplex_bench_simplify" --file-job "$job" "$g" "$plain/out.off") ;;
        esac
        r=$(/usr/bin/time -f '%M %e %U %S' "${cmd[@]}" 2>&1 >/dev/null | tail -1)
        printf '%s\t%s\t%s\n' "$(basename "$f")" "$job" "${r// /$'\t'}" >>"$results/simplify_cli.tsv"
      done
      rm -f "$g"
    done
    rm -rf "$plain"
    cat "$results/simplify_cli.tsv"
  fi
  # Issue 14: link-checked contractions per second on the 300×300 triangle grid (tri-180k of
  # benches/live.rs), next to OpenMesh's is_collapse_ok + collapse.
  run topoplex_bench_contract contract 300
  for f in $(datasets 'surf-*.off') $(datasets 'tet-*.mesh') $(datasets 'alpha-*.simplices') \
           $(datasets 'rips-*.simplices'); do
    run topoplex_bench_gudhi gudhi "$f"
  done
fi

# `cargo bench --bench NAME` (criterion, --quick with --quick) into $results/LOG.log; a failure
# shows the log's tail and is recorded.
criterion_bench() {
  local args=(--noplot)
  if [ "$quick" = 1 ]; then args+=(--quick); fi
  if ! (cd "$root" && CARGO_TARGET_DIR=$target cargo bench --bench "$1" -- "${args[@]}") \
      >"$results/$2.log" 2>&1; then
    tail -5 "$results/$2.log" >&2
    failed+=("cargo bench --bench $1 (see $2.log)")
  fi
}

echo "== cargo bench --bench structures (criterion)"
if [ -f "$root/benches/structures.rs" ]; then
  criterion_bench structures criterion
  echo "criterion output: $results/criterion.log, reports in $target/criterion"
  # The criterion bench's own tables (benches/structures_table.py, when that script exists).
  if [ -f "$root/benches/structures_table.py" ]; then
    python3 "$root/benches/structures_table.py" "$target/criterion" >"$results/criterion.md" \
      || failed+=("benches/structures_table.py")
  fi
else
  echo "benches/structures.rs not present: skipped"
fi

echo "== cargo bench --bench live (criterion: link-checked contractions, storage vs the IA)"
if [ -f "$root/benches/live.rs" ]; then
  criterion_bench live live
  grep -E '^(storage|contract) |live/(link|contract) +time|thrpt' "$results/live.log" || true
fi

echo "== the Python package (scripts/bench_py.sh: release builds, then scripts/bench_py.py)"
if [ "$quick" = 1 ]; then py_args=(--quick); else py_args=(); fi
TOPOPLEX_BENCH_DATA="$data" "$root/scripts/bench_py.sh" "$results/python.md" "${py_args[@]}" \
  || failed+=("scripts/bench_py.sh")

echo "== table"
python3 "$root/scripts/bench_table.py" "$results" --datasets "$data/datasets.tsv" \
  | tee "$results/table.md" || failed+=("bench_table.py")

if [ -s "$results/criterion.md" ]; then
  echo
  echo "== Rust API (criterion): $results/criterion.md"
fi
echo
echo "results: $results"
if [ ${#failed[@]} -gt 0 ]; then
  printf 'FAILED: %s\n' "${failed[@]}" >&2
  exit 1
fi
