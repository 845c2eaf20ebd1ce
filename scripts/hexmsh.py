"""Structured Hex8 boxes and their Gmsh 4.1 ASCII file, for the scripts that write meshes without
Gmsh (`examples/make_block_on_plane_3d.py`, `scripts/ccx_slide.py`).

Each box has its own nodes (boxes in contact carry coincident but distinct nodes, as the LATIN
interface needs); its bottom (z = z0) and top (z = z0 + lz) faces are quad groups. In the file,
every group is a physical group with one entity of its own, and each box's nodes belong to its
volume entity.
"""


def hex_box(nodes, origin, lengths, counts):
    """Appends the nodes (tag, x, y, z) of a box of `counts` = (nx, ny, nz) cells to `nodes`;
    returns its hexes and its bottom and top quads (node tags)."""
    (x0, y0, z0), (lx, ly, lz), (nx, ny, nz) = origin, lengths, counts
    first = len(nodes) + 1

    def tag(i, j, k):
        return first + i + (nx + 1) * (j + (ny + 1) * k)

    for k in range(nz + 1):
        for j in range(ny + 1):
            for i in range(nx + 1):
                nodes.append((tag(i, j, k), x0 + lx * i / nx, y0 + ly * j / ny, z0 + lz * k / nz))
    hexes = [[tag(i, j, k), tag(i + 1, j, k), tag(i + 1, j + 1, k), tag(i, j + 1, k),
              tag(i, j, k + 1), tag(i + 1, j, k + 1), tag(i + 1, j + 1, k + 1), tag(i, j + 1, k + 1)]
             for k in range(nz) for j in range(ny) for i in range(nx)]
    faces = [[[tag(i, j, k), tag(i + 1, j, k), tag(i + 1, j + 1, k), tag(i, j + 1, k)]
              for j in range(ny) for i in range(nx)] for k in (0, nz)]
    return hexes, faces[0], faces[1]


def write_msh41(path, volumes, surfaces):
    """Writes `volumes` (name -> (its nodes, its hexes)) and `surfaces` (name -> quads)."""
    surf, vol = list(surfaces), list(volumes)
    nnodes = sum(len(n) for n, _ in volumes.values())
    out = ["$MeshFormat", "4.1 0 8", "$EndMeshFormat", "$PhysicalNames", str(len(surf) + len(vol))]
    out += [f'2 {t} "{n}"' for t, n in enumerate(surf, 1)]
    out += [f'3 {t} "{n}"' for t, n in enumerate(vol, 1)]
    # Entities: bounding boxes are not used by the reader (left zero), no bounding lists.
    out += ["$EndPhysicalNames", "$Entities", f"0 0 {len(surf)} {len(vol)}"]
    out += [f"{t} 0 0 0 0 0 0 1 {t} 0" for names in (surf, vol) for t in range(1, len(names) + 1)]
    out += ["$EndEntities", "$Nodes", f"{len(vol)} {nnodes} 1 {nnodes}"]
    for v, name in enumerate(vol, 1):
        block = volumes[name][0]
        out.append(f"3 {v} 0 {len(block)}")
        out += [str(n[0]) for n in block]
        out += [f"{n[1]:.17g} {n[2]:.17g} {n[3]:.17g}" for n in block]
    out.append("$EndNodes")
    nelem = sum(len(h) for _, h in volumes.values()) + sum(len(s) for s in surfaces.values())
    out += ["$Elements", f"{len(surf) + len(vol)} {nelem} 1 {nelem}"]
    tag = 1
    for dim, kind, groups in ((2, 3, [surfaces[n] for n in surf]),
                              (3, 5, [volumes[n][1] for n in vol])):
        for t, cells in enumerate(groups, 1):
            out.append(f"{dim} {t} {kind} {len(cells)}")
            for c in cells:
                out.append(" ".join(map(str, [tag] + c)))
                tag += 1
    out.append("$EndElements")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
