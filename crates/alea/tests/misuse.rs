//! Misuse from issue 14, each with its documented exit code (`docs/study-file.md`, "Exit
//! codes") and a message naming file, line and field:
//! - every Gmsh error (missing file, a directory, truncated, wrong counts, bad node reference,
//!   version 2.2, binary garbage) and interface error (same substructure twice, sides not
//!   facing, facets in two interfaces) is an input error (2) at the study file's field;
//! - duplicate quantity names, a point quantity far from every node, `kde_points = 0`, deep
//!   expressions: 2;
//! - sizes beyond memory or sane limits (cells, grids, runs, thresholds, samples, threads) are
//!   refused at load time (2), before any run, with the estimate in the message;
//! - a solve that does not converge, and a study where no run converged: 4, after writing the
//!   outputs.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

mod common;
use common::text;

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    common::fresh_dir("alea-misuse", name)
}

/// Line (1-based) of the first line of `text` containing `needle`.
fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("'{needle}' not in the file"))
        + 1
}

fn expect_input_error(o: &Output, file: &Path, line: usize, field: &str, what: &str) {
    let t = text(o);
    assert_eq!(o.status.code(), Some(2), "{what}: {t}");
    assert!(!t.contains("panicked"), "{what}: {t}");
    let name = file.file_name().unwrap().to_string_lossy();
    assert!(
        t.contains(&format!("{name}:{line}: {field}")),
        "{what}: '{name}:{line}: {field}' expected in: {t}"
    );
}

const GMSH_CASE: &str = r#"[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "gmsh"
file = "m.msh"

[analysis]
type = "plane_stress"

[[substructure]]
name = "plate"
young = 1000.0
poisson = 0.3
constraint = [ { group = "xmin", x = 0.0, y = 0.0 } ]
load = [ { group = "xmax", traction = [1.0, 0.0] } ]
"#;

#[test]
fn gmsh_errors_are_input_errors_at_the_mesh_file_field() {
    let dir = tmp("gmsh");
    let case = dir.join("case.toml");
    std::fs::write(&case, GMSH_CASE).unwrap();
    let good =
        std::fs::read_to_string(root().join("crates/alea-mesh/tests/fixtures/square_q4_ascii.msh"))
            .unwrap();
    let solve = || {
        alea()
            .arg("solve")
            .arg(&case)
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap()
    };
    // The good file solves.
    std::fs::write(dir.join("m.msh"), &good).unwrap();
    let o = solve();
    assert!(o.status.success(), "{}", text(&o));
    let line = line_of(GMSH_CASE, "file = ");
    let nodes_at = good.find("$Nodes\n").unwrap() + "$Nodes\n".len();
    let elements_at = good.find("$Elements\n").unwrap() + "$Elements\n".len();
    let first_element_line = good[elements_at..].lines().nth(2).unwrap().to_string();
    let mut bad_ref = first_element_line.split_whitespace().collect::<Vec<_>>();
    let last = bad_ref.len() - 1;
    bad_ref[last] = "999999";
    let cases: Vec<(&str, Option<Vec<u8>>, &str)> = vec![
        ("missing file", None, "m.msh"),
        (
            "truncated",
            Some(good.as_bytes()[..good.len() / 2].to_vec()),
            "m.msh:",
        ),
        (
            "wrong node count",
            Some(
                format!(
                    "{}{}",
                    &good[..nodes_at],
                    good[nodes_at..].replacen(" 15 1 15", " 16 1 16", 1)
                )
                .into_bytes(),
            ),
            "m.msh:",
        ),
        (
            "bad node reference",
            Some(
                good.replacen(&first_element_line, &bad_ref.join(" "), 1)
                    .into_bytes(),
            ),
            "m.msh:",
        ),
        (
            "version 2.2",
            Some(good.replacen("4.1 0 8", "2.2 0 8", 1).into_bytes()),
            "m.msh:2:",
        ),
        (
            "binary garbage",
            Some(
                (0..4096u32)
                    .map(|i| ((i * 2_654_435_761) >> 13) as u8)
                    .collect(),
            ),
            "m.msh:",
        ),
    ];
    for (what, content, mention) in cases {
        let _ = std::fs::remove_file(dir.join("m.msh"));
        if let Some(c) = content {
            std::fs::write(dir.join("m.msh"), c).unwrap();
        }
        let o = solve();
        expect_input_error(&o, &case, line, "mesh.file", what);
        assert!(text(&o).contains(mention), "{what}: {}", text(&o));
    }
    // A directory where the file should be.
    let _ = std::fs::remove_file(dir.join("m.msh"));
    std::fs::create_dir_all(dir.join("m.msh")).unwrap();
    expect_input_error(&solve(), &case, line, "mesh.file", "a directory");
}

