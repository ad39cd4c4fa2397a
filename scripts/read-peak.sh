#!/usr/bin/env bash
# Issue 16 class 5: reading and normalising a file (Complex::from_path) must peak under 5× the
# file's size, also for files of very short lines (the worst case: every line costs the same
# reader output and sort memory whatever its length). Generates files of short lines in each
# text format (about $1 MB each, default 100) and runs examples/read_peak.rs on each under
# /usr/bin/time -v, one process per file. Prints: file, size MB, lines, max RSS MB (time -v),
# peak above start / size (the example's own VmHWM), and fails when a ratio reaches 5.
# Figures are recorded in docs/bad-input.md (class 5) and docs/benchmarks.md ("Reading").
set -euo pipefail
cd "$(dirname "$0")/.."
mb=${1:-100}
cargo build --release --example read_peak >/dev/null
bin=target/release/examples/read_peak
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work" "$mb" <<'PY'
import sys
work, mb = sys.argv[1], int(sys.argv[2])
n = mb * 1000 * 1000 // 8            # 8-byte lines
verts10 = "".join("0 0 0\n" for _ in range(10))
files = {
    "short.simplices": "s 1 2 3\n" * n,
    "short.off": "OFF\n10 %d 0\n" % n + verts10 + "3 1 2 3\n" * n,
    "short.obj": "".join("v 0 0 0\n" for _ in range(10)) + "f 1 2 3\n" * n,
    "short.mesh": "MeshVersionFormatted 2\nDimension 3\nVertices\n10\n"
        + "".join("0 0 0 0\n" for _ in range(10)) + "Triangles\n%d\n" % n + "1 2 3 0\n" * n + "End\n",
    "short.ply": "ply\nformat ascii 1.0\nelement vertex 10\nproperty float x\nproperty float y\n"
        "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n" % n
        + verts10 + "3 1 2 3\n" * n,
    # CELLS lines of 8 bytes and CELL_TYPES lines of 2.
    "short.vtk": "# vtk DataFile Version 2.0\nshort\nASCII\nDATASET UNSTRUCTURED_GRID\n"
        "POINTS 10 float\n" + verts10 + "CELLS %d %d\n" % (n * 4 // 5, 4 * (n * 4 // 5))
        + "3 1 2 3\n" * (n * 4 // 5) + "CELL_TYPES %d\n" % (n * 4 // 5) + "5\n" * (n * 4 // 5),
    # Version 5: OFFSETS and CONNECTIVITY, one cell per line.
    "short.v5.vtk": "# vtk DataFile Version 5.1\nshort\nASCII\nDATASET UNSTRUCTURED_GRID\n"
        "POINTS 10 float\n" + verts10 + "CELLS %d %d\nOFFSETS vtktypeint64\n" % (n // 2 + 1, 3 * (n // 2))
        + "".join("%d\n" % (3 * i) for i in range(n // 2 + 1))
        + "CONNECTIVITY vtktypeint64\n" + "1 2 3\n" * (n // 2)
        + "CELL_TYPES %d\n" % (n // 2) + "5\n" * (n // 2),
}
# VTU with ASCII data arrays (our streaming reader, src/io/vtu/ascii.rs), one cell per line.
c = n // 2
files["short.vtu"] = (
    '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">\n'
    '<UnstructuredGrid>\n<Piece NumberOfPoints="10" NumberOfCells="%d">\n<Points>\n'
    '<DataArray type="Float64" NumberOfComponents="3" format="ascii">\n' % c + verts10
    + '</DataArray>\n</Points>\n<Cells>\n<DataArray type="Int64" Name="connectivity" format="ascii">\n'
    + "1 2 3\n" * c
    + '</DataArray>\n<DataArray type="Int64" Name="offsets" format="ascii">\n'
    + "".join("%d\n" % (3 * i + 3) for i in range(c))
    + '</DataArray>\n<DataArray type="UInt8" Name="types" format="ascii">\n' + "5\n" * c
    + '</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n')
for name, text in files.items():
    with open(f"{work}/{name}", "w") as f:
        f.write(text)
# MSH 2.2: element lines carry their own increasing id, so they are 15-20 bytes.
m = mb * 1000 * 1000 // 18
with open(f"{work}/short.msh", "w") as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n")
    f.write("".join("%d 0 0 0\n" % (i + 1) for i in range(10)))
    f.write("$EndNodes\n$Elements\n%d\n" % m)
    for start in range(0, m, 1 << 20):
        f.write("".join("%d 2 0 1 2 3\n" % (i + 1) for i in range(start, min(m, start + (1 << 20)))))
    f.write("$EndElements\n")
PY
fail=0
printf 'file\tsize MB\tlines\tmax RSS MB\tpeak/size\n'
for f in "$work"/short.*; do
  out=$( { /usr/bin/time -v "$bin" "$f" 2>"$work/time.txt"; } ) || { cat "$work/time.txt"; exit 1; }
  rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$work/time.txt")
  IFS=$'\t' read -r _ size lines _ ratio _ <<<"$out"
  printf '%s\t%s\t%s\t%s\t%s\n' "$(basename "$f")" "$((size / 1000000))" "$lines" "$((rss / 1024))" "$ratio"
  if awk -v r="$ratio" 'BEGIN { exit !(r >= 5) }'; then
    echo "  (over the bound)"
    fail=1
  fi
done
exit $fail
