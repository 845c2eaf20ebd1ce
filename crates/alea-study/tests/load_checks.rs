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

/// The study with a second parameter and a joint law table (for the joint-law checks).
fn with_joint(joint: &str) -> String {
    study("", "tip", PL).replace(
        "[[substructure]]",
        &format!(
            "[[parameter]]\nname = \"P\"\nlaw = \"uniform\"\nlo = 0.5\nhi = 1.5\n\n{joint}\n\n[[substructure]]"
        ),
    )
}

#[test]
fn settings_that_would_be_ignored_are_refused() {
    refused(
        &with_joint(
            "[joint]\ntype = \"gaussian_copula\"\ncorrelation = [[1.0, 0.3], [0.3, 1.0]]\ndensity = \"E * P\"",
        ),
        "density = ",
        "joint.density",
        "type = \"density\" only",
    );
    refused(
        &with_joint(
            "[joint]\ntype = \"density\"\ndensity = \"E * P\"\ncorrelation = [[1.0, 0.3], [0.3, 1.0]]",
        ),
        "correlation = ",
        "joint.correlation",
        "gaussian_copula",
    );
    refused(
        &study("", "tip", "type = \"adaptive\"\ndepth = 2"),
        "depth = 2",
        "method[0].depth",
        "improved criterion",
    );
    refused(
        &study(
            "",
            "tip",
            "type = \"adaptive\"\ncriterion = \"max_error\"\nfraction = 0.3",
        ),
        "fraction = 0.3",
        "method[0].fraction",
        "max_error",
    );
    refused(
        &study("", "tip", "type = \"pc_projection\"\nruns = 40"),
        "runs = 40",
        "method[0].runs",
        "points_per_dim",
    );
    refused(
        &study(
            "",
            "tip",
            "type = \"pc_regression\"\ndesign = \"lhs\"\nruns = 20\npoints_per_dim = 4",
        ),
        "points_per_dim = 4",
        "method[0].points_per_dim",
        "not used",
    );
    refused(
        &study(
            "",
            "tip",
            "type = \"monte_carlo\"\nruns = 20\nmax_runs = 50",
        ),
        "max_runs = 50",
        "method[0].max_runs",
        "not adaptive",
    );
    refused(
        &study("", "tip", "type = \"piecewise_linear\"\ndegree = 3"),
        "degree = 3",
        "method[0].degree",
        "no polynomial degree",
    );
    // What the settings are for still loads.
    for method in [
        "type = \"adaptive\"\ncriterion = \"max_error\"\ndepth = 2\nmax_runs = 20",
        "type = \"adaptive\"\nfraction = 0.3",
        "type = \"pc_projection\"\npoints_per_dim = 3",
        "type = \"pc_regression\"\ndesign = \"grid\"\npoints_per_dim = 4",
        "type = \"monte_carlo\"\nruns = 20",
    ] {
        Study::from_source(Source::from_text("checks.toml", &study("", "tip", method)))
            .unwrap_or_else(|e| panic!("{method}: {e}"));
    }
    Study::from_source(Source::from_text(
        "checks.toml",
        &with_joint("[joint]\ntype = \"gaussian_copula\"\ncorrelation = [[1.0, 0.3], [0.3, 1.0]]"),
    ))
    .unwrap();
}

#[test]
fn names_that_would_share_a_file_name_are_refused() {
    let two = study("", "tip", PL)
        .replace("name = \"plate\"", "name = \"é\"")
        .replace("substructure = \"plate\"", "substructure = \"é\"")
        + "\n[[substructure]]\nname = \"è\"\nyoung = 1.0\npoisson = 0.0\n";
    refused(
        &two,
        "name = \"è\"",
        "substructure[1].name",
        "same file name '_'",
    );
}

