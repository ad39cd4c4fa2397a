#!/usr/bin/env python3
"""One Markdown table of Topoplex / peer ratios from the side-by-side benchmarks, then the aims
of issue 9 part 3 with met / not met.

usage: scripts/bench_table.py RESULTS_DIR [--datasets DATASETS_TSV]

RESULTS_DIR holds Google Benchmark JSON files (--benchmark_format=json) named
`<program>__<dataset file>.json`, program one of surface, tets, gudhi, simplify, contract
(scripts/bench.sh writes them so; simplify and contract get tables of their own). Benchmark names are `<op>/<lib>` (cpp_tests/bench/bench_common.hpp): lib is a peer
(openmesh, cgal_sm, cgal_t3, gudhi) or `tpx_<kind>`. Every benchmark carries the counter
`elements` (elements retrieved per iteration; for load/build the simplices of the complex) and,
for load/build, `heap_bytes` and `peak_heap_bytes`.

Ratios are Topoplex / peer, so below 1 means Topoplex is faster or smaller:
- time: (real time per element of tpx_<kind>) / (the same of the peer), same op, same file;
- memory (load/build rows only): heap_bytes ratio, then peak_heap_bytes ratio.
Python 3.11 standard library only.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import statistics
import sys
from collections import defaultdict
from pathlib import Path

PROGRAMS = ("surface", "tets", "gudhi", "simplify", "contract")
UNIT_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
# Which kinds the aims call "top-simplex structures" on a tetrahedral mesh: they store the top
# simplices and their adjacencies (IA, its non-manifold extension NMIA, and the IQM).
TOP_SIMPLEX_KINDS = ("ia", "nmia", "iqm")
# The family's own program: where its build time per simplex is read for the flatness aim.
NATIVE = {"surf": "surface", "tet": "tets", "alpha": "gudhi", "rips": "gudhi"}


# Set by `--cpu`: ratios from CPU time instead of wall time.
USE_CPU_TIME = False


class Run:
    """One `<op>/<lib>` measurement: time per element and memory."""

    def __init__(self, entries: list[dict]):
        def med(key):
            vals = [e[key] for e in entries if isinstance(e.get(key), (int, float))]
            return statistics.median(vals) if vals else None

        first = entries[0]
        unit = UNIT_NS.get(first.get("time_unit", "ns"), 1.0)
        # Wall time by default; `--cpu` (a machine shared with other jobs) reads CPU time.
        real = med("cpu_time" if USE_CPU_TIME else "real_time")
        self.elements = med("elements")
        ips = med("items_per_second")
        if real is not None and self.elements:
            self.ns_per_elem = real * unit / self.elements
        elif ips:
            self.ns_per_elem = 1e9 / ips
        else:
            self.ns_per_elem = None
        self.heap = med("heap_bytes")
        self.peak = med("peak_heap_bytes")
        self.faces_out = med("faces_out")
        self.items_per_second = ips
        self.contracted = med("contracted")
        self.passed = med("passed")
        if self.peak is not None and self.peak < 0:
            self.peak = None


def load_results(results: Path) -> dict[tuple[str, str], dict[str, dict[str, Run]]]:
    """(program, dataset) -> op -> lib -> Run."""
    out: dict[tuple[str, str], dict[str, dict[str, Run]]] = {}
    for path in sorted(results.glob("*__*.json")):
        program, dataset = path.name[: -len(".json")].split("__", 1)
        try:
            data = json.loads(path.read_text())
        except (OSError, json.JSONDecodeError) as e:
            print(f"warning: {path.name}: {e}", file=sys.stderr)
            continue
        grouped: dict[tuple[str, str], list[dict]] = defaultdict(list)
        for b in data.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration" or b.get("error_occurred"):
                continue
            parts = b.get("run_name", b["name"]).split("/")
            if len(parts) < 2:
                continue
            grouped[(parts[0], parts[1])].append(b)
        ops: dict[str, dict[str, Run]] = defaultdict(dict)
        for (op, lib), entries in grouped.items():
            ops[op][lib] = Run(entries)
        out[(program, dataset)] = dict(ops)
    return out


def family(dataset: str) -> str:
    return dataset.split("-", 1)[0]


def size_of(dataset: str) -> int:
    m = re.search(r"-(\d+)\.[a-z]+$", dataset)
    return int(m.group(1)) if m else 0


def fmt_ratio(x: float | None) -> str:
    if x is None or not math.isfinite(x):
        return "—"
    if x >= 10:
        return f"{x:.0f}"
    return f"{x:.2f}" if x >= 0.1 else f"{x:.2g}"


def fmt_ns(x: float | None) -> str:
    if x is None:
        return "—"
    return f"{x:.3g}"


def ratio(a: float | None, b: float | None) -> float | None:
    if a is None or b is None or b == 0:
        return None
    return a / b


def kinds_in(results) -> list[str]:
    order = ["ig", "sig", "ia", "iqm", "nmia", "ts", "pe", "le", "de"]
    seen = {
        lib[4:]
        for ops in results.values()
        for libs in ops.values()
        for lib in libs
        if lib.startswith("tpx_")
    }
    return [k for k in order if k in seen] + sorted(seen - set(order))


def main_table(results, kinds: list[str], sizes: dict[str, str]) -> list[str]:
    lines = [
        "Cells: time per element, Topoplex / peer (below 1: Topoplex faster). For `load` and "
        "`build` also `m` = retained heap ratio and `pk` = peak heap ratio. "
        "— : the kind refuses the complex or did not run.",
        "",
        "| dataset | top simplices | program | op | peer | peer ns/elem | "
        + " | ".join(f"tpx_{k}" for k in kinds)
        + " | best kind |",
        "|---|---:|---|---|---|---:|" + "---:|" * len(kinds) + "---|",
    ]
    keys = sorted(results, key=lambda k: (family(k[1]), size_of(k[1]), k[1], PROGRAMS.index(k[0]) if k[0] in PROGRAMS else 9))
    for program, dataset in keys:
        if program in ("simplify", "contract"):
            continue  # their own tables (simplify_table, contract_table)
        ops = results[(program, dataset)]
        for op in ops:
            libs = ops[op]
            # `<op>_batch` (one tpx_related_batch / tpx_degree_batch call over every simplex)
            # and `<op>_view` (answers read inline from a lent relation view) have no peer run
            # of their own: compare them with the peers' per-element walk of `<op>`.
            peer_libs = libs
            for suffix in FORMS:
                if op.endswith(suffix):
                    peer_libs = ops.get(op[: -len(suffix)], {})
            peers = [lib for lib in peer_libs if not lib.startswith("tpx_")]
            for peer in peers:
                p = peer_libs[peer]
                cells, best = [], None
                for k in kinds:
                    t = libs.get(f"tpx_{k}")
                    if t is None:
                        cells.append("—")
                        continue
                    r = ratio(t.ns_per_elem, p.ns_per_elem)
                    cell = fmt_ratio(r)
                    if op in ("load", "build"):
                        cell += f" m{fmt_ratio(ratio(t.heap, p.heap))}"
                        if t.peak is not None and p.peak is not None:
                            cell += f" pk{fmt_ratio(ratio(t.peak, p.peak))}"
                    cells.append(cell)
                    if r is not None and (best is None or r < best[1]):
                        best = (k, r)
                best_s = f"{best[0]} {fmt_ratio(best[1])}" if best else "—"
                lines.append(
                    f"| {dataset} | {sizes.get(dataset, f'{size_of(dataset):,}')} | {program} | {op} | {peer} "
                    f"| {fmt_ns(p.ns_per_elem)} | " + " | ".join(cells) + f" | {best_s} |"
                )
    return lines


def simplify_table(results) -> list[str]:
    """Issue 14: simplification to 1% next to OpenMesh's Decimater and CGAL's SMS."""
    keys = sorted((k for k in results if k[0] == "simplify"), key=lambda k: (size_of(k[1]), k[1]))
    if not keys:
        return []
    out = [
        "",
        "## Simplification (issue 14): quadric-error edge contraction to 1% of the triangles",
        "",
        "Whole job from the same in-memory soup: build the mesh, simplify, as the peer does. "
        "Cells: Topoplex / peer for time and peak heap (below 1: Topoplex better); "
        "`tpx` free contraction, `tpx_preserve` link-checked.",
        "",
        "| dataset | triangles | peer | peer ms | peer peak MB | faces left (peer / tpx) | tpx time | tpx peak | tpx_preserve time | tpx_preserve peak |",
        "|---|---:|---|---:|---:|---|---:|---:|---:|---:|",
    ]
    worst = {}
    for _, dataset in keys:
        libs = results[("simplify", dataset)].get("simplify", {})
        for peer in ("openmesh", "cgal_sm"):
            p = libs.get(peer)
            if p is None:
                continue
            cells = []
            for lib in ("tpx", "tpx_preserve"):
                t = libs.get(lib)
                rt = ratio(t.ns_per_elem, p.ns_per_elem) if t else None
                rm = ratio(t.peak, p.peak) if t else None
                cells += [fmt_ratio(rt), fmt_ratio(rm)]
                if lib == "tpx" and rt is not None and rm is not None:
                    w = worst.setdefault(peer, [0.0, 0.0])
                    w[0], w[1] = max(w[0], rt), max(w[1], rm)
            ms = p.ns_per_elem * p.elements / 1e6 if p.ns_per_elem and p.elements else None
            t = libs.get("tpx")
            faces = f"{p.faces_out:,.0f} / {t.faces_out:,.0f}" if t and p.faces_out and t.faces_out else "—"
            peak_mb = f"{p.peak / 2**20:.0f}" if p.peak else "—"
            out.append(
                f"| {dataset} | {p.elements:,.0f} | {peer} | {fmt_ns(ms)} | {peak_mb} | {faces} | "
                + " | ".join(cells)
                + " |"
            )
    out.append("")
    for peer, (rt, rm) in worst.items():
        out.append(
            f"- aim ≤ 1.0× the time and peak memory of {peer} (worst over the datasets: time {fmt_ratio(rt)}, "
            f"peak {fmt_ratio(rm)}): {verdict(rt <= 1.0 and rm <= 1.0)}"
        )
    return out


def contract_table(results) -> list[str]:
    """Issue 14: link-checked contractions per second next to OpenMesh's collapses."""
    keys = sorted(k for k in results if k[0] == "contract")
    if not keys:
        return []
    out = [
        "",
        "## Link-checked contractions (issue 14): calls per second on the K×K triangle grid",
        "",
        "20,000 calls (a sample of the edges, in ascending order) on a fresh copy; rate by the "
        "benchmark thread's CPU time. `contract`: check and collapse; `check`: the check alone on "
        "the unchanged mesh. Ratio: Topoplex / OpenMesh calls per second (above 1: Topoplex faster).",
        "",
        "| grid K | op | lib | calls/s | contracted / passed | vs openmesh |",
        "|---:|---|---|---:|---:|---:|",
    ]
    for _, k in keys:
        for op, count in (("contract", "contracted"), ("check", "passed")):
            libs = results[("contract", k)].get(op, {})
            peer = libs.get("openmesh")
            for lib in ("openmesh", "tpx", "tpx_manifold"):
                r = libs.get(lib)
                if r is None or not r.items_per_second:
                    continue
                vs = ratio(r.items_per_second, peer.items_per_second) if peer and peer.items_per_second else None
                n = getattr(r, count) or 0
                out.append(
                    f"| {k} | {op} | {lib} | {r.items_per_second / 1e6:.2f} M | {n:,.0f} | {fmt_ratio(vs)} |"
                )
    return out


