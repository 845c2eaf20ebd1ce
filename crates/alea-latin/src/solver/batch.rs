//! Batched runs (issue 20, item 1): several runs of one solver advance in lockstep. Every run
//! of a solver shares the factorisation of each substructure's `A0` (a Young's-modulus factor
//! `alpha_s` only scales the right-hand side and the search direction, module
//! `linear_stage`), so one iteration of a batch makes, per substructure, **one** triangular
//! solve `A0 [u_1 .. u_b] = [r_1 .. r_b]` with `b` columns - one pass over the factor for all
//! runs still iterating - then each run's coarse correction, relaxation, local stage,
//! acceleration and convergence check exactly as [`LatinSolver::run_shared`] does. A run that
//! stops (converged, diverged, without equilibrium) leaves the batch; the others go on with
//! fewer columns. A run alone is a batch of one ([`LatinSolver::run_shared`]): this is the
//! one LATIN loop.
//!
//! **Same results as one at a time.** Column `j` of a multi-column solve is the solve of `r_j`
//! alone in exact arithmetic. With a simplicial factor (2D substructures up to 50 flops
//! per factor entry, `alea_fem::FactorKind`) the multi-column kernel makes, column by column,
//! the operations of the single-column solve in the same order, so a batched run is **bitwise**
//! the run alone (`tests/batch.rs`; the 2D turbine, `cargo bench -p alea-study --bench
//! batch_turbine`). With a supernodal factor (3D) faer accumulates a block of columns in
//! another order than one column (matrix-matrix against matrix-vector products): a batched run
//! can then differ from the same run alone by rounding in each solve, which the iteration
//! carries to the level of the stopping tolerance. The coarse correction and the local stage
//! are per run and the same code as alone. The result of a run depends on which runs share its
//! batch only through that rounding, never on the thread
//! count: the substructures' solves run in parallel, each on its own columns.

use std::time::Instant;

use alea_fem::SolveScratch;
use rayon::prelude::*;

use super::SubOperator;
use super::acceleration::Acceleration;
use super::condensed::Condensed;
use super::convergence::Monitor;
use super::linear_stage::{assemble_rhs, condensed_fields, interface_fields};
use super::{InterfaceState, LatinSolver, Run, RunInput, SubState};
use crate::{LatinError, RunResult, RunStatus};

/// One run's column of a substructure's block: its state of the substructure, its interface
/// state, constant right-hand side, Young's-modulus factor and, on a condensed substructure,
/// its constant interface response `w0`.
type Column<'r> = (
    &'r mut SubState,
    &'r [InterfaceState],
    &'r [f64],
    f64,
    Option<&'r [f64]>,
);

/// Per substructure: the solve's scratch and the block of right-hand sides.
type BlockScratch = (Option<SolveScratch>, Vec<f64>);

/// One run of a batch with its iteration state.
struct Lane<'a> {
    run: Run<'a>,
    acceleration: Acceleration<'a>,
    monitor: Monitor,
    stopped: Option<RunStatus>,
    done: bool,
}

impl LatinSolver {
    /// Runs the LATIN iteration for every input of `inputs` together (module doc); the
    /// results in input order. An input that does not start (invalid) gets its error, the
    /// others run. On a model cut into subdomains the inputs and results are the user's
    /// (module [`super::split`]).
    pub fn run_batch(&self, inputs: &[RunInput]) -> Vec<Result<RunResult, LatinError>> {
        match &self.split {
            Some(split) => split.run_batch(self, inputs),
            None => self.run_solved(inputs),
        }
    }

