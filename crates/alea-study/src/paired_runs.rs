//! The paired solves of the error budget's mesh part (`[budget] refined_mesh`) and sliding part
//! (`[budget] large_sliding = true`), issue 36: the study's model and the other model (its
//! refined-mesh study, its large-sliding study) solved cold at the
//! [`design_size`](crate::budget::paired::design_size) design points of
//! [`design_points`], from which `crate::budget::paired`
//! makes the part.
//!
//! They belong to the **run phase**: the runner solves them after every design, adaptive,
//! confirmation and validation run, counted in the progress bar, each committed to the store as
//! it finishes, so a killed run resumes without solving again the stored ones and a second
//! `alea run` of a finished study solves none. The outputs (`alea report`, Python's
//! `alea.report`) read them ([`read`]) and never solve: a store without them (a study finished
//! by an older alea, or stopped before they were all solved) gives the part "not estimated:
//! run `alea run` again to solve the paired points".
//!
//! **Stored apart from the runs** (the store's tables `paired_models` and `paired_runs`, module
//! `store::paired`), keyed by the run hash of the model solved: they are solves of other models
//! (and the study's own solves among them are cold starts, where a design run at the same
//! point may be warm-started), so as rows of `runs` they would be taken for design runs of the
//! study's model. Keyed by run hash, the study's own solves are shared by the mesh and the
//! sliding parts, and every edit of the study file that keeps a model's runs keeps its paired
//! solves (their quantity values are mapped by the quantities' keys, as the runs').
//!
//! **How they are solved.** One model after the other (the study's on the runner's solver, the
//! other's solver built only when one of its solves is missing), the missing points of a model
//! in parallel on the rayon pool, each with [`RunContext::solve`] (cold, no error estimate, no
//! ParaView files): the same solves as before they were stored, so the parts are the same bit
//! for bit. Over MPI they are solved on rank 0 alone (the other ranks hold the study's solver
//! only, not the other model's): 2 (2 d + 3) solves, after the runs.

use std::collections::HashMap;
use std::sync::Mutex;
use std::time::Instant;

use alea_latin::LatinSolver;
use rayon::prelude::*;

use crate::StudyError;
use crate::budget::paired::{PairedCheck, PairedResult, PointValues, design_points};
use crate::solve::{RunContext, RunJob, RunSetup};
use crate::store::{PairedModel, RunRecord, Store, point_key, remap_quantities};
use crate::study::Study;

/// Why a part is not estimated when its paired solves are not all stored.
pub const NOT_SOLVED: &str = "run `alea run` again to solve the paired points";

/// The paired solves of a study's run ([`StudyRuns::paired`](crate::study_runs::StudyRuns)).
#[derive(Debug, Default)]
pub struct PairedSolves {
    /// The mesh part's check, or why it is not estimated (`None`: no `[budget] refined_mesh`).
    pub mesh: Option<PairedResult>,
    /// The sliding part's (`None`: no `[budget] large_sliding = true`).
    pub sliding: Option<PairedResult>,
    /// Paired solves computed by this invocation.
    pub computed: usize,
    /// Paired solves found in the store.
    pub resumed: usize,
    /// Wall-clock seconds of this invocation's paired solves (their solvers' set-up included).
    pub seconds: f64,
}

/// The models of the paired solves of `study`: the study itself, then its refined-mesh study,
/// then its large-sliding study; none without a paired part.
fn models(study: &Study) -> Vec<&Study> {
    let others: Vec<&Study> = [&study.refined, &study.large_sliding]
        .into_iter()
        .filter_map(|s| s.as_deref())
        .collect();
    if others.is_empty() {
        return others;
    }
    std::iter::once(study).chain(others).collect()
}

/// The number of paired solves of `study`.
pub fn count(study: &Study) -> usize {
    models(study).len() * design_points(study).len()
}

/// The stored solves of `model` by point key, as usable: a converged one with its values in the
/// model's quantity order, another with `None`; a converged one lacking a quantity's value is
/// left out (to be solved again).
fn usable(model: &Study, store: &Store) -> Result<HashMap<String, PointValues>, StudyError> {
    let wanted = &model.identity.quantities;
    Ok(store
        .paired_runs(&model.identity.run_hash)?
        .into_iter()
        .filter_map(|(key, row)| {
            if row.status != "converged" {
                return Some((key, None));
            }
            let stored: Vec<&str> = row.quantities.iter().map(String::as_str).collect();
            remap_quantities(&row.qois, &stored, wanted).map(|v| (key, Some(v)))
        })
        .collect())
}

/// The points of `points` that `model` still has to solve (none if its solver could not be
/// built: that is stored too).
fn todo(model: &Study, points: &[Vec<f64>], store: &Store) -> Result<Vec<Vec<f64>>, StudyError> {
    if let Some(PairedModel::Failed(_)) = store.paired_model(&model.identity.run_hash)? {
        return Ok(Vec::new());
    }
    let have = usable(model, store)?;
    Ok(points
        .iter()
        .filter(|p| !have.contains_key(&point_key(p)))
        .cloned()
        .collect())
}

/// The number of paired solves of `study` that need no solve (stored).
///
/// # Errors
/// On store errors.
pub fn settled(study: &Study, store: &Store) -> Result<usize, StudyError> {
    let points = design_points(study);
    let mut n = 0;
    for model in models(study) {
        n += points.len() - todo(model, &points, store)?.len();
    }
    Ok(n)
}

