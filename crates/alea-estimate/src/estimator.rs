//! The estimator: Gram matrices and interface data of the runs, the terms at one parameter
//! point ([`Estimator::at`]), their expectations over a [`Rule`] ([`Estimator::expectation`]),
//! and the exact substructure part from weight moments ([`Estimator::substructure_moments`]).
//! The formulas are in the crate doc.

use std::collections::BTreeMap;

use rayon::prelude::*;

use crate::data::{InterfaceKind, Layout, RunData};
use crate::gram::Gram;
use crate::{EstimateError, Rule};

/// The weights of a surrogate: `w_k(xi)` of the runs, as `(run, weight)` pairs.
pub trait Weights: Sync {
    /// Clears `w` and pushes the non-zero weights at `xi`.
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>);
}

/// Every surrogate of the stochastic toolkit gives its weights.
impl<S: alea_uq::surrogate::LinearSurrogate + ?Sized> Weights for S {
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        alea_uq::surrogate::LinearSurrogate::weights(self, xi, w);
    }
}

/// What the parameters change in the model, as far as the estimate is concerned.
pub trait Parameters: Sync {
    /// Young's-modulus factor of every substructure at `xi` (`out` has one slot per
    /// substructure).
    fn young(&self, xi: &[f64], out: &mut [f64]);
    /// Friction coefficient at every point of interface `interface` at `xi` (`out` has one
    /// slot per point; not called for perfect interfaces).
    fn friction(&self, xi: &[f64], interface: usize, out: &mut [f64]);
}

/// Terms of one substructure at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubPoint {
    /// `e_s^2 = 1/2 ||sigma~ - sigma_h1||^2` (3.30 integrand).
    pub e2: f64,
    /// `geo_s^2 = 1/2 ||sigma~ - sigma_h2||^2` (4.2 integrand).
    pub geo2: f64,
    /// `||sigma~||^2_{K^-1}` (4.8 denominator integrand); `||sigma_h1||^2_{K^-1}` for a
    /// substructure with FE samples only.
    pub norm2: f64,
}

/// Terms of one interface at one point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InterfacePoint {
    /// `e_I = sum_i m_i rho*(w~, F~; mu(xi))` (3.31 integrand, crate doc).
    pub e: f64,
    /// `geo_I = sum_k w_k(xi) rho_k`, the runs' own interface errors interpolated.
    pub geo: f64,
}

/// Every term at one parameter point.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PointEstimate {
    /// Per substructure.
    pub subs: Vec<SubPoint>,
    /// Per interface.
    pub interfaces: Vec<InterfacePoint>,
    /// Largest relative violation of the interface admissibility (`w~_n >= 0`, `F_n >= 0`) at
    /// this point (0 if none).
    pub violation: f64,
}

impl PointEstimate {
    /// `e^2(xi)`: the CRE of the interpolated admissible solution (3.28 integrand).
    pub fn e2(&self) -> f64 {
        self.subs.iter().map(|s| s.e2).sum::<f64>()
            + self.interfaces.iter().map(|i| i.e).sum::<f64>()
    }

    /// Space part of `e^2(xi)`.
    pub fn geo2(&self) -> f64 {
        self.subs.iter().map(|s| s.geo2).sum::<f64>()
            + self.interfaces.iter().map(|i| i.geo).sum::<f64>()
    }

    /// Stochastic part `e^2 - geo^2` at `xi`.
    pub fn sto2(&self) -> f64 {
        self.e2() - self.geo2()
    }

    /// `sum_s ||sigma~_s||^2_{K^-1}` at `xi`.
    pub fn norm2(&self) -> f64 {
        self.subs.iter().map(|s| s.norm2).sum()
    }
}

/// Expectations of one entity's terms.
#[derive(Clone, Debug, PartialEq)]
pub struct EntityEstimate {
    /// Substructure or interface name.
    pub name: String,
    /// `E[e^2]` of the entity (3.30 / 3.31).
    pub e2: f64,
    /// `E[geo^2]` (4.2 / 4.4).
    pub geo2: f64,
    /// `E[e^2] - E[geo^2]` (4.3 / 4.5).
    pub sto2: f64,
    /// Substructures: the part of `e2` from the error of the mean fields (3.32); interfaces: 0.
    pub mean2: f64,
    /// Substructures: `e2 - mean2`, the part from the fluctuations (3.32); interfaces: 0.
    pub std2: f64,
}

/// The expectations over a rule (crate doc, "Totals").
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Per substructure.
    pub subs: Vec<EntityEstimate>,
    /// Per interface.
    pub interfaces: Vec<EntityEstimate>,
    /// `e~^2` (3.28).
    pub e2: f64,
    /// `I_geo^2` (4.7).
    pub geo2: f64,
    /// `I_sto^2 = e~^2 - I_geo^2` (4.6).
    pub sto2: f64,
    /// `E[sum_s ||sigma~_s||^2_{K^-1}]`.
    pub norm2: f64,
    /// Per cell tag of the rule: `(cell, int sto(xi) f(xi) dxi, int e^2 f dxi)` over the cell
    /// (probability weights), cells in increasing tag order.
    pub cells: Vec<(usize, f64, f64)>,
    /// Probability (rule weight) of the points where the interpolated interface fields violate
    /// the admissibility beyond the tolerance (the estimate is then not a bound there).
    pub violation_probability: f64,
    /// Largest relative violation over the rule.
    pub max_violation: f64,
}

