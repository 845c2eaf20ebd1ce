#!/usr/bin/env python3
"""Checks the sliding part of the error budget against the true change under large sliding.

usage: sliding_check.py STUDY.toml [ALEA]

Writes two copies of STUDY.toml next to it in a temporary directory (its .msh files copied too):
- "small": the study with `[budget] large_sliding = true` (the sliding part: paired solves in
  small and large sliding at the 2 d + 3 design points of `alea_study::budget::mesh`; a
  `[budget]` of the study is replaced by this one, in both copies);
- "large": the study with `sliding = "large"` on every `law = "coulomb"` interface, without its
  `[[reliability]]` tables, on the same design;
runs both with ALEA (default target/release/alea, 2 threads), then prints, for every method,
quantity and statistic, the small model's value, the large model's, their difference (the true
change: same design, same draws) and the sliding part with their ratio, and the share of
statistics whose part covers the change and the share within 10x of it.
"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile


def stats(summary):
    out = {}
    for m in json.load(open(summary))["methods"]:
        for q in m.get("qois", []):
            t = {"mean": q["mean"], "std": q["std"]}
            for p, v in q["quantiles"]:
                t["q%g" % p] = v
            for f in q["failure"]:
                t["P(> %g)" % f["threshold"]] = f["probability"]
            out[(m["label"], q["name"])] = t
    return out


def main(study, alea):
    text = open(study).read()
    work = tempfile.mkdtemp(prefix="alea-sliding-")
    for msh in glob.glob(os.path.join(os.path.dirname(os.path.abspath(study)), "*.msh")):
        shutil.copy(msh, work)
    # A [budget] of the study is left out of both copies (its mesh part is not what is
    # checked); the small copy gets one with the sliding part alone.
    text = "".join(b for b in re.split(r"(?m)^(?=\[)", text) if not b.startswith("[budget]"))
    small = re.sub(r"(?m)^\[solver\]", "[budget]\nlarge_sliding = true\n\n[solver]", text, count=1)
    if "large_sliding" not in small:
        small = text + "\n[budget]\nlarge_sliding = true\n"
    large = text.replace('law = "coulomb"\n', 'law = "coulomb"\nsliding = "large"\n')
    blocks = re.split(r"(?m)^(?=\[)", large)
    large = "".join(b for b in blocks if not b.startswith("[[reliability]]"))
    for name, body in (("small", small), ("large", large)):
        path = os.path.join(work, name + ".toml")
        open(path, "w").write(body)
        subprocess.run([alea, "run", path, "--dir", os.path.join(work, name), "--threads", "2", "-q"],
                       check=True, stdout=subprocess.DEVNULL)
    truth = stats(os.path.join(work, "large", "summary.json"))
    n = covered = tight = 0
    for m in json.load(open(os.path.join(work, "small", "summary.json")))["methods"]:
        for q in m.get("qois", []):
            for row in q.get("budget", {}).get("rows", []):
                t = truth.get((m["label"], q["name"]), {}).get(row["statistic"])
                part = row.get("sliding")
                if t is None or part is None:
                    continue
                change = abs(row["value"] - t)
                n += 1
                covered += part >= change
                tight += part <= 10 * max(change, row["sampling"])
                ratio = part / change if change > 0 else float("inf")
                print("%-24s %-14s %-10s small %11.5g large %11.5g change %9.3e sliding %9.3e ratio %6.2f"
                      % (m["label"][:24], q["name"][:14], row["statistic"], row["value"], t, change,
                         part, ratio))
    print("covered %d/%d, within 10x %d/%d (work directory %s)" % (covered, n, tight, n, work))


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else "target/release/alea")
