//! Load histories: a sequence of load steps, each a LATIN solve that starts from the end of
//! the previous one with the friction state carried over.
//!
//! Friction is path-dependent: press-then-slide, or loading and unloading a fretting contact,
//! have answers that a single proportional solve cannot give. A history is a list of steps
//! `k = 1..K`, each with its own loads (load factors) and, when the imposed displacements
//! change, its own [`LatinSolver`] (same meshes and interfaces, other prescribed values).
//!
//! **State carried from step to step.** The interface state at the end of step `k` is the
//! local-stage pair `(W_hat, F_hat)` of both sides of every interface ([`LocalState`]); it is
//! the initial state of step `k + 1` (its first linear stage starts from it) and it defines the
//! tangential jump `j0 = [W_hat]_t = (W_hat_2 - W_hat_1) - ((W_hat_2 - W_hat_1).n) n` of each
//! point at the start of the step.
//!
//! **Incremental Coulomb law.** Within step `k + 1` slip is the increment of the tangential jump
//! within the step, `d_t = [W]_t - j0`: a point sticks where `|Phi_t| < mu Phi_n` and then
//! `[W]_t = j0` (it stays where the previous step left it), and slips otherwise with
//! `d_t = -lambda Phi_t`, `lambda >= 0`. The normal part is path-independent (the unilateral
//! condition on the total gap `g = [W].n + g0`). The closed-form local stage is the law's own,
//! shifted by `j0` ([`crate::law::local_stage_from`]). This is the backward-Euler (one
//! increment per step) form of the rate law: a step whose slip direction changes inside it
//! is resolved only at its end, so a loop is followed by steps small enough for the slip
//! direction to be constant within each.
//!
//! **What a step reports of the path is its own**: its slip `[W_hat]_t - j0`, its friction
//! dissipation `-int ([W_hat]_t - j0) . Phi dS` and the work of its interface forces
//! `int ([W_hat] + g0 n - j0) . Phi dS` are measured from the same origin `j0` the law used
//! ([`step_origins`]; the output of a step writes the total jump `[W_hat]_t` beside its slip).
//!
//! The first step (no previous state) is the static, total-slip law of [`crate::law`], which is
//! the incremental law from the unloaded state. A step that ends not converged stops the
//! history: its state is not an equilibrium to start from, so the later steps are not run.
//!
//! The pairing is that of the initial configuration in every step (small sliding: the slip
//! accumulated over the history must stay small against the mesh size).

use alea_mesh::vec3::dot;

use crate::{LatinError, LatinSolver, LocalState, PointData, RunInput, RunResult, RunStatus};
use std::sync::Arc;

type V3 = [f64; 3];

/// Per interface and point, the tangential part of the local-stage jump
/// `[W_hat] = W_hat_2 - W_hat_1` of `state`, with the normals of `points`.
pub(crate) fn slip_origins(state: &LocalState, points: &[Vec<PointData>]) -> Vec<Vec<V3>> {
    state
        .what
        .iter()
        .zip(points)
        .map(|(w, pts)| {
            w[0].iter()
                .zip(&w[1])
                .zip(pts)
                .map(|((a, b), p)| {
                    let j = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
                    let jn = dot(&j, &p.normal);
                    [
                        j[0] - jn * p.normal[0],
                        j[1] - jn * p.normal[1],
                        j[2] - jn * p.normal[2],
                    ]
                })
                .collect()
        })
        .collect()
}

impl RunResult {
    /// The local-stage state `(W_hat, F_hat)` at the end of this run: the start of the next
    /// load step ([`RunInput::previous_step`]).
    pub fn end_state(&self) -> LocalState {
        if let Some(state) = &self.split_state {
            return (**state).clone();
        }
        LocalState {
            what: self.interfaces.iter().map(|i| i.what.clone()).collect(),
            fhat: self.interfaces.iter().map(|i| i.fhat.clone()).collect(),
        }
    }
}

impl LatinSolver {
    /// Runs the load steps `steps` in order on this solver (steps that differ only by their
    /// loads), each from the end state of the previous one; see [`run_history`].
    pub fn run_steps(&self, steps: &[RunInput]) -> Result<Vec<RunResult>, LatinError> {
        let pairs: Vec<(&LatinSolver, RunInput)> =
            steps.iter().map(|s| (self, s.clone())).collect();
        run_history(&pairs)
    }
}

