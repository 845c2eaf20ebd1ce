//! When a run stops and what it is called ([`RunStatus`]). The indicator is relative to the
//! size of the iterates, so on its own it cannot tell convergence from a floating substructure
//! drifting away (the iterates grow, the indicator shrinks). When `eta < tol`, the run is
//! **converged** only if every substructure is also in equilibrium under its loads and the
//! local-stage interface forces and no floating substructure moved rigidly by more than a bound
//! (module [`crate::equilibrium`], options `equilibrium_tolerance` and `max_rigid_motion`);
//! otherwise it goes on for a few iterations ([`UNBALANCED_ITERATIONS`]) and ends as
//! [`RunStatus::NoEquilibrium`]. A non-finite indicator ends it as [`RunStatus::Diverged`]. A
//! run that reaches `max_iterations` is not converged, or has no equilibrium when a
//! substructure drifts beyond the bound, or when its sampled imbalance did not decrease over the
//! second half of the run ([`persistent_imbalance`]) **and** no interface forces admitted by
//! the laws can balance its loads in its free rigid modes (the certificate of module
//! `existence`; without it a stagnating run is only "not converged").

use rayon::prelude::*;

use super::condensed::RunCondensed;
use super::{InterfaceState, LatinSolver, Run, SubState};
use crate::{RunResult, RunStatus, SubEquilibrium};

/// The convergence watch of one run.
pub(super) struct Monitor {
    /// Iterations spent below the tolerance without equilibrium (see `equilibrium`).
    unbalanced: usize,
    /// The equilibrium check that stopped the run.
    equilibrium: Option<Vec<SubEquilibrium>>,
    /// (iteration, largest relative imbalance), sampled along the run: tells a run that
    /// cannot balance its loads from a slow one when the iteration limit is reached.
    imbalance: Vec<(usize, f64)>,
    /// Some substructure has free rigid modes (otherwise nothing is sampled).
    floating: bool,
    /// Iterations between two samples.
    stride: usize,
}

impl Monitor {
    /// Nothing seen yet.
    pub(super) fn new(solver: &LatinSolver) -> Self {
        Monitor {
            unbalanced: 0,
            equilibrium: None,
            imbalance: Vec::new(),
            floating: solver.subs.iter().any(|op| op.rigid.num_free() > 0),
            stride: (solver.options.max_iterations / 100).max(10),
        }
    }

    /// Records the indicator `eta` of `iteration` in the run's residual history; returns the
    /// run's final status when it stops here (diverged, converged or without equilibrium).
    pub(super) fn check(
        &mut self,
        solver: &LatinSolver,
        run: &mut Run<'_>,
        iteration: usize,
        eta: f64,
    ) -> Option<RunStatus> {
        let (istate, sstate, load_factors) = (&run.istate, &run.sstate, &run.input.load_factors);
        let cond = run.condensed.as_slice();
        if !eta.is_finite() {
            run.residuals.push(f64::NAN);
            return Some(RunStatus::Diverged);
        }
        run.residuals.push(eta);
        if self.floating && iteration % self.stride == self.stride - 1 {
            let eq = solver.equilibrium(istate, sstate, cond, load_factors);
            let worst = eq.iter().map(|e| e.relative_imbalance).fold(0.0, f64::max);
            self.imbalance.push((iteration, worst));
        }
        if eta < solver.options.tolerance {
            // Small indicator: converged only if every substructure is in equilibrium.
            let eq = solver.equilibrium(istate, sstate, cond, load_factors);
            let drift = eq
                .iter()
                .any(|e| e.relative_rigid_motion > solver.options.max_rigid_motion);
            if solver.balanced(&eq) {
                self.equilibrium = Some(eq);
                return Some(RunStatus::Converged);
            }
            self.unbalanced += 1;
            if drift || self.unbalanced > UNBALANCED_ITERATIONS {
                self.equilibrium = Some(eq);
                return Some(RunStatus::NoEquilibrium);
            }
        }
        None
    }

    /// The final status and equilibrium check of a run that stopped with `stopped` (`None`:
    /// at the iteration limit).
    pub(super) fn finish(
        self,
        solver: &LatinSolver,
        run: &Run<'_>,
        stopped: Option<RunStatus>,
    ) -> (RunStatus, Vec<SubEquilibrium>) {
        let mut status = stopped.unwrap_or(RunStatus::NotConverged);
        let equilibrium = match self.equilibrium {
            Some(eq) => eq,
            None => solver.equilibrium(
                &run.istate,
                &run.sstate,
                &run.condensed,
                &run.input.load_factors,
            ),
        };
        // A run stopped by the iteration limit while a floating substructure drifts away, or
        // stays out of balance without improving, has no static equilibrium rather than a slow
        // convergence.
        // A stagnating imbalance alone is no proof (a slow run stagnates too): it counts only
        // with the certificate that no admissible interface forces can balance the loads
        // (module `existence`).
        if status == RunStatus::NotConverged
            && (equilibrium
                .iter()
                .any(|e| e.relative_rigid_motion > solver.options.max_rigid_motion)
                || persistent_imbalance(
                    &self.imbalance,
                    run.residuals.len(),
                    solver.options.equilibrium_tolerance,
                ) && solver.equilibrium_excluded(&run.points, &run.input.load_factors))
        {
            status = RunStatus::NoEquilibrium;
        }
        (status, equilibrium)
    }
}

