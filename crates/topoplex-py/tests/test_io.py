"""Files and converters: write/read, .tpx save/open, meshio and trimesh round trips."""

import os

import numpy as np
import pytest

import topoplex

TRIS = np.array([[0, 1, 2], [0, 2, 3], [0, 1, 4], [0, 1, 5]])
PTS = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0, 1], [0.5, 0, -1]], dtype=float
)


def fan():
    return topoplex.Complex.from_arrays([TRIS, np.array([[2, 3]])], points=PTS)


@pytest.mark.parametrize("ext", ["off", "obj", "ply", "vtk", "vtu", "msh", "simplices", "mesh"])
def test_write_then_read_gives_the_same_complex(tmp_path, ext):
    c = fan()
    path = tmp_path / f"m.{ext}"
    c.write(path)
    back = topoplex.read(path)
    for p in range(3):
        assert back.simplices(p).tolist() == c.simplices(p).tolist()
    if ext != "simplices":
        assert np.array_equal(back.points, PTS)


def test_save_and_open_give_the_structure_and_the_complex(tmp_path):
    c = fan()
    topoplex.save(c, tmp_path / "a.tpx", structure="ts")
    s = topoplex.open(tmp_path / "a.tpx")
    assert isinstance(s, topoplex.Structure) and s.kind == "ts"
    ref = c.build("ts")
    for q in range(3):
        for a, b in zip(s.relation(1, q), ref.relation(1, q)):
            assert a.tolist() == b.tolist()
    topoplex.save(c, tmp_path / "b.tpx")
    back = topoplex.open(tmp_path / "b.tpx")
    assert isinstance(back, topoplex.Complex) and back.census() == c.census()
    ig = topoplex.open(tmp_path / "b.tpx", kind="ig")
    assert ig.kind == "ig" and ig.count(1) == c.count(1)
    live = c.live()
    live.remove([[0, 1, 5]])
    topoplex.save(live, tmp_path / "live.tpx")
    again = topoplex.open(tmp_path / "live.tpx")
    assert again.kind == "iastar" and again.count(2) == 3


def test_meshio_round_trip_keeps_blocks_points_and_data():
    meshio = pytest.importorskip("meshio")
    tets = np.array([[0, 1, 2, 3]])
    mesh = meshio.Mesh(
        PTS,
        [("triangle", TRIS[1:]), ("tetra", tets), ("line", np.array([[4, 5]]))],
        point_data={"temperature": np.arange(6, dtype=np.float64)},
        cell_data={"region": [np.array([1, 2, 3], dtype=np.int32), np.array([7], dtype=np.int32), np.array([9], dtype=np.int32)]},
    )
    c = topoplex.from_meshio(mesh)
    assert c.census()["tops"] == [0, 1, 2, 1]
    where, t = c.attributes["temperature"]
    assert where == "vertices" and t.tolist() == list(range(6))
    assert c.attributes["region"][1].tolist() == [1, 2, 3, 7, 9]
    back = c.to_meshio()
    assert [b.type for b in back.cells] == ["triangle", "tetra", "line"]
    for a, b in zip(back.cells, mesh.cells):
        assert a.data.tolist() == b.data.tolist()
    assert np.array_equal(back.points, PTS)
    assert [x.tolist() for x in back.cell_data["region"]] == [[1, 2, 3], [7], [9]]
    assert back.point_data["temperature"].tolist() == list(range(6))


def test_meshio_file_written_by_topoplex_reads_in_meshio(tmp_path):
    meshio = pytest.importorskip("meshio")
    c = fan()
    c.write(tmp_path / "m.vtu")
    m = meshio.read(tmp_path / "m.vtu")
    tris = np.concatenate([b.data for b in m.cells if b.type == "triangle"])
    assert sorted(map(tuple, np.sort(tris, axis=1).tolist())) == sorted(map(tuple, c.tops(2).tolist()))


def test_trimesh_gets_every_triangle_and_topoplex_the_adjacency_trimesh_drops():
    trimesh = pytest.importorskip("trimesh")
    c = fan()
    tm = c.to_trimesh()
    assert tm.faces.tolist() == TRIS.tolist()
    assert np.array_equal(tm.vertices, PTS)
    # The edge [0 1] is in three triangles: face adjacency over it is three pairs.
    s = c.build("ts")
    off, ids = s.relation(2, 2)
    pairs = {tuple(sorted((i, int(j)))) for i in range(s.count(2)) for j in ids[off[i]:off[i + 1]]}
    tris = s.simplices(2).tolist()
    over01 = {pr for pr in pairs if set(tris[pr[0]]) & set(tris[pr[1]]) == {0, 1}}
    assert len(over01) == 3
    assert len(pairs) >= len(tm.face_adjacency)


def test_decompose_writes_components_and_gluing(tmp_path):
    c = topoplex.Complex.from_arrays(np.array([[0, 1, 2], [0, 3, 4]]), points=np.random.default_rng(1).random((5, 3)))
    paths = topoplex.decompose(c, tmp_path / "parts")
    names = sorted(os.path.basename(p) for p in paths)
    assert "gluing.json" in names and len(names) == 3
    total = sum(topoplex.read(p).count(2) for p in paths if not p.endswith(".json"))
    assert total == 2


def test_attributes_set_read_written_and_removed(tmp_path):
    c = fan()
    heat = np.linspace(0, 1, 6)
    region = np.array([1, 1, 2, 2, 3], dtype=np.int32)
    c2 = c.with_attribute("heat", "vertices", heat).with_attribute("region", "listed", region)
    assert c.attributes == {}
    where, got = c2.attributes["heat"]
    assert where == "vertices" and np.array_equal(got, heat)
    assert c2.attributes["region"][1].tolist() == region.tolist()
    c2.write(tmp_path / "d.vtu")
    back = topoplex.read(tmp_path / "d.vtu")
    assert np.array_equal(back.attributes["heat"][1], heat)
    assert back.attributes["region"][1].tolist() == region.tolist()
    assert "heat" not in c2.without_attribute("heat").attributes
    with pytest.raises(KeyError):
        c.without_attribute("heat")
    with pytest.raises(ValueError):
        c.with_attribute("short", "vertices", np.zeros(2))


def test_meshio_refuses_a_simplex_it_has_no_cell_type_for():
    pytest.importorskip("meshio")
    c = topoplex.Complex.from_arrays(np.array([[0, 1, 2, 3, 4]]))
    with pytest.raises(topoplex.InputError, match="5 vertices"):
        c.to_meshio()
