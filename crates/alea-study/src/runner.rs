//! Running a study's deterministic solves.
//!
//! The union of all methods' design points is run once (points shared by several methods are
//! run once). Runs go through one multiresolution [`LatinSolver`] (set-up and factorisations
//! shared) in **batches of a fixed schedule** (sizes 1, 2, 4, then 8): the runs of a batch are
//! solved in parallel, each warm-started from the nearest converged run of the earlier batches
//! (distance in the parameter box scaled to the unit cube). The schedule depends only on the
//! design, never on the thread count or on what a previous, interrupted invocation finished,
//! so results are identical with 1 or 2 threads and after a resume. Points are ordered by a
//! greedy nearest-neighbour walk from the nominal point, so each batch starts near finished runs.
//!
//! Each finished run is committed to the [`Store`] at once; `run_study` on a directory that
//! already holds runs skips them (a resume) and loads their local-stage states for the warm
//! starts.

use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use alea_latin::{LatinSolver, LocalState, RunStatus};
use rayon::prelude::*;

use crate::method::{Method, build_methods};
use crate::qoi::{Qoi, build_qois};
use crate::spec::{ModelFile, OutputSpec};
use crate::store::{RunRecord, Store, point_key, text_hash};
use crate::{BuiltModel, ParamSpace, Source, StudyError, build_model, build_params};

/// A loaded, validated study.
pub struct Study {
    /// The study file.
    pub source: Source,
    /// Its parsed content.
    pub file: ModelFile,
    /// Random parameters.
    pub params: ParamSpace,
    /// The mechanical model.
    pub model: BuiltModel,
    /// Quantities of interest.
    pub qois: Vec<Qoi>,
    /// Methods (the first is the study's answer).
    pub methods: Vec<Method>,
    /// Seed of all random draws.
    pub seed: u64,
    /// Hash of the study file's text.
    pub hash: String,
    /// Outputs.
    pub output: OutputSpec,
}

impl std::fmt::Debug for Study {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Study")
            .field("file", &self.source.path)
            .finish()
    }
}

/// Observer of a running study (progress bars live in the binary).
pub trait Progress: Sync {
    /// The study has `total` runs, `done` of which are already in the store.
    fn begin(&self, _total: usize, _done: usize) {}
    /// A run finished (converged or not).
    fn finished(&self, _rec: &RunRecord) {}
    /// All runs are done.
    fn end(&self) {}
}

/// A progress observer that does nothing.
pub struct NoProgress;
impl Progress for NoProgress {}

impl Study {
    /// Loads and checks a study from its source text.
    pub fn from_source(source: Source) -> Result<Self, StudyError> {
        let file: ModelFile = source.parse()?;
        let params = build_params(&source, &file)?;
        if params.names.is_empty() {
            return Err(source.error(0..0, "parameter", "a study needs at least one [[parameter]] (use 'alea solve' for a deterministic case)"));
        }
        if file.quantity.is_empty() {
            return Err(source.error(0..0, "quantity", "a study needs at least one [[quantity]]"));
        }
        if file.method.is_empty() {
            return Err(source.error(0..0, "method", "a study needs at least one [[method]]"));
        }
        let model = build_model(&source, &file, &params)?;
        let qois = build_qois(&source, &file.quantity, &model)?;
        let seed = file.study.seed.unwrap_or(1);
        let methods = build_methods(&source, &file.method, &params, seed)?;
        let hash = text_hash(&source.text);
        let output = file.output.clone();
        Ok(Study {
            source,
            file,
            params,
            model,
            qois,
            methods,
            seed,
            hash,
            output,
        })
    }

    /// Loads a study file.
    pub fn load(path: &Path) -> Result<Self, StudyError> {
        Self::from_source(Source::read(path)?)
    }

    /// The title (from `[study]`, else the file name).
    pub fn title(&self) -> String {
        self.file.study.title.clone().unwrap_or_else(|| {
            self.source
                .path
                .file_stem()
                .map_or("study".into(), |s| s.to_string_lossy().into_owned())
        })
    }

