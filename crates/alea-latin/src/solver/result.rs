//! Assembly of a finished run's [`RunResult`] (the last linear stage's displacements, the
//! interface fields of both stages, status and equilibrium check).

use std::time::Instant;

use rayon::prelude::*;

use super::{LatinSolver, Run};
use crate::{InterfaceResult, RunResult, RunStatus, SubEquilibrium};

impl LatinSolver {
    /// The result of a run that ended with `status`; `t_start`: when the run started.
    pub(super) fn finish_run(
        &self,
        mut run: Run<'_>,
        status: RunStatus,
        equilibrium: Vec<SubEquilibrium>,
        t_start: Instant,
    ) -> RunResult {
        // Final fields: the last linear stage's displacement (recovered from its interface
        // data on a condensed substructure, module `condensed`).
        self.recover_volumes(&mut [&mut run]);
        // With ranks, each from its owner (module `ranks`).
        let mut displacements: Vec<Vec<f64>> = self
            .subs
            .par_iter()
            .zip(run.sstate.par_iter())
            .enumerate()
            .map(|(s, (op, st))| match self.owns(s) {
                true => op.dofs.expand(&self.displacement(s, st)),
                false => Vec::new(),
            })
            .collect();
        self.share_displacements(&mut displacements);
        let points = std::mem::take(&mut run.points);
        let interfaces: Vec<InterfaceResult> = self
            .ifaces
            .iter()
            .zip(run.istate.iter())
            .zip(points)
            .map(|((op, st), pts)| {
                let side = |s: usize| &run.sstate[op.sub[s]];
                InterfaceResult {
                    name: op.name.clone(),
                    law: op.law.name(),
                    subs: op.sub,
                    nodes: [0, 1].map(|s| {
                        let proj = &op.pairing.sides[s];
                        (0..proj.len()).map(|p| proj.main_node(p)).collect()
                    }),
                    pairing: op.pairing.clone(),
                    points: pts,
                    weights: op.weights.clone(),
                    w: [side(0).w[op.link[0]].clone(), side(1).w[op.link[1]].clone()],
                    f: [side(0).f[op.link[0]].clone(), side(1).f[op.link[1]].clone()],
                    what: st.what.clone(),
                    what_prev: st.what_prev.clone(),
                    fhat: st.fhat.clone(),
                    status: st.status.clone(),
                }
            })
            .collect();
        let Run {
            alpha,
            residuals,
            mut timings,
            ..
        } = run;
        timings.total = t_start.elapsed().as_secs_f64();
        RunResult {
            status,
            iterations: residuals.len(),
            residuals,
            displacements,
            interfaces,
            young_factors: alpha,
            cell_young: Vec::new(),
            equilibrium,
            timings,
            split_state: None,
        }
    }
}
