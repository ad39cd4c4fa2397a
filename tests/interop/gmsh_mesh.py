"""Meshes a labelled geometry with real Gmsh (its Python API) for tests/it/gmsh_real.rs.

Two unit cubes side by side, glued by OpenCASCADE's boolean fragments so that they share their
interface; physical groups: the volumes "left" and "right" (dimension 3), their common face
"interface" and the far face of the left cube "inlet" (dimension 2), and one edge of the
interface "corner" (dimension 1). Written as MSH 4.1 ASCII, MSH 4.1 binary and MSH 2.2 ASCII
into DIR; prints, as JSON, what Gmsh itself says: the physical groups with their names, and the
number of elements of each physical group and of each elementary entity in a group, per
dimension.

usage: python3 gmsh_mesh.py DIR
"""

import json
import os
import sys

import gmsh


def main(out):
    gmsh.initialize(["gmsh", "-nopopup"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("two_cubes")
        occ = gmsh.model.occ
        a = occ.addBox(0, 0, 0, 1, 1, 1)
        b = occ.addBox(1, 0, 0, 1, 1, 1)
        occ.fragment([(3, a)], [(3, b)])
        occ.synchronize()
        volumes = sorted(t for _, t in gmsh.model.getEntities(3))
        left, right = volumes

        def faces(v):
            return {t for _, t in gmsh.model.getBoundary([(3, v)], oriented=False)}

        shared = sorted(faces(left) & faces(right))
        assert len(shared) == 1, shared
        interface = shared[0]

        def centre(dim, tag):
            return gmsh.model.occ.getCenterOfMass(dim, tag)

        inlet = [t for t in faces(left) if abs(centre(2, t)[0]) < 1e-9]
        assert len(inlet) == 1, inlet
        edges = sorted(
            t for _, t in gmsh.model.getBoundary([(2, interface)], oriented=False)
        )
        gmsh.model.addPhysicalGroup(3, [left], 11, "left")
        gmsh.model.addPhysicalGroup(3, [right], 12, "right")
        gmsh.model.addPhysicalGroup(2, [interface], 21, "interface")
        gmsh.model.addPhysicalGroup(2, inlet, 22, "inlet")
        gmsh.model.addPhysicalGroup(1, [edges[0]], 31, "corner")
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.35)
        gmsh.model.mesh.generate(3)

        groups = []
        for dim, tag in gmsh.model.getPhysicalGroups():
            name = gmsh.model.getPhysicalName(dim, tag)
            entities = []
            for e in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                types, tags, _ = gmsh.model.mesh.getElements(dim, e)
                entities.append([int(e), sum(len(t) for t in tags)])
            groups.append(
                {"dim": dim, "tag": tag, "name": name, "entities": entities}
            )
        for name, version, binary in [
            ("t41.msh", 4.1, 0),
            ("t41b.msh", 4.1, 1),
            ("t22.msh", 2.2, 0),
        ]:
            gmsh.option.setNumber("Mesh.MshFileVersion", version)
            gmsh.option.setNumber("Mesh.Binary", binary)
            gmsh.write(os.path.join(out, name))
        print(json.dumps({"version": gmsh.__version__, "groups": groups}))
    finally:
        gmsh.finalize()


if __name__ == "__main__":
    main(sys.argv[1])
