#!/usr/bin/env python3
"""Issue 40's acceptance on cases with EXACT statistics, built for it: contact in each, a kink
off every grid and an atom at zero (a fit or a gap that opens), 2 to 4 parameters, 2D and 3D.

usage: validation_acceptance.py [ALEA] [--keep DIR] [--set 1|3|4|5|6]

ALEA defaults to target/release/alea (built first). Each case is a study written here, run with
`alea run --threads 2`, and its every method's budget rows (mean, std, q0.05 - q0.95, P(N > t))
are compared with the exact statistics of the SAME discretised model:

- shrink fits of two rings (plane stress, frictionless, Quad8): while the fit is closed the
  problem is linear and each ring's stiffness scales with its modulus, so the normal force over
  the contact is exactly `N = max(0, d + d2) / (alpha / E1 + beta / E2)` (radial interference
  `d`, a second interference `d2` (a coating), the shaft's and the hub's moduli `E1`, `E2`);
  `alpha`, `beta` are fitted by least squares on the study's own tight runs (the fit's largest
  relative residual is printed: the formula is exact to the solver's tolerance), and where the
  fit is loose the runs' answer is exactly 0 (an atom of probability).
- a block pressed on a plane in 3D (Hex8, Poisson's ratio 0, top moved down by 1e-3 mm, initial
  gap `g`): uniaxial strain, which the elements represent exactly, so
  `N = 2 max(0, 1e-3 - g) / (1 / Eb + 1 / Ep)` with no fit.

The exact statistics integrate the law of `d` (or `g`), uniform, in closed form given the other
parameters, and the others by a midpoint rule (40 points per parameter); quantiles by bisection
on the exact cdf. A row is covered when |estimate - exact| <= total (the estimate users read:
the value corrected by the validation runs where they detect the surrogate's error); the tightness
is the median of total / |error| over the rows whose error exceeds the sampling half-width.
These cases are the EVALUATION set: the validation rule was chosen on tests/budget_coverage.rs.
"""
import itertools
import json
import math
import os
import sqlite3
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ORDERS = [0.05, 0.25, 0.5, 0.75, 0.95]

RINGS = """
[study]
seed = {seed}
title = "{title}"

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "concentric_rings"
kind = "quad8"
params = {{ r_in = 50.0, r_contact = 80.0, r_out = 120.0, angle_deg = 90.0, n_inner = 3, n_outer = 3, n_theta = 8 }}

[analysis]
type = "plane_stress"
thickness = 1.0

{parameters}

[[substructure]]
name = "shaft"
cells = "inner"
young = "{e1}"
poisson = 0.3
constraint = [ {{ group = "inner_side0", y = 0.0 }}, {{ group = "inner_side1", x = 0.0 }} ]

[[substructure]]
name = "hub"
cells = "outer"
young = "{e2}"
poisson = 0.3
constraint = [ {{ group = "outer_side0", y = 0.0 }}, {{ group = "outer_side1", x = 0.0 }} ]

[[interface]]
name = "fit"
side1 = ["shaft", "inner_contact"]
side2 = ["hub", "outer_contact"]
law = "coulomb"
mu = 0.0
gap = "{gap}"

[[quantity]]
name = "N"
kind = "contact_pressure"
interface = "fit"
unit = "N"
thresholds = [{threshold}]

{methods}

[statistics]
samples = 100000
"""

BLOCK = """
[study]
seed = {seed}
title = "{title}"

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "gmsh"
file = "{mesh}"

[analysis]
type = "solid"

{parameters}

[[substructure]]
name = "plane"
cells = "plane"
young = "{ep}"
poisson = 0.0
constraint = [{{ group = "plane_bottom", x = 0.0, y = 0.0, z = 0.0 }}]

[[substructure]]
name = "block"
cells = "block"
young = "{eb}"
poisson = 0.0
constraint = [{{ group = "block_top", x = 0.0, y = 0.0, z = -1e-3 }}]

[[interface]]
name = "contact"
side1 = ["plane", "plane_top"]
side2 = ["block", "block_bottom"]
law = "coulomb"
mu = 0.3
gap = "g"

[[quantity]]
name = "N"
kind = "contact_pressure"
interface = "contact"
unit = "N"
thresholds = [{threshold}]

{methods}

[solver]
tolerance = 1e-8

[statistics]
samples = 100000
"""


