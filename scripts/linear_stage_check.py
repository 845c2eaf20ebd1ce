#!/usr/bin/env python3
"""Every shipped study's statistics with the interface-condensed linear stage against the
volume one (issue 41: "every shipped example's statistics unchanged to the solver's tolerance").

usage: linear_stage_check.py [ALEA] [EXAMPLE ...]

Each study of examples/ (a file with a [[method]]; by default all of them) is run twice with
`alea run --threads 2 -q`, once as shipped (`[solver] linear_stage` left to `auto`) and once with
`linear_stage = "volume"` added to its `[solver]` table, in a temporary directory. Prints, per
study: the runs converged in both, the mean LATIN iterations of each, the largest change of a
quantity at a run over that quantity's largest magnitude over the runs, and the largest change of a method's mean or std of a quantity over that
quantity's std (summary.json), and which linear stage `auto` chose (the run's console line).
"""
import glob
import json
import os
import re
import sqlite3
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def runs(directory):
    db = sqlite3.connect(os.path.join(directory, "study.db"))
    f = lambda b: struct.unpack("<%dd" % (len(b) // 8), b)
    return {f(p): (s, i, f(q)) for p, s, i, q in
            db.execute("select params, status, iterations, qois from runs")}


def with_volume(text):
    if re.search(r"^\[solver\]\s*$", text, re.M):
        return re.sub(r"^\[solver\]\s*$", '[solver]\nlinear_stage = "volume"', text, count=1,
                      flags=re.M)
    return text + '\n[solver]\nlinear_stage = "volume"\n'


def main(args):
    alea = args[0] if args and not args[0].endswith(".toml") else os.path.join(
        ROOT, "target", "release", "alea")
    files = [a for a in args if a.endswith(".toml")] or sorted(
        f for f in glob.glob(os.path.join(ROOT, "examples", "*.toml"))
        if "[[method]]" in open(f).read())
    work = tempfile.mkdtemp(prefix="alea-stage-")
    print("| study | runs | iterations auto / volume | largest change at a run / largest value | "
          "largest change of a mean or std / std | auto chose |")
    print("|---|---|---|---|---|---|")
    for path in files:
        name = os.path.basename(path)[:-5]
        text = open(path).read()
        dirs = {}
        chose = ""
        for stage, body in (("auto", text), ("volume", with_volume(text))):
            study = os.path.join(os.path.dirname(path), ".stage-%s-%s.toml" % (name, stage))
            with open(study, "w") as f:
                f.write(body)
            d = os.path.join(work, "%s-%s" % (name, stage))
            try:
                out = subprocess.run([alea, "run", study, "--dir", d, "--threads", "2"],
                                     capture_output=True, text=True)
            finally:
                os.remove(study)
            if out.returncode != 0:
                print("| %s | %s failed: %s |" % (name, stage, out.stderr.strip()[-200:]))
                break
            if stage == "auto":
                m = re.search(r"^linear stage: (.*)$", out.stdout, re.M)
                chose = m.group(1) if m else "(no line)"
            dirs[stage] = d
        if len(dirs) < 2:
            continue
        a, v = runs(dirs["auto"]), runs(dirs["volume"])
        both = [k for k in a if k in v and a[k][0] == "converged" and v[k][0] == "converged"]
        it = lambda r: sum(r[k][1] for k in both) / max(1, len(both))
        # Relative to each quantity's largest magnitude over the runs (a quantity that is 0 at
        # some runs, a resultant that changes sign, has no relative change there).
        nq = len(a[both[0]][2]) if both else 0
        scale = [max([abs(a[k][2][q]) for k in both] + [1e-300]) for q in range(nq)]
        worst = max((abs(x - y) / scale[q]
                     for k in both for q, (x, y) in enumerate(zip(a[k][2], v[k][2]))),
                    default=0.0)
        sa = json.load(open(os.path.join(dirs["auto"], "summary.json")))
        sv = json.load(open(os.path.join(dirs["volume"], "summary.json")))
        stat = 0.0
        for ma, mv in zip(sa["methods"], sv["methods"]):
            for qa, qv in zip(ma.get("qois", []), mv.get("qois", [])):
                std = max(abs(qa["std"]), abs(qv["std"]), 1e-300)
                stat = max(stat, abs(qa["mean"] - qv["mean"]) / std,
                           abs(qa["std"] - qv["std"]) / std)
        print("| %s | %d | %.2f / %.2f | %.1e | %.1e | %s |" % (
            name, len(both), it(a), it(v), worst, stat, chose[:120]), flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