/// `sign(v) (|v| / norm2)^(1/2)`: a negative squared part keeps its sign (never a silent 0).
fn rel(v: f64, norm2: f64) -> f64 {
    if norm2 > 0.0 && v.is_finite() {
        v.signum() * (v.abs() / norm2).sqrt()
    } else {
        0.0
    }
}

impl Estimate {
    /// Relative error `e~ / (E[sum ||sigma~||^2])^(1/2)`.
    pub fn relative(&self) -> f64 {
        rel(self.e2, self.norm2)
    }

    /// `i_geo` (4.8); negative (`-(|I_geo^2| / norm)^(1/2)`) if `I_geo^2 < 0`, a defect that
    /// [`Estimate::negative_parts`] names.
    pub fn i_geo(&self) -> f64 {
        rel(self.geo2, self.norm2)
    }

    /// `i_sto` (4.9); negative if `I_sto^2 < 0` (see [`Estimate::i_geo`]).
    pub fn i_sto(&self) -> f64 {
        rel(self.sto2, self.norm2)
    }

    /// Relative share of an entity's `e2` (or `geo2`, `sto2`) in the normalisation, with the
    /// sign of `v`.
    pub fn relative_of(&self, v: f64) -> f64 {
        rel(v, self.norm2)
    }

    /// The squared parts that came out negative beyond round-off (`-1e-9 e~^2`), as messages
    /// naming the entity and the part: `I_sto^2` of an entity is `E[e^2] - E[geo^2]`, which no
    /// construction keeps non-negative (e.g. a substructure whose interpolated stresses fit the
    /// interpolated displacements better than the runs' own did). Empty when there is none.
    pub fn negative_parts(&self) -> Vec<String> {
        let tol = 1e-9 * self.e2.abs().max(f64::MIN_POSITIVE);
        let mut out = Vec::new();
        for (what, list) in [
            ("substructure", &self.subs),
            ("interface", &self.interfaces),
        ] {
            for e in list {
                for (part, v) in [("e~^2", e.e2), ("I_geo^2", e.geo2), ("I_sto^2", e.sto2)] {
                    if v < -tol {
                        out.push(format!(
                            "{what} '{}': {part} = {v:.3e} < 0 ({:.2} % of e~^2)",
                            e.name,
                            100.0 * v / self.e2.abs().max(f64::MIN_POSITIVE)
                        ));
                    }
                }
            }
        }
        for (part, v) in [
            ("e~^2", self.e2),
            ("I_geo^2", self.geo2),
            ("I_sto^2", self.sto2),
        ] {
            if v < -tol {
                out.push(format!("total: {part} = {v:.3e} < 0"));
            }
        }
        out
    }
}

/// Weight moments of one substructure: `M_f = E[f(xi) w w^T]`, dense row-major `K x K`, for
/// `f = 1 / alpha_s`, `1` and `alpha_s`.
#[derive(Clone, Debug, PartialEq)]
pub struct SubstructureMoments {
    /// `E[w w^T / alpha]`.
    pub inv_alpha: Vec<f64>,
    /// `E[w w^T]`.
    pub one: Vec<f64>,
    /// `E[alpha w w^T]`.
    pub alpha: Vec<f64>,
}

/// Options of the estimator.
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Relative tolerance of the interface admissibility checks.
    pub admissibility_tolerance: f64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            admissibility_tolerance: 1e-8,
        }
    }
}