def parameter(name, law):
    """A `[[parameter]]` table: `law` is `(lo, hi)` (uniform) or a dict of the law's keys."""
    if isinstance(law, tuple):
        law = {"law": "uniform", "lo": law[0], "hi": law[1]}
    keys = "".join("%s = %s\n" % (k, '"%s"' % v if isinstance(v, str) else repr(v))
                   for k, v in law.items())
    return '[[parameter]]\nname = "%s"\n%s' % (name, keys)


def quantile(law, u):
    """The quantile of order `u` of a law of `parameter` (those the cases use)."""
    from statistics import NormalDist
    if isinstance(law, tuple):
        return law[0] + (law[1] - law[0]) * u
    kind = law["law"]
    if kind == "normal":
        return NormalDist(law["mean"], law["std"]).inv_cdf(u)
    if kind == "lognormal":
        s2 = math.log(1.0 + (law["std"] / law["mean"]) ** 2)
        return math.exp(math.log(law["mean"]) - s2 / 2 + math.sqrt(s2) * NormalDist().inv_cdf(u))
    if kind == "triangular":
        a, c, b = law["lo"], law["mode"], law["hi"]
        f = (c - a) / (b - a)
        if u < f:
            return a + math.sqrt(u * (b - a) * (c - a))
        return b - math.sqrt((1 - u) * (b - a) * (b - c))
    raise ValueError(kind)


def methods(*specs):
    return "\n".join("[[method]]\n" + "\n".join("%s = %s" % kv for kv in s) + "\n" for s in specs)


PL = lambda n: [("type", '"piecewise_linear"'), ("points_per_dim", n)]
PC = lambda p: [("type", '"pc_regression"'), ("degree", p)]
PROJ = lambda p: [("type", '"pc_projection"'), ("degree", p)]
POLY = lambda p: [("type", '"polynomial"'), ("degree", p)]
ADAPT = lambda n: [("type", '"adaptive"'), ("max_runs", n)]
GOAL = lambda n, t, tol: [("type", '"adaptive"'), ("max_runs", n), (
    "goal", '{ quantity = "N", threshold = %r, tolerance = %r }' % (t, tol))]
MC = lambda n: [("type", '"monte_carlo"'), ("runs", n)]

E = (180e3, 240e3)
D = (-0.02, 0.05)
D2 = (-0.01, 0.01)


def rings_case(name, seed, params, threshold, ms, laws=None):
    """A shrink-fit case; `params` among E1, E2, d, d2 (the others fixed); `laws` overrides
    the default laws (d and d2 stay uniform: the exact statistics integrate them in closed
    form)."""
    laws = dict({"E1": E, "E2": E, "d": D, "d2": D2}, **(laws or {}))
    text = RINGS.format(
        seed=seed, title=name, threshold=threshold,
        parameters="\n".join(parameter(k, laws[k]) for k in params),
        e1="E1" if "E1" in params else "210e3", e2="E2" if "E2" in params else "210e3",
        gap="-d - d2" if "d2" in params else "-d",
        methods=methods(*ms))
    return {"name": name, "kind": "rings", "params": params, "laws": laws, "text": text,
            "threshold": threshold, "goal_tolerance": 0.01}


