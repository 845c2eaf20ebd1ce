//! Interface behaviours and the closed-form LATIN local stage at one interface point.
//!
//! # Conventions (used everywhere in this crate)
//! An interface joins side 1 (substructure `a`) and side 2 (substructure `b`). At each interface
//! point, `n` is the **outward unit normal of side 1** (pointing from 1 into 2). `F_s` is the
//! traction exerted **on** substructure `s` by the interface (the linear stage solves
//! `K u = f + M_Gamma F`). Interface equilibrium: `F_1 + F_2 = 0`; we write `Phi = F_2 = -F_1`.
//! The displacement jump is `[W] = W_2 - W_1`, and with a normal shape defect / initial gap
//! `g0(x)` (thesis (2.17)-(2.19): material removed opens the contact) the normal separation is
//! `g = [W].n + g0`. The Coulomb law (2.1) in the static, displacement-jump form reads
//! `g >= 0, Phi_n = Phi.n >= 0, Phi_n g = 0; |Phi_t| <= mu Phi_n`, and where `|Phi_t| < mu Phi_n`
//! the tangential jump `[W]_t` vanishes (stick), otherwise `[W]_t = -lambda Phi_t`, `lambda >= 0`
//! (slip opposite to the friction force acting on side 2).
//!
//! # Local stage
//! The ascent search direction is `F_hat_s - F_s = k_s (W_hat_s - W_s)` on each side, i.e.
//! `F_hat_s = a_s + k_s W_hat_s` with `a_s = F_s - k_s W_s`. Eliminating the side values with
//! `F_hat_1 = -Phi`, `F_hat_2 = Phi`:
//! `[W_hat] = Phi / kappa - R / kappa`, with the series stiffness
//! `kappa = (1/k_1 + 1/k_2)^-1` and `R = kappa (a_2/k_2 - a_1/k_1)` (for `k_1 = k_2 = k`:
//! `kappa = k/2`, `R = (a_2 - a_1)/2`, as in SEED-NOTES section 2). So `Phi = R + kappa [W_hat]`
//! and each law is a closed form in `(R, kappa)`:
//! - **perfect**: `[W_hat] = 0`, `Phi = R`;
//! - **contact**, with `R_n = R.n`, `R_t = R - R_n n`:
//!   - open if `R_n <= kappa g0`: `Phi = 0`, `[W_hat] = -R/kappa` (then `g = g0 - R_n/kappa >= 0`);
//!   - closed otherwise: `Phi_n = R_n - kappa g0 > 0`, `[W_hat].n = -g0`, and
//!     - stick if `|R_t| <= mu Phi_n`: `Phi_t = R_t`, `[W_hat]_t = 0`;
//!     - slip otherwise: `Phi_t = mu Phi_n R_t/|R_t|`, `[W_hat]_t = (Phi_t - R_t)/kappa`
//!       (anti-parallel to `Phi_t`, as the law requires).
//!
//! Finally `W_hat_1 = (-Phi - a_1)/k_1`, `W_hat_2 = (Phi - a_2)/k_2`. A search direction split
//! along the normal (`k_n != k_t`, module `solver::direction`) uses these closed forms at
//! `kappa_n` and rescales the tangential jump by `kappa_n / kappa_t` (the laws are invariant
//! under a positive scaling of the tangential jump).

use alea_mesh::vec3::dot;

/// Contact status of an interface point after a local stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PointStatus {
    /// Perfect (bonded) interface.
    Perfect,
    /// Contact open (no force).
    Open,
    /// Closed, sticking.
    Stick,
    /// Closed, slipping.
    Slip,
}

impl PointStatus {
    /// Numeric code for output files: perfect 0, open 1, stick 2, slip 3.
    pub fn code(self) -> u8 {
        match self {
            PointStatus::Perfect => 0,
            PointStatus::Open => 1,
            PointStatus::Stick => 2,
            PointStatus::Slip => 3,
        }
    }
}

