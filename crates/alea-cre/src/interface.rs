//! The interface term of the CRE with contact (thesis (3.26)-(3.27), 3.1.3.2 b).
//!
//! Conventions of `alea_latin::law`: side 1 has the outward normal `n`; `Phi = F_hat_2` is the
//! force on side 2; the jump `[W] = W_2 - W_1`; the separation `g = [W].n + g0`. The thesis'
//! interface fields are `w^c = [W_hat] + g0 n` (the gap included in the jump, so that
//! `w^c_n = g`) and `F^c = Phi`: its Coulomb law (2.1) (`w_n >= 0`, `F_n >= 0`, `F_n w_n = 0`,
//! `|F_t| <= mu F_n`, `w_t . F_t <= 0`) is exactly the law of `alea_latin`. With the de Saxce
//! bipotential `b(v, F) = chi_B(v) + chi_C(mu)(F) + mu F_n |v_t|`, `B = {v_n <= 0}`,
//! `C(mu) = {F_n >= 0, |F_t| <= mu F_n}`, the pointwise density is
//!
//! `e(x) = b(-w, F) + w . F = chi_B(-w) + chi_C(F) + mu F_n |w_t| + w_n F_n + w_t . F_t`,
//!
//! which is `>= 0` and vanishes iff `(w, F)` satisfies the law. `w` is the local-stage jump of
//! stage `n - 1` (`InterfaceResult::what_prev`), `F` the local-stage force of stage `n`
//! (`InterfaceResult::fhat`), both strictly admissible by construction ((3.27): the local stage
//! returns `F in C(mu)` and `g >= 0`).
//!
//! **Indicator functions.** They are never evaluated as `+inf`: each point is checked for
//! `g >= -tol W`, `F_n >= -tol F`, `|F_t| <= mu F_n + tol F` (`W`, `F` the largest jump and force
//! magnitudes on the interface, `tol` = [`crate::CreOptions::admissibility_tolerance`]); a point
//! passing the checks gets `chi = 0`, a point failing them is counted in
//! [`InterfaceEstimate::violations`] with its relative size in
//! [`InterfaceEstimate::max_violation`] (and still gets `chi = 0`, so the estimate stays finite
//! but is then **not** a bound). A perfect interface has `b(v, F) = chi_{v = 0}(v)`: its density
//! is `w . F` and the check is `|w| <= tol W_scale` with `W_scale` the largest side displacement.
//! The integral uses the lumped interface weights of the run (`InterfaceResult::weights`).
//!
//! **2D and 3D.** Everything is computed on 3-vectors: `w_t = w - w_n n`, `F_t = F - F_n n` are
//! the projections on the tangent line (2D) or plane (3D) and `|w_t|` their Euclidean norm, so
//! the same code serves both (`tests/contact3d.rs`: hand-made states with oblique slips, and a 3D
//! LATIN run). In 3D the density at a slipping point, `mu F_n |w_t| (1 - cos angle(-w_t, F_t))`,
//! is non-zero while the slip direction still turns between stages `n - 1` and `n`, so the
//! term decays with the LATIN residual instead of vanishing as soon as the statuses settle.

use alea_latin::InterfaceResult;
use alea_mesh::vec3::dot;

use crate::CreError;

/// Interface term of one interface.
#[derive(Clone, Debug)]
pub struct InterfaceEstimate {
    /// Interface name.
    pub name: String,
    /// Law name.
    pub law: &'static str,
    /// `int [b(-w, F) + w . F] dS` (its contribution to `theta^2` is twice this).
    pub term: f64,
    /// Pointwise density `e(x_i)` at each interface point.
    pub density: Vec<f64>,
    /// Number of points where the strict admissibility (3.27) fails beyond the tolerance.
    pub violations: usize,
    /// Largest relative violation (0 if none).
    pub max_violation: f64,
}

/// Evaluates the interface term of a run's interface.
///
/// # Errors
/// [`CreError::Invalid`] if the per-point arrays of `ir` do not all have the same length.
pub fn interface_term(ir: &InterfaceResult, tolerance: f64) -> Result<InterfaceEstimate, CreError> {
    let np = ir.points.len();
    let lens = [
        ir.weights.len(),
        ir.what_prev[0].len(),
        ir.what_prev[1].len(),
        ir.fhat[1].len(),
    ];
    if lens.iter().any(|&l| l != np) {
        return Err(CreError::Invalid(format!(
            "interface '{}': {np} points but arrays of lengths {lens:?}",
            ir.name
        )));
    }
    let jump = |i: usize| -> [f64; 3] {
        // Side 2 in the points' frame (a cyclic interface's `R^T W_2`).
        let (a, b) = (
            ir.what_prev[0][i],
            ir.pairing.to_points(1, ir.what_prev[1][i]),
        );
        let p = &ir.points[i];
        [
            b[0] - a[0] + p.gap * p.normal[0],
            b[1] - a[1] + p.gap * p.normal[1],
            b[2] - a[2] + p.gap * p.normal[2],
        ]
    };
    let perfect = ir.law == "perfect";
    let mut w_scale: f64 = 0.0;
    let mut f_scale: f64 = 0.0;
    for i in 0..np {
        let w = jump(i);
        w_scale = w_scale.max(dot(&w, &w).sqrt());
        for s in 0..2 {
            let v = ir.what_prev[s][i];
            w_scale = w_scale.max(dot(&v, &v).sqrt());
        }
        let f = ir.side2_force(i);
        f_scale = f_scale.max(dot(&f, &f).sqrt());
    }
    let w_tol = tolerance * w_scale.max(f64::MIN_POSITIVE);
    let f_tol = tolerance * f_scale.max(f64::MIN_POSITIVE);
    let mut density = Vec::with_capacity(np);
    let mut violations = 0;
    let mut max_violation: f64 = 0.0;
    let mut term = 0.0;
    for i in 0..np {
        let w = jump(i);
        let f = ir.side2_force(i);
        let n = ir.points[i].normal;
        let mut viol: f64 = 0.0;
        let e = if perfect {
            let wn = dot(&w, &w).sqrt();
            if wn > w_tol {
                viol = viol.max(wn / w_scale);
            }
            dot(&w, &f)
        } else {
            let mu = ir.points[i].mu;
            let (wn, fn_) = (dot(&w, &n), dot(&f, &n));
            let wt = [w[0] - wn * n[0], w[1] - wn * n[1], w[2] - wn * n[2]];
            let ft = [f[0] - fn_ * n[0], f[1] - fn_ * n[1], f[2] - fn_ * n[2]];
            let ftn = dot(&ft, &ft).sqrt();
            if wn < -w_tol {
                viol = viol.max(-wn / w_scale);
            }
            if fn_ < -f_tol {
                viol = viol.max(-fn_ / f_scale);
            }
            if ftn > mu * fn_ + f_tol {
                viol = viol.max((ftn - mu * fn_) / f_scale);
            }
            mu * fn_ * dot(&wt, &wt).sqrt() + wn * fn_ + dot(&wt, &ft)
        };
        if viol > 0.0 {
            violations += 1;
            max_violation = max_violation.max(viol);
        }
        term += ir.weights[i] * e;
        density.push(e);
    }
    Ok(InterfaceEstimate {
        name: ir.name.clone(),
        law: ir.law,
        term,
        density,
        violations,
        max_violation,
    })
}
