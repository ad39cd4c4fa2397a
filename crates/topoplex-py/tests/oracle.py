"""A brute-force oracle in pure Python: the closure of a list of simplices and every relation
R_{p,q}, computed from the definitions (README, "Relations") by enumerating subsets."""

from itertools import combinations

import numpy as np
from hypothesis import strategies as st


def closure(tops):
    """Every face of every simplex of `tops`, by dimension: a sorted list of sorted tuples."""
    faces = set()
    for t in tops:
        t = tuple(sorted(set(t)))
        for k in range(1, len(t) + 1):
            faces.update(combinations(t, k))
    dim = max((len(f) for f in faces), default=1) - 1
    return [sorted(f for f in faces if len(f) == p + 1) for p in range(dim + 1)]


class Oracle:
    """Relations of the closure of `tops` over vertices 0..n-1 (isolated vertices included)."""

    def __init__(self, tops, n):
        by_dim = closure(tops)
        verts = set(v for (v,) in by_dim[0]) if by_dim else set()
        by_dim[0] = [(v,) for v in range(n)]
        assert verts <= set(range(n))
        self.by_dim = by_dim
        self.index = [{s: i for i, s in enumerate(level)} for level in by_dim]
        self.dim = len(by_dim) - 1
        self.n = n

    def count(self, p):
        return len(self.by_dim[p]) if p <= self.dim else 0

    def related(self, p, q, s):
        """Sorted dense q-indices related to p-simplex tuple s."""
        S = set(s)
        if q < p:
            out = [self.index[q][f] for f in combinations(s, q + 1)]
        elif q > p:
            out = [i for i, t in enumerate(self.by_dim[q]) if S <= set(t)]
        elif p == 0:
            v = s[0]
            out = [w for (a, b) in self.by_dim[1] if v in (a, b) for w in (a, b) if w != v] if self.dim >= 1 else []
        else:
            out = [
                i
                for i, t in enumerate(self.by_dim[p])
                if t != s and len(S & set(t)) == p
            ]
        return sorted(set(out))

    def csr(self, p, q, selection=None):
        rows = self.by_dim[p] if selection is None else [self.by_dim[p][i] for i in selection]
        offsets = [0]
        ids = []
        for s in rows:
            r = self.related(p, q, s)
            ids.extend(r)
            offsets.append(len(ids))
        return np.array(offsets, dtype=np.int64), np.array(ids, dtype=np.uint32)


@st.composite
def complexes(draw, max_vertices=9, max_dim=6):
    """Random non-manifold, mixed-dimensional complexes: (tops as lists, vertex count). Some
    vertices may be isolated; tops may repeat or be faces of others (absorbed)."""
    n = draw(st.integers(min_value=2, max_value=max_vertices))
    k_max = min(max_dim + 1, n)
    simplex = st.lists(
        st.integers(min_value=0, max_value=n - 1), min_size=1, max_size=k_max, unique=True
    )
    tops = draw(st.lists(simplex, min_size=1, max_size=8))
    return tops, n


def blocks_of(tops):
    """The same simplices as a list of (m, k) arrays, one per size."""
    by = {}
    for t in tops:
        by.setdefault(len(t), []).append(t)
    return [np.array(v, dtype=np.int64) for _, v in sorted(by.items())]