/// The runs' data reduced to what the pointwise terms need.
#[derive(Clone, Debug)]
pub struct Estimator {
    layout: Layout,
    k: usize,
    /// Per substructure, per run: Young's factor.
    young: Vec<Vec<f64>>,
    /// Per substructure (`None` when left out; `C` only without admissible samples).
    grams: Vec<Option<Gram>>,
    /// Per interface, point-major: `jump[p * K + k]`.
    jump: Vec<Vec<[f64; 3]>>,
    /// Per interface, point-major: `force[p * K + k]`.
    force: Vec<Vec<[f64; 3]>>,
    /// Per interface, point-major: `m_p rho*(w_hat_k, F_hat_k; mu(xi_k))`, run `k`'s own
    /// interface error density at point `p` (crate doc, "Interfaces"): the terms that the
    /// surrogate's weights interpolate into the space part `geo_I`.
    run_rho: Vec<Vec<f64>>,
    /// Per interface: the largest jump and force magnitudes over the runs' points, the scales
    /// of the admissibility checks (a scale taken from the interpolated fields themselves made
    /// round-off in an all-sticking interface, where every jump is ~0, count as a violation).
    scales: Vec<(f64, f64)>,
    options: Options,
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The interface error density of a contact point (crate doc, "Interfaces"): the finite part of
/// the bipotential evaluated on the fields brought onto the admissible set, plus the work of
/// the correction,
/// `rho*(w, F) = mu F_n+ |w_t| + |w_n F_n| + w_t . P(F_t) + |w_t| |F_t - P(F_t)|`, with
/// `F_n+ = max(F_n, 0)` and `P` the projection onto the disk of radius `mu F_n+`. Non-negative,
/// continuous in `(w, F, mu)`, equal to `rho(w, F) = mu F_n |w_t| + w_n F_n + w_t . F_t` when
/// `w_n >= 0`, `F_n >= 0` and `|F_t| <= mu F_n`, and 0 exactly when the pair obeys the law.
pub fn contact_density(w: &[f64; 3], f: &[f64; 3], n: &[f64; 3], mu: f64) -> f64 {
    let (wn, fn_) = (dot(w, n), dot(f, n));
    let wt = [w[0] - wn * n[0], w[1] - wn * n[1], w[2] - wn * n[2]];
    let ft = [f[0] - fn_ * n[0], f[1] - fn_ * n[1], f[2] - fn_ * n[2]];
    let wtn = dot(&wt, &wt).sqrt();
    let ftn = dot(&ft, &ft).sqrt();
    let radius = mu * fn_.max(0.0);
    let (wt_pft, excess) = if ftn > radius {
        // P(F_t) = radius F_t / |F_t|; the correction's length is |F_t| - radius.
        (radius / ftn * dot(&wt, &ft), ftn - radius)
    } else {
        (dot(&wt, &ft), 0.0)
    };
    // Round-off can leave the sum a hair below 0 when the pair obeys the law.
    (radius * wtn + (wn * fn_).abs() + wt_pft + wtn * excess).max(0.0)
}

/// The interface error density of a perfect (bonded) point: the admissible jump is 0, so the
/// fields brought onto the admissible set carry no work and the correction's is `|w| |F|`
/// (`rho = w . F` is 0 there; `|w| |F| >= |w . F|`).
pub fn perfect_density(w: &[f64; 3], f: &[f64; 3]) -> f64 {
    dot(w, w).sqrt() * dot(f, f).sqrt()
}

/// `sum_kl x_k y_l M_kl` over sparse vectors.
fn form(m: &[f64], k: usize, x: &[(usize, f64)], y: &[(usize, f64)]) -> f64 {
    let mut s = 0.0;
    for &(i, xi) in x {
        let row = &m[i * k..(i + 1) * k];
        let mut r = 0.0;
        for &(j, yj) in y {
            r += row[j] * yj;
        }
        s += xi * r;
    }
    s
}

impl Estimator {
    /// Builds the Gram matrices and gathers the interface data of `runs` (in surrogate run
    /// order: run `k` of the surrogate is `runs[k]`, computed at the parameter point
    /// `run_points[k]`; `params` gives the friction coefficient there, for each run's own
    /// interface error).
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] if a run does not match the layout.
    pub fn new(
        layout: Layout,
        runs: &[RunData],
        run_points: &[Vec<f64>],
        params: &dyn Parameters,
        options: Options,
    ) -> Result<Self, EstimateError> {
        for (k, r) in runs.iter().enumerate() {
            layout
                .check(r)
                .map_err(|e| EstimateError::Invalid(format!("run {k}: {e}")))?;
        }
        let young = (0..layout.subs.len())
            .map(|s| runs.iter().map(|r| r.young[s]).collect())
            .collect();
        let grams = layout
            .subs
            .iter()
            .enumerate()
            .map(|(s, sub)| {
                (!sub.is_empty()).then(|| {
                    let h: Vec<&[f64]> = runs.iter().map(|r| r.fe[s].as_slice()).collect();
                    if sub.admissible {
                        let a: Vec<&[f64]> =
                            runs.iter().map(|r| r.admissible[s].as_slice()).collect();
                        Gram::new(&a, &h)
                    } else {
                        Gram::fe_only(&h)
                    }
                })
            })
            .collect();
        let jump = runs.iter().map(|r| r.jump.clone()).collect();
        let force = runs.iter().map(|r| r.force.clone()).collect();
        Self::from_parts(
            layout, young, grams, jump, force, run_points, params, options,
        )
    }