/// The record of a paired solve that failed (`why`).
fn failed(theta: &[f64], why: &str) -> RunRecord {
    RunRecord {
        status: format!("failed: {why}"),
        iterations: 0,
        residual: f64::MAX,
        seconds: 0.0,
        qois: Vec::new(),
        history: Vec::new(),
        state: Vec::new(),
        slide: None,
        params: theta.to_vec(),
    }
}

/// Nodes of a solver's model, over its substructures.
fn nodes(solver: &LatinSolver) -> usize {
    (0..solver.num_subs())
        .map(|k| solver.model(k).mesh.num_nodes())
        .sum()
}

/// Solves the paired solves of `study` missing from `store` (module doc), the study's own on
/// `solver`, committing each as it finishes and telling `finished` (also of the solves of a
/// model whose solver could not be built, which is stored instead); `stop`: as
/// [`RunContext::stop`]. Returns the solves computed and those found stored, and the seconds.
///
/// # Errors
/// [`StudyError::Interrupted`] when `stop` turned true (the finished solves are stored); store
/// errors.
pub fn run(
    study: &Study,
    store: &Mutex<Store>,
    solver: &LatinSolver,
    finished: &(dyn Fn(&RunRecord) + Sync),
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<(usize, usize, f64), StudyError> {
    let t0 = Instant::now();
    let lock = || store.lock().map_err(|_| StudyError::Poisoned("store"));
    let points = design_points(study);
    let (mut computed, mut resumed) = (0, 0);
    for model in models(study) {
        let pending = todo(model, &points, &*lock()?)?;
        resumed += points.len() - pending.len();
        if pending.is_empty() {
            continue;
        }
        let hash = model.identity.run_hash.as_str();
        let built;
        // A solver spread over ranks solves only with its group (the executor's runs): the
        // paired solves, on this rank alone, get a solver of their own.
        let solver = if std::ptr::eq(model, study) && solver.rank_count() == 1 {
            solver
        } else {
            match RunSetup::build(model) {
                Ok(setup) => {
                    built = setup.solver;
                    &*built
                }
                Err(e) => {
                    let why = e.to_string();
                    lock()?.set_paired_model(hash, &PairedModel::Failed(why.clone()))?;
                    for p in &pending {
                        finished(&failed(p, &format!("its model was not built: {why}")));
                    }
                    continue;
                }
            }
        };
        lock()?.set_paired_model(hash, &PairedModel::Nodes(nodes(solver)))?;
        let dir = lock()?.dir().to_path_buf();
        let ctx = RunContext {
            study: model,
            solver,
            cre: None,
            dir: &dir,
            stop,
            files: false,
        };
        let results: Vec<Result<(), StudyError>> = pending
            .par_iter()
            .map(|theta| {
                if stop() {
                    return Err(StudyError::Interrupted);
                }
                let job = RunJob {
                    theta: theta.clone(),
                    start: None,
                };
                let rec = match ctx.solve(&job) {
                    Ok(out) => out.rec,
                    Err(e) => failed(theta, &e.to_string()),
                };
                lock()?.commit_paired(hash, &rec, &model.identity.quantities)?;
                finished(&rec);
                Ok(())
            })
            .collect();
        computed += results.iter().filter(|r| r.is_ok()).count();
        results.into_iter().collect::<Result<(), _>>()?;
    }
    Ok((computed, resumed, t0.elapsed().as_secs_f64()))
}

/// The mesh and sliding parts' checks from the paired solves stored for `study`, solving
/// nothing: per part, `None` without it, else the check, or why it is not estimated (the error
/// that kept a model's solver from being built, or [`NOT_SOLVED`] when a solve is missing).
///
/// # Errors
/// On store errors.
pub fn read(
    study: &Study,
    store: &Store,
) -> Result<(Option<PairedResult>, Option<PairedResult>), StudyError> {
    let points = design_points(study);
    let values = |model: &Study| -> Result<Result<(Vec<PointValues>, usize), String>, StudyError> {
        let n = match store.paired_model(&model.identity.run_hash)? {
            None => return Ok(Err(NOT_SOLVED.to_string())),
            Some(PairedModel::Failed(why)) => return Ok(Err(why)),
            Some(PairedModel::Nodes(n)) => n,
        };
        let have = usable(model, store)?;
        let v: Option<Vec<PointValues>> = points
            .iter()
            .map(|p| have.get(&point_key(p)).cloned())
            .collect();
        Ok(v.map(|v| (v, n)).ok_or_else(|| NOT_SOLVED.to_string()))
    };
    let part = |other: &Option<Box<Study>>| -> Result<Option<PairedResult>, StudyError> {
        let Some(other) = other.as_deref() else {
            return Ok(None);
        };
        let (coarse, n0) = match values(study)? {
            Ok(v) => v,
            Err(why) => return Ok(Some(Err(why))),
        };
        let (fine, n1) = match values(other)? {
            Ok(v) => v,
            Err(why) => return Ok(Some(Err(why))),
        };
        Ok(Some(Ok(PairedCheck::from_solves(
            study.qois.len(),
            points.clone(),
            &coarse,
            &fine,
            (n0, n1),
        ))))
    };
    Ok((part(&study.refined)?, part(&study.large_sliding)?))
}
