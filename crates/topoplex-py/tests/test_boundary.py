"""Boundary matrices as scipy.sparse: ∂∂ = 0 over Z/2 and signed, each column the faces the
oracle gives, signs from the ascending order and the kept winding."""

import numpy as np
import pytest
from hypothesis import given

import topoplex
from oracle import Oracle, blocks_of, complexes

pytest.importorskip("scipy")


@given(complexes(max_dim=6))
def test_boundary_of_boundary_is_zero_over_z2_and_signed(drawn):
    tops, n = drawn
    o = Oracle(tops, n)
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    s = c.build("iastar")
    for p in range(1, o.dim + 1):
        z2 = s.boundary_matrix(p)
        assert z2.shape == (o.count(p - 1), o.count(p))
        # Column j holds exactly the facets of p-simplex j.
        dense = z2.toarray()
        for j, simplex in enumerate(o.by_dim[p]):
            assert np.flatnonzero(dense[:, j]).tolist() == o.related(p, p - 1, simplex)
        signed = s.boundary_matrix(p, signed=True)
        assert (abs(signed.toarray()) == dense).all()
        if p >= 2:
            assert ((s.boundary_matrix(p - 1) @ z2).toarray() % 2 == 0).all()
            assert ((s.boundary_matrix(p - 1, signed=True) @ signed).toarray() == 0).all()


def test_signed_boundary_follows_the_winding_of_a_top_triangle():
    # [0 2 1] is an odd permutation of [0 1 2]: its column is negated.
    c = topoplex.Complex.from_arrays(np.array([[0, 2, 1], [1, 2, 3]]))
    s = c.build("ig")
    assert s.winding(2).tolist() == [-1, 1]
    b = s.boundary_matrix(2, signed=True).toarray()
    # Edges in order: 01 02 12 13 23. ∂[0 1 2] = [1 2] - [0 2] + [0 1].
    assert b[:, 0].tolist() == [-1, 1, -1, 0, 0]
    assert b[:, 1].tolist() == [0, 0, 1, -1, 1]
