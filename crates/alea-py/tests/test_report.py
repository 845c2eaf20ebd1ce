"""``alea.report(directory)``: every output of a study directory rebuilt from its store, by the
same Rust orchestration as ``alea report DIR`` (crate ``alea-pipeline``).

The plate of ``data/plate.toml`` is run from Python (which writes only the store), then
``report`` writes ``summary.json``, ``samples.csv``, the fields and the HTML report; the
statistics in ``summary.json`` are the ones ``run`` returned, bit for bit.
"""

import json
from pathlib import Path

import pytest

import alea

pytestmark = pytest.mark.skipif(not alea.SOLVER, reason="toolkit-only build (no solver)")

DATA = Path(__file__).parent / "data"


@pytest.fixture(scope="module")
def plate(tmp_path_factory):
    directory = tmp_path_factory.mktemp("plate-report") / "out"
    res = alea.run(DATA / "plate.toml", directory=directory)
    assert not (directory / "summary.json").exists()  # run writes only the store
    return res, directory, alea.report(directory)


def test_report_writes_the_html_report_and_its_plots(plate):
    res, directory, out = plate
    assert isinstance(out, alea.StudyOutputs)
    assert out.report == directory / "report" / "report.html"
    html = out.report.read_text()
    assert html.startswith("<!DOCTYPE html>") and res.title in html
    assert out.plots and all(p.is_file() and p.parent == out.report.parent for p in out.plots)
    assert {p.suffix for p in out.plots} == {".png", ".svg"}
    assert not (directory / "report" / "report-input.json").exists()  # not an output
    assert isinstance(out.notes, list)


def test_summary_holds_the_statistics_of_run(plate):
    res, directory, out = plate
    assert out.summary == directory / "summary.json"
    summary = json.loads(out.summary.read_text())
    assert summary["study_hash"] == res.study_hash
    assert [p["name"] for p in summary["parameters"]] == res.parameters
    assert [m["label"] for m in summary["methods"]] == [m.label for m in res.methods]
    for m in summary["methods"]:
        for q in m["qois"]:
            row = res.statistics.loc[(m["label"], q["name"])]
            assert (q["mean"], q["std"]) == (row["mean"], row["std"])
    assert len(summary["runs"]) == len(res.runs)
    assert out.samples == directory / "samples.csv"
    with out.samples.open() as f:
        assert f.readline().strip() == "E,P,tip"
    assert out.fields is None or out.fields.is_file()
    # open_store now names the columns from summary.json.
    stored = alea.open_store(directory)
    assert stored.parameters == ["E", "P"] and stored.quantities == ["tip"]


def test_report_again_gives_the_same_bytes(plate):
    _, directory, out = plate
    before = out.summary.read_bytes()
    again = alea.report(directory)
    assert again.summary.read_bytes() == before
    assert again.report == out.report


def test_report_refuses_a_directory_without_a_study(tmp_path):
    with pytest.raises(ValueError, match="not a study directory"):
        alea.report(tmp_path)
