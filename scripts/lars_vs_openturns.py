#!/usr/bin/env python3
"""Sparse chaos by LARS + corrected leave-one-out: alea against OpenTURNS on the same designs
(a benchmark, not a test; issue 24 item 2; the table is in BENCHMARKS.md).

Functions: Ishigami (3 uniform inputs on [-pi, pi], candidate basis of total degree p) and the
wing weight function (Forrester et al. 2008; 10 uniform inputs, hyperbolic basis of q-norm
0.5 <= p, the same candidate set in both libraries: OpenTURNS' hyperbolic enumeration truncated
at alea's size). Legendre polynomials, degrees 8-14, N = 100, 200, 400 LHS points drawn by
OpenTURNS (seeds 1..S), validation error 1 - Q2 = sum (y - y~)^2 / sum (y - mean)^2 on the same
10^5 Monte Carlo points for both. Times are wall clock of one fit each (loaded 2-core machine:
indicative only).

With --ablation, the LARS orderings compared on Ishigami at N = 100 (NumPy re-implementation of
the path, same corrected-LOO selection as OpenTURNS): raw orthonormal columns with the constant
first (OpenTURNS, alea now) against centred columns scaled to unit norm (alea before), each with
the path capped at K - 1 and at K/2 terms.

Needs openturns, numpy and the alea wheel in one environment:
    python3 -m venv /tmp/otvenv && /tmp/otvenv/bin/pip install openturns numpy pandas
    (cd crates/alea-py && maturin build --release --no-default-features --out /tmp/wheels)
    /tmp/otvenv/bin/pip install /tmp/wheels/alea-*.whl
    /tmp/otvenv/bin/python scripts/lars_vs_openturns.py [--seeds 3] [--ablation]
"""
import argparse
import math
import time

import numpy as np
import openturns as ot

import alea

ot.Log.Show(ot.Log.NONE)


def ishigami():
    bounds = [(-math.pi, math.pi)] * 3

    def f(x):
        return np.sin(x[:, 0]) + 7 * np.sin(x[:, 1]) ** 2 + 0.1 * x[:, 2] ** 4 * np.sin(x[:, 0])

    return "Ishigami", bounds, f, 1.0


def wing_weight():
    bounds = [(150, 200), (220, 300), (6, 10), (-10, 10), (16, 45), (0.5, 1), (0.08, 0.18),
              (2.5, 6), (1700, 2500), (0.025, 0.08)]

    def f(x):
        sw, wfw, a, lam, q, taper, tc, nz, wdg, wp = x.T
        c = np.cos(np.radians(lam))
        return (0.036 * sw**0.758 * wfw**0.0035 * (a / c**2) ** 0.6 * q**0.006 * taper**0.04
                * (100 * tc / c) ** -0.3 * (nz * wdg) ** 0.49 + sw * wp)

    return "wing weight", bounds, f, 0.5


def qnorm_count(d, p, q):
    """Number of multi-indices of dimension d with q-norm <= p (alea's hyperbolic set)."""
    n = 0

    def rec(i, left, acc):
        nonlocal n
        if i == d:
            n += 1
            return
        for a in range(left + 1):
            s = acc + a**q
            if s ** (1 / q) > p + 1e-9:
                break
            rec(i + 1, left - a, s)

    rec(0, p, 0.0)
    return n


def ot_lars(design, y, dist, d, degree, q):
    enum = ot.LinearEnumerateFunction(d) if q == 1.0 else ot.HyperbolicAnisotropicEnumerateFunction(d, q)
    size = enum.getBasisSizeFromTotalDegree(degree) if q == 1.0 else qnorm_count(d, degree, q)
    factory = ot.OrthogonalProductPolynomialFactory([ot.LegendreFactory()] * d, enum)
    sel = ot.LeastSquaresMetaModelSelectionFactory(ot.LARS(), ot.CorrectedLeaveOneOut())
    algo = ot.FunctionalChaosAlgorithm(design, y, dist, ot.FixedStrategy(factory, size),
                                       ot.LeastSquaresStrategy(design, y, sel))
    algo.run()
    res = algo.getResult()
    return res, size


def rel_error(yt, pred):
    return float(np.sum((yt - pred) ** 2) / np.sum((yt - yt.mean()) ** 2))


