#!/usr/bin/env python3
"""Dump what meshio reads from each mesh file of this directory, as <stem>.expected.json.

The Rust test `tests/mesh_meshio.rs` reads the same files with aster-nl's readers and
compares. Usage: `python3 meshio_expected.py` (needs `pip install meshio`, and h5py for MED).

MED groups come from meshio's cell_tags / point_tags (families); as MED stores cells type
by type, their cell groups are compared as sets ("group_order": "unordered").

JSON layout:
  points:       [[x, y, z], ...] in meshio order (file order)
  cells:        {meshio_type: [[point indices], ...]} cells of each type in file order
  cell_groups:  {name: [[meshio_type, index among cells of that type], ...]} in file order
  node_groups:  {name: sorted point indices} (the nodes of the group's cells)

Groups: Gmsh 4.1 named physical groups come from meshio's cell_sets; Gmsh 2.2 groups and
unnamed physical groups come from cell_data["gmsh:physical"] plus field_data (name ->
[tag, dim]). Unnamed groups are named GM<tag> (cells) and GN<tag> (nodes), the convention
aster-nl follows. meshio keeps only the first physical tag of a 4.1 entity in
gmsh:physical, so an unnamed second physical group of an entity is invisible here.

meshio does not read the Code_Aster native format (.mail): the expected files of the .mail
meshes are written by hand.
"""
import json
import pathlib
import sys

import meshio

DIM = {
    "vertex": 0, "line": 1, "line3": 1, "triangle": 2, "triangle6": 2, "quad": 2,
    "quad8": 2, "tetra": 3, "hexahedron": 3, "wedge": 3, "pyramid": 3,
}


def dump(path):
    m = meshio.read(path)
    cells = {}
    # (type, index within type) of each cell of each block
    block_ids = []
    for block in m.cells:
        lst = cells.setdefault(block.type, [])
        start = len(lst)
        lst.extend([[int(i) for i in c] for c in block.data])
        block_ids.append([(block.type, start + k) for k in range(len(block.data))])

    if str(path).endswith(".med"):
        return dump_med(m, cells, block_ids)

    groups = {}
    named = {}  # (dim, tag) -> name
    for name, (tag, dim) in m.field_data.items():
        named[(int(dim), int(tag))] = name
    # Named groups: cell_sets when meshio builds them (4.1), else gmsh:physical (2.2).
    sets = {k: v for k, v in m.cell_sets.items() if not k.startswith("gmsh:")}
    if sets:
        for name, per_block in sets.items():
            groups[name] = [block_ids[b][int(i)] for b, idx in enumerate(per_block)
                            for i in idx]
    phys = m.cell_data.get("gmsh:physical", [])
    for b, tags in enumerate(phys):
        for k, tag in enumerate(tags):
            tag = int(tag)
            if tag == 0:
                continue
            key = (DIM[m.cells[b].type], tag)
            if key in named and sets:
                continue  # already taken from cell_sets
            name = named.get(key, f"GM{tag}")
            groups.setdefault(name, []).append(block_ids[b][k])

    # Groups list cells in file order: order by block, then by position in the block.
    order = {cid: n for n, cid in enumerate(c for blk in block_ids for c in blk)}
    for name in groups:
        groups[name].sort(key=lambda c: order[c])
    node_groups = {}
    for name, members in groups.items():
        nodes = sorted({p for (t, i) in members for p in cells[t][i]})
        nn = f"GN{name[2:]}" if name not in named.values() and name.startswith("GM") else name
        node_groups[nn] = nodes

    return {
        "source": f"meshio {meshio.__version__}",
        "points": [[float(x) for x in p] for p in m.points],
        "cells": cells,
        "cell_groups": {k: [list(c) for c in v] for k, v in groups.items()},
        "node_groups": node_groups,
    }


def dump_med(m, cells, block_ids):
    """MED groups are families: cell_tags / point_tags give each family's group names."""
    groups = {}
    for b, fams in enumerate(m.cell_data.get("cell_tags", [])):
        for k, fam in enumerate(fams):
            for g in m.cell_tags.get(fam, []):
                groups.setdefault(g, []).append(block_ids[b][k])
    node_groups = {}
    for i, fam in enumerate(m.point_data.get("point_tags", [])):
        for g in m.point_tags.get(fam, []):
            node_groups.setdefault(g, []).append(i)
    return {
        "source": f"meshio {meshio.__version__}",
        "points": [[float(x) for x in p] + [0.0] * (3 - len(p)) for p in m.points],
        "cells": cells,
        # MED lists cells type by type: group members are compared as sets.
        "cell_groups": {k: sorted(list(c) for c in v) for k, v in groups.items()},
        "node_groups": {k: sorted(v) for k, v in node_groups.items()},
        "group_order": "unordered",
    }


def main():
    here = pathlib.Path(__file__).resolve().parent
    for path in sorted(here.iterdir()):
        if path.suffix in (".msh", ".med"):
            out = path.with_name(path.stem + ".expected.json")
            out.write_text(json.dumps(dump(path), indent=1) + "\n")
            print(f"wrote {out.name}")
        elif path.suffix == ".mail":
            print(f"{path.name}: meshio has no reader for the Code_Aster native format; "
                  f"{path.stem}.expected.json is written by hand", file=sys.stderr)


if __name__ == "__main__":
    main()
