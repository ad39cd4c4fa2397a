#!/usr/bin/env python3
"""Markdown tables from `cargo bench --bench structures` output (criterion's JSON files).

Usage: benches/structures_table.py [CRITERION_DIR] [BASELINE]
  CRITERION_DIR defaults to $CARGO_TARGET_DIR/criterion or target/criterion;
  BASELINE is criterion's baseline directory name: `new` (the last run, default) or a name
  given to `--save-baseline`.

Each cell is criterion's mean time of one iteration divided by the elements it retrieved
(simplices of the complex for `build`), in ns.
"""
import json
import os
import sys
from collections import defaultdict
from pathlib import Path

KINDS = ["ig", "sig", "ia", "iqm", "nmia", "ts", "pe", "le", "de"]
# Complexes in the order the bench runs them; others follow in name order.
ORDER = ["tri-10k", "tri-100k", "tri-1M", "tet-10k", "tet-100k", "tet-1M"]


def op_key(op):
    if op == "build":
        return (0, 0, 0)
    p, q = (int(x) for x in op[1:].split(","))
    # Boundary of top simplices, then co-boundary of vertices, then adjacencies.
    if p > 0 and q < p:
        return (1, -q, 0)
    if p == 0 and q > 0:
        return (2, q, 0)
    return (3, p, 0)


def load(root, baseline):
    cells = defaultdict(dict)  # complex -> (kind, op) -> ns per element
    for bench in root.glob(f"*/*/*/{baseline}/benchmark.json"):
        meta = json.loads(bench.read_text())
        est = json.loads((bench.parent / "estimates.json").read_text())
        elements = (meta.get("throughput") or {}).get("Elements")
        if not elements:
            continue
        group, kind, op = meta["group_id"], meta["function_id"], meta["value_str"]
        cells[group][(kind, op)] = est["mean"]["point_estimate"] / elements
    return cells


def fmt(x):
    if x is None:
        return "–"
    return f"{x:.0f}" if x >= 10 else f"{x:.1f}"


def main():
    target = os.environ.get("CARGO_TARGET_DIR", "target")
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(target) / "criterion"
    baseline = sys.argv[2] if len(sys.argv) > 2 else "new"
    cells = load(root, baseline)
    if not cells:
        sys.exit(f"no criterion results under {root} (baseline {baseline})")
    groups = [g for g in ORDER if g in cells] + sorted(g for g in cells if g not in ORDER)

    print("Build, ns per simplex of the complex (closure included):\n")
    print("| structure | " + " | ".join(groups) + " |")
    print("|---|" + "---:|" * len(groups))
    for k in KINDS:
        row = [cells[g].get((k, "build")) for g in groups]
        if any(row):
            print(f"| {k} | " + " | ".join(fmt(x) for x in row) + " |")

    # Flatness from 10^4 to 10^6: largest over smallest ns per simplex, per grid family.
    families = [f for f in ("tri", "tet") if all(f"{f}-{s}" in cells for s in ("10k", "100k", "1M"))]
    if families:
        print("\nBuild ns per simplex, largest / smallest over 10^4, 10^5, 10^6 (aim: within ±30 %):\n")
        print("| structure | " + " | ".join(f"{f} grid" for f in families) + " |")
        print("|---|" + "---:|" * len(families))
        for k in KINDS:
            vals = []
            for f in families:
                xs = [cells[f"{f}-{s}"].get((k, "build")) for s in ("10k", "100k", "1M")]
                vals.append(f"{max(xs) / min(xs):.2f}" if all(xs) else "–")
            if any(v != "–" for v in vals):
                print(f"| {k} | " + " | ".join(vals) + " |")

    for g in groups:
        ops = sorted({op for (_, op) in cells[g] if op != "build"}, key=op_key)
        print(f"\n{g}, ns per retrieved element:\n")
        print("| structure | " + " | ".join(ops) + " |")
        print("|---|" + "---:|" * len(ops))
        for k in KINDS:
            row = [cells[g].get((k, op)) for op in ops]
            if any(row):
                print(f"| {k} | " + " | ".join(fmt(x) for x in row) + " |")


if __name__ == "__main__":
    main()
