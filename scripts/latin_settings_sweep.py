#!/usr/bin/env python3
"""Mean LATIN iterations of the 225-run 2D turbine study against the true accuracy of its runs,
for several Anderson depths, search-direction factors, tangential / normal search-direction
ratios on the contact interfaces and tolerances (issue 20, "iterations").

Each variant is examples/turbine-2d-wear-reference.toml with its [solver] table edited; the
accuracy is the largest difference of the surrogate's values at the first 50 000 Monte Carlo draws
(piecewise-linear interpolation of the runs, so a bound of the runs' differences) from the same
study solved to tolerance 1e-10.

Usage: python3 scripts/latin_settings_sweep.py [path/to/alea]   (default target/release/alea)
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ALEA = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "target/release/alea")
BASE = open(os.path.join(ROOT, "examples/turbine-2d-wear-reference.toml")).read()

# (Anderson depth, search-direction factor, k_t / k_n on contact interfaces, tolerance). The
# isotropic (5, 0.5, 1, 1e-6) was the example's until issue 20; it now uses (5, 1, 0.25, 1.4e-6).
VARIANTS = [(5, 0.5, 1.0, 1e-10), (5, 0.5, 1.0, 1e-6), (12, 0.5, 1.0, 1e-6), (30, 0.5, 1.0, 1e-6),
            (5, 1.0, 1.0, 1e-6), (5, 1.0, 1.0, 2e-7), (5, 2.0, 1.0, 1e-6), (5, 2.0, 1.0, 5e-8),
            (5, 0.25, 1.0, 2e-6),
            (5, 0.5, 0.25, 1e-6), (5, 0.5, 0.25, 2e-6), (5, 0.5, 0.5, 1e-6), (5, 0.5, 0.5, 2e-6),
            (5, 1.0, 0.125, 1e-6), (5, 1.0, 0.125, 2e-6), (5, 1.0, 0.25, 1e-6),
            (5, 1.0, 0.25, 1.4e-6), (5, 1.0, 0.25, 2e-6), (5, 2.0, 0.25, 5e-7),
            (5, 1.0, 0.25, 1e-10)]


def run(tmp, acc, sdf, tan, tol):
    solver = (f"[solver]\ntolerance = {tol}\nmax_iterations = 5000\n"
              f"search_direction_factor = {sdf}\nsearch_direction_tangential = {tan}\n"
              f"acceleration = {acc}\n")
    # The example's [solver] table (comments and keys up to the next table) replaced.
    text = re.sub(r"\[solver\]\n(?:(?:#.*|[a-z_]+ = .*)\n)*", solver, BASE)
    assert solver in text
    tag = f"{acc}-{sdf}-{tan}-{tol}"
    study = os.path.join(tmp, f"s-{tag}.toml")
    out = os.path.join(tmp, f"o-{tag}")
    open(study, "w").write(text)
    log = subprocess.run([ALEA, "run", study, "--dir", out], capture_output=True, text=True,
                         check=True).stdout
    mean = float(re.search(r"iterations per converged run: min \d+, mean ([0-9.]+)", log)[1])
    with open(os.path.join(out, "samples.csv")) as f:
        rows = [list(map(float, r[2:])) for _, r in zip(range(50_000), list(csv.reader(f))[1:])]
    return mean, rows


with tempfile.TemporaryDirectory() as tmp:
    ref_it, ref = run(tmp, *VARIANTS[0])
    print(f"{'depth':>5} {'k factor':>8} {'k_t/k_n':>7} {'tolerance':>9} {'mean it.':>8} "
          f"{'max |dq| per quantity':>24}")
    print(f"{5:>5} {0.5:>8} {1.0:>7} {1e-10:>9.0e} {ref_it:>8.1f}   (reference)")
    for acc, sdf, tan, tol in VARIANTS[1:]:
        it, rows = run(tmp, acc, sdf, tan, tol)
        worst = [max(abs(a[j] - b[j]) for a, b in zip(rows, ref)) for j in range(len(ref[0]))]
        print(f"{acc:>5} {sdf:>8} {tan:>7} {tol:>9.1e} {it:>8.1f}   "
              + "  ".join(f"{w:.2e}" for w in worst), flush=True)
