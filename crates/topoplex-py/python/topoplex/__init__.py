"""Topoplex for Python: compact topological data structures for arbitrary simplicial complexes
(non-manifold, mixed-dimensional, any dimension up to 15), with numpy arrays in and out.

A :class:`Complex` is read from a file (:func:`read`, :func:`open`) or made from arrays
(:meth:`Complex.from_arrays`); :meth:`Complex.build` makes one of the survey's structures by
name (``ig sig ia iqm nmia ts pe le de``) or the editable live mesh (``iastar``,
:meth:`Complex.live`). Every p-simplex has a *dense index*: its row in ``simplices(p)``
(ascending lexicographic order of its sorted vertex ids; a vertex's index is its id).
Relations come back as CSR pairs ``(offsets, ids)`` of numpy arrays.

>>> import numpy as np, topoplex
>>> # Two triangles sharing the edge [1 2], and a dangling edge [3 4].
>>> c = topoplex.Complex.from_arrays([np.array([[0, 1, 2], [1, 2, 3]]), np.array([[3, 4]])])
>>> c.census()["simplices"]
[5, 6, 2]
>>> ig = c.build("ig")
>>> offsets, ids = ig.relation(0, 2)          # the triangles around each vertex
>>> [ids[offsets[v]:offsets[v + 1]].tolist() for v in range(5)]
[[0], [0, 1], [0, 1], [1], []]
>>> int(ig.locate([2, 1]))                    # the edge [1 2]'s dense index
2
>>> ig.degree(1, 2).tolist()                  # triangles per edge: [1 2] has two
[1, 1, 2, 1, 1, 0]

Arrays in: C-contiguous arrays of the right dtype (uint32 ids, float64 points) are read in
place; anything else is converted once (``np.ascontiguousarray``). Answers (simplices,
relations, degrees, remaps) are Rust vectors moved into numpy, never copied; ``points``,
``attributes`` and ``listed()`` are copied once out of the complex that owns them, except for a
complex opened from a saved ``.tpx`` file (:func:`open`, :func:`read`), whose are read-only
views into the file (mapped; ``writeable`` is False, and each view keeps the map alive).
Long calls release the GIL. Errors are :class:`TopoplexError` subclasses (also ``ValueError``,
``OSError`` or ``MemoryError``).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _core  # type: ignore[attr-defined]  # the compiled extension: no type information
from . import _errors
from ._errors import (
    DomainError,
    EditRefused,
    FileError,
    InputError,
    ReadError,
    TopoplexError,
    TopoplexMemoryError,
    WriteError,
)

__all__ = [
    "ACROSS_NONE",
    "ACROSS_MANY",
    "Complex",
    "Structure",
    "Undo",
    "read",
    "open",
    "save",
    "simplify",
    "decompose",
    "structure_names",
    "from_meshio",
    "to_meshio",
    "from_gudhi",
    "to_gudhi",
    "to_trimesh",
]
# The exception classes, listed once beside their definitions.
__all__ += _errors.__all__

if TYPE_CHECKING:
    from typing import final

    @final
    class Undo:
        """What :meth:`Structure.contract` returns for one contraction: give it to
        :meth:`Structure.split` to undo that contraction."""

        @property
        def edge(self) -> Tuple[int, int]: ...

else:
    Undo = _core.Undo
_Path = Union[str, "os.PathLike[str]"]
#: A relation's answers as CSR: ``ids[offsets[k]:offsets[k + 1]]`` belong to the k-th simplex.
_Csr = Tuple[npt.NDArray[np.int64], npt.NDArray[np.uint32]]
#: Simplices as one (n, k) array, a list of such arrays, or a CSR pair ``(offsets, ids)``.
_Simplices = Union[npt.ArrayLike, List[npt.ArrayLike], Tuple[npt.ArrayLike, npt.ArrayLike]]
_U32_MAX = 2**32 - 1
#: :meth:`Structure.adjacency`: no other top of the same dimension across the facet.
ACROSS_NONE: int = _core.ACROSS_NONE
#: :meth:`Structure.adjacency`: two or more (a non-manifold facet).
ACROSS_MANY: int = _core.ACROSS_MANY


def structure_names() -> List[str]:
    """The structures by name: the survey's nine, then the live mesh ``iastar``."""
    return list(_core.structure_names())


# ---- array checks: one conversion at most, never a crash ----