#[test]
fn interface_errors_are_input_errors_at_the_interface() {
    let dir = tmp("iface");
    let base = std::fs::read_to_string(root().join("examples/dovetail-contact.toml")).unwrap();
    let second = r#"[[interface]]
name = "flank_right"
side1 = ["disk", "flank_right_disk"]
side2 = ["root", "flank_right_root"]"#;
    assert!(base.contains(second));
    let cases = [
        (
            "same substructure twice",
            base.replacen(
                "side2 = [\"root\", \"flank_left_root\"]",
                "side2 = [\"disk\", \"flank_right_disk\"]",
                1,
            ),
            "side2 = [\"disk\", \"flank_right_disk\"]",
            "interface[0].side2",
            "two different substructures",
        ),
        (
            "sides not facing (left flank of the disk with the right flank of the root)",
            base.replacen(
                "side2 = [\"root\", \"flank_left_root\"]",
                "side2 = [\"root\", \"SWAPPED\"]",
                1,
            )
            .replacen(
                "side2 = [\"root\", \"flank_right_root\"]",
                "side2 = [\"root\", \"flank_left_root\"]",
                1,
            )
            .replacen("SWAPPED", "flank_right_root", 1),
            "side2 = [\"root\", \"flank_right_root\"]",
            "interface[0].side2",
            "faces side 1",
        ),
        (
            "facets in two interfaces",
            base.replacen(
                second,
                &format!(
                    "{}\nlaw = \"perfect\"\n\n{second}",
                    second.replace("\"flank_right\"", "\"again\"")
                ),
                1,
            ),
            "name = \"flank_right\"",
            "interface[2].side1",
            "already belong to interface[1] 'again'",
        ),
    ];
    // Two bodies on the same cells: the contact nodes coincide but the sides face the same way.
    let slip = std::fs::read_to_string(root().join("examples/full-slip.toml")).unwrap();
    let overlap = slip
        .replacen("cells = \"upper\"", "cells = \"lower\"", 1)
        .replacen(
            "constraint = [ { group = \"upper_top\", x = 0.05 } ]",
            "constraint = [ { group = \"lower_bottom\", x = 0.0, y = 0.0 } ]",
            1,
        )
        .replacen(
            "load = [ { group = \"upper_top\"",
            "load = [ { group = \"lower_top\"",
            1,
        )
        .replacen(
            "side2 = [\"block\", \"upper_bottom\"]",
            "side2 = [\"block\", \"lower_top\"]",
            1,
        );
    assert_eq!(
        overlap.matches("lower").count(),
        slip.matches("lower").count() + 4
    );
    let cases = [
        cases[0].clone(),
        cases[1].clone(),
        cases[2].clone(),
        (
            "sides facing the same way",
            overlap,
            "side1 = [\"base\", \"lower_top\"]",
            "interface[0]",
            "do not face each other",
        ),
    ];
    for (i, (what, t, at, field, msg)) in cases.iter().enumerate() {
        let case = dir.join(format!("case{i}.toml"));
        std::fs::write(&case, t).unwrap();
        let o = alea()
            .arg("solve")
            .arg(&case)
            .arg("--out")
            .arg(&dir)
            .output()
            .unwrap();
        let mut line = line_of(t, at);
        if *what == "facets in two interfaces" {
            line += 1; // side1 of the interface after the copy
        }
        expect_input_error(&o, &case, line, field, what);
        assert!(text(&o).contains(msg), "{what}: {}", text(&o));
    }
}

/// The shipped plate study with some text replaced (each replacement must apply).
fn plate(dir: &Path, name: &str, edits: &[(&str, &str)], tail: &str) -> (PathBuf, String) {
    let mut t = std::fs::read_to_string(root().join("examples/plate-random-E.toml")).unwrap();
    for (a, b) in edits {
        assert!(t.contains(a), "{a}");
        t = t.replacen(a, b, 1);
    }
    t.push_str(tail);
    let p = dir.join(format!("{name}.toml"));
    std::fs::write(&p, &t).unwrap();
    (p, t)
}

/// A misuse case: what, text edits, text appended, the field and the words of the message.
type Case<'a> = (&'a str, Vec<(&'a str, &'a str)>, String, &'a str, &'a str);