    /// Builds the estimator from Gram matrices computed elsewhere (e.g. substructure by
    /// substructure, to bound memory) and the runs' interface fields: `young[s][k]`,
    /// `grams[s]` (`None`: substructure left out; [`Gram::fe_only`] for a substructure without
    /// admissible samples), `jump[k][i][p]`, `force[k][i][p]`, the runs' parameter points
    /// `run_points[k]` and the friction law `params` (for each run's own interface error).
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] on inconsistent counts or non-finite data.
    #[allow(clippy::too_many_arguments)]
    pub fn from_parts(
        layout: Layout,
        young: Vec<Vec<f64>>,
        grams: Vec<Option<Gram>>,
        jump: Vec<Vec<Vec<[f64; 3]>>>,
        force: Vec<Vec<Vec<[f64; 3]>>>,
        run_points: &[Vec<f64>],
        params: &dyn Parameters,
        options: Options,
    ) -> Result<Self, EstimateError> {
        if !(options.admissibility_tolerance >= 0.0 && options.admissibility_tolerance.is_finite())
        {
            return Err(EstimateError::Invalid(format!(
                "admissibility tolerance {}",
                options.admissibility_tolerance
            )));
        }
        let k = jump.len();
        let ns = layout.subs.len();
        let ni = layout.interfaces.len();
        if young.len() != ns
            || grams.len() != ns
            || force.len() != k
            || young
                .iter()
                .any(|y| y.len() != k || y.iter().any(|a| !(a.is_finite() && *a > 0.0)))
            || grams.iter().flatten().any(|g| g.k != k)
        {
            return Err(EstimateError::Invalid(format!(
                "{ns} substructures and {k} runs: inconsistent Young's factors or Gram matrices"
            )));
        }
        for (s, g) in grams.iter().enumerate() {
            let sub = &layout.subs[s];
            if g.is_some() == sub.is_empty() {
                return Err(EstimateError::Invalid(format!(
                    "substructure '{}': Gram matrices {} but the layout says it is {}left out",
                    sub.name,
                    if g.is_some() { "given" } else { "missing" },
                    if sub.is_empty() { "" } else { "not " }
                )));
            }
            if let Some(g) = g
                && g.has_admissible() != sub.admissible
            {
                return Err(EstimateError::Invalid(format!(
                    "substructure '{}': Gram matrices {} admissible samples, the layout {}",
                    sub.name,
                    if g.has_admissible() {
                        "with"
                    } else {
                        "without"
                    },
                    if sub.admissible {
                        "has them"
                    } else {
                        "has FE samples only"
                    }
                )));
            }
        }
        let gather =
            |f: &Vec<Vec<Vec<[f64; 3]>>>, i: usize| -> Result<Vec<[f64; 3]>, EstimateError> {
                let np = layout.interfaces[i].weights.len();
                let mut out = Vec::with_capacity(np * k);
                for p in 0..np {
                    for run in f {
                        let v = run
                        .get(i)
                        .and_then(|pts| pts.get(p))
                        .filter(|v| v.iter().all(|x| x.is_finite()))
                        .ok_or_else(|| {
                            EstimateError::Invalid(format!(
                                "interface '{}': a run lacks point {p} or has a non-finite value",
                                layout.interfaces[i].name
                            ))
                        })?;
                        out.push(*v);
                    }
                }
                Ok(out)
            };
        if jump.iter().chain(&force).any(|r| r.len() != ni)
            || jump.iter().chain(&force).any(|r| {
                r.iter()
                    .zip(&layout.interfaces)
                    .any(|(pts, it)| pts.len() != it.weights.len())
            })
        {
            return Err(EstimateError::Invalid(format!(
                "{ni} interfaces: a run's interface fields do not match the layout"
            )));
        }
        let jump: Vec<Vec<[f64; 3]>> = (0..ni)
            .map(|i| gather(&jump, i))
            .collect::<Result<_, _>>()?;
        let force: Vec<Vec<[f64; 3]>> = (0..ni)
            .map(|i| gather(&force, i))
            .collect::<Result<_, _>>()?;
        if run_points.len() != k || run_points.iter().any(|p| p.iter().any(|x| !x.is_finite())) {
            return Err(EstimateError::Invalid(format!(
                "{k} runs but {} run points (or a non-finite one)",
                run_points.len()
            )));
        }
        // Each run's own interface error density, point by point, with its own mu(xi_k).
        let mut mu = Vec::new();
        let run_rho = (0..ni)
            .map(|i| {
                let it = &layout.interfaces[i];
                let np = it.weights.len();
                let mut out = vec![0.0; np * k];
                for (r, xi) in run_points.iter().enumerate() {
                    if it.kind == InterfaceKind::Contact {
                        mu.clear();
                        mu.resize(np, 0.0);
                        params.friction(xi, i, &mut mu);
                    }
                    for p in 0..np {
                        let (wv, fv) = (&jump[i][p * k + r], &force[i][p * k + r]);
                        out[p * k + r] = it.weights[p]
                            * match it.kind {
                                InterfaceKind::Contact => {
                                    contact_density(wv, fv, &it.normals[p], mu[p])
                                }
                                InterfaceKind::Perfect => perfect_density(wv, fv),
                            };
                    }
                }
                out
            })
            .collect();
        let norm = |v: &[f64; 3]| dot(v, v).sqrt();
        let scales = (0..ni)
            .map(|i| {
                (
                    jump[i].iter().map(norm).fold(0.0, f64::max),
                    force[i].iter().map(norm).fold(0.0, f64::max),
                )
            })
            .collect();
        Ok(Estimator {
            layout,
            k,
            young,
            grams,
            jump,
            force,
            run_rho,
            scales,
            options,
        })
    }

    /// The layout.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Number of runs.
    pub fn num_runs(&self) -> usize {
        self.k
    }

    /// The Gram matrices of substructure `s` (`None` when it is left out).
    pub fn gram(&self, s: usize) -> Option<&Gram> {
        self.grams[s].as_ref()
    }

    /// Every term at `xi` with the surrogate weights `w` (from [`Weights::weights`]).
    pub fn at(&self, xi: &[f64], w: &[(usize, f64)], params: &dyn Parameters) -> PointEstimate {
        let ns = self.layout.subs.len();
        let mut alpha = vec![1.0; ns];
        params.young(xi, &mut alpha);
        let k = self.k;
        let subs = (0..ns)
            .map(|s| {
                let Some(g) = &self.grams[s] else {
                    return SubPoint::default();
                };
                let a = alpha[s];
                let d: Vec<(usize, f64)> = w
                    .iter()
                    .map(|&(r, wr)| (r, wr * (a / self.young[s][r])))
                    .collect();
                if !g.has_admissible() {
                    // FE samples only: no error term; `||sigma_h1||^2 = d^T C d / alpha`.
                    return SubPoint {
                        e2: 0.0,
                        geo2: 0.0,
                        norm2: form(&g.hh, k, &d, &d) / a,
                    };
                }
                let caac = form(&g.aa, k, w, w);
                let e2 = 0.5 * (caac - 2.0 * form(&g.ah, k, w, &d) + form(&g.hh, k, &d, &d)) / a;
                let geo2 = 0.5 * (caac - 2.0 * form(&g.ah, k, w, w) + form(&g.hh, k, w, w)) / a;
                SubPoint {
                    e2,
                    geo2,
                    norm2: caac / a,
                }
            })
            .collect();
        let mut violation: f64 = 0.0;
        let mut mu = Vec::new();
        let interfaces = (0..self.layout.interfaces.len())
            .map(|i| {
                let (out, v) = self.interface_at(i, xi, w, params, &mut mu, None);
                violation = violation.max(v);
                out
            })
            .collect();
        PointEstimate {
            subs,
            interfaces,
            violation,
        }
    }

    /// The terms of interface `i` at `xi` (weights `w`) and the largest relative violation of
    /// the admissibility there; `per_point[p]` (if given) receives `[m_p rho*(w~, F~),
    /// m_p sum_k w_k rho_k,p]` of each point. `mu` is scratch space.
    fn interface_at(
        &self,
        i: usize,
        xi: &[f64],
        w: &[(usize, f64)],
        params: &dyn Parameters,
        mu: &mut Vec<f64>,
        mut per_point: Option<&mut [[f64; 2]]>,
    ) -> (InterfacePoint, f64) {
        let k = self.k;
        let tol = self.options.admissibility_tolerance;
        let mut violation: f64 = 0.0;
        let it = &self.layout.interfaces[i];
        let np = it.weights.len();
        let contact = it.kind == InterfaceKind::Contact;
        if contact {
            mu.clear();
            mu.resize(np, 0.0);
            params.friction(xi, i, mu);
        }
        // Interpolated fields; the scales of the admissibility checks are the runs'.
        let mut wf: Vec<([f64; 3], [f64; 3])> = Vec::with_capacity(np);
        let (w_scale, f_scale) = self.scales[i];
        for p in 0..np {
            let mut wt = [0.0; 3];
            let mut ft = [0.0; 3];
            for &(r, wr) in w {
                let (j, f) = (&self.jump[i][p * k + r], &self.force[i][p * k + r]);
                for c in 0..3 {
                    wt[c] += wr * j[c];
                    ft[c] += wr * f[c];
                }
            }
            wf.push((wt, ft));
        }
        let mut out = InterfacePoint::default();
        let rho_k = &self.run_rho[i];
        for (p, (wt, ft)) in wf.iter().enumerate() {
            let m = it.weights[p];
            let e = if contact {
                let n = it.normals[p];
                let (wn, fn_) = (dot(wt, &n), dot(ft, &n));
                if w_scale > 0.0 && wn < -tol * w_scale {
                    violation = violation.max(-wn / w_scale);
                }
                if f_scale > 0.0 && fn_ < -tol * f_scale {
                    violation = violation.max(-fn_ / f_scale);
                }
                m * contact_density(wt, ft, &n, mu[p])
            } else {
                m * perfect_density(wt, ft)
            };
            // The space part: the runs' own interface errors, interpolated (crate doc).
            let geo: f64 = w.iter().map(|&(r, wr)| wr * rho_k[p * k + r]).sum();
            out.e += e;
            out.geo += geo;
            if let Some(pp) = per_point.as_deref_mut() {
                pp[p] = [e, geo];
            }
        }
        (out, violation)
    }

    /// Per interface and point: `[E[m_p rho*(w~, F~)], E[m_p sum_k w_k rho_k,p]]` over `rule` (the
    /// terms of (3.31) and (4.4) point by point; per interface they add up to its `e2` and
    /// `geo2` of [`Estimator::expectation`] on the same rule). Divided by `m_p`: the error
    /// densities per unit interface measure, for maps.
    pub fn interface_point_terms(
        &self,
        rule: &Rule,
        weights: &dyn Weights,
        params: &dyn Parameters,
    ) -> Vec<Vec<[f64; 2]>> {
        let zero = || -> Vec<Vec<[f64; 2]>> {
            self.layout
                .interfaces
                .iter()
                .map(|it| vec![[0.0; 2]; it.weights.len()])
                .collect()
        };
        // Fixed chunks summed in order: independent of the thread count.
        const CHUNK: usize = 512;
        let starts: Vec<usize> = (0..rule.len()).step_by(CHUNK).collect();
        let parts: Vec<Vec<Vec<[f64; 2]>>> = starts
            .par_iter()
            .map(|&q0| {
                let mut acc = zero();
                let mut scratch = zero();
                let (mut w, mut mu) = (Vec::new(), Vec::new());
                for q in q0..(q0 + CHUNK).min(rule.len()) {
                    let (xi, om) = (rule.point(q), rule.weight(q));
                    weights.weights(xi, &mut w);
                    for (i, (a, sc)) in acc.iter_mut().zip(&mut scratch).enumerate() {
                        self.interface_at(i, xi, &w, params, &mut mu, Some(sc));
                        for (x, v) in a.iter_mut().zip(sc.iter()) {
                            x[0] += om * v[0];
                            x[1] += om * v[1];
                        }
                    }
                }
                acc
            })
            .collect();
        let mut out = zero();
        for part in &parts {
            for (o, p) in out.iter_mut().zip(part) {
                for (x, v) in o.iter_mut().zip(p) {
                    x[0] += v[0];
                    x[1] += v[1];
                }
            }
        }
        out
    }

    /// [`Estimator::at`] at every point of a row-major list, in parallel (results in order).
    pub fn evaluate(
        &self,
        points: &[f64],
        dim: usize,
        weights: &dyn Weights,
        params: &dyn Parameters,
    ) -> Vec<PointEstimate> {
        points
            .par_chunks(dim.max(1))
            .map_init(Vec::new, |w, xi| {
                weights.weights(xi, w);
                self.at(xi, w, params)
            })
            .collect()
    }

    /// Expectations of every term over `rule` (crate doc), with per-cell sums.
    pub fn expectation(
        &self,
        rule: &Rule,
        weights: &dyn Weights,
        params: &dyn Parameters,
    ) -> Estimate {
        let ns = self.layout.subs.len();
        let ni = self.layout.interfaces.len();
        let k = self.k;
        // Fixed chunks summed in order: independent of the thread count.
        const CHUNK: usize = 512;
        struct Part {
            subs: Vec<[f64; 3]>,
            ifs: Vec<[f64; 2]>,
            // Per substructure: E[w / sqrt(alpha)] and E[sqrt(alpha) w] (mean split, 3.32).
            p: Vec<Vec<f64>>,
            q: Vec<Vec<f64>>,
            cells: BTreeMap<usize, (f64, f64)>,
            viol_p: f64,
            viol_max: f64,
        }
        let starts: Vec<usize> = (0..rule.len()).step_by(CHUNK).collect();
        let parts: Vec<Part> = starts
            .par_iter()
            .map(|&q0| {
                let mut part = Part {
                    subs: vec![[0.0; 3]; ns],
                    ifs: vec![[0.0; 2]; ni],
                    p: vec![vec![0.0; k]; ns],
                    q: vec![vec![0.0; k]; ns],
                    cells: BTreeMap::new(),
                    viol_p: 0.0,
                    viol_max: 0.0,
                };
                let mut w = Vec::new();
                let mut alpha = vec![1.0; ns];
                for q in q0..(q0 + CHUNK).min(rule.len()) {
                    let xi = rule.point(q);
                    let om = rule.weight(q);
                    weights.weights(xi, &mut w);
                    let pe = self.at(xi, &w, params);
                    params.young(xi, &mut alpha);
                    for (s, sp) in pe.subs.iter().enumerate() {
                        part.subs[s][0] += om * sp.e2;
                        part.subs[s][1] += om * sp.geo2;
                        part.subs[s][2] += om * sp.norm2;
                        let sa = alpha[s].sqrt();
                        for &(r, wr) in &w {
                            part.p[s][r] += om * wr / sa;
                            part.q[s][r] += om * wr * sa;
                        }
                    }
                    for (i, ip) in pe.interfaces.iter().enumerate() {
                        part.ifs[i][0] += om * ip.e;
                        part.ifs[i][1] += om * ip.geo;
                    }
                    let c = part.cells.entry(rule.cell(q)).or_insert((0.0, 0.0));
                    c.0 += om * pe.sto2();
                    c.1 += om * pe.e2();
                    if pe.violation > 0.0 {
                        part.viol_p += om;
                        part.viol_max = part.viol_max.max(pe.violation);
                    }
                }
                part
            })
            .collect();
        let mut subs = vec![[0.0; 3]; ns];
        let mut ifs = vec![[0.0; 2]; ni];
        let mut p = vec![vec![0.0; k]; ns];
        let mut q = vec![vec![0.0; k]; ns];
        let mut cells: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
        let (mut viol_p, mut viol_max) = (0.0, 0.0f64);
        for part in &parts {
            for s in 0..ns {
                for c in 0..3 {
                    subs[s][c] += part.subs[s][c];
                }
                for r in 0..k {
                    p[s][r] += part.p[s][r];
                    q[s][r] += part.q[s][r];
                }
            }
            for i in 0..ni {
                ifs[i][0] += part.ifs[i][0];
                ifs[i][1] += part.ifs[i][1];
            }
            for (&c, &(a, b)) in &part.cells {
                let e = cells.entry(c).or_insert((0.0, 0.0));
                e.0 += a;
                e.1 += b;
            }
            viol_p += part.viol_p;
            viol_max = viol_max.max(part.viol_max);
        }
        let sub_est: Vec<EntityEstimate> = (0..ns)
            .map(|s| {
                let [e2, geo2, _] = subs[s];
                let mean2 = match &self.grams[s] {
                    Some(g) if g.has_admissible() => {
                        let pv: Vec<(usize, f64)> = p[s].iter().copied().enumerate().collect();
                        let qv: Vec<(usize, f64)> = q[s]
                            .iter()
                            .enumerate()
                            .map(|(r, v)| (r, v / self.young[s][r]))
                            .collect();
                        0.5 * (form(&g.aa, k, &pv, &pv) - 2.0 * form(&g.ah, k, &pv, &qv)
                            + form(&g.hh, k, &qv, &qv))
                    }
                    _ => 0.0,
                };
                EntityEstimate {
                    name: self.layout.subs[s].name.clone(),
                    e2,
                    geo2,
                    sto2: e2 - geo2,
                    mean2,
                    std2: e2 - mean2,
                }
            })
            .collect();
        let if_est: Vec<EntityEstimate> = (0..ni)
            .map(|i| EntityEstimate {
                name: self.layout.interfaces[i].name.clone(),
                e2: ifs[i][0],
                geo2: ifs[i][1],
                sto2: ifs[i][0] - ifs[i][1],
                mean2: 0.0,
                std2: 0.0,
            })
            .collect();
        let e2 = sub_est.iter().chain(&if_est).map(|e| e.e2).sum::<f64>();
        let geo2 = sub_est.iter().chain(&if_est).map(|e| e.geo2).sum::<f64>();
        Estimate {
            subs: sub_est,
            interfaces: if_est,
            e2,
            geo2,
            sto2: e2 - geo2,
            norm2: subs.iter().map(|v| v[2]).sum(),
            cells: cells.into_iter().map(|(c, (a, b))| (c, a, b)).collect(),
            violation_probability: viol_p,
            max_violation: viol_max,
        }
    }

    /// Weight moments of every substructure over `rule` ([`SubstructureMoments`]).
    pub fn moments(
        &self,
        rule: &Rule,
        weights: &dyn Weights,
        params: &dyn Parameters,
    ) -> Vec<SubstructureMoments> {
        weight_moments(rule, weights, params, self.layout.subs.len(), self.k)
    }

    /// The substructure terms from weight moments (exact when the moments are):
    /// `E[e_s^2] = 1/2 [tr(M_{1/alpha} A) - 2 tr(M_1 B D) + tr(M_alpha D C D)]`,
    /// `E[geo_s^2] = 1/2 tr(M_{1/alpha} (A - B - B^T + C))`, `E[||sigma~||^2] =
    /// tr(M_{1/alpha} A)`; returns `[e2, geo2, norm2]` per substructure (zeros when left
    /// out; `[0, 0, tr(M_alpha D C D)]`, the FE energy, without admissible samples).
    ///
    /// # Errors
    /// [`EstimateError::Invalid`] if the moments do not match the runs.
    pub fn substructure_moments(
        &self,
        moments: &[SubstructureMoments],
    ) -> Result<Vec<[f64; 3]>, EstimateError> {
        let k = self.k;
        if moments.len() != self.layout.subs.len()
            || moments.iter().any(|m| {
                m.inv_alpha.len() != k * k || m.one.len() != k * k || m.alpha.len() != k * k
            })
        {
            return Err(EstimateError::Invalid(format!(
                "moments of {} substructures for {} runs",
                moments.len(),
                k
            )));
        }
        Ok(self
            .grams
            .iter()
            .zip(moments)
            .enumerate()
            .map(|(s, (g, m))| {
                let Some(g) = g else {
                    return [0.0; 3];
                };
                let y = &self.young[s];
                if !g.has_admissible() {
                    let mut c = 0.0;
                    for i in 0..k {
                        for j in 0..k {
                            let ij = i * k + j;
                            c += m.alpha[ij] * g.hh[ij] / (y[i] * y[j]);
                        }
                    }
                    return [0.0, 0.0, c];
                }
                let (mut a, mut b, mut c, mut geo) = (0.0, 0.0, 0.0, 0.0);
                for i in 0..k {
                    for j in 0..k {
                        let ij = i * k + j;
                        a += m.inv_alpha[ij] * g.aa[ij];
                        b += m.one[ij] * g.ah[ij] / y[j];
                        c += m.alpha[ij] * g.hh[ij] / (y[i] * y[j]);
                        geo += m.inv_alpha[ij] * (g.aa[ij] - 2.0 * g.ah[ij] + g.hh[ij]);
                    }
                }
                [0.5 * (a - 2.0 * b + c), 0.5 * geo, a]
            })
            .collect())
    }
}

