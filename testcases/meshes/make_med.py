#!/usr/bin/env python3
"""Write the MED test meshes of this directory with meshio (no SALOME needed).

    python3 make_med.py   (needs meshio and h5py)

meshio writes the oldest HDF5 layout (version 0 superblock, symbol-table groups, 64-bit
integers). Recent MED files use the HDF5 1.8 layout: version 2 superblock, new-style groups
that track link creation order (more than 8 members go to "dense" storage: a fractal heap
indexed by B-trees), and usually 32-bit integers. `*_med4.med` rewrites a meshio file in
that layout, so that the reader is tested on both.

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


# line_med: 13 nodes on a line, 12 SEG2 cells each in its own family (more families than
# a compact group holds) and in ALL, two POI1 cells; one node group per node.
n = 13
points = np.array([[0.1 * i, 0.0, 0.0] for i in range(n)])
cells = [("line", np.array([[i, i + 1] for i in range(n - 1)])), ("vertex", np.array([[0], [n - 1]]))]
m = meshio.Mesh(points, cells)
m.cell_data["cell_tags"] = [np.array([-(i + 1) for i in range(n - 1)]), np.array([-13, -14])]
m.cell_tags = {-(i + 1): [f"SEG{i + 1}", "ALL"] for i in range(n - 1)}
m.cell_tags[-13] = ["PA"]
m.cell_tags[-14] = ["PB", "PTS"]
m.point_data["point_tags"] = np.array([i + 1 for i in range(n)])
m.point_tags = {i + 1: [f"G{i + 1}"] for i in range(n)}
meshio.write("line_med.med", m, file_format="med")


def rewrite_like_med4(src, dst):
    """Copy `src` into `dst` with the HDF5 layout of the MED library (see the top)."""
    import h5py

    def ints(v):
        return v.astype("i4") if isinstance(v, np.ndarray) else np.int32(v)

    with h5py.File(src, "r") as s, h5py.File(dst, "w", libver=("v108", "v108"),
                                            track_order=True) as d:
        def copy(sg, dg):
            for k, v in sg.attrs.items():
                dg.attrs.create(k, v, dtype="i4") if isinstance(v, np.integer) else dg.attrs.__setitem__(k, v)
            for name, obj in sg.items():
                if isinstance(obj, h5py.Group):
                    copy(obj, dg.create_group(name, track_order=True))
                    continue
                if obj.dtype.kind == "i" and obj.dtype.shape == ():
                    ds = dg.create_dataset(name, data=ints(obj[()]))
                else:  # character tables (arrays of 80 or 16 bytes) and reals, as they are
                    ds = dg.create_dataset(name, shape=obj.shape, dtype=obj.dtype)
                    buf = np.empty(obj.shape, dtype=obj.dtype)
                    obj.id.read(h5py.h5s.ALL, h5py.h5s.ALL, buf, mtype=obj.id.get_type())
                    ds.id.write(h5py.h5s.ALL, h5py.h5s.ALL, buf, mtype=obj.id.get_type())
                for k, v in obj.attrs.items():
                    ds.attrs.create(k, v, dtype="i4") if isinstance(v, np.integer) else ds.attrs.__setitem__(k, v)
        copy(s, d)


# beam_med (testcases/beam_med.comm): a straight tube along X, L = 1, 20 SEG2 cells in
# Tube, its end nodes in BaseL and BaseR, written in the MED-library layout.
n = 21
points = np.array([[i / (n - 1), 0.0, 0.0] for i in range(n)])
m = meshio.Mesh(points, [("line", np.array([[i, i + 1] for i in range(n - 1)]))])
m.cell_data["cell_tags"] = [np.full(n - 1, -1)]
m.cell_tags = {-1: ["Tube"]}
m.point_data["point_tags"] = np.array([1] + [0] * (n - 2) + [2])
m.point_tags = {1: ["BaseL"], 2: ["BaseR"]}
meshio.write("beam_med_meshio.med", m, file_format="med")

rewrite_like_med4("plate_med.med", "plate_med4.med")
rewrite_like_med4("line_med.med", "line_med4.med")
rewrite_like_med4("beam_med_meshio.med", "../beam_med.med")
import os
os.remove("beam_med_meshio.med")
print("wrote plate_med.med, solid_med.med, line_med.med, plate_med4.med, line_med4.med, ../beam_med.med")
