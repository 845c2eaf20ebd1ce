//! A study's model evaluated point by point, for a caller outside the study (issue 39: `alea
//! serve`, the UM-Bridge server of the `alea` binary).
//!
//! The model is the study's: its inputs are the study's parameters in the study file's order
//! (the KL variables of its random fields appended, as everywhere), its outputs its quantities
//! of interest. A [`ModelSession`] holds the study directory's lock, its store and the solver
//! built once (factorisations shared by every evaluation), so that each evaluated point is a
//! run of the study like any other:
//!
//! - a point within round-off of a stored run is answered from the store, solving nothing
//!   (module `points`; a session restarted after a kill answers every finished point so);
//! - the points of one [`ModelSession::evaluate`] call are solved together - generation by
//!   generation of the schedule over them, in groups that share their triangular solves - each
//!   warm-started from its nearest converged runs among those of the store and of the earlier
//!   calls (module `runner`), and committed to the store as each group finishes;
//! - a point the model cannot take (a modulus that is not positive there, a wrong number of
//!   values, a value that is not finite) and a run that does not converge or has no equilibrium
//!   are answers of their own ([`PointAnswer`]), never an error of the session.
//!
//! What differs from `alea run`: the points come from the caller, so the warm starts depend on
//! the order in which they were asked (the values differ by the solver's tolerance, not more).

use std::path::Path;

use crate::StudyError;
use crate::lock::StudyLock;
use crate::points::PointIndex;
use crate::runner::{Progress, Runner};
use crate::store::point_key;
use crate::study::Study;

/// The answer for one point.
#[derive(Clone, Debug, PartialEq)]
pub enum PointAnswer {
    /// The quantities of interest of the converged run, in the study's order.
    Values(Vec<f64>),
    /// The run did not converge, or the model has no equilibrium there: its status (with the
    /// cause), the last residual and the iterations it took. Stored like every run.
    Failed {
        /// The run's status as the study reports it (`"not converged"`, `"no equilibrium:
        /// ..."`).
        status: String,
        /// The last LATIN residual.
        residual: f64,
        /// LATIN iterations over all load steps.
        iterations: usize,
    },
    /// The point was refused before any solve, and why.
    Invalid(String),
}

/// The study's model, open for evaluations (module doc).
pub struct ModelSession<'a> {
    runner: Runner<'a>,
    index: PointIndex,
    _lock: StudyLock,
}

impl<'a> ModelSession<'a> {
    /// Opens the study directory `dir` for `study` (its store kept when the study's runs are
    /// those of its previous version, discarded with `restart`), taking its lock (`command`
    /// names the holder for another process that finds it taken) and building the solver.
    pub fn open(
        study: &'a Study,
        dir: &'a Path,
        restart: bool,
        command: &str,
        progress: &'a dyn Progress,
    ) -> Result<Self, StudyError> {
        let lock = StudyLock::acquire(dir, command)?;
        if let Some(previous) = lock.previous() {
            progress.note(&format!(
                "took over the lock of {} left by {previous}, which is no longer running",
                dir.display()
            ));
        }
        let (runner, index) = Runner::open(study, dir, restart, progress, true)?;
        Ok(ModelSession {
            runner,
            index,
            _lock: lock,
        })
    }

    /// The number of inputs: the study's parameters.
    pub fn input_size(&self) -> usize {
        self.runner.study.params.names.len()
    }

    /// The number of outputs: the study's quantities of interest.
    pub fn output_size(&self) -> usize {
        self.runner.study.qois.len()
    }

    /// Runs stored in the directory (this session's included).
    pub fn stored_runs(&self) -> usize {
        self.runner.by_key.len()
    }

    /// The answers for `points`, in their order: the stored ones read, the others solved
    /// together (module doc). An error only for what stops the session itself (the store
    /// cannot be written, the user interrupted).
    pub fn evaluate(&mut self, points: &[Vec<f64>]) -> Result<Vec<PointAnswer>, StudyError> {
        let d = self.input_size();
        let study = self.runner.study;
        let mut answers: Vec<Option<PointAnswer>> = vec![None; points.len()];
        let mut canonical: Vec<Option<Vec<f64>>> = vec![None; points.len()];
        for (k, p) in points.iter().enumerate() {
            if p.len() != d {
                answers[k] = Some(PointAnswer::Invalid(format!(
                    "{} values for the {d} parameters of the study ({})",
                    p.len(),
                    study.params.names.join(", ")
                )));
            } else if let Some(i) = p.iter().position(|v| !v.is_finite()) {
                answers[k] = Some(PointAnswer::Invalid(format!(
                    "parameter '{}' is {}, not a finite number",
                    study.params.names[i], p[i]
                )));
            } else if let Err(e) = study.check_point(&self.runner.solver, p) {
                answers[k] = Some(PointAnswer::Invalid(e.to_string()));
            } else {
                canonical[k] = Some(self.index.canonical(p));
            }
        }
        let todo: Vec<Vec<f64>> = canonical.iter().flatten().cloned().collect();
        self.runner.run_points(&todo)?;
        for (answer, point) in answers.iter_mut().zip(&canonical) {
            let Some(p) = point else { continue };
            let rec = self
                .runner
                .by_key
                .get(&point_key(p))
                .ok_or_else(|| StudyError::Internal("an evaluated run is missing".into()))?;
            *answer = Some(if rec.converged() {
                PointAnswer::Values(rec.qois.clone())
            } else {
                PointAnswer::Failed {
                    status: rec.status.clone(),
                    residual: rec.residual,
                    iterations: rec.iterations,
                }
            });
        }
        Ok(answers.into_iter().flatten().collect())
    }
}
