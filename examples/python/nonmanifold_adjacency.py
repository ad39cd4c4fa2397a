"""Face adjacency of a triangle complex with non-manifold edges: topoplex's R_{2,2} lists every
pair of triangles sharing an edge, including the edges in three or more triangles, which
trimesh's face_adjacency leaves out. Run: python examples/python/nonmanifold_adjacency.py"""

import numpy as np

import topoplex

# A "book": five pages (triangles) bound along the edge [0 1], and one more triangle beside.
tris = np.array([[0, 1, 2], [0, 1, 3], [0, 1, 4], [0, 1, 5], [0, 1, 6], [1, 2, 7]])
pts = np.random.default_rng(0).random((8, 3))
c = topoplex.Complex.from_arrays(tris, points=pts)

ts = c.build("ts")
offsets, ids = ts.relation(2, 2)
pairs = {(i, int(j)) for i in range(ts.count(2)) for j in ids[offsets[i]:offsets[i + 1]] if i < j}
print(f"topoplex: {len(pairs)} adjacent triangle pairs")
degree = ts.degree(1, 2)
edges = ts.simplices(1)
print("non-manifold edges:", edges[degree > 2].tolist())
print("boundary edges:", len(edges[degree == 1]))

try:
    tm = c.to_trimesh()
    print(f"trimesh face_adjacency: {len(tm.face_adjacency)} pairs")
except ImportError:
    print("trimesh not installed")