    /// Every distinct design point, in method order.
    pub fn all_points(&self) -> Vec<Vec<f64>> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for m in &self.methods {
            for p in &m.points {
                if seen.insert(point_key(p)) {
                    out.push(p.clone());
                }
            }
        }
        out
    }

    /// A point scaled to the unit cube of the parameter box.
    pub fn normalise(&self, p: &[f64]) -> Vec<f64> {
        p.iter()
            .enumerate()
            .map(|(j, v)| (v - self.params.lo[j]) / (self.params.hi[j] - self.params.lo[j]))
            .collect()
    }

    /// Checks the parameter-dependent model data at a design point (Young's moduli > 0, finite
    /// load factors, mu >= 0 and finite gaps at every interface point): errors name the field.
    fn check_point(&self, solver: &LatinSolver, theta: &[f64]) -> Result<(), StudyError> {
        let src = &self.source;
        let at = || {
            self.params
                .names
                .iter()
                .zip(theta)
                .map(|(n, v)| format!("{n} = {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let par = &self.model.parametric;
        for (s, e) in par.young.iter().enumerate() {
            let v = e.eval(theta);
            if !(v.is_finite() && v > 0.0) {
                let sp = &self.file.substructure[s].young;
                return Err(src.error(
                    sp.span(),
                    format!("substructure[{s}].young"),
                    format!("evaluates to {v} at {}; must be > 0", at()),
                ));
            }
        }
        for (s, fs) in par.load_factors.iter().enumerate() {
            for (j, e) in fs.iter().enumerate() {
                let v = e.eval(theta);
                if !v.is_finite() {
                    let sp = self.file.substructure[s].load[j]
                        .factor
                        .as_ref()
                        .map_or(0..0, |f| f.span());
                    return Err(src.error(
                        sp,
                        format!("substructure[{s}].load[{j}].factor"),
                        format!("evaluates to {v} at {}", at()),
                    ));
                }
            }
        }
        let input = par.run_input(theta, vec![]);
        for i in 0..solver.num_interfaces() {
            for p in solver.interface_points(i) {
                let mu = input.mu[i].as_ref().map_or(p.mu, |f| f(p.x));
                let gap = input.gap[i].as_ref().map_or(p.gap, |f| f(p.x));
                let spec = &self.file.interface[i];
                if !(mu.is_finite() && mu >= 0.0) {
                    let sp = spec.mu.as_ref().map_or(spec.name.span(), |m| m.span());
                    return Err(src.error(sp, format!("interface[{i}].mu"), format!(
                        "friction coefficient {mu} at ({:.4}, {:.4}, {:.4}) for {}; must be finite and >= 0",
                        p.x[0], p.x[1], p.x[2], at()
                    )));
                }
                if !gap.is_finite() {
                    let sp = spec.gap.as_ref().map_or(spec.name.span(), |m| m.span());
                    return Err(src.error(
                        sp,
                        format!("interface[{i}].gap"),
                        format!(
                            "gap {gap} at ({:.4}, {:.4}, {:.4}) for {}",
                            p.x[0],
                            p.x[1],
                            p.x[2],
                            at()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The batches of the fixed schedule: indices into the ordered points.
fn schedule(n: usize) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut start = 0;
    let mut size = 1;
    while start < n {
        let end = (start + size).min(n);
        out.push(start..end);
        start = end;
        size = (size * 2).min(8);
    }
    out
}

/// Greedy nearest-neighbour walk from the point nearest to `origin` (deterministic).
fn nn_order(points: &[Vec<f64>], origin: &[f64]) -> Vec<usize> {
    let d2 = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>();
    let mut left: Vec<usize> = (0..points.len()).collect();
    let mut order = Vec::with_capacity(points.len());
    let mut cur = origin.to_vec();
    while !left.is_empty() {
        let (k, _) = left
            .iter()
            .enumerate()
            .map(|(k, &i)| (k, d2(&points[i], &cur)))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        let i = left.remove(k);
        cur = points[i].clone();
        order.push(i);
    }
    order
}

/// What [`run_study`] returns.
pub struct StudyRuns {
    /// Every design point's record, in [`Study::all_points`] order.
    pub records: Vec<RunRecord>,
    /// Runs computed by this invocation.
    pub computed: usize,
    /// Runs found in the store.
    pub resumed: usize,
    /// Solver set-up seconds.
    pub setup_seconds: f64,
    /// Wall-clock seconds of the solves of this invocation.
    pub solve_seconds: f64,
    /// The solver (for field output and further runs).
    pub solver: Arc<LatinSolver>,
}

/// Runs (or resumes) every design point of `study` in the study directory `dir`.
pub fn run_study(
    study: &Study,
    dir: &Path,
    restart: bool,
    progress: &dyn Progress,
) -> Result<StudyRuns, StudyError> {
    let store = Store::open(dir, &study.hash, restart)?;
    let points = study.all_points();
    let previous = store.runs()?;
    let mut by_key: std::collections::HashMap<String, RunRecord> = previous
        .into_iter()
        .map(|r| (point_key(&r.params), r))
        .collect();
    let solver = Arc::new(study.model.solver()?);
    for p in &points {
        study.check_point(&solver, p)?;
    }
    let sizes = solver.interface_sizes();
    let normalised: Vec<Vec<f64>> = points.iter().map(|p| study.normalise(p)).collect();
    let centre = study.normalise(&study.params.nominal);
    let order = nn_order(&normalised, &centre);
    let done_before = points
        .iter()
        .filter(|p| by_key.contains_key(&point_key(p)))
        .count();
    progress.begin(points.len(), done_before);
    let store = Mutex::new(store);
    let t0 = Instant::now();
    let mut computed = 0;
    let mut finished_order: Vec<usize> = Vec::new(); // indices into points, in schedule order
    for batch in schedule(order.len()) {
        let members: Vec<usize> = order[batch].to_vec();
        // Warm-start sources: converged runs of earlier batches only.
        let sources: Vec<(usize, Arc<LocalState>)> = finished_order
            .iter()
            .filter_map(|&i| {
                let r = by_key.get(&point_key(&points[i]))?;
                if !r.converged() {
                    return None;
                }
                LocalState::from_slice(&sizes, &r.state).map(|s| (i, Arc::new(s)))
            })
            .collect();
        let pending: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&i| !by_key.contains_key(&point_key(&points[i])))
            .collect();
        let results: Vec<Result<RunRecord, StudyError>> = pending
            .par_iter()
            .map(|&i| {
                let theta = &points[i];
                let mut input = study.model.parametric.run_input(theta, vec![]);
                input.initial = sources
                    .iter()
                    .map(|(k, s)| {
                        let d: f64 = normalised[*k]
                            .iter()
                            .zip(&normalised[i])
                            .map(|(a, b)| (a - b) * (a - b))
                            .sum();
                        (d, *k, s)
                    })
                    .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))
                    .map(|(_, _, s)| s.clone());
                let res = solver.run_shared(&input)?;
                let qois = study
                    .qois
                    .iter()
                    .map(|q| q.eval(&solver, &res))
                    .collect::<Result<Vec<_>, _>>()?;
                let status = match (res.status, solver.equilibrium_report(&res)) {
                    (RunStatus::NoEquilibrium, Some(why)) => format!("no equilibrium: {why}"),
                    (st, _) => st.label().to_string(),
                };
                let state = LocalState {
                    what: res.interfaces.iter().map(|it| it.what.clone()).collect(),
                    fhat: res.interfaces.iter().map(|it| it.fhat.clone()).collect(),
                };
                let rec = RunRecord {
                    params: theta.clone(),
                    status,
                    iterations: res.iterations,
                    residual: res
                        .residuals
                        .last()
                        .copied()
                        .filter(|v| v.is_finite())
                        .unwrap_or(f64::MAX),
                    seconds: res.timings.total,
                    qois: qois
                        .iter()
                        .map(|&v| if v.is_finite() { v } else { f64::NAN })
                        .collect(),
                    history: res
                        .residuals
                        .iter()
                        .map(|v| if v.is_finite() { *v } else { f64::MAX })
                        .collect(),
                    state: state.to_vec(),
                };
                if rec.qois.iter().any(|v| v.is_nan()) && rec.converged() {
                    return Err(StudyError::Other(format!(
                        "a quantity of interest is not finite at {theta:?}"
                    )));
                }
                let fields: Vec<f64> = res.displacements.iter().flatten().copied().collect();
                if study.output.vtu.unwrap_or(false) {
                    let path = dir.join("vtu").join(format!(
                        "{}.vtm",
                        store
                            .lock()
                            .map_err(|_| StudyError::Other("store lock poisoned".into()))?
                            .field_path(theta)
                            .file_stem()
                            .map_or("run".into(), |s| s.to_string_lossy().into_owned())
                    ));
                    alea_latin::output::write_run(&path, &solver, &res)?;
                }
                store
                    .lock()
                    .map_err(|_| StudyError::Other("store lock poisoned".into()))?
                    .commit(&rec, &fields)?;
                progress.finished(&rec);
                Ok(rec)
            })
            .collect();
        for r in results {
            let rec = r?;
            computed += 1;
            by_key.insert(point_key(&rec.params), rec);
        }
        finished_order.extend(members);
    }
    progress.end();
    let records = points
        .iter()
        .map(|p| {
            by_key
                .remove(&point_key(p))
                .ok_or_else(|| StudyError::Other("a run is missing".into()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(StudyRuns {
        records,
        computed,
        resumed: done_before,
        setup_seconds: solver.setup_seconds,
        solve_seconds: t0.elapsed().as_secs_f64(),
        solver,
    })
}
