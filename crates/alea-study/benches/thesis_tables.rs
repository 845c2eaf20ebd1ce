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

use alea_cre::{CreOptions, EnergySampler};
use alea_estimate::gram::CrossGram;
use alea_estimate::reference::{self, expected_distances};
use alea_estimate::{Rule, Weights};
use alea_fem::{Location, PointLocator};
use alea_latin::LatinSolver;
use alea_study::Source;
use alea_study::adaptive::AdaptiveOutcome;
use alea_study::cre::StudyParameters;
use alea_study::estimate::{MethodEstimateInput, error_settings, estimate_method};
use alea_study::method::MethodKind;
use alea_study::method::Surrogate;
use alea_study::runner::{NoProgress, Study, StudyRuns, run_study};
use alea_study::store::{Store, point_key};
use rayon::prelude::*;

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
fn study_text(base: &str, factor: f64, methods: &str, error: bool) -> String {
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
    let error = if error { "\n[error]\nwarn = 1.0\n" } else { "" };
    format!(
        "{}\n{methods}\n[statistics]\nsamples = 20000\n{error}{}",
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

/// The study of one space mesh.
struct MeshStudy {
    study: Study,
    runs: StudyRuns,
    rows: Vec<Row>,
    dir: PathBuf,
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
    /// `e~^2`, its substructure part and the normalisation `E[sum ||sigma~||^2]`.
    e2: f64,
    sub_e2: f64,
    norm2: f64,
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
        let (_, me) = estimate_method(&MethodEstimateInput {
            study,
            setup: &setup,
            solver: &runs.solver,
            store: &store,
            method: m,
            points: &m.points,
            sur: &sur,
            settings: &settings,
        })
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
            e2: est.e2,
            sub_e2: est.subs.iter().map(|x| x.e2).sum(),
            norm2: est.norm2,
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
        let text = study_text(&base, f * scale, &methods, true);
        let study = load(&format!("mesh{i}.toml"), &text);
        let dir = root.join(format!("mesh{i}-{}", study.hash));
        let (runs, rows, secs) = run(&study, &dir);
        println!(
            "mesh {i}: {} dof, {} runs ({} computed), {secs:.1} s",
            dofs(&runs),
            runs.records.len(),
            runs.computed
        );
        per_mesh.push(MeshStudy {
            study,
            runs,
            rows,
            dir,
        });
    }

    if wants("4.1") {
        println!("\nTable 4.1 (piecewise linear on regular grids):");
        println!("| dof | K | e~ | i_geo | i_sto | i_sto per entity [%] |");
        println!("|---|---|---|---|---|---|");
        for MeshStudy { runs, rows, .. } in &per_mesh {
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
        for MeshStudy { runs, rows, .. } in &per_mesh {
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
        println!("\ni_sto per entity [%] of the 9-run surrogates:");
        for MeshStudy { runs, rows, .. } in &per_mesh {
            for r in rows.iter().filter(|r| r.runs == 9) {
                println!("| {} | {} | {} |", dofs(runs), r.label, r.entities);
            }
        }
    }

    if wants("4.3")
        && let Some(MeshStudy { runs, rows, .. }) = per_mesh.last()
    {
        table_43(runs, rows, &[0.1, strict]);
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

/// A surrogate's weights with its run indices mapped into a larger list of runs.
struct Remapped<'a> {
    surrogate: &'a Surrogate,
    map: Vec<usize>,
}

impl Weights for Remapped<'_> {
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        Weights::weights(self.surrogate, xi, w);
        for (k, _) in w.iter_mut() {
            *k = self.map[*k];
        }
    }
}

/// Offset of substructure `s`'s displacement in a stored field vector.
fn field_offset(solver: &LatinSolver, s: usize) -> usize {
    (0..s)
        .map(|t| solver.model(t).mesh.num_nodes() * solver.model(t).mesh.dim)
        .sum()
}

/// Nodes of a regular grid of `n` points per parameter, per parameter.
fn grid_breaks(study: &Study, n: usize) -> Vec<Vec<f64>> {
    let p = &study.params;
    (0..p.lo.len())
        .map(|j| {
            (0..n)
                .map(|i| p.lo[j] + (p.hi[j] - p.lo[j]) * i as f64 / (n - 1) as f64)
                .collect()
        })
        .collect()
}

/// The stochastic efficiency index (thesis 3.3.3, `alea_estimate::reference`) of every
/// (mesh, K) of table 4.1 against the reference study: space mesh with 2x the finest mesh's cell
/// counts (4x in area), piecewise linear on 11 x 11 runs. Per substructure, the reference runs'
/// strains and the coarse runs' (located at the reference mesh's sample points) in energy
/// coordinates give the Gram blocks of `E[alpha |sum r_m z_ref,m - sum w_k z_h,k|^2]`,
/// accumulated over blocks of reference cells; the expectation is taken over Gauss rules on the
/// cells of the union of both grids' nodes.
fn efficiency(base: &str, scale: f64, root: &Path, per_mesh: &[MeshStudy]) {
    let t0 = Instant::now();
    let text = study_text(base, REFERENCE * scale, &grid(11), false);
    let rstudy = load("reference.toml", &text);
    let rdir = root.join(format!("reference-{}", rstudy.hash));
    let rruns = run_study(&rstudy, &rdir, false, &NoProgress).unwrap();
    let rmethod = &rruns.methods[0];
    let rpoints = rmethod.points.clone();
    for p in &rpoints {
        let ok = rruns
            .records
            .iter()
            .any(|r| point_key(&r.params) == point_key(p) && r.converged());
        assert!(ok, "reference: the run at {p:?} did not converge");
    }
    let rsur = rmethod.surrogate(&rstudy.params, &rpoints).unwrap();
    let rstore = Store::open(&rdir, &rstudy.hash, false).unwrap();
    let rfields: Vec<Vec<f64>> = rpoints.iter().map(|p| rstore.fields(p).unwrap()).collect();
    println!(
        "\nreference: {} dof, {} runs ({} computed), {:.1} s",
        dofs(&rruns),
        rpoints.len(),
        rruns.computed,
        t0.elapsed().as_secs_f64()
    );
    println!(
        "\nTable 4.1, stochastic efficiency index nu = e~ / (E[sum_s ||sigma_ref - sigma_h1||^2])^(1/2):"
    );
    println!(
        "| dof | K | e~ | reference distance | nu | sqrt(2) nu | nu of the substructures' part of e~ | seconds since the mesh's Gram blocks began |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for ms in per_mesh {
        let t1 = Instant::now();
        let (study, runs) = (&ms.study, &ms.runs);
        let Some(m25) = runs.methods.iter().find(|m| m.label == "K = 25") else {
            continue;
        };
        let cpoints = m25.points.clone();
        let store = Store::open(&ms.dir, &study.hash, false).unwrap();
        let cfields: Vec<Vec<f64>> = cpoints.iter().map(|p| store.fields(p).unwrap()).collect();
        let ns = runs.solver.num_subs();
        let mut grams = Vec::with_capacity(ns);
        for s in 0..ns {
            let (rmodel, cmodel) = (rruns.solver.model(s), runs.solver.model(s));
            let (roff, coff) = (
                field_offset(&rruns.solver, s),
                field_offset(&runs.solver, s),
            );
            let sampler = EnergySampler::new(rmodel, &CreOptions::default()).unwrap();
            let locator = PointLocator::new(&cmodel.mesh).unwrap();
            let ncells = rmodel.mesh.num_cells();
            let locs: Vec<Location> = (0..ncells)
                .into_par_iter()
                .flat_map_iter(|c| {
                    sampler
                        .cell_points(c)
                        .map(|(_, x)| {
                            locator.locate_nearest(x, 1e-3).unwrap_or_else(|| {
                                panic!("sample point {x:?} of the reference is off the coarse mesh")
                            })
                        })
                        .collect::<Vec<_>>()
                })
                .collect();
            let point_offset: Vec<usize> = sampler.cell_offsets().iter().map(|o| o / 3).collect();
            const BLOCK: usize = 256;
            let starts: Vec<usize> = (0..ncells).step_by(BLOCK).collect();
            let parts: Vec<CrossGram> = starts
                .par_iter()
                .map(|&c0| {
                    let c1 = (c0 + BLOCK).min(ncells);
                    let m = 3 * (point_offset[c1] - point_offset[c0]);
                    let mut a = Vec::with_capacity(m * rfields.len());
                    for f in &rfields {
                        let u = &f[roff..];
                        sampler.strain_samples(
                            c0..c1,
                            |c, xi, _| EnergySampler::strain_at(rmodel, u, c, xi),
                            &mut a,
                        );
                    }
                    let mut b = Vec::with_capacity(m * cfields.len());
                    for f in &cfields {
                        let u = &f[coff..];
                        let mut q = point_offset[c0];
                        sampler.strain_samples(
                            c0..c1,
                            |_, _, _| {
                                let l = locs[q];
                                q += 1;
                                EnergySampler::strain_at(cmodel, u, l.cell, l.xi)
                            },
                            &mut b,
                        );
                    }
                    let mut g = CrossGram::zeros(rfields.len(), cfields.len());
                    g.add_block(m, &a, &b);
                    g
                })
                .collect();
            let mut g = CrossGram::zeros(rfields.len(), cfields.len());
            for p in &parts {
                g.add(p);
            }
            grams.push(Some(g));
        }
        let params = StudyParameters::new(&study.model.parametric, &runs.solver);
        for k in [2usize, 3, 5] {
            let label = format!("K = {}", k * k);
            let (Some(m), Some(row)) = (
                runs.methods.iter().find(|m| m.label == label),
                ms.rows.iter().find(|r| r.label == label),
            ) else {
                continue;
            };
            let sur = m.surrogate(&study.params, &m.points).unwrap();
            let map: Vec<usize> = m
                .points
                .iter()
                .map(|p| {
                    cpoints
                        .iter()
                        .position(|c| point_key(c) == point_key(p))
                        .expect("nested grids")
                })
                .collect();
            let remapped = Remapped {
                surrogate: &sur,
                map,
            };
            let mut breaks = grid_breaks(study, 11);
            for (b, g) in breaks.iter_mut().zip(grid_breaks(study, k)) {
                b.extend(g);
            }
            let cells = Rule::product_cells(&breaks).unwrap();
            let tags: Vec<usize> = (0..cells.len()).collect();
            let rule = Rule::on_cells(&cells, &tags, 4, study.params.joint.as_ref()).unwrap();
            let d2: f64 = expected_distances(&rule, &rsur, &remapped, &params, &grams)
                .iter()
                .sum();
            let (nu, nu_ps) = reference::efficiency(row.e2, d2).unwrap_or((f64::NAN, f64::NAN));
            let nu_subs = reference::efficiency(row.sub_e2, d2).map_or(f64::NAN, |x| x.0);
            println!(
                "| {} | {} | {} | {} | {nu:.3} | {nu_ps:.3} | {nu_subs:.3} | {:.1} |",
                dofs(runs),
                k * k,
                pct(row.e),
                pct((d2 / row.norm2).sqrt()),
                t1.elapsed().as_secs_f64()
            );
        }
    }
}
