//! Trends of the thesis's tables 4.1 and 4.3 / 4.4 (Bellec 2008, 4.1.3 and 4.2.3) on coarsened
//! copies of the simple blade root (`examples/blade-root-simple.toml`: its model, laws and
//! quantity; only the mesh's cell counts and the methods change), through the study's own
//! estimate path. The full-size tables are `benches/thesis_tables.rs` (root BENCHMARKS.md).
//!
//! - The space part `i_geo` falls as the space mesh is refined (same stochastic grid); the
//!   interfaces' space part is the runs' own interface error, ~0 at converged LATIN runs.
//! - The stochastic part `i_sto` falls with the regular stochastic grid K = 4, 9, 25, and its
//!   substructure part (the root's random Young's modulus: interpolation of `1/E2`) like `h^2`.
//!   The interfaces' part (interpolation between runs of different contact status) falls too.
//! - The improved adaptive criterion, from the corners plus the centre, reaches a target a
//!   quarter below the 2 x 2 grid's `i_sto` with fewer runs than the regular grid that reaches
//!   it. (On this model that is where the adaptive study wins: for targets below the 3 x 3
//!   grid's `i_sto` the regular grids need fewer runs, see BENCHMARKS.md.)

use alea_study::Source;
use alea_study::estimate::{MethodEstimateInput, error_settings, estimate_method};
use alea_study::method::MethodKind;
use alea_study::runner::{NoProgress, Study, StudyRuns, run_study};
use alea_study::store::{Store, point_key};

/// Cell counts of the shipped mesh.
const SHIPPED: [(&str, f64); 4] = [
    ("n_flank", 36.0),
    ("n_side", 45.0),
    ("n_root", 36.0),
    ("n_shank", 27.0),
];

