//! `alea run` end to end on a coarse version of the thesis's simple blade root:
//! - a study killed with SIGKILL part-way resumes, recomputes no committed run, and ends with a
//!   `summary.json` identical to an uninterrupted run's;
//! - the same study with 1 and 2 threads gives byte-identical `summary.json`;
//! - malformed study files give specific messages naming file, line and field, exit code 2,
//!   never a panic.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

mod common;
use common::stored_runs;

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("alea-study-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The shipped comparison study on a coarse mesh and a 7 x 7 reference grid (about 60 runs).
fn coarse_study(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/blade-root-simple-comparison.toml"))
        .unwrap()
        .replace(
            "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27 }",
            "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9 }",
        )
        .replace("points_per_dim = 11", "points_per_dim = 7")
        .replace(
            "[[method]]\ntype = \"pc_regression\"",
            "[statistics]\nsamples = 20000\n\n[[method]]\ntype = \"pc_regression\"",
        );
    assert!(
        text.contains("n_flank = 12")
            && text.contains("points_per_dim = 7")
            && text.contains("samples = 20000")
    );
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn run(study: &Path, dir: &Path, extra: &[&str]) -> std::process::Output {
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
fn killed_study_resumes_to_the_same_summary() {
    let base = tmp("resume");
    let study = coarse_study(&base);
    // Uninterrupted reference.
    let full = base.join("full");
    let o = run(&study, &full, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let reference = std::fs::read(full.join("summary.json")).unwrap();
    let out = String::from_utf8_lossy(&o.stdout).into_owned();
    let total: usize = out
        .split(" distinct runs")
        .next()
        .and_then(|s| s.rsplit(' ').next())
        .and_then(|s| s.parse().ok())
        .expect("distinct run count printed");
    assert!(total > 50, "{out}");
    // Start, wait for a few committed runs, SIGKILL.
    let dir = base.join("killed");
    let mut child = alea()
        .arg("run")
        .arg(&study)
        .arg("--dir")
        .arg(&dir)
        .arg("-q")
        .arg("--threads")
        .arg("1")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    loop {
        // Runs committed with their fields.
        if stored_runs(&dir, "fields") >= 10 {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(120), "no progress");
        if let Ok(Some(_)) = child.try_wait() {
            panic!("the study finished before it could be killed");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.kill().unwrap(); // SIGKILL on Unix
    child.wait().unwrap();
    assert!(!dir.join("summary.json").exists(), "killed before the end");
    let o = run(&study, &dir, &[]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // "runs: C computed, R resumed"
    let nums: Vec<usize> = text
        .split("runs: ")
        .nth(1)
        .unwrap()
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .take(2)
        .map(|s| s.parse().unwrap())
        .collect();
    let (computed, resumed) = (nums[0], nums[1]);
    assert_eq!(computed + resumed, total, "{text}");
    assert!(resumed >= 9, "committed runs must be kept: {text}");
    let resumed_summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let reference = String::from_utf8(reference).unwrap();
    if let Some((i, (a, b))) = reference
        .lines()
        .zip(resumed_summary.lines())
        .enumerate()
        .find(|(_, (a, b))| a != b)
    {
        panic!("resumed summary differs at line {}: {a:?} vs {b:?}", i + 1);
    }
    assert_eq!(resumed_summary.len(), reference.len());
    // A third invocation computes nothing.
    let o = run(&study, &dir, &[]);
    assert!(
        String::from_utf8_lossy(&o.stdout).contains(&format!("runs: 0 computed, {total} resumed"))
    );
    // A changed model is refused unless --restart (a changed seed, which defines no run, is
    // not: issue 42, item 4, crates/alea/tests/study_dir.rs).
    let changed = base.join("study.toml");
    let t =
        std::fs::read_to_string(&changed)
            .unwrap()
            .replacen("young = 210e3", "young = 211e3", 1);
    std::fs::write(&changed, t).unwrap();
    let o = run(&changed, &dir, &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--restart"));
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn one_and_two_threads_give_identical_summaries() {
    let base = tmp("threads");
    let study = coarse_study(&base);
    let mut outs = Vec::new();
    for t in ["1", "2"] {
        let dir = base.join(format!("t{t}"));
        let o = run(&study, &dir, &["--threads", t]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        outs.push(std::fs::read(dir.join("summary.json")).unwrap());
        assert!(dir.join("report/report.html").exists());
        assert!(dir.join("samples.csv").exists());
        // The report can be rebuilt from the saved data alone.
        std::fs::remove_file(dir.join("report/report.html")).unwrap();
        let o = alea().arg("report").arg(&dir).output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(dir.join("report/report.html").exists());
    }
    assert!(
        outs[0] == outs[1],
        "summaries differ between 1 and 2 threads"
    );
    let text = String::from_utf8_lossy(&outs[0]);
    assert!(!text.contains("NaN") && !text.contains("inf"));
    let _ = std::fs::remove_dir_all(&base);
}

/// Issue 42, outputs sized to use: `samples.csv` holds the first `[output] samples_rows` draws
/// (default 10 000; the 50-run example's 250 000 draws made it 19 MB, and the report's input,
/// no longer written, 21 MB more), `"all"` every draw; the setting is not part of the runs (an
/// edit resumes), and a bad value is refused at its line.
#[test]
fn samples_csv_holds_the_draws_asked_for() {
    let base = tmp("samples-rows");
    let study = coarse_study(&base);
    let text = std::fs::read_to_string(&study).unwrap();
    let dir = base.join("d");
    let lines = || {
        std::fs::read_to_string(dir.join("samples.csv"))
            .unwrap()
            .lines()
            .count()
    };
    let with = |tail: &str| {
        std::fs::write(
            &study,
            format!("{text}\n[output]\nmean_fields = false\n{tail}"),
        )
        .unwrap();
        run(&study, &dir, &[])
    };
    // Default: the first 10 000 of the 20 000 draws, and no report input beside the report.
    let o = with("");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(lines(), 1 + 10_000);
    assert!(dir.join("report/report.html").exists());
    assert!(!dir.join("report/report-input.json").exists());
    let summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    assert!(
        summary.contains("\"draws\": 20000"),
        "the statistics use every draw"
    );
    let o = with("samples_rows = 500\n");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(lines(), 1 + 500);
    let o = with("samples_rows = \"all\"\n");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(lines(), 1 + 20_000);
    // `alea report` rebuilds it as the study file says (`-q` as `alea run` takes it: no
    // spinner, the same account).
    std::fs::remove_file(dir.join("samples.csv")).unwrap();
    let o = alea().arg("report").arg(&dir).arg("-q").output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(lines(), 1 + 20_000);
    // Refused at load, at the key's line.
    let key_line = text.lines().count() + 4;
    for (tail, phrase) in [
        ("samples_rows = \"some\"\n", "unknown value 'some'"),
        ("samples_rows = 0\n", "at least 1"),
        ("samples_csv = false\nsamples_rows = 10\n", "ignored"),
    ] {
        let o = with(tail);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{tail}: {err}");
        let line = key_line + usize::from(tail.starts_with("samples_csv"));
        assert!(
            err.contains(&format!("study.toml:{line}:")) && err.contains("output.samples_rows"),
            "{tail}: {err}"
        );
        assert!(err.contains(phrase), "{tail}: {err}");
    }
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn malformed_study_files_give_specific_errors() {
    let base = tmp("bad");
    let good = std::fs::read_to_string(root().join("examples/blade-root-simple.toml")).unwrap();
    // (original text, replacement, field named in the message, phrase of the message)
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            "seed = 2008",
            "seed = 2008\ncolour = 1",
            "colour",
            "unknown field",
        ),
        ("mean = 0.5", "mean = \"half\"", "mean", "invalid type"),
        (
            "mean = 0.5\nstd = 0.2\n",
            "mean = 0.5\n",
            "parameter[1].std",
            "needs 'std'",
        ),
        (
            "side1 = [\"S1\", \"G1_disk\"]",
            "side1 = [\"S1\", \"G1_disc\"]",
            "interface[0].side1",
            "no facet group 'G1_disc'",
        ),
        (
            "mu = \"mu\"\ngap",
            "mu = -0.2\ngap",
            "interface[0].mu",
            ">= 0",
        ),
        (
            "mu = \"mu\"\ngap",
            "mu = \"mu - 0.5\"\ngap",
            "interface[0].mu",
            ">= 0",
        ),
        (
            "young = 210e3\npoisson = 0.3\n# symmetry",
            "young = 0.0\npoisson = 0.3\n# symmetry",
            "substructure[0].young",
            "> 0",
        ),
        (
            "young = \"E2\"\npoisson = 0.3",
            "young = \"E2\"\npoisson = 0.5",
            "substructure[1].poisson",
            "(-1, 0.5)",
        ),
        (
            "young = 210e3\npoisson = 0.3\n# symmetry",
            "young = nan\npoisson = 0.3\n# symmetry",
            "substructure[0].young",
            "finite",
        ),
        (
            "young = \"E2\"",
            "young = \"E3\"",
            "substructure[1].young",
            "unknown name 'E3'",
        ),
        (
            "law = \"truncated_normal\"\nmean = 0.5\nstd = 0.2",
            "law = \"truncated_normal\"\nmean = 0.5\nstd = -0.2",
            "parameter[1]",
            "std",
        ),
        (
            "interface = \"G2\"",
            "interface = \"G3\"",
            "quantity[0].interface",
            "unknown interface 'G3'",
        ),
        (
            "type = \"pc_regression\"",
            "type = \"kriging\"",
            "method[0].type",
            "unknown method 'kriging'",
        ),
        (
            "status = \"stick\"",
            "status = \"sticky\"",
            "quantity[1].status",
            "unknown status 'sticky'",
        ),
        (
            "status = \"stick\"",
            "status = \"stick\"\nexclude_groups = [\"S2_left\"]",
            "quantity[1].exclude_groups",
            "not used by a 'contact_status' quantity",
        ),
        ("radius = 1.0", "radius = -1.0", "quantity[2].radius", "> 0"),
        (
            "radius = 1.0",
            "radius = 0.001",
            "quantity[2].radius",
            "no quadrature point",
        ),
        (
            "point = [8.0, 10.0]\nradius = 1.0",
            "point = [8.0, 10.0]",
            "quantity[2].radius",
            "missing",
        ),
    ];
    for (i, (from, to, field, phrase)) in cases.iter().enumerate() {
        assert!(
            good.contains(from),
            "case {i}: fixture must contain {from:?}"
        );
        let text = good.replacen(from, to, 1);
        let path = base.join(format!("bad{i}.toml"));
        std::fs::write(&path, &text).unwrap();
        let o = run(&path, &base.join(format!("d{i}")), &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "case {i}: {err}");
        assert!(!err.contains("panicked"), "case {i}: {err}");
        assert!(
            err.contains(&format!("bad{i}.toml:")),
            "case {i}: file not named: {err}"
        );
        assert!(
            err.contains(field),
            "case {i}: field {field} not named: {err}"
        );
        assert!(err.contains(phrase), "case {i}: '{phrase}' not in: {err}");
        let line: usize = err
            .split(&format!("bad{i}.toml:"))
            .nth(1)
            .unwrap()
            .split(':')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(line > 0, "case {i}: no line: {err}");
    }
    let _ = std::fs::remove_dir_all(&base);
}

/// The simple blade root on a coarse mesh with an adaptive method (improved criterion, 9 to at
/// most 18 runs) and the stochastic error estimate.
fn adaptive_study(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/blade-root-simple.toml")).unwrap();
    let text = text.replace(
        "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27 }",
        "n_flank = 9, n_side = 11, n_root = 9, n_shank = 7 }",
    );
    let start = text.find("[[method]]").expect("methods");
    let end = text.find("[solver]").expect("solver");
    let text = format!(
        "{}[[method]]\ntype = \"adaptive\"\ncriterion = \"improved\"\nmax_runs = 18\n\n[error]\n\n[statistics]\nsamples = 20000\n\n{}",
        &text[..start],
        &text[end..]
    );
    assert!(text.contains("n_flank = 9") && text.contains("type = \"adaptive\""));
    let path = dir.join("adaptive.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// An adaptive study is deterministic (1 or 2 threads), resumes after a SIGKILL in the middle
/// of its loop to the same summary without recomputing committed runs, and its outputs can be
/// rebuilt from the store alone (`alea report` replays the loop).
#[test]
fn adaptive_study_is_deterministic_and_resumable() {
    let base = tmp("adaptive");
    let study = adaptive_study(&base);
    let mut outs = Vec::new();
    for t in ["1", "2"] {
        let dir = base.join(format!("t{t}"));
        let o = run(&study, &dir, &["--threads", t]);
        assert!(
            o.status.success(),
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        outs.push(std::fs::read_to_string(dir.join("summary.json")).unwrap());
    }
    assert!(
        outs[0] == outs[1],
        "summaries differ between 1 and 2 threads"
    );
    let summary: serde_json::Value = serde_json::from_str(&outs[0]).unwrap();
    let steps = summary["methods"][0]["adaptive"]["steps"]
        .as_array()
        .expect("adaptive steps in summary.json");
    assert!(steps.len() >= 2, "{steps:?}");
    let runs: Vec<u64> = steps.iter().map(|s| s["runs"].as_u64().unwrap()).collect();
    assert_eq!(runs[0], 5, "corners and centre");
    assert!(runs.windows(2).all(|w| w[1] > w[0]), "{runs:?}");
    assert!(*runs.last().unwrap() <= 18);
    // Reference done; now kill a run part-way through the adaptive loop.
    let dir = base.join("killed");
    let mut child = alea()
        .arg("run")
        .arg(&study)
        .arg("--dir")
        .arg(&dir)
        .arg("-q")
        .arg("--threads")
        .arg("1")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    loop {
        // Runs committed with their error estimates.
        if stored_runs(&dir, "cre") >= 7 {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(120), "no progress");
        if let Ok(Some(_)) = child.try_wait() {
            panic!("the study finished before it could be killed");
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let o = run(&study, &dir, &[]);
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let resumed = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    if let Some((i, (a, b))) = outs[0]
        .lines()
        .zip(resumed.lines())
        .enumerate()
        .find(|(_, (a, b))| a != b)
    {
        panic!("resumed summary differs at line {}: {a:?} vs {b:?}", i + 1);
    }
    assert_eq!(resumed.len(), outs[0].len());
    assert!(text.contains(" resumed"), "{text}");
    // Nothing left to compute; the outputs rebuild from the store.
    let o = run(&study, &dir, &[]);
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("runs: 0 computed"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    let o = alea().arg("report").arg(&dir).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read_to_string(dir.join("summary.json")).unwrap(),
        outs[0],
        "rebuilt summary"
    );
    let _ = std::fs::remove_dir_all(&base);
}

/// The shipped mortar example (two parts meshed separately in Gmsh) runs end to end with every
/// output: per-run ParaView files, mean / std fields, samples, summary and report.
#[test]
fn mortar_example_runs_with_every_output() {
    let dir = tmp("mortar");
    let text = std::fs::read_to_string(root().join("examples/punch-on-base.toml")).unwrap()
        + "\n[output]\nvtu = true\n\n[statistics]\nsamples = 20000\n";
    // The mesh path is relative to the study file: copy the mesh beside the copy.
    let input = tmp("mortar-input");
    std::fs::create_dir_all(input.join("meshes")).unwrap();
    std::fs::copy(
        root().join("examples/meshes/punch-on-base.msh"),
        input.join("meshes/punch-on-base.msh"),
    )
    .unwrap();
    let study = input.join("study.toml");
    std::fs::write(&study, text).unwrap();
    let o = run(&study, &dir, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let vtm = std::fs::read_dir(dir.join("vtu"))
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "vtm")
        })
        .count();
    // One per run: the 16 design runs and 5 validation runs.
    assert_eq!(vtm, 21);
    for f in [
        "summary.json",
        "samples.csv",
        "paraview/mean_std.vtm",
        "report/report.html",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
}
