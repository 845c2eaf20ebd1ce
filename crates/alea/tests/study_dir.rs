//! The study directory under misuse (issue 14):
//! - a second process on a busy study directory is refused (exit 5) with the holder named
//!   (pid, host, start time); a lock left by a dead process is taken over;
//! - `alea report DIR` rebuilds every output from the store alone (a study run with
//!   `report = false`, outputs deleted as a kill during the output phase would leave them),
//!   byte-identical to what `alea run` wrote, and refuses a directory that holds no study;
//! - a changed mesh file makes a different study: the runs of the old one are not reused.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use alea_study::lock::StudyLock;

mod common;
use common::text;

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    common::fresh_dir("alea-dir", name)
}

/// The shipped plate study, smaller (a few tenths of a second).
fn small_study(dir: &Path, extra: &str) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/plate-random-E.toml"))
        .unwrap()
        .replace("runs = 400", "runs = 30")
        + "\n[statistics]\nsamples = 4000\n"
        + extra;
    let path = dir.join("plate.toml");
    std::fs::write(&path, text).unwrap();
    path
}

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
fn a_busy_study_directory_is_refused_and_a_dead_holder_taken_over() {
    let base = tmp("busy");
    let study = small_study(&base, "");
    let dir = base.join("out");
    {
        let _held = StudyLock::acquire(&dir, "alea run other.toml").unwrap();
        for extra in [&[][..], &["--restart"][..]] {
            let o = run(&study, &dir, extra);
            let t = text(&o);
            assert_eq!(o.status.code(), Some(5), "{t}");
            assert!(
                t.contains(&format!("pid {} on host", std::process::id()))
                    && t.contains("UTC")
                    && t.contains("alea run other.toml"),
                "holder named: {t}"
            );
            assert!(!dir.join("study.db").exists(), "nothing written: {t}");
        }
        let o = alea().arg("report").arg(&dir).output().unwrap();
        assert_eq!(o.status.code(), Some(5), "{}", text(&o));
    }
    // What a SIGKILLed holder leaves behind: its record, no lock.
    let stale = "pid 4000000 on host gone, started 2026-01-01 00:00:00 UTC (alea run x.toml)";
    std::fs::write(dir.join("lock"), stale).unwrap();
    let o = run(&study, &dir, &[]);
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("took over the lock") && t.contains(stale), "{t}");
    assert_eq!(std::fs::read_to_string(dir.join("lock")).unwrap(), "");
}

