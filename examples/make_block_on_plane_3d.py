#!/usr/bin/env python3
"""Writes `block-on-plane-3d.msh` (Gmsh 4.1, ASCII) for `block-on-plane-3d.toml`.

Plain Python, no Gmsh needed: two structured Hex8 boxes with their own nodes (the contact faces
carry coincident but distinct nodes, as the LATIN interface needs):
- volume "plane": [0, 2] x [0, 1] x [-1, 0], volume "block": [0, 2] x [0, 1] x [0, 1],
  each NX x NY x NZ cells;
- surfaces "plane_bottom" (z = -1), "plane_top" (z = 0, of the plane), "block_bottom" (z = 0, of
  the block), "block_top" (z = 1).
Run from this directory: `python3 make_block_on_plane_3d.py`.
"""

NX, NY, NZ = 4, 2, 2
LX, LY, LZ = 2.0, 1.0, 1.0

nodes = []  # (tag, x, y, z)
volumes = {}  # name -> list of hex node tags
surfaces = {}  # name -> list of quad node tags


def body(name, z0, bottom, top):
    base = len(nodes)

    def tag(i, j, k):
        return base + 1 + i + (NX + 1) * (j + (NY + 1) * k)

    for k in range(NZ + 1):
        for j in range(NY + 1):
            for i in range(NX + 1):
                nodes.append((tag(i, j, k), LX * i / NX, LY * j / NY, z0 + LZ * k / NZ))
    hexes = []
    for k in range(NZ):
        for j in range(NY):
            for i in range(NX):
                hexes.append([tag(i, j, k), tag(i + 1, j, k), tag(i + 1, j + 1, k), tag(i, j + 1, k),
                              tag(i, j, k + 1), tag(i + 1, j, k + 1), tag(i + 1, j + 1, k + 1),
                              tag(i, j + 1, k + 1)])
    volumes[name] = hexes
    for face, k in ((bottom, 0), (top, NZ)):
        surfaces[face] = [[tag(i, j, k), tag(i + 1, j, k), tag(i + 1, j + 1, k), tag(i, j + 1, k)]
                          for j in range(NY) for i in range(NX)]


body("plane", -LZ, "plane_bottom", "plane_top")
body("block", 0.0, "block_bottom", "block_top")

surf_names = list(surfaces)
vol_names = list(volumes)
out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames",
       str(len(surf_names) + len(vol_names))]
out += [f'{dim} {t} "{n}"' for dim, names in ((2, surf_names), (3, vol_names))
        for t, n in enumerate(names, 1)]
out.append("$EndPhysicalNames")
# Entities: one surface entity per surface group, one volume entity per volume group (the
# bounding boxes are not used by the reader; the bounding lists are left empty).
out += ["$Entities", f"0 0 {len(surf_names)} {len(vol_names)}"]
out += [f"{t} 0 0 0 0 0 0 1 {t} 0" for names in (surf_names, vol_names)
        for t in range(1, len(names) + 1)]
out.append("$EndEntities")
# Nodes: all in the volume entity of their body.
out += ["$Nodes", f"{len(vol_names)} {len(nodes)} 1 {len(nodes)}"]
per = len(nodes) // len(vol_names)
for v in range(len(vol_names)):
    block = nodes[v * per:(v + 1) * per]
    out.append(f"3 {v + 1} 0 {len(block)}")
    out += [str(n[0]) for n in block]
    out += [f"{n[1]:.17g} {n[2]:.17g} {n[3]:.17g}" for n in block]
out.append("$EndNodes")
nelem = sum(len(v) for v in volumes.values()) + sum(len(s) for s in surfaces.values())
out += ["$Elements", f"{len(surf_names) + len(vol_names)} {nelem} 1 {nelem}"]
tag = 1
for t, n in enumerate(surf_names, 1):
    out.append(f"2 {t} 3 {len(surfaces[n])}")
    for q in surfaces[n]:
        out.append(" ".join(map(str, [tag] + q)))
        tag += 1
for t, n in enumerate(vol_names, 1):
    out.append(f"3 {t} 5 {len(volumes[n])}")
    for h in volumes[n]:
        out.append(" ".join(map(str, [tag] + h)))
        tag += 1
out.append("$EndElements")
with open("block-on-plane-3d.msh", "w") as f:
    f.write("\n".join(out) + "\n")
