//! The paired solves of the mesh part (`[budget] refined_mesh`) belong to the run (issue 36):
//! `run_study` solves and stores them, the analysis of a reopened directory (what `alea report
//! DIR` and Python's `alea.report` do) reads them and solves nothing, a run killed before they
//! were all stored solves only the missing ones, and a store without them (a study finished by
//! an older alea) reports the part "not estimated". Kirsch's plate on a 6 x 6 Quad4 mesh, the
//! refined one 12 x 12, one parameter (3 paired points per model): a few seconds.

use std::path::{Path, PathBuf};

use alea_study::Source;
use alea_study::analysis::AnalysisSettings;
use alea_study::budget::{QoiBudget, Statistic};
use alea_study::runner::{NoProgress, Study, StudyRuns, run_study};

const STUDY: &str = r#"
[study]
title = "Kirsch plate, stored paired solves"
seed = 5

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "plate_with_hole"
kind = "quad4"
params = { radius = 10.0, half_width = 100.0, n_arc = 6, n_radial = 6, grading = 6.0 }

[analysis]
type = "plane_stress"

[[parameter]]
name = "P"
law = "normal"
mean = 1.0
std = 0.1

[[substructure]]
name = "plate"
young = 210e3
poisson = 0.3
constraint = [ { group = "xsym", x = 0.0 }, { group = "ysym", y = 0.0 } ]
load = [ { group = "right", traction = [100.0, 0.0], factor = "P" } ]

[[quantity]]
name = "vm_hole"
kind = "max_von_mises"
substructure = "plate"
group = "hole"
thresholds = [330.0]

[[method]]
type = "pc_regression"
degree = 2
design = "lhs"
runs = 6

[statistics]
samples = 2000

[budget]
refined_mesh = { params = { n_arc = 12, n_radial = 12 } }
validation_runs = 0
"#;

fn study() -> Study {
    Study::from_source(Source::from_text("kirsch-paired.toml", STUDY)).unwrap()
}

