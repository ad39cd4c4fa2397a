#!/usr/bin/env python3
"""The Python package's benchmarks (issue 28), side by side; a measuring script, not a test.

  build    Complex.from_arrays of a 10^7-triangle numpy array (a 2236×2236 grid of squares)
           against the Rust call doing the same on the same rows in memory (Complex::from_uniform,
           examples/grid_build.rs):
           time and peak resident memory of the call, each side in fresh processes (best time,
           median peak of --runs); the peak is VmHWM after resetting it once the input is made,
           so the input is counted on both sides and its making on neither.
  stars    every vertex's star: Topoplex's relation(0, d) (and R_{0,q} for every q, the whole
           star as GUDHI gives it) against a Python loop of GUDHI's SimplexTree.get_star([v]) on
           the same Rips and alpha complexes (GUDHI on every --stride-th vertex above 20,000
           vertices, its time scaled to all of them: marked "~").
  adjacency  the face adjacency of a ~1.2M-triangle mesh: Structure.adjacency(2) of the live
           mesh (made into trimesh's (n, 2) pairs) against trimesh's face_adjacency from the same
           arrays (a fresh Trimesh each run, process=False), on the mesh and on the mesh with
           "fins" (a triangle on every 50th triangle's first edge: non-manifold edges), and on
           ../shared/data's truck.obj; with the adjacencies trimesh drops (pairs of triangles
           sharing an edge, counted from the edges themselves).
  threads  two Python threads against one: queries per second of relation(0, 2) on the mesh's
           `ia` (TOPOPLEX_THREADS=1 in a child process, so each call runs on its own thread).
  import   `import topoplex` in a fresh interpreter (median of 15; numpy's import alone beside it).
  wheel    with --wheel: the size of the release wheel `maturin build --release` makes.

usage: scripts/bench_py.py [--quick] [--only NAME,...] [--runs N] [--rust-bin PATH]
                           [--data DIR] [--shared DIR] [--wheel] [--out FILE.md]
Needs the package installed in the running Python (scripts/py-tests.sh's venv, built with
`maturin develop --release` for numbers to publish), gudhi and trimesh, and the Rust side built
the same way: `cargo build --release --example grid_build` (--rust-bin; default
target/release/examples/grid_build). Data: --data (default /work/bench-data, else
$TOPOPLEX_BENCH_DATA) holds surf-bunny00-1206528.off, rips-kitten-*.simplices and
alpha-*.simplices (scripts/bench.sh makes them); missing files are skipped with a note.
"""

import argparse
import os
import statistics
import subprocess
import sys
import threading
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def status_bytes(key):
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(key):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def best(f, runs):
    """The best wall time of `runs` calls of f, and its last result."""
    times, out = [], None
    for _ in range(runs):
        t = time.perf_counter()
        out = f()
        times.append(time.perf_counter() - t)
    return min(times), out


def mib(b):
    return f"{b / 2**20:.0f} MiB"


# ---- build: one measurement per process ----


def grid(k):
    """The rows examples/grid_build.rs makes, in its order: per square (i, j), a = j(K+1) + i,
    the triangles [a, a+1, a+K+2] and [a, a+K+2, a+K+1]."""
    w = k + 1
    j, i = np.divmod(np.arange(k * k, dtype=np.uint32), np.uint32(k))
    a = j * np.uint32(w) + i
    tris = np.empty((2 * k * k, 3), dtype=np.uint32)
    tris[0::2, 0], tris[0::2, 1], tris[0::2, 2] = a, a + 1, a + w + 1
    tris[1::2, 0], tris[1::2, 1], tris[1::2, 2] = a, a + w + 1, a + w
    return tris


def child_build(k):
    import topoplex

    tris = grid(k)
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass
    before = status_bytes("VmRSS:")
    t = time.perf_counter()
    c = topoplex.Complex.from_arrays(tris, n_vertices=(k + 1) ** 2)
    dt = time.perf_counter() - t
    print(f"triangles {tris.shape[0]} rss_before_bytes {before} complex_s {dt:.4f} "
          f"peak_bytes {status_bytes('VmHWM:')} tops {c.census()['tops'][2]}")


def parse(line):
    f = line.split()
    return {f[i]: float(f[i + 1]) for i in range(0, len(f) - 1, 2)}


