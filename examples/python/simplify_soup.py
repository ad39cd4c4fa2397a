"""Simplify a non-manifold triangle soup (a grid with a fin of triangles standing on one of its
edges) to a quarter of its triangles, keeping its topology (link condition).
Run: python examples/python/simplify_soup.py"""

import numpy as np

import topoplex

k = 20
pts = [[i, j, 0.0] for j in range(k) for i in range(k)]
tris = []
for j in range(k - 1):
    for i in range(k - 1):
        a = j * k + i
        tris += [[a, a + 1, a + k + 1], [a, a + k + 1, a + k]]
# The fin: a strip of triangles standing on the grid's middle row, sharing its edges.
row = (k // 2) * k
for i in range(k - 1):
    top = len(pts)
    pts.append([i + 0.5, k / 2, 1.0])
    tris.append([row + i, row + i + 1, top])
c = topoplex.Complex.from_arrays(np.array(tris), points=np.array(pts))
print("input:", c.census())
out, stats = topoplex.simplify(c, 0.25, preserve_topology=True)
print("output:", out.census())
print("stats:", stats)
v, e, f = out.census()["simplices"]
print("Euler characteristic kept:", v - e + f == c.census()["simplices"][0] - c.census()["simplices"][1] + c.census()["simplices"][2])
