#!/usr/bin/env python3
"""The large-sliding benchmark (issue 21): a steel block pressed by 10 MPa on a clamped steel
base and slid by 0.8 mm (8 base cells) by an imposed displacement of its top, Coulomb friction
mu = 0.2, solved by alea (`sliding = "large"`) and by CalculiX (surface-to-surface contact,
which re-finds the contact pairs in the deformed configuration) on the same Hex8 meshes.

Geometry (mm): base [0, 3] x [0, 1] x [-0.5, 0], 30 x 10 x 5 cells times `--refine`; block
[0.5, 1.5] x [0.25, 0.75] x [0, 0.5], 7 x 4 x 4 cells times `--refine` (the contact faces do
not match: mortar in alea). Block top: ux = 0.8, uy = 0, pressure 10 MPa; base bottom clamped.

Closed form (resultants; exact for any elastic field, in the slid configuration): normal force
N = 10 x 0.5 = 5 N, friction T = mu N = 1 N; the base's bottom reactions have their normal
centroid at x_R = 1.0 + 0.8 + mu x 0.5 (block moment) + mu x 0.5 (base moment) = 2.0 mm
(the pairing of the initial configuration would give 1.2 mm).

Usage:
    python3 scripts/ccx_slide.py OUTDIR [--refine R] [--alea target/release/alea] [--ccx ccx]
writes OUTDIR/slide.msh, slide.toml (alea) and slide.inp (CalculiX), runs both when the
executables are found, and prints time and answer side by side.
"""

import argparse
import base64
import os
import re
import resource
import shutil
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hexmsh import hex_box, write_msh41  # noqa: E402

E, NU, P, MU, SLIDE = 210e3, 0.3, 10.0, 0.2, 0.8


def boxes(refine):
    r = refine
    return [
        ("base", (0.0, 0.0, -0.5), (3.0, 1.0, 0.5), (30 * r, 10 * r, 5 * r)),
        ("block", (0.5, 0.25, 0.0), (1.0, 0.5, 0.5), (7 * r, 4 * r, 4 * r)),
    ]


def build(refine):
    """Nodes (tag, x, y, z) of both bodies, the nodes and hexes of each body, and the quads of
    each face group (bottom / top per body)."""
    nodes, volumes, quads = [], {}, {}
    for name, x0, l, n in boxes(refine):
        start = len(nodes)
        hexes, bottom, top = hex_box(nodes, x0, l, n)
        volumes[name] = (nodes[start:], hexes)
        quads[f"{name}_bottom"], quads[f"{name}_top"] = bottom, top
    return nodes, volumes, quads


TOML = """# Written by scripts/ccx_slide.py: a block pressed on a base and slid by {slide} mm (8 base
# cells), large sliding (the mortar pairing re-found in the deformed configuration).
[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "gmsh"
file = "slide.msh"

[analysis]
type = "solid"

[[substructure]]
name = "base"
cells = "base"
young = {e}
poisson = {nu}
constraint = [ {{ group = "base_bottom", x = 0.0, y = 0.0, z = 0.0 }} ]

[[substructure]]
name = "block"
cells = "block"
young = {e}
poisson = {nu}
constraint = [ {{ group = "block_top", x = {slide}, y = 0.0 }} ]
load = [ {{ name = "press", group = "block_top", traction = [0.0, 0.0, -{p}] }} ]

[[interface]]
name = "contact"
side1 = ["base", "base_top"]
side2 = ["block", "block_bottom"]
law = "coulomb"
mu = {mu}
pairing = "mortar"
sliding = "large"

[solver]
tolerance = 1e-6
"""


