#!/usr/bin/env python3
"""`alea serve` from the UM-Bridge Python client (PyPI `umbridge`) and from OpenTURNS (issue 39).

usage: umbridge_check.py ALEA [--points N]

Run by .ci/run in the venv of the Python block (umbridge and openturns from PyPI). On the
shipped simple blade root with its two parameters made uniform on their ranges (the study is
written to a temporary directory):

1. `alea run` of the study gives the reference: its stored runs.
2. `alea serve` of the same study on a fresh directory, any free port; the client checks the
   model's sizes and evaluates N (default 20) of the reference's points from 2 client threads:
   each answer equals `alea run`'s value at that point to 1e-4 of the quantity's scale (the
   solver's tolerance: the warm starts differ).
3. Bad requests through the client - a point of the wrong size, a non-positive modulus, an
   unknown config key - each raise an error naming its cause, and the server goes on answering.
4. OpenTURNS through the client (`PythonFunction` around it): a least-squares chaos of degree 3
   on the design of alea's `pc_regression` method (`alea.pc_collocation`, 16 points) gives the
   mean and standard deviation of alea's chaos on the same points to 1e-8 relative, for every
   quantity.
"""
import concurrent.futures
import os
import re
import sqlite3
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def uniform_study(directory):
    """The simple blade root with its parameters uniform on their ranges."""
    text = open(os.path.join(ROOT, "examples", "blade-root-simple.toml")).read()
    text = re.sub(r'law = "truncated_normal"\nmean = [^\n]*\nstd = [^\n]*\n', 'law = "uniform"\n', text)
    assert text.count('law = "uniform"') == 2, "the example's parameters changed"
    path = os.path.join(directory, "blade-root-uniform.toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def stored_runs(directory):
    """(parameters, quantities) of every converged run of a study directory."""
    con = sqlite3.connect(os.path.join(directory, "study.db"))
    rows = con.execute("SELECT params, qois FROM runs WHERE status = 'converged' ORDER BY rowid")
    unpack = lambda b: list(struct.unpack("<%dd" % (len(b) // 8), b))
    return [(unpack(p), unpack(q)) for p, q in rows]


def start_server(alea, study, directory):
    proc = subprocess.Popen([alea, "serve", study, "--dir", directory, "--port", "0",
                             "--threads", "2"], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True)
    line = proc.stdout.readline()
    match = re.search(r"http://[0-9.]+:[0-9]+", line)
    if not match:
        proc.kill()
        raise SystemExit("no address in the server's first line: %r" % line)
    return proc, match.group(0)


def check_against_run(model, reference, n):
    scale = [max(abs(r[1][q]) for r in reference) for q in range(len(reference[0][1]))]
    points = [r[0] for r in reference[:n]]
    with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
        answers = list(pool.map(lambda p: model([p])[0], points))
    worst = 0.0
    for (p, expected), got in zip(reference[:n], answers):
        for q, (a, b) in enumerate(zip(got, expected)):
            worst = max(worst, abs(a - b) / scale[q])
            assert abs(a - b) <= 1e-4 * scale[q], (p, q, a, b)
    print("%d evaluations from 2 client threads equal alea run's runs: largest difference "
          "%.2e of the quantity's scale" % (len(points), worst))


def check_bad_requests(model, good_point):
    bad = [([[1.0]], {}, "InvalidInput"),
           ([[-1.0, 0.5]], {}, "must be > 0"),
           ([good_point], {"tolerance": 1e-3}, "unknown config key 'tolerance'")]
    for point, config, phrase in bad:
        try:
            model(point, config)
        except Exception as e:  # the client raises a plain Exception with the type and message
            assert phrase in str(e), (point, config, str(e))
        else:
            raise AssertionError("no error for %r %r" % (point, config))
    assert len(model([good_point])[0]) == 3
    print("bad requests: %d errors naming their cause, and the server goes on" % len(bad))


def check_openturns(model):
    import alea
    import openturns as ot
    lo, hi = [210e3, 0.1], [270e3, 0.9]
    law = alea.Joint([alea.Uniform(lo[0], hi[0]), alea.Uniform(lo[1], hi[1])])
    points = [list(map(float, p)) for p in alea.pc_collocation(law, 3, 16)]
    f = ot.PythonFunction(2, 3, lambda x: model([list(x)])[0])
    values = f(ot.Sample(points))
    distribution = ot.JointDistribution([ot.Uniform(lo[0], hi[0]), ot.Uniform(lo[1], hi[1])])
    basis = ot.OrthogonalProductPolynomialFactory([ot.LegendreFactory()] * 2)
    terms = basis.getEnumerateFunction().getStrataCumulatedCardinal(3)
    algo = ot.FunctionalChaosAlgorithm(ot.Sample(points), values, distribution,
                                       ot.FixedStrategy(basis, terms), ot.LeastSquaresStrategy())
    algo.run()
    vector = ot.FunctionalChaosRandomVector(algo.getResult())
    mean, cov = vector.getMean(), vector.getCovariance()
    for q in range(3):
        column = [values[i, q] for i in range(len(points))]
        pce = alea.PolynomialChaos.regression(law, 3, points, column)
        ot_mean, ot_std = mean[q], cov[q, q] ** 0.5
        for name, a, b in [("mean", pce.mean, ot_mean), ("std", pce.std, ot_std)]:
            rel = abs(a - b) / max(abs(b), 1e-300)
            assert rel <= 1e-8, (q, name, a, b)
        print("quantity %d: OpenTURNS chaos mean %.10g std %.10g, alea's %.10g %.10g"
              % (q, ot_mean, ot_std, pce.mean, pce.std))


def main(args):
    alea_bin = args[0]
    n = int(args[args.index("--points") + 1]) if "--points" in args else 20
    import umbridge
    with tempfile.TemporaryDirectory(prefix="alea-umbridge-") as work:
        study = uniform_study(work)
        reference_dir = os.path.join(work, "reference")
        subprocess.run([alea_bin, "run", study, "--dir", reference_dir, "-q", "--threads", "2"],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        reference = stored_runs(reference_dir)
        assert len(reference) >= n, "%d runs" % len(reference)
        proc, url = start_server(alea_bin, study, os.path.join(work, "served"))
        try:
            model = umbridge.HTTPModel(url, "forward")
            assert model.get_input_sizes() == [2] and model.get_output_sizes() == [3]
            assert model.supports_evaluate() and not model.supports_gradient()
            check_against_run(model, reference, n)
            check_bad_requests(model, reference[0][0])
            check_openturns(model)
        finally:
            proc.terminate()
            proc.wait(timeout=60)
    print("umbridge check: ok")


if __name__ == "__main__":
    main(sys.argv[1:])
