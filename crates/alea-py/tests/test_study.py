"""A study file run end to end from Python, against exact statistics.

The plate of ``data/plate.toml`` (plane stress, nu = 0, traction s = 200 MPa scaled by
``P ~ N(1, 0.1^2)``, ``E ~ U(a, b)``, length L = 100 mm) has the tip displacement
``u = P s L / E`` exactly, so ``E[u] = s L E[P] ln(b/a) / (b - a)``,
``E[u^2] = s^2 L^2 E[P^2] / (a b)`` and ``P(u > t) = int_a^b (1 - Phi((t E / (s L) - 1) / 0.1)) dE / (b - a)``.
Each method's mean, standard deviation and failure probability must match within a few of its
Monte Carlo standard errors (plus a small surrogate error for the chaos). Then the store is read
back, the study resumed (nothing solved again) and run with one thread (identical results).
"""

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import alea

pytestmark = pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build (no solver)")

DATA = Path(__file__).parent / "data"
A, B, S, L, T = 150e3, 250e3, 200.0, 100.0, 0.13
MEAN = S * L * math.log(B / A) / (B - A)
STD = math.sqrt(S * S * L * L * 1.01 / (A * B) - MEAN**2)


def exact_pf():
    t, w = np.polynomial.legendre.leggauss(200)
    e = 0.5 * (B - A) * t + 0.5 * (B + A)
    z = (T * e / (S * L) - 1.0) / 0.1
    sf = np.array([0.5 * math.erfc(v / math.sqrt(2)) for v in z])
    return 0.5 * np.dot(w, sf)


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    directory = tmp_path_factory.mktemp("plate") / "out"
    calls = []
    res = alea.run(DATA / "plate.toml", directory=directory, progress=lambda done, total: calls.append((done, total)))
    return res, directory, calls


def test_every_run_is_exact(study):
    res, _, _ = study
    runs = res.runs
    # 30 + 200 design runs and 7 validation runs (a quarter of the chaos design, 30).
    assert len(runs) == 237 and runs["converged"].all()
    assert list(runs.columns) == ["E", "P", "status", "converged", "iterations", "residual", "seconds", "tip"]
    np.testing.assert_allclose(runs["tip"], runs["P"] * S * L / runs["E"], rtol=1e-9)
    assert res.units == {"E": "", "P": "", "tip": "mm"}  # the file gives no parameter units


def test_statistics_match_the_exact_law(study):
    res, _, _ = study
    pf = exact_pf()
    stats = res.statistics
    assert list(stats.index) == [("PC regression p=4", "tip"), ("Monte Carlo", "tip")]
    for (method, _), row in stats.iterrows():
        n = row["draws"]
        slack = 1e-4 * MEAN if method.startswith("PC") else 0.0
        assert abs(row["mean"] - MEAN) < 4 * STD / math.sqrt(n) + slack
        assert abs(row["std"] - STD) < 4 * 1.2 * STD / math.sqrt(2 * n) + slack
        assert row["q0.01"] < row["q0.5"] < row["q0.99"]
    fail = res.failure.set_index("method")
    for method, row in fail.iterrows():
        n = stats.loc[(method, "tip"), "draws"]
        assert row["threshold"] == T
        assert abs(row["probability"] - pf) < 4 * math.sqrt(pf * (1 - pf) / n) + (2e-3 if method.startswith("PC") else 0)
        assert row["ci_low"] <= row["probability"] <= row["ci_high"]


def test_failure_and_statistics_carry_the_total_interval_beside_the_sampling_one(study):
    """Issue 40, item 3: what users read is the budget's estimate with its total interval; the
    Wilson interval is there too, named sampling-only, and the total contains it."""
    res, _, _ = study
    budget = res.budget.set_index(["method", "quantity", "statistic"])
    for _, row in res.failure.iterrows():
        b = budget.loc[(row["method"], row["quantity"], f"P(> {T})")]
        assert row["estimate"] == b["estimate"]
        assert (row["total_low"], row["total_high"]) == (b["total_low"], b["total_high"])
        assert (row["sampling_low"], row["sampling_high"]) == (row["ci_low"], row["ci_high"])
        assert row["total_low"] <= row["sampling_low"] <= row["sampling_high"] <= row["total_high"], row.to_dict()
        assert row["total_high"] - row["total_low"] > 0
    for (method, quantity), row in res.statistics.iterrows():
        for stat in ("mean", "std"):
            b = budget.loc[(method, quantity, stat)]
            assert row[f"{stat}_estimate"] == b["estimate"]
            assert row[f"{stat}_low"] <= row[f"{stat}_estimate"] <= row[f"{stat}_high"]
            assert abs(0.5 * (row[f"{stat}_high"] - row[f"{stat}_low"]) - b["total"]) <= 1e-12 * abs(b["estimate"]) or stat == "std"
        # The sampling-only half-width of the mean inside the total one.
        assert row["mean_ci_half_width"] <= 0.5 * (row["mean_high"] - row["mean_low"]) * (1 + 1e-12)