/// Per-cell expectations of one substructure's terms, `(E[geo_E^2], E[e_E^2])` for every cell
/// `E` (the sums over the cells are the substructure's `geo2` and `e2` when the moments come
/// from the same rule): `1/2 sum_kl M_{1/alpha,kl} d_k . d_l` on the cell for the space part
/// (`d_k = y(sigma_hat_k) - y(sigma_h,k)`) and the crate doc's quadratic form for the total.
/// `admissible[k]`, `fe[k]`: run `k`'s sample vectors; `young[k]`: its Young's factor;
/// `cell_offsets`: the layout's. Entries of the moments below `1e-300` in absolute value are
/// skipped (a piecewise-linear surrogate couples only neighbouring runs).
///
/// # Panics
/// If the lengths do not match (`K` runs, `K x K` moments, samples covering the offsets).
pub fn cell_terms(
    admissible: &[&[f64]],
    fe: &[&[f64]],
    young: &[f64],
    cell_offsets: &[usize],
    moments: &SubstructureMoments,
) -> Vec<(f64, f64)> {
    let k = admissible.len();
    assert!(fe.len() == k && young.len() == k && moments.one.len() == k * k);
    let pairs: Vec<(usize, usize)> = (0..k)
        .flat_map(|i| (0..k).map(move |j| (i, j)))
        .filter(|&(i, j)| {
            let ij = i * k + j;
            moments.inv_alpha[ij].abs() > 1e-300
                || moments.one[ij].abs() > 1e-300
                || moments.alpha[ij].abs() > 1e-300
        })
        .collect();
    let ncell = cell_offsets.len().saturating_sub(1);
    (0..ncell)
        .into_par_iter()
        .map(|c| {
            let r = cell_offsets[c]..cell_offsets[c + 1];
            let (mut geo, mut e) = (0.0, 0.0);
            for &(i, j) in &pairs {
                let ij = i * k + j;
                let (ai, aj) = (&admissible[i][r.clone()], &admissible[j][r.clone()]);
                let (hi, hj) = (&fe[i][r.clone()], &fe[j][r.clone()]);
                let (mut aa, mut ah, mut hh, mut dd) = (0.0, 0.0, 0.0, 0.0);
                for q in 0..ai.len() {
                    aa += ai[q] * aj[q];
                    ah += ai[q] * hj[q];
                    hh += hi[q] * hj[q];
                    dd += (ai[q] - hi[q]) * (aj[q] - hj[q]);
                }
                geo += moments.inv_alpha[ij] * dd;
                e += moments.inv_alpha[ij] * aa - 2.0 * moments.one[ij] * ah / young[j]
                    + moments.alpha[ij] * hh / (young[i] * young[j]);
            }
            (0.5 * geo, 0.5 * e)
        })
        .collect()
}