def block_case(name, seed, params, g, threshold, ms, laws=None):
    laws = dict({"Eb": E, "Ep": E, "g": g}, **(laws or {}))
    text = BLOCK.format(
        seed=seed, title=name, threshold=threshold,
        mesh=os.path.join(ROOT, "examples", "block-on-plane-3d.msh"),
        parameters="\n".join(parameter(k, laws[k]) for k in params),
        ep="Ep" if "Ep" in params else "210e3", eb="Eb" if "Eb" in params else "210e3",
        methods=methods(*ms))
    return {"name": name, "kind": "block", "params": params, "laws": laws, "text": text,
            "threshold": threshold, "goal_tolerance": 0.01}


CASES = [
    rings_case("rings-2 (E1, d)", 3, ["E1", "d"], 1000.0,
               [PL(5), PL(9), PC(3), PROJ(3), ADAPT(30), MC(24)]),
    rings_case("rings-3 (E1, E2, d)", 5, ["E1", "E2", "d"], 1500.0,
               [PL(3), PC(2), PC(3), POLY(2), ADAPT(45)]),
    rings_case("rings-4 (E1, E2, d, d2)", 7, ["E1", "E2", "d", "d2"], 1000.0,
               [PL(3), PC(2), ADAPT(60), GOAL(60, 1000.0, 0.01)]),
    block_case("block-3d kink (Eb, g)", 9, ["Eb", "g"], (-5e-4, 2e-3), 50.0,
               [PL(5), PC(3), ADAPT(30), GOAL(40, 50.0, 0.01)]),
    block_case("block-3d smooth (Eb, Ep, g)", 11, ["Eb", "Ep", "g"], (-5e-4, 5e-4), 150.0,
               [PL(3), PC(2), POLY(2)]),
]

TARGET = lambda n, t: [("type", '"adaptive"'), ("max_runs", n), ("target", t)]
SPARSE = lambda p: [("type", '"pc_sparse"'), ("degree", p)]

# Evaluation set 3, written before any rule was changed after evaluation set 1 (`--set 3`):
# other laws (normal, lognormal, triangular), a kink along a diagonal (d + d2 = 0), a larger
# and a smaller atom, other method types (sparse chaos, degree 4, grids of 4, 7 and 8 points,
# adaptive loops stopped by a target), and a goal.
CASES3 = [
    rings_case("rings-2 lognormal E1 (E1, d)", 13, ["E1", "d"], 800.0,
               [PL(4), PL(7), PC(4), SPARSE(4), TARGET(40, 0.02), MC(30)],
               laws={"E1": {"law": "lognormal", "mean": 210e3, "std": 20e3},
                     "d": (-0.03, 0.04)}),
    rings_case("rings-3 normal / triangular (E1, E2, d)", 17, ["E1", "E2", "d"], 1500.0,
               [PL(4), PC(3), POLY(3), TARGET(80, 0.05)],
               laws={"E1": {"law": "normal", "mean": 210e3, "std": 15e3},
                     "E2": {"law": "triangular", "lo": 180e3, "mode": 200e3, "hi": 250e3},
                     "d": (-0.01, 0.06)}),
    rings_case("rings-2 diagonal kink (d, d2)", 19, ["d", "d2"], 500.0,
               [PL(5), PL(8), PC(3), PC(5), ADAPT(40), GOAL(60, 500.0, 0.01)],
               laws={"d": (-0.02, 0.02), "d2": (-0.015, 0.015)}),
    block_case("block-3d lognormal Eb (Eb, g)", 23, ["Eb", "g"], (-8e-4, 1.2e-3), 100.0,
               [PL(4), PC(3), TARGET(40, 0.05)],
               laws={"Eb": {"law": "lognormal", "mean": 200e3, "std": 30e3}}),
]

