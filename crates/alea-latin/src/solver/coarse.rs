//! The coarse step of the two-scale LATIN (`LatinOptions::coarse`; macro space and
//! substructure responses in module [`crate::coarse`]): the macro imbalance `b` of the plain
//! linear stage's interface forces (resultants and moments per interface), the macro unknowns
//! `lambda = (macro operator)^-1 b`, and the correction of every substructure's `u`, `W`, `F`;
//! the active set of interfaces (those not open at every point, module `coarse`, "Open
//! interfaces") and the re-inversion of the macro operator when it changes.

use rayon::prelude::*;

use super::{Coarse, LatinSolver, Run, SubOperator, SubState};
use crate::coarse::{SubMacro, macro_inverse};
use crate::{PointData, PointStatus};

impl Coarse {
    /// Per macro unknown: whether its interface is active.
    pub(super) fn mask(&self, active: &[bool]) -> Vec<bool> {
        let mut mask = vec![false; self.n];
        for (m, &a) in self.modes.iter().zip(active) {
            mask[m.offset..m.offset + m.len()].fill(a);
        }
        mask
    }
}

impl LatinSolver {
    /// Per interface, before any local stage: false for a gap law whose initial gap is positive
    /// at every point (open from the start), true otherwise.
    pub(super) fn initially_closed(&self, points: &[Vec<PointData>]) -> Vec<bool> {
        self.ifaces
            .iter()
            .zip(points)
            .map(|(op, pts)| {
                !(op.law.uses_gap() && !pts.is_empty() && pts.iter().all(|p| p.gap > 0.0))
            })
            .collect()
    }

    /// Corrects the plain linear stage of every substructure so that its interface forces
    /// balance macroscopically across every active interface (nothing without the coarse
    /// problem). `first`: no local stage yet (the active set is the initial one).
    pub(super) fn coarse_step(&self, run: &mut Run<'_>, first: bool) {
        for st in run.sstate.iter_mut() {
            st.coarse_u.clear();
        }
        let Some(cs) = &self.coarse else {
            return;
        };
        if !first {
            let active: Vec<bool> = run
                .istate
                .iter()
                .map(|st| st.status.iter().any(|s| *s != PointStatus::Open))
                .collect();
            if active != run.macro_active {
                let mask = cs.mask(&active);
                run.macro_inv = Some(macro_inverse(cs.n, &cs.subs, &run.alpha, &mask));
                run.macro_active = active;
            }
        }
        let Some(inv) = &run.macro_inv else {
            return;
        };
        let (sstate, alpha) = (&mut run.sstate, &run.alpha);
        let n = cs.n;
        let mut b = vec![0.0; n];
        for (i, op) in self.ifaces.iter().enumerate() {
            for side in 0..2 {
                let (s, l) = (op.sub[side], op.link[side]);
                let w = &self.subs[s].links[l].proj.weights;
                cs.side_modes(i, side)
                    .add_resultants(w, &sstate[s].f_new[l], &mut b);
            }
        }
        let lambda: Vec<f64> = (0..n)
            .map(|r| (0..n).map(|c| inv[r * n + c] * b[c]).sum())
            .collect();
        self.subs
            .par_iter()
            .zip(sstate.par_iter_mut())
            .zip(cs.subs.par_iter())
            .enumerate()
            .for_each(|(s, ((op, st), sm))| coarse_correction(op, sm, cs, st, &lambda, alpha[s]));
    }
}

/// The coarse correction of one substructure's linear stage (module `coarse`):
/// `F -= k (sum lambda Pi u^(Gj) + E lambda_G)`, `W += sum lambda Pi u_d^(Gj)` (`u_d`: the
/// response without its free rigid part), and `u += sum lambda u_d^(Gj)` recorded in
/// `coarse_u`, to be applied where the displacement is read ([`LatinSolver::displacement`]:
/// the iteration itself only needs `W` and `F`).
fn coarse_correction(
    op: &SubOperator,
    sm: &SubMacro,
    cs: &Coarse,
    st: &mut SubState,
    lambda: &[f64],
    alpha: f64,
) {
    // Forces from the whole response (admissible with the corrected displacement: a rigid
    // motion in the free modes does no work), displacements without the free rigid part.
    for (li, l) in op.links.iter().enumerate() {
        let im = cs.side_modes(l.iface, l.side);
        let lam = &lambda[im.offset..im.offset + im.len()];
        for p in 0..l.proj.len() {
            let mut e = [0.0; 3];
            for (j, mode) in im.modes.iter().enumerate() {
                for c in 0..3 {
                    e[c] += lam[j] * mode[p][c];
                }
            }
            let ke = l.dir[p].apply(alpha, &e);
            for c in 0..3 {
                st.f_new[li][p][c] -= ke[c];
            }
        }
    }
    for (c, col) in sm.columns.iter().enumerate() {
        let a = lambda[col.index];
        if a == 0.0 {
            continue;
        }
        st.coarse_u.push((c, a));
        for (li, l) in op.links.iter().enumerate() {
            for p in 0..l.proj.len() {
                let d = &l.dir[p];
                if d.is_isotropic() {
                    let k = alpha * d.kt;
                    for c in 0..3 {
                        st.w_new[li][p][c] += a * col.w[li][p][c];
                        st.f_new[li][p][c] -= k * a * col.w_full[li][p][c];
                    }
                } else {
                    let wf = col.w_full[li][p];
                    let kw = d.apply(alpha, &[a * wf[0], a * wf[1], a * wf[2]]);
                    for c in 0..3 {
                        st.w_new[li][p][c] += a * col.w[li][p][c];
                        st.f_new[li][p][c] -= kw[c];
                    }
                }
            }
        }
    }
}

impl LatinSolver {
    /// The reduced displacement of substructure `s` at the last linear stage: the plain
    /// solve plus its coarse correction, `u^0 + sum lambda u_d^(Gj)` (the columns in their
    /// order, as the correction was always summed).
    pub(super) fn displacement(&self, s: usize, st: &SubState) -> Vec<f64> {
        let mut u = st.rhs.clone();
        if let Some(cs) = &self.coarse {
            for &(c, a) in &st.coarse_u {
                for (u, v) in u.iter_mut().zip(&cs.subs[s].columns[c].u) {
                    *u += a * v;
                }
            }
        }
        u
    }
}