def test_error_budget_covers_the_exact_statistics(study):
    """Each statistic's reported total error covers its true error (exact law above)."""
    res, _, _ = study
    exact = {"mean": MEAN, "std": STD, f"P(> {T})": exact_pf()}
    budget = res.budget
    assert set(budget["method"]) == {"PC regression p=4", "Monte Carlo"}
    for _, row in budget[budget["statistic"].isin(list(exact))].iterrows():
        assert abs(row["value"] - exact[row["statistic"]]) <= row["total"], row.to_dict()
        assert np.isnan(row["mesh"])  # not estimated, and said so
    mc = budget[budget["method"] == "Monte Carlo"]
    assert (mc["surrogate"] == 0).all()  # the runs themselves: no surrogate error
    assert "PC regression of degree 3" in res.budget_basis[("PC regression p=4", "tip")]


def test_reliability_table_matches_the_exact_probability(study):
    res, _, _ = study
    (r,) = res.reliability
    pf = exact_pf()
    assert r["quantity"] == "tip" and r["threshold"] == T and r["method"] == "PC regression p=4"
    for name in ("importance", "subset"):
        e = r[name]
        assert e["lower"] - 2e-3 <= pf <= e["upper"] + 2e-3, (name, e, pf)
    assert abs(r["sorm"]["pf_breitung"] / pf - 1) < 0.1
    assert r["warnings"] == [] and r["errors"] == []


def test_reliability_table_has_one_row_per_algorithm(study):
    res, _, _ = study
    t = res.reliability_table
    assert list(t["algorithm"]) == ["FORM", "SORM", "importance sampling", "subset simulation"]
    (r,) = res.reliability
    assert (t["quantity"] == "tip").all() and (t["threshold"] == T).all()
    assert t["pf"].iloc[2] == r["importance"]["pf"] and t["ci_high"].iloc[3] == r["subset"]["upper"]
    assert t["evaluations"].iloc[0] == r["form_evaluations"]
    assert t["beta"].iloc[0] == r["design_points"][0]["beta"] and np.isnan(t["beta"].iloc[3])
    pf = exact_pf()
    for _, row in t.iloc[2:].iterrows():
        assert row["ci_low"] - 2e-3 <= pf <= row["ci_high"] + 2e-3


def test_parameter_table_and_budget_bases(study):
    res, _, _ = study
    p = res.parameter_table
    assert list(p.index) == ["E", "P"]
    assert (p.loc["E", "lo"], p.loc["E", "hi"], p.loc["E", "nominal"]) == (A, B, 0.5 * (A + B))
    assert p.loc["P", "nominal"] == 1.0 and "normal" in p.loc["P", "law"]
    assert p["field"].isna().all() and res.fields == [] and res.field_modes.empty
    # Sobol' indices (every study with independent inputs; chaos: exact from the expansion):
    # u = P s L / E with P, E independent, so V_P = Var(P) E[1/E]^2 and V_E = Var(1/E) E[P]^2
    # (times (s L)^2), the interaction being the rest.
    m = math.log(B / A) / (B - A)
    v = 1.01 / (A * B) - m * m
    s_p, s_e = 0.01 * m * m / v, (1.0 / (A * B) - m * m) / v
    sob = res.sensitivity.loc[("PC regression p=4", "tip")]
    assert sob.loc["P", "first"] == pytest.approx(s_p, abs=2e-3)
    assert sob.loc["E", "first"] == pytest.approx(s_e, abs=2e-3)
    assert sob.loc["P", "total"] == pytest.approx(1.0 - s_e, abs=2e-3)
    assert sob.loc["E", "total"] == pytest.approx(1.0 - s_p, abs=2e-3)
    bases = res.budget_bases.set_index("method")
    assert bases.loc["PC regression p=4", "surrogate"] == res.budget_basis[("PC regression p=4", "tip")]
    assert bases.loc["Monte Carlo", "draws"] == 200
    assert "not estimated" in bases.loc["Monte Carlo", "mesh"]