def _ids(a: Any, name: str = "ids") -> np.ndarray:
    """``a`` as a C-contiguous uint32 array (no copy when it already is one)."""
    arr = np.asarray(a)
    if arr.dtype == np.uint32:
        return np.ascontiguousarray(arr)
    if arr.size == 0:
        return np.ascontiguousarray(arr, dtype=np.uint32)
    if arr.dtype.kind not in "iu":
        raise InputError(f"{name}: an integer array is needed, got dtype {arr.dtype}")
    lo, hi = int(arr.min()), int(arr.max())
    if lo < 0:
        raise InputError(f"{name}: negative id {lo}")
    if hi > _U32_MAX:
        raise InputError(f"{name}: id {hi} does not fit in 32 bits")
    return np.ascontiguousarray(arr, dtype=np.uint32)


def _points(a: Any, name: str = "points") -> np.ndarray:
    """``a`` as a C-contiguous float64 (n, k) array."""
    arr = np.asarray(a)
    if arr.dtype.kind not in "fiu":
        raise InputError(f"{name}: a real array is needed, got dtype {arr.dtype}")
    if arr.ndim == 1:
        arr = arr.reshape(-1, 1)
    if arr.ndim != 2:
        raise InputError(f"{name}: shape (n, k) needed, got {arr.shape}")
    return np.ascontiguousarray(arr, dtype=np.float64)


def _csr(simplices: Any, name: str = "simplices") -> Tuple[np.ndarray, np.ndarray]:
    """Simplices as ``(ids uint32, offsets uintp)``, given as one (n, k) array (or nested
    list), a list of such blocks (a 1-D block is one simplex), or a CSR pair: a *tuple* of two
    1-D numpy arrays ``(offsets, ids)``."""
    if (
        isinstance(simplices, tuple)
        and len(simplices) == 2
        and all(isinstance(x, np.ndarray) and x.ndim == 1 for x in simplices)
    ):
        offsets, ids = simplices[0], _ids(simplices[1], name)
        if offsets.size == 0 or offsets.dtype.kind not in "iu":
            raise InputError(f"{name}: CSR offsets must be a non-empty 1-D integer array")
        if int(offsets[0]) != 0 or np.any(np.diff(offsets.astype(np.int64)) < 0) or int(offsets[-1]) != ids.size:
            raise InputError(
                f"{name}: CSR offsets must start at 0, not decrease and end at len(ids) = {ids.size}"
            )
        return ids, np.ascontiguousarray(offsets, dtype=np.uintp)
    if isinstance(simplices, np.ndarray):
        blocks = [simplices]
    else:
        try:
            whole = np.asarray(simplices)
        except ValueError:  # ragged: a list of blocks
            whole = None
        if whole is not None and whole.dtype != object and whole.ndim == 2:
            blocks = [whole]
        else:
            blocks = [np.asarray(b) for b in simplices]
            blocks = [b.reshape(1, -1) if b.ndim == 1 and b.size else b for b in blocks]
    ids_parts: List[np.ndarray] = []
    shapes: List[Tuple[int, int]] = []
    for b in blocks:
        if b.ndim == 1 and b.size == 0:
            continue
        if b.ndim != 2:
            raise InputError(f"{name}: each block must be an (n, k) array, got shape {b.shape}")
        if b.shape[1] == 0 and b.shape[0] > 0:
            raise InputError(f"{name}: a block of {b.shape[0]} simplices with no vertex")
        ids_parts.append(_ids(b, name).reshape(-1))
        shapes.append(b.shape)
    if not ids_parts:
        return np.zeros(0, np.uint32), np.zeros(1, np.uintp)
    ids = ids_parts[0] if len(ids_parts) == 1 else np.concatenate(ids_parts)
    # The offsets of each block are an arithmetic run (one array, no temporaries for a single
    # block: what the Rust caller of Complex::from_arrays holds beside its ids).
    if len(shapes) == 1:
        m, k = shapes[0]
        offsets = np.arange(0, m * k + 1, k, dtype=np.uintp) if k else np.zeros(1, np.uintp)
    else:
        offsets = np.empty(sum(m for m, _ in shapes) + 1, dtype=np.uintp)
        offsets[0] = 0
        row = start = 0
        for m, k in shapes:
            if m:
                offsets[row + 1 : row + m + 1] = np.arange(start + k, start + m * k + 1, k, dtype=np.uintp)
            row += m
            start += m * k
    return np.ascontiguousarray(ids), offsets