# Evaluation set 4, written before the atom rule of `budget/validation.rs` (sets 1 and 3 showed
# the misses it answers, so they no longer evaluate it; `--set 4`): the hub's modulus, a large
# atom (5/8: q0.05 - q0.5 all 0), a diagonal kink in 3 parameters, the plane's modulus in 3D, a
# case without atom, and a goal.
CASES4 = [
    rings_case("rings-2 large atom (E2, d)", 29, ["E2", "d"], 600.0,
               [PL(6), PC(2), PROJ(4), TARGET(50, 0.03), MC(40)],
               laws={"d": (-0.05, 0.03)}),
    rings_case("rings-3 diagonal kink (E1, d, d2)", 31, ["E1", "d", "d2"], 300.0,
               [PL(3), PL(5), PC(3), SPARSE(3), ADAPT(60)],
               laws={"E1": {"law": "lognormal", "mean": 210e3, "std": 25e3},
                     "d": (-0.02, 0.025), "d2": (-0.01, 0.01)}),
    block_case("block-3d triangular Ep (Ep, g)", 37, ["Ep", "g"], (-1e-4, 1.5e-3), 200.0,
               [PL(3), PL(6), PC(4), TARGET(40, 0.02), GOAL(50, 200.0, 0.01)],
               laws={"Ep": {"law": "triangular", "lo": 150e3, "mode": 220e3, "hi": 260e3}}),
    block_case("block-3d no atom (Eb, Ep, g)", 41, ["Eb", "Ep", "g"], (-9e-4, 5e-4), 300.0,
               [PL(3), PC(2), PC(3)],
               laws={"Eb": {"law": "normal", "mean": 210e3, "std": 10e3}}),
]


# Evaluation set 5, written and committed after every rule of sessions 12 and 13 was fixed
# (the atom rule, the quantiles' residual RMS, the runs' precision) and before it was first
# run (`--set 5`): one parameter (rings and block), the shaft's modulus triangular, a diagonal
# kink in 3 parameters with a normal hub modulus, 4 parameters with a lognormal modulus, the
# plane's modulus normal in 3D, a small atom near the edge of the range, grids of 4, 6 and 9
# points, chaos of degree 2 - 6 (regression, projection, sparse), standard polynomials,
# adaptive loops with and without a target, two goals, Monte Carlo on the model.
CASES5 = [
    rings_case("rings-1 (d)", 43, ["d"], 1200.0,
               [PL(4), PL(9), PC(3), PC(6), ADAPT(20), MC(20)],
               laws={"d": (-0.015, 0.045)}),
    block_case("block-3d one parameter (g)", 47, ["g"], (-3e-4, 1.4e-3), 120.0,
               [PL(5), PROJ(4), POLY(3), TARGET(20, 0.01)]),
    rings_case("rings-2 triangular E1, small atom (E1, d)", 53, ["E1", "d"], 2500.0,
               [PL(6), PC(2), PROJ(5), SPARSE(5), ADAPT(25), MC(50)],
               laws={"E1": {"law": "triangular", "lo": 170e3, "mode": 230e3, "hi": 250e3},
                     "d": (-0.005, 0.06)}),
    rings_case("rings-3 diagonal kink, normal E2 (E2, d, d2)", 59, ["E2", "d", "d2"], 800.0,
               [PL(4), PC(4), POLY(2), TARGET(60, 0.03), GOAL(60, 800.0, 0.01)],
               laws={"E2": {"law": "normal", "mean": 200e3, "std": 12e3},
                     "d": (-0.03, 0.03), "d2": (-0.02, 0.02)}),
    rings_case("rings-4 lognormal E1 (E1, E2, d, d2)", 61, ["E1", "E2", "d", "d2"], 1200.0,
               [PL(3), SPARSE(3), ADAPT(80)],
               laws={"E1": {"law": "lognormal", "mean": 205e3, "std": 15e3}}),
    block_case("block-3d normal Ep (Eb, Ep, g)", 67, ["Eb", "Ep", "g"], (-2e-4, 1.6e-3), 100.0,
               [PL(4), PC(3), ADAPT(40), GOAL(50, 100.0, 0.01)],
               laws={"Ep": {"law": "normal", "mean": 215e3, "std": 12e3}}),
]


