"""Relations against GUDHI's SimplexTree (an oracle we did not write): co-faces, stars and
boundaries of every simplex, on random complexes to dimension 6; and the round trip."""

import pytest
from hypothesis import given

import topoplex
from oracle import blocks_of, complexes

gudhi = pytest.importorskip("gudhi")


def tree_of(tops):
    st = gudhi.SimplexTree()
    for t in tops:
        st.insert(sorted(t))
    return st


@pytest.mark.parametrize("kind", ["ig", "sig", "iqm", "iastar"])
@given(complexes(max_dim=6))
def test_cofaces_stars_and_boundaries_equal_gudhi_simplex_tree(kind, drawn):
    tops, n = drawn
    used = sorted({v for t in tops for v in t})
    st = tree_of(tops)
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    s = c.build(kind)
    rows = [s.simplices(p) for p in range(s.dimension + 1)]
    assert st.dimension() == s.dimension
    for p in range(s.dimension + 1):
        gudhi_p = sorted(tuple(x) for x, _ in st.get_skeleton(p) if len(x) == p + 1)
        mine = [tuple(r) for r in rows[p].tolist()]
        if p == 0:
            mine = [r for r in mine if r[0] in used]
        assert mine == gudhi_p
        for q in range(s.dimension + 1):
            if q == p:
                continue
            off, ids = s.relation(p, q)
            for i, simplex in enumerate(rows[p].tolist()):
                if p == 0 and simplex[0] not in used:
                    continue
                got = sorted(tuple(rows[q][j].tolist()) for j in ids[off[i] : off[i + 1]])
                if q > p:
                    want = sorted(
                        tuple(x) for x, _ in st.get_cofaces(simplex, q - p)
                    )
                    star = sorted(tuple(x) for x, _ in st.get_star(simplex) if len(x) == q + 1)
                    assert got == want == star
                elif q == p - 1:
                    want = sorted(tuple(x) for x, _ in st.get_boundaries(simplex))
                    assert got == want


@given(complexes(max_dim=5))
def test_gudhi_round_trip_keeps_every_simplex(drawn):
    tops, n = drawn
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    st = c.to_gudhi()
    back = topoplex.from_gudhi(st, n_vertices=n)
    assert back.census() == c.census()
    for p in range(c.dimension + 1):
        assert back.simplices(p).tolist() == c.simplices(p).tolist()