def bench_build(a, out):
    k = 500 if a.quick else 2236
    rust = a.rust_bin or os.path.join(ROOT, "target", "release", "examples", "grid_build")
    if not os.path.exists(rust):
        out.append(f"build: skipped, no Rust side at {rust} (cargo build --release --example grid_build)")
        return
    sides = {
        "Rust Complex::from_uniform": [rust, str(k)],
        "Python Complex.from_arrays": [sys.executable, os.path.abspath(__file__), "--child-build", str(k)],
    }
    got = {}
    for name, cmd in sides.items():
        rows = [parse(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
                for _ in range(a.runs)]
        got[name] = rows
    out.append(f"### build: {int(got['Rust Complex::from_uniform'][0]['triangles']):,} triangles "
               f"(a {k}×{k} grid), {a.runs} fresh processes per side\n")
    out.append("| side | best time | median peak RSS of the call (input included) | RSS before |")
    out.append("|---|---|---|---|")
    for name, rows in got.items():
        t = min(r["complex_s"] for r in rows)
        peak = statistics.median(r["peak_bytes"] for r in rows)
        before = statistics.median(r["rss_before_bytes"] for r in rows)
        out.append(f"| {name} | {t:.3f} s | {mib(peak)} | {mib(before)} |")
    r, p = got["Rust Complex::from_uniform"], got["Python Complex.from_arrays"]
    tr, tp = min(x["complex_s"] for x in r), min(x["complex_s"] for x in p)
    # Each side's peak less its process's own baseline (the RSS before the call less the input,
    # the same 12 bytes a triangle on both sides: what remains is the interpreter, numpy and the
    # module on Python's side): the input and what the call adds.
    n = r[0]["triangles"]
    inputs = {"r": 12 * n, "p": 12 * n}
    nr = statistics.median(x["peak_bytes"] - (x["rss_before_bytes"] - inputs["r"]) for x in r)
    np_ = statistics.median(x["peak_bytes"] - (x["rss_before_bytes"] - inputs["p"]) for x in p)
    out.append(f"\nPython / Rust: time {tp / tr:.3f}× (aim ≤ 1.05×); peak net of each process's own "
               f"baseline (RSS before the call less the input) {mib(np_)} / {mib(nr)} = {np_ / nr:.3f}× "
               f"(aim ≤ 1.05×); whole-process peaks {statistics.median(x['peak_bytes'] for x in p) / statistics.median(x['peak_bytes'] for x in r):.3f}× "
               f"(the interpreter and numpy included).\n")


# ---- stars ----


def bench_stars(a, out):
    import gudhi  # noqa: F401
    import topoplex

    names = ["rips-kitten-10000.simplices", "alpha-kitten-10162.simplices"]
    if not a.quick:
        names += ["rips-kitten-100000.simplices", "alpha-building-143651.simplices"]
    out.append("### stars: every vertex's star, Topoplex against a Python loop of GUDHI's get_star\n")
    out.append("| complex | vertices | dim | kind | relation(0, d) | whole star (R_{0,q}, q = 1..d) "
               "| GUDHI get_star loop | GUDHI / whole star | GUDHI / relation(0, d) |")
    out.append("|---|---|---|---|---|---|---|---|---|")
    for name in names:
        path = os.path.join(a.data, name)
        if not os.path.exists(path):
            out.append(f"| {name} | missing | | | | | | | |")
            continue
        c = topoplex.read(path)
        d, n = c.dimension, c.vertex_count
        st = c.to_gudhi()
        stride = 1 if n <= 20000 else a.stride
        vs = range(0, n, stride)
        t = time.perf_counter()
        for v in vs:
            st.get_star([v])
        tg = (time.perf_counter() - t) * (n / len(vs))
        approx = "~" if stride > 1 else ""
        for kind in ("ig", "sig", "iastar"):
            s = c.build(kind)
            t1, _ = best(lambda: s.relation(0, d), a.runs)
            tw, _ = best(lambda: [s.relation(0, q) for q in range(1, d + 1)], a.runs)
            out.append(f"| {name} | {n:,} | {d} | {kind} | {t1 * 1e3:.1f} ms | {tw * 1e3:.1f} ms | "
                       f"{approx}{tg:.2f} s | {approx}{tg / tw:.0f}× | {approx}{tg / t1:.0f}× |")
    out.append("\nAim: ≥ 100× faster than the GUDHI loop. GUDHI's get_star lists every coface "
               "(all dimensions, with filtrations): compare it with the whole star; `ig` stores every "
               "simplex (as the SimplexTree does), `sig` and `iastar` only the tops, so their lower "
               "R_{0,q} name faces by dense index at a cost.\n")


# ---- adjacency ----


def edge_pairs(faces):
    """Every pair of triangles sharing an edge, from the edges themselves: the pairs of the
    edges in two triangles and those of the edges in more, as sets of (smaller, larger)
    triangle indices, and the number of edges in more than two triangles."""
    e = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2).astype(np.int64), axis=1)
    key = e[:, 0] << 32 | e[:, 1]
    order = np.argsort(key, kind="stable")
    key, tri = key[order], order // 3
    starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    sizes = np.diff(np.r_[starts, key.size])
    two = starts[sizes == 2]
    manifold = set(map(tuple, np.sort(np.stack([tri[two], tri[two + 1]], axis=1), axis=1).tolist()))
    more = set()
    for s, k in zip(starts[sizes > 2], sizes[sizes > 2]):
        t = sorted(tri[s:s + k].tolist())
        more.update((t[x], t[y]) for x in range(k) for y in range(x + 1, k))
    return manifold, more, int((sizes > 2).sum())


