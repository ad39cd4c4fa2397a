"""Real complexes from ../shared/data (skipped when absent): every structure that accepts a
file gives the IG's answers for every relation, and the co-faces and boundaries of sampled
simplices equal GUDHI's SimplexTree's."""

import os
from pathlib import Path

import numpy as np
import pytest

import topoplex

DATA = Path(os.environ.get("TOPOPLEX_DATA", Path(__file__).resolve().parents[3].parent / "shared" / "data"))
FILES = [
    "nonmanifold/fan3.obj",
    "nonmanifold/tet.obj",
    "nonmanifold/hourglass_ico.obj",
    "nonmanifold/triple_vierbein.obj",
    "labelled/gmsh_t15.msh",
    "tetrahedral/octopus-low.mesh",
    "mixed/gmsh_baffles_wire.mesh",
    "mixed/alpha_kitten.simplices",
    "highdim/rips_hippo1.simplices",
]


def load(name):
    path = DATA / name
    if not path.exists():
        pytest.skip(f"{path} is absent")
    return topoplex.read(path)


@pytest.mark.parametrize("name", FILES)
def test_every_structure_gives_the_incidence_graphs_answers_on_real_data(name):
    c = load(name)
    ig = c.build("ig")
    built = 0
    for kind in topoplex.structure_names():
        try:
            s = c.build(kind)
        except topoplex.DomainError:
            continue
        built += 1
        for p in range(c.dimension + 1):
            assert np.array_equal(s.simplices(p), ig.simplices(p)), (kind, p)
            for q in range(c.dimension + 1):
                a, b = s.relation(p, q), ig.relation(p, q)
                assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]), (kind, p, q)
    assert built >= 4


@pytest.mark.parametrize("name", FILES)
def test_sampled_cofaces_and_boundaries_equal_gudhi_on_real_data(name):
    gudhi = pytest.importorskip("gudhi")
    c = load(name)
    st = gudhi.SimplexTree()
    for p in range(c.dimension + 1):
        for row in c.tops(p).tolist():
            st.insert(row)
    s = c.build("sig")
    rng = np.random.default_rng(5)
    rows = [s.simplices(p) for p in range(c.dimension + 1)]
    for p in range(c.dimension + 1):
        sample = rng.choice(len(rows[p]), size=min(40, len(rows[p])), replace=False)
        for q in range(c.dimension + 1):
            if q == p:
                continue
            off, ids = s.relation(p, q, simplices=sample)
            for k, i in enumerate(sample):
                simplex = rows[p][i].tolist()
                if p == 0 and st.find(simplex) is False:
                    continue  # a vertex of no simplex: GUDHI holds no such vertex
                got = sorted(tuple(rows[q][j].tolist()) for j in ids[off[k] : off[k + 1]])
                if q > p:
                    want = sorted(tuple(x) for x, _ in st.get_cofaces(simplex, q - p))
                elif q == p - 1:
                    want = sorted(tuple(x) for x, _ in st.get_boundaries(simplex))
                else:
                    continue
                assert got == want, (name, p, q, simplex)
