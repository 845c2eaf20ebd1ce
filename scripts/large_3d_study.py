#!/usr/bin/env python3
"""The 3D turbine study of BENCHMARKS.md, "Automatic subdomains" / "In studies": the shipped
`examples/turbine-3d-wear.toml` with its method replaced by 2 Monte Carlo runs (no error
estimate, no budget) and the mesh and solver settings given.

Usage: python3 scripts/large_3d_study.py OUT.toml [--split 1] [--nz 12]
           [--subdomains auto|always|never] [--subdomain-dofs N] [--ranks-per-run R]
then `/usr/bin/time -f "%e s %M kB" alea run OUT.toml -q` (the table's lines: --split 0;
--split 1 --subdomains never; --split 1; --split 1 --ranks-per-run 2 under `mpirun -np 2`;
the 2-million-dof model: --split 1 --nz 40)."""
import argparse
import pathlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
ap = argparse.ArgumentParser()
ap.add_argument("out")
ap.add_argument("--split", type=int, default=1)
ap.add_argument("--nz", type=int, default=12)
ap.add_argument("--subdomains", default="auto")
ap.add_argument("--subdomain-dofs", type=int)
ap.add_argument("--ranks-per-run", type=int)
a = ap.parse_args()
text = (ROOT / "examples/turbine-3d-wear.toml").read_text()
head = text[: text.index("[[method]]")]
assert "n_z = 12 }" in head, "the example's mesh line changed"
head = head.replace("n_z = 12 }", f"n_z = {a.nz} }}\nsplit = {a.split}")
solver = f'subdomains = "{a.subdomains}"\n'
if a.subdomain_dofs:
    solver += f"subdomain_dofs = {a.subdomain_dofs}\n"
if a.ranks_per_run:
    solver += f"ranks_per_run = {a.ranks_per_run}\n"
pathlib.Path(a.out).write_text(
    head
    + '[[method]]\ntype = "monte_carlo"\nruns = 2\nlabel = "mc2"\n\n'
    + "[solver]\ntolerance = 1e-6\nmax_iterations = 5000\nsearch_direction_factor = 0.5\n"
    + solver
)