def as_pairs(adj):
    """Structure.adjacency's manifold entries as trimesh's pairs (i < j, each once)."""
    import topoplex

    rows = np.repeat(np.arange(adj.shape[0], dtype=np.int64), adj.shape[1])
    other = adj.reshape(-1).astype(np.int64)
    keep = (other < topoplex.ACROSS_MANY) & (rows < other)
    return np.stack([rows[keep], other[keep]], axis=1)


def with_fins(faces, pts, every=50):
    """A triangle on the first edge of every `every`-th triangle, to a new vertex beside it."""
    sel = faces[::every]
    new = np.arange(pts.shape[0], pts.shape[0] + sel.shape[0])
    fins = np.stack([sel[:, 0], sel[:, 1], new], axis=1)
    far = pts[sel[:, 2]] + (pts[sel[:, 0]] - pts[sel[:, 2]]) * 0.5
    return np.concatenate([faces, fins]), np.concatenate([pts, far])


def bench_adjacency(a, out):
    import topoplex
    import trimesh

    meshes = []
    bunny = os.path.join(a.data, "surf-bunny00-1206528.off" if not a.quick else "surf-elephant-88928.off")
    if os.path.exists(bunny):
        c = topoplex.read(bunny)
        faces, pts = np.ascontiguousarray(c.tops(2)), c.points
        meshes.append((os.path.basename(bunny), faces, pts))
        meshes.append((os.path.basename(bunny) + " + fins", *with_fins(faces, pts)))
    truck = os.path.join(a.shared, "nonmanifold", "truck.obj")
    if os.path.exists(truck):
        c = topoplex.read(truck)
        meshes.append(("truck.obj", np.ascontiguousarray(c.tops(2)), c.points))
    out.append("### adjacency: face adjacency, Topoplex against trimesh's face_adjacency\n")
    out.append("| mesh | triangles | edges in > 2 triangles | Topoplex adjacency(2) → pairs | "
               "from the array (complex, live, adjacency) | trimesh face_adjacency | trimesh / Topoplex "
               "| pairs: all / trimesh / dropped by trimesh |")
    out.append("|---|---|---|---|---|---|---|---|")
    for name, faces, pts in meshes:
        manifold, more, nm_edges = edge_pairs(faces)

        def topo_from_array():
            live = topoplex.Complex.from_arrays(faces, points=pts).live()
            return live, as_pairs(live.adjacency(2))

        te, (live, _) = best(topo_from_array, a.runs)
        # The adjacency alone, on a fresh live mesh each run (the first call after a build
        # makes the index).
        times = []
        for _ in range(a.runs):
            live = topoplex.Complex.from_arrays(faces, points=pts).live()
            rows = live.live_tops()[2]
            t = time.perf_counter()
            mine = as_pairs(live.adjacency(2))
            times.append(time.perf_counter() - t)
        ta = min(times)
        # Topoplex's rows are its live tops: map them back to the input's triangle order.
        index = {tuple(sorted(r)): i for i, r in enumerate(faces.tolist())}
        back = np.array([index[tuple(sorted(r))] for r in rows.tolist()], dtype=np.int64)
        mine = np.sort(back[mine], axis=1)

        def tm():
            m = trimesh.Trimesh(vertices=pts, faces=faces, process=False)
            return m.face_adjacency

        tt, theirs = best(tm, a.runs)
        theirs = np.sort(theirs.astype(np.int64), axis=1)
        all_pairs = manifold | more
        tp, kp = set(map(tuple, theirs.tolist())), set(map(tuple, mine.tolist()))
        many = int((live.adjacency(2) == topoplex.ACROSS_MANY).sum())
        # Topoplex's pairs are exactly those of the edges in two triangles.
        assert kp == manifold, (len(kp), len(manifold))
        out.append(f"| {name} | {faces.shape[0]:,} | {nm_edges:,} | {ta * 1e3:.0f} ms | {te * 1e3:.0f} ms | "
                   f"{tt * 1e3:.0f} ms | {tt / ta:.1f}× | {len(all_pairs):,} / {len(tp & all_pairs):,} / "
                   f"{len(all_pairs - tp):,} |")
        out.append(f"|  | | | (manifold pairs {len(kp):,}; facets marked ACROSS_MANY: {many:,}) | | | | |")
    out.append("\nAim: ≥ 3× faster than trimesh. Topoplex's pairs are those of the edges in two "
               "triangles (checked equal to the edges' own); a non-manifold edge is marked "
               "ACROSS_MANY on each of its triangles (its triangles: relation(1, 2)); the last "
               "column counts the pairs of triangles sharing an edge that trimesh's pairs leave out.\n")


