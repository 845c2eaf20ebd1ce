#!/usr/bin/env python3
"""Writes `block-on-plane-3d.msh` (Gmsh 4.1, ASCII) for `block-on-plane-3d.toml`.

Plain Python, no Gmsh needed (`scripts/hexmsh.py`): two structured Hex8 boxes with their own
nodes (the contact faces carry coincident but distinct nodes, as the LATIN interface needs):
- volume "plane": [0, 2] x [0, 1] x [-1, 0], volume "block": [0, 2] x [0, 1] x [0, 1],
  each NX x NY x NZ cells;
- surfaces "plane_bottom" (z = -1), "plane_top" (z = 0, of the plane), "block_bottom" (z = 0, of
  the block), "block_top" (z = 1).
Run from this directory: `python3 make_block_on_plane_3d.py`.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from hexmsh import hex_box, write_msh41  # noqa: E402

NX, NY, NZ = 4, 2, 2
LX, LY, LZ = 2.0, 1.0, 1.0

nodes = []  # (tag, x, y, z), both boxes
volumes, surfaces = {}, {}
for name, z0 in (("plane", -LZ), ("block", 0.0)):
    start = len(nodes)
    hexes, bottom, top = hex_box(nodes, (0.0, 0.0, z0), (LX, LY, LZ), (NX, NY, NZ))
    volumes[name] = (nodes[start:], hexes)
    surfaces[f"{name}_bottom"], surfaces[f"{name}_top"] = bottom, top

write_msh41("block-on-plane-3d.msh", volumes, surfaces)
