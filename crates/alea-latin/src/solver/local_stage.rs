//! The local stage (per interface point, in parallel; closed form of [`crate::law`]) and the
//! error indicator, the k-weighted distance between the two half-iterates:
//! `eta = ||s - s_hat|| / max(1/2 (||s|| + ||s_hat||), ||s_0||)`,
//! `||s||^2 = sum_points m (W . k W + F . k^-1 F)` over both sides of every interface, with
//! `s_0 = (W_hat, F_hat)` the state the run started from (the warm start; zero for a cold
//! start). The floor `||s_0||` keeps the indicator's scale from vanishing with the answer: a run
//! warm-started from a neighbour whose contact is closed, at a point where the contact barely
//! closes (the answer tiny next to the start), has iterates that shrink towards the answer
//! while their relative distance stays of order one; measured against the start it falls like
//! the iterates (issue 35; a run whose answer is exactly zero starts cold instead, module
//! `start`). The floor only raises the denominator, so a run that converged without it
//! converges no later; its answer is then accurate to `tol ||s_0||` instead of `tol ||s||`, the
//! absolute accuracy of the neighbour it started from (measured on the 225-run 2D turbine
//! against runs at tolerance 1e-10: largest relative error of the friction work 1.44e-3 against
//! 1.12e-3 without the floor, of the fillet stress 9.7e-6 against 8.0e-6). The Anderson
//! safeguard keeps the distance relative to the iterates alone, so the iteration itself is the
//! same with or without the floor. With a split direction
//! (module `direction`) the series stiffness `kappa` is split too and the law is applied
//! through `split_local_stage`.

use std::sync::Arc;
use std::time::Instant;

use rayon::prelude::*;

use super::direction::Series;
use super::{InterfaceOperator, InterfaceState, LatinSolver, Run, SubOperator, SubState, V3};
use crate::PointData;
use crate::cyclic::{apply, apply_transpose};
use crate::law::local_stage_from;
use alea_mesh::vec3::dot;

impl LatinSolver {
    /// The local stage of every interface from the last linear stage; returns the error
    /// indicator `eta` (the stopping test's) and the same distance relative to the iterates
    /// alone (the Anderson safeguard's, unchanged by the floor so that the iteration itself is
    /// the same). The first call of a run records the norm of the state the run started from
    /// (the floor of the indicator's scale, module doc).
    pub(super) fn local_stage(&self, run: &mut Run<'_>) -> (f64, f64) {
        let t0 = Instant::now();
        let sums: Vec<[f64; 4]> = self
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
        let tot = sums.iter().fold([0.0; 4], |acc, v| {
            [acc[0] + v[0], acc[1] + v[1], acc[2] + v[2], acc[3] + v[3]]
        });
        // With subdomains (module `split`) the stopping test's scale is that of the user's
        // interfaces alone: the cuts carry the body's inner forces, whose size would dilute the
        // indicator (measured: 14x the undivided model's error at the same indicator). The
        // distance still counts the cuts.
        let scale = match &self.split {
            Some(split) => sums
                .iter()
                .enumerate()
                .filter(|(i, _)| !split.is_cut(*i))
                .fold([tot[0], 0.0, 0.0, 0.0], |acc, (_, v)| {
                    [acc[0], acc[1] + v[1], acc[2] + v[2], acc[3] + v[3]]
                }),
            None => tot,
        };
        let start = *run.start_norm.get_or_insert(scale[3].sqrt());
        (indicator(scale, start), indicator(tot, 0.0))
    }
}

