#!/usr/bin/env python3
"""Compare alea-uq with OpenTURNS on the same points (not part of the Rust tests).

1. Sparse chaos of Ishigami by LARS + corrected LOO, candidate total degrees 8-14, on one
   200-point LHS design: terms kept, reported error, true error 1 - Q2 on 1e5 test points.
   alea's numbers come from `cargo run --example lars_report design.csv test.csv` on the same
   CSV files.
2. Sampling speed: 1e6 draws of a truncated normal and of a 3-D Gaussian copula with
   truncated-normal / lognormal / uniform marginals (alea's side: `cargo bench --bench uq`).

Run from the workspace root with OpenTURNS installed (pip install openturns):
    python3 crates/alea-uq/scripts/ot_compare.py
"""
import math
import os
import subprocess
import sys
import tempfile
import time

import openturns as ot

ot.Log.Show(ot.Log.NONE)
ot.RandomGenerator.SetSeed(1)
dist = ot.JointDistribution([ot.Uniform(-math.pi, math.pi)] * 3)
model = ot.SymbolicFunction(["x1", "x2", "x3"], ["sin(x1) + 7*sin(x2)^2 + 0.1*x3^4*sin(x1)"])
design = ot.LHSExperiment(dist, 200).generate()
test = dist.getSample(100_000)
y = model(design)
yt = model(test)
tmp = tempfile.mkdtemp()
for name, s in (("design.csv", design), ("test.csv", test)):
    with open(os.path.join(tmp, name), "w") as f:
        f.write("x1,x2,x3\n")
        for row in s:
            f.write(",".join(repr(float(v)) for v in row) + "\n")

print("OpenTURNS", ot.__version__)
print("degree,terms,corrected_loo,held_out,fit_ms")
var_t = yt.computeVariance()[0] * (yt.getSize() - 1)
mean_t = yt.computeMean()[0]
ot_rows = {}
for degree in range(8, 15):
    t0 = time.perf_counter()
    enum = ot.LinearEnumerateFunction(3)
    factory = ot.OrthogonalProductPolynomialFactory([ot.LegendreFactory()] * 3, enum)
    size = enum.getStrataCumulatedCardinal(degree)
    basis_sel = ot.LeastSquaresMetaModelSelectionFactory(ot.LARS(), ot.CorrectedLeaveOneOut())
    strategy = ot.LeastSquaresStrategy(design, y, basis_sel)
    algo = ot.FunctionalChaosAlgorithm(design, y, dist, ot.FixedStrategy(factory, size), strategy)
    algo.run()
    res = algo.getResult()
    ms = (time.perf_counter() - t0) * 1e3
    terms = res.getIndices().getSize()
    # Error of the selected basis: the smallest corrected-LOO error along the LARS path.
    err = min(res.getErrorHistory())
    pred = res.getMetaModel()(test)
    sq = sum((a[0] - b[0]) ** 2 for a, b in zip(yt, pred))
    ot_rows[degree] = (terms, err, sq / var_t, ms)
    print(f"{degree},{terms},{err:.4e},{sq / var_t:.4e},{ms:.1f}")

root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
out = subprocess.run(
    ["cargo", "run", "-q", "-p", "alea-uq", "--release", "--example", "lars_report",
     os.path.join(tmp, "design.csv"), os.path.join(tmp, "test.csv")],
    cwd=root, capture_output=True, text=True, check=True).stdout
print("alea-uq (same points)")
print(out.strip())
print("ratios alea / OpenTURNS: terms, reported error, held-out error")
for line in out.strip().splitlines()[1:]:
    d, terms, err, held, _ = line.split(",")
    o = ot_rows[int(d)]
    print(f"degree {d}: {int(terms) / o[0]:.2f} {float(err) / o[1]:.2f} {float(held) / o[2]:.2f}")

# Sampling speed.
print("sampling, 1e6 draws (OpenTURNS):")
tn = ot.TruncatedNormal(1.0, 0.2, 0.5, 1.5)
t0 = time.perf_counter()
tn.getSample(1_000_000)
print(f"  truncated normal: {(time.perf_counter() - t0) * 1e3:.1f} ms")
R = ot.CorrelationMatrix(3)
R[0, 1] = R[1, 0] = 0.5
R[1, 2] = R[2, 1] = 0.3
cop = ot.JointDistribution(
    [ot.TruncatedNormal(1.0, 0.2, 0.5, 1.5), ot.LogNormal(0.0, 0.25, 0.0), ot.Uniform(0.0, 1.0)],
    ot.NormalCopula(R))
t0 = time.perf_counter()
cop.getSample(1_000_000)
print(f"  gaussian copula (3-D): {(time.perf_counter() - t0) * 1e3:.1f} ms")
