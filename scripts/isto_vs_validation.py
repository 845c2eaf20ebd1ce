#!/usr/bin/env python3
"""i_sto against what the validation runs measure (issue 40: "where i_sto and the validation
disagree by more than 3x, say so").

usage: isto_vs_validation.py STUDY_DIR [STUDY_DIR ...]

For every method of each finished study (its summary.json) that has both a stochastic error
estimate (`error_estimate.i_sto`: the surrogate's error relative to the solution's energy,
estimated from the design's runs) and validation runs (`budget.validation_errors` of its
quantities), prints i_sto beside each quantity's relative RMS error at the validation runs,
`e_q = rms(q - q~) / rms(q)` - the same normalisation (an error over the size of what is
measured), measured by runs of the solver independent of the design - and their ratio, flagged
when it exceeds 3 either way. The two do not measure the same thing (the energy of the whole
field against one scalar of it): a local quantity (a maximum, a contact length) may carry a
larger relative error than the energy, an integral one (a resultant) a smaller one; the table
says where they disagree, not which is right.
"""
import json
import os
import sys


def main(dirs):
    print("| study | method | runs | validation runs | i_sto | quantity | e_q (validation) "
          "| i_sto / e_q |")
    print("|---|---|---|---|---|---|---|---|")
    flagged = total = 0
    for d in dirs:
        s = json.load(open(os.path.join(d, "summary.json")))
        title = s.get("title") or os.path.basename(d.rstrip("/"))
        for m in s["methods"]:
            est = m.get("error_estimate") or {}
            i_sto = est.get("i_sto")
            if i_sto is None:
                continue
            for q in m.get("qois", []):
                v = (q.get("budget") or {}).get("validation_errors")
                if not v:
                    continue
                e = v["relative"]
                ratio = i_sto / e if e > 0 else float("inf")
                flag = ratio > 3 or ratio < 1 / 3
                flagged += flag
                total += 1
                print("| %s | %s | %d | %d | %.2f %% | %s | %.3g %% | %.3g%s |" % (
                    title[:40], m["label"][:40], est.get("runs", 0), v["runs"], 100 * i_sto,
                    q["name"], 100 * e, ratio, " **>3x**" if flag else ""))
    print("\n%d of %d (method, quantity) pairs disagree by more than 3x" % (flagged, total))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