def _values(values: Any, n: int) -> np.ndarray:
    """Attribute rows as a C-contiguous float64 (n, components) array; integers beyond 2**53
    (which float64 would round) refused."""
    arr = np.asarray(values)
    if arr.dtype.kind not in "fiub":
        raise InputError(f"values: a real array is needed, got dtype {arr.dtype}")
    if arr.dtype.kind in "iu" and arr.size and int(np.abs(arr).max()) > 2**53:
        raise InputError("values: labels beyond 2**53 cannot be set exactly")
    if arr.ndim == 0 or (arr.ndim == 1 and n != 1):
        arr = arr.reshape(-1, 1)
    elif arr.ndim == 1:
        arr = arr.reshape(1, -1)
    if arr.ndim != 2:
        raise InputError(f"values: shape (n,) or (n, components) needed, got {arr.shape}")
    if arr.shape[0] != n:
        raise InputError(f"values: {arr.shape[0]} rows for {n} simplices")
    return np.ascontiguousarray(arr, dtype=np.float64)


def _index_array(simplices: Any) -> Optional[np.ndarray]:
    return None if simplices is None else _ids(np.asarray(simplices).reshape(-1), "simplices")


class Complex:
    """An immutable simplicial complex: the closure of the simplices given, with optional
    vertex coordinates (``points``) and attributes.

    >>> import topoplex
    >>> c = topoplex.Complex.from_arrays([[0, 1, 2, 3]])     # one tetrahedron
    >>> c.simplices(2).tolist()
    [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]]
    """

    __slots__ = ("_c",)

    def __init__(self, core: Any) -> None:
        if not isinstance(core, _core.Complex):
            raise TypeError("use Complex.from_arrays, topoplex.read or topoplex.open")
        self._c = core

    @staticmethod
    def from_arrays(
        simplices: _Simplices,
        points: Optional[npt.ArrayLike] = None,
        n_vertices: Optional[int] = None,
    ) -> "Complex":
        """A complex from its simplices: one (n, k) integer array (n simplices of k vertices),
        a list of such arrays (one per size, or in any grouping), or a CSR pair
        ``(offsets, ids)``. ``points``: optional (n_vertices, dim) coordinates. The vertex
        count is ``len(points)``, else ``n_vertices``, else the largest id + 1. One (n, k)
        uint32 array is read in place as it lies (no offsets are made: the cost and memory of
        the Rust call on the same array); other forms go through a CSR.

        >>> import numpy as np, topoplex
        >>> tris = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.uint32)
        >>> pts = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
        >>> c = topoplex.Complex.from_arrays(tris, points=pts)
        >>> c.census()["simplices"], c.points.shape
        ([4, 5, 2], (4, 3))
        """
        # One (n, k) numpy array is passed as it lies (no offsets: the Rust call the same
        # array would make); anything else as a CSR.
        width: Optional[int] = None
        if isinstance(simplices, np.ndarray) and simplices.ndim == 2 and simplices.shape[1] > 0:
            width = int(simplices.shape[1])
            ids, offsets = _ids(simplices, "simplices").reshape(-1), None
        else:
            ids, offsets = _csr(simplices)
        pts = None if points is None else _points(points)
        if pts is not None:
            n = pts.shape[0]
        elif n_vertices is not None:
            n = int(n_vertices)
        else:
            n = int(ids.max()) + 1 if ids.size else 0
        if n < 0 or n > _U32_MAX:
            raise InputError(f"vertex count {n} does not fit in 32 bits")
        if width is not None:
            return Complex(_core.Complex._from_uniform(n, width, ids, pts))
        return Complex(_core.Complex._from_csr(n, ids, offsets, pts))

    @property
    def vertex_count(self) -> int:
        """Number of vertices (ids ``0..vertex_count``)."""
        return self._c.vertex_count

    @property
    def dimension(self) -> int:
        """The largest simplex's dimension."""
        return self._c.dimension

    @property
    def points(self) -> Optional[npt.NDArray[np.float64]]:
        """Vertex coordinates, float64 (n, k), or None (a read-only view into the file for a
        complex opened from a ``.tpx`` file, see :attr:`mapped`)."""
        return self._c.points

    @property
    def mapped(self) -> bool:
        """Whether :attr:`points`, :attr:`attributes` and :meth:`listed` are read-only views
        into a saved file (a complex from :func:`open` or :func:`read` of a ``.tpx``) rather
        than copies.

        >>> import os, tempfile, numpy as np, topoplex
        >>> c = topoplex.Complex.from_arrays([[0, 1, 2]], points=np.eye(3))
        >>> path = os.path.join(tempfile.mkdtemp(), "tri.tpx")
        >>> topoplex.save(c, path)
        >>> o = topoplex.open(path)
        >>> o.mapped, o.points.flags.writeable, np.shares_memory(o.points, o.points)
        (True, False, True)
        """
        return self._c.mapped

    @property
    def attributes(self) -> Dict[str, Tuple[str, np.ndarray]]:
        """Attributes: name → (location, array); location ``"vertices"`` (one row per vertex)
        or ``"listed"`` (one row per simplex as listed, see :meth:`listed`)."""
        return dict(self._c.attributes)

    def with_attribute(self, name: str, location: str, values: npt.ArrayLike) -> "Complex":
        """A copy with attribute ``name`` set to ``values`` (int32, int64, float32 or float64;
        shape (n,) or (n, components)) on ``"vertices"`` or ``"listed"`` simplices."""
        arr = np.ascontiguousarray(values)
        if arr.dtype not in (np.int32, np.int64, np.float32, np.float64):
            raise InputError(f"attribute {name}: dtype {arr.dtype}: int32, int64, float32 or float64")
        return Complex(self._c._with_attribute(name, location, arr))

    def without_attribute(self, name: str) -> "Complex":
        """A copy without attribute ``name`` (KeyError if absent)."""
        return Complex(self._c._without_attribute(name))

    def count(self, p: int) -> int:
        """Number of p-simplices."""
        return self._c.count(p)

    def simplices(self, p: int) -> npt.NDArray[np.uint32]:
        """Every p-simplex as an (n_p, p+1) uint32 array of ascending ids, in ascending
        lexicographic order: row i is the p-simplex of dense index i."""
        return self._c.simplices(p)

    def tops(self, p: int) -> npt.NDArray[np.uint32]:
        """The top p-simplices (faces of no other simplex) as rows of ascending ids."""
        return self._c.tops(p)

    def listed(self) -> _Csr:
        """The simplices as listed (input order and winding): a CSR pair (offsets, ids)."""
        return self._c.listed()

    def census(self) -> Dict[str, Any]:
        """dimension, vertices, simplices per dimension, tops per dimension."""
        return dict(self._c.census())

    def build(self, kind: str) -> "Structure":
        """A structure by name: ``ig sig ia iqm nmia ts pe le de``, or ``iastar`` (the live
        mesh). :class:`DomainError` when the structure cannot encode this complex."""
        return Structure(self._c.build(kind))

    def live(self) -> "Structure":
        """The live, editable mesh (``iastar``) of this complex."""
        return Structure(self._c.live())

    def write(self, path: _Path, format: Optional[str] = None) -> None:
        """Writes the complex (simplices as listed, with winding and data); format by the
        extension (off obj mesh simplices ply stl vtk vtu msh) or by ``format``."""
        self._c.write(os.fspath(path), format)

    def boundary_matrix(self, p: int, signed: bool = False) -> Any:
        """∂_p as a scipy.sparse CSR matrix (see :meth:`Structure.boundary_matrix`)."""
        return self.build("ig").boundary_matrix(p, signed)

    def __repr__(self) -> str:
        return repr(self._c)

    # interop (pure Python, the package imported lazily)
    def to_meshio(self) -> Any:
        """A ``meshio.Mesh`` (see :func:`to_meshio`)."""
        return to_meshio(self)

    def to_gudhi(self) -> Any:
        """A ``gudhi.SimplexTree`` of the complex (see :func:`to_gudhi`)."""
        return to_gudhi(self)

    def to_trimesh(self) -> Any:
        """A ``trimesh.Trimesh`` of the triangles (see :func:`to_trimesh`)."""
        return to_trimesh(self)


