#!/usr/bin/env bash
# Issue 29's benchmarks of the PETSc DMPlex bridge (docs/dmplex.md, "Benchmarks"): builds and
# installs Topoplex with the bridge (release), builds examples/dmplex/bench_dmplex against the
# installed package, runs it under mpiexec and prints one markdown table per part:
#   (a) per-rank DMPlex topology memory (PETSc's malloc counter and the heap) vs Topoplex's;
#   (b) conversion rate RankMesh::from_dm (+ the IA's build);
#   (c) every owned vertex's star: Topoplex vs DMPlexGetTransitiveClosure(useCone = false),
#       counts checked vertex by vertex (a mismatch fails the script);
#   (d) weak scaling on 1, 2, 4 ranks (fixed simplices per rank);
#   (e) each rank's peak resident set (VmHWM) after each phase, the big grid included.
# Grids: about $SIMPLICES simplices (all dimensions counted) over 2 and 4 ranks, $WEAK per rank
# on 1, 2, 4 ranks, and $BIG over 2 ranks. Ranks above the cores run oversubscribed
# (mpiexec --oversubscribe; the tables say so): their times share cores.
#
# usage: scripts/bench_dmplex.sh [--small]
#   --small: 1e6 / 2.5e5 per rank / 1e6 (a loaded machine's indicative run, a few minutes)
#   default: SIMPLICES=1e7 WEAK=2.5e6 BIG=1e8 (a quiet machine: see docs/dmplex.md for the
#   expected time and memory); each can be set in the environment.
# Needs PETSc and MPI (scripts/install-deps.sh libpetsc-real-dev openmpi-bin), cmake, ninja.
# Cargo's target dir is $CARGO_TARGET_DIR or the repository's target/; TOPOPLEX_CARGO_PREBUILT=ON
# takes the library already built there (release profile). Work files: $BENCH_DIR (default
# target/bench-dmplex). As root, OpenMPI needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM), set here.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
if [ "${1:-}" = --small ]; then
  : "${SIMPLICES:=1e6}" "${WEAK:=2.5e5}" "${BIG:=1e6}"
elif [ -n "${1:-}" ]; then
  echo "usage: $0 [--small]" >&2
  exit 1
fi
: "${SIMPLICES:=1e7}" "${WEAK:=2.5e6}" "${BIG:=1e8}"
dir=${BENCH_DIR:-$root/target/bench-dmplex}
mkdir -p "$dir/runs"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

echo "== build and install Topoplex with the DMPlex bridge into $dir/prefix" >&2
cmake -S "$root" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DTOPOPLEX_CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}" \
  -DTOPOPLEX_CARGO_PROFILE=release \
  -DTOPOPLEX_CARGO_PREBUILT="${TOPOPLEX_CARGO_PREBUILT:-OFF}" >"$dir/build.log"
cmake --build "$dir/build" >>"$dir/build.log"
cmake --install "$dir/build" --prefix "$dir/prefix" >>"$dir/build.log"
if [ ! -f "$dir/prefix/lib/cmake/Topoplex/TopoplexDmplex.cmake" ]; then
  echo "the bridge was not built (PETSc or MPI not found): see $dir/build.log" >&2
  exit 1
fi
cmake -S "$root/examples/dmplex" -B "$dir/bench" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$dir/prefix" >>"$dir/build.log"
cmake --build "$dir/bench" --target bench_dmplex >>"$dir/build.log"
bench=$dir/bench/bench_dmplex

cores=$(nproc)
commit=$(git -C "$root" rev-parse --short HEAD)$(git -C "$root" diff --quiet HEAD -- dmplex include examples/dmplex || echo "+dirty")
started=$(date -u '+%Y-%m-%d %H:%M UTC')
load_start=$(cut -d' ' -f1-3 /proc/loadavg)
t0=$(date +%s)

