//! The local stage (per interface point, in parallel; closed form of [`crate::law`]) and the
//! error indicator, the k-weighted distance between the two half-iterates:
//! `eta = ||s - s_hat|| / (1/2 (||s|| + ||s_hat||))`,
//! `||s||^2 = sum_points m (k |W|^2 + |F|^2 / k)` over both sides of every interface.

use std::sync::Arc;
use std::time::Instant;

use rayon::prelude::*;

use super::{InterfaceOperator, InterfaceState, LatinSolver, Run, SubOperator, SubState};
use crate::PointData;
use crate::law::local_stage_from;

impl LatinSolver {
    /// The local stage of every interface from the last linear stage; returns the error
    /// indicator `eta`.
    pub(super) fn local_stage(&self, run: &mut Run<'_>) -> f64 {
        let t0 = Instant::now();
        let sums: Vec<[f64; 3]> = self
            .ifaces
            .par_iter()
            .zip(run.istate.par_iter_mut())
            .zip(run.points.par_iter())
            .enumerate()
            .map(|(i, ((op, st), pts))| {
                let origin = run.slip_origin.get(i).map(Vec::as_slice);
                local_stage(op, st, pts, origin, &self.subs, &run.sstate, &run.alpha)
            })
            .collect();
        run.timings.local += t0.elapsed().as_secs_f64();
        indicator(&sums)
    }
}

/// The error indicator from the interfaces' parts of `||s - s_hat||^2`, `||s||^2` and
/// `||s_hat||^2` (0 when both half-iterates vanish).
fn indicator(sums: &[[f64; 3]]) -> f64 {
    let tot = sums.iter().fold([0.0; 3], |acc, v| {
        [acc[0] + v[0], acc[1] + v[1], acc[2] + v[2]]
    });
    let den = 0.5 * (tot[1].sqrt() + tot[2].sqrt());
    if den > 0.0 { tot[0].sqrt() / den } else { 0.0 }
}

/// Local stage on one interface; returns the interface's parts of `||s - s_hat||^2`,
/// `||s||^2` and `||s_hat||^2`. `origin`: the tangential jump of each point at the start of the
/// load step (incremental law, [`crate::law::local_stage_from`]), `None` for a single step.
fn local_stage(
    op: &InterfaceOperator,
    st: &mut InterfaceState,
    pts: &[PointData],
    origin: Option<&[[f64; 3]]>,
    subs: &[Arc<SubOperator>],
    sstate: &[SubState],
    alpha: &[f64],
) -> [f64; 3] {
    let k = [
        alpha[op.sub[0]] * subs[op.sub[0]].links[op.link[0]].k0,
        alpha[op.sub[1]] * subs[op.sub[1]].links[op.link[1]].k0,
    ];
    let kappa = 1.0 / (1.0 / k[0] + 1.0 / k[1]);
    let w = [
        &sstate[op.sub[0]].w[op.link[0]],
        &sstate[op.sub[1]].w[op.link[1]],
    ];
    let f = [
        &sstate[op.sub[0]].f[op.link[0]],
        &sstate[op.sub[1]].f[op.link[1]],
    ];
    std::mem::swap(&mut st.what_prev, &mut st.what_last);
    let (mut dist, mut norm_s, mut norm_h) = (0.0, 0.0, 0.0);
    for (i, p) in pts.iter().enumerate() {
        let mut a = [[0.0; 3]; 2];
        for s in 0..2 {
            for c in 0..3 {
                a[s][c] = f[s][i][c] - k[s] * w[s][i][c];
            }
        }
        let r = [
            kappa * (a[1][0] / k[1] - a[0][0] / k[0]),
            kappa * (a[1][1] / k[1] - a[0][1] / k[0]),
            kappa * (a[1][2] / k[1] - a[0][2] / k[0]),
        ];
        let sol = match origin {
            Some(j0) => local_stage_from(op.law.as_ref(), p, r, kappa, j0[i]),
            None => op.law.local_stage(p, r, kappa),
        };
        st.status[i] = sol.status;
        let m = op.weights[i];
        for c in 0..3 {
            let phi = sol.force[c];
            st.fhat[0][i][c] = -phi;
            st.fhat[1][i][c] = phi;
            st.what[0][i][c] = (-phi - a[0][c]) / k[0];
            st.what[1][i][c] = (phi - a[1][c]) / k[1];
        }
        for s in 0..2 {
            for c in 0..3 {
                let dw = w[s][i][c] - st.what[s][i][c];
                let df = f[s][i][c] - st.fhat[s][i][c];
                dist += m * (k[s] * dw * dw + df * df / k[s]);
                norm_s += m * (k[s] * w[s][i][c].powi(2) + f[s][i][c].powi(2) / k[s]);
                norm_h += m * (k[s] * st.what[s][i][c].powi(2) + st.fhat[s][i][c].powi(2) / k[s]);
            }
        }
    }
    st.what_last[0].clone_from(&st.what[0]);
    st.what_last[1].clone_from(&st.what[1]);
    [dist, norm_s, norm_h]
}
