"""A study with random fields run from Python (``data/field.toml``: the simple blade root of
``examples/blade-root-simple-field.toml`` on a coarse mesh, mu a bounded random field along
each flank, 2 KL modes each, a degree-2 chaos on 24 runs), checked against truth:

* each field's KL eigenvalues and modes are the Galerkin KL of its stated kernel on its own
  mesh (``alea.KarhunenLoeve`` on the returned nodes and cells), the modes are orthonormal in
  the P1 mass matrix, the total variance is ``sigma^2 |D|`` with the flank's length, and the two
  mirror flanks have the same eigenvalues;
* the Sobol' indices per KL mode and per field satisfy the identities of a chaos (``S_i <=
  T_i``, ``sum S_i <= 1 <= sum T_i``, ``T_F = 1 - closed index of the other field``);
* every table equals what ``summary.json`` (written by ``alea.report`` from the same store, as
  the command line does) holds: Sobol' indices, budget rows and bases, parameter laws.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import alea

pytestmark = pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build (no solver)")

DATA = Path(__file__).parent / "data"


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    directory = tmp_path_factory.mktemp("field") / "out"
    res = alea.run(DATA / "field.toml", directory=directory)
    return res, directory


def p1_mass(nodes, cells):
    n = len(nodes)
    m = np.zeros((n, n))
    for a, b in cells:
        h = np.linalg.norm(nodes[a] - nodes[b])
        m[np.ix_([a, b], [a, b])] += h / 6.0 * np.array([[2.0, 1.0], [1.0, 2.0]])
    return m


def test_fields_are_the_galerkin_kl_of_their_kernel_on_their_mesh(study):
    res, _ = study
    assert [f.name for f in res.fields] == ["MU_G1", "MU_G2"]
    assert [f.interface for f in res.fields] == ["G1", "G2"]
    assert [f.substructure for f in res.fields] == ["", ""]  # fields along interfaces
    assert res.fields[0].variables == ["MU_G1_1", "MU_G1_2"]
    for f in res.fields:
        assert f.cells.shape[1] == 2 and f.modes.shape == (2, len(f.nodes))
        length = sum(np.linalg.norm(f.nodes[a] - f.nodes[b]) for a, b in f.cells)
        # The flank of the blade root: 10 mm high at 45 degrees.
        assert length == pytest.approx(10.0 * math.sqrt(2.0), rel=1e-12)
        # Bounded transform of a standard Gaussian field: sigma^2 = 1.
        assert f.total_variance == pytest.approx(length, rel=1e-12)
        assert f.captured_fraction == pytest.approx(f.eigenvalues.sum() / f.total_variance, rel=1e-12)
        kl = alea.KarhunenLoeve(f.nodes, f.cells.tolist(), "squared_exponential", 1.0, 10.0, modes=2)
        assert f.eigenvalues == pytest.approx(kl.eigenvalues, rel=1e-12)
        for k in range(2):
            # The same mode up to its sign.
            assert abs(f.modes[k] @ kl.modes[k]) == pytest.approx(np.sum(kl.modes[k] ** 2), rel=1e-10)
        m = p1_mass(f.nodes, f.cells)
        np.testing.assert_allclose(f.modes @ m @ f.modes.T, np.eye(2), atol=1e-10)
    np.testing.assert_allclose(res.fields[0].eigenvalues, res.fields[1].eigenvalues, rtol=1e-12)
    modes = res.field_modes
    assert list(modes["variable"]) == ["MU_G1_1", "MU_G1_2", "MU_G2_1", "MU_G2_2"]
    assert modes["cumulative_share"].iloc[1] == pytest.approx(res.fields[0].captured_fraction)
    table = res.parameter_table
    assert list(table["field"]) == ["MU_G1", "MU_G1", "MU_G2", "MU_G2"]
    assert list(table["mode"]) == [1, 2, 1, 2]
    assert (table["nominal"] == 0.0).all()


def test_sobol_indices_per_mode_and_per_field_satisfy_the_chaos_identities(study):
    res, _ = study
    sens = res.sensitivity
    fields = res.field_sensitivity.set_index(["quantity", "field"])
    for q in res.quantities:
        s = sens.loc[("chaos p=2", q)]
        assert (s["estimator"] == "pc_expansion").all()
        assert (s["first"] <= s["total"] + 1e-12).all()
        assert s["first"].sum() <= 1.0 + 1e-12 <= s["total"].sum() + 2e-12
        g1, g2 = fields.loc[(q, "MU_G1")], fields.loc[(q, "MU_G2")]
        # Two fields cover every variable: T_F = 1 - closed index of the other one.
        assert g1["total"] == pytest.approx(1.0 - g2["closed"], abs=1e-12)
        assert g2["total"] == pytest.approx(1.0 - g1["closed"], abs=1e-12)
        # A field's closed index holds at least its modes' first-order indices.
        for name, row in ((f"MU_G{i}", fields.loc[(q, f"MU_G{i}")]) for i in (1, 2)):
            modes = s[s["field"] == name]
            assert row["closed"] >= modes["first"].sum() - 1e-12
            assert row["total"] <= modes["total"].sum() + 1e-12


def test_tables_equal_summary_json(study):
    res, directory = study
    alea.report(directory)
    summary = json.loads((directory / "summary.json").read_text())
    (method,) = summary["methods"]
    for q in method["qois"]:
        s = res.sensitivity.loc[(method["label"], q["name"])]
        np.testing.assert_array_equal(s["first"], q["sobol"]["first"])
        np.testing.assert_array_equal(s["total"], q["sobol"]["total"])
        f = res.field_sensitivity
        f = f[f["quantity"] == q["name"]]
        assert list(f["closed"]) == [v["closed"] for v in q["sobol"]["fields"]]
        b = res.budget[(res.budget["quantity"] == q["name"])]
        assert list(b["statistic"]) == [r["statistic"] for r in q["budget"]["rows"]]
        np.testing.assert_array_equal(b["total"], [r["total"] for r in q["budget"]["rows"]])
        bases = res.budget_bases.set_index("quantity").loc[q["name"]]
        assert bases["surrogate"] == q["budget"]["surrogate_basis"]
        assert bases["mesh"] == q["budget"]["mesh_basis"]
        assert bases["draws"] == q["budget"]["draws"]
        errors = q["budget"]["validation_errors"]
        assert bases["validation_runs"] == errors["runs"] >= 2
        assert bases["validation_relative"] == errors["relative"]
        assert bases["validation_rms"] == pytest.approx(errors["relative"] * errors["scale"], rel=1e-12)
    assert list(res.parameter_table["law"]) == [p["law"] for p in summary["parameters"]]
    np.testing.assert_array_equal(res.parameter_table["hi"], [p["hi"] for p in summary["parameters"]])