def verdict(ok: bool | None) -> str:
    return {True: "**met**", False: "**not met**", None: "no data"}[ok]


def best_over(libs: dict[str, Run], peer: str, kinds=None) -> tuple[str, float] | None:
    p = libs.get(peer)
    if p is None:
        return None
    best = None
    for lib, t in libs.items():
        if not lib.startswith("tpx_") or (kinds and lib[4:] not in kinds):
            continue
        r = ratio(t.ns_per_elem, p.ns_per_elem)
        if r is not None and (best is None or r < best[1]):
            best = (lib[4:], r)
    return best


def aims(results) -> list[str]:
    out = ["", "### Aims of issue 9 part 3", ""]

    # 1. Storage on manifold tetrahedral meshes: bytes per simplex (all dimensions) from the
    #    gudhi program's build (the same complex for every library). One verdict per structure:
    #    the SIG against 16 B, each top-simplex structure against 8 B, all against half of GUDHI.
    rows, per_kind = [], {}
    for (program, dataset), ops in sorted(results.items(), key=lambda kv: size_of(kv[0][1])):
        if program != "gudhi" or family(dataset) != "tet" or "build" not in ops:
            continue
        libs = ops["build"]

        def bps(lib):
            r = libs.get(lib)
            return r.heap / r.elements if r and r.heap is not None and r.elements else None

        g = bps("gudhi")
        cells = []
        for k, limit in [("sig", 16)] + [(k, 8) for k in TOP_SIMPLEX_KINDS]:
            v = bps(f"tpx_{k}")
            if v is None:
                continue
            ok = v <= limit and (g is None or v <= g / 2)
            per_kind[k] = ok and per_kind.get(k, True)
            cells.append(f"{k} {v:.2f} {'✓' if ok else '✗'}")
        rows.append(f"  - {dataset}: {', '.join(cells) or '—'}; gudhi {fmt_ns(g)} B/simplex")
    ok_all = all(per_kind.values()) if per_kind else None
    kinds_s = "; ".join(f"{k} {verdict(v)}" for k, v in per_kind.items())
    out.append(
        f"1. SIG ≤ 16 B/simplex, top-simplex structures ({', '.join(TOP_SIMPLEX_KINDS)}) ≤ 8 "
        f"B/simplex on manifold tetrahedral meshes, each ≤ ½ of GUDHI Simplex_tree "
        f"(retained heap after `build` / simplices of all dimensions): {verdict(ok_all)}"
        + (f" ({kinds_s})" if kinds_s else "")
    )
    out += rows or ["  - no tetrahedral results"]

    # 2..4: speed aims against one peer, best kind per dataset.
    def speed_aim(title, program_ok, op, peer, limit, as_factor=False):
        rows, ok_all = [], None
        for (program, dataset), ops in sorted(results.items(), key=lambda kv: (family(kv[0][1]), size_of(kv[0][1]))):
            if not program_ok(program, dataset) or op not in ops:
                continue
            b = best_over(ops[op], peer)
            if b is None:
                continue
            ok = b[1] <= limit
            ok_all = ok if ok_all is None else ok_all and ok
            shown = f"{1 / b[1]:.1f}× faster" if as_factor else f"ratio {fmt_ratio(b[1])}"
            rows.append(f"  - {dataset} `{op}`: best tpx_{b[0]} {shown} → {verdict(ok)}")
        return [f"{title}: {verdict(ok_all)}"] + (rows or ["  - no results"])

    out += speed_aim(
        "2. Co-boundary of every vertex ≥ 20× faster than GUDHI cofaces (`cofaces_v`, best kind)",
        lambda p, d: p == "gudhi", "cofaces_v", "gudhi", 1 / 20, as_factor=True,
    )
    out += speed_aim(
        "3. Vertex stars of tetrahedral meshes no slower than CGAL `incident_cells` (`star_cells`, best kind)",
        lambda p, d: p == "tets", "star_cells", "cgal_t3", 1.0,
    )
    walk_rows, walk_ok = [], None
    for op in ("VF", "VV", "FF"):
        part = speed_aim("", lambda p, d: p == "surface", op, "openmesh", 1.0)
        walk_rows += part[1:]
        v = {"**met**": True, "**not met**": False}.get(part[0].split(": ")[-1])
        if v is not None:
            walk_ok = v if walk_ok is None else walk_ok and v
    out.append(f"4. VF/VV/FF walks over a triangle mesh no slower than OpenMesh circulators (best kind): {verdict(walk_ok)}")
    out += walk_rows or ["  - no results"]

    # 5. Build time per simplex flat (±30 % of its mean over the family's sizes), per kind.
    out.append(
        "5. Build time per simplex flat (every size within ±30 % of the mean over the family's "
        "sizes, 10^4 … 10^6; from the family's own program, `build`):"
    )
    series: dict[tuple[str, str], list[tuple[int, float]]] = defaultdict(list)
    for (program, dataset), ops in results.items():
        fam = family(dataset)
        if NATIVE.get(fam) != program or "build" not in ops:
            continue
        for lib, r in ops["build"].items():
            if r.ns_per_elem is not None:
                series[(fam, lib)].append((size_of(dataset), r.ns_per_elem))
    flat_all = None
    for (fam, lib), pts in sorted(series.items()):
        pts.sort()
        if len(pts) < 2:
            continue
        mean = statistics.fmean(v for _, v in pts)
        flat = all(0.7 * mean <= v <= 1.3 * mean for _, v in pts)
        if lib.startswith("tpx_"):
            flat_all = flat if flat_all is None else flat_all and flat
        vals = ", ".join(f"{n:,}: {v:.3g}" for n, v in pts)
        tag = verdict(flat) if lib.startswith("tpx_") else "(peer, for reference)"
        out.append(f"  - {fam} {lib}: ns/simplex {vals} → {tag}")
    out.append(f"  - all Topoplex kinds: {verdict(flat_all)}")
    out += handle_aims(results)
    return out


