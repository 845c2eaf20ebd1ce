//! How a study's bookkeeping grows with its number of runs (`cargo bench -p alea-study --bench
//! scale`; `-- quick` stops at 10^4 runs):
//! - start-up: loading a Monte Carlo study of `n` runs and building its solver, then the
//!   generations of the schedule and the warm-start parents of every run (what happens before
//!   and between generations; their number is the study's critical path, their sizes its
//!   parallel width), for n = 10^3, 10^4, 10^5;
//! - the mean / std fields of a piecewise-linear study on a `k x k` grid of runs (K = k^2 =
//!   1 024, 10 000, 99 856) from synthetic run fields written to a study directory (the runs
//!   are not solved: the fields' cost does not depend on where the fields came from), against the
//!   previous dense all-pairs computation where it is affordable;
//! - the weight moments alone on 10^6 draws (the 225-run grid of the turbine study), new and
//!   previous.
//!
//! The model is the simple blade root on a coarse mesh (a few hundred nodes).

use std::path::Path;
use std::time::Instant;

use alea_study::fields::{WeightMoments, mean_std_fields};
use alea_study::runner::{RunSetup, Study, StudyRuns};
use alea_study::store::{RunRecord, Store};
use alea_study::{Source, StudyError};
use rayon::prelude::*;

mod support;
use support::synthetic_record;

fn root() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The blade-root study on a coarse mesh with `method` as its only method.
fn study_text(method: &str) -> String {
    let text = std::fs::read_to_string(root().join("examples/blade-root-simple-comparison.toml"))
        .expect("example")
        .replace(
            "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27 }",
            "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9 }",
        );
    assert!(
        text.contains("n_flank = 12,"),
        "the example's mesh line changed"
    );
    let head = &text[..text.find("[[method]]").expect("a method")];
    format!("{head}\n[statistics]\nsamples = 100000\n\n[[method]]\n{method}\n")
}

fn secs(t: Instant) -> f64 {
    t.elapsed().as_secs_f64()
}

fn startup(n: usize) {
    let t0 = Instant::now();
    let study = Study::from_source(Source::from_text(
        "mc.toml",
        &study_text(&format!("type = \"monte_carlo\"\nruns = {n}")),
    ))
    .expect("study");
    let load = secs(t0);
    let t1 = Instant::now();
    let _setup = RunSetup::build(&study).expect("solver");
    let build = secs(t1);
    let t2 = Instant::now();
    let plan = alea_study::runner::warm_start_plan(&study, &study.all_points());
    let walk = secs(t2);
    let widths: Vec<usize> = plan.iter().map(Vec::len).collect();
    println!(
        "start-up n = {n:>6}: study file + design {load:.3} s, solver {build:.3} s, generations + warm-start parents {walk:.3} s ({} runs; critical path {} generations, widths {widths:?})",
        widths.iter().sum::<usize>(),
        widths.len()
    );
}

/// Synthetic fields of a run at `p` (smooth in the parameters, `width` values).
fn synthetic(p: &[f64], width: usize) -> Vec<f64> {
    let s = p[0] / 2.0e5 + 3.0 * p[1];
    (0..width)
        .map(|i| 1e-3 * ((i as f64 * 0.01).sin() + s * (1.0 + (i as f64 * 0.003).cos())))
        .collect()
}

/// The previous computation: dense `E[w_a w_b]` per chunk, then all pairs for every value.
fn dense_moments(
    weights: &alea_study::fields::Weigher<'_>,
    k: usize,
    d: usize,
    draws: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let parts: Vec<(Vec<f64>, Vec<f64>)> = draws
        .par_chunks(d * 4096)
        .map(|block| {
            let mut e1 = vec![0.0; k];
            let mut e2 = vec![0.0; k * k];
            let (mut t, mut w) = (vec![0.0; d], Vec::new());
            for x in block.chunks_exact(d) {
                weights(x, &mut t, &mut w);
                for &(a, wa) in &w {
                    e1[a] += wa;
                    for &(b, wb) in &w {
                        e2[a * k + b] += wa * wb;
                    }
                }
            }
            (e1, e2)
        })
        .collect();
    let n = (draws.len() / d) as f64;
    let mut ew = vec![0.0; k];
    let mut ew2 = vec![0.0; k * k];
    for (e1, e2) in &parts {
        for (a, b) in ew.iter_mut().zip(e1) {
            *a += b / n;
        }
        for (a, b) in ew2.iter_mut().zip(e2) {
            *a += b / n;
        }
    }
    (ew, ew2)
}

