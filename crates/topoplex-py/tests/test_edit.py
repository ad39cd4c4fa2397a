"""Edits of the live mesh in numpy batches against the oracle: insert and remove top
simplices, contract with the link condition and split back, coordinates, compact's remap,
simplify."""

import numpy as np
import pytest
from hypothesis import event, given, strategies as st

import topoplex
from oracle import Oracle, blocks_of, closure, complexes


def tops_of(live):
    """The live mesh's top simplices as sorted tuples."""
    return sorted(tuple(sorted(r)) for block in live.live_tops() for r in block.tolist())


def oracle_tops(tops):
    faces = closure(tops)
    allf = {f for level in faces for f in level}
    # The live mesh's tops are of dimension >= 1 (an isolated vertex is a vertex with an
    # empty star).
    return sorted(
        f
        for f in allf
        if len(f) > 1 and not any(len(g) > len(f) and set(f) <= set(g) for g in allf)
    )


@given(complexes(max_vertices=8, max_dim=4), st.data())
def test_insert_then_remove_in_batches_matches_the_oracle(drawn, data):
    tops, n = drawn
    live = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n).live()
    extra = data.draw(
        st.lists(st.lists(st.integers(0, n - 1), min_size=2, max_size=4, unique=True), max_size=4)
    )
    current = [tuple(sorted(t)) for t in tops]
    for t in extra:
        t = tuple(sorted(t))
        if any(set(t) <= set(u) for u in oracle_tops(current)):
            continue  # a face of a simplex already there is refused, tested below
        live.insert([np.array(t)])
        current.append(t)
    live.validate()
    assert tops_of(live) == oracle_tops(current)
    o = Oracle(current, n)
    for p in range(o.dim + 1):
        for q in range(o.dim + 1):
            off, ids = live.relation(p, q)
            eoff, eids = o.csr(p, q)
            assert off.tolist() == eoff.tolist() and ids.tolist() == eids.tolist()
    # Remove half of the tops in one batch.
    now = oracle_tops(current)
    gone = now[::2]
    live.remove([np.array(g) for g in gone])
    live.validate()
    kept = [t for t in now if t not in gone]
    assert tops_of(live) == oracle_tops(kept)


def test_inserting_a_face_of_a_top_is_refused_and_changes_nothing():
    live = topoplex.Complex.from_arrays(np.array([[0, 1, 2]])).live()
    with pytest.raises(topoplex.EditRefused):
        live.insert(np.array([[0, 1]]))
    assert tops_of(live) == [(0, 1, 2)]
    with pytest.raises(ValueError):
        live.remove(np.array([[0, 3]]))


def grid_mesh(k=4):
    pts = np.array([[i, j, 0.0] for j in range(k) for i in range(k)])
    tris = []
    for j in range(k - 1):
        for i in range(k - 1):
            a = j * k + i
            tris += [[a, a + 1, a + k + 1], [a, a + k + 1, a + k]]
    return topoplex.Complex.from_arrays(np.array(tris), points=pts)


def test_contract_checks_the_link_condition_and_split_restores_exactly():
    c = grid_mesh()
    live = c.live()
    before = tops_of(live)
    # Interior edge (5, 6): link condition holds.
    assert live.can_contract(5, 6)
    undo = live.contract(np.array([[5, 6]]), positions=np.array([[1.5, 1.0, 0.0]]))
    live.validate()
    assert live.points[5].tolist() == [1.5, 1.0, 0.0]
    assert all(6 not in t for t in tops_of(live))
    assert len(tops_of(live)) == len(before) - 2
    live.split(undo[0])
    live.validate()
    assert tops_of(live) == before
    assert live.points[5].tolist() == [1.0, 1.0, 0.0]
    # Vertices 0 and 15 share no edge: refused with the link condition, allowed free.
    assert not live.can_contract(0, 15)
    with pytest.raises(topoplex.EditRefused):
        live.contract([[0, 15]])
    assert live.can_contract(0, 15, mode="free")


