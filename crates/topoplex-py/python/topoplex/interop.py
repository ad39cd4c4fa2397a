"""Converters to and from meshio, GUDHI and trimesh, in pure Python over the array API. Each
package is imported when a converter is called, so topoplex needs none of them."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, List, Optional

import numpy as np

from ._errors import InputError

if TYPE_CHECKING:
    from . import Complex

# meshio's cell types for simplices, by vertex count.
_MESHIO_TYPES = {1: "vertex", 2: "line", 3: "triangle", 4: "tetra"}
_MESHIO_SIZES = {v: k for k, v in _MESHIO_TYPES.items()}


def _blocks(offsets: np.ndarray, ids: np.ndarray) -> List[tuple]:
    """Runs of consecutive listed simplices of one size: (start, stop, k, (n, k) array)."""
    sizes = np.diff(offsets)
    out = []
    start = 0
    n = sizes.size
    while start < n:
        k = int(sizes[start])
        stop = start
        while stop < n and sizes[stop] == k:
            stop += 1
        rows = ids[int(offsets[start]) : int(offsets[stop])].reshape(-1, k)
        out.append((start, stop, k, rows))
        start = stop
    return out


def to_meshio(complex: Complex) -> Any:
    """A ``meshio.Mesh``: one cell block per run of listed simplices of one size (vertex,
    line, triangle, tetra; input order and winding kept), points (zeros in 3-D when the
    complex has none), attributes as ``point_data`` and ``cell_data``. Simplices of
    dimension 4 and up have no meshio cell type: :class:`InputError`."""
    import meshio

    offsets, ids = complex.listed()
    cells = []
    blocks = _blocks(offsets, ids)
    for _, _, k, rows in blocks:
        if k not in _MESHIO_TYPES:
            raise InputError(f"to_meshio: a simplex of {k} vertices has no meshio cell type")
        cells.append((_MESHIO_TYPES[k], rows.astype(np.int64)))
    pts = complex.points
    if pts is None:
        pts = np.zeros((complex.vertex_count, 3))
    point_data: Dict[str, np.ndarray] = {}
    cell_data: Dict[str, List[np.ndarray]] = {}
    for name, (where, values) in complex.attributes.items():
        if where == "vertices":
            point_data[name] = values
        else:
            cell_data[name] = [values[a:b] for a, b, _, _ in blocks]
    return meshio.Mesh(pts, cells, point_data=point_data, cell_data=cell_data)


def from_meshio(mesh: Any) -> Complex:
    """A :class:`topoplex.Complex` from a ``meshio.Mesh``: every simplex block (vertex, line,
    triangle, tetra) in order, its points, ``point_data`` on the vertices and ``cell_data``
    on the listed simplices (integer and real arrays kept in their type; 64-bit integers as
    int64). A non-simplex cell block is refused (:class:`InputError`)."""
    from . import Complex

    blocks = []
    for cb in mesh.cells:
        k = _MESHIO_SIZES.get(cb.type)
        if k is None:
            raise InputError(f"from_meshio: cell type {cb.type!r} is not a simplex")
        blocks.append(np.asarray(cb.data).reshape(-1, k))
    pts = np.asarray(mesh.points, dtype=np.float64)
    c = Complex.from_arrays(blocks, points=pts)
    for name, values in mesh.point_data.items():
        c = c.with_attribute(name, "vertices", _attribute_values(values))
    for name, parts in mesh.cell_data.items():
        c = c.with_attribute(name, "listed", _attribute_values(np.concatenate(list(parts))))
    return c


def _attribute_values(values: Any) -> np.ndarray:
    a = np.asarray(values)
    if a.dtype.kind in "iu":
        small = a.size == 0 or (a.min() >= -(2**31) and a.max() < 2**31)
        a = a.astype(np.int32 if a.dtype.itemsize <= 4 and small else np.int64)
    elif a.dtype == np.float32:
        pass
    elif a.dtype.kind == "f":
        a = a.astype(np.float64)
    else:
        raise InputError(f"attribute of dtype {a.dtype}: integers or reals only")
    return np.ascontiguousarray(a)


def to_gudhi(complex: Complex) -> Any:
    """A ``gudhi.SimplexTree`` holding the complex (its top simplices inserted, filtration 0)."""
    import gudhi

    st = gudhi.SimplexTree()
    for p in range(complex.dimension + 1):
        for row in complex.tops(p):
            st.insert(row.tolist(), 0.0)
    return st


def from_gudhi(st: Any, n_vertices: Optional[int] = None) -> Complex:
    """A :class:`topoplex.Complex` from a ``gudhi.SimplexTree``: all its simplices (faces are
    absorbed into their cofaces; the filtration values are not kept). Vertex ids must be
    non-negative 32-bit integers."""
    from . import Complex

    by_size: Dict[int, List[List[int]]] = {}
    for s, _ in st.get_simplices():
        by_size.setdefault(len(s), []).append(s)
    blocks = [np.asarray(v, dtype=np.int64) for _, v in sorted(by_size.items())]
    return Complex.from_arrays(blocks, n_vertices=n_vertices)


def to_trimesh(complex: Complex, process: bool = False) -> Any:
    """A ``trimesh.Trimesh`` of the triangles as listed (input order and winding), vertices
    from ``points`` (padded to 3-D). Listed edges, vertices and tetrahedra are not carried;
    ``process=False`` keeps the vertex ids as they are."""
    import trimesh

    offsets, ids = complex.listed()
    faces = [rows for _, _, k, rows in _blocks(offsets, ids) if k == 3]
    faces_arr = np.concatenate(faces) if faces else np.zeros((0, 3), dtype=np.uint32)
    pts = complex.points
    if pts is None:
        raise InputError("to_trimesh: the complex has no coordinates")
    if pts.shape[1] != 3:
        pts = np.pad(pts, ((0, 0), (0, 3 - pts.shape[1])))[:, :3]
    return trimesh.Trimesh(vertices=pts, faces=faces_arr.astype(np.int64), process=process)
