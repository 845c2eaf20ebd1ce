//! The thesis's tables 3.1 / 4.1 / 4.2 / 4.3 / 4.4 (Bellec 2008, chapters 3.3, 4.1.3, 4.2.3)
//! on the simple blade root (`examples/blade-root-simple.toml`: its model, laws and quantity
//! `T`; only the mesh's cell counts and the methods change), with the study's own estimator
//! (`alea_study::estimate::estimate_method`, the code path of `alea run`):
//!
//! - **4.1**: three space meshes (about 1 000 / 5 000 / 16 000 dof) x regular stochastic grids
//!   K = 4, 9, 25 (piecewise multilinear): `i_geo`, `i_sto`, `e~` and the stochastic efficiency
//!   index against a reference (space mesh refined 4x in area from the finest, 11 x 11 runs;
//!   `alea_estimate::reference`, see [`efficiency`] below);
//! - **3.1 / 4.2**: chaos (degree 2, collocation at the roots of the degree-3 orthogonal
//!   polynomials), standard polynomial (degree 2, least squares on the 3 x 3 grid) and piecewise
//!   linear 3 x 3 on each mesh: `i_sto` of each from the same code path;
//! - **4.3 / 4.4**: on the finest mesh, regular grids K = 4, 9, 25, 81 against the adaptive
//!   study with the maximum-error and the improved criterion (start: corners + centre, target
//!   `i_sto <= 10 %`): runs, `i_sto`, `i_geo` and the thesis's cost (run = 1, estimate = 1.5)
//!   of the first method or step that reaches the target.
//!
//! Environment:
//! - `TABLES` = comma list of `4.1`, `4.2`, `4.3`, `eff` (default all; `eff` is the reference
//!   study and the efficiency indices of table 4.1);
//! - `TABLES_SCALE` multiplies every mesh's cell counts (default 1; 0.5 for a quick check);
//! - `TABLES_DIR` = where the study stores go (default a temporary directory, removed at the
//!   end unless `TABLES_KEEP=1`; a kept directory is resumed: runs are not recomputed).
//!
//! Run: `cargo bench -p alea-study --bench thesis_tables` (record in the root BENCHMARKS.md).

use std::path::{Path, PathBuf};
use std::time::Instant;

use alea_study::Source;
use alea_study::adaptive::AdaptiveOutcome;
use alea_study::estimate::{error_settings, estimate_method};
use alea_study::method::MethodKind;
use alea_study::runner::{NoProgress, Study, StudyRuns, run_study};
use alea_study::store::{Store, point_key};

/// Cell counts of the shipped mesh (11 544 dof).
const SHIPPED: [(&str, f64); 4] = [
    ("n_flank", 36.0),
    ("n_side", 45.0),
    ("n_root", 36.0),
    ("n_shank", 27.0),
];

/// Mesh factors of table 4.1 (about 1 000 / 5 000 / 16 000 dof) and of the reference (2x the
/// finest's cell counts: 4x in area).
const MESHES: [f64; 3] = [0.29, 0.65, 1.18];
const REFERENCE: f64 = 2.36;

