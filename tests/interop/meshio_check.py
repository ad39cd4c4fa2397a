"""Independent reader and writer for tests/interop.rs: Python meshio.

usage: meshio_check.py read FILE FORMAT      prints the mesh meshio reads, as JSON
       meshio_check.py write FILE FORMAT     writes the test mesh for FORMAT, prints it as JSON

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
    print(json.dumps({"points": points, "cells": cells}))


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


def main():
    mode, path, fmt = sys.argv[1:4]
    binary = fmt.endswith("-binary")
    name = fmt.removesuffix("-binary")
    if mode == "read":
        dump(meshio.read(path, file_format="gmsh" if name == "gmsh22" else name))
    else:
        mesh = test_mesh(name)
        kwargs = {}
        if name in ("gmsh", "gmsh22", "vtk", "vtu", "ply", "stl"):
            kwargs["binary"] = binary
        meshio.write(path, mesh, file_format=name, **kwargs)
        dump(mesh)


main()
