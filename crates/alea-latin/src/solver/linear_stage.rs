//! The linear stage (thesis 2.1; per substructure, in parallel): with `k_s = alpha_s k0_s`
//! (a tensor per interface point, module `direction`),
//! `A0 u = (f + M_Gamma (F_hat + k W_hat)) / alpha - A0 u_p` with the factorisation of `A0` made
//! at set-up, then `W = Pi u|Gamma` and `F = F_hat - k (W - W_hat)`; after the coarse
//! correction (module `coarse` of the solver), the relaxation
//! `(W, F) <- rho (W, F) + (1 - rho) (W, F)_previous`.

use rayon::prelude::*;

use super::condensed::{Condensed, point_load};
use super::{InterfaceState, LatinSolver, Run, SubOperator, SubState, V3};

impl LatinSolver {
    /// Relaxation of the linear stage: the option's, at most 0.8 with the coarse problem and
    /// without acceleration (`LatinOptions::coarse`; `acceleration`: the run's Anderson depth).
    fn relaxation(&self, acceleration: usize) -> f64 {
        if self.coarse.is_some() && acceleration == 0 {
            self.options.relaxation.min(0.8)
        } else {
            self.options.relaxation
        }
    }

    /// After the plain solves: the coarse correction and the relaxation (none in the first
    /// iteration).
    pub(super) fn correct_and_relax(&self, run: &mut Run<'_>, first: bool) {
        self.coarse_step(run, first);
        let r = if first {
            1.0
        } else {
            self.relaxation(run.acceleration)
        };
        run.sstate.par_iter_mut().for_each(|st| relax(st, r));
    }
}

/// The right-hand side `(f + M_Gamma (F_hat + k W_hat)) / alpha - A0 u_p` of one substructure
/// into `rhs` (`base` holds its constant part).
pub(super) fn assemble_rhs(
    op: &SubOperator,
    istate: &[InterfaceState],
    base: &[f64],
    alpha: f64,
    rhs: &mut [f64],
) {
    rhs.copy_from_slice(base);
    for l in &op.links {
        let is = &istate[l.iface];
        for (p, &m) in l.proj.weights.iter().enumerate() {
            let v = point_load(l, is, p, m, alpha);
            for (n, c) in l.proj.row(p) {
                let cv = [c * v[0], c * v[1], c * v[2]];
                op.dofs.add_node_force(n, &cv, rhs);
            }
        }
    }
}

/// `W = Pi u|Gamma` and `F = F_hat - k (W - W_hat)` of one substructure from its solved `u`
/// (`st.rhs`) into `w_new`, `f_new`.
pub(super) fn interface_fields(
    op: &SubOperator,
    st: &mut SubState,
    istate: &[InterfaceState],
    alpha: f64,
) {
    let SubState {
        rhs, w_new, f_new, ..
    } = st;
    write_fields(op, w_new, f_new, istate, alpha, |li, p| {
        let l = &op.links[li];
        let mut w = [0.0; 3];
        for (n, c) in l.proj.row(p) {
            let u = op.dofs.node_displacement(n, rhs);
            for d in 0..3 {
                w[d] += c * u[d];
            }
        }
        w
    });
}

/// `W` from the interface unknowns `st.wi` of a condensed substructure and `F = F_hat - k (W -
/// W_hat)` into `w_new`, `f_new`; marks the volume solution as not recovered.
pub(super) fn condensed_fields(
    op: &SubOperator,
    cd: &Condensed,
    st: &mut SubState,
    istate: &[InterfaceState],
    alpha: f64,
) {
    let SubState {
        wi, w_new, f_new, ..
    } = st;
    write_fields(op, w_new, f_new, istate, alpha, |li, p| cd.point(wi, li, p));
    st.stale = true;
}

/// `W` (from `w_at(link, point)`) and `F = F_hat - k (W - W_hat)` into `w_new`, `f_new`.
#[inline(always)]
fn write_fields(
    op: &SubOperator,
    w_new: &mut [Vec<V3>],
    f_new: &mut [Vec<V3>],
    istate: &[InterfaceState],
    alpha: f64,
    w_at: impl Fn(usize, usize) -> V3,
) {
    for (li, l) in op.links.iter().enumerate() {
        let is = &istate[l.iface];
        for p in 0..l.proj.len() {
            let w = w_at(li, p);
            let wh = is.what[l.side][p];
            let fh = is.fhat[l.side][p];
            let kd = l.dir[p].apply(alpha, &[w[0] - wh[0], w[1] - wh[1], w[2] - wh[2]]);
            for c in 0..3 {
                w_new[li][p][c] = w[c];
                f_new[li][p][c] = fh[c] - kd[c];
            }
        }
    }
}

/// Relaxation of the linear stage: `(W, F) <- r (W, F)_new + (1 - r) (W, F)_previous`.
fn relax(st: &mut SubState, r: f64) {
    for li in 0..st.w.len() {
        for p in 0..st.w[li].len() {
            for c in 0..3 {
                st.w[li][p][c] = r * st.w_new[li][p][c] + (1.0 - r) * st.w[li][p][c];
                st.f[li][p][c] = r * st.f_new[li][p][c] + (1.0 - r) * st.f[li][p][c];
            }
        }
    }
}