fn example() -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/blade-root-simple.toml");
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// The example with its cell counts times `factor` and `methods` in place of its methods.
fn study_text(base: &str, factor: f64, methods: &str) -> String {
    let mut out = String::new();
    for line in base.lines() {
        if line.starts_with("params = {") {
            let mut l = line.to_string();
            for (name, n) in SHIPPED {
                let old = format!("{name} = {n}");
                assert!(l.contains(&old), "the example's mesh has no {old}");
                let new = format!("{name} = {}", ((n * factor).round() as usize).max(2));
                l = l.replace(&old, &new);
            }
            out.push_str(&l);
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    let first = out.find("\n[[method]]").expect("the example has methods");
    let solver = out.find("\n[solver]").expect("the example has [solver]");
    assert!(solver > first, "[solver] after the methods");
    format!(
        "{}\n{methods}\n[statistics]\nsamples = 20000\n\n[error]\nwarn = 1.0\n{}",
        &out[..first],
        &out[solver..]
    )
}

fn load(name: &str, text: &str) -> Study {
    Study::from_source(Source::from_text(name, text)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn dofs(runs: &StudyRuns) -> usize {
    (0..runs.solver.num_subs())
        .map(|s| {
            let m = runs.solver.model(s);
            m.mesh.num_nodes() * m.mesh.dim
        })
        .sum()
}

/// One estimated method.
#[derive(Clone, Debug)]
struct Row {
    label: String,
    runs: usize,
    e: f64,
    i_geo: f64,
    i_sto: f64,
    /// `i_sto` per entity (substructures, then interfaces), `name=value` in %: signed, with
    /// `-` when the entity's `I_sto^2` is negative (an interface's `sto_I` of (4.5) has no sign).
    entities: String,
}

/// Runs `study` in `dir` and estimates every non-adaptive method.
fn run(study: &Study, dir: &Path) -> (StudyRuns, Vec<Row>, f64) {
    let t0 = Instant::now();
    let runs = run_study(study, dir, false, &NoProgress).unwrap();
    let setup = runs.cre.clone().expect("[error] turns estimation on");
    let store = Store::open(dir, &study.hash, false).unwrap();
    let settings = error_settings(study).unwrap();
    let mut rows = Vec::new();
    for m in &runs.methods {
        if matches!(m.kind, MethodKind::Adaptive(_) | MethodKind::MonteCarlo) {
            continue;
        }
        for p in &m.points {
            let ok = runs
                .records
                .iter()
                .any(|r| point_key(&r.params) == point_key(p) && r.converged());
            assert!(ok, "{}: a run at {p:?} did not converge", m.label);
        }
        let sur = m.surrogate(&study.params, &m.points).unwrap();
        let (_, me) = estimate_method(
            study,
            &setup,
            &runs.solver,
            &store,
            m,
            &m.points,
            &sur,
            &settings,
        )
        .unwrap();
        let est = &me.estimate;
        rows.push(Row {
            label: m.label.clone(),
            runs: m.points.len(),
            e: est.relative(),
            i_geo: est.i_geo(),
            i_sto: est.i_sto(),
            entities: est
                .subs
                .iter()
                .chain(&est.interfaces)
                .map(|x| {
                    let v = 100.0 * (x.sto2.abs() / est.norm2).sqrt();
                    format!("{}={}{v:.3}", x.name, if x.sto2 < 0.0 { "-" } else { "" })
                })
                .collect::<Vec<_>>()
                .join(" "),
        });
    }
    (runs, rows, t0.elapsed().as_secs_f64())
}

fn grid(k: usize) -> String {
    format!(
        "[[method]]\ntype = \"piecewise_linear\"\npoints_per_dim = {k}\nlabel = \"K = {}\"\n\n",
        k * k
    )
}

const SURROGATES: &str = r#"
[[method]]
type = "pc_regression"
degree = 2
label = "chaos p=2"

[[method]]
type = "polynomial"
degree = 2
design = "grid"
points_per_dim = 3
label = "standard polynomial p=2"
"#;

fn adaptive(criterion: &str, target: f64) -> String {
    format!(
        "[[method]]\ntype = \"adaptive\"\ncriterion = \"{criterion}\"\ntarget = {target}\nmax_runs = 81\nlabel = \"adaptive {criterion}\"\n\n"
    )
}

fn pct(x: f64) -> String {
    format!("{:.2} %", 100.0 * x)
}

fn main() {
    let wanted = std::env::var("TABLES").unwrap_or_else(|_| "4.1,4.2,4.3,eff".into());
    let wants = |t: &str| wanted.split(',').any(|w| w.trim() == t);
    let scale: f64 = std::env::var("TABLES_SCALE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0);
    let strict: f64 = std::env::var("TABLES_TARGET")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.001);
    let keep = std::env::var("TABLES_KEEP").is_ok_and(|v| v == "1");
    let root: PathBuf = std::env::var("TABLES_DIR").map_or_else(
        |_| std::env::temp_dir().join(format!("alea-thesis-tables-{}", std::process::id())),
        PathBuf::from,
    );
    std::fs::create_dir_all(&root).unwrap();
    let base = example();
    println!(
        "thesis tables on examples/blade-root-simple.toml, mesh scale {scale}, threads {}",
        rayon::current_num_threads()
    );

    // One study per mesh: K = 4, 9, 25 (+ 81 and the adaptive methods on the finest mesh for
    // tables 4.3 / 4.4) and the two global surrogates.
    let mut per_mesh = Vec::new();
    for (i, f) in MESHES.iter().enumerate() {
        let finest = i + 1 == MESHES.len();
        let mut methods = String::new();
        if wants("4.1") || wants("4.2") || wants("eff") || (finest && wants("4.3")) {
            for k in [2, 3, 5] {
                methods.push_str(&grid(k));
            }
        }
        if wants("4.2") {
            methods.push_str(SURROGATES);
        }
        if finest && wants("4.3") {
            methods.push_str(&grid(9));
            methods.push_str(&adaptive("max_error", strict));
            methods.push_str(&adaptive("improved", strict));
        }
        if methods.is_empty() {
            continue;
        }
        let text = study_text(&base, f * scale, &methods);
        let study = load(&format!("mesh{i}.toml"), &text);
        let (runs, rows, secs) = run(&study, &root.join(format!("mesh{i}-{}", study.hash)));
        println!(
            "mesh {i}: {} dof, {} runs ({} computed), {secs:.1} s",
            dofs(&runs),
            runs.records.len(),
            runs.computed
        );
        per_mesh.push((i, study, runs, rows));
    }

    if wants("4.1") {
        println!("\nTable 4.1 (piecewise linear on regular grids):");
        println!("| dof | K | e~ | i_geo | i_sto | i_sto per entity [%] |");
        println!("|---|---|---|---|---|---|");
        for (_, _, runs, rows) in &per_mesh {
            for r in rows.iter().filter(|r| r.label.starts_with("K = ")) {
                if r.runs > 25 {
                    continue;
                }
                println!(
                    "| {} | {} | {} | {} | {} | {} |",
                    dofs(runs),
                    r.runs,
                    pct(r.e),
                    pct(r.i_geo),
                    pct(r.i_sto),
                    r.entities
                );
            }
        }
    }

    if wants("4.2") {
        println!("\nTables 3.1 / 4.2 (9 runs each):");
        println!(
            "| dof | chaos p=2 i_sto | standard polynomial p=2 i_sto | piecewise linear 3 x 3 i_sto | i_geo (PL 3 x 3) |"
        );
        println!("|---|---|---|---|---|");
        for (_, _, runs, rows) in &per_mesh {
            let get = |l: &str| rows.iter().find(|r| r.label == l).map(|r| r.i_sto);
            let (Some(c), Some(s), Some(p)) = (
                get("chaos p=2"),
                get("standard polynomial p=2"),
                get("K = 9"),
            ) else {
                continue;
            };
            let g = rows
                .iter()
                .find(|r| r.label == "K = 9")
                .map_or(0.0, |r| r.i_geo);
            println!(
                "| {} | {} | {} | {} | {} |",
                dofs(runs),
                pct(c),
                pct(s),
                pct(p),
                pct(g)
            );
        }
    }

    if wants("4.3") {
        if let Some((_, _, runs, rows)) = per_mesh.last() {
            table_43(runs, rows, &[0.1, strict]);
        }
    }

    if wants("eff") {
        efficiency(&base, scale, &root, &per_mesh);
    }

    if !keep {
        drop(per_mesh);
        let _ = std::fs::remove_dir_all(&root);
    }
}

/// Tables 4.3 / 4.4: regular grids against the two adaptive criteria on the finest mesh.
fn table_43(runs: &StudyRuns, rows: &[Row], targets: &[f64]) {
    println!(
        "\nTables 4.3 / 4.4 ({} dof; cost: run = 1, estimate = 1.5):",
        dofs(runs),
    );
    println!("| method | runs | estimates | i_sto | i_geo | thesis cost |");
    println!("|---|---|---|---|---|---|");
    for r in rows.iter().filter(|r| r.label.starts_with("K = ")) {
        println!(
            "| regular {} | {} | 1 | {} | {} | {} |",
            r.label,
            r.runs,
            pct(r.i_sto),
            pct(r.i_geo),
            r.runs as f64 + 1.5
        );
    }
    for a in &runs.adaptive {
        print_adaptive(runs, a);
    }
    for &target in targets {
        println!("\ntarget i_sto <= {}:", pct(target));
        let regular = rows
            .iter()
            .filter(|r| r.label.starts_with("K = "))
            .find(|r| r.i_sto <= target)
            .map(|r| (r.label.clone(), r.runs as f64 + 1.5));
        match &regular {
            Some((l, c)) => println!("- first regular grid that reaches it: {l}, cost {c}"),
            None => println!("- no regular grid reaches it"),
        }
        for a in &runs.adaptive {
            let label = &runs.methods[a.method].label;
            let step = a.steps.iter().find(|s| s.error.estimate.i_sto() <= target);
            match (step, &regular) {
                (Some(s), Some((_, c))) => println!(
                    "- {label}: reaches it with {} runs, cost {} = {:.0} % of the regular grid's",
                    s.runs,
                    s.thesis_cost,
                    100.0 * s.thesis_cost / c
                ),
                (Some(s), None) => println!(
                    "- {label}: reaches it with {} runs, cost {}",
                    s.runs, s.thesis_cost
                ),
                (None, _) => println!("- {label}: does not reach it"),
            }
        }
    }
}

fn print_adaptive(runs: &StudyRuns, a: &AdaptiveOutcome) {
    let label = &runs.methods[a.method].label;
    for (k, s) in a.steps.iter().enumerate() {
        println!(
            "| {label} step {} | {} | {} | {} | {} | {} |",
            k + 1,
            s.runs,
            k + 1,
            pct(s.error.estimate.i_sto()),
            pct(s.error.estimate.i_geo()),
            s.thesis_cost
        );
    }
    println!("| {label}: stop | {} | | | | |", a.stop);
}

/// The stochastic efficiency index of every (mesh, K) of table 4.1 (not yet wired).
fn efficiency(
    _base: &str,
    _scale: f64,
    _root: &Path,
    _per_mesh: &[(usize, Study, StudyRuns, Vec<Row>)],
) {
}
