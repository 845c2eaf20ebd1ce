//! Anderson acceleration of the iteration (`LatinOptions::acceleration`; mixing in module
//! [`crate::anderson`]): the sequence of local-stage states is a fixed-point iteration, packed
//! with the scaling `sqrt(m k) W_hat`, `sqrt(m / k) F_hat` so that the Euclidean norm is the
//! indicator's norm. The accelerated state is applied at the start of the next iteration only,
//! so that whenever the loop ends the interface state is a true local stage; a clear increase
//! of the indicator (more than twice its best value) restarts from a plain step.

use super::direction::PointDirection;
use super::{InterfaceOperator, InterfaceState, LatinSolver};
use crate::anderson::Anderson;

/// The acceleration state of one run.
pub(super) struct Acceleration<'a> {
    ifaces: &'a [InterfaceOperator],
    /// The search direction and Young's-modulus factor of both sides of every interface.
    scales: Vec<[(&'a [PointDirection], f64); 2]>,
    anderson: Anderson,
    /// Smallest indicator so far.
    best_eta: f64,
    /// Accelerated state for the next iteration.
    pending: Option<Vec<f64>>,
    on: bool,
    /// Length of the packed state: 2 sides x 6 values per interface point.
    packed_len: usize,
}

impl<'a> Acceleration<'a> {
    /// No history, for a run with Young's-modulus factors `alpha`.
    pub(super) fn new(solver: &'a LatinSolver, alpha: &[f64], depth: usize) -> Self {
        // Scaling of the packed state for the acceleration: (m k)^(1/2) W and (m / k)^(1/2) F.
        let scales: Vec<[(&[PointDirection], f64); 2]> = solver
            .ifaces
            .iter()
            .map(|op| {
                [0, 1].map(|s| {
                    (
                        solver.subs[op.sub[s]].links[op.link[s]].dir.as_slice(),
                        alpha[op.sub[s]],
                    )
                })
            })
            .collect();
        Acceleration {
            ifaces: &solver.ifaces,
            scales,
            anderson: Anderson::new(depth),
            best_eta: f64::INFINITY,
            pending: None,
            on: depth > 0,
            packed_len: solver.ifaces.iter().map(|op| 12 * op.weights.len()).sum(),
        }
    }

    /// Replaces the local-stage state by the accelerated one of the last step, if any.
    pub(super) fn apply_pending(&mut self, istate: &mut [InterfaceState]) {
        if let Some(v) = self.pending.take() {
            self.unpack(istate, &v);
        }
    }

    /// The packed input of this iteration's linear stage (`None` without acceleration).
    pub(super) fn input(&self, istate: &[InterfaceState]) -> Option<Vec<f64>> {
        self.on.then(|| self.pack(istate))
    }

    /// One Anderson step from this iteration's input `x_in` to its local stage `istate` with
    /// indicator `eta`; the result is applied at the start of the next iteration.
    pub(super) fn step(&mut self, x_in: Option<Vec<f64>>, eta: f64, istate: &[InterfaceState]) {
        if let Some(x) = x_in {
            // Safeguard: a clear increase of the indicator restarts from a plain step.
            if eta > 2.0 * self.best_eta {
                self.anderson.reset();
            } else {
                let f = self.pack(istate);
                self.pending = Some(self.anderson.step(&x, &f));
            }
            self.best_eta = self.best_eta.min(eta);
        }
    }

    fn pack(&self, istate: &[InterfaceState]) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.packed_len);
        for ((st, op), k) in istate.iter().zip(self.ifaces).zip(&self.scales) {
            for s in 0..2 {
                let (dir, alpha) = k[s];
                for (i, m) in op.weights.iter().enumerate() {
                    let d = &dir[i];
                    if d.is_isotropic() {
                        let k = alpha * d.kt;
                        let (a, b) = ((m * k).sqrt(), (m / k).sqrt());
                        v.extend(st.what[s][i].iter().map(|w| a * w));
                        v.extend(st.fhat[s][i].iter().map(|f| b * f));
                    } else {
                        v.extend(d.sqrt_scaled(*m, alpha, false, &st.what[s][i]));
                        v.extend(d.sqrt_scaled(*m, alpha, true, &st.fhat[s][i]));
                    }
                }
            }
        }
        v
    }

    fn unpack(&self, istate: &mut [InterfaceState], v: &[f64]) {
        let mut it = v.iter();
        for ((st, op), k) in istate.iter_mut().zip(self.ifaces).zip(&self.scales) {
            for s in 0..2 {
                let (dir, alpha) = k[s];
                for (i, m) in op.weights.iter().enumerate() {
                    let d = &dir[i];
                    let mut next = || [0; 3].map(|_| it.next().copied().unwrap_or(0.0));
                    let (w, f) = (next(), next());
                    if d.is_isotropic() {
                        let k = alpha * d.kt;
                        let (a, b) = ((m * k).sqrt(), (m / k).sqrt());
                        for c in 0..3 {
                            st.what[s][i][c] = w[c] / a;
                            st.fhat[s][i][c] = f[c] / b;
                        }
                    } else {
                        // The inverse scalings: (m k)^(-1/2) = (1 / (m k))^(1/2), and so on.
                        st.what[s][i] = d.sqrt_scaled(1.0 / m, alpha, true, &w);
                        st.fhat[s][i] = d.sqrt_scaled(1.0 / m, alpha, false, &f);
                    }
                }
            }
        }
    }
}