/// Weight moments `M_f = E[f(xi) w w^T]` (`f = 1/alpha_s, 1, alpha_s`) of `num_subs`
/// substructures for a surrogate of `k` runs, over `rule`.
pub fn weight_moments(
    rule: &Rule,
    weights: &dyn Weights,
    params: &dyn Parameters,
    num_subs: usize,
    k: usize,
) -> Vec<SubstructureMoments> {
    let mut out: Vec<SubstructureMoments> = (0..num_subs)
        .map(|_| SubstructureMoments {
            inv_alpha: vec![0.0; k * k],
            one: vec![0.0; k * k],
            alpha: vec![0.0; k * k],
        })
        .collect();
    let mut w = Vec::new();
    let mut alpha = vec![1.0; num_subs];
    for q in 0..rule.len() {
        let xi = rule.point(q);
        let om = rule.weight(q);
        weights.weights(xi, &mut w);
        params.young(xi, &mut alpha);
        for (s, m) in out.iter_mut().enumerate() {
            for &(i, wi) in &w {
                for &(j, wj) in &w {
                    let v = om * wi * wj;
                    m.inv_alpha[i * k + j] += v / alpha[s];
                    m.one[i * k + j] += v;
                    m.alpha[i * k + j] += v * alpha[s];
                }
            }
        }
    }
    out
}