# run LABEL RANKS ARGS...: one mpiexec, its @-lines kept in $dir/runs/LABEL.out.
run() {
  local label=$1 np=$2
  shift 2
  local over=()
  [ "$np" -le "$cores" ] || over=(--oversubscribe)
  local file
  file="$dir/runs/$(printf '%02d' "${#outs[@]}")-$(echo "$label" | tr ' /' '__')"
  echo "== $label: mpiexec -n $np ${over[*]} bench_dmplex $*" >&2
  mpiexec -n "$np" "${over[@]}" "$bench" -label "$label" -malloc_view -malloc_view_threshold 1e15 "$@" \
    >"$file.log" 2>&1 || { tail -30 "$file.log" >&2; echo "run $label failed" >&2; exit 1; }
  grep '^[@#]' "$file.log" >"$file.out"
  outs+=("$file.out")
}

outs=()
rm -f "$dir"/runs/*.out "$dir"/runs/*.log
run "$SIMPLICES/2" 2 -simplices "$SIMPLICES"
run "$SIMPLICES/4" 4 -simplices "$SIMPLICES"
for np in 1 2 4; do run "weak $WEAK x$np" "$np" -simplices "$WEAK" -per_rank; done
# The big grid as a cell-vertex DM by default: DMPlexInterpolate's peak (about 880 B per
# tetrahedron on each rank, measured at 1e6) would put 1e8 over 2 ranks near 21 GB; the
# cell-vertex path peaks near 400 B per tetrahedron (about 9 GB in all). BIG_INTERPOLATE=1 asks
# for the interpolated DM anyway (without the topology rebuild of part (a)).
if [ "${BIG_INTERPOLATE:-0}" = 1 ]; then
  run "big $BIG/2 interpolated" 2 -simplices "$BIG" -self_dm 0
else
  run "big $BIG/2 cell-vertex" 2 -simplices "$BIG" -self_dm 0 -interpolate 0
fi
elapsed=$(($(date +%s) - t0))

rows() { cat "${outs[@]}" | grep "^@$1|" | sed "s/^@$1//"; }
header() {
  echo
  echo "### $1"
  echo
  echo "$started, commit $commit, load average $load_start at the start and $(cut -d' ' -f1-3 /proc/loadavg) at the end, $cores cores (ranks above them oversubscribed), runs ${elapsed} s."
  echo
}
echo "# DMPlex bridge benchmarks (scripts/bench_dmplex.sh)"
echo
grep -h '^#' "${outs[@]}" | sed 's/^# /- /'

header "(a) per-rank topology memory: DMPlex against Topoplex"
echo "DMPlex: the rank's cells (overlap included) rebuilt as an interpolated DMPlex on PETSC_COMM_SELF (cones, orientations, supports, their sections, depth and celltype labels; no coordinates, no SF): growth of PetscMallocGetCurrentUsage and of the heap (mallinfo2). Held: what DMDestroy of the distributed DM frees, less its coordinate values. Topoplex (coordinates left out on both sides): the IA's own arrays (tpx_structure_storage) and the IA as held (heap growth of its build: its arrays and its handle bookkeeping, the tops' windings), the complex's heap less its coordinates (moved out and dropped once the IA is built: the IA holds the tops), the RankMesh maps (RankMesh::bytes(): top runs, ghost copies if any, the global vertex numbering), and the edge and triangle tables the first query naming an edge or triangle by dense id builds (part (c)). Ratios against the PETSc counter ("n/a": not rebuilt, the big run). Aim: Topoplex kept (IA held + maps) <= 0.2."
echo
echo "| run | ranks | rank | tets | points | DMPlex MiB (PETSc) | DMPlex MiB (heap) | DMPlex B/tet | DM held − coords MiB | IA MiB | IA held MiB | complex MiB (dropped) | maps MiB | edge+triangle tables MiB | IA / DMPlex | kept: IA held + maps / DMPlex | + tables / DMPlex | + complex if kept / DMPlex |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
rows a

header "(b) conversion: RankMesh::from_dm (interpolated DM -> complex and maps) and the IA"
echo "Wall and CPU seconds on the rank; Complex::from_arrays alone on the same tops is the core's share. Aim: >= 10 M cells/s per rank."
echo
echo "| run | ranks | rank | tets | from_dm s | from_dm CPU s | from_arrays s | IA build s | M tets/s (from_dm) | M tets/s (from_dm, CPU) | M tets/s (from_dm + IA) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
rows b

header "(c) every owned vertex's star: Topoplex (IA) against DMPlexGetTransitiveClosure(useCone = PETSC_FALSE)"
echo "Counts equal: closure size = |star| + 1 and cells in the closure = |R_{0,3}|, vertex by vertex (a cell-vertex DM's closure holds the vertex and its cells only: there the cells are compared, and tpx_star with R01+R02+R03). Aim: >= 5x."
echo
echo "Tables: the edge and triangle tables (dense ids of edges and triangles; the IA stores neither) are built by one query before the timed loops ('tables build s', their memory in part (a))."
echo
echo "Views: R_{0,1}, R_{0,2}, R_{0,3} lent as CSR by Structure::view (the IA stores none: their indices are built once, 'views build s', holding 'views MiB'), the stars then read inline."
echo
echo "| run | ranks | rank | owned vertices | DMPlex s | R03 s | R01+R02+R03 s | tpx_star s | tables build s | views build s | views star s | views MiB | R03 speed-up | R03 speed-up (CPU) | R01..R03 speed-up | R01..R03 speed-up (CPU) | tpx_star speed-up | tpx_star speed-up (CPU) | views star speed-up | closure points | cells | equal |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
rows c

header "(d) phases per rank (weak scaling: the 'weak' runs, $WEAK simplices per rank)"
echo "| run | ranks | rank | points | tets | create s | distribute + interpolate s | from_dm s | IA s | DMPlex stars s | R03 stars s | VmHWM MiB |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
rows d

header "(e) peak resident set per rank (VmHWM, MiB, after each phase)"
echo "| run | ranks | rank | tets | created | distributed + interpolated | + DMPlex topology rebuilt | + from_dm + IA | end |"
echo "|---|---|---|---|---|---|---|---|---|"
rows e
echo
echo "| run | ranks | simplices | tetrahedra | max VmHWM MiB | load at start |"
echo "|---|---|---|---|---|---|"
rows s
