"""The co-faces of every vertex of a Rips complex, from topoplex's R_{0,d} in one call, next to
GUDHI's get_star in a Python loop (the same answers). Run: python examples/python/rips_cofaces.py"""

import time

import numpy as np

import topoplex

gudhi = __import__("gudhi")
pts = np.random.default_rng(1).random((300, 3))
st = gudhi.RipsComplex(points=pts, max_edge_length=0.2).create_simplex_tree(max_dimension=3)
c = topoplex.from_gudhi(st, n_vertices=len(pts))
s = c.build("iastar")
print("simplices per dimension:", c.census()["simplices"])

t = time.perf_counter()
offsets, ids = s.relation(0, 1)
mine = time.perf_counter() - t
t = time.perf_counter()
theirs = [sum(1 for x, _ in st.get_star([v]) if len(x) == 2) for v in range(len(pts))]
gudhi_s = time.perf_counter() - t
assert np.diff(offsets).tolist() == theirs
print(f"edges at every vertex: topoplex {mine * 1e3:.2f} ms, GUDHI get_star loop {gudhi_s * 1e3:.2f} ms")
