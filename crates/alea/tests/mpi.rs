//! `mpirun -np N alea run` (feature `mpi`; needs `mpirun` on the PATH) on a coarse version of
//! the simple blade root with a fixed grid, a chaos on the same runs and an adaptive method (its
//! steps go through the same executor, with per-run error-estimate data coming back):
//! - 2 and 3 ranks give a `summary.json` byte-identical to one process's;
//! - a job killed part-way resumes with another rank count, recomputes no committed run and ends
//!   with the same summary;
//! - a run that fails on a rank is reported with the rank and the run; the job resumes once the
//!   cause is gone.
#![cfg(feature = "mpi")]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

mod common;

fn alea() -> &'static str {
    env!("CARGO_BIN_EXE_alea")
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    common::fresh_dir("alea-mpi", name)
}

/// The comparison study on a coarse mesh, 20 000 draws, plus an adaptive method (about 60
/// runs); `extra` is appended to the file.
fn study(dir: &Path, extra: &str) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/blade-root-simple-comparison.toml"))
        .unwrap()
        .replace(
            "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27 }",
            "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9 }",
        )
        .replace(
            "[[method]]\ntype = \"pc_regression\"",
            "[statistics]\nsamples = 20000\n\n[[method]]\ntype = \"pc_regression\"",
        );
    assert!(text.contains("n_flank = 12,") && text.contains("samples = 20000"));
    let text = format!(
        "{text}\n[[method]]\ntype = \"adaptive\"\nmax_runs = 14\nlabel = \"adaptive\"\n{extra}"
    );
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn single(study: &Path, dir: &Path) -> Output {
    Command::new(alea())
        .arg("run")
        .arg(study)
        .arg("--dir")
        .arg(dir)
        .arg("-q")
        .output()
        .unwrap()
}

fn mpirun(np: usize) -> Command {
    let mut c = Command::new("mpirun");
    c.args(["--allow-run-as-root", "--oversubscribe", "-np"])
        .arg(np.to_string())
        .arg(alea());
    c
}