impl LatinSolver {
    /// A sentence naming the substructure whose equilibrium check fails worst, with its
    /// unbalanced force and moment (free directions) and its rigid motion; `None` when every
    /// substructure is within the bounds of the options.
    pub fn equilibrium_report(&self, r: &RunResult) -> Option<String> {
        let o = &self.options;
        let badness = |e: &SubEquilibrium| {
            (e.relative_imbalance / o.equilibrium_tolerance)
                .max(e.relative_rigid_motion / o.max_rigid_motion)
        };
        let (s, e) = r
            .equilibrium
            .iter()
            .enumerate()
            .filter(|(_, e)| !e.holds(o.equilibrium_tolerance, o.max_rigid_motion))
            .max_by(|a, b| badness(a.1).total_cmp(&badness(b.1)))?;
        let dim = self.model(s).mesh.dim;
        let force = e.force[..dim]
            .iter()
            .map(|v| format!("{v:.4e}"))
            .collect::<Vec<_>>()
            .join(", ");
        let moment = if dim == 2 {
            format!("{:.4e}", e.moment[2])
        } else {
            format!(
                "({:.4e}, {:.4e}, {:.4e})",
                e.moment[0], e.moment[1], e.moment[2]
            )
        };
        Some(format!(
            "substructure '{}': unbalanced force ({force}), moment {moment} = {:.3e} of its load \
             (tolerance {:.1e}); rigid motion {:.3e} x the model size (bound {})",
            self.sub_name(s),
            e.relative_imbalance,
            o.equilibrium_tolerance,
            e.relative_rigid_motion,
            o.max_rigid_motion
        ))
    }

    /// True if every substructure satisfies both equilibrium bounds of the options.
    fn balanced(&self, eq: &[SubEquilibrium]) -> bool {
        eq.iter().all(|e| {
            e.holds(
                self.options.equilibrium_tolerance,
                self.options.max_rigid_motion,
            )
        })
    }

    /// Equilibrium of every substructure under its loads (with the run's load factors) and the
    /// local-stage interface forces, with its rigid motion (module `equilibrium`); with ranks,
    /// each substructure's from its owner (module `ranks`).
    fn equilibrium(
        &self,
        istate: &[InterfaceState],
        sstate: &[SubState],
        cond: &[Option<RunCondensed>],
        load_factors: &[Vec<f64>],
    ) -> Vec<SubEquilibrium> {
        let mut eq: Vec<SubEquilibrium> = self
            .subs
            .par_iter()
            .zip(sstate.par_iter())
            .enumerate()
            .map(|(s, (op, st))| {
                let rm = &op.rigid;
                if rm.num_free() == 0 || !self.owns(s) {
                    return SubEquilibrium::default();
                }
                let coords = &op.model.mesh.coords;
                let (mut g, mut scale) = rm.applied(load_factors.get(s).map(|v| v.as_slice()));
                for l in &op.links {
                    let fhat = &istate[l.iface].fhat[l.side];
                    for (p, (&m, f)) in l.proj.weights.iter().zip(fhat).enumerate() {
                        for (n, c) in l.proj.row(p) {
                            let mc = m * c;
                            let mf = [mc * f[0], mc * f[1], mc * f[2]];
                            rm.add_force(&coords[n], &mf, &mut g, &mut scale);
                        }
                    }
                }
                // The rigid moments of the displacement: from the interface data on a
                // condensed substructure (module `condensed`), else from `u`.
                let moments = || match (&self.condensed[s], cond.get(s).and_then(Option::as_ref)) {
                    (Some(cd), Some(rc)) => cd.moments(&rc.moments0, &st.v, &st.coarse_u),
                    _ => rm.moments(coords, &op.dofs.expand(&self.displacement(s, st))),
                };
                rm.finish(&g, scale, coords, moments, self.model_size)
            })
            .collect();
        let floating: Vec<bool> = self.subs.iter().map(|o| o.rigid.num_free() > 0).collect();
        self.share_equilibrium(&mut eq, &floating);
        eq
    }
}

/// True if the sampled imbalance of the second half of a run is above the tolerance and has
/// stagnated (its second-half minimum at least [`STAGNATION`] times its first-half one): the
/// loads are not balanced and the iteration does not bring them closer to balance. Measured:
/// a root pulled out of its slot (no equilibrium) keeps a second-half imbalance 1.04-1.08
/// times its first-half one, while its LATIN indicator may still fall a hundredfold (so the
/// indicator is no sign of convergence here); long chains of substructures without the coarse
/// problem (slow, but with an equilibrium) bring it down to 0.70-0.83 times, and are reported
/// as not converged rather than as having no equilibrium (tests `coarse.rs` and the study's
/// `no_equilibrium.rs`).
fn persistent_imbalance(samples: &[(usize, f64)], iterations: usize, tolerance: f64) -> bool {
    let min_of = |first: bool| {
        samples
            .iter()
            .filter(|(i, _)| (2 * i < iterations) == first)
            .map(|s| s.1)
            .fold(f64::INFINITY, f64::min)
    };
    let (early, late) = (min_of(true), min_of(false));
    early.is_finite() && late.is_finite() && late > tolerance && late >= STAGNATION * early
}

/// Ratio of the second-half to the first-half minimum above which a quantity of a run is said
/// to stagnate ([`persistent_imbalance`]).
const STAGNATION: f64 = 0.9;

/// Iterations a run may spend below the tolerance while some substructure is out of
/// equilibrium (within the rigid-motion bound) before it is reported as having no static
/// equilibrium: a true solution restores the balance within a few iterations.
const UNBALANCED_ITERATIONS: usize = 25;
