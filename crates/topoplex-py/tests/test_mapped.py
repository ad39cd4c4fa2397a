"""A complex opened from a saved .tpx file lends its arrays (points, attributes, the listing)
as read-only numpy views into the mapped file: the same bytes on every call, never writeable,
and alive as long as a view is, whatever happens to the complex's Python name."""

import gc
import weakref

import numpy as np
import pytest
from hypothesis import given, strategies as st

import topoplex
from oracle import blocks_of, complexes


def saved(tmp_path, structure=None):
    rng = np.random.default_rng(3)
    tets = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])
    c = topoplex.Complex.from_arrays([tets, np.array([[4, 5]])], points=rng.random((6, 3)))
    c = c.with_attribute("heat", "vertices", rng.random((6, 2)).astype(np.float32))
    c = c.with_attribute("region", "listed", np.array([7, -3, 2**40], dtype=np.int64))
    path = tmp_path / "m.tpx"
    topoplex.save(c, path, structure=structure)
    return c, path


def the_map(a):
    """The object at the end of a view's base chain: what owns its bytes."""
    while isinstance(a, np.ndarray) and a.base is not None:
        a = a.base
    return a.obj if isinstance(a, memoryview) else a


def test_points_attributes_and_listing_of_an_opened_file_are_read_only_views(tmp_path):
    c, path = saved(tmp_path)
    o = topoplex.open(path)
    assert isinstance(o, topoplex.Complex) and o.mapped and not c.mapped
    assert np.array_equal(o.points, c.points)
    for name, (where, values) in c.attributes.items():
        got_where, got = o.attributes[name]
        assert got_where == where and got.dtype == values.dtype
        assert np.array_equal(got, values)
    for got, want in zip(o.listed(), c.listed()):
        assert got.dtype == want.dtype and got.tolist() == want.tolist()
    views = [o.points, o.attributes["heat"][1], o.attributes["region"][1], *o.listed()]
    again = [o.points, o.attributes["heat"][1], o.attributes["region"][1], *o.listed()]
    owner = the_map(views[0])
    for a, b in zip(views, again):
        # Two calls view the same bytes (no copy), of one map, which nobody can write.
        assert np.shares_memory(a, b)
        assert the_map(a) is owner and the_map(b) is owner
        assert not a.flags.writeable
        with pytest.raises(ValueError):
            a.setflags(write=True)
    with pytest.raises(ValueError):
        views[0][0, 0] = 1.0
    # A complex made in memory hands out copies: two calls never share.
    assert not np.shares_memory(c.points, c.points)


def test_read_of_a_saved_file_and_a_structure_opened_from_it_view_the_file_too(tmp_path):
    c, path = saved(tmp_path, structure="ig")
    for got in (topoplex.read(path), topoplex.open(path).to_complex()):
        assert got.mapped and not got.points.flags.writeable
        assert np.array_equal(got.points, c.points)
    s = topoplex.open(path)
    assert s.kind == "ig" and not s.points.flags.writeable
    assert np.array_equal(s.points, c.points)
    assert np.array_equal(s.attributes["heat"][1], c.attributes["heat"][1])
    # The live mesh opened from a file is editable: its points are its own copy.
    live = topoplex.open(path, kind="iastar")
    assert live.points.flags.writeable


def test_a_view_outlives_the_name_of_its_complex_and_the_map_is_freed_last(tmp_path):
    c, path = saved(tmp_path)
    want_points = c.points.copy()
    want_ids = c.listed()[1].copy()
    o = topoplex.open(path)
    points = o.points
    ids = o.listed()[1]
    owner = weakref.ref(the_map(points))
    complex_gone = weakref.ref(o._c)
    del o
    gc.collect()
    # The complex is gone; its views still read the file's bytes through the map they hold.
    assert complex_gone() is None and owner() is not None
    assert np.array_equal(points, want_points) and ids.tolist() == want_ids.tolist()
    del points
    gc.collect()
    assert owner() is not None  # the other view still holds it
    assert ids.tolist() == want_ids.tolist()
    del ids
    gc.collect()
    assert owner() is None


@given(complexes(max_vertices=8, max_dim=5), st.integers(0, 3))
def test_random_complexes_open_with_views_equal_to_what_was_saved(tmp_path_factory, drawn, k):
    tops, n = drawn
    rng = np.random.default_rng(len(tops) * 31 + n)
    pts = rng.random((n, k)) if k else None
    c = topoplex.Complex.from_arrays(blocks_of(tops), points=pts, n_vertices=n)
    path = tmp_path_factory.mktemp("r") / "r.tpx"
    topoplex.save(c, path)
    o = topoplex.open(path)
    if k:
        assert o.points.shape == (n, k) and np.array_equal(o.points, pts)
        assert not o.points.flags.writeable
    else:
        assert o.points is None
    for got, want in zip(o.listed(), c.listed()):
        assert got.tolist() == want.tolist() and not got.flags.writeable
    assert o.census() == c.census()