fn dense_fields(ew: &[f64], ew2: &[f64], data: &[f64], k: usize, width: usize) -> Vec<f64> {
    let mut std = vec![0.0; width];
    for j in 0..width {
        let v: Vec<f64> = (0..k).map(|a| data[a * width + j]).collect();
        let m1: f64 = (0..k).map(|a| ew[a] * v[a]).sum();
        let m2: f64 = (0..k)
            .map(|a| v[a] * (0..k).map(|b| ew2[a * k + b] * v[b]).sum::<f64>())
            .sum();
        std[j] = (m2 - m1 * m1).max(0.0).sqrt();
    }
    std
}

fn fields(k: usize, dir: &Path, draws_n: usize) -> Result<(), StudyError> {
    let _ = std::fs::remove_dir_all(dir);
    let study = Study::from_source(Source::from_text(
        "pl.toml",
        &study_text(&format!(
            "type = \"piecewise_linear\"\npoints_per_dim = {k}"
        )),
    ))?;
    let setup = RunSetup::build(&study)?;
    let solver = setup.solver.clone();
    let width: usize = (0..solver.num_subs())
        .map(|s| solver.model(s).mesh.num_nodes() * solver.model(s).mesh.dim)
        .sum();
    let points = study.methods[0].points.clone();
    let records: Vec<RunRecord> = points
        .iter()
        .map(|p| RunRecord::known(p.clone(), vec![0.0; study.qois.len()]))
        .collect();
    // The runs' fields, stored as `alea run` stores them (into the database), 1024 runs per
    // transaction.
    let store = Store::open(dir, &study.hash, false)?;
    let t0 = Instant::now();
    for chunk in records.chunks(1024) {
        let data: Vec<Vec<f64>> = chunk
            .par_iter()
            .map(|r| synthetic(&r.params, width))
            .collect();
        let group: Vec<alea_study::store::RunToCommit<'_>> = chunk
            .iter()
            .zip(&data)
            .map(|(r, f)| (r, f.as_slice(), None))
            .collect();
        store.commit_group(&group)?;
    }
    let write = secs(t0);
    // What the mean / std fields read of the store, one run at a time (its connection is not
    // shared between threads).
    let t0 = Instant::now();
    for p in &points {
        std::hint::black_box(store.fields(p)?);
    }
    let read = secs(t0);
    drop(store);
    let runs = StudyRuns {
        records,
        computed: 0,
        resumed: points.len(),
        setup_seconds: 0.0,
        solve_seconds: 0.0,
        estimate_seconds: 0.0,
        solver: solver.clone(),
        methods: study.methods.clone(),
        adaptive: vec![],
        cre: None,
        paired: Default::default(),
        lock: alea_study::lock::StudyLock::acquire(dir, "scale benchmark")?,
    };
    let draws = alea_uq::design::monte_carlo(study.params.joint.as_ref(), draws_n, 7);
    let draws = draws.points();
    let t1 = Instant::now();
    let f = mean_std_fields(&study, &runs, dir, 0, draws)?;
    let new = secs(t1);
    let rss = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM")).map(|l| {
                l.split_whitespace()
                    .nth(1)
                    .unwrap_or("0")
                    .parse::<f64>()
                    .unwrap_or(0.0)
                    / 1024.0
            })
        })
        .unwrap_or(0.0);
    print!(
        "fields K = {:>6} ({width} displacement values per run, {draws_n} draws): stored in {write:.2} s, read back one by one in {read:.3} s; mean/std {new:.3} s (peak RSS so far {rss:.0} MB)",
        points.len()
    );
    if points.len() <= 2100 {
        // Previous: all run data in memory, dense moments, all pairs.
        let sur = study.methods[0].surrogate(&study.params, &points)?;
        let d = study.params.names.len();
        let t2 = Instant::now();
        let (ew, ew2) = dense_moments(&|x, t, w| sur.weights(x, t, w), points.len(), d, draws);
        let data: Vec<f64> = points.iter().flat_map(|p| synthetic(p, width)).collect();
        let std = dense_fields(&ew, &ew2, &data, points.len(), width);
        let old = secs(t2);
        let dev = std
            .iter()
            .zip(&f[0].displacement_std)
            .map(|(a, b)| (a - b).abs() / a.abs().max(1e-300))
            .fold(0.0, f64::max);
        print!(
            "; previous (displacements only, files not read) {old:.3} s, largest relative difference of the std {dev:.1e}"
        );
    }
    println!();
    let _ = std::fs::remove_dir_all(dir);
    Ok(())
}