# Evaluation set 6, written after set 5 was reported and before its own first run (`--set 6`):
# the method variants no earlier set has - chaos and polynomials on Latin hypercube and Sobol'
# designs of a stated size, sparse chaos on its default design, the adaptive method's
# maximum-error criterion, a goal on the mean (relative tolerance, no threshold).
DESIGN = lambda kind, p, design, n: [("type", '"%s"' % kind), ("degree", p),
                                     ("design", '"%s"' % design), ("runs", n)]
MAXERR = lambda n: [("type", '"adaptive"'), ("max_runs", n), ("criterion", '"max_error"')]
MEANGOAL = lambda n, r: [("type", '"adaptive"'), ("max_runs", n), (
    "goal", '{ quantity = "N", relative_tolerance = %r }' % r)]
CASES6 = [
    rings_case("rings-2 designs (E1, d)", 71, ["E1", "d"], 1500.0,
               [DESIGN("pc_regression", 3, "lhs", 30), DESIGN("pc_regression", 4, "sobol", 40),
                DESIGN("polynomial", 2, "sobol", 20), SPARSE(4), MAXERR(30)],
               laws={"d": (-0.01, 0.05)}),
    rings_case("rings-3 designs (E1, E2, d)", 73, ["E1", "E2", "d"], 1000.0,
               [DESIGN("pc_regression", 2, "lhs", 40), DESIGN("polynomial", 3, "lhs", 50),
                MAXERR(40), MEANGOAL(50, 0.01)],
               laws={"E2": {"law": "normal", "mean": 205e3, "std": 10e3}}),
    block_case("block-3d designs (Eb, g)", 79, ["Eb", "g"], (-4e-4, 1.8e-3), 150.0,
               [DESIGN("pc_regression", 3, "sobol", 24), SPARSE(3), MAXERR(25)]),
]


