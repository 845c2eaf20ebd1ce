"""The root README's Python example runs as written and its numbers are right: the study's
statistics match the exact law of the plate (u = P s L / E) within their Monte Carlo error and
the chaos fitted to the exact model reproduces its exact mean."""

import math
import re
from pathlib import Path

import pytest

import alea

pytestmark = pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build (no solver)")

ROOT = Path(__file__).resolve().parents[3]


def readme_example():
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Python\n", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert len(blocks) == 1
    return blocks[0]


def test_readme_example(tmp_path, monkeypatch, capsys):
    code = readme_example()
    assert len([line for line in code.splitlines() if line.strip()]) == 10
    monkeypatch.chdir(tmp_path)
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    out = capsys.readouterr().out
    assert "PC regression p=4" in out and "Monte Carlo" in out
    assert (tmp_path / "out" / "plate-random-E" / "study.db").is_file()
    a, b, s, l = 150e3, 250e3, 200.0, 100.0
    mean = s * l * math.log(b / a) / (b - a)
    std = math.sqrt(s * s * l * l * 1.01 / (a * b) - mean**2)
    res, draws, pc = scope["res"], scope["draws"], scope["pc"]
    row = res.statistics.loc[("PC regression p=4", "tip")]
    assert abs(row["mean"] - mean) < 4 * std / math.sqrt(row["draws"]) + 1e-4 * mean
    assert draws.shape == (250_000, 3)
    # The chaos of the exact model: degree 4 in E leaves a relative error below 1e-4.
    assert pc.mean == pytest.approx(mean, rel=1e-4)
    assert pc.std == pytest.approx(std, rel=1e-3)
    # Total indices of u = c P / E: S_T,P = c^2 Var(P) E[1/E^2] / Var(u),
    # S_T,E = c^2 E[P^2] Var(1/E) / Var(u), with E[1/E^2] = 1/(a b).
    c2 = (s * l) ** 2
    var_inv_e = 1 / (a * b) - (math.log(b / a) / (b - a)) ** 2
    exact_st = [c2 * 1.01 * var_inv_e / std**2, c2 * 0.01 / (a * b) / std**2]
    assert pc.sobol_total() == pytest.approx(exact_st, abs=2e-4)
    assert pc.predict([[2e5, 1.1]])[0] == pytest.approx(0.11, rel=1e-4)
