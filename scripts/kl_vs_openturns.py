#!/usr/bin/env python3
"""Karhunen-Loeve of the exponential kernel on [-a, a]: alea (Galerkin P1) vs OpenTURNS
(KarhunenLoeveP1Algorithm) on the same uniform mesh, both vs the closed form (Ghanem-Spanos).

    python3 -m venv /tmp/ot && /tmp/ot/bin/pip install openturns
    /tmp/ot/bin/python scripts/kl_vs_openturns.py [a L cells modes]

Prints the closed-form, alea and OpenTURNS eigenvalue lists and their relative errors; alea is
run twice: with its default quadrature of C_ij (column "alea") and with the kernel interpolated
at the nodes, C = M K M (column "alea nodal"), which is OpenTURNS's formulation, so the two
libraries can be compared on the same discrete problem. Also the largest mode difference (up to
sign, in a discrete L2 norm) between alea nodal and OpenTURNS, and the wall times.
"""
import json
import math
import subprocess
import sys
import time

import openturns as ot


def exact_exponential(a, length, count):
    """Largest `count` eigenvalues of exp(-|x-y|/L) on [-a, a] (unit variance)."""
    c = 1.0 / length

    def bisect(f, lo, hi):
        flo = f(lo)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if (f(mid) > 0) == (flo > 0):
                lo = mid
            else:
                hi = mid
        return 0.5 * (lo + hi)

    eps = 1e-12
    lam = []
    for i in range(count):
        w = bisect(lambda w: c * math.cos(w * a) - w * math.sin(w * a),
                   (i * math.pi + eps) / a, ((i + 0.5) * math.pi - eps) / a)
        lam.append(2 * c / (w * w + c * c))
        w = bisect(lambda w: w * math.cos(w * a) + c * math.sin(w * a),
                   ((i + 0.5) * math.pi + eps) / a, ((i + 1) * math.pi - eps) / a)
        lam.append(2 * c / (w * w + c * c))
    return sorted(lam, reverse=True)[:count]


def main():
    a = float(sys.argv[1]) if len(sys.argv) > 1 else 1.0
    length = float(sys.argv[2]) if len(sys.argv) > 2 else 1.0
    cells = int(sys.argv[3]) if len(sys.argv) > 3 else 100
    modes = int(sys.argv[4]) if len(sys.argv) > 4 else 20

    def run_alea(integration):
        out = subprocess.run(
            ["cargo", "run", "-q", "-p", "alea-uq", "--release", "--example", "kl_eigenvalues",
             "--", str(a), str(length), str(cells), str(modes), "exponential", integration],
            check=True, capture_output=True, text=True).stdout
        return json.loads(out)

    alea = run_alea("quadrature")
    nodal = run_alea("nodal")

    t0 = time.perf_counter()
    mesh = ot.IntervalMesher([cells]).build(ot.Interval([-a], [a]))
    model = ot.ExponentialModel([length], [1.0])
    algo = ot.KarhunenLoeveP1Algorithm(mesh, model, 0.0)
    algo.setNbModes(modes)
    algo.run()
    res = algo.getResult()
    ot_seconds = time.perf_counter() - t0
    ot_lam = list(res.getEigenvalues())[:modes]
    ot_modes = res.getModesAsProcessSample()
    verts = [v[0] for v in mesh.getVertices()]
    order = sorted(range(len(verts)), key=lambda i: verts[i])
    assert [round(verts[i], 12) for i in order] == \
        [round(-a + 2 * a * i / cells, 12) for i in range(cells + 1)], "mesh nodes differ"

    exact = exact_exponential(a, length, modes)
    h = 2 * a / cells
    print(f"exponential kernel, unit variance, L = {length}, on [-{a}, {a}], {cells} P1 cells")
    print(f"{'k':>3} {'closed form':>14} {'alea':>14} {'alea nodal':>14} {'OpenTURNS':>14} "
          f"{'alea err':>9} {'nodal err':>9} {'OT err':>9} {'|nodal-OT|/OT':>13} {'mode diff':>9}")
    worst = {"alea": 0.0, "ot": 0.0, "diff": 0.0, "mode": 0.0}
    for k in range(modes):
        ea = abs(alea["eigenvalues"][k] - exact[k]) / exact[k]
        eo = abs(ot_lam[k] - exact[k]) / exact[k]
        en = abs(nodal["eigenvalues"][k] - exact[k]) / exact[k]
        d = abs(nodal["eigenvalues"][k] - ot_lam[k]) / ot_lam[k]
        # Mode difference in the P1 mass norm (trapezoid-like sum is enough for a check).
        om = [ot_modes[k][i][0] for i in order]
        am = nodal["modes"][k]
        dot = sum(x * y for x, y in zip(am, om))
        s = 1.0 if dot >= 0 else -1.0
        md = math.sqrt(h * sum((x - s * y) ** 2 for x, y in zip(am, om)))
        worst = {"alea": max(worst["alea"], ea), "nodal": max(worst.get("nodal", 0.0), en),
                 "ot": max(worst["ot"], eo),
                 "diff": max(worst["diff"], d), "mode": max(worst["mode"], md)}
        print(f"{k + 1:>3} {exact[k]:>14.8e} {alea['eigenvalues'][k]:>14.8e} "
              f"{nodal['eigenvalues'][k]:>14.8e} {ot_lam[k]:>14.8e} "
              f"{ea:>9.2e} {en:>9.2e} {eo:>9.2e} {d:>13.2e} {md:>9.2e}")
    print(f"max relative error vs closed form: alea {worst['alea']:.2e}, "
          f"alea nodal {worst['nodal']:.2e}, OpenTURNS {worst['ot']:.2e}")
    print(f"alea nodal vs OpenTURNS: max relative eigenvalue difference {worst['diff']:.2e}, "
          f"max mode difference {worst['mode']:.2e}")
    print(f"time: alea {alea['seconds']:.3f} s, alea nodal {nodal['seconds']:.3f} s "
          f"(assembly + eigensolve), "
          f"OpenTURNS {ot_seconds:.3f} s (mesh + algorithm)")


if __name__ == "__main__":
    main()