def write_inp(path, nodes, hexes, quads, refine, increment):
    h = 0.1 / refine
    out = ["*HEADING", "block slid 0.8 mm over a base (scripts/ccx_slide.py)", "*NODE"]
    out += [f"{n[0]}, {n[1]:.17g}, {n[2]:.17g}, {n[3]:.17g}" for n in nodes]
    eid = 1
    first = {}
    for name, hs in hexes.items():
        out.append(f"*ELEMENT, TYPE=C3D8, ELSET={name.upper()}")
        first[name] = eid
        for hx in hs:
            out.append(", ".join(map(str, [eid] + hx)))
            eid += 1
    # Faces of the C3D8 (ccx numbering): S1 = nodes 1-2-3-4 (bottom), S2 = 5-6-7-8 (top).
    for name, hs in hexes.items():
        _, _, _, n = [b for b in boxes_cache if b[0] == name][0]
        per_layer = n[0] * n[1]
        bottom = [first[name] + e for e in range(per_layer)]
        top = [first[name] + len(hs) - per_layer + e for e in range(per_layer)]
        out.append(f"*ELSET, ELSET={name.upper()}_BOT")
        out += [", ".join(map(str, bottom[i:i + 16])) for i in range(0, len(bottom), 16)]
        out.append(f"*ELSET, ELSET={name.upper()}_TOP")
        out += [", ".join(map(str, top[i:i + 16])) for i in range(0, len(top), 16)]
    for g, qs in quads.items():
        tags = sorted({t for q in qs for t in q})
        out.append(f"*NSET, NSET=N{g.upper()}")
        out += [", ".join(map(str, tags[i:i + 16])) for i in range(0, len(tags), 16)]
    out += ["*SURFACE, NAME=SBASE, TYPE=ELEMENT", "BASE_TOP, S2",
            "*SURFACE, NAME=SBLOCK, TYPE=ELEMENT", "BLOCK_BOT, S1",
            "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E}, {NU}",
            "*SOLID SECTION, ELSET=BASE, MATERIAL=STEEL",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
            "*SURFACE INTERACTION, NAME=SI",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            # Penalty stiffness: 100 x E / h (MPa/mm), tension at large clearance 0.
            f"{100 * E / h:.6g}, 0.0",
            "*FRICTION", f"{MU}, {100 * E / h:.6g}",
            "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE",
            "SBLOCK, SBASE",
            "*BOUNDARY", "NBASE_BOTTOM, 1, 3, 0.0",
            "NBLOCK_TOP, 2, 2, 0.0",
            # Step 1: press, step 2: slide (CalculiX follows the slide in increments).
            "*STEP, INC=1000", "*STATIC", "0.1, 1.0, 1e-6, 0.25",
            "*BOUNDARY", "NBLOCK_TOP, 1, 1, 0.0",
            "*DLOAD", f"BLOCK_TOP, P2, {P}",
            "*END STEP",
            "*STEP, INC=1000", "*STATIC", f"{increment}, 1.0, 1e-6, {increment}",
            "*BOUNDARY", f"NBLOCK_TOP, 1, 1, {SLIDE}",
            "*NODE PRINT, NSET=NBASE_BOTTOM", "RF",
            "*END STEP"]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def vtu_arrays(path, names):
    """Named point arrays and the points of a base64 VTU written by alea (UInt64 headers)."""
    text = open(path).read()
    out = {}
    for name in names + ["Points"]:
        if name == "Points":
            m = re.search(r"<Points>\s*<DataArray[^>]*>([^<]*)</DataArray>", text)
        else:
            m = re.search(r'<DataArray[^>]*Name="%s"[^>]*>([^<]*)</DataArray>' % name, text)
        raw = base64.b64decode(m.group(1).strip())
        (nbytes,) = struct.unpack("<Q", raw[:8])
        out[name] = struct.unpack("<%dd" % (nbytes // 8), raw[8:8 + nbytes])
    return out


def centroid(points, forces):
    """Sum of the z forces and the x centroid of their (normal) part."""
    fz = sum(forces)
    return fz, sum(f * x for f, x in zip(forces, points)) / fz


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_alea(alea, outdir):
    t0, c0 = time.time(), cpu_children()
    p = subprocess.run([alea, "solve", os.path.join(outdir, "slide.toml"), "--out",
                        os.path.join(outdir, "alea")], capture_output=True, text=True)
    wall = (time.time() - t0, cpu_children() - c0)
    if p.returncode != 0:
        print(p.stdout, p.stderr)
        return None
    a = vtu_arrays(os.path.join(outdir, "alea", "slide", "base.vtu"), ["reaction"])
    pts, r = a["Points"], a["reaction"]
    n = len(pts) // 3
    # Base-bottom nodes (z = -0.5): reactions.
    sel = [i for i in range(n) if abs(pts[3 * i + 2] + 0.5) < 1e-9]
    fz, xr = centroid([pts[3 * i] for i in sel], [r[3 * i + 2] for i in sel])
    fx = sum(r[3 * i] for i in sel)
    lines = [ln for ln in p.stdout.splitlines() if "large sliding" in ln or "converged" in ln]
    return wall, fz, fx, xr, lines


def run_ccx(ccx, outdir, coords):
    t0, c0 = time.time(), cpu_children()
    p = subprocess.run([ccx, "-i", "slide"], cwd=outdir, capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1"))
    wall = (time.time() - t0, cpu_children() - c0)
    dat = os.path.join(outdir, "slide.dat")
    if not os.path.exists(dat):
        print(p.stdout[-3000:], p.stderr[-2000:])
        return None
    # The last block of "forces (fx,fy,fz)" lines: node, fx, fy, fz.
    blocks, cur = [], None
    for ln in open(dat):
        if "forces (fx,fy,fz)" in ln:
            cur = []
            blocks.append(cur)
        elif cur is not None:
            v = ln.split()
            if len(v) == 4:
                try:
                    cur.append((int(v[0]), float(v[1]), float(v[2]), float(v[3])))
                except ValueError:
                    pass
    last = blocks[-1]
    fz, xr = centroid([coords[n][0] for n, _, _, _ in last], [f for _, _, _, f in last])
    fx = sum(f for _, f, _, _ in last)
    incs = len(re.findall(r"increment\s+\d+ attempt", p.stdout))
    return wall, fz, fx, xr, incs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--refine", type=int, default=1)
    ap.add_argument("--alea", default="target/release/alea")
    ap.add_argument("--ccx", default=shutil.which("ccx") or "ccx")
    # CalculiX re-finds its contact pairs at the start of each increment: its answer lags by
    # one increment of slide (measured: x_R = 1.960 with 0.05, i.e. 0.04 mm increments).
    ap.add_argument("--increment", type=float, default=0.05,
                    help="CalculiX's fixed time increment of the slide step (fraction of it)")
    ap.add_argument("--skip-ccx", action="store_true")
    a = ap.parse_args()
    global boxes_cache
    boxes_cache = boxes(a.refine)
    os.makedirs(a.outdir, exist_ok=True)
    nodes, volumes, quads = build(a.refine)
    write_msh41(os.path.join(a.outdir, "slide.msh"), volumes, quads)
    hexes = {name: h for name, (_, h) in volumes.items()}
    with open(os.path.join(a.outdir, "slide.toml"), "w") as f:
        f.write(TOML.format(slide=SLIDE, e=E, nu=NU, p=P, mu=MU))
    write_inp(os.path.join(a.outdir, "slide.inp"), nodes, hexes, quads, a.refine, a.increment)
    coords = {n[0]: (n[1], n[2], n[3]) for n in nodes}
    print(f"refine {a.refine}: {sum(len(h) for h in hexes.values())} Hex8 cells, {len(nodes)} nodes")
    print("closed form: base reaction Rz = 5 N, Rx = -1 N, normal centroid x_R = 2.0 mm "
          "(initial pairing: 1.2 mm)")
    if shutil.which(a.alea) or os.path.exists(a.alea):
        r = run_alea(a.alea, a.outdir)
        if r:
            wall, fz, fx, xr, lines = r
            print(f"alea:     {wall[0]:7.2f} s wall, {wall[1]:7.2f} s CPU, Rz = {fz:.6f} N, Rx = {fx:.6f} N, x_R = {xr:.5f} mm")
            for ln in lines:
                print("          " + ln.strip())
    if not a.skip_ccx and (shutil.which(a.ccx) or os.path.exists(a.ccx)):
        r = run_ccx(a.ccx, a.outdir, coords)
        if r:
            wall, fz, fx, xr, incs = r
            print(f"CalculiX: {wall[0]:7.2f} s wall, {wall[1]:7.2f} s CPU, Rz = {fz:.6f} N, Rx = {fx:.6f} N, x_R = {xr:.5f} mm "
                  f"({incs} increment attempts)")


boxes_cache = boxes(1)

if __name__ == "__main__":
    sys.exit(main())