fn run(study: &Path, dir: &Path, extra: &[&str]) -> Output {
    alea()
        .arg("run")
        .arg(study)
        .arg("--dir")
        .arg(dir)
        .arg("-q")
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn duplicates_far_points_and_bad_statistics_are_refused() {
    let dir = tmp("dups");
    let quantity = "[[quantity]]\nname = \"tip\"";
    let deep = format!("young = \"{}E{}\"", "(".repeat(5000), ")".repeat(5000));
    let cases: Vec<Case> = vec![
        (
            "same quantity name",
            vec![],
            format!(
                "\n{quantity}\nkind = \"displacement\"\nsubstructure = \"plate\"\npoint = [0.0, 0.0]\ncomponent = 1\n"
            ),
            "quantity[1].name",
            "already the name",
        ),
        (
            "point far from every node",
            vec![("point = [100.0, 20.0]", "point = [500.0, 20.0]")],
            String::new(),
            "quantity[0].point",
            "no node of substructure",
        ),
        (
            "kde_points = 0",
            vec![],
            "\n[statistics]\nkde_points = 0\n".into(),
            "statistics.kde_points",
            "must be in 2",
        ),
        (
            "deep expression",
            vec![("young = \"E\"", deep.as_str())],
            String::new(),
            "substructure[0].young",
            "nested more than",
        ),
    ];
    for (i, (what, edits, tail, field, msg)) in cases.iter().enumerate() {
        let (p, _) = plate(&dir, &format!("s{i}"), edits, tail);
        let o = run(&p, &dir.join(format!("out{i}")), &[]);
        let t2 = text(&o);
        assert_eq!(o.status.code(), Some(2), "{what}: {t2}");
        assert!(t2.contains(field) && t2.contains(msg), "{what}: {t2}");
        assert!(t2.contains(&format!("s{i}.toml:")), "{what}: {t2}");
    }
}

#[test]
fn sizes_beyond_the_limits_are_refused_before_any_run() {
    let dir = tmp("sizes");
    let many = format!("thresholds = [{}]", vec!["0.1"; 10_000].join(","));
    let cases: Vec<Case> = vec![
        (
            "cells 2^63-1 x 2",
            vec![("cells = [10, 2]", "cells = [9223372036854775807, 2]")],
            String::new(),
            "mesh.cells",
            "memory",
        ),
        (
            "cells 1e5 x 1e5",
            vec![("cells = [10, 2]", "cells = [100000, 100000]")],
            String::new(),
            "mesh.cells",
            "memory",
        ),
        (
            "1000 x 1000 grid",
            vec![(
                "type = \"monte_carlo\"\nruns = 400",
                "type = \"piecewise_linear\"\npoints_per_dim = 1000",
            )],
            String::new(),
            "method[1].points_per_dim",
            "1.000e6 runs",
        ),
        (
            "10^9 model runs",
            vec![("runs = 400", "runs = 1000000000")],
            String::new(),
            "method[1].runs",
            "at most 100000",
        ),
        (
            "10^4 thresholds",
            vec![("thresholds = [0.13]", many.as_str())],
            String::new(),
            "quantity[0].thresholds",
            "at most 1000",
        ),
        (
            "10^9 Monte Carlo samples",
            vec![],
            "\n[statistics]\nsamples = 1000000000\n".into(),
            "statistics.samples",
            "memory",
        ),
        (
            "10^12 Monte Carlo samples",
            vec![],
            "\n[statistics]\nsamples = 1000000000000\n".into(),
            "statistics.samples",
            "memory",
        ),
        (
            "PC degree 200 in 2 parameters",
            vec![("degree = 4", "degree = 200")],
            String::new(),
            "method[0].degree",
            "terms",
        ),
    ];
    for (i, (what, edits, tail, field, msg)) in cases.iter().enumerate() {
        let (p, _) = plate(&dir, &format!("z{i}"), edits, tail);
        let out = dir.join(format!("out{i}"));
        let t0 = Instant::now();
        let o = run(&p, &out, &[]);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{what}: {t}");
        assert!(t.contains(field) && t.contains(msg), "{what}: {t}");
        assert!(
            !out.join("study.db").exists(),
            "{what}: refused before any run"
        );
        assert!(t0.elapsed().as_secs_f64() < 10.0, "{what}: refused quickly");
    }
    let (p, _) = plate(&dir, "threads", &[], "");
    let o = run(&p, &dir.join("threads"), &["--threads", "100000"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--threads 100000"), "{}", text(&o));
}

#[test]
fn no_convergence_exits_4_after_writing_the_outputs() {
    let dir = tmp("noconv");
    let t = std::fs::read_to_string(root().join("examples/dovetail-contact.toml"))
        .unwrap()
        .replace("max_iterations = 3000", "max_iterations = 2");
    let case = dir.join("case.toml");
    std::fs::write(&case, t).unwrap();
    let o = alea()
        .arg("solve")
        .arg(&case)
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(4), "{}", text(&o));
    assert!(text(&o).contains("did not converge"), "{}", text(&o));
    assert!(dir.join("case.vtm").exists(), "the last iterate is written");
    // A study none of whose runs converged.
    let t = std::fs::read_to_string(root().join("examples/turbine-2d-wear.toml"))
        .unwrap()
        .replace("max_iterations = 5000", "max_iterations = 1");
    let study = dir.join("study.toml");
    std::fs::write(&study, t).unwrap();
    let o = run(&study, &dir.join("study"), &[]);
    assert_eq!(o.status.code(), Some(4), "{}", text(&o));
    assert!(text(&o).contains("no run converged"), "{}", text(&o));
    assert!(dir.join("study/summary.json").exists());
}

/// Issue 21, item 4: a single floating substructure under a self-equilibrated load (equal and
/// opposite tractions on two faces, no constraint) is refused as an input error (exit 2) at
/// its substructure, once, with the reason - not "stiffness matrix is not positive definite"
/// with exit 4 and no location.
#[test]
fn a_single_floating_body_is_an_input_error_at_its_substructure() {
    let case_text = r#"
[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [10.0, 2.0]
cells = [4, 2]

[analysis]
type = "plane_stress"

[[substructure]]
name = "bar"
young = 1000.0
poisson = 0.3
load = [ { group = "xmax", traction = [1.0, 0.0] }, { group = "xmin", traction = [-1.0, 0.0] } ]
"#;
    let dir = tmp("floating");
    let case = dir.join("floating.toml");
    std::fs::write(&case, case_text).unwrap();
    let o = alea()
        .arg("solve")
        .arg(&case)
        .arg("--out")
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    let line = line_of(case_text, "name = \"bar\"");
    assert!(
        t.contains(&format!("floating.toml:{line}:")) && t.contains("substructure[0].constraint"),
        "{t}"
    );
    assert!(t.contains("rigid body"), "{t}");
    assert_eq!(t.matches("rigid body").count(), 1, "said once: {t}");
}

/// Issue 42, item 5, end to end: keys that used to be ignored are input errors (2) at
/// `file:line: field` - bounds on a normal law (the study used to run an untruncated normal),
/// `std` on a uniform law, and `params` on a Gmsh mesh (which said "expected one of: " with an
/// empty list, and not that `file` was missing).
#[test]
fn keys_that_would_be_ignored_are_input_errors_at_their_line() {
    let dir = tmp("ignored");
    let cases = [
        (
            "bounds on a normal law",
            ("std = 0.1", "std = 0.1\nlo = 0.8\nhi = 1.2"),
            "lo = 0.8",
            "parameter[1].lo",
            "law = \"truncated_normal\"",
        ),
        (
            "std on a uniform law",
            ("hi = 250e3", "hi = 250e3\nstd = 1e4"),
            "std = 1e4",
            "parameter[0].std",
            "law 'uniform' does not use 'std'",
        ),
        (
            "params on a Gmsh mesh",
            (
                "generator = \"rectangle\"\nkind = \"quad4\"\nsize = [100.0, 20.0]\ncells = [10, 2]",
                "generator = \"gmsh\"\nparams = { size = 1.0 }",
            ),
            "params = ",
            "mesh.params",
            "the gmsh generator takes no params, only file = \"<mesh>.msh\" (a Gmsh 4.1 file, relative to the study file); file is missing",
        ),
    ];
    for (i, (what, edit, needle, field, msg)) in cases.into_iter().enumerate() {
        let (p, t) = plate(&dir, &format!("k{i}"), &[edit], "");
        let o = run(&p, &dir.join(format!("out{i}")), &[]);
        expect_input_error(&o, &p, line_of(&t, needle), field, what);
        assert!(text(&o).contains(msg), "{what}: {}", text(&o));
        assert!(!text(&o).contains("one of: \n"), "{what}: {}", text(&o));
    }
}