    /// [`LatinSolver::run_batch`] on the solved substructures and interfaces (the
    /// subdomains and the cuts when the model is split).
    pub(super) fn run_solved(&self, inputs: &[RunInput]) -> Vec<Result<RunResult, LatinError>> {
        if inputs
            .iter()
            .any(|i| i.cell_young.iter().any(Option::is_some))
        {
            // Each such run has operators of its own (module `cell_young`): nothing to share.
            return inputs
                .iter()
                .map(|i| match i.cell_young.iter().any(Option::is_some) {
                    true => self.run_with_cell_young(i),
                    false => self
                        .run_solved(std::slice::from_ref(i))
                        .pop()
                        .expect("a batch of one gives one result"),
                })
                .collect();
        }
        // A solver spread over ranks runs one batch at a time (module `ranks`).
        let _turn = self.ranks.as_ref().map(|r| r.turn());
        let t_start = Instant::now();
        let mut lanes: Vec<Result<Lane<'_>, LatinError>> = inputs
            .iter()
            .map(|input| {
                let run = self.start(input)?;
                Ok(Lane {
                    acceleration: Acceleration::new(self, &run.alpha, run.acceleration),
                    monitor: Monitor::new(self),
                    run,
                    stopped: None,
                    done: false,
                })
            })
            .collect();
        // Per substructure, the solve's scratch and the block of right-hand sides, allocated
        // once for the batch (not in every iteration).
        let mut scratch: Vec<BlockScratch> = self
            .subs
            .iter()
            .map(|op| {
                let Some(chol) = &op.chol else {
                    return (None, Vec::new());
                };
                let block = Vec::with_capacity(op.dofs.num_free() * inputs.len());
                (Some(chol.solve_scratch(inputs.len())), block)
            })
            .collect();
        let max_iterations = lanes
            .iter()
            .filter_map(|l| l.as_ref().ok())
            .map(|l| l.run.max_iterations)
            .max()
            .unwrap_or(0);
        for iteration in 0..max_iterations {
            let mut active: Vec<&mut Lane<'_>> = lanes
                .iter_mut()
                .filter_map(|l| l.as_mut().ok())
                .filter(|l| !l.done && iteration < l.run.max_iterations)
                .collect();
            if active.is_empty() {
                break;
            }
            let x_in: Vec<Option<Vec<f64>>> = active
                .iter_mut()
                .map(|l| {
                    l.acceleration.apply_pending(&mut l.run.istate);
                    l.acceleration.input(&l.run.istate)
                })
                .collect();
            let t0 = Instant::now();
            let solve_time = self.batch_solves(&mut active, &mut scratch);
            self.share_fields(active.iter_mut().map(|l| &mut l.run.sstate).collect());
            let share = 1.0 / active.len() as f64;
            for l in active.iter_mut() {
                self.correct_and_relax(&mut l.run, iteration == 0);
            }
            let linear = t0.elapsed().as_secs_f64();
            for (l, x) in active.iter_mut().zip(x_in) {
                l.run.timings.linear += linear * share;
                l.run.timings.triangular_solves += solve_time * share;
                let (eta, eta_iterates) = self.local_stage(&mut l.run);
                l.stopped = l.monitor.check(self, &mut l.run, iteration, eta);
                if l.stopped.is_some() {
                    l.done = true;
                } else {
                    l.acceleration.step(x, eta_iterates, &l.run.istate);
                }
            }
        }
        // The volume solutions of the condensed substructures, one solve for all the runs.
        let mut runs: Vec<&mut Run<'_>> = lanes
            .iter_mut()
            .filter_map(|l| l.as_mut().ok())
            .map(|l| &mut l.run)
            .collect();
        self.recover_volumes(&mut runs);
        lanes
            .into_iter()
            .map(|lane| {
                let l = lane?;
                let (status, equilibrium) = l.monitor.finish(self, &l.run, l.stopped);
                Ok(self.finish_run(l.run, status, equilibrium, t_start))
            })
            .collect()
    }

