#!/usr/bin/env python3
"""The application benchmark of issue 25: topoplex_bench_app on OpenMesh and on Topoplex's mesh,
side by side, one process per run (so each peak RSS is that application's alone), runs of the
two libraries alternated so that a change in the machine's load hits both.

Prints a Markdown table: per input, each phase's median time for both libraries and the ratio
Topoplex / OpenMesh (below 1 = Topoplex faster), the whole application's, and the ratio of peak
RSS. The answers (valence histogram, boundary edges, face neighbours by a numbering-free key,
the smoothed coordinates' sum to 1e-6 relative: OpenMesh's OFF reader parses single-precision
floats even into double points) must agree, else the input is marked: OpenMesh drops the faces
of a non-manifold input when it reads it, and only Topoplex's figures are shown then.

With --kept, a third program runs alternated with the two: Topoplex's indexed mesh
(`topoplex-kept`: both indices built in `load`, as OpenMesh builds its halfedges while loading:
the facet adjacency, kept from then on and read by `ff`, and the one-rings, read by the
smoothing and the stats), printed as a second row per input.

usage: scripts/bench_app.py BIN [--runs N] [--kept] INPUT.off...
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile

PHASES = ["load", "smooth", "stats", "ff", "ff_each", "write", "total"]
EXACT = ["faces", "boundary", "valence_hash", "ff_sum", "ff_each_sum"]


def run(binary, lib, path, out):
    p = subprocess.run([binary, lib, path, out], capture_output=True, text=True)
    if p.returncode != 0:
        return None, p.stderr.strip()
    kv = dict(item.split("=", 1) for item in p.stdout.split())
    return kv, ""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("inputs", nargs="+")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--kept", action="store_true")
    a = ap.parse_args()
    libs = ["openmesh", "topoplex"] + (["topoplex-kept"] if a.kept else [])
    load = os.getloadavg()
    print(f"load average at start: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}; "
          f"{a.runs} runs per library and input, alternated; medians")
    print()
    head = "| input | faces | " + " | ".join(PHASES) + " | peak RSS | note |"
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    tmp = tempfile.mkdtemp()
    for path in a.inputs:
        if path.endswith(".off"):
            # OpenMesh 9.0's OFF reader reads no face after a comment line (the generated
            # datasets have one under the header): both libraries read the same copy without.
            with open(path) as f:
                lines = [ln for ln in f if not ln.startswith("#")]
            copy = os.path.join(tmp, os.path.basename(path))
            with open(copy, "w") as f:
                f.writelines(lines)
            path = copy
        res = {lib: [] for lib in libs}
        err = {}
        for _ in range(a.runs):
            for lib in libs:
                kv, e = run(a.binary, lib, path, os.path.join(tmp, f"{lib}.off"))
                if kv is None:
                    err[lib] = e
                else:
                    res[lib].append(kv)
        for lib in libs[1:]:
            name = os.path.basename(path) + (" (indexed: adjacency kept, rings)" if lib == "topoplex-kept" else "")
            row(name, res[lib], res["openmesh"], err.get(lib))
    load = os.getloadavg()
    print()
    print(f"load average at end: {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")


def row(name, t, o, failure):
    """One input's row: Topoplex's runs `t` against OpenMesh's `o`."""
    if not t:
        print(f"| {name} | | " + " | " * len(PHASES) + f" | Topoplex failed: {failure} |")
        return

    def med(rows, key):
        return statistics.median(float(r[key]) for r in rows if key in r)

    same = bool(o) and all(t[0][k] == o[0][k] for k in EXACT) and abs(
        float(t[0]["coord_sum"]) - float(o[0]["coord_sum"])
    ) <= 1e-6 * max(1.0, abs(float(o[0]["coord_sum"])))
    cells = []
    for ph in PHASES:
        key = ph + "_ms"
        tm = med(t, key)
        if same:
            om = med(o, key)
            cells.append(f"{tm / om:.2f} ({tm:.1f} / {om:.1f} ms)")
        else:
            cells.append(f"{tm:.1f} ms")
    trss = med(t, "peak_rss_kib") / 1024
    if same:
        orss = med(o, "peak_rss_kib") / 1024
        cells.append(f"{trss / orss:.2f} ({trss:.0f} / {orss:.0f} MiB)")
        note = ""
    else:
        cells.append(f"{trss:.0f} MiB")
        note = ("OpenMesh cannot read it" if not o else
                "OpenMesh's answers differ (it drops non-manifold faces): Topoplex alone")
    print(f"| {name} | {t[0]['faces']} | " + " | ".join(cells) + f" | {note} |")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