#[test]
fn report_rebuilds_every_output_from_the_store() {
    let base = tmp("report");
    let study = small_study(&base, "\n[output]\nreport = false\n");
    let dir = base.join("out");
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(!dir.join("report").exists());
    let summary = std::fs::read(dir.join("summary.json")).unwrap();
    let samples = std::fs::read(dir.join("samples.csv")).unwrap();
    // A kill during the outputs: summary gone, samples half written; the study file moved away.
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    std::fs::write(dir.join("samples.csv"), &samples[..samples.len() / 2]).unwrap();
    std::fs::rename(&study, base.join("moved.toml")).unwrap();
    let o = alea().arg("report").arg(&dir).output().unwrap();
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("80 of 80 runs finished"), "{t}");
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
    assert_eq!(std::fs::read(dir.join("samples.csv")).unwrap(), samples);
    assert!(dir.join("report/report.html").exists());
    assert!(dir.join("paraview/mean_std.vtm").exists());
    // No temporary file is left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    // An output that cannot be written (here a directory where summary.json goes; a full disk
    // gives the same kind of error): a file-system error, exit code 3.
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    std::fs::create_dir(dir.join("summary.json")).unwrap();
    let o = alea().arg("report").arg(&dir).output().unwrap();
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert!(text(&o).contains("summary.json"), "{}", text(&o));
    // Not a study directory: an input error naming it, not a crash.
    let empty = tmp("report-empty");
    let o = alea().arg("report").arg(&empty).output().unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("not a study directory"), "{}", text(&o));
    let o = alea()
        .arg("report")
        .arg(base.join("does-not-exist"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
}

#[test]
fn a_changed_mesh_file_is_a_different_study() {
    let base = tmp("mesh");
    let msh = root().join("crates/alea-mesh/tests/fixtures/square_q4_ascii.msh");
    std::fs::copy(&msh, base.join("m.msh")).unwrap();
    let study = base.join("gmsh.toml");
    let text = std::fs::read_to_string(small_study(&base, ""))
        .unwrap()
        .replace(
            "generator = \"rectangle\"\nkind = \"quad4\"\nsize = [100.0, 20.0]\ncells = [10, 2]",
            "generator = \"gmsh\"\nfile = \"m.msh\"",
        )
        .replace("point = [100.0, 20.0]", "point = [2.0, 1.0]")
        .replace("thresholds = [0.13]", "thresholds = [0.001]");
    assert!(text.contains("m.msh"));
    std::fs::write(&study, text).unwrap();
    let dir = base.join("out");
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", text_of(&o));
    // Same study file, another mesh (an extra section the reader skips changes the bytes).
    let mut m = std::fs::read(base.join("m.msh")).unwrap();
    m.extend_from_slice(b"$Comments\nremeshed\n$EndComments\n");
    std::fs::write(base.join("m.msh"), m).unwrap();
    let o = run(&study, &dir, &[]);
    assert_eq!(o.status.code(), Some(2), "{}", text_of(&o));
    assert!(
        text_of(&o).contains("mesh file counts too"),
        "{}",
        text_of(&o)
    );
    let o = run(&study, &dir, &["--restart"]);
    assert!(o.status.success(), "{}", text_of(&o));
    assert!(text_of(&o).contains(" 0 resumed"), "{}", text_of(&o));
}

fn text_of(o: &Output) -> String {
    text(o)
}

#[test]
fn a_study_without_parameters_is_one_deterministic_run() {
    let base = tmp("deterministic");
    let text = std::fs::read_to_string(root().join("examples/full-slip.toml")).unwrap()
        + r#"
[[quantity]]
name = "friction"
kind = "interface_force"
interface = "contact"
component = 0
unit = "N"

[[quantity]]
name = "dissipation"
kind = "friction_dissipation"
interface = "contact"

[output]
vtu = true
"#;
    let study = base.join("slip.toml");
    std::fs::write(&study, &text).unwrap();
    let dir = base.join("out");
    let o = run(&study, &dir, &[]);
    let t = text_of(&o);
    assert!(o.status.success(), "{t}");
    // The friction force of full slip, -mu N = -120 N, printed at full precision.
    let v: f64 = t
        .split("friction = ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{t}"));
    assert!((v + 120.0).abs() < 1e-6, "{v}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["runs"].as_array().unwrap().len(), 1);
    assert_eq!(summary["runs"][0]["status"], "converged");
    assert_eq!(summary["methods"][0]["label"], "deterministic");
    assert!(dir.join("report/report.html").exists());
    let vtu: Vec<_> = std::fs::read_dir(dir.join("vtu"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_dir())
        .collect();
    assert_eq!(vtu.len(), 1);
    assert!(vtu[0].join("interface_contact.csv").exists());
    // Methods need parameters.
    let bad = base.join("bad.toml");
    std::fs::write(&bad, text + "\n[[method]]\ntype = \"monte_carlo\"\n").unwrap();
    let o = run(&bad, &base.join("bad"), &[]);
    assert_eq!(o.status.code(), Some(2), "{}", text_of(&o));
    assert!(text_of(&o).contains("method[0].type"), "{}", text_of(&o));
}

/// The `runs: N computed, M resumed` counts of a run's output.
fn counts(o: &Output) -> (usize, usize) {
    let t = text_of(o);
    let line = t
        .lines()
        .find(|l| l.contains(" computed, ") && l.contains(" resumed"))
        .unwrap_or_else(|| panic!("no run counts in: {t}"));
    let number_before = |word: &str| -> usize {
        let head = &line[..line.find(word).unwrap()];
        head.split_whitespace().last().unwrap().parse().unwrap()
    };
    (number_before(" computed"), number_before(" resumed"))
}

/// Issue 42, item 4: edits that leave what defines a run unchanged keep every stored run - a
/// comment, a threshold and a statistics setting (nothing computed), a method (its new points
/// only), a Monte Carlo method's run count raised (the new draws only); a changed Young's
/// modulus or load is still refused.
#[test]
fn edits_that_keep_the_runs_reuse_them() {
    let base = tmp("edits");
    let study = small_study(&base, "");
    let original = std::fs::read_to_string(&study).unwrap();
    let dir = base.join("out");
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", text_of(&o));
    // 40 LHS points, 30 Monte Carlo draws and 10 validation runs (a quarter of the LHS design).
    assert_eq!(counts(&o), (80, 0), "{}", text_of(&o));
    let edit = |text: &str| {
        std::fs::write(&study, text).unwrap();
        run(&study, &dir, &[])
    };
    // (a) a comment appended.
    let o = edit(&format!("{original}\n# checked against the closed form\n"));
    assert!(o.status.success(), "{}", text_of(&o));
    assert_eq!(counts(&o), (0, 80), "{}", text_of(&o));
    // (b) a threshold added, and more draws on the surrogate.
    let text = original
        .replace("thresholds = [0.13]", "thresholds = [0.13, 0.15]")
        .replace("samples = 4000", "samples = 5000");
    let o = edit(&text);
    assert!(o.status.success(), "{}", text_of(&o));
    assert_eq!(counts(&o), (0, 80), "{}", text_of(&o));
    let summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    assert!(summary.contains("0.15"), "the outputs are rewritten");
    // (c) a method added: its 8 new points only (the largest design, and so the validation
    // runs, unchanged).
    let text = format!(
        "{text}\n[[method]]\ntype = \"pc_regression\"\nlabel = \"PC 2\"\ndegree = 2\ndesign = \"lhs\"\nruns = 8\n"
    );
    let o = edit(&text);
    assert!(o.status.success(), "{}", text_of(&o));
    assert_eq!(counts(&o), (8, 80), "{}", text_of(&o));
    // (d) the Monte Carlo method raised from 30 to 40 runs: 10 new draws.
    let text = text.replace("runs = 30", "runs = 40");
    let o = edit(&text);
    assert!(o.status.success(), "{}", text_of(&o));
    assert_eq!(counts(&o), (10, 88), "{}", text_of(&o));
    // (e) another Young's modulus or another load: a different model, refused.
    for changed in [
        text.replace("young = \"E\"", "young = \"1.1 * E\""),
        text.replace("traction = [200.0, 0.0]", "traction = [210.0, 0.0]"),
    ] {
        assert_ne!(changed, text);
        let o = edit(&changed);
        assert_eq!(o.status.code(), Some(2), "{}", text_of(&o));
        assert!(
            text_of(&o).contains("what defines its runs differs"),
            "{}",
            text_of(&o)
        );
    }
    // Refused without harm: the last accepted study still resumes every run.
    let o = edit(&text);
    assert_eq!(counts(&o), (0, 98), "{}", text_of(&o));
}

/// Issue 42, item 2: two methods whose designs hold the same point up to round-off (a 3 x 3
/// grid's centre `0.1 + 0.6 / 2 = 0.4` and the corners-and-centre design's
/// `0.5 * (0.1 + 0.7) = 0.39999999999999997`) make one run of it, not two.
#[test]
fn points_equal_up_to_round_off_are_one_run() {
    let base = tmp("round-off");
    let study = base.join("twins.toml");
    let text = std::fs::read_to_string(small_study(&base, ""))
        .unwrap()
        .replace(
            "law = \"normal\"\nmean = 1.0\nstd = 0.1",
            "law = \"uniform\"\nlo = 0.1\nhi = 0.7",
        );
    let methods = text.find("[[method]]").unwrap();
    let text = format!(
        "{}[[method]]\ntype = \"polynomial\"\ndegree = 1\ndesign = \"grid\"\npoints_per_dim = 3\n\n\
         [[method]]\ntype = \"pc_regression\"\ndegree = 1\ndesign = \"corners_centre\"\n\n\
         [statistics]\nsamples = 4000\n",
        &text[..methods]
    );
    assert!(text.contains("lo = 0.1"), "{text}");
    std::fs::write(&study, text).unwrap();
    let dir = base.join("out");
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", text_of(&o));
    // 9 grid points; the 4 corners and the centre of the other design are among them; and 5
    // validation runs (the fewest).
    assert_eq!(counts(&o), (14, 0), "{}", text_of(&o));
    let o = run(&study, &dir, &[]);
    assert_eq!(counts(&o), (0, 14), "{}", text_of(&o));
}

/// Issue 42, item 4: a quantity added is not refused - the runs that lack its value are
/// computed again; removing or renaming a quantity then keeps every run.
#[test]
fn a_quantity_added_recomputes_the_runs_that_lack_it() {
    let base = tmp("quantity");
    let study = small_study(&base, "");
    let original = std::fs::read_to_string(&study).unwrap();
    let dir = base.join("out");
    let o = run(&study, &dir, &[]);
    assert_eq!(counts(&o), (80, 0), "{}", text_of(&o));
    let added = format!(
        "{original}\n[[quantity]]\nname = \"tip_y\"\nkind = \"displacement\"\nsubstructure = \"plate\"\npoint = [100.0, 20.0]\ncomponent = 1\n"
    );
    std::fs::write(&study, &added).unwrap();
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", text_of(&o));
    assert_eq!(counts(&o), (80, 0), "{}", text_of(&o));
    // Back to the one quantity, renamed: every run has its value.
    std::fs::write(
        &study,
        original.replace("name = \"tip\"", "name = \"u_tip\""),
    )
    .unwrap();
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", text_of(&o));
    assert_eq!(counts(&o), (0, 80), "{}", text_of(&o));
}