def compare(name, bounds, f, q, seeds, sizes, degrees):
    d = len(bounds)
    dist = ot.JointDistribution([ot.Uniform(a, b) for a, b in bounds])
    law = alea.Joint([alea.Uniform(a, b) for a, b in bounds])
    ot.RandomGenerator.SetSeed(12345)
    test = np.array(dist.getSample(100_000))
    yt = f(test)
    print(f"\n{name} (d = {d}, {'total degree' if q == 1.0 else f'q-norm {q}'}), "
          f"validation on {len(yt)} points")
    print("| N | degree | candidates | OT terms | alea terms | OT 1-Q2 | alea 1-Q2 | alea/OT "
          f"(seed 1) | alea/OT over {len(seeds)} seeds: geo. mean [min, max] | OT fit | alea fit |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for n in sizes:
        for degree in degrees:
            rows = []
            for seed in seeds:
                ot.RandomGenerator.SetSeed(seed)
                x = np.array(ot.LHSExperiment(dist, n).generate())
                y = f(x)
                t0 = time.perf_counter()
                res, size = ot_lars(ot.Sample(x), ot.Sample(y[:, None]), dist, d, degree, q)
                t_ot = time.perf_counter() - t0
                e_ot = rel_error(yt, np.array(res.getMetaModel()(ot.Sample(test))).ravel())
                t0 = time.perf_counter()
                pc = alea.PolynomialChaos.lars(law, degree, x, y, q=None if q == 1.0 else q)
                t_al = time.perf_counter() - t0
                assert pc.multi_indices.shape[1] == d
                e_al = rel_error(yt, pc.predict(test))
                rows.append((res.getIndices().getSize(), len(pc.coefficients), e_ot, e_al, t_ot, t_al, size))
            r = np.array([row[3] / row[2] for row in rows])
            t_ot, t_al = np.median([row[4] for row in rows]), np.median([row[5] for row in rows])
            s = rows[0]
            print(f"| {n} | {degree} | {s[6]} | {s[0]} | {s[1]} | {s[2]:.2e} | {s[3]:.2e} | {s[3] / s[2]:.2f} "
                  f"| {np.exp(np.mean(np.log(r))):.2f} [{r.min():.2f}, {r.max():.2f}] "
                  f"| {t_ot * 1e3:.0f} ms | {t_al * 1e3:.0f} ms |", flush=True)


# ---- ablation: the LARS orderings on the same designs (NumPy) --------------------------------

def lars_order(psi, y, standardise, max_terms):
    """Columns in the order LARS brings them in (column 0 is the constant)."""
    k, _ = psi.shape
    if standardise:
        x = psi[:, 1:] - psi[:, 1:].mean(0)
        x = x / np.linalg.norm(x, axis=0)
        target, offset, order = y - y.mean(), 1, [0]
    else:
        x, target, offset, order = psi, y, 0, []
    active, inactive, mu = [], np.ones(x.shape[1], bool), np.zeros(k)
    while len(order) < max_terms:
        c = x.T @ (target - mu)
        j = 0 if (not standardise and not active) else int(np.argmax(np.where(inactive, np.abs(c), -1)))
        active.append(j)
        inactive[j] = False
        order.append(j + offset)
        cmax = abs(c[j])
        s = np.where(c[active] < 0, -1.0, 1.0)
        g = np.linalg.solve(x[:, active].T @ x[:, active], s)
        a_a = 1 / math.sqrt(s @ g)
        u = x[:, active] @ (a_a * g)
        a = x.T @ u
        step = cmax / a_a
        for i in np.nonzero(inactive)[0]:
            for cand in ((cmax - c[i]) / (a_a - a[i]), (cmax + c[i]) / (a_a + a[i])):
                if cand > 0:
                    step = min(step, cand)
        mu = mu + step * u
    return order


def select(psi, y, order, small=10, factor=2.0, max_error=0.5):
    """OpenTURNS' LeastSquaresMetaModelSelection with CorrectedLeaveOneOut: the best prefix."""
    k, var = len(y), y.var(ddof=1)
    best = (math.inf, 0)
    for n in range(1, min(len(order), k - 1) + 1):
        qm, rm = np.linalg.qr(psi[:, order[:n]])
        h = (qm * qm).sum(1)
        if np.any(1 - h < 1e-12):
            break
        res = y - qm @ (qm.T @ y)
        rinv = np.linalg.inv(rm)
        err = k / (k - n) * (1 + (rinv * rinv).sum()) * np.mean((res / (1 - h)) ** 2) / var
        if err < best[0]:
            best = (err, n)
        elif n > small and (err > factor * best[0] or err > max_error):
            break
    return best[1]


def ablation(seeds, degrees):
    name, bounds, f, _ = ishigami()
    n = 100
    dist = ot.JointDistribution([ot.Uniform(a, b) for a, b in bounds])
    enum = ot.LinearEnumerateFunction(3)
    factory = ot.OrthogonalProductPolynomialFactory([ot.LegendreFactory()] * 3, enum)
    ot.RandomGenerator.SetSeed(12345)
    test = np.array(dist.getSample(100_000))
    yt = f(test)

    def design_matrix(x, size):
        xs = ot.Sample(x / math.pi)
        return np.column_stack([np.array(factory.build(i)(xs)).ravel() for i in range(size)])

    print(f"\nAblation, {name}, N = {n}: terms and 1 - Q2 of the LARS orderings")
    print("| degree | seed | raw, cap K-1 (OpenTURNS, alea now) | raw, cap K/2 | standardised, cap K-1 "
          "| standardised, cap K/2 (alea before) |")
    print("|---|---|---|---|---|---|")
    for degree in degrees:
        size = enum.getBasisSizeFromTotalDegree(degree)
        psit = design_matrix(test, size)
        for seed in seeds:
            ot.RandomGenerator.SetSeed(seed)
            x = np.array(ot.LHSExperiment(dist, n).generate())
            y = f(x)
            psi = design_matrix(x, size)
            cells = []
            for standardise, cap in ((False, n - 1), (False, n // 2), (True, n - 1), (True, n // 2)):
                order = lars_order(psi, y, standardise, min(cap, size))
                m = select(psi, y, order)
                coef, *_ = np.linalg.lstsq(psi[:, order[:m]], y, rcond=None)
                cells.append(f"{m}: {rel_error(yt, psit[:, order[:m]] @ coef):.2e}")
            print(f"| {degree} | {seed} | " + " | ".join(cells) + " |", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--sizes", default="100,200,400")
    ap.add_argument("--degrees", default="8,9,10,11,12,13,14")
    ap.add_argument("--functions", default="ishigami,wing")
    ap.add_argument("--ablation", action="store_true")
    a = ap.parse_args()
    seeds = list(range(1, a.seeds + 1))
    sizes = [int(v) for v in a.sizes.split(",")]
    degrees = [int(v) for v in a.degrees.split(",")]
    print("OpenTURNS", ot.__version__, "alea", alea.__version__)
    for fname in a.functions.split(","):
        compare(*(ishigami() if fname == "ishigami" else wing_weight()), seeds, sizes, degrees)
    if a.ablation:
        ablation(seeds, [10, 12, 14])


if __name__ == "__main__":
    main()
