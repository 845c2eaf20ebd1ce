//! The estimator: Gram matrices and interface data of the runs, the terms at one parameter
//! point ([`Estimator::at`]), their expectations over a [`Rule`] ([`Estimator::expectation`]),
//! and the exact substructure part from weight moments ([`Estimator::substructure_moments`]).
//! The formulas are in the crate doc.

use std::collections::BTreeMap;

use rayon::prelude::*;

use crate::data::{InterfaceKind, Layout, RunData};
use crate::gram::{Gram, form};
use crate::interface::{contact_density, dot, perfect_density};
use crate::results::{EntityEstimate, Estimate, InterfacePoint, PointEstimate, SubPoint};
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
    pub(crate) layout: Layout,
    pub(crate) k: usize,
    /// Per substructure, per run: Young's factor.
    pub(crate) young: Vec<Vec<f64>>,
    /// Per substructure (`None` when left out; `C` only without admissible samples).
    pub(crate) grams: Vec<Option<Gram>>,
    /// Per interface, point-major: `jump[p * K + k]`.
    pub(crate) jump: Vec<Vec<[f64; 3]>>,
    /// Per interface, point-major: `force[p * K + k]`.
    pub(crate) force: Vec<Vec<[f64; 3]>>,
    /// Per interface, point-major: `m_p rho*(w_hat_k, F_hat_k; mu(xi_k))`, run `k`'s own
    /// interface error density at point `p` (crate doc, "Interfaces"): the terms that the
    /// surrogate's weights interpolate into the space part `geo_I`.
    pub(crate) run_rho: Vec<Vec<f64>>,
    /// Per interface: the largest jump and force magnitudes over the runs' points, the scales
    /// of the admissibility checks (a scale taken from the interpolated fields themselves made
    /// round-off in an all-sticking interface, where every jump is ~0, count as a violation).
    pub(crate) scales: Vec<(f64, f64)>,
    pub(crate) options: Options,
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
}

impl Estimator {
    /// The terms of interface `i` at `xi` (weights `w`) and the largest relative violation of
    /// the admissibility there; `per_point[p]` (if given) receives `[m_p rho*(w~, F~),
    /// m_p sum_k w_k rho_k,p]` of each point. `mu` is scratch space.
    pub(crate) fn interface_at(
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
}