    /// The plain linear stage of every active run: per substructure (in parallel) the
    /// right-hand sides of all runs as the columns of one block, one solve, then each run's
    /// `W`, `F`. Returns the seconds of the triangular solves (summed over substructures).
    /// With ranks, only this rank's substructures (module `ranks`).
    fn batch_solves(&self, active: &mut [&mut Lane<'_>], scratch: &mut [BlockScratch]) -> f64 {
        let nsub = self.subs.len();
        // Per substructure: each run's state of it, with what its right-hand side needs.
        let mut per_sub: Vec<Vec<Column<'_>>> = (0..nsub).map(|_| Vec::new()).collect();
        for l in active.iter_mut() {
            let Run {
                sstate,
                istate,
                base,
                alpha,
                condensed,
                ..
            } = &mut l.run;
            for (s, st) in sstate.iter_mut().enumerate() {
                let w0 = condensed[s].as_ref().map(|c| c.w0.as_slice());
                per_sub[s].push((st, istate.as_slice(), base[s].as_slice(), alpha[s], w0));
            }
        }
        self.subs
            .par_iter()
            .zip(self.condensed.par_iter())
            .zip(per_sub.par_iter_mut())
            .zip(scratch.par_iter_mut())
            .map(|(((op, cd), cols), (scratch, block))| {
                let (Some(chol), Some(scratch)) = (&op.chol, scratch) else {
                    // Another rank's substructure (module `ranks`).
                    return 0.0;
                };
                if let Some(cd) = cd {
                    return condensed_block(op, cd, cols);
                }
                let n = cols.first().map_or(0, |c| c.0.rhs.len());
                if n == 0 {
                    for (st, istate, _, alpha, _) in cols.iter_mut() {
                        interface_fields(op, st, istate, *alpha);
                    }
                    return 0.0;
                }
                block.clear();
                block.resize(n * cols.len(), 0.0);
                for ((_, istate, base, alpha, _), r) in cols.iter().zip(block.chunks_exact_mut(n)) {
                    assemble_rhs(op, istate, base, *alpha, r);
                }
                let t0 = Instant::now();
                // The last iterate is the start of a single-precision factor's refinement step
                // (module `precision`); a double-precision factor just solves.
                let previous: Vec<&[f64]> = cols.iter().map(|c| c.0.rhs.as_slice()).collect();
                chol.solve_near(block, &previous, scratch);
                let t = t0.elapsed().as_secs_f64();
                for ((st, istate, _, alpha, _), u) in cols.iter_mut().zip(block.chunks_exact(n)) {
                    st.rhs.copy_from_slice(u);
                    interface_fields(op, st, istate, *alpha);
                }
                t
            })
            .sum()
    }
}

/// The condensed linear stage of one substructure for every active run of a batch: the runs'
/// interface data as the columns of one block, one dense product `W = w0 + H v` for all
/// (each column's bits those of the run alone, `Condensed::apply`), then each run's `W`, `F`.
/// Returns the seconds of the product.
fn condensed_block(op: &SubOperator, cd: &Condensed, cols: &mut [Column<'_>]) -> f64 {
    let n = cd.n;
    let mut v = vec![0.0; n * cols.len()];
    let mut w = vec![0.0; n * cols.len()];
    for ((_, istate, _, alpha, w0), (vj, wj)) in cols.iter().zip(
        v.chunks_exact_mut(n.max(1))
            .zip(w.chunks_exact_mut(n.max(1))),
    ) {
        cd.gather(&op.links, istate, *alpha, vj);
        if let Some(w0) = w0 {
            wj.copy_from_slice(w0);
        }
    }
    let t0 = Instant::now();
    cd.apply(&v, &mut w);
    let t = t0.elapsed().as_secs_f64();
    for ((st, istate, _, alpha, _), (vj, wj)) in cols
        .iter_mut()
        .zip(v.chunks_exact(n.max(1)).zip(w.chunks_exact(n.max(1))))
    {
        st.v.copy_from_slice(vj);
        st.wi.copy_from_slice(wj);
        condensed_fields(op, cd, st, istate, *alpha);
    }
    t
}
