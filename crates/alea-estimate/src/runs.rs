//! The runs an estimate is built from, behind one narrow interface ([`RunSource`]): per run
//! `k`, the Young's factor `alpha_(k,s)` and the stress samples of every substructure `s` (the
//! admissible `y(sigma_hat_k)` and FE `y(sigma_h,k)` vectors in compliance coordinates, crate
//! doc) and the interface fields (jump `w_hat` and force `F_hat` at every interface point).
//! The caller (crate `alea-study`: its store and estimator set-up) only says where they are;
//! this module assembles from them:
//!
//! - the estimator ([`Estimator::from_runs`]): the Gram matrices `G_kl = y_k . y_l` of every
//!   substructure, built one substructure at a time so that only one substructure's samples of
//!   all runs are in memory, and the interface fields;
//! - the per-cell terms of the error maps ([`sub_cell_terms`], [`crate::cell_terms`] on one
//!   substructure's samples);
//! - the surrogate's reproduction of the load factors ([`load_defect`]): the interpolated
//!   fields are statically admissible for the loads at `xi` only if
//!   `sum_k w_k(xi) f(xi_k) = f(xi)` for every load factor `f`; the largest relative defect
//!   `max_q |sum_k w_k(xi_q) f(xi_k) - f(xi_q)| / max_k |f(xi_k)|` over the rule's points is
//!   reported (0 for load factors affine in the parameters and a surrogate reproducing affine
//!   functions).

use crate::data::Layout;
use crate::estimator::{Estimator, Options, Parameters, Weights};
use crate::gram::Gram;
use crate::moments::{SubstructureMoments, cell_terms};
use crate::{EstimateError, Rule};

/// A vector at every point of every interface of one run (`[interface][point]`).
pub type InterfaceVectors = Vec<Vec<[f64; 3]>>;

/// Where the data of the runs are (surrogate run order `k = 0 .. num_runs`).
pub trait RunSource {
    /// The caller's error (a run that cannot be read or does not match the model); the
    /// estimator's own errors convert into it.
    type Error: From<EstimateError>;

    /// Number of runs.
    fn num_runs(&self) -> usize;

    /// Young's factor of substructure `s` in run `k`.
    ///
    /// # Errors
    /// A run without the factor of `s`.
    fn young(&self, k: usize, s: usize) -> Result<f64, Self::Error>;

    /// Admissible and FE stress samples of substructure `s` in run `k` (the admissible vector
    /// empty for a substructure without admissible stress).
    ///
    /// # Errors
    /// A run whose data do not match the model.
    fn samples(&self, k: usize, s: usize) -> Result<(Vec<f64>, Vec<f64>), Self::Error>;

    /// Per interface and point: the jump `w_hat` and the force `F_hat` of run `k`.
    fn interface_fields(&self, k: usize) -> (InterfaceVectors, InterfaceVectors);
}

/// The samples of substructure `s` in every run: admissible and FE vectors, run by run.
fn sub_samples<R: RunSource>(runs: &R, s: usize) -> Result<[Vec<Vec<f64>>; 2], R::Error> {
    let n = runs.num_runs();
    let mut a = Vec::with_capacity(n);
    let mut h = Vec::with_capacity(n);
    for k in 0..n {
        let (ya, yh) = runs.samples(k, s)?;
        a.push(ya);
        h.push(yh);
    }
    Ok([a, h])
}

/// Slices of sample vectors.
fn slices(v: &[Vec<f64>]) -> Vec<&[f64]> {
    v.iter().map(|x| x.as_slice()).collect()
}