/// The data of one interface point that a law may use.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointData {
    /// Position (nominal geometry).
    pub x: [f64; 3],
    /// Outward unit normal of side 1.
    pub normal: [f64; 3],
    /// Friction coefficient `mu(x)` at this point.
    pub mu: f64,
    /// Initial normal gap / shape defect `g0(x)` at this point (length).
    pub gap: f64,
}

/// Result of the local stage at one point: the force on side 2 and the jump.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalSolution {
    /// `Phi = F_hat_2 = -F_hat_1`.
    pub force: [f64; 3],
    /// `[W_hat] = W_hat_2 - W_hat_1`.
    pub jump: [f64; 3],
    /// Which branch of the law holds.
    pub status: PointStatus,
}

/// A pointwise interface behaviour: solves the local stage in closed form.
pub trait InterfaceLaw: Send + Sync + std::fmt::Debug {
    /// Short name for messages and output ("perfect", "coulomb").
    fn name(&self) -> &'static str;

    /// Given `R` and `kappa` (module doc), returns `(Phi, [W_hat], status)` satisfying both
    /// the law and `Phi = R + kappa [W_hat]`.
    fn local_stage(&self, p: &PointData, r: [f64; 3], kappa: f64) -> LocalSolution;

    /// True if the law uses the normal gap (then a mortar pairing adds the nominal distance
    /// between the sides to the gap field). Default true.
    fn uses_gap(&self) -> bool {
        true
    }
}

/// Perfect (bonded) interface.
#[derive(Clone, Copy, Debug, Default)]
pub struct Perfect;

impl InterfaceLaw for Perfect {
    fn name(&self) -> &'static str {
        "perfect"
    }
    fn uses_gap(&self) -> bool {
        false
    }
    fn local_stage(&self, _p: &PointData, r: [f64; 3], _kappa: f64) -> LocalSolution {
        LocalSolution {
            force: r,
            jump: [0.0; 3],
            status: PointStatus::Perfect,
        }
    }
}

/// Unilateral contact with Coulomb friction; `mu` and the gap come from [`PointData`].
#[derive(Clone, Copy, Debug, Default)]
pub struct CoulombContact;

impl InterfaceLaw for CoulombContact {
    fn name(&self) -> &'static str {
        "coulomb"
    }
    fn local_stage(&self, p: &PointData, r: [f64; 3], kappa: f64) -> LocalSolution {
        let n = p.normal;
        let rn = dot(&r, &n);
        if rn <= kappa * p.gap {
            return LocalSolution {
                force: [0.0; 3],
                jump: [-r[0] / kappa, -r[1] / kappa, -r[2] / kappa],
                status: PointStatus::Open,
            };
        }
        let fn_ = rn - kappa * p.gap;
        let rt = [r[0] - rn * n[0], r[1] - rn * n[1], r[2] - rn * n[2]];
        let rt_norm = dot(&rt, &rt).sqrt();
        let limit = p.mu * fn_;
        let (ft, status) = if rt_norm <= limit {
            (rt, PointStatus::Stick)
        } else {
            let s = limit / rt_norm;
            ([s * rt[0], s * rt[1], s * rt[2]], PointStatus::Slip)
        };
        let mut force = [0.0; 3];
        let mut jump = [0.0; 3];
        for c in 0..3 {
            force[c] = fn_ * n[c] + ft[c];
            jump[c] = -p.gap * n[c] + (ft[c] - rt[c]) / kappa;
        }
        LocalSolution {
            force,
            jump,
            status,
        }
    }
}