fn moments_1e6() -> Result<(), StudyError> {
    let study = Study::from_source(Source::from_text(
        "pl.toml",
        &study_text("type = \"piecewise_linear\"\npoints_per_dim = 15"),
    ))?;
    let points = study.methods[0].points.clone();
    let sur = study.methods[0].surrogate(&study.params, &points)?;
    let d = study.params.names.len();
    let draws = alea_uq::design::monte_carlo(study.params.joint.as_ref(), 1_000_000, 7);
    let draws = draws.points();
    let weigh = |x: &[f64], t: &mut [f64], w: &mut Vec<(usize, f64)>| sur.weights(x, t, w);
    let t0 = Instant::now();
    let m = WeightMoments::estimate(&weigh, points.len(), d, draws);
    let new = secs(t0);
    let t1 = Instant::now();
    let (ew, _) = dense_moments(&weigh, points.len(), d, draws);
    let old = secs(t1);
    let dev = ew
        .iter()
        .zip(&m.mean)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    println!(
        "weight moments, 225 runs, 10^6 draws: sparse {new:.3} s ({} non-zeros), previous dense {old:.3} s; largest difference of E[w] {dev:.1e}",
        m.nnz()
    );
    Ok(())
}

/// Rank 0's serial work per run: committing it (its row and its field data in one synced
/// transaction).
fn commit_cost(values: usize, dir: &Path) -> Result<(), StudyError> {
    let _ = std::fs::remove_dir_all(dir);
    let store = Store::open(dir, "bench", false)?;
    let fields: Vec<f64> = (0..values).map(|i| i as f64).collect();
    let n = 200;
    let t0 = Instant::now();
    for r in 0..n {
        let rec = synthetic_record(r, 40, 2, 400);
        store.commit(&rec, &fields, None)?;
    }
    println!(
        "commit of a run with {values} field values: {:.2} ms",
        1e3 * secs(t0) / n as f64
    );
    let _ = std::fs::remove_dir_all(dir);
    Ok(())
}

fn main() {
    let quick = std::env::args().any(|a| a == "quick");
    println!("threads: {}", rayon::current_num_threads());
    let cdir = std::env::temp_dir().join(format!("alea-bench-commit-{}", std::process::id()));
    for values in [3_000, 40_000] {
        commit_cost(values, &cdir).expect("commit");
    }
    let ns: &[usize] = if quick {
        &[1_000, 10_000]
    } else {
        &[1_000, 10_000, 100_000]
    };
    for &n in ns {
        startup(n);
    }
    moments_1e6().expect("moments");
    let dir = std::env::temp_dir().join(format!("alea-bench-fields-{}", std::process::id()));
    let ks: &[usize] = if quick {
        &[32, 100]
    } else {
        &[32, 45, 100, 316]
    };
    for &k in ks {
        fields(k, &dir, 100_000).expect("fields");
    }
}