def test_compact_returns_the_remap_and_renumbers_densely():
    live = grid_mesh().live()
    live.contract([[5, 6]])
    remap = live.compact()
    v = remap["vertices"]
    assert v.dtype == np.uint32 and len(v) == 16
    assert v[6] == 2**32 - 1 and v[7] == 6 and v[5] == 5
    assert live.vertex_count == 15
    live.validate()


def test_set_points_whole_array_and_per_vertex():
    live = grid_mesh().live()
    pts = np.arange(48, dtype=float).reshape(16, 3)
    live.set_points(pts)
    assert np.array_equal(live.points, pts)
    live.set_points([[9.0, 9.0, 9.0]], vertices=[3])
    assert live.points[3].tolist() == [9.0, 9.0, 9.0]
    with pytest.raises(topoplex.EditRefused):
        live.set_points(np.zeros((3, 3)))


def test_simplify_reduces_tops_and_keeps_topology_when_asked():
    c = grid_mesh(6)
    out, stats = topoplex.simplify(c, 0.5, preserve_topology=True)
    assert stats["output_tops"] <= stats["input_tops"]
    assert out.count(2) < c.count(2)
    # Euler characteristic kept (a disc: 1).
    counts = out.census()["simplices"]
    assert counts[0] - counts[1] + counts[2] == 1
    live = c.live()
    s = topoplex.simplify(live, 0.5, preserve_topology=True)
    assert s["contractions"] > 0
    live.validate()


@given(complexes(max_vertices=8, max_dim=4), st.data())
def test_contracting_an_edge_gives_the_oracles_image_complex_and_split_undoes_it(drawn, data):
    tops, n = drawn
    o = Oracle(tops, n)
    if o.dim < 1 or not o.by_dim[1]:
        return
    a, b = data.draw(st.sampled_from(o.by_dim[1]))
    live = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n).live()
    mode = data.draw(st.sampled_from(["topology", "free"]))
    allowed = live.can_contract(a, b, mode)
    event(f"{mode}: {'contracted' if allowed else 'refused'}")
    if not allowed:
        with pytest.raises(topoplex.EditRefused):
            live.contract([[a, b]], mode=mode)
        return
    (undo,) = live.contract([[a, b]], mode=mode)
    live.validate()
    images = [tuple(sorted({a if v == b else v for v in t})) for t in tops]
    assert tops_of(live) == oracle_tops(images)
    # The live mesh names vertices by id: b's slot is a tombstone until compact(), skipped
    # by simplices(0) and by the rows of relation(0, q).
    after = Oracle(images, n)
    alive = [v for v in range(n) if v != b]
    assert live.simplices(0).ravel().tolist() == alive
    for q in range(after.dim + 1):
        off, ids = live.relation(0, q)
        eoff, eids = after.csr(0, q, alive)
        assert off.tolist() == eoff.tolist() and ids.tolist() == eids.tolist()
        assert live.degree(0, q).tolist() == np.diff(eoff).tolist()
    for p in range(1, after.dim + 1):
        assert live.simplices(p).tolist() == [list(x) for x in after.by_dim[p]]
        for q in range(after.dim + 1):
            off, ids = live.relation(p, q)
            eoff, eids = after.csr(p, q)
            assert off.tolist() == eoff.tolist() and ids.tolist() == eids.tolist()
    live.split(undo)
    live.validate()
    assert tops_of(live) == oracle_tops(tops)


def test_the_live_mesh_carries_vertex_data_through_a_contraction():
    c = grid_mesh().with_attribute("id", "vertices", np.arange(16, dtype=np.int64))
    live = c.live()
    live.contract([[5, 6]])
    where, ids = live.attributes["id"]
    # Vertex 6 is gone; the others keep their values in the renumbered complex.
    assert where == "vertices" and ids.tolist() == [v for v in range(16) if v != 6]
