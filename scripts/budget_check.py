#!/usr/bin/env python3
"""Checks the error budget of a study's statistics against a reference study of the same model.

usage: budget_check.py STUDY/summary.json REFERENCE/summary.json

With the same file twice (a study whose first method is its own dense reference, e.g.
examples/blade-root-simple-comparison.toml), that first method is the truth and is not checked.

For every method of the study, quantity and statistic (mean, std, quantiles, P(q > t)) it prints
the true error |value - reference value| (the reference's first method is taken as the truth),
the budget's total and their ratio, then the share of statistics whose total covers the true
error and the share within 10x of it (against the sampling half-width where the true error is
below it: no estimate can tell an error below the noise of the draws).
"""
import json
import sys


def truths(q):
    t = {"mean": q["mean"], "std": q["std"]}
    for p, v in q["quantiles"]:
        t["q%g" % p] = v
    for f in q["failure"]:
        t["P(> %g)" % f["threshold"]] = f["probability"]
    return t


def main(study, reference):
    ref = json.load(open(reference))["methods"][0]["qois"]
    s = json.load(open(study))
    n = covered = tight = 0
    methods = s["methods"][1:] if study == reference else s["methods"]
    for m in methods:
        for qi, q in enumerate(m.get("qois", [])):
            truth = truths(ref[qi])
            for row in q.get("budget", {}).get("rows", []):
                t = truth.get(row["statistic"].replace("q0.", "q0."))
                if t is None:
                    continue
                actual = abs(row["value"] - t)
                n += 1
                covered += row["total"] >= actual
                tight += row["total"] <= 10 * max(actual, row["sampling"])
                ratio = row["total"] / actual if actual > 0 else float("inf")
                print("%-26s %-14s %-10s true %9.3e total %9.3e ratio %7.2f"
                      % (m["label"][:26], q["name"][:14], row["statistic"], actual,
                         row["total"], ratio))
    print("covered %d/%d, within 10x %d/%d" % (covered, n, tight, n))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