fn distributed(np: usize, study: &Path, dir: &Path) -> Output {
    mpirun(np)
        .arg("run")
        .arg(study)
        .arg("--dir")
        .arg(dir)
        .arg("-q")
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// `(computed, resumed)` from "runs: C computed, R resumed".
fn counts(o: &Output) -> (usize, usize) {
    let t = String::from_utf8_lossy(&o.stdout).into_owned();
    let nums: Vec<usize> = t
        .split("runs: ")
        .nth(1)
        .unwrap_or_else(|| panic!("no run counts in {t}"))
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .take(2)
        .map(|s| s.parse().unwrap())
        .collect();
    (nums[0], nums[1])
}

fn assert_same(a: &[u8], b: &[u8], what: &str) {
    if a != b {
        let (a, b) = (String::from_utf8_lossy(a), String::from_utf8_lossy(b));
        let line = a
            .lines()
            .zip(b.lines())
            .position(|(x, y)| x != y)
            .map_or(0, |i| i + 1);
        panic!("{what}: summaries differ (first at line {line})");
    }
}

#[test]
fn two_and_three_ranks_give_the_single_process_summary() {
    let base = tmp("ranks");
    let study = study(&base, "");
    let o = single(&study, &base.join("one"));
    assert!(o.status.success(), "{}", text(&o));
    let reference = std::fs::read(base.join("one/summary.json")).unwrap();
    for np in [2, 3] {
        let dir = base.join(format!("np{np}"));
        let o = distributed(np, &study, &dir);
        let t = text(&o);
        assert!(o.status.success(), "{t}");
        assert!(t.contains(&format!("MPI: {np} ranks")), "{t}");
        // Every rank solved runs.
        let per_rank: Vec<usize> = t
            .split("runs per rank [")
            .nth(1)
            .and_then(|s| s.split(']').next())
            .unwrap()
            .split(", ")
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(per_rank.len(), np);
        assert!(per_rank.iter().all(|&n| n > 0), "{t}");
        assert!(dir.join("mpi-dispatch.log").exists());
        assert_same(
            &reference,
            &std::fs::read(dir.join("summary.json")).unwrap(),
            &format!("{np} ranks"),
        );
    }
    let _ = std::fs::remove_dir_all(&base);
}

/// `[solver] ranks_per_run` (issue 38): one run spread over a group of ranks, each owning some
/// of the model's 3 substructures, and groups solving runs at once - 2 ranks in one group, 4
/// ranks in 2 groups of 2 and in one group of 4 - give the single process's `summary.json`
/// (the setting changes no bit of a run, module `alea_latin::ranks`, nor the run hash).
#[test]
fn ranks_per_run_gives_the_single_process_summary() {
    let base = tmp("per-run");
    let plain = study(&base, "");
    let text_of = |per_run: usize| {
        std::fs::read_to_string(&plain).unwrap().replace(
            "[solver]\n",
            &format!("[solver]\nranks_per_run = {per_run}\n"),
        )
    };
    // Per setting, its study file and the single process's summary of it (which ignores it).
    let mut reference = std::collections::HashMap::new();
    for (np, per_run) in [(2, 2), (4, 2), (4, 4)] {
        let path = base.join(format!("r{per_run}/study.toml"));
        if let std::collections::hash_map::Entry::Vacant(e) = reference.entry(per_run) {
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, text_of(per_run)).unwrap();
            assert!(
                std::fs::read_to_string(&path)
                    .unwrap()
                    .contains("ranks_per_run")
            );
            let one = base.join(format!("one-r{per_run}"));
            let o = single(&path, &one);
            assert!(o.status.success(), "{}", text(&o));
            e.insert(std::fs::read(one.join("summary.json")).unwrap());
        }
        let dir = base.join(format!("np{np}-r{per_run}"));
        let o = distributed(np, &path, &dir);
        let t = text(&o);
        assert!(o.status.success(), "{np} ranks, {per_run} per run: {t}");
        // Only the first rank of each group reports runs.
        let per_rank: Vec<usize> = t
            .split("runs per rank [")
            .nth(1)
            .and_then(|s| s.split(']').next())
            .unwrap()
            .split(", ")
            .map(|v| v.parse().unwrap())
            .collect();
        for (r, n) in per_rank.iter().enumerate() {
            assert_eq!(
                *n > 0,
                r % per_run == 0,
                "{np} ranks, {per_run} per run: {t}"
            );
        }
        assert_same(
            &reference[&per_run],
            &std::fs::read(dir.join("summary.json")).unwrap(),
            &format!("{np} ranks, {per_run} per run"),
        );
    }
    // A job whose ranks are not a multiple of the setting is refused.
    let path = base.join("study-3.toml");
    std::fs::write(&path, text_of(3)).unwrap();
    let o = distributed(2, &path, &base.join("bad"));
    assert!(!o.status.success());
    assert!(text(&o).contains("multiple"), "{}", text(&o));
    let _ = std::fs::remove_dir_all(&base);
}

/// Processes whose parent is `pid`.
fn children(pid: u32) -> Vec<u32> {
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(p) = e.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let Ok(stat) = std::fs::read_to_string(format!("/proc/{p}/stat")) else {
            continue;
        };
        // pid (comm) state ppid ...
        let after = stat.rsplit(')').next().unwrap_or("");
        let ppid = after.split_whitespace().nth(1).and_then(|v| v.parse().ok());
        if ppid == Some(pid) {
            out.push(p);
        }
    }
    out
}

