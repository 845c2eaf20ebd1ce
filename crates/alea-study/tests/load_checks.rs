//! Settings that used to be found bad only after every run (issue 23: fixing the file then
//! changes the study's hash and every run is lost) or accepted silently are refused when the
//! study is loaded, naming the file, the line and the field.

use alea_study::Source;
use alea_study::runner::Study;

fn study(error: &str, quantity_name: &str, method: &str) -> String {
    format!(
        r#"
[study]
title = "load checks"

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [10.0, 2.0]
cells = [2, 1]

[analysis]
type = "plane_stress"

[[parameter]]
name = "E"
law = "uniform"
lo = 150e3
hi = 250e3

[[substructure]]
name = "plate"
young = "E"
poisson = 0.0
constraint = [ {{ group = "xmin", x = 0.0 }}, {{ group = "ymin", y = 0.0 }} ]
load = [ {{ group = "xmax", traction = [1.0, 0.0] }} ]

[[quantity]]
name = "{quantity_name}"
kind = "displacement"
substructure = "plate"
point = [10.0, 2.0]
component = 0

[[method]]
{method}

{error}
"#
    )
}

fn refused(text: &str, needle: &str, field: &str, words: &str) {
    let e = Study::from_source(Source::from_text("checks.toml", text)).expect_err("refused");
    let msg = e.to_string();
    let line = text
        .lines()
        .position(|l| l.contains(needle))
        .map(|i| i + 1)
        .unwrap();
    assert!(
        msg.contains(&format!("checks.toml:{line}:")),
        "line {line}: {msg}"
    );
    assert!(msg.contains(field), "{field}: {msg}");
    assert!(msg.contains(words), "'{words}': {msg}");
}

const PL: &str = "type = \"piecewise_linear\"";

#[test]
fn bad_error_settings_are_refused_at_load() {
    refused(
        &study("[error]\nwarn = -1.0", "tip", PL),
        "warn = -1.0",
        "error.warn",
        "must be > 0",
    );
    refused(
        &study("[error]\nwarn = nan", "tip", PL),
        "warn = nan",
        "error.warn",
        "must be > 0",
    );
    refused(
        &study("[error]\npoints_per_cell = 0", "tip", PL),
        "points_per_cell = 0",
        "error.points_per_cell",
        "at least 1",
    );
    refused(
        &study("[error]\ncells_per_dim = 0", "tip", PL),
        "cells_per_dim = 0",
        "error.cells_per_dim",
        "at least 1",
    );
    refused(
        &study("[error]\npoints_per_cell = 10000000", "tip", PL),
        "points_per_cell = 10000000",
        "error.points_per_cell",
        "integration points",
    );
    refused(
        &study("[error]\nmap_points = 100000000", "tip", PL),
        "map_points",
        "error.map_points",
        "2..=1000",
    );
    // Good settings load.
    Study::from_source(Source::from_text(
        "checks.toml",
        &study("[error]\nwarn = 0.2\ncells_per_dim = 8", "tip", PL),
    ))
    .unwrap();
}

#[test]
fn an_empty_quantity_name_and_too_few_monte_carlo_runs_are_refused() {
    refused(
        &study("", "", PL),
        "name = \"\"",
        "quantity[0].name",
        "is empty",
    );
    refused(
        &study("", "tip", "type = \"monte_carlo\"\nruns = 0"),
        "runs = 0",
        "method[0].runs",
        "at least 2",
    );
    refused(
        &study("", "tip", "type = \"monte_carlo\"\nruns = 1"),
        "runs = 1",
        "method[0].runs",
        "two runs",
    );
}
