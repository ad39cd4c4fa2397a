"""The live mesh's attributes set by index (rows, or the whole array) and read back against a
brute-force model of the rows, across edits; and the live mesh's facet adjacency against a
brute-force adjacency on random non-manifold complexes."""

import numpy as np
import pytest
from hypothesis import given, strategies as st

import topoplex
from oracle import blocks_of, complexes

NONE, MANY = topoplex.ACROSS_NONE, topoplex.ACROSS_MANY


def with_data(tops, n):
    """A complex with a 2-component float vertex attribute and an int64 label on each listed
    simplex (the listed tops of dimension >= 1 are the live tops' rows)."""
    c = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n)
    off, _ = c.listed()
    c = c.with_attribute("xy", "vertices", np.arange(2.0 * n).reshape(n, 2))
    return c.with_attribute("label", "listed", np.arange(off.size - 1, dtype=np.int64) * 10)


@given(complexes(max_vertices=8, max_dim=4), st.data())
def test_vertex_values_set_by_row_and_whole_equal_a_brute_force_model(drawn, data):
    tops, n = drawn
    live = with_data(tops, n).live()
    model = {v: [2.0 * v, 2.0 * v + 1] for v in range(n)}
    assert live.vertex_values("xy").tolist() == [model[v] for v in range(n)]
    for _ in range(data.draw(st.integers(1, 4))):
        vs = data.draw(st.lists(st.integers(0, n - 1), min_size=1, max_size=n, unique=True))
        rows = data.draw(
            st.lists(
                st.lists(st.floats(-1e6, 1e6), min_size=2, max_size=2),
                min_size=len(vs),
                max_size=len(vs),
            )
        )
        live.set_vertex_values("xy", np.array(rows), vertices=vs)
        for v, r in zip(vs, rows):
            model[v] = r
        assert live.vertex_values("xy").tolist() == [model[v] for v in range(n)]
        some = sorted(vs)
        assert live.vertex_values("xy", vertices=some).tolist() == [model[v] for v in some]
    whole = np.array([[v, -v] for v in range(n)], dtype=float)
    live.set_vertex_values("xy", whole)
    assert live.vertex_values("xy").tolist() == whole.tolist()
    # to_complex carries them (no vertex removed: the same numbering).
    assert live.attributes["xy"][1].tolist() == whole.tolist()


def rows_of(live, p):
    """The live top p-simplices as sorted tuples, in the order of ``live_tops()[p]``."""
    by_dim = live.live_tops()
    return [tuple(sorted(t)) for t in by_dim[p].tolist()] if p < len(by_dim) else []


@given(complexes(max_vertices=8, max_dim=4), st.data())
def test_top_values_set_by_row_and_whole_equal_a_brute_force_model_across_edits(drawn, data):
    tops, n = drawn
    live = with_data(tops, n).live()
    dims = [p for p, t in enumerate(live.live_tops()) if p > 0 and t.shape[0]]
    if not dims:
        return
    p = data.draw(st.sampled_from(dims))
    # The model: top (sorted vertices) -> label.
    model = {
        tuple(sorted(t)): int(x)
        for t, x in zip(live.live_tops()[p].tolist(), live.top_values("label", p).tolist())
    }
    for _ in range(data.draw(st.integers(1, 3))):
        tops_now = rows_of(live, p)
        rows = data.draw(st.lists(st.integers(0, len(tops_now) - 1), min_size=1, unique=True))
        labels = data.draw(st.lists(st.integers(-2**40, 2**40), min_size=len(rows), max_size=len(rows)))
        live.set_top_values("label", p, np.array(labels, dtype=np.int64), rows=rows)
        for r, x in zip(rows, labels):
            model[tops_now[r]] = x
        # An edit: remove the first top; the others keep their rows.
        first = live.live_tops()[p][0]
        live.remove([first])
        del model[tuple(sorted(first.tolist()))]
        now = rows_of(live, p)
        if not now:
            return
        assert live.top_values("label", p).tolist() == [model[t] for t in now]
    whole = np.arange(len(now), dtype=np.int64) - 5
    live.set_top_values("label", p, whole)
    assert live.top_values("label", p).tolist() == whole.tolist()


