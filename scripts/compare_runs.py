#!/usr/bin/env python3
"""Compares the runs of two study directories of the same study (e.g. one made by an older
build): mean LATIN iterations over the runs converged in both, their ratio, and the largest
relative difference of every quantity of interest; with a third directory (the same study at a
tight solver tolerance), each one's largest and mean relative error against it.

Usage: scripts/compare_runs.py OLD_DIR NEW_DIR [TIGHT_DIR]
"""
import sqlite3
import struct
import sys


def load(directory):
    db = sqlite3.connect(f"{directory}/study.db")
    as_floats = lambda b: struct.unpack(f"<{len(b) // 8}d", b)
    return {
        as_floats(p): (s, i, as_floats(q))
        for p, s, i, q in db.execute("select params, status, iterations, qois from runs")
    }


def main():
    old, new = load(sys.argv[1]), load(sys.argv[2])
    both = [k for k in old if k in new and old[k][0] == "converged" and new[k][0] == "converged"]
    it_old = sum(old[k][1] for k in both) / max(1, len(both))
    it_new = sum(new[k][1] for k in both) / max(1, len(both))
    worst = max(
        (abs(a - b) / max(abs(a), abs(b), 1e-300) for k in both for a, b in zip(old[k][2], new[k][2])),
        default=0.0,
    )
    failed = sum(1 for v in new.values() if v[0] != "converged")
    print(
        f"runs {len(old)} / {len(new)}, converged in both {len(both)}; mean iterations "
        f"{it_old:.2f} -> {it_new:.2f} (ratio {it_new / it_old:.4f}); largest relative change of "
        f"a quantity {worst:.2e}; failed in the second {failed}"
    )
    if len(sys.argv) > 3:
        tight = load(sys.argv[3])
        nq = len(next(iter(tight.values()))[2])
        for j in range(nq):
            for name, runs in (("first", old), ("second", new)):
                errs = [abs(runs[k][2][j] - tight[k][2][j]) / abs(tight[k][2][j]) for k in tight if k in runs and tight[k][2][j] != 0]
                print(f"quantity {j}: {name} max rel error {max(errs):.2e}, mean {sum(errs) / len(errs):.2e}")


if __name__ == "__main__":
    main()
