"""Independent reader and writer for tests/it/interop.rs: Python meshio.

usage: meshio_check.py < JOBS, one job a line (one Python start for all of them):
       read FILE FORMAT      prints the mesh meshio reads, as one JSON line
       write FILE FORMAT     writes the test mesh for FORMAT, prints it as one JSON line
       readdata FILE FORMAT  prints the point and cell data meshio reads, as one JSON line
       writedata FILE FORMAT writes the data test mesh for FORMAT, prints its data

FORMAT is a meshio format name, optionally suffixed with "-binary". Points are printed as
repr() strings so that the Rust side parses them exactly; cells as [type, [[ids...]...]] blocks
in file order.
"""
import json
import sys

import meshio
import numpy as np


def dump(mesh):
    points = [[repr(float(x)) for x in p] for p in mesh.points]
    # meshio turns UInt64 connectivity (as vtkio writes .vtu) into float64: exact for these ids.
    cells = [[b.type, b.data.astype(np.int64).tolist()] for b in mesh.cells]
    print(json.dumps({"points": points, "cells": cells}), flush=True)


def test_mesh(fmt):
    # Exact 32-bit floats for STL; awkward doubles elsewhere.
    if fmt.startswith("stl"):
        pts = [[0, 0, 0], [1, 0, 0], [1, 1, 0.5], [0, 1, 0.25], [2, 0.125, -1]]
    else:
        pts = [[0.1, -0.0, 1e-300], [1 / 3, 0, 0], [1, 1, 0.5], [0, 1, 2.5e10], [2, 0.125, -1]]
    tris = [[0, 1, 2], [0, 2, 3], [1, 4, 2]]
    cells = [("triangle", tris)]
    if fmt.startswith(("medit", "vtk", "vtu", "gmsh")):
        cells = [("tetra", [[0, 1, 2, 4]]), ("triangle", [[0, 2, 3]]), ("line", [[3, 4]])]
    point_data, cell_data = {}, {}
    if fmt == "gmsh":
        # meshio's 4.1 writer needs each node's and each cell's entity for several cell types.
        point_data["gmsh:dim_tags"] = np.array([[3, 1]] * len(pts))
        cell_data["gmsh:geometrical"] = [np.ones(len(c[1]), dtype=int) for c in cells]
        cell_data["gmsh:physical"] = [np.zeros(len(c[1]), dtype=int) for c in cells]
    return meshio.Mesh(
        np.array(pts, dtype=float), cells, point_data=point_data, cell_data=cell_data
    )


def dump_data(mesh):
    # Values as repr() strings (exact; NaN and infinities included), cell data concatenated
    # over the blocks (in file order); meshio's own gmsh:* bookkeeping left out.
    def flat(a):
        return [repr(float(x)) for x in np.asarray(a, dtype=float).reshape(-1)]

    point = {k: flat(v) for k, v in mesh.point_data.items() if not k.startswith("gmsh:")}
    cell = {
        k: [x for block in v for x in flat(block)]
        for k, v in mesh.cell_data.items()
        if not k.startswith("gmsh:")
    }
    print(json.dumps({"point_data": point, "cell_data": cell}), flush=True)


def data_mesh(fmt):
    # One tetrahedron and two triangles (grouped by type, so that meshio's blocks are in file
    # order; the triangles alone for Gmsh), real fields of 1 and 3 components with NaN, infinities and a subnormal.
    pts = np.array([[0.1, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], dtype=float)
    cells = [("tetra", [[0, 1, 2, 3]]), ("triangle", [[0, 1, 4], [1, 2, 4]])]
    density = [np.array([2.5]), np.array([np.inf, -0.0])]
    if fmt.startswith("gmsh"):
        # meshio 5.3's MSH 2.2 reader fails on element data over several cell types.
        cells, density = cells[1:], density[1:]
    point_data = {
        "temperature": np.array([1.5, np.nan, -np.inf, 5e-324, 1 / 3]),
        "velocity": np.arange(15, dtype=float).reshape(5, 3) / 7,
    }
    cell_data = {"density": density}
    if fmt == "gmsh":
        point_data["gmsh:dim_tags"] = np.array([[3, 1]] * len(pts))
        cell_data["gmsh:geometrical"] = [np.ones(len(c[1]), dtype=int) for c in cells]
        cell_data["gmsh:physical"] = [np.zeros(len(c[1]), dtype=int) for c in cells]
    if fmt == "vtu":
        cell_data["region"] = [np.array([7], dtype=np.int32), np.array([8, 9], dtype=np.int32)]
    return meshio.Mesh(pts, cells, point_data=point_data, cell_data=cell_data)


def job(mode, path, fmt):
    binary = fmt.endswith("-binary")
    name = fmt.removesuffix("-binary")
    if mode == "readdata":
        dump_data(meshio.read(path, file_format="gmsh" if name == "gmsh22" else name))
    elif mode == "writedata":
        mesh = data_mesh(name)
        meshio.write(path, mesh, file_format=name, binary=binary)
        dump_data(mesh)
    elif mode == "read":
        dump(meshio.read(path, file_format="gmsh" if name == "gmsh22" else name))
    else:
        mesh = test_mesh(name)
        kwargs = {}
        if name in ("gmsh", "gmsh22", "vtk", "vtu", "ply", "stl"):
            kwargs["binary"] = binary
        meshio.write(path, mesh, file_format=name, **kwargs)
        dump(mesh)


for line in sys.stdin:
    if line.strip():
        job(*line.split())
