#!/usr/bin/env bash
# Benchmarks of issue 26 (data travels with the mesh). Not tests: nothing here is timed by the
# test suite. Run on a quiet machine; results go to docs/benchmarks.md ("Data with the mesh").
#
#  (a) reading: the largest file of $DATA (default ../shared/data/labelled) as given, and the
#      same mesh rewritten by our writer in its own format with and without its data
#      (`convert --drop-data all`: the same text but the data), each read REPS times in one
#      process (examples/read_attributes.rs, median); ratio with/without (aim <= 1.1). Also the
#      CLI as a whole: `topoplex save FILE --out x.tpx` against the same with `--drop-data all`
#      (wall time of LOOP processes in a row, per process; the median of RUNS such loops).
#  (b) memory: the peak resident memory a read adds (above the process's start), with data
#      against without, next to the attribute bytes (`Attributes::bytes`); aim: with <= without
#      + attribute bytes + 2 %. Time and peak are each the median over RUNS processes.
#  (c) simplify: `topoplex simplify IN --out OUT --ratio R --preserve-topology` with and
#      without `--keep-regions NAME` on the multi-region tetrahedral meshes (gmsh_t16.msh and
#      gmsh_t5.msh by `gmsh:geometrical`, gmsh_t16.mesh by `medit:ref`), median CPU time (user +
#      sys) and peak RSS of RUNS processes each; ratio keep-regions/plain (aim <= 1.2); the
#      CLI's own line (count reached, contractions, refusals) of the last run of each.
#
# usage: scripts/bench_attributes.sh      (env: DATA, REPS=50, RUNS=5, LOOP=20, RATIO=0.5)
set -euo pipefail
cd "$(dirname "$0")/.."
data=${DATA:-${TOPOPLEX_SHARED_DATA:-../shared/data}/labelled}
reps=${REPS:-50}
runs=${RUNS:-5}
loop=${LOOP:-20}
ratio=${RATIO:-0.5}
[ -d "$data" ] || { echo "no $data: nothing to measure" >&2; exit 1; }
cargo build --release --bin topoplex --example read_attributes >/dev/null
bin=$PWD/target/release/topoplex
reader=$PWD/target/release/examples/read_attributes
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Median of the numbers on stdin.
median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
# Median CPU seconds (user + sys) and median peak RSS (KiB) of RUNS runs of a command.
cpu_and_rss() {
  local t=() m=()
  for _ in $(seq "$runs"); do
    /usr/bin/time -f '%U %S %M' -o "$work/time" "$@" >/dev/null 2>"$work/err" ||
      { cat "$work/err" "$work/time" >&2; exit 1; }
    read -r u s k <"$work/time"
    t+=("$(awk -v u="$u" -v s="$s" 'BEGIN { print u + s }')")
    m+=("$k")
  done
  echo "$(printf '%s\n' "${t[@]}" | median) $(printf '%s\n' "${m[@]}" | median)"
}
# Median over RUNS of the wall seconds per process of LOOP runs of a command in a row.
wall_per_run() {
  local t=()
  for _ in $(seq "$runs"); do
    local start end
    start=$(date +%s.%N)
    for _ in $(seq "$loop"); do "$@" >/dev/null; done
    end=$(date +%s.%N)
    t+=("$(awk -v a="$start" -v b="$end" -v n="$loop" 'BEGIN { print (b - a) / n }')")
  done
  printf '%s\n' "${t[@]}" | median
}

echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); $(git log -1 --format='%h %cs')"
largest=$(ls -S "$data"/* | head -1)
ext=${largest##*.}
"$bin" convert "$largest" "$work/with.$ext" >/dev/null
"$bin" convert "$largest" "$work/without.$ext" --drop-data all >/dev/null

echo
echo "## (a), (b) reading $(basename "$largest") ($reps reads per process, median of $runs processes)"
printf '| file | bytes | read ms | attribute bytes | peak added KiB |\n|---|--:|--:|--:|--:|\n'
declare -A ms peak attr
for f in "$largest" "$work/with.$ext" "$work/without.$ext"; do
  # RUNS processes: a peak of 2 MiB moves by ±100 KiB from process to process (malloc).
  secs_all=() added_all=()
  for _ in $(seq "$runs"); do
    IFS=$'\t' read -r _ size secs bytes added < <("$reader" "$f" "$reps")
    secs_all+=("$secs")
    added_all+=("$added")
  done
  secs=$(printf '%s\n' "${secs_all[@]}" | median)
  added=$(printf '%s\n' "${added_all[@]}" | median)
  name=$(basename "$f")
  ms[$name]=$(awk -v s="$secs" 'BEGIN { printf "%.3f", s * 1000 }')
  peak[$name]=$((added / 1024))
  attr[$name]=$bytes
  printf '| %s | %s | %s | %s | %s |\n' "$name" "$size" "${ms[$name]}" "$bytes" "${peak[$name]}"
done
w=with.$ext
wo=without.$ext
awk -v a="${ms[$w]}" -v b="${ms[$wo]}" 'BEGIN { printf "read time with/without data: %.3f (aim <= 1.1)\n", a / b }'
awk -v p="${peak[$w]}" -v q="${peak[$wo]}" -v x="${attr[$w]}" 'BEGIN {
  printf "peak added with data: %d KiB; without + attribute bytes: %d KiB; ratio %.3f (aim <= 1.02)\n",
    p, q + x / 1024, p / (q + x / 1024) }'
cw=$(wall_per_run "$bin" save "$largest" --out "$work/a.tpx")
co=$(wall_per_run "$bin" save "$largest" --out "$work/b.tpx" --drop-data all)
awk -v a="$cw" -v b="$co" 'BEGIN {
  printf "CLI save (wall per process): %.2f ms with data, %.2f ms with --drop-data all: ratio %.3f\n",
    a * 1000, b * 1000, a / b }'

echo
echo "## (c) simplify --ratio $ratio --preserve-topology, with and without --keep-regions ($runs runs, median)"
printf '| mesh | regions by | plain CPU s | keep-regions CPU s | ratio | plain RSS KiB | keep-regions RSS KiB |\n|---|---|--:|--:|--:|--:|--:|\n' >"$work/table"
: >"$work/lines"
for job in gmsh_t16.msh:gmsh:geometrical gmsh_t5.msh:gmsh:geometrical gmsh_t16.mesh:medit:ref; do
  file=${job%%:*}
  attr=${job#*:}
  [ -f "$data/$file" ] || { echo "| $file | absent |" >>"$work/table"; continue; }
  out=$work/out.${file##*.}
  read -r tp rp < <(cpu_and_rss "$bin" simplify "$data/$file" --out "$out" --ratio "$ratio" --preserve-topology)
  echo "$file plain: $("$bin" simplify "$data/$file" --out "$out" --ratio "$ratio" --preserve-topology)" >>"$work/lines"
  read -r tk rk < <(cpu_and_rss "$bin" simplify "$data/$file" --out "$out" --ratio "$ratio" --preserve-topology --keep-regions "$attr")
  echo "$file keep-regions: $("$bin" simplify "$data/$file" --out "$out" --ratio "$ratio" --preserve-topology --keep-regions "$attr")" >>"$work/lines"
  awk -v f="$file" -v at="$attr" -v a="$tp" -v b="$tk" -v r="$rp" -v q="$rk" 'BEGIN {
    printf "| %s | %s | %.3f | %.3f | %.2f | %d | %d |\n", f, at, a, b, (a > 0 ? b / a : 0), r, q }' >>"$work/table"
done
cat "$work/table"
echo
sed "s|$work/||" "$work/lines"