def test_setting_attributes_checks_everything_first_and_changes_nothing_on_error():
    c = with_data([[0, 1, 2], [1, 2, 3]], 4)
    live = c.live()
    before = live.vertex_values("xy").copy()
    with pytest.raises(KeyError):
        live.set_vertex_values("nope", [[1.0, 2.0]], vertices=[0])
    with pytest.raises(topoplex.InputError):
        live.set_vertex_values("xy", [[1.0, 2.0, 3.0]], vertices=[0])  # 3 components for 2
    with pytest.raises(topoplex.InputError):
        live.set_vertex_values("xy", [[1.0, 2.0], [3.0, 4.0]], vertices=[0, 9])  # no vertex 9
    with pytest.raises(topoplex.InputError):
        live.set_vertex_values("xy", [[1.0, 2.0]], vertices=[0, 1])  # 1 row for 2 vertices
    assert live.vertex_values("xy").tolist() == before.tolist()
    labels = live.top_values("label", 2).copy()
    with pytest.raises(topoplex.InputError):
        live.set_top_values("label", 2, [1.5, 2.0])  # not whole numbers
    with pytest.raises(topoplex.InputError):
        live.set_top_values("label", 2, [1, 2], rows=[0, 2])  # 2 tops only
    with pytest.raises(topoplex.InputError):
        live.set_top_values("label", 2, np.array([2**60, 1], dtype=np.int64))  # beyond 2**53
    assert live.top_values("label", 2).tolist() == labels.tolist()
    with pytest.raises(topoplex.InputError):
        c.build("ia").set_vertex_values("xy", [[1.0, 2.0]], vertices=[0])  # not the live mesh
    live.contract([[1, 2]], mode="free")
    with pytest.raises(topoplex.InputError):
        live.vertex_values("xy", vertices=[2])  # contracted into 1: removed
    with pytest.raises(topoplex.InputError):
        live.set_vertex_values("xy", [[1.0, 2.0]], vertices=[2])


def brute_adjacency(rows):
    """For each top (row of vertices) and each of its vertices j, what lies across the facet
    opposite j among the other rows: NONE, the one row holding the facet, or MANY."""
    out = []
    for i, t in enumerate(rows):
        entry = []
        for j in range(len(t)):
            facet = set(t) - {t[j]}
            others = [k for k, u in enumerate(rows) if k != i and facet <= set(u)]
            entry.append(NONE if not others else others[0] if len(others) == 1 else MANY)
        out.append(entry)
    return out


@given(complexes(max_vertices=7, max_dim=4), st.booleans(), st.data())
def test_facet_adjacency_equals_brute_force_on_random_non_manifold_complexes(drawn, keep, data):
    tops, n = drawn
    live = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n).live()
    if keep:  # repaired by each edit rather than built again
        live.keep_adjacency()
    for step in range(3):
        by_dim = live.live_tops()
        for p in range(1, live.dimension + 1):
            adj = live.adjacency(p)
            assert adj.dtype == np.uint32 and adj.shape == (by_dim[p].shape[0], p + 1)
            assert adj.tolist() == brute_adjacency(by_dim[p].tolist())
        # An edit drops the index; the next call answers for the new state.
        k = min(3, n)
        extra = data.draw(st.lists(st.integers(0, n - 1), min_size=k, max_size=k, unique=True))
        try:
            live.insert([extra])
        except topoplex.EditRefused:
            first = [t for t in by_dim if t.shape[0]]
            live.remove([first[-1][0]])
        if live.dimension == 0:
            break


@given(complexes(max_vertices=7, max_dim=4), st.data())
def test_rings_equal_brute_force_on_random_non_manifold_complexes(drawn, data):
    tops, n = drawn
    live = topoplex.Complex.from_arrays(blocks_of(tops), n_vertices=n).live()
    for step in range(3):
        rows = [t for block in live.live_tops() for t in block.tolist()]
        off, ids, held = live.rings()
        assert off.dtype == np.int64 and ids.dtype == np.uint32 and held.dtype == np.uint32
        assert len(off) == n + 1 and off[-1] == len(ids) == len(held)
        for v in range(n):
            want = {}
            for t in rows:
                if v in t:
                    for w in t:
                        if w != v:
                            want[w] = want.get(w, 0) + 1
            got = list(zip(ids[off[v]:off[v + 1]].tolist(), held[off[v]:off[v + 1]].tolist()))
            assert sorted(got) == sorted(want.items()), f"ring of {v}"
        # An edit drops the rings; the next call answers for the new state.
        k = min(3, n)
        extra = data.draw(st.lists(st.integers(0, n - 1), min_size=k, max_size=k, unique=True))
        try:
            live.insert([extra])
        except topoplex.EditRefused:
            first = [t for t in live.live_tops() if t.shape[0]]
            live.remove([first[-1][0]])
        if live.dimension == 0:
            break


def test_adjacency_of_three_triangles_on_an_edge_is_many_and_of_a_strip_one():
    # Three triangles on edge [0 1] (non-manifold), and a fourth sharing [1 2] with the first.
    live = topoplex.Complex.from_arrays([[0, 1, 2], [0, 1, 3], [0, 1, 4], [1, 2, 5]]).live()
    rows = live.live_tops()[2].tolist()
    adj = live.adjacency(2).tolist()
    first = rows.index([0, 1, 2])
    # Opposite 2 is [0 1]: many; opposite 0 is [1 2]: the strip's other triangle.
    assert adj[first][2] == MANY
    assert adj[first][0] == rows.index([1, 2, 5])
    assert adj[first][1] == NONE
    with pytest.raises(topoplex.InputError):
        live.adjacency(0)
    with pytest.raises(topoplex.InputError):
        live.adjacency(3)
    with pytest.raises(topoplex.InputError):
        topoplex.Complex.from_arrays([[0, 1, 2]]).build("ia").adjacency(2)