/// The example with its cell counts times `factor` and `methods` in place of its own.
fn study(factor: f64, methods: &str) -> Study {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/blade-root-simple.toml");
    let base = std::fs::read_to_string(&p).unwrap();
    let mut out = String::new();
    for line in base.lines() {
        let mut l = line.to_string();
        if l.starts_with("params = {") {
            for (name, n) in SHIPPED {
                let old = format!("{name} = {n}");
                assert!(l.contains(&old), "the example's mesh has no {old}");
                l = l.replace(&old, &format!("{name} = {}", (n * factor).round() as usize));
            }
        }
        out.push_str(&l);
        out.push('\n');
    }
    let first = out.find("\n[[method]]").expect("methods");
    let solver = out.find("\n[solver]").expect("[solver]");
    let text = format!(
        "{}\n{methods}\n[statistics]\nsamples = 2000\n\n[error]\nwarn = 1.0\n{}",
        &out[..first],
        &out[solver..]
    );
    Study::from_source(Source::from_text("blade-root-trends.toml", &text)).unwrap()
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("alea-trends-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn grid(k: usize) -> String {
    format!("[[method]]\ntype = \"piecewise_linear\"\npoints_per_dim = {k}\nlabel = \"K{k}\"\n\n")
}

/// Runs the study and estimates its non-adaptive methods: `(label, runs, estimate)`.
fn estimates(s: &Study, name: &str) -> (StudyRuns, Vec<(String, usize, alea_estimate::Estimate)>) {
    let dir = scratch(name);
    let runs = run_study(s, &dir, false, &NoProgress).unwrap();
    let setup = runs.cre.clone().unwrap();
    let store = Store::open(&dir, &s.hash, false).unwrap();
    let settings = error_settings(s).unwrap();
    let mut out = Vec::new();
    for m in &runs.methods {
        if matches!(m.kind, MethodKind::Adaptive(_)) {
            continue;
        }
        for p in &m.points {
            assert!(
                runs.records
                    .iter()
                    .any(|r| point_key(&r.params) == point_key(p) && r.converged()),
                "{}: run at {p:?} converged",
                m.label
            );
        }
        let sur = m.surrogate(&s.params, &m.points).unwrap();
        let (_, e) = estimate_method(&MethodEstimateInput {
            study: s,
            setup: &setup,
            solver: &runs.solver,
            store: &store,
            method: m,
            points: &m.points,
            sur: &sur,
            settings: &settings,
        })
        .unwrap();
        out.push((m.label.clone(), m.points.len(), e.estimate));
    }
    drop(store);
    let _ = std::fs::remove_dir_all(&dir);
    (runs, out)
}

#[test]
fn space_error_falls_as_the_space_mesh_is_refined() {
    let mut i_geo = Vec::new();
    for (i, f) in [0.15, 0.3, 0.45].into_iter().enumerate() {
        let (_, e) = estimates(&study(f, &grid(2)), &format!("geo{i}"));
        let est = &e[0].2;
        // The space part of the interfaces is the runs' own interface error, ~0 at converged
        // runs: I_geo is the substructures' space error.
        for it in &est.interfaces {
            assert!(it.geo2.abs() < 1e-9 * est.e2, "{est:?}");
        }
        i_geo.push(est.i_geo());
    }
    for w in i_geo.windows(2) {
        assert!(w[1] < 0.95 * w[0], "i_geo {i_geo:?} against the mesh");
    }
}

#[test]
fn stochastic_error_falls_with_the_regular_grid() {
    let methods: String = [2, 3, 5].iter().map(|&k| grid(k)).collect();
    let (_, e) = estimates(&study(0.15, &methods), "sto");
    let i_sto: Vec<f64> = e.iter().map(|x| x.2.i_sto()).collect();
    let i_geo: Vec<f64> = e.iter().map(|x| x.2.i_geo()).collect();
    for w in i_sto.windows(2) {
        assert!(w[1] < 0.8 * w[0], "i_sto {i_sto:?} against K = 4, 9, 25");
    }
    // The root's part: linear interpolation of 1/E2, like h^2 (ratio 4 per halving); 2.5 at
    // least.
    let s2: Vec<f64> = e
        .iter()
        .map(|x| {
            let sub = x.2.subs.iter().find(|s| s.name == "S2").unwrap();
            x.2.relative_of(sub.sto2)
        })
        .collect();
    for w in s2.windows(2) {
        assert!(w[1] * 2.5 < w[0], "S2's i_sto {s2:?}");
    }
    // The space part hardly depends on the stochastic grid.
    for g in &i_geo {
        assert!((g - i_geo[2]).abs() < 0.02 * i_geo[2], "i_geo {i_geo:?}");
    }
}

#[test]
fn improved_adaptive_study_reaches_a_target_with_fewer_runs_than_the_regular_grid() {
    let methods: String = [2, 3, 5].iter().map(|&k| grid(k)).collect();
    let (_, regular) = estimates(&study(0.15, &methods), "regular");
    let target = 0.75 * regular[0].2.i_sto();
    let (runs_needed, k) = regular
        .iter()
        .find(|(_, _, e)| e.i_sto() <= target)
        .map(|(l, n, _)| (*n, l.clone()))
        .expect("a regular grid reaches the target");
    // The subject is the criterion's cost to reach i_sto <= target (thesis table 4.3): the
    // target stop's validation runs, which go on while a quantity's error exceeds the target
    // (module `target_validation`: here they take the loop from 9 to 21 runs), are switched
    // off.
    let adaptive = format!(
        "[[method]]\ntype = \"adaptive\"\ncriterion = \"improved\"\ntarget = {target}\nmax_runs = 25\nlabel = \"improved\"\n\n[budget]\nvalidation_runs = 0\n"
    );
    let dir = scratch("adaptive");
    let runs = run_study(&study(0.15, &adaptive), &dir, false, &NoProgress).unwrap();
    let a = &runs.adaptive[0];
    let last = a.steps.last().unwrap();
    assert!(
        last.error.estimate.i_sto() <= target,
        "stopped by {}: i_sto {}",
        a.stop,
        last.error.estimate.i_sto()
    );
    assert!(
        last.runs < runs_needed,
        "improved: {} runs for i_sto <= {target}; regular grid {k}: {runs_needed}; stop: {}",
        last.runs,
        a.stop
    );
    drop(runs);
    let _ = std::fs::remove_dir_all(&dir);
}
