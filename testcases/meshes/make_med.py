#!/usr/bin/env python3
"""Write the MED test meshes of this directory with meshio (no SALOME needed).

    python3 make_med.py   (needs meshio and h5py)

Groups are written as MED families: each node/cell carries a family number, and each
family lists the groups it belongs to (FAS/<mesh>/NOEUD and ELEME). The meshes are small
and hand-made; meshio_expected.py then records what meshio reads back from them.
"""
import meshio
import numpy as np

# plate_med: 2D (ESP=2) square split in a quad and two triangles, edges, a point.
points = np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 1.0], [1.0, 1.0],
                   [2.0, 1.0], [0.1, 0.2]])
cells = [
    ("vertex", np.array([[2]])),
    ("line", np.array([[0, 1], [1, 2]])),
    ("quad", np.array([[0, 1, 4, 3]])),
    ("triangle", np.array([[1, 2, 5], [1, 5, 4]])),
]
m = meshio.Mesh(points, cells)
# Families: cells -1 BOTTOM, -2 PLATE, -3 PLATE+RIGHT, -4 CORNER; nodes 1 LEFT, 2 LEFT+TOP
m.cell_data["cell_tags"] = [np.array([-4]), np.array([-1, -1]), np.array([-2]),
                            np.array([-3, -2])]
m.cell_tags = {-1: ["BOTTOM"], -2: ["PLATE"], -3: ["PLATE", "RIGHT"], -4: ["CORNER"]}
m.point_data["point_tags"] = np.array([1, 0, 0, 2, 0, 0, 0])
m.point_tags = {1: ["LEFT"], 2: ["LEFT", "TOP"]}
meshio.write("plate_med.med", m, file_format="med")

# solid_med: 3D, one hexahedron, one tetrahedron and a quadratic edge; no groups.
points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1],
                   [1, 1, 1], [0, 1, 1], [2, 0, 0], [1.5, 0, 0.5]], dtype=float) / 3.0
cells = [
    ("hexahedron", np.array([[0, 1, 2, 3, 4, 5, 6, 7]])),
    ("tetra", np.array([[1, 8, 2, 5]])),
    ("line3", np.array([[1, 8, 9]])),
]
meshio.write("solid_med.med", meshio.Mesh(points, cells), file_format="med")
print("wrote plate_med.med, solid_med.med")
