"""Every relation of every structure and of the live mesh against the brute-force oracle, on
random non-manifold complexes up to dimension 6."""

import numpy as np
import pytest
from hypothesis import given, strategies as st

import topoplex
from oracle import Oracle, blocks_of, complexes

KINDS = topoplex.structure_names()
# The kinds whose domain is every complex: they must never refuse.
ANY_COMPLEX = {"ig", "sig", "iqm", "iastar"}


def structure_or_refusal(c, kind):
    try:
        return c.build(kind)
    except topoplex.DomainError as e:
        assert kind not in ANY_COMPLEX, f"{kind} refused: {e}"
        assert kind in str(e)
        return None


def check_against_oracle(s, o):
    assert s.dimension == o.dim
    for p in range(o.dim + 1):
        assert s.count(p) == o.count(p)
        assert s.simplices(p).tolist() == [list(x) for x in o.by_dim[p]]
        for q in range(o.dim + 1):
            off, ids = s.relation(p, q)
            eoff, eids = o.csr(p, q)
            assert off.tolist() == eoff.tolist(), (s.kind, p, q)
            assert ids.tolist() == eids.tolist(), (s.kind, p, q)
            assert s.degree(p, q).tolist() == np.diff(eoff).tolist(), (s.kind, p, q)


@pytest.mark.parametrize("kind", KINDS)
@given(complexes(max_dim=6))
def test_every_relation_of_each_structure_equals_the_oracle_on_random_complexes(kind, drawn):
    tops, n = drawn
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    s = structure_or_refusal(c, kind)
    if s is None:
        return
    s.validate()
    check_against_oracle(s, Oracle(tops, n))


@given(complexes(max_dim=5), st.data())
def test_relation_of_a_subset_and_locate_agree_with_the_oracle(drawn, data):
    tops, n = drawn
    o = Oracle(tops, n)
    s = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n).build("sig")
    p = data.draw(st.integers(0, o.dim))
    q = data.draw(st.integers(0, o.dim))
    sel = data.draw(st.lists(st.integers(0, o.count(p) - 1), max_size=6))
    off, ids = s.relation(p, q, simplices=np.array(sel, dtype=np.int64))
    eoff, eids = o.csr(p, q, sel)
    assert off.tolist() == eoff.tolist() and ids.tolist() == eids.tolist()
    assert s.degree(p, q, simplices=sel).tolist() == np.diff(eoff).tolist()
    # locate: every simplex, with its vertices reversed, finds its own row.
    rows = s.simplices(p)
    assert s.locate(rows[:, ::-1]).tolist() == list(range(len(rows)))
    if len(rows):
        assert s.locate(rows[-1][::-1].copy()) == len(rows) - 1


@given(complexes(max_dim=4))
def test_the_complex_census_and_simplices_equal_the_oracle(drawn):
    tops, n = drawn
    o = Oracle(tops, n)
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    assert c.census()["simplices"] == [o.count(p) for p in range(o.dim + 1)]
    for p in range(o.dim + 1):
        assert c.simplices(p).tolist() == [list(x) for x in o.by_dim[p]]
        assert c.simplices(p).dtype == np.uint32


def test_the_three_input_forms_give_the_same_complex():
    tris = np.array([[0, 1, 2], [1, 2, 3]])
    edges = np.array([[3, 4]])
    a = topoplex.Complex.from_arrays([tris, edges])
    off = np.array([0, 3, 6, 8])
    ids = np.array([0, 1, 2, 1, 2, 3, 3, 4], dtype=np.uint32)
    b = topoplex.Complex.from_arrays((off, ids))
    for p in range(3):
        assert a.simplices(p).tolist() == b.simplices(p).tolist()
    assert a.census() == b.census() and a.census()["simplices"] == [5, 6, 2]


@given(st.integers(1, 5), st.integers(2, 9), st.data())
def test_one_array_passed_as_it_lies_gives_what_its_csr_gives(k, n, data):
    # One (m, k) array goes to the Rust call without offsets; the same rows as a CSR pair go
    # with them: the same complex (listing, simplices, census), or the same refusal.
    rows = data.draw(st.lists(st.lists(st.integers(0, n), min_size=k, max_size=k), max_size=8))
    arr = np.array(rows, dtype=np.int64).reshape(-1, k)
    csr = (np.arange(0, arr.size + 1, k, dtype=np.int64), arr.reshape(-1))
    try:
        want = topoplex.Complex.from_arrays(csr, n_vertices=n)
    except topoplex.InputError as e:
        with pytest.raises(topoplex.InputError) as got:
            topoplex.Complex.from_arrays(arr, n_vertices=n)
        assert str(got.value) == str(e)
        return
    got = topoplex.Complex.from_arrays(arr, n_vertices=n)
    assert got.census() == want.census()
    for a, b in zip(got.listed(), want.listed()):
        assert a.tolist() == b.tolist()
    for p in range(want.dimension + 1):
        assert got.simplices(p).tolist() == want.simplices(p).tolist()


def test_radial_order_around_a_non_manifold_edge_lists_its_three_triangles():
    c = topoplex.Complex.from_arrays(np.array([[0, 1, 2], [0, 1, 3], [0, 1, 4]]))
    for kind in ("ts", "pe", "de"):
        s = c.build(kind)
        cycles = s.radial(0, 1)
        got = sorted(int(i) for cyc in cycles for i in cyc)
        assert got == [0, 1, 2], kind


@given(complexes(max_dim=4))
def test_natural_order_holds_the_same_answers_as_sorted_order(drawn):
    tops, n = drawn
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    for kind in ("ig", "iastar"):
        s = c.build(kind)
        for p in range(c.dimension + 1):
            for q in range(c.dimension + 1):
                a_off, a = s.relation(p, q, order="natural")
                b_off, b = s.relation(p, q)
                assert a_off.tolist() == b_off.tolist()
                for i in range(len(a_off) - 1):
                    assert sorted(a[a_off[i]:a_off[i + 1]].tolist()) == b[b_off[i]:b_off[i + 1]].tolist()


@pytest.mark.parametrize("kind", ["ig", "ts", "pe", "de", "iastar"])
def test_fans_around_a_bowtie_vertex_are_its_two_wings_each_joined_through_edges(kind):
    # Vertex 0 pinches two wings of two triangles each: two fans.
    c = topoplex.Complex.from_arrays(np.array([[0, 1, 2], [0, 2, 3], [0, 4, 5], [0, 5, 6]]))
    s = c.build(kind)
    fans = [sorted(f.tolist()) for f in s.fans(0)]
    tris = s.simplices(2).tolist()
    wings = sorted(fans)
    assert [[tris[i] for i in w] for w in wings] == [[[0, 1, 2], [0, 2, 3]], [[0, 4, 5], [0, 5, 6]]]
    # Vertex 2 is inside one wing: one fan, its star.
    off, ids = s.relation(0, 2)
    assert [sorted(f.tolist()) for f in s.fans(2)] == [ids[off[2]:off[3]].tolist()]