class Structure:
    """A structure of the survey, or the live editable mesh (``kind == "iastar"``).

    Simplices are named by dense indices (rows of :meth:`simplices`); relations come back as
    CSR pairs. On the live mesh, dense indices are those of the moment: an edit renumbers them;
    its vertices are named by their ids (slots), and a removed vertex's slot is skipped by
    ``simplices(0)`` and by the rows of ``relation(0, q)`` until :meth:`compact`.

    >>> import topoplex
    >>> s = topoplex.Complex.from_arrays([[0, 1, 2], [0, 1, 3], [0, 1, 4]]).build("ts")
    >>> off, ids = s.relation(1, 2)     # the triangles around each edge
    >>> int(off[1] - off[0])            # the edge [0 1] is in three triangles
    3
    """

    __slots__ = ("_s",)

    def __init__(self, core: Any) -> None:
        if not isinstance(core, _core.Structure):
            raise TypeError("use Complex.build or Complex.live")
        self._s = core

    @property
    def kind(self) -> str:
        """ig, sig, ia, iqm, nmia, ts, pe, le, de or iastar."""
        return self._s.kind

    @property
    def dimension(self) -> int:
        return self._s.dimension

    @property
    def vertex_count(self) -> int:
        """Vertex ids (the live mesh: slots, removed ones included until :meth:`compact`)."""
        return self._s.vertex_count

    @property
    def editable(self) -> bool:
        return self._s.editable

    def count(self, p: int) -> int:
        """Number of p-simplices."""
        return self._s.count(p)

    def simplices(self, p: int) -> npt.NDArray[np.uint32]:
        """Every p-simplex, (n_p, p+1) uint32, ascending ids, row i = dense index i."""
        return self._s.simplices(p)

    def relation(
        self, p: int, q: int, simplices: Optional[npt.ArrayLike] = None, order: str = "sorted"
    ) -> _Csr:
        """R_{p,q} as CSR ``(offsets, ids)``: the q-simplices related to each p-simplex (or
        to the dense p-indices ``simplices``): boundary q < p, co-boundary q > p, adjacency
        q = p. ``offsets`` is int64 of length n+1, ``ids`` uint32 dense q-indices, ascending
        within each answer (``order="natural"``: the structure's walk order).

        >>> import topoplex
        >>> s = topoplex.Complex.from_arrays([[0, 1, 2]]).build("ia")
        >>> off, ids = s.relation(2, 1)
        >>> ids.tolist()
        [0, 1, 2]
        """
        return self._s._relation(p, q, _index_array(simplices), order)

    def degree(self, p: int, q: int, simplices: Optional[npt.ArrayLike] = None) -> npt.NDArray[np.uint32]:
        """|R_{p,q}| per p-simplex (or per dense index in ``simplices``), uint32."""
        return self._s._degree(p, q, _index_array(simplices))

    def locate(self, vertices: npt.ArrayLike) -> Union[int, npt.NDArray[np.int64]]:
        """Dense index of the simplex with these vertex ids (any order); a 2-D array of rows
        gives an int64 array, -1 for rows that are not simplices of the complex. A single
        simplex not in the complex raises :class:`InputError`."""
        arr = np.asarray(vertices)
        if arr.size == 0:
            raise InputError("locate: a simplex with no vertex")
        if arr.ndim == 1:
            return int(self._s._locate(_ids(arr, "vertices").reshape(1, -1), False)[0])
        if arr.ndim != 2:
            raise InputError(f"vertices: 1-D or 2-D array needed, got shape {arr.shape}")
        return self._s._locate(_ids(arr, "vertices"), True)

    def winding(self, p: int) -> npt.NDArray[np.int8]:
        """±1 per p-simplex: the parity of a top simplex's vertex order as given; +1 else."""
        return self._s.winding(p)

    def fans(self, v: int) -> List[npt.NDArray[np.uint32]]:
        """The fans of top simplices around vertex ``v``, each in cyclic order."""
        return list(self._s.fans(v))

    def radial(self, a: int, b: int, q: int = 2) -> List[npt.NDArray[np.uint32]]:
        """The q-simplices around edge (a, b) in radial order, per cycle."""
        return list(self._s.radial(a, b, q))

    def boundary_matrix(self, p: int, signed: bool = False) -> Any:
        """∂_p: the (n_{p-1}, n_p) scipy.sparse CSR matrix with a nonzero where a
        (p-1)-simplex (row) is a face of a p-simplex (column). Over Z/2 (uint8 ones) by
        default; ``signed=True`` gives the oriented boundary (int8 ±1): faces omitting the i-th
        of the ascending vertices get (-1)^i, and a top simplex's column is multiplied by the
        parity of its winding as given. ∂_{p-1} ∂_p = 0 either way (mod 2 for Z/2)."""
        import scipy.sparse as sp

        if p < 1 or p > self.dimension:
            raise InputError(f"boundary_matrix: p = {p} must be in 1..={self.dimension}")
        offsets, ids = self.relation(p, p - 1)
        n_rows, n_cols = self.count(p - 1), self.count(p)
        if signed:
            k = np.arange(ids.size) % (p + 1)
            # The k-th face in ascending order omits vertex p - k.
            data = np.where((p - k) % 2 == 0, 1, -1).astype(np.int8)
            w = self.winding(p)
            data *= np.repeat(w, p + 1)
        else:
            data = np.ones(ids.size, dtype=np.uint8)
        m = sp.csc_matrix((data, ids, offsets), shape=(n_rows, n_cols))
        return m.tocsr()

    def census(self) -> Dict[str, Any]:
        return dict(self._s.census())

    def report(self) -> Dict[str, Any]:
        """Census and storage: kind, simplices, tops, integers, bits, bytes, summary."""
        return dict(self._s.report())

    def validate(self) -> None:
        """Checks the structure's invariants (InputError naming the first broken one)."""
        self._s.validate()

    def to_complex(self) -> Complex:
        """The complex it holds (the live mesh: its current complex, renumbered densely)."""
        return Complex(self._s.to_complex())

    @property
    def attributes(self) -> Dict[str, Tuple[str, np.ndarray]]:
        """The attributes (as :attr:`Complex.attributes`) of the complex it holds; the live
        mesh's carried through its edits, in the numbering of :meth:`to_complex`."""
        return self.to_complex().attributes

    # ---- the live mesh ----

    @property
    def points(self) -> Optional[npt.NDArray[np.float64]]:
        """Coordinates (the live mesh: per vertex slot, a copy), or None."""
        return self._s.points

    def set_points(self, points: npt.ArrayLike, vertices: Optional[npt.ArrayLike] = None) -> None:
        """Sets every vertex's coordinates ((slots, k) array), or those of ``vertices`` (one
        row of ``points`` each)."""
        pts = _points(points)
        if vertices is None:
            self._s._set_points(pts)
        else:
            ids = _ids(np.asarray(vertices).reshape(-1), "vertices")
            if ids.size != pts.shape[0]:
                raise InputError(f"set_points: {pts.shape[0]} rows of points for {ids.size} vertices")
            self._s._set_point_rows(ids, pts)

    def insert(self, simplices: _Simplices) -> int:
        """Inserts top simplices (an (n, k) array, a list of them, or a CSR pair), in order;
        returns how many. :class:`EditRefused` names the first refused row (earlier rows stay
        inserted)."""
        ids, offsets = _csr(simplices)
        return self._s._insert(ids, offsets)

    def remove(self, simplices: _Simplices) -> int:
        """Removes top simplices (as :meth:`insert` takes them); returns how many."""
        ids, offsets = _csr(simplices)
        return self._s._remove(ids, offsets)

    def add_vertex(self, xyz: npt.ArrayLike = ()) -> int:
        """Adds an isolated vertex with coordinates ``xyz``; returns its id."""
        return self._s._add_vertex(np.ascontiguousarray(xyz, dtype=np.float64).reshape(-1))

    def can_contract(self, a: int, b: int, mode: str = "topology") -> bool:
        """Whether contracting b into a is allowed (``mode``: topology = link condition,
        manifold = link condition with the boundary, free)."""
        return self._s.can_contract(a, b, mode)

    def contract(
        self, pairs: npt.ArrayLike, mode: str = "topology", positions: Optional[npt.ArrayLike] = None
    ) -> List[Undo]:
        """Contracts each (a, b) of ``pairs`` (b into a, a moved to the row of ``positions``
        when given) in order; returns the :class:`Undo` records for :meth:`split`."""
        arr = _ids(np.asarray(pairs).reshape(-1, 2), "pairs")
        pos = None if positions is None else _points(positions)
        if pos is not None and pos.shape[0] != arr.shape[0]:
            raise InputError(f"positions: {pos.shape[0]} rows for {arr.shape[0]} pairs")
        return list(self._s._contract(arr, mode, pos))

    def split(self, undo: Undo) -> None:
        """Undoes a contraction (in reverse order of contractions touching the same simplices)."""
        self._s.split(undo)

    def compact(self) -> Dict[str, Any]:
        """Drops tombstones, renumbering densely; returns ``{"vertices": old→new (uint32,
        2**32-1 for a removed vertex), "tops": [old slot→new slot per dimension]}``."""
        v, tops = self._s._compact()
        return {"vertices": v, "tops": list(tops)}

    def live_tops(self) -> List[npt.NDArray[np.uint32]]:
        """The live mesh's top simplices of dimension >= 1 as given (winding): item p is an
        (n, p+1) array (item 0 is empty: an isolated vertex is a vertex with an empty star)."""
        return list(self._s._live_tops())

    def adjacency(self, p: int) -> npt.NDArray[np.uint32]:
        """The tops across each facet of the live mesh's top p-simplices (p >= 1): a uint32
        (n, p+1) array whose row i is for row i of ``live_tops()[p]`` and entry j for its facet
        opposite its j-th vertex (as listed there): the row of the one other top p-simplex
        through that facet, :data:`ACROSS_NONE` when none is (a boundary facet, or one only
        tops of other dimensions share), :data:`ACROSS_MANY` when two or more are (a
        non-manifold facet, which trimesh's ``face_adjacency`` drops). Built on the first call
        after an edit (the GIL released), then copied out: an edit would move the index.

        >>> import topoplex
        >>> m = topoplex.Complex.from_arrays([[0, 1, 2], [1, 2, 3], [1, 2, 4], [2, 3, 5]]).live()
        >>> adj = m.adjacency(2)
        >>> m.live_tops()[2][1].tolist(), adj[1].tolist()   # [2 3]: row 3; [1 3]: none; [1 2]: many
        ([1, 2, 3], [3, 4294967295, 4294967294])
        """
        return self._s._adjacency(p)

    def rings(self) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.uint32], npt.NDArray[np.uint32]]:
        """Every vertex's one-ring as CSR ``(offsets, neighbours, tops)``: row v (a vertex
        slot, empty for a removed or isolated vertex) holds the vertices sharing an edge with
        v, each once, in the order v's star first names them, and ``tops`` beside each the
        number of top simplices holding that edge (on a triangle mesh: 1 on the boundary, 2
        inside, more at a non-manifold edge). Built on the first call after an edit of the
        topology (the GIL released; moving vertices keeps it), then copied out.

        >>> import topoplex
        >>> m = topoplex.Complex.from_arrays([[0, 1, 2], [0, 1, 3], [0, 1, 4]]).live()
        >>> off, ids, tops = m.rings()
        >>> sorted(zip(ids[off[0]:off[1]].tolist(), tops[off[0]:off[1]].tolist()))
        [(1, 3), (2, 1), (3, 1), (4, 1)]
        """
        return self._s._rings()

    def keep_adjacency(self, keep: bool = True) -> None:
        """Keeps :meth:`adjacency`'s index across edits (built now, then repaired by each
        insert, removal, contraction and split around what it changed: O(1) to ask for after
        an edit, each edit a little dearer), or with ``keep=False`` goes back to building it
        on request and dropping it at each edit (the default)."""
        self._s.keep_adjacency(keep)

    def vertex_values(self, name: str, vertices: Optional[npt.ArrayLike] = None) -> np.ndarray:
        """The rows of vertex attribute ``name`` (in its own dtype; shape (n,) for one
        component, else (n, components)) for the live vertices ``vertices`` (ids; default:
        every live vertex, ascending, as ``simplices(0)`` lists them). KeyError without such an
        attribute, :class:`InputError` for a removed or unknown vertex."""
        ids = self._vertex_ids(vertices)
        got = self._s._vertex_values(name, ids)
        return got if got is not None else self._empty_values(name)

    def set_vertex_values(
        self, name: str, values: npt.ArrayLike, vertices: Optional[npt.ArrayLike] = None
    ) -> None:
        """Sets the rows of vertex attribute ``name`` of the live vertices ``vertices``
        (default: every live vertex, ascending) to ``values`` (one row each; shape (n,) or
        (n, components)); reals are rounded to the attribute's type, labels must be whole
        numbers within it (exact up to 2**53). Everything is checked first: on an error
        nothing changes.

        >>> import numpy as np, topoplex
        >>> c = topoplex.Complex.from_arrays([[0, 1, 2]]).with_attribute("t", "vertices", np.zeros(3))
        >>> m = c.live()
        >>> m.set_vertex_values("t", [5.0], vertices=[1])
        >>> m.vertex_values("t").tolist()
        [0.0, 5.0, 0.0]
        """
        ids = self._vertex_ids(vertices)
        self._s._set_vertex_values(name, ids, _values(values, ids.size))

    def top_values(self, name: str, p: int, rows: Optional[npt.ArrayLike] = None) -> np.ndarray:
        """The rows of listed attribute ``name`` for the live top p-simplices ``rows`` (row
        indices of ``live_tops()[p]``; default all of them), as :meth:`vertex_values`."""
        idx = self._top_rows(p, rows)
        got = self._s._top_values(name, p, idx)
        return got if got is not None else self._empty_values(name)

    def set_top_values(
        self, name: str, p: int, values: npt.ArrayLike, rows: Optional[npt.ArrayLike] = None
    ) -> None:
        """Sets the rows of listed attribute ``name`` of the live top p-simplices ``rows``
        (row indices of ``live_tops()[p]``; default all of them) to ``values``, as
        :meth:`set_vertex_values`. A top made by an edit has unset numbers (labels 0, reals
        NaN) until set; :attr:`attributes` carries the rows into :meth:`to_complex`."""
        idx = self._top_rows(p, rows)
        self._s._set_top_values(name, p, idx, _values(values, idx.size))

    def _vertex_ids(self, vertices: Any) -> np.ndarray:
        if vertices is None:
            return np.ascontiguousarray(self.simplices(0).reshape(-1))
        return _ids(np.asarray(vertices).reshape(-1), "vertices")

    def _top_rows(self, p: int, rows: Any) -> np.ndarray:
        if rows is None:
            tops = self.live_tops()
            n = tops[p].shape[0] if 0 <= p < len(tops) else 0
            return np.arange(n, dtype=np.uint32)
        return _ids(np.asarray(rows).reshape(-1), "rows")

    def _empty_values(self, name: str) -> np.ndarray:
        """No row asked for: an empty array of the attribute's dtype and row shape."""
        got = self.attributes.get(name)
        if got is None:
            raise KeyError(name)
        a = got[1]
        return np.empty((0,) + a.shape[1:], dtype=a.dtype)

    def simplify(
        self, ratio: float, preserve_topology: bool = False, keep_regions: Optional[str] = None
    ) -> Dict[str, int]:
        """Decimates the live mesh in place to about ``ratio`` of its top simplices; stats."""
        return dict(self._s._simplify(ratio, preserve_topology, keep_regions))

    def __repr__(self) -> str:
        return repr(self._s)