/// Runs a load history: each `(solver, input)` is one step, solved by `solver` (the steps'
/// solvers share meshes and interfaces and may differ by their prescribed displacements) from
/// the end state of the previous step ([`RunInput::previous_step`], set here; the first step
/// keeps its own). Returns one result per step run: the history stops after the first step
/// that is not converged.
pub fn run_history(steps: &[(&LatinSolver, RunInput)]) -> Result<Vec<RunResult>, LatinError> {
    let mut results: Vec<RunResult> = Vec::with_capacity(steps.len());
    for (k, (solver, input)) in steps.iter().enumerate() {
        let mut input = input.clone();
        if let Some(prev) = results.last() {
            if prev.status != RunStatus::Converged {
                break;
            }
            if solver.interface_sizes() != steps[k - 1].0.interface_sizes() {
                return Err(LatinError::Invalid(format!(
                    "load step {}: its interfaces differ from those of step {k}",
                    k + 1
                )));
            }
            input.previous_step = Some(Arc::new(prev.end_state()));
        }
        results.push(solver.run_shared(&input)?);
    }
    Ok(results)
}

/// The slip origin `j0` of every point of every interface of the step whose run is `cur`:
/// the tangential jump `[W_hat]_t` at the end of the previous step `prev` (same pairing), with
/// the normals of `cur`; zero for the first step (`prev = None`: the unloaded state). This is
/// the origin the incremental law measured the step's slip from ([`crate::law::local_stage_from`]).
pub fn step_origins(prev: Option<&RunResult>, cur: &RunResult) -> Vec<Vec<V3>> {
    cur.interfaces
        .iter()
        .enumerate()
        .map(|(i, it)| {
            (0..it.points.len())
                .map(|p| match prev.and_then(|r| r.interfaces.get(i)) {
                    Some(old) => tangential(
                        old.what[0][p],
                        old.pairing.to_points(1, old.what[1][p]),
                        it.points[p].normal,
                    ),
                    None => [0.0; 3],
                })
                .collect()
        })
        .collect()
}

/// Tangential part of `b - a` for the normal `n`.
pub(crate) fn tangential(a: V3, b: V3, n: V3) -> V3 {
    let j = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let jn = dot(&j, &n);
    [j[0] - jn * n[0], j[1] - jn * n[1], j[2] - jn * n[2]]
}

impl crate::InterfaceResult {
    /// The slip of point `p` within its step: `[W_hat]_t - j0`, with `j0 = origin[p]` the
    /// tangential jump at the start of the step ([`step_origins`]; zero: since the unloaded
    /// state, the total tangential jump).
    pub fn step_slip(&self, p: usize, origin: &[V3]) -> V3 {
        let jt = tangential(
            self.what[0][p],
            self.pairing.to_points(1, self.what[1][p]),
            self.points[p].normal,
        );
        let j0 = origin.get(p).copied().unwrap_or([0.0; 3]);
        [jt[0] - j0[0], jt[1] - j0[1], jt[2] - j0[2]]
    }

    /// Energy dissipated by friction within the step, `-int ([W_hat]_t - j0) . Phi dS >= 0`
    /// (`origin`: `j0` per point, [`step_origins`]).
    pub fn step_friction_dissipation(&self, origin: &[V3]) -> f64 {
        (0..self.points.len())
            .map(|p| -self.weights[p] * dot(&self.step_slip(p, origin), &self.side2_force(p)))
            .sum()
    }

    /// Work of the interface forces on the jump of the step,
    /// `int ([W_hat] + g0 n - j0) . Phi dS` (`origin`: `j0` per point, [`step_origins`]): the
    /// normal part vanishes by complementarity, so for Coulomb contact it is minus the step's
    /// friction dissipation. With `j0 = 0` it is [`crate::InterfaceResult::work`].
    pub fn step_work(&self, origin: &[V3]) -> f64 {
        (0..self.points.len())
            .map(|p| {
                let j = self.jump(p);
                let j0 = origin.get(p).copied().unwrap_or([0.0; 3]);
                let d = [j[0] - j0[0], j[1] - j0[1], j[2] - j0[2]];
                self.weights[p] * dot(&d, &self.side2_force(p))
            })
            .sum()
    }
}

/// Energy dissipated by friction within one load step on interface result `cur`:
/// `-int ([W_hat] - j0)_t . Phi_t dS >= 0`, with `j0` the tangential jump at the end of the
/// previous step (`prev`, the same interface; `None`: the unloaded state, `j0 = 0`). With
/// `prev = None` this is [`crate::InterfaceResult::friction_dissipation`].
pub fn step_friction_dissipation(
    prev: Option<&crate::InterfaceResult>,
    cur: &crate::InterfaceResult,
) -> f64 {
    let origin: Vec<V3> = (0..cur.points.len())
        .map(|i| match prev {
            Some(p) => tangential(p.what[0][i], p.what[1][i], cur.points[i].normal),
            None => [0.0; 3],
        })
        .collect();
    cur.step_friction_dissipation(&origin)
}
