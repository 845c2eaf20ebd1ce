#!/usr/bin/env python3
"""Runs the root README's Python example as a user would (in the current directory, which must
hold `examples/`) and checks the numbers it prints against the exact law of the plate.

The plate of examples/plate-random-E.toml: tip = c P / E with c = s L = 200 * 100 = 2e4,
E ~ U(150e3, 250e3), P ~ N(1, 0.1), so E[tip] = c ln(b/a) / (b - a) = 0.102168 and
P(tip > 0.13) = (1/(b-a)) int_a^b Phi((1 - 0.13 E / c) / 0.1) dE = 0.0825 (Simpson's rule
below). Checked: the main method's printed mean within 4 of its Monte Carlo standard errors of
the exact mean, the exact probability inside the printed confidence interval, the printed mean
of the chaos of the exact model within 1e-4 (relative) and its printed prediction at
(E, P) = (2e5, 1.1) within 1e-4 of 0.11. Exit status 1 with the reason if any check fails.

    python scripts/check_readme_example.py [README.md]

.ci/run runs it with the wheel installed in a fresh virtual environment.
"""
import contextlib
import io
import math
import re
import sys
from pathlib import Path

A, B, C, P_MEAN, P_STD, THRESHOLD = 150e3, 250e3, 2e4, 1.0, 0.1, 0.13
MAIN = "PC regression p=4"


def exact_failure_probability(n=2000):
    def integrand(e):
        return 0.5 * math.erfc((THRESHOLD * e / C - P_MEAN) / (P_STD * math.sqrt(2.0)))

    h = (B - A) / n
    s = integrand(A) + integrand(B)
    s += sum((4 if i % 2 else 2) * integrand(A + i * h) for i in range(1, n))
    return s * h / 3 / (B - A)


def readme_example(readme):
    section = readme.read_text().split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    if len(blocks) != 1:
        raise SystemExit(f"{readme}: expected one Python block in '## Python', found {len(blocks)}")
    return blocks[0]


NUMBER = r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?"


def main():
    readme = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parents[1] / "README.md")
    code = readme_example(readme)
    out = io.StringIO()
    scope = {}
    with contextlib.redirect_stdout(out):
        exec(compile(code, str(readme), "exec"), scope)
    text = out.getvalue()
    print(text, end="")
    mean = C * math.log(B / A) / (B - A)
    p_fail = exact_failure_probability()
    failures = []

    stats = re.search(rf"^{re.escape(MAIN)}\s+tip\s+({NUMBER})\s+({NUMBER})\s+({NUMBER})\s*$", text, re.M)
    if not stats:
        failures.append("no statistics row for the main method's tip")
    else:
        m, s = float(stats[1]), float(stats[2])
        draws = scope["res"].samples.shape[0]
        bound = 4 * s / math.sqrt(draws)
        if abs(m - mean) > bound:
            failures.append(f"printed mean {m} is {abs(m - mean):.2e} from the exact {mean:.6f} (> {bound:.2e})")
        print(f"check: printed mean {m} vs exact {mean:.6f}: |diff| {abs(m - mean):.2e} <= 4 s/sqrt({draws}) = {bound:.2e}")

    fail = re.search(rf"^\d+\s+{re.escape(MAIN)}\s+tip\s+({NUMBER})\s+({NUMBER})\s+({NUMBER})\s+({NUMBER})\s*$", text, re.M)
    if not fail:
        failures.append("no failure row for the main method's tip")
    else:
        t, p, lo, hi = (float(fail[i]) for i in range(1, 5))
        ok = t == THRESHOLD and lo <= p_fail <= hi
        if not ok:
            failures.append(f"exact P(tip > {THRESHOLD}) = {p_fail:.5f} outside the printed interval [{lo}, {hi}]")
        print(f"check: exact P(tip > {THRESHOLD}) = {p_fail:.5f} in the printed interval [{lo}, {hi}] (estimate {p})")

    lines = text.strip().splitlines()
    chaos = re.match(rf"^({NUMBER}) ", lines[-2]) if len(lines) >= 2 else None
    pred = re.match(rf"^\[({NUMBER})\]$", lines[-1]) if lines else None
    if not chaos or abs(float(chaos[1]) / mean - 1) > 1e-4:
        failures.append(f"chaos mean line {lines[-2] if len(lines) >= 2 else None!r} not within 1e-4 of {mean:.6f}")
    else:
        print(f"check: chaos mean {float(chaos[1]):.6f} vs exact {mean:.6f}")
    if not pred or abs(float(pred[1]) / 0.11 - 1) > 1e-4:
        failures.append(f"prediction line {lines[-1] if lines else None!r} not within 1e-4 of 0.11")
    else:
        print(f"check: prediction {float(pred[1]):.6f} vs exact 0.11")
    if failures:
        print("README example: FAILED\n  " + "\n  ".join(failures), file=sys.stderr)
        sys.exit(1)
    print("README example: every printed number checked")


if __name__ == "__main__":
    main()
