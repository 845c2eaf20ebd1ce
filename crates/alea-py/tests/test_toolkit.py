"""The two builds: the full package (cargo feature `solver`, default) and the toolkit-only build
(`--no-default-features`). On the toolkit build every study function raises `SolverNotBuilt`
with a message saying what is missing and how to get it, before touching any file; the toolkit
(laws, designs, surrogates, fields) works in both builds."""

import math

import numpy as np
import pytest

import alea


def test_toolkit_works_in_both_builds():
    law = alea.Joint([alea.Uniform(-1.0, 1.0), alea.Uniform(-1.0, 1.0)])
    x = alea.lhs(law, 30, seed=3)
    pc = alea.PolynomialChaos.regression(law, 2, x, 1.0 + x[:, 0] * x[:, 1])
    # Exact: mean 1, variance E[x^2]^2 = 1/9.
    assert pc.mean == pytest.approx(1.0, abs=1e-12)
    assert pc.std == pytest.approx(math.sqrt(1.0 / 9.0), rel=1e-10)


@pytest.mark.skipif(alea.SOLVER, reason="full build: the solver is there")
@pytest.mark.parametrize(
    "call",
    [
        lambda d: alea.run(d / "study.toml", d / "out"),
        lambda d: alea.open_store(d),
        lambda d: alea.report(d),
    ],
    ids=["run", "open_store", "report"],
)
def test_solver_functions_raise_a_clear_error_on_the_toolkit_build(tmp_path, call):
    with pytest.raises(alea.SolverNotBuilt, match="--no-default-features") as e:
        call(tmp_path)
    assert isinstance(e.value, RuntimeError)
    assert "Install the full package" in str(e.value)
    assert not any(tmp_path.iterdir())
    assert not hasattr(alea._core, "run_study_file")


@pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build")
def test_full_build_has_the_solver_functions():
    for name in ("run_study_file", "read_store", "rebuild_outputs"):
        assert callable(getattr(alea._core, name))
    assert np.all(np.isfinite(alea.lhs(alea.Normal(0.0, 1.0), 4, seed=1)))
