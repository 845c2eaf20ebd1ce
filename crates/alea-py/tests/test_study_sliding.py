"""The sliding part of the error budget from Python (``[budget] large_sliding = true``).

The simple blade root of ``examples/blade-root-simple.toml`` on a coarsened mesh (every cell
count divided by 3), T only, piecewise linear 2 x 2: ``Results.budget`` has a ``sliding`` column
with the part of every statistic (the change under large sliding, which is large here: the root
slides 0.3 mm up its flanks), the total includes it, ``budget_bases`` says how it was obtained, and
the same study in large sliding moves T's mean by no more than the part.
"""

import re
from pathlib import Path

import numpy as np
import pytest

import alea

pytestmark = pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build (no solver)")

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "blade-root-simple.toml"


def blade_root(large: bool, budget: bool) -> str:
    text = EXAMPLE.read_text()
    text = re.sub(r"(n_\w+) = (\d+)", lambda m: "%s = %d" % (m.group(1), max(1, int(m.group(2)) // 3)), text)
    blocks = re.split(r"(?m)^(?=\[)", text)
    keep = []
    for b in blocks:
        if b.startswith("[[method]]"):
            continue
        if b.startswith("[[quantity]]") and 'name = "T"' not in b:
            continue
        keep.append(b)
    text = "".join(keep)
    if large:
        text = text.replace('law = "coulomb"\n', 'law = "coulomb"\nsliding = "large"\n')
    text += '\n[[method]]\ntype = "piecewise_linear"\npoints_per_dim = 2\n\n[statistics]\nsamples = 5000\n'
    if budget:
        # Without validation runs: the total is then the sum of the parts (with them, the
        # validation part combines with the surrogate and sampling parts instead).
        text += "\n[budget]\nlarge_sliding = true\nvalidation_runs = 0\n"
    return text


def test_budget_has_the_sliding_part(tmp_path):
    small_file = tmp_path / "small.toml"
    small_file.write_text(blade_root(large=False, budget=True))
    large_file = tmp_path / "large.toml"
    large_file.write_text(blade_root(large=True, budget=False))
    small = alea.run(small_file, directory=tmp_path / "small")
    large = alea.run(large_file, directory=tmp_path / "large")
    budget = small.budget
    assert "sliding" in budget.columns
    assert np.isfinite(budget["sliding"]).all() and (budget["sliding"] > 0).all()
    parts = budget["sampling"] + budget["surrogate"].fillna(0) + budget["mesh"].fillna(0) + budget["sliding"]
    np.testing.assert_allclose(budget["total"], parts, rtol=1e-12)
    basis = small.budget_bases.set_index("quantity").loc["T", "sliding"]
    assert basis.startswith("paired solves in small and in large sliding"), basis
    mean = budget.set_index("statistic").loc["mean"]
    change = abs(mean["value"] - large.statistics.loc[(large.statistics.index[0][0], "T"), "mean"])
    assert change > 0.1 * mean["value"]  # a large change: the check is not trivial
    assert mean["sliding"] >= change
    # Without the table the column is there and empty.
    assert large.budget["sliding"].isna().all()
    assert large.budget_bases["sliding"].isna().all()