#[test]
fn study_files_that_are_not_text_files_are_input_errors_with_a_location() {
    let dir = std::env::temp_dir().join(format!("alea-load-checks-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Invalid UTF-8 on line 3: an input error (exit code 2) at that line.
    let path = dir.join("latin1.toml");
    std::fs::write(&path, b"[study]\ntitle = \"ok\"\n# caf\xe9\n").unwrap();
    let e = Study::load(&path).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(e.to_string().contains("latin1.toml:3: (text)"), "{e}");
    assert!(e.to_string().contains("column 6"), "{e}");
    // A device: refused before reading a byte.
    let t = std::time::Instant::now();
    let e = Study::load(std::path::Path::new("/dev/zero")).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(
        e.to_string()
            .starts_with("/dev/zero:0: (file): not a regular file (a device"),
        "{e}"
    );
    assert!(t.elapsed().as_secs_f64() < 1.0);
    // A mesh file that is a device: refused at mesh.file, with its line.
    let text = study("", "tip", PL).replace(
        "generator = \"rectangle\"\nkind = \"quad4\"\nsize = [10.0, 2.0]\ncells = [2, 1]",
        "generator = \"gmsh\"\nfile = \"/dev/zero\"",
    );
    let t = std::time::Instant::now();
    refused(
        &text,
        "file = \"/dev/zero\"",
        "mesh.file",
        "not a regular file",
    );
    assert!(t.elapsed().as_secs_f64() < 1.0);
    // A very long expression is quoted abbreviated in the message.
    let long = format!("E * {}", "x".repeat(200_000));
    let text = study("", "tip", PL).replace("young = \"E\"", &format!("young = \"{long}\""));
    let e = Study::from_source(Source::from_text("checks.toml", &text)).unwrap_err();
    assert!(
        e.to_string().len() < 1000,
        "{} characters",
        e.to_string().len()
    );
    assert!(
        e.to_string().contains("(200004 characters)"),
        "{}",
        &e.to_string()[..300]
    );
}

/// The memory check of the mean / std fields counts the pairs of runs that a surrogate's
/// weights couple: a 10 000-run piecewise-linear study (2 runs per draw in 1D) loads, as its
/// fields need about 260 MB (the former check, `128 runs^2` bytes for any surrogate, asked 12.8
/// GB and refused it); a global chaos on 100 000 runs (10^10 pairs, about 560 GB) is refused at
/// load with the way out in the message, and accepted without mean / std fields.
#[test]
fn mean_fields_memory_is_checked_by_the_surrogates_support() {
    let load = |text: &str| Study::from_source(Source::from_text("checks.toml", text));
    let pl = study(
        "",
        "tip",
        "type = \"piecewise_linear\"\npoints_per_dim = 10000",
    );
    load(&pl).expect("a local surrogate's fields fit in memory");
    let chaos = "type = \"pc_regression\"\ndegree = 2\ndesign = \"lhs\"\nruns = 100000";
    let e = load(&study("", "tip", chaos)).expect_err("refused");
    let msg = e.to_string();
    assert!(
        msg.contains("mean / std fields") && msg.contains("mean_fields = false"),
        "{msg}"
    );
    load(&study("[output]\nmean_fields = false", "tip", chaos)).expect("no fields: accepted");
}

/// The study with the parameter `E` under `law` (its keys in `keys`, one `key = value` a line).
fn with_law(law: &str, keys: &str) -> String {
    study("", "tip", PL).replace(
        "law = \"uniform\"\nlo = 150e3\nhi = 250e3",
        &format!("law = \"{law}\"\n{keys}"),
    )
}

/// Issue 42, item 5: a key that the parameter's law does not use is refused with its line and
/// field (`lo` / `hi` on a normal law used to be dropped: the study then ran an untruncated
/// normal), and the law's own keys are named.
#[test]
fn keys_a_law_does_not_use_are_refused() {
    let normal = with_law("normal", "mean = 200e3\nstd = 20e3\nlo = 150e3\nhi = 250e3");
    refused(
        &normal,
        "lo = 150e3",
        "parameter[0].lo",
        "law = \"truncated_normal\"",
    );
    refused(
        &normal,
        "lo = 150e3",
        "parameter[0].lo",
        "it takes mean, std",
    );
    refused(
        &with_law("uniform", "lo = 150e3\nhi = 250e3\nstd = 10e3"),
        "std = 10e3",
        "parameter[0].std",
        "law 'uniform' does not use 'std' (it takes lo, hi)",
    );
    // Every other law refuses a key of another law, at that key's line.
    for (law, keys, bad, field) in [
        (
            "lognormal",
            "mean = 200e3\nstd = 20e3\nhi = 9e5",
            "hi = 9e5",
            "hi",
        ),
        (
            "truncated_normal",
            "mean = 200e3\nstd = 20e3\nlo = 150e3\nhi = 250e3\nmode = 2e5",
            "mode = 2e5",
            "mode",
        ),
        (
            "beta",
            "alpha = 2.0\nbeta = 3.0\nlo = 150e3\nhi = 250e3\nmean = 2e5",
            "mean = 2e5",
            "mean",
        ),
        (
            "triangular",
            "lo = 150e3\nmode = 2e5\nhi = 250e3\nstd = 1e4",
            "std = 1e4",
            "std",
        ),
        (
            "empirical",
            "data = \"e.csv\"\nmean = 2e5",
            "mean = 2e5",
            "mean",
        ),
        ("kde", "data = \"e.csv\"\nlo = 1e5", "lo = 1e5", "lo"),
        ("fit", "data = \"e.csv\"\nstd = 1e4", "std = 1e4", "std"),
    ] {
        refused(
            &with_law(law, keys),
            bad,
            &format!("parameter[0].{field}"),
            &format!("law '{law}' does not use '{field}'"),
        );
    }
    // The first key not used, in the order of the file, is the one named.
    refused(
        &with_law("normal", "hi = 250e3\nmean = 200e3\nstd = 20e3\nlo = 150e3"),
        "hi = 250e3",
        "parameter[0].hi",
        "truncated_normal",
    );
    // Each parametric law with its own keys loads.
    for (law, keys) in [
        ("uniform", "lo = 150e3\nhi = 250e3"),
        ("normal", "mean = 200e3\nstd = 20e3"),
        (
            "truncated_normal",
            "mean = 200e3\nstd = 20e3\nlo = 150e3\nhi = 250e3",
        ),
        ("lognormal", "mean = 200e3\nstd = 20e3\nunit = \"MPa\""),
        ("beta", "alpha = 2.0\nbeta = 3.0\nlo = 150e3\nhi = 250e3"),
        ("triangular", "lo = 150e3\nmode = 2e5\nhi = 250e3"),
    ] {
        Study::from_source(Source::from_text("checks.toml", &with_law(law, keys)))
            .unwrap_or_else(|e| panic!("{law}: {e}"));
    }
}

/// A lognormal Young's modulus under an adaptive method (whose start runs are the corners of
/// the parameter box) loads: the box of a law on a half-line is its 1e-6 tail quantiles, not
/// its support's end 0, where the modulus would vanish ("evaluates to 0 at E = 0; must be >
/// 0" before). The box is the law's quantiles to the digits of the closed form.
#[test]
fn a_lognormal_modulus_has_a_box_away_from_zero() {
    let text = with_law("lognormal", "mean = 200e3\nstd = 20e3")
        .replace(PL, "type = \"adaptive\"\nmax_runs = 20\n");
    let s = Study::from_source(Source::from_text("ln.toml", &text)).expect("loads");
    // log-mean and log-std of the law of mean 200e3 and std 20e3.
    let s2 = (1.0f64 + 0.01).ln();
    let (mu, sigma) = (200e3f64.ln() - s2 / 2.0, s2.sqrt());
    let z = 4.753_424_308_822_899; // the standard normal quantile of 1 - 1e-6
    let (lo, hi) = ((mu - sigma * z).exp(), (mu + sigma * z).exp());
    assert!(
        (s.params.lo[0] - lo).abs() < 1e-6 * lo,
        "{} vs {lo}",
        s.params.lo[0]
    );
    assert!(
        (s.params.hi[0] - hi).abs() < 1e-6 * hi,
        "{} vs {hi}",
        s.params.hi[0]
    );
}

/// A normal Young's modulus wide enough for its box's lower end (the 1e-6 quantile) to be
/// negative: refused before any run, at the modulus's line, saying that the end is the law's
/// tail quantile and naming the laws that avoid it.
#[test]
fn a_normal_modulus_whose_box_reaches_below_zero_says_why_and_what_to_use() {
    let text = with_law("normal", "mean = 210e3\nstd = 60e3");
    let s = Study::from_source(Source::from_text("wide.toml", &text)).expect("loads");
    let dir = std::env::temp_dir().join(format!("alea-wide-normal-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let Err(e) = alea_study::runner::run_study(&s, &dir, false, &alea_study::runner::NoProgress)
    else {
        panic!("a negative modulus at the box's end must be refused");
    };
    let text = e.to_string();
    for words in [
        "wide.toml:",
        "young",
        "must be > 0",
        "1e-6 and 1 - 1e-6 quantiles",
        "truncated_normal",
    ] {
        assert!(text.contains(words), "'{words}' in {text}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The study with its `[mesh]` keys replaced by `mesh`.
fn with_mesh(mesh: &str) -> String {
    study("", "tip", PL).replace(
        "generator = \"rectangle\"\nkind = \"quad4\"\nsize = [10.0, 2.0]\ncells = [2, 1]",
        mesh,
    )
}

/// Issue 42, item 5: `params` on the gmsh generator says that it takes only `file` (and that
/// `file` is missing when it is) instead of "expected one of: " and an empty list; the `[mesh]`
/// keys a generator does not read (`file` but with gmsh, `size` / `cells` but with rectangle
/// and box) are refused.
#[test]
fn mesh_keys_a_generator_does_not_use_are_refused() {
    let no_file = with_mesh("generator = \"gmsh\"\nparams = { radius = 1.0 }");
    refused(
        &no_file,
        "params = ",
        "mesh.params",
        "the gmsh generator takes no params, only file = ",
    );
    refused(&no_file, "params = ", "mesh.params", "file is missing");
    let msg = Study::from_source(Source::from_text("checks.toml", &no_file))
        .unwrap_err()
        .to_string();
    assert!(!msg.contains("one of"), "{msg}");
    let with_file = with_mesh("generator = \"gmsh\"\nfile = \"m.msh\"\nparams = { radius = 1.0 }");
    refused(&with_file, "params = ", "mesh.params", "only file = ");
    let msg = Study::from_source(Source::from_text("checks.toml", &with_file))
        .unwrap_err()
        .to_string();
    assert!(!msg.contains("missing"), "{msg}");
    refused(
        &with_mesh(
            "generator = \"rectangle\"\nsize = [10.0, 2.0]\ncells = [2, 1]\nparams = { n = 2 }",
        ),
        "params = ",
        "mesh.params",
        "generator 'rectangle' takes no params, only size and cells",
    );
    refused(
        &with_mesh(
            "generator = \"rectangle\"\nsize = [10.0, 2.0]\ncells = [2, 1]\nfile = \"m.msh\"",
        ),
        "file = ",
        "mesh.file",
        "generator 'rectangle' does not use 'file' (it takes size and cells)",
    );
    refused(
        &with_mesh("generator = \"gmsh\"\nfile = \"m.msh\"\ncells = [2, 1]"),
        "cells = ",
        "mesh.cells",
        "does not use 'cells' (it takes file)",
    );
    refused(
        &with_mesh(
            "generator = \"plate_with_hole\"\nsize = [10.0, 2.0]\nparams = { radius = 1.0, half_width = 5.0 }",
        ),
        "size = ",
        "mesh.size",
        "its parameters go in params",
    );
    refused(
        &with_mesh("generator = \"rectangel\"\nsize = [10.0, 2.0]\ncells = [2, 1]"),
        "generator = ",
        "mesh.generator",
        "unknown generator 'rectangel'; expected rectangle, box,",
    );
}

/// Extra `[[parameter]]` tables `x1 .. x{count}` of one family (`uniform`, `normal`, `mixed`:
/// the other laws of a study file in turn).
fn extra_parameters(family: &str, count: usize) -> String {
    let law = |j: usize| match (family, j % 5) {
        ("uniform", _) => "law = \"uniform\"\nlo = 1.0\nhi = 3.0".to_string(),
        ("normal", _) | ("mixed", 0) => "law = \"normal\"\nmean = 1.0\nstd = 0.2".to_string(),
        ("mixed", 1) => "law = \"lognormal\"\nmean = 1.0\nstd = 0.3".to_string(),
        ("mixed", 2) => {
            "law = \"truncated_normal\"\nmean = 0.5\nstd = 0.2\nlo = 0.1\nhi = 0.9".to_string()
        }
        ("mixed", 3) => "law = \"beta\"\nalpha = 2.0\nbeta = 3.0\nlo = 0.0\nhi = 1.0".to_string(),
        _ => "law = \"triangular\"\nlo = 0.0\nmode = 0.3\nhi = 1.0".to_string(),
    };
    (1..=count)
        .map(|j| format!("[[parameter]]\nname = \"x{j}\"\n{}\n", law(j)))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn default_chaos_design_determines_its_surrogate() {
    // Issue 42, item 9: degree 3 on three uniform parameters used to spend its 40 runs and end
    // "matrix is singular (pivot 10 of 20)". Every default design now loads (its information
    // matrix is checked at load) and its surrogate is built on its points, before any run.
    for family in ["uniform", "normal", "mixed"] {
        for d in 1..=6 {
            for p in 1..=5 {
                let text = study(
                    &extra_parameters(family, d - 1),
                    "tip",
                    &format!("type = \"pc_regression\"\ndegree = {p}"),
                );
                let s = Study::from_source(Source::from_text("checks.toml", &text))
                    .unwrap_or_else(|e| panic!("{family}, d = {d}, p = {p}: {e}"));
                let method = &s.methods[0];
                let terms = (1..=d).fold(1usize, |t, k| t * (p + k) / k);
                let full = (p + 1).pow(d as u32);
                assert_eq!(method.points.len(), full.min(2 * terms), "{family} {d} {p}");
                method
                    .surrogate(&s.params, &method.points)
                    .unwrap_or_else(|e| panic!("{family}, d = {d}, p = {p}: {e}"));
            }
        }
    }
}

#[test]
fn chaos_designs_that_cannot_determine_it_are_refused_at_load() {
    let three = extra_parameters("uniform", 2);
    // An explicit run count below the 20 terms of degree 3 in 3 parameters.
    refused(
        &study(
            &three,
            "tip",
            "type = \"pc_regression\"\ndegree = 3\nruns = 19",
        ),
        "runs = 19",
        "method[0].runs",
        "20 terms: at least that many runs",
    );
    // More collocation runs than the 64 roots.
    refused(
        &study(
            &three,
            "tip",
            "type = \"pc_regression\"\ndegree = 3\nruns = 65",
        ),
        "runs = 65",
        "method[0].runs",
        "64 candidate points",
    );
    // A grid of 3 nodes per parameter cannot tell a cubic from lower terms.
    refused(
        &study(
            &three,
            "tip",
            "type = \"pc_regression\"\ndegree = 3\ndesign = \"grid\"\npoints_per_dim = 3",
        ),
        "points_per_dim = 3",
        "method[0].points_per_dim",
        "the term (3, 0, 0) (leading monomial E^3) is a combination of the terms before it",
    );
    // Corners and centre: 9 runs for 10 terms of degree 2 in 3 parameters.
    refused(
        &study(
            &three,
            "tip",
            "type = \"pc_regression\"\ndegree = 2\ndesign = \"corners_centre\"",
        ),
        "design = \"corners_centre\"",
        "method[0].design",
        "10 terms: at least that many runs are needed, got 9",
    );
    // The run count that suffices loads, with the exact number of runs asked.
    let s = Study::from_source(Source::from_text(
        "checks.toml",
        &study(
            &three,
            "tip",
            "type = \"pc_regression\"\ndegree = 3\nruns = 20",
        ),
    ))
    .unwrap();
    assert_eq!(s.methods[0].points.len(), 20);
}

/// The load-time memory estimate of a 3D mesh (`alea_study::limits::mesh_memory`) bounds the
/// peaks measured on the 3D turbine studies (BENCHMARKS.md, "Single-precision factors": 2 Monte
/// Carlo runs, `/usr/bin/time -f %M`), within 2x, so that it neither accepts a model that does
/// not fit nor refuses one that fits with half the memory to spare.
#[test]
fn the_3d_memory_estimate_bounds_the_measured_peaks() {
    use alea_study::limits::{FactorLayout, mesh_memory};
    let auto = FactorLayout {
        part_dofs: Some(alea_latin::split::AUTO_MIN_DOFS),
        single: true,
    };
    let never = FactorLayout {
        part_dofs: None,
        ..auto
    };
    let double = FactorLayout {
        single: false,
        ..auto
    };
    // (nodes, layout, measured peak in bytes)
    let measured = [
        (27_508.0, auto, 0.40e9),    // unrefined, 4 substructures undivided
        (200_700.0, auto, 2.65e9),   // split = 1, 30 parts
        (722_364.0, auto, 10.2e9),   // split = 1 and 40 layers, 96 parts
        (200_700.0, never, 5.20e9),  // split = 1 undivided (set-up in double precision)
        (200_700.0, double, 3.62e9), // split = 1, 30 parts, factor_precision = "double"
    ];
    for (nodes, layout, peak) in measured {
        let estimate = mesh_memory(nodes, 3, layout);
        assert!(
            estimate >= peak && estimate <= 2.0 * peak.max(1e9),
            "{nodes} nodes, {layout:?}: estimate {estimate:.3e} bytes against {peak:.3e} measured"
        );
    }
}