impl Estimator {
    /// Builds the estimator of the runs of `runs` at the parameter points `run_points`, one
    /// substructure at a time (module doc): Gram matrices of the admissible and FE samples
    /// ([`Gram::new`]), of the FE samples only for a substructure without admissible stress
    /// ([`Gram::fe_only`]), none for a substructure left out of `layout`.
    ///
    /// # Errors
    /// The source's errors; [`EstimateError::Invalid`] (as the source's error) on samples whose
    /// lengths are not the layout's, inconsistent counts or non-finite data
    /// ([`Estimator::from_parts`]).
    pub fn from_runs<R: RunSource>(
        layout: Layout,
        runs: &R,
        run_points: &[Vec<f64>],
        params: &dyn Parameters,
        options: Options,
    ) -> Result<Self, R::Error> {
        let n = runs.num_runs();
        let ns = layout.subs.len();
        let mut young = vec![Vec::with_capacity(n); ns];
        for k in 0..n {
            for (s, y) in young.iter_mut().enumerate() {
                y.push(runs.young(k, s)?);
            }
        }
        let mut grams = Vec::with_capacity(ns);
        for (s, sub) in layout.subs.iter().enumerate() {
            if sub.is_empty() {
                grams.push(None);
                continue;
            }
            let [a, h] = sub_samples(runs, s)?;
            if let Some(k) =
                (0..n).find(|&k| a[k].len() != sub.admissible_len() || h[k].len() != sub.len())
            {
                return Err(EstimateError::Invalid(format!(
                    "run {k}: samples of substructure '{}' of lengths {} (admissible) and {} (FE) for a layout of {} and {}",
                    sub.name,
                    a[k].len(),
                    h[k].len(),
                    sub.admissible_len(),
                    sub.len()
                ))
                .into());
            }
            grams.push(Some(if sub.admissible {
                Gram::new(&slices(&a), &slices(&h))
            } else {
                Gram::fe_only(&slices(&h))
            }));
        }
        let (jump, force) = (0..n).map(|k| runs.interface_fields(k)).unzip();
        Ok(Self::from_parts(
            layout, young, grams, jump, force, run_points, params, options,
        )?)
    }
}

/// Per-cell expectations `(E[geo_E^2], E[e_E^2])` of substructure `s` ([`crate::cell_terms`])
/// from the samples of every run of `runs`, the substructure's `cell_offsets` and its weight
/// `moments`.
///
/// # Errors
/// The source's errors; [`EstimateError::Invalid`] (as the source's error) on samples that do
/// not cover the cells or moments that are not `K x K` for the `K` runs.
pub fn sub_cell_terms<R: RunSource>(
    runs: &R,
    s: usize,
    cell_offsets: &[usize],
    moments: &SubstructureMoments,
) -> Result<Vec<(f64, f64)>, R::Error> {
    let n = runs.num_runs();
    let [a, h] = sub_samples(runs, s)?;
    let young = (0..n)
        .map(|k| runs.young(k, s))
        .collect::<Result<Vec<f64>, _>>()?;
    let len = cell_offsets.last().copied().unwrap_or(0);
    let kk = n * n;
    if let Some(k) = (0..n).find(|&k| a[k].len() != len || h[k].len() != len) {
        return Err(EstimateError::Invalid(format!(
            "run {k}: samples of substructure {s} of lengths {} and {} for cells covering {len}",
            a[k].len(),
            h[k].len()
        ))
        .into());
    }
    if [&moments.inv_alpha, &moments.one, &moments.alpha]
        .iter()
        .any(|m| m.len() != kk)
    {
        return Err(EstimateError::Invalid(format!(
            "weight moments of substructure {s} are not {n} x {n}"
        ))
        .into());
    }
    Ok(cell_terms(
        &slices(&a),
        &slices(&h),
        &young,
        cell_offsets,
        moments,
    ))
}

/// Largest relative error of the surrogate's reproduction of every load factor of `factors`
/// (functions of the parameter point) on the rule's points (module doc): `weights` the
/// surrogate's, built on the runs at `run_points`. A factor that vanishes at every run is
/// skipped.
pub fn load_defect<F: Fn(&[f64]) -> f64>(
    rule: &Rule,
    weights: &dyn Weights,
    run_points: &[Vec<f64>],
    factors: impl IntoIterator<Item = F>,
) -> f64 {
    let mut worst: f64 = 0.0;
    let mut w = Vec::new();
    for f in factors {
        let vals: Vec<f64> = run_points.iter().map(|p| f(p)).collect();
        let scale = vals.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !(scale > 0.0) {
            continue;
        }
        for q in 0..rule.len() {
            let xi = rule.point(q);
            weights.weights(xi, &mut w);
            let interp: f64 = w.iter().map(|&(k, wk)| wk * vals[k]).sum();
            worst = worst.max((interp - f(xi)).abs() / scale);
        }
    }
    worst
}