/// The local stage of `law` within a load step that starts from the tangential jump `j0`
/// (incremental Coulomb law, module [`crate::steps`]): slip is the increment of the tangential
/// jump within the step, so "stick" means `[W_hat]_t = j0` rather than `0`.
///
/// With `j0` tangential (`j0 . n = 0`) and `Phi = R + kappa [W_hat]`, write
/// `[W_hat] = j0 + d`; then `Phi = R' + kappa d` with `R' = R + kappa j0`, and `d` obeys the
/// law of the step (stick `d_t = 0`, slip `d_t` opposite to `Phi_t`, the normal part unchanged
/// since `R'_n = R_n`). So the law's own closed form at `R'` gives `(Phi, d)`, and
/// `[W_hat] = j0 + d`. With `j0 = 0` this is [`InterfaceLaw::local_stage`].
pub fn local_stage_from(
    law: &dyn InterfaceLaw,
    p: &PointData,
    r: [f64; 3],
    kappa: f64,
    j0: [f64; 3],
) -> LocalSolution {
    let shifted = [
        r[0] + kappa * j0[0],
        r[1] + kappa * j0[1],
        r[2] + kappa * j0[2],
    ];
    let mut sol = law.local_stage(p, shifted, kappa);
    for c in 0..3 {
        sol.jump[c] += j0[c];
    }
    sol
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(mu: f64, gap: f64) -> PointData {
        // A tilted 2D normal, to catch component mix-ups.
        let a: f64 = 0.3;
        PointData {
            x: [0.0; 3],
            normal: [a.sin(), a.cos(), 0.0],
            mu,
            gap,
        }
    }

    /// Checks the law itself: complementarity, Coulomb cone, slip direction, and the search
    /// direction identity `Phi = R + kappa [W]`.
    fn check_law(p: &PointData, r: [f64; 3], kappa: f64, s: &LocalSolution) {
        let n = p.normal;
        let fnorm = dot(&s.force, &n);
        let g = dot(&s.jump, &n) + p.gap;
        let scale = 1.0 + dot(&r, &r).sqrt();
        for c in 0..3 {
            assert!((s.force[c] - r[c] - kappa * s.jump[c]).abs() < 1e-12 * scale);
        }
        assert!(fnorm >= -1e-12 * scale, "F_n >= 0");
        assert!(g >= -1e-12 * scale / kappa, "g >= 0");
        assert!(
            (fnorm * g).abs() < 1e-10 * scale * scale / kappa,
            "F_n g = 0"
        );
        let ft: Vec<f64> = (0..3).map(|c| s.force[c] - fnorm * n[c]).collect();
        let wt: Vec<f64> = (0..3)
            .map(|c| s.jump[c] - dot(&s.jump, &n) * n[c])
            .collect();
        let ftn = ft.iter().map(|v| v * v).sum::<f64>().sqrt();
        let wtn = wt.iter().map(|v| v * v).sum::<f64>().sqrt();
        assert!(ftn <= p.mu * fnorm + 1e-12 * scale, "Coulomb cone");
        let work: f64 = ft.iter().zip(&wt).map(|(a, b)| a * b).sum();
        assert!(work <= 1e-12 * scale * scale, "slip opposes friction force");
        if wtn > 1e-12 {
            assert!(
                (ftn - p.mu * fnorm).abs() < 1e-10 * scale,
                "slip => on the cone"
            );
        }
    }

    #[test]
    fn every_branch_of_the_contact_law() {
        let kappa = 2.5;
        let p = point(0.4, 0.01);
        let n = p.normal;
        let t = [n[1], -n[0], 0.0];
        let comb = |a: f64, b: f64| [a * n[0] + b * t[0], a * n[1] + b * t[1], 0.0];
        // Open: normal part below kappa g0 (includes a slightly compressive R).
        let r = comb(0.5 * kappa * 0.01, 3.0);
        let s = CoulombContact.local_stage(&p, r, kappa);
        assert_eq!(s.status, PointStatus::Open);
        assert_eq!(s.force, [0.0; 3]);
        check_law(&p, r, kappa, &s);
        // Closed, stick: |R_t| <= mu (R_n - kappa g0).
        let r = comb(10.0, 0.3 * (10.0 - kappa * 0.01));
        let s = CoulombContact.local_stage(&p, r, kappa);
        assert_eq!(s.status, PointStatus::Stick);
        assert!((dot(&s.jump, &n) + p.gap).abs() < 1e-14);
        check_law(&p, r, kappa, &s);
        // Closed, slip, both tangential directions.
        for sign in [1.0, -1.0] {
            let r = comb(10.0, sign * 7.0);
            let s = CoulombContact.local_stage(&p, r, kappa);
            assert_eq!(s.status, PointStatus::Slip);
            let ft = dot(&s.force, &t);
            assert!((ft - sign * 0.4 * (10.0 - kappa * 0.01)).abs() < 1e-12);
            assert!(dot(&s.jump, &t) * sign < 0.0, "slip opposite to Phi_t");
            check_law(&p, r, kappa, &s);
        }
        // Exactly at the open/closed threshold: no force, zero gap.
        let r = comb(kappa * 0.01, 0.0);
        let s = CoulombContact.local_stage(&p, r, kappa);
        assert_eq!(s.force, [0.0; 3]);
        check_law(&p, r, kappa, &s);
        // 3D: tangential plane of dimension 2.
        let p3 = PointData {
            x: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
            mu: 0.3,
            gap: 0.0,
        };
        let r = [3.0, -4.0, 2.0];
        let s = CoulombContact.local_stage(&p3, r, kappa);
        assert_eq!(s.status, PointStatus::Slip);
        assert!((s.force[0] - 0.3 * 2.0 * 0.6).abs() < 1e-14);
        assert!((s.force[1] + 0.3 * 2.0 * 0.8).abs() < 1e-14);
        check_law(&p3, r, kappa, &s);
    }

    #[test]
    fn a_step_starting_from_a_slipped_state_sticks_at_that_state() {
        let kappa = 2.5;
        let p = point(0.4, 0.0);
        let n = p.normal;
        let t = [n[1], -n[0], 0.0];
        // The previous step slipped by j0 along t; this step's R would slip back without it.
        let j0 = [0.7 * t[0], 0.7 * t[1], 0.0];
        let r = [10.0 * n[0] - 1.0 * t[0], 10.0 * n[1] - 1.0 * t[1], 0.0];
        let s = local_stage_from(&CoulombContact, &p, r, kappa, j0);
        // R' = R + kappa j0 = 10 n + 0.75 t: |R'_t| = 0.75 <= 0.4 * 10, stick at j0.
        assert_eq!(s.status, PointStatus::Stick);
        for c in 0..3 {
            assert!((s.jump[c] - j0[c]).abs() < 1e-14);
            assert!((s.force[c] - r[c] - kappa * s.jump[c]).abs() < 1e-12);
        }
        // A large reverse R slips back, on the cone, by an increment opposite to Phi_t.
        let r = [10.0 * n[0] - 20.0 * t[0], 10.0 * n[1] - 20.0 * t[1], 0.0];
        let s = local_stage_from(&CoulombContact, &p, r, kappa, j0);
        assert_eq!(s.status, PointStatus::Slip);
        assert!((dot(&s.force, &t) + 4.0).abs() < 1e-12);
        let d = [s.jump[0] - j0[0], s.jump[1] - j0[1], 0.0];
        assert!(
            dot(&d, &t) > 0.0,
            "slip increment opposite to the friction force"
        );
        // Without j0 the same R sticks at zero jump: the step matters.
        let r = [10.0 * n[0] - 1.0 * t[0], 10.0 * n[1] - 1.0 * t[1], 0.0];
        let s0 = local_stage_from(&CoulombContact, &p, r, kappa, [0.0; 3]);
        assert_eq!(s0, CoulombContact.local_stage(&p, r, kappa));
    }

    #[test]
    fn perfect_law_transmits_r() {
        let p = point(0.0, 0.0);
        let r = [1.0, -2.0, 0.5];
        let s = Perfect.local_stage(&p, r, 3.0);
        assert_eq!(s.force, r);
        assert_eq!(s.jump, [0.0; 3]);
    }
}