def test_samples_are_the_main_methods_draws(study):
    res, _, _ = study
    assert res.main_method == "PC regression p=4"
    assert res.sample_columns == ["E", "P", "tip"]
    x = res.samples
    assert x.shape == (100_000, 3)
    assert x[:, 2].mean() == pytest.approx(res.statistics.loc[(res.main_method, "tip"), "mean"], rel=1e-12)
    # The surrogate's values at the draws are the exact model's within the chaos error (largest
    # in the normal load factor's tails).
    rel = x[:, 2] / (x[:, 1] * S * L / x[:, 0]) - 1
    assert np.sqrt(np.mean(rel**2)) < 5e-4 and np.abs(rel).max() < 0.05
    # The Monte Carlo method's draws are its runs.
    mc = res.samples_of("Monte Carlo")
    assert isinstance(mc, np.ndarray) and mc.shape == (200, 3)
    assert res.sample_columns_of("Monte Carlo") == ["E", "P", "tip"]
    # The main method's draws, by label or index, are `samples` itself.
    np.testing.assert_array_equal(res.samples_of(res.main_method), x)
    np.testing.assert_array_equal(res.samples_of(0), x)
    np.testing.assert_allclose(mc[:, 2], mc[:, 1] * S * L / mc[:, 0], rtol=1e-9)
    xs, pdf = res.kde("tip")
    assert np.sum(pdf) * (xs[1] - xs[0]) == pytest.approx(1.0, abs=1e-3)


def test_progress_reports_every_run(study):
    _, _, calls = study
    # 230 design runs and 7 validation runs, counted from the start.
    assert calls[0] == (0, 237) and calls[-1] == (237, 237) and len(calls) == 238


def test_store_read_back_and_resume(study, tmp_path):
    res, directory, _ = study
    stored = alea.open_store(directory, study=DATA / "plate.toml")
    assert stored.parameters == ["E", "P"] and stored.quantities == ["tip"]
    a = stored.runs.sort_values(["E", "P"]).reset_index(drop=True)
    b = res.runs.sort_values(["E", "P"]).reset_index(drop=True)
    cols = ["E", "P", "status", "iterations", "residual", "tip"]
    assert a[cols].equals(b[cols])
    # Without the study file: generic names (no summary.json from the command line here).
    anonymous = alea.open_store(directory)
    assert anonymous.parameters == ["x1", "x2"] and anonymous.quantities == ["q1"]
    np.testing.assert_array_equal(anonymous.runs["q1"], stored.runs["tip"])
    # Names from the command line's summary.json when it belongs to the same study version.
    summary = {
        "study_hash": res.study_hash,
        "parameters": [{"name": "E"}, {"name": "P"}],
        "methods": [{"qois": [{"name": "tip"}]}],
    }
    (directory / "summary.json").write_text(json.dumps(summary))
    named = alea.open_store(directory)
    assert named.parameters == ["E", "P"] and named.quantities == ["tip"]
    (directory / "summary.json").write_text(json.dumps(dict(summary, study_hash="0")))
    assert alea.open_store(directory).parameters == ["x1", "x2"]
    (directory / "summary.json").unlink()
    # Another version of the study file is refused.
    changed = tmp_path / "plate.toml"
    changed.write_text((DATA / "plate.toml").read_text().replace("seed = 7", "seed = 8"))
    with pytest.raises(ValueError, match="different study or version"):
        alea.open_store(directory, study=changed)
    with pytest.raises(FileNotFoundError):
        alea.open_store(tmp_path / "nothing")
    # Resuming solves nothing and gives the same statistics.
    again = alea.run(DATA / "plate.toml", directory=directory)
    assert (again.computed, again.resumed) == (0, 237)
    assert again.statistics.equals(res.statistics)


def test_one_thread_gives_identical_results(study, tmp_path):
    res, _, _ = study
    one = alea.run(DATA / "plate.toml", directory=tmp_path / "one", threads=1)
    assert one.statistics.equals(res.statistics)
    np.testing.assert_array_equal(one.samples, res.samples)


def test_bad_study_file_names_file_line_and_field(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text((DATA / "plate.toml").read_text().replace("std = 0.1", "std = -0.1"))
    with pytest.raises(ValueError, match=r"bad\.toml:\d+: parameter"):
        alea.run(bad, directory=tmp_path / "bad")
    with pytest.raises(FileNotFoundError):
        alea.run(tmp_path / "missing.toml", directory=tmp_path / "missing")