#[test]
fn killed_job_resumes_with_another_rank_count() {
    let base = tmp("killed");
    let study = study(&base, "");
    let o = single(&study, &base.join("one"));
    assert!(o.status.success(), "{}", text(&o));
    let reference = std::fs::read(base.join("one/summary.json")).unwrap();
    let (total, _) = counts(&o);
    let dir = base.join("killed");
    let mut child = mpirun(2)
        .arg("run")
        .arg(&study)
        .arg("--dir")
        .arg(&dir)
        .arg("-q")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    loop {
        if common::stored_runs(&dir, "fields") >= 10 {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(120), "no progress");
        if let Ok(Some(_)) = child.try_wait() {
            panic!("the job finished before it could be killed");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    // As a scheduler does at a time limit: every process of the job at once.
    for p in children(child.id()) {
        let _ = Command::new("kill")
            .args(["-KILL", &p.to_string()])
            .status();
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!dir.join("summary.json").exists(), "killed before the end");
    let o = distributed(3, &study, &dir);
    assert!(o.status.success(), "{}", text(&o));
    let (computed, resumed) = counts(&o);
    assert!(resumed >= 9, "committed runs must be kept: {}", text(&o));
    assert_eq!(computed + resumed, total, "{}", text(&o));
    assert_same(
        &reference,
        &std::fs::read(dir.join("summary.json")).unwrap(),
        "resumed on 3 ranks",
    );
    // Nothing left to compute, on one process.
    let o = single(&study, &dir);
    assert!(text(&o).contains(&format!("runs: 0 computed, {total} resumed")));
    let _ = std::fs::remove_dir_all(&base);
}

#[test]
fn a_failing_rank_is_named_with_its_run_and_the_job_resumes() {
    let base = tmp("failing");
    // Per-run ParaView files: the rank that solves a run writes them.
    let study = study(&base, "\n[output]\nvtu = true\n");
    let o = single(&study, &base.join("one"));
    assert!(o.status.success(), "{}", text(&o));
    let reference = std::fs::read(base.join("one/summary.json")).unwrap();
    // The first run of the schedule is the design point nearest the nominal one (ties to the
    // first); it is the only job of the first batch, which goes to rank 1 (other ranks first).
    let summary: serde_json::Value = serde_json::from_slice(&reference).unwrap();
    let params = summary["parameters"].as_array().unwrap();
    let names: Vec<String> = params
        .iter()
        .map(|p| p["name"].as_str().unwrap().to_string())
        .collect();
    let scaled = |j: usize, v: f64| {
        let (lo, hi) = (
            params[j]["lo"].as_f64().unwrap(),
            params[j]["hi"].as_f64().unwrap(),
        );
        (v - lo) / (hi - lo)
    };
    let nominal: Vec<f64> = (0..params.len())
        .map(|j| scaled(j, params[j]["nominal"].as_f64().unwrap()))
        .collect();
    let first: Vec<f64> = summary["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r["params"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect::<Vec<f64>>()
        })
        .fold((f64::INFINITY, Vec::new()), |best, p| {
            let d: f64 = p
                .iter()
                .enumerate()
                .map(|(j, v)| (scaled(j, *v) - nominal[j]).powi(2))
                .sum();
            if d < best.0 { (d, p) } else { best }
        })
        .1;
    // Its ParaView file cannot be written: a directory stands where the file goes.
    let dir = base.join("failing");
    let blocker = dir
        .join("vtu")
        .join(format!("{}.vtm", alea_study::store::run_file_stem(&first)));
    std::fs::create_dir_all(&blocker).unwrap();
    let o = distributed(2, &study, &dir);
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    let at = names
        .iter()
        .zip(&first)
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ");
    assert!(
        t.contains(&format!("rank 1 failed on the run at {at}")),
        "the report names the rank and the run: {t}"
    );
    assert!(t.contains("to resume"), "{t}");
    assert!(!dir.join("summary.json").exists());
    // The cause gone, the job resumes to the single-process summary.
    std::fs::remove_dir_all(&blocker).unwrap();
    let o = distributed(2, &study, &dir);
    assert!(o.status.success(), "{}", text(&o));
    assert_same(
        &reference,
        &std::fs::read(dir.join("summary.json")).unwrap(),
        "resumed after a failure",
    );
    let _ = std::fs::remove_dir_all(&base);
}
