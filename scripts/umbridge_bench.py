#!/usr/bin/env python3
"""Benchmark of `alea serve` (issue 39; BENCHMARKS.md "alea serve"): N evaluations (default
1000) at seeded uniform points of the simple blade root's parameter box from T client threads
(default 4) through the UM-Bridge Python client, then the same points again (answered from the
store, no solve: the serving overhead alone).

usage: umbridge_bench.py ALEA [--points N] [--threads T]

Prints: wall time of the first pass and the solver's time for those runs (the `seconds` of the
stored runs), the count of stored runs (N: none lost, none duplicated) and answers, and the
second pass's time per request - HTTP, JSON, the queue to the model thread and the store
look-up, with no solve.
"""
import concurrent.futures
import os
import random
import sqlite3
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from umbridge_check import start_server, uniform_study  # noqa: E402


def main(args):
    alea_bin = args[0]
    n = int(args[args.index("--points") + 1]) if "--points" in args else 1000
    threads = int(args[args.index("--threads") + 1]) if "--threads" in args else 4
    import umbridge
    rng = random.Random(39)
    points = [[rng.uniform(210e3, 270e3), rng.uniform(0.1, 0.9)] for _ in range(n)]
    with tempfile.TemporaryDirectory(prefix="alea-umbridge-bench-") as work:
        study = uniform_study(work)
        directory = os.path.join(work, "served")
        proc, url = start_server(alea_bin, study, directory)
        try:
            model = umbridge.HTTPModel(url, "forward")
            passes = []
            for k in range(2):
                if k == 1:
                    # The first pass's server time is printed when the server stops: restart
                    # it for the second pass alone (its points are all in the store).
                    proc.terminate()
                    first_line = proc.communicate(timeout=60)[0].strip()
                    proc, url = start_server(alea_bin, study, directory)
                    model = umbridge.HTTPModel(url, "forward")
                t0 = time.perf_counter()
                with concurrent.futures.ThreadPoolExecutor(max_workers=threads) as pool:
                    answers = list(pool.map(lambda p: model([p])[0], points))
                passes.append((time.perf_counter() - t0, answers))
        finally:
            proc.terminate()
            second_line = proc.communicate(timeout=60)[0].strip()
        con = sqlite3.connect(os.path.join(directory, "study.db"))
        stored, solve = con.execute("SELECT COUNT(*), SUM(seconds) FROM runs").fetchone()
    (wall1, a1), (wall2, a2) = passes
    assert len(a1) == n and a1 == a2, "answers lost or changed"
    print("first pass: %d evaluations from %d client threads in %.2f s wall (%.2f ms each); "
          "solver time of the runs %.2f s (%.2f ms each)"
          % (n, threads, wall1, 1e3 * wall1 / n, solve, 1e3 * solve / n))
    print("stored runs: %d for %d distinct points (lost or duplicated: %d)"
          % (stored, n, abs(stored - n)))
    print("second pass (every point from the store, no solve): %.2f s wall, %.3f ms per request"
          " at the client" % (wall2, 1e3 * wall2 / n))
    print("server, first pass: " + first_line.splitlines()[-1])
    print("server, second pass: " + second_line.splitlines()[-1])


if __name__ == "__main__":
    main(sys.argv[1:])