def runs_of(db, dim):
    """(params, N) of every converged run in a study's store."""
    con = sqlite3.connect(db)
    out = []
    for params, qois, status in con.execute("SELECT params, qois, status FROM runs"):
        if status != "converged":
            continue
        x = struct.unpack("<%dd" % (len(params) // 8), params)
        q = struct.unpack("<%dd" % (len(qois) // 8), qois)
        if len(x) == dim:
            out.append((dict(), x, q[0]))
    return out


def solve3(a, b):
    """Least squares for 3 or fewer unknowns by the normal equations (Gauss elimination)."""
    n = len(a[0])
    m = [[sum(r[i] * r[j] for r in a) for j in range(n)] + [sum(r[i] * y for r, y in zip(a, b))]
         for i in range(n)]
    for i in range(n):
        piv = max(range(i, n), key=lambda k: abs(m[k][i]))
        m[i], m[piv] = m[piv], m[i]
        for k in range(n):
            if k != i:
                f = m[k][i] / m[i][i]
                m[k] = [u - f * v for u, v in zip(m[k], m[i])]
    return [m[i][n] / m[i][i] for i in range(n)]


def rings_model(case, runs):
    """(a(rest), s0(rest)) with N = a max(0, d - s0): alpha, beta fitted on tight runs."""
    names = case["params"]
    get = lambda x, k, default: x[names.index(k)] if k in names else default
    rows, rhs = [], []
    for _, x, n in runs:
        if n <= 1e-6:
            continue
        e1, e2, d, d2 = get(x, "E1", 210e3), get(x, "E2", 210e3), get(x, "d", 0), get(x, "d2", 0)
        # N (alpha / E1 + beta / E2) = d + d2
        rows.append([n / e1, n / e2])
        rhs.append(d + d2)
    if "E1" in names or "E2" in names:
        alpha, beta = solve3(rows, rhs)
    else:
        # Both moduli fixed: only alpha + beta is seen; split it evenly (the model is the same).
        alpha = beta = solve3([[r[0] + r[1]] for r in rows], rhs)[0]
    worst = 0.0
    # Runs whose force is at the solver's tolerance of 0 (the fit just closed) say nothing of
    # the relative residual.
    floor = 1e-6 * max(n for _, _, n in runs)
    for _, x, n in runs:
        if n <= floor:
            continue
        e1, e2, d, d2 = get(x, "E1", 210e3), get(x, "E2", 210e3), get(x, "d", 0), get(x, "d2", 0)
        model = max(0.0, d + d2) / (alpha / e1 + beta / e2)
        worst = max(worst, abs(model - n) / n)
    print("  fit: alpha %.6e beta %.6e, largest relative residual %.2e on %d runs"
          % (alpha, beta, worst, len(rows)))

    def law(rest):
        e1, e2 = rest.get("E1", 210e3), rest.get("E2", 210e3)
        return 1.0 / (alpha / e1 + beta / e2), -rest.get("d2", 0.0)
    return law, "d", worst


def block_model(case):
    def law(rest):
        eb, ep = rest.get("Eb", 210e3), rest.get("Ep", 210e3)
        # N = 2 max(0, 1e-3 - g) / (1/Eb + 1/Ep) = a max(0, s - s0) with s = -g, s0 = -1e-3.
        return 2.0 / (1.0 / eb + 1.0 / ep), -1e-3
    return law, "g", 0.0


def exact_stats(case, law, linear, threshold, per_dim=40):
    """Mean, std, quantiles, P(N > t) of N = a max(0, s - s0), s uniform (s = d, or -g)."""
    laws = case["laws"]
    others = [k for k in case["params"] if k != linear]
    lo, hi = laws[linear]
    if linear == "g":
        lo, hi = -hi, -lo
    # Midpoints in probability: the law's quantiles at (i + 1/2) / n.
    grids = [[quantile(laws[k], (i + 0.5) / per_dim) for i in range(per_dim)] for k in others]
    cells = [dict(zip(others, c)) for c in itertools.product(*grids)] if others else [{}]
    pieces = [law(c) for c in cells]
    w = hi - lo
    m1 = m2 = above = 0.0
    for a, s0 in pieces:
        # int_m^hi (s - s0)^k ds / w with m = max(lo, s0), k = 1, 2.
        m = max(s0, lo)
        if hi > m:
            m1 += a * ((hi - s0) ** 2 - (m - s0) ** 2) / (2 * w)
            m2 += a * a * ((hi - s0) ** 3 - (m - s0) ** 3) / (3 * w)
        above += min(1.0, max(0.0, (hi - max(s0 + threshold / a, lo)) / w))
    n = len(pieces)
    mean, second = m1 / n, m2 / n

    def cdf(y):
        if y < 0:
            return 0.0
        return sum(min(1.0, max(0.0, (s0 + y / a - lo) / w)) for a, s0 in pieces) / n

    top = max(a * (hi - s0) for a, s0 in pieces)
    out = {"mean": mean, "std": (second - mean * mean) ** 0.5, "P(> %g)" % threshold: above / n}
    for p in ORDERS:
        if cdf(0.0) >= p:
            out["q%g" % p] = 0.0
            continue
        a_, b_ = 0.0, top
        for _ in range(60):
            mid = 0.5 * (a_ + b_)
            if cdf(mid) >= p:
                b_ = mid
            else:
                a_ = mid
        out["q%g" % p] = 0.5 * (a_ + b_)
    return out


def estimate(row):
    v = row.get("validation")
    return v["value"] if v and v.get("detected") else row["value"]


def main(args):
    keep = None
    if "--keep" in args:
        i = args.index("--keep")
        keep = args[i + 1]
        del args[i:i + 2]
    cases = CASES
    if "--set" in args:
        i = args.index("--set")
        cases = {"1": CASES, "3": CASES3, "4": CASES4, "5": CASES5, "6": CASES6}[args[i + 1]]
        del args[i:i + 2]
    alea = args[0] if args else os.path.join(ROOT, "target", "release", "alea")
    if not args:
        subprocess.run(["cargo", "build", "--release", "-q"], cwd=ROOT, check=True)
    work = keep or tempfile.mkdtemp(prefix="alea-validation-")
    os.makedirs(work, exist_ok=True)
    total = {"n": 0, "covered": 0, "ratios": []}
    cost = []
    goals = []
    for k, case in enumerate(cases):
        print("== %s" % case["name"])
        path = os.path.join(work, "case%d.toml" % k)
        with open(path, "w") as f:
            f.write(case["text"])
        d = os.path.join(work, "case%d" % k)
        subprocess.run([alea, "run", path, "--dir", d, "--threads", "2", "-q"], check=True,
                       stdout=subprocess.DEVNULL)
        runs = runs_of(os.path.join(d, "study.db"), len(case["params"]))
        if case["kind"] == "rings":
            law, linear, _ = rings_model(case, runs)
        else:
            law, linear, _ = block_model(case)
        truth = exact_stats(case, law, linear, case["threshold"])
        s = json.load(open(os.path.join(d, "summary.json")))
        n_case = covered_case = 0
        validation_runs = 0
        for m in s["methods"]:
            for q in m.get("qois", []):
                for row in q.get("budget", {}).get("rows", []):
                    t = truth.get(row["statistic"])
                    if t is None:
                        continue
                    if row.get("validation"):
                        validation_runs = max(validation_runs, row["validation"]["runs"])
                    err = abs(estimate(row) - t)
                    ok = row["total"] >= err
                    n_case += 1
                    covered_case += ok
                    if err > row["sampling"]:
                        total["ratios"].append(row["total"] / err)
                    print("  %-34s %-10s exact %11.5g estimate %11.5g error %9.3e total %9.3e%s%s"
                          % (m["label"][:34], row["statistic"], t, estimate(row), err,
                             row["total"],
                             " (corrected)" if (row.get("validation") or {}).get("detected")
                             else "", "" if ok else "  NOT COVERED"))
        for m in s["methods"]:
            a = m.get("adaptive") or {}
            steps = a.get("steps") or []
            goal = (steps[-1].get("goal") or [None])[0] if steps else None
            if goal is None:
                continue
            exact = truth.get(goal["statistic"])
            reached = a.get("stop", "").startswith("goal reached")
            err = abs(goal["value"] - exact) if exact is not None else float("nan")
            tol = case["goal_tolerance"]
            goals.append((case["name"], goal["statistic"], reached, err, tol))
            print("  goal %s: %s; value %.5g +- %.3g, exact %.5g, error %.3g (tolerance %g)%s" % (
                goal["statistic"], a.get("stop", "")[:90], goal["value"], goal["total"], exact,
                err, tol, "  WRONG STOP" if reached and err > tol else ""))
        total["n"] += n_case
        total["covered"] += covered_case
        design = max(m["design_runs"] for m in s["methods"] if "monte" not in m["label"].lower())
        cost.append((case["name"], len(runs), validation_runs, design, covered_case, n_case))
        print("  covered %d/%d" % (covered_case, n_case))
    r = sorted(total["ratios"])
    median = r[len(r) // 2] if r else float("nan")
    print("\ncase | runs in the store | validation runs used | largest surrogate design | covered")
    for c in cost:
        print("%s | %d | %d | %d | %d/%d" % c)
    wrong = sum(1 for g in goals if g[2] and g[3] > g[4])
    print("goals: %d, reached %d, reached with an exact error above the tolerance %d" % (
        len(goals), sum(1 for g in goals if g[2]), wrong))
    print("evaluation set: covered %d/%d (%.1f %%); median total / error where the error exceeds "
          "the sampling half-width %.2f over %d rows (work directory %s)" % (
              total["covered"], total["n"], 100.0 * total["covered"] / max(total["n"], 1),
              median, len(r), work))


if __name__ == "__main__":
    main(sys.argv[1:])