def read(path: _Path) -> Complex:
    """Reads a mesh file (OFF, OBJ, MEDIT, .simplices, PLY, STL, VTK, VTU, Gmsh by extension)
    or a saved ``.tpx`` file. :class:`ReadError` names the file and line."""
    return Complex(_core.Complex._read(os.fspath(path)))


def open(path: _Path, kind: Optional[str] = None) -> Union[Complex, Structure]:
    """Opens a saved ``.tpx`` file: the structure ``kind`` (mapped when the file holds that
    kind, else built), or with ``kind=None`` the saved structure, or the complex when the file
    holds none."""
    got = _core._open(os.fspath(path), kind)
    return Structure(got) if isinstance(got, _core.Structure) else Complex(got)


def save(
    obj: Union[Complex, Structure],
    path: _Path,
    structure: Optional[str] = None,
) -> None:
    """Saves a complex (with the structure named ``structure`` built on it, if given) or a
    structure (with its complex; the live mesh with its data) as a ``.tpx`` file."""
    p = os.fspath(path)
    if isinstance(obj, Structure):
        if structure is not None and structure != obj.kind:
            raise InputError(f"save: a `{obj.kind}` structure was given with structure={structure!r}")
        obj._s._save(p)
    elif isinstance(obj, Complex):
        s = None if structure is None else obj._c.build(structure)
        obj._c._save(p, s)
    else:
        raise TypeError("save: a topoplex.Complex or topoplex.Structure")


def simplify(
    obj: Union[Complex, Structure],
    ratio: float,
    preserve_topology: bool = False,
    keep_regions: Optional[str] = None,
) -> Any:
    """Quadric decimation to about ``ratio`` of the top simplices. A :class:`Complex` gives
    ``(simplified complex, stats)``; the live mesh is simplified in place and gives stats."""
    if isinstance(obj, Structure):
        return obj.simplify(ratio, preserve_topology, keep_regions)
    c, stats = _core._simplify(obj._c, float(ratio), preserve_topology, keep_regions)
    return Complex(c), dict(stats)


def decompose(
    complex: Complex, out: _Path, format: Optional[str] = None
) -> List[str]:
    """Cuts the complex into its IQM components (standard decomposition) and writes each, and
    ``gluing.json``, into the directory ``out``; returns the paths written."""
    return [os.fspath(p) for p in _core._decompose(complex._c, os.fspath(out), format)]


from .interop import from_gudhi, from_meshio, to_gudhi, to_meshio, to_trimesh  # noqa: E402