# Topoplex-only forms of a walk, compared with the peer's walk of the plain op: one batch call
# over every simplex, and per-query answers read inline from a lent relation view.
FORMS = ("_batch", "_view")
# Whole-mesh passes of issue 13 (their `_view` form reads an index built outside the timing).
WHOLE_PASSES = ("stats", "FF_index")


def handle_aims(results) -> list[str]:
    """Issue 13: the handle API per op against each peer, best kind over the per-call walk
    (`op`), the batch form (`op_batch`) and the lent view (`op_view`), each compared with the
    peer's per-element walk."""
    out = ["", "### Aims of issue 13 (handles)", ""]
    aims13 = [
        ("surface", "VF", ("openmesh", "cgal_sm"), 0.8),
        ("surface", "VV", ("openmesh", "cgal_sm"), 0.8),
        ("surface", "FF", ("openmesh", "cgal_sm"), 0.8),
        ("tets", "star_cells", ("cgal_t3",), 0.8),
        ("tets", "star_edges", ("cgal_t3",), 0.8),
        ("surface", "stats", ("openmesh",), 1.0),
        ("surface", "FF_index", ("openmesh",), 1.0),
    ]
    for program, op, peers, limit in aims13:
        for peer in peers:
            rows, ok_all = [], None
            for (prog, dataset), ops in sorted(results.items(), key=lambda kv: (family(kv[0][1]), size_of(kv[0][1]))):
                if prog != program or op not in ops or peer not in ops[op]:
                    continue
                best = None
                # A whole-mesh pass pays for its index: judged per call and in batch form (the
                # index built inside the timed loop), not through a view built beforehand.
                forms = ("_batch",) if op in WHOLE_PASSES else FORMS
                for form in (op,) + tuple(op + f for f in forms):
                    if form not in ops:
                        continue
                    libs = dict(ops[form])
                    libs[peer] = ops[op][peer]
                    b = best_over(libs, peer)
                    if b is not None and (best is None or b[1] < best[2]):
                        best = (b[0], form, b[1])
                if best is None:
                    continue
                ok = best[2] <= limit
                ok_all = ok if ok_all is None else ok_all and ok
                rows.append(f"  - {dataset}: best tpx_{best[0]} `{best[1]}` ratio {fmt_ratio(best[2])} → {verdict(ok)}")
            out.append(f"- `{op}` ≤ {limit}× {peer}: {verdict(ok_all)}")
            out += rows or ["  - no results"]
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results", type=Path)
    ap.add_argument("--datasets", type=Path, help="datasets.tsv from the dataset maker")
    ap.add_argument("--cpu", action="store_true",
                    help="ratios from CPU time (a loaded or shared machine), not wall time")
    args = ap.parse_args()
    global USE_CPU_TIME
    USE_CPU_TIME = args.cpu
    results = load_results(args.results)
    if not results:
        print(f"no `<program>__<dataset>.json` results in {args.results}", file=sys.stderr)
        return 1
    sizes = {}
    if args.datasets and args.datasets.exists():
        for line in args.datasets.read_text().splitlines()[1:]:
            f = line.split("\t")
            if len(f) >= 4:
                sizes[f[0]] = f"{int(f[2]):,} ({f[3]})"
    lines = main_table(results, kinds_in(results), sizes)
    lines += aims(results)
    lines += simplify_table(results)
    lines += contract_table(results)
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