fn settings() -> AnalysisSettings {
    AnalysisSettings {
        samples: 2000,
        bandwidth: alea_uq::kde::Bandwidth::Silverman,
        kde_points: 32,
        confidence: 0.95,
    }
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("alea-paired-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// The budget of the study's quantity from `runs`.
fn budget(s: &Study, runs: &StudyRuns) -> QoiBudget {
    let results = alea_pipeline::analyse_all(s, runs, &settings());
    results[0].qois[0].budget.clone().unwrap()
}

/// The budget of the study directory `d` reopened from its store (as `alea report DIR`).
fn reported(d: &Path) -> QoiBudget {
    let re = alea_study::reopen::reopen(d, "test").unwrap();
    budget(&re.study, &re.runs)
}

/// Every number of a budget's rows, as bits (the parts `None` as a marker).
fn bits(b: &QoiBudget) -> Vec<u64> {
    b.rows
        .iter()
        .flat_map(|r| [r.value, r.mesh.unwrap_or(-1.0), r.total])
        .map(f64::to_bits)
        .collect()
}

/// Runs SQL on the store of `d`.
fn sql(d: &Path, statement: &str) -> usize {
    let conn = rusqlite::Connection::open(d.join("study.db")).unwrap();
    conn.execute(statement, []).unwrap()
}

#[test]
fn a_report_reads_the_stored_paired_solves_and_solves_none() {
    let d = dir("report");
    let s = study();
    let runs = run_study(&s, &d, false, &NoProgress).unwrap();
    let n = alea_study::paired_runs::count(&s);
    assert_eq!(n, 6, "3 points on each of the two models");
    assert_eq!((runs.paired.computed, runs.paired.resumed), (n, 0));
    let ran = budget(&s, &runs);
    assert!(
        ran.mesh_basis.starts_with("paired solves"),
        "{}",
        ran.mesh_basis
    );
    assert!(ran.rows.iter().all(|r| r.mesh.is_some_and(|m| m > 0.0)));
    drop(runs);
    // Reopened (what `alea report` analyses): the same budget, bit for bit.
    assert_eq!(bits(&reported(&d)), bits(&ran));
    // The stored values of the refined model are what the report uses: doubled in the store,
    // the mean's mesh part D = 2 max |q_h - q_h/2| moves accordingly - a solve would have
    // given the old part.
    let refined = s.refined.as_ref().unwrap().identity.run_hash.clone();
    let rows = s.identity.run_hash.clone();
    let store = alea_study::store::Store::open(&d, &s.hash, false).unwrap();
    let coarse = store.paired_runs(&rows).unwrap();
    let fine = store.paired_runs(&refined).unwrap();
    drop(store);
    let expected = 2.0
        * fine
            .iter()
            .map(|(k, f)| (coarse[k].qois[0] - 2.0 * f.qois[0]).abs())
            .fold(0.0f64, f64::max);
    let conn = rusqlite::Connection::open(d.join("study.db")).unwrap();
    for (k, f) in &fine {
        let doubled: Vec<u8> = f
            .qois
            .iter()
            .flat_map(|v| (2.0 * v).to_le_bytes())
            .collect();
        conn.execute(
            "UPDATE paired_runs SET qois = ?1 WHERE model = ?2 AND key = ?3",
            rusqlite::params![doubled, refined, k],
        )
        .unwrap();
    }
    drop(conn);
    let tampered = reported(&d);
    let mean = tampered
        .rows
        .iter()
        .find(|r| r.statistic == Statistic::Mean)
        .unwrap();
    assert_eq!(mean.mesh, Some(expected));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_killed_run_solves_only_the_missing_paired_points() {
    let d = dir("resume");
    let s = study();
    let runs = run_study(&s, &d, false, &NoProgress).unwrap();
    let first = budget(&s, &runs);
    drop(runs);
    // Killed before three of its paired solves were committed (one of the study's model, two
    // of the refined one).
    let refined = s.refined.as_ref().unwrap().identity.run_hash.clone();
    let own = s.identity.run_hash.clone();
    let removed = sql(
        &d,
        &format!(
            "DELETE FROM paired_runs WHERE rowid IN (SELECT rowid FROM paired_runs WHERE model = '{own}' LIMIT 1) \
             OR rowid IN (SELECT rowid FROM paired_runs WHERE model = '{refined}' LIMIT 2)"
        ),
    );
    assert_eq!(removed, 3);
    // Until then the report does not estimate the part, and solves nothing.
    let partial = reported(&d);
    assert_eq!(
        partial.mesh_basis,
        "not estimated: run `alea run` again to solve the paired points"
    );
    let again = run_study(&s, &d, false, &NoProgress).unwrap();
    assert_eq!(again.computed, 0);
    assert_eq!((again.paired.computed, again.paired.resumed), (3, 3));
    assert_eq!(bits(&budget(&s, &again)), bits(&first));
    drop(again);
    // A third run solves none.
    let third = run_study(&s, &d, false, &NoProgress).unwrap();
    assert_eq!((third.paired.computed, third.paired.resumed), (0, 6));
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_store_without_paired_solves_reports_the_part_not_estimated() {
    let d = dir("older");
    let s = study();
    drop(run_study(&s, &d, false, &NoProgress).unwrap());
    // What an older alea left: no paired solve stored.
    sql(&d, "DELETE FROM paired_runs");
    sql(&d, "DELETE FROM paired_models");
    let b = reported(&d);
    assert_eq!(
        b.mesh_basis,
        "not estimated: run `alea run` again to solve the paired points"
    );
    for r in &b.rows {
        assert_eq!(r.mesh, None, "{}: not counted, not 0", r.statistic);
        assert_eq!(r.total, r.sum_of_parts());
    }
    // `alea report DIR` says so in its notes, and solves nothing: still none stored.
    let out = alea_pipeline::rebuild(&d, "test", &alea_pipeline::Silent).unwrap();
    assert!(
        out.notes.iter().any(
            |n| n.starts_with("the error budget's mesh part is not estimated") && !n.contains("  ")
        ),
        "{:?}",
        out.notes
    );
    let store = alea_study::store::Store::open(&d, &s.hash, false).unwrap();
    assert!(store.paired_runs(&s.identity.run_hash).unwrap().is_empty());
    let _ = std::fs::remove_dir_all(&d);
}

/// Asks to stop once the first paired solve is done (the runs come first; `paired`: their
/// number, 0 never to stop), counting the runs.
struct StopAfterFirstPaired {
    paired: usize,
    total: std::sync::atomic::AtomicUsize,
    finished: std::sync::atomic::AtomicUsize,
}

impl alea_study::runner::Progress for StopAfterFirstPaired {
    fn begin(&self, total: usize, done: usize) {
        use std::sync::atomic::Ordering::SeqCst;
        self.total.store(total, SeqCst);
        self.finished.store(done, SeqCst);
    }
    fn finished(&self, _rec: &alea_study::store::RunRecord) {
        self.finished
            .fetch_add(1, std::sync::atomic::Ordering::SeqCst);
    }
    fn stop_requested(&self) -> bool {
        use std::sync::atomic::Ordering::SeqCst;
        self.paired > 0 && self.finished.load(SeqCst) > self.total.load(SeqCst) - self.paired
    }
}

#[test]
fn an_interrupted_run_resumes_its_paired_solves() {
    let d = dir("interrupted");
    let s = study();
    let n = alea_study::paired_runs::count(&s);
    let progress = StopAfterFirstPaired {
        paired: n,
        total: 0.into(),
        finished: 0.into(),
    };
    let stopped = run_study(&s, &d, false, &progress);
    assert!(
        matches!(stopped, Err(alea_study::StudyError::Interrupted)),
        "{:?}",
        stopped.err()
    );
    let store = alea_study::store::Store::open(&d, &s.hash, false).unwrap();
    let stored = alea_study::paired_runs::settled(&s, &store).unwrap();
    drop(store);
    assert!(stored >= 1 && stored < n, "{stored} of {n} stored");
    // Resumed: the progress counts the paired solves, the stored ones as done, and each
    // solved one as it finishes.
    let progress = StopAfterFirstPaired {
        paired: 0,
        total: 0.into(),
        finished: 0.into(),
    };
    let again = run_study(&s, &d, false, &progress).unwrap();
    assert_eq!(
        (again.paired.computed, again.paired.resumed),
        (n - stored, stored)
    );
    let total = progress.total.load(std::sync::atomic::Ordering::SeqCst);
    assert_eq!(total, again.records.len() + n);
    assert_eq!(
        progress.finished.load(std::sync::atomic::Ordering::SeqCst),
        total
    );
    assert!(again.paired.mesh.as_ref().is_some_and(|c| c.is_ok()));
    let _ = std::fs::remove_dir_all(&d);
}