# ---- threads ----


def child_threads(path, calls):
    import topoplex

    s = topoplex.read(path).build("ia")
    s.relation(0, 2)

    def work(k):
        for _ in range(k):
            s.relation(0, 2)

    t = time.perf_counter()
    work(calls)
    one = calls / (time.perf_counter() - t)
    ts = [threading.Thread(target=work, args=(calls,)) for _ in range(2)]
    t = time.perf_counter()
    for x in ts:
        x.start()
    for x in ts:
        x.join()
    two = 2 * calls / (time.perf_counter() - t)
    print(f"one {one:.3f} two {two:.3f}")


def bench_threads(a, out):
    path = os.path.join(a.data, "surf-bunny00-1206528.off" if not a.quick else "surf-elephant-88928.off")
    if not os.path.exists(path):
        out.append(f"threads: skipped, {path} missing")
        return
    env = dict(os.environ, TOPOPLEX_THREADS="1")
    rows = []
    for _ in range(a.runs):
        r = subprocess.run([sys.executable, os.path.abspath(__file__), "--child-threads", path,
                            str(4 if a.quick else 8)], check=True, capture_output=True, text=True, env=env)
        rows.append(parse(r.stdout))
    one = statistics.median(r["one"] for r in rows)
    two = statistics.median(r["two"] for r in rows)
    out.append(f"### threads: relation(0, 2) of every vertex of {os.path.basename(path)} (`ia`), "
               f"TOPOPLEX_THREADS=1\n")
    out.append("| one thread | two threads | speed-up (aim ≥ 1.8×) | cores |")
    out.append("|---|---|---|---|")
    out.append(f"| {one:.2f} calls/s | {two:.2f} calls/s | {two / one:.2f}× | {os.cpu_count()} |\n")


# ---- import time, wheel ----


def bench_import(a, out):
    def fresh(stmt):
        code = f"import time; t = time.perf_counter(); {stmt}; print(time.perf_counter() - t)"
        return statistics.median(
            float(subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                                 text=True).stdout) for _ in range(15))

    tn = fresh("import numpy")
    tt = fresh("import topoplex")
    out.append("### import (fresh interpreter, median of 15)\n")
    out.append("| import numpy | import topoplex (numpy included) | topoplex's own share | aim |")
    out.append("|---|---|---|---|")
    out.append(f"| {tn * 1e3:.0f} ms | {tt * 1e3:.0f} ms | {(tt - tn) * 1e3:.0f} ms | < 100 ms |\n")


def bench_wheel(a, out):
    import glob
    import shutil
    import tempfile

    d = tempfile.mkdtemp(prefix="topoplex-wheel-")
    try:
        subprocess.run(["maturin", "build", "--release", "-m",
                        os.path.join(ROOT, "crates", "topoplex-py", "Cargo.toml"), "--out", d],
                       check=True, capture_output=True)
        for w in glob.glob(os.path.join(d, "*.whl")):
            out.append(f"### wheel\n\n{os.path.basename(w)}: {os.path.getsize(w) / 2**20:.2f} MiB (aim ≤ 5 MB)\n")
    finally:
        shutil.rmtree(d, ignore_errors=True)


def main():
    if len(sys.argv) > 2 and sys.argv[1] == "--child-build":
        return child_build(int(sys.argv[2]))
    if len(sys.argv) > 3 and sys.argv[1] == "--child-threads":
        return child_threads(sys.argv[2], int(sys.argv[3]))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small inputs (a smoke run)")
    ap.add_argument("--only", default="build,stars,adjacency,threads,import")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--stride", type=int, default=10)
    ap.add_argument("--rust-bin")
    ap.add_argument("--data", default=os.environ.get("TOPOPLEX_BENCH_DATA", "/work/bench-data"))
    ap.add_argument("--shared", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--wheel", action="store_true")
    ap.add_argument("--out")
    a = ap.parse_args()
    if not os.path.isdir(os.path.join(a.shared, "nonmanifold")) and os.path.isdir("/work/shared/data"):
        a.shared = "/work/shared/data"
    out = [f"## Python package (indicative unless the machine was quiet)\n",
           f"Python {sys.version.split()[0]}, numpy {np.__version__}, {os.cpu_count()} cores, "
           f"TOPOPLEX_THREADS={os.environ.get('TOPOPLEX_THREADS', 'unset')}\n"]
    steps = {"build": bench_build, "stars": bench_stars, "adjacency": bench_adjacency,
             "threads": bench_threads, "import": bench_import}
    for name in a.only.split(","):
        print(f"== {name}", file=sys.stderr)
        steps[name](a, out)
    if a.wheel:
        bench_wheel(a, out)
    text = "\n".join(out) + "\n"
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)


if __name__ == "__main__":
    main()
