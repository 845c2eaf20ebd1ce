#!/usr/bin/env python3
"""Every quantity of a study on its mesh and on a finer one, run by run.

usage: mesh_check.py STUDY.toml [FACTOR] [ALEA]

Writes copies of STUDY.toml (a generator mesh: `[mesh] params` with `n_*` counts) in a
temporary directory: the study as written and with every `n_*` count multiplied by FACTOR
(default 2; `n_fillet` kept even), both with one method, piecewise linear 3 x 3 (9 runs, plus
the automatic validation draws), and without `[budget]` (no paired solves). Runs both with ALEA
(default target/release/alea, 2 threads) and prints, for every run at the same parameters, each
quantity on both meshes and its relative change, then the largest change of each quantity.

Used for the mesh-convergence table of examples/turbine-2d-fretting.toml (BENCHMARKS.md
"Fretting: the 2D turbine example").
"""
import json
import os
import re
import subprocess
import sys
import tempfile


def scaled(text, factor):
    def count(m):
        n = max(1, round(int(m.group(2)) * factor))
        if m.group(1) == "n_fillet" and n % 2:
            n += 1
        return "%s = %d" % (m.group(1), n)

    lines = text.split("\n")
    out = []
    for line in lines:
        if line.startswith("params = {"):
            line = re.sub(r"(n_\w+) = (\d+)", count, line)
        out.append(line)
    return "\n".join(out)


def one_design(text):
    """The study with its methods replaced by piecewise linear 3 x 3, and no [budget]."""
    blocks = re.split(r"(?m)^(?=\[)", text)
    kept = [b for b in blocks if not b.startswith(("[[method]]", "[budget]"))]
    return "".join(kept) + '\n[[method]]\ntype = "piecewise_linear"\npoints_per_dim = 3\n'


def runs(summary):
    s = json.load(open(summary))
    names = [q["name"] for q in s["methods"][0]["qois"]]
    return names, {tuple(r["params"]): r for r in s["runs"]}


def main(study, factor, alea):
    text = one_design(open(study).read())
    tmp = tempfile.mkdtemp(prefix="alea-mesh-check-")
    dirs = []
    for tag, f in (("as-written", 1.0), ("refined", factor)):
        path = os.path.join(tmp, tag + ".toml")
        open(path, "w").write(text if f == 1.0 else scaled(text, f))
        out = os.path.join(tmp, tag)
        subprocess.run([alea, "run", path, "--dir", out, "--threads", "2", "-q"], check=True)
        dirs.append(out)
    names, coarse = runs(os.path.join(dirs[0], "summary.json"))
    _, fine = runs(os.path.join(dirs[1], "summary.json"))
    worst = [0.0] * len(names)
    for p in sorted(set(coarse) & set(fine)):
        a, b = coarse[p], fine[p]
        print("(%s): %s / %s" % (", ".join("%.4g" % x for x in p), a["status"], b["status"]))
        for i, n in enumerate(names):
            x, y = a["qois"][i], b["qois"][i]
            change = (y - x) / abs(x) if x else float("nan")
            if x:
                worst[i] = max(worst[i], abs(change))
            print("  %-12s %12.6g %12.6g  %+7.2f %%" % (n, x, y, 100 * change))
    print("largest change under x%g refinement:" % factor)
    for n, w in zip(names, worst):
        print("  %-12s %.2f %%" % (n, 100 * w))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    factor = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0
    alea = sys.argv[3] if len(sys.argv) > 3 else "target/release/alea"
    main(sys.argv[1], factor, alea)