/// The error indicator from the totals of `||s - s_hat||^2`, `||s||^2` and `||s_hat||^2` over
/// the interfaces and the norm `||s_0||` of the run's start (0 when the half-iterates and the
/// start all vanish).
fn indicator(tot: [f64; 4], start: f64) -> f64 {
    let den = (0.5 * (tot[1].sqrt() + tot[2].sqrt())).max(start);
    if den > 0.0 { tot[0].sqrt() / den } else { 0.0 }
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The law at one point with a split series stiffness `kappa = kappa_n n n^T + kappa_t
/// (I - n n^T)`: `Phi = R + kappa [W_hat]`. The laws are invariant under a positive scaling of
/// the tangential jump (stick: `[W]_t = 0`; slip: `[W]_t` opposite to `Phi_t`; the normal part
/// and the force unchanged), so with `[W]' = kappa_n^-1 kappa [W]` (tangential part scaled by
/// `kappa_t / kappa_n`), `Phi = R + kappa_n [W]'` is the law's scalar closed form, and
/// `[W]_t = (kappa_n / kappa_t) [W]'_t`. With a load step's origin `j0` (tangential): `R' = R +
/// kappa j0 = R + kappa_t j0`, then `[W] = j0 + d` ([`crate::law::local_stage_from`]).
fn split_local_stage(
    law: &dyn crate::InterfaceLaw,
    p: &PointData,
    r: [f64; 3],
    kappa: &Series,
    j0: Option<[f64; 3]>,
) -> crate::law::LocalSolution {
    let j0 = j0.unwrap_or([0.0; 3]);
    let shifted = [
        r[0] + kappa.kt * j0[0],
        r[1] + kappa.kt * j0[1],
        r[2] + kappa.kt * j0[2],
    ];
    let mut sol = law.local_stage(p, shifted, kappa.kn);
    let n = &kappa.normal;
    let jn = dot(&sol.jump, n);
    let scale = kappa.kn / kappa.kt;
    for c in 0..3 {
        let t = sol.jump[c] - jn * n[c];
        sol.jump[c] = jn * n[c] + scale * t + j0[c];
    }
    sol
}

/// Local stage on one interface; returns the interface's parts of `||s - s_hat||^2`,
/// `||s||^2`, `||s_hat||^2` and of the squared norm of the state the linear stage started from
/// (`(W_hat, F_hat)` before this local stage replaces it). `origin`: the tangential jump of each point at the start of the
/// load step (incremental law, [`crate::law::local_stage_from`]), `None` for a single step.
fn local_stage(
    op: &InterfaceOperator,
    st: &mut InterfaceState,
    pts: &[PointData],
    origin: Option<&[[f64; 3]]>,
    subs: &[Arc<SubOperator>],
    sstate: &[SubState],
    alpha: &[f64],
) -> [f64; 4] {
    let dirs = [
        subs[op.sub[0]].links[op.link[0]].dir.as_slice(),
        subs[op.sub[1]].links[op.link[1]].dir.as_slice(),
    ];
    let al = [alpha[op.sub[0]], alpha[op.sub[1]]];
    let w = [
        &sstate[op.sub[0]].w[op.link[0]],
        &sstate[op.sub[1]].w[op.link[1]],
    ];
    let f = [
        &sstate[op.sub[0]].f[op.link[0]],
        &sstate[op.sub[1]].f[op.link[1]],
    ];
    // Cyclic symmetry (module `crate::cyclic`): side 2 seen in side 1's frame, `R^T W_2`,
    // `R^T F_2`; its local-stage values are rotated back below. The direction of a cyclic
    // (perfect) interface is isotropic, so every norm is the same in either frame.
    let rot = op.pairing.rotation;
    let back = |v: &Vec<V3>| -> Vec<V3> {
        v.iter()
            .map(|x| rot.map_or(*x, |r| apply_transpose(&r, x)))
            .collect()
    };
    let (w1r, f1r) = match rot {
        Some(_) => (back(w[1]), back(f[1])),
        None => (Vec::new(), Vec::new()),
    };
    let (w, f) = match rot {
        Some(_) => ([w[0], &w1r], [f[0], &f1r]),
        None => (w, f),
    };
    std::mem::swap(&mut st.what_prev, &mut st.what_last);
    let (mut dist, mut norm_s, mut norm_h, mut norm_in) = (0.0, 0.0, 0.0, 0.0);
    for (i, p) in pts.iter().enumerate() {
        let d = [&dirs[0][i], &dirs[1][i]];
        if d[0].is_isotropic() && d[1].is_isotropic() {
            // The scalar search direction (the same operations as always).
            let k = [al[0] * d[0].kt, al[1] * d[1].kt];
            let kappa = 1.0 / (1.0 / k[0] + 1.0 / k[1]);
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
            for s in 0..2 {
                for c in 0..3 {
                    norm_in +=
                        m * (k[s] * st.what[s][i][c].powi(2) + st.fhat[s][i][c].powi(2) / k[s]);
                }
            }
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
                    norm_h +=
                        m * (k[s] * st.what[s][i][c].powi(2) + st.fhat[s][i][c].powi(2) / k[s]);
                }
            }
            continue;
        }
        // Split directions (module `direction`): a_s = F_s - k_s W_s,
        // R = kappa (k_2^-1 a_2 - k_1^-1 a_1).
        let a = [0, 1].map(|s| {
            let kw = d[s].apply(al[s], &w[s][i]);
            [f[s][i][0] - kw[0], f[s][i][1] - kw[1], f[s][i][2] - kw[2]]
        });
        let b = [d[0].solve(al[0], &a[0]), d[1].solve(al[1], &a[1])];
        let kappa = Series::new(d, al);
        let r = kappa.apply(&[b[1][0] - b[0][0], b[1][1] - b[0][1], b[1][2] - b[0][2]]);
        let sol = split_local_stage(op.law.as_ref(), p, r, &kappa, origin.map(|j0| j0[i]));
        st.status[i] = sol.status;
        let m = op.weights[i];
        for s in 0..2 {
            norm_in +=
                m * (d[s].energy(al[s], &st.what[s][i]) + d[s].co_energy(al[s], &st.fhat[s][i]));
        }
        let phi = sol.force;
        st.fhat[0][i] = [-phi[0], -phi[1], -phi[2]];
        st.fhat[1][i] = phi;
        st.what[0][i] = d[0].solve(
            al[0],
            &[-phi[0] - a[0][0], -phi[1] - a[0][1], -phi[2] - a[0][2]],
        );
        st.what[1][i] = d[1].solve(
            al[1],
            &[phi[0] - a[1][0], phi[1] - a[1][1], phi[2] - a[1][2]],
        );
        for s in 0..2 {
            let dw = sub(&w[s][i], &st.what[s][i]);
            let df = sub(&f[s][i], &st.fhat[s][i]);
            dist += m * (d[s].energy(al[s], &dw) + d[s].co_energy(al[s], &df));
            norm_s += m * (d[s].energy(al[s], &w[s][i]) + d[s].co_energy(al[s], &f[s][i]));
            norm_h +=
                m * (d[s].energy(al[s], &st.what[s][i]) + d[s].co_energy(al[s], &st.fhat[s][i]));
        }
    }
    if let Some(r) = &rot {
        for v in st.what[1].iter_mut().chain(st.fhat[1].iter_mut()) {
            *v = apply(r, v);
        }
    }
    st.what_last[0].clone_from(&st.what[0]);
    st.what_last[1].clone_from(&st.what[1]);
    [dist, norm_s, norm_h, norm_in]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::CoulombContact;
    use crate::{PointStatus, solver::direction::PointDirection};

    /// Every branch of the Coulomb law with a split series stiffness: `Phi = R + kappa [W]`,
    /// the gap and cone conditions, and slip opposite to the friction force.
    #[test]
    fn split_stiffness_keeps_the_law_and_the_search_direction() {
        let a: f64 = 0.3;
        let n = [a.sin(), a.cos(), 0.0];
        let t = [n[1], -n[0], 0.0];
        let d1 = PointDirection {
            normal: n,
            kn: 4.0,
            kt: 1.0,
        };
        let d2 = PointDirection {
            normal: n,
            kn: 8.0,
            kt: 2.0,
        };
        let kappa = Series::new([&d1, &d2], [1.0, 1.5]);
        let p = PointData {
            x: [0.0; 3],
            normal: n,
            mu: 0.4,
            gap: 0.01,
        };
        let comb = |x: f64, y: f64| [x * n[0] + y * t[0], x * n[1] + y * t[1], 0.0];
        for (r, status, j0) in [
            (comb(0.01, 3.0), PointStatus::Open, [0.0; 3]),
            (comb(10.0, 1.0), PointStatus::Stick, [0.0; 3]),
            (comb(10.0, -9.0), PointStatus::Slip, [0.0; 3]),
            (comb(10.0, 9.0), PointStatus::Slip, comb(0.0, 0.3)),
            (comb(10.0, 1.0), PointStatus::Stick, comb(0.0, -0.2)),
        ] {
            let s = split_local_stage(&CoulombContact, &p, r, &kappa, Some(j0));
            assert_eq!(s.status, status, "{r:?}");
            let kw = kappa.apply(&s.jump);
            for c in 0..3 {
                assert!((s.force[c] - r[c] - kw[c]).abs() < 1e-12, "{r:?}");
            }
            let fnorm = dot(&s.force, &n);
            let gap = dot(&s.jump, &n) + p.gap;
            assert!(fnorm >= 0.0 && gap >= -1e-14 && (fnorm * gap).abs() < 1e-12);
            let ft = dot(&s.force, &t);
            assert!(ft.abs() <= p.mu * fnorm + 1e-12);
            let slip = dot(&s.jump, &t) - dot(&j0, &t);
            match status {
                PointStatus::Stick => assert!(slip.abs() < 1e-14),
                PointStatus::Slip => {
                    assert!(slip * ft < 0.0);
                    assert!((ft.abs() - p.mu * fnorm).abs() < 1e-12);
                }
                _ => assert_eq!(s.force, [0.0; 3]),
            }
        }
    }
}
