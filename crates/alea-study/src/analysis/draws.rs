//! A surrogate method's values at the Monte Carlo draws: where each draw stands with respect
//! to the failed runs, the model and the surrogate at the validation runs, the comparison
//! surrogates of the error budget, at the draws and their smooth fits at the runs, the
//! region of the failed runs as the draws see it, and the kept draws and surrogate part of the
//! budget of one quantity.

use std::collections::HashMap;

use rayon::prelude::*;

use crate::budget::{self, Comparison, SurrogatePart};
use crate::failure_region::{FailureRegion, RegionTally, local_weight, touches, two_nearest};
use crate::method::{Method, Surrogate};
use crate::store::{RunRecord, point_key};
use crate::study::Study;

/// Where one draw stands with respect to the failed runs (module `failure_region`).
#[derive(Clone, Copy, Default)]
pub(super) struct DrawRegion {
    /// Its weight on failed runs, in [0, 1].
    pub(super) weight: f64,
    /// Wholly in the region.
    pub(super) whole: bool,
    /// Touching it.
    pub(super) touched: bool,
}

/// Evaluates a method's surrogate at a draw, and where the draw stands with respect to the
/// failed runs.
pub(super) struct DrawEvaluator<'a> {
    study: &'a Study,
    sur: &'a Surrogate,
    /// Per quantity, the values at the surrogate's points.
    sur_values: &'a [Vec<f64>],
    /// A local surrogate built on every design point, failed ones included.
    tolerant: bool,
    /// Per design point, whether its run failed.
    failed: &'a [bool],
    /// The normalised design points (with failed runs and a surrogate that is not
    /// `tolerant`: the region is that of the nearest runs; empty otherwise).
    design_norm: Vec<Vec<f64>>,
}

impl<'a> DrawEvaluator<'a> {
    /// The evaluator of `sur` (built on `sur_values`) for `method`'s design.
    pub(super) fn new(
        study: &'a Study,
        method: &Method,
        sur: &'a Surrogate,
        sur_values: &'a [Vec<f64>],
        tolerant: bool,
        failed: &'a [bool],
    ) -> Self {
        // Weights once per draw, reused for every quantity; with failed runs, the draw's
        // weight on them (module `failure_region`).
        let design_norm: Vec<Vec<f64>> = if failed.iter().any(|&f| f) && !tolerant {
            method.points.iter().map(|p| study.normalise(p)).collect()
        } else {
            Vec::new()
        };
        DrawEvaluator {
            study,
            sur,
            sur_values,
            tolerant,
            failed,
            design_norm,
        }
    }

    /// A draw's values on the surrogate and where it stands with respect to the failed runs
    /// (`t`, `w`: scratch space).
    pub(super) fn evaluate(
        &self,
        x: &[f64],
        t: &mut [f64],
        w: &mut Vec<(usize, f64)>,
    ) -> (Vec<f64>, DrawRegion) {
        let nq = self.study.qois.len();
        self.sur.weights(x, t, w);
        let v: Vec<f64> = (0..nq)
            .map(|q| w.iter().map(|&(k, wk)| wk * self.sur_values[q][k]).sum())
            .collect();
        let failed = self.failed;
        let region = if self.tolerant {
            let weight = local_weight(w, failed);
            DrawRegion {
                weight,
                whole: weight >= 1.0 - 1e-12,
                touched: touches(w, failed),
            }
        } else if self.design_norm.is_empty() {
            DrawRegion::default()
        } else {
            let (a, b) = two_nearest(&self.study.normalise(x), &self.design_norm);
            DrawRegion {
                weight: f64::from(u8::from(failed[a])),
                whole: failed[a] && failed[b],
                touched: failed[a] || failed[b],
            }
        };
        (v, region)
    }

    /// Whether a draw is kept for the statistics: outside the failure region.
    pub(super) fn kept(&self, r: &DrawRegion) -> bool {
        if self.tolerant {
            !r.touched
        } else {
            r.weight == 0.0
        }
    }

    /// Every draw of `pts` (row-major), evaluated in parallel.
    pub(super) fn at_draws(&self, pts: &[f64]) -> Vec<(Vec<f64>, DrawRegion)> {
        let d = self.study.params.names.len();
        pts.par_chunks(d)
            .map_init(
                || (vec![0.0; d], Vec::new()),
                |(t, w), x| self.evaluate(x, t, w),
            )
            .collect()
    }

    /// The validation runs (module `crate::validation_runs`): the model and the surrogate at
    /// each converged one outside the failure region, per quantity.
    #[allow(clippy::type_complexity)]
    pub(super) fn validation_pairs(
        &self,
        by_key: &HashMap<String, &RunRecord>,
    ) -> Vec<(Vec<f64>, Vec<f64>)> {
        let study = self.study;
        let d = study.params.names.len();
        let nq = study.qois.len();
        let found = crate::validation_runs::found(study, &|k| by_key.contains_key(k));
        let (mut t, mut w) = (vec![0.0; d], Vec::new());
        let mut pairs: Vec<(Vec<f64>, Vec<f64>)> = vec![(Vec::new(), Vec::new()); nq];
        for p in &found {
            let Some(r) = by_key.get(&point_key(p)).filter(|r| r.converged()) else {
                continue;
            };
            let (v, region) = self.evaluate(p, &mut t, &mut w);
            if self.kept(&region) {
                for (q, (model, surrogate)) in pairs.iter_mut().enumerate() {
                    model.push(r.qois[q]);
                    surrogate.push(v[q]);
                }
            }
        }
        pairs
    }
}

/// Each comparison surrogate's values at every draw of `pts` (per comparison, per draw, per
/// quantity; `values`: per quantity, the values at the method's used runs).
pub(super) fn comparisons_at_draws(
    comparisons: &Result<Vec<Comparison>, String>,
    pts: &[f64],
    d: usize,
    nq: usize,
    values: &[Vec<f64>],
) -> Vec<Vec<Vec<f64>>> {
    comparisons
        .iter()
        .flatten()
        .map(|c| {
            pts.par_chunks(d)
                .map_init(
                    || (vec![0.0; d], Vec::new()),
                    |(t, w), x| {
                        c.surrogate.weights(x, t, w);
                        (0..nq)
                            .map(|q| w.iter().map(|&(k, wk)| wk * values[q][c.runs[k]]).sum())
                            .collect::<Vec<f64>>()
                    },
                )
                .collect()
        })
        .collect()
}

/// The smooth fits at the used runs, for the check of their credibility per quantity (per
/// comparison, empty for one that is not a smooth fit; per run, per quantity).
pub(super) fn smooth_fits_at_runs(
    comparisons: &Result<Vec<Comparison>, String>,
    used_points: &[Vec<f64>],
    d: usize,
    nq: usize,
    values: &[Vec<f64>],
) -> Vec<Vec<Vec<f64>>> {
    comparisons
        .iter()
        .flatten()
        .map(|c| {
            if !c.smooth {
                return Vec::new();
            }
            let (mut t, mut w) = (vec![0.0; d], Vec::new());
            used_points
                .iter()
                .map(|x| {
                    c.surrogate.weights(x, &mut t, &mut w);
                    (0..nq)
                        .map(|q| w.iter().map(|&(k, wk)| wk * values[q][c.runs[k]]).sum())
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// What the statistics of each quantity are drawn from.
pub(super) struct DrawnValues<'a> {
    /// The surrogate's values at each draw and where it stands.
    pub(super) per_draw: &'a [(Vec<f64>, DrawRegion)],
    /// Whether each draw is kept (outside the failure region).
    pub(super) keep: &'a [bool],
    /// The comparison surrogates at the draws (`comparisons_at_draws`).
    pub(super) coarse_per_draw: &'a [Vec<Vec<f64>>],
    /// The comparison surrogates, or why there are none.
    pub(super) comparisons: &'a Result<Vec<Comparison>, String>,
    /// The smooth fits at the runs (`smooth_fits_at_runs`).
    pub(super) fits_at_runs: &'a [Vec<Vec<f64>>],
    /// Per quantity, the model and the surrogate at the validation runs.
    pub(super) validation: &'a [(Vec<f64>, Vec<f64>)],
    /// Per quantity, the values at the method's used runs.
    pub(super) values: &'a [Vec<f64>],
}

impl DrawnValues<'_> {
    /// Quantity `q` at the kept draws.
    pub(super) fn kept_draws(&self, q: usize) -> Vec<f64> {
        self.per_draw
            .iter()
            .zip(self.keep)
            .filter(|(_, k)| **k)
            .map(|(v, _)| v.0[q])
            .collect()
    }

    /// Quantity `q` at the kept draws of each comparison surrogate, through `project`.
    pub(super) fn kept_coarse_draws(
        &self,
        q: usize,
        project: impl Fn(f64) -> f64,
    ) -> Vec<Vec<f64>> {
        self.coarse_per_draw
            .iter()
            .map(|c| {
                c.iter()
                    .zip(self.keep)
                    .filter(|(_, k)| **k)
                    .map(|(v, _)| project(v[q]))
                    .collect()
            })
            .collect()
    }
}

/// The region of the failed runs as the draws see it (`keep`: those outside it).
pub(super) fn failure_region_of_draws(
    per_draw: &[(Vec<f64>, DrawRegion)],
    keep: &[bool],
    tolerant: bool,
    failed_runs: usize,
    confidence: f64,
) -> FailureRegion {
    let mut tally = RegionTally::default();
    for ((_, r), &k) in per_draw.iter().zip(keep) {
        tally.add(r.weight, r.whole, r.touched, !k);
    }
    let basis = if tolerant {
        "the failure indicator interpolated by the method's surrogate; interval from the \
         draws whose every node failed to those with any failed node"
    } else {
        "the draws whose nearest run failed; interval from those whose two nearest runs \
         failed to those with either failed"
    };
    tally.region(failed_runs, confidence, basis)
}

/// The comparison surrogates of the error budget (with failed runs, a local method's coarser
/// mesh would need them: only its smooth fits on the converged runs).
pub(super) fn comparison_surrogates(
    study: &Study,
    method: &Method,
    used_points: &[Vec<f64>],
    failed_runs: usize,
    tolerant: bool,
) -> Result<Vec<Comparison>, String> {
    if tolerant {
        let fits = budget::smooth_fits(&study.params, used_points);
        if fits.is_empty() {
            Err(format!(
                "{failed_runs} run(s) failed and the coarser mesh needs them; too few converged \
                 runs for a smooth fit"
            ))
        } else {
            Ok(fits)
        }
    } else {
        budget::comparisons(method, &study.params, used_points)
    }
}

/// The surrogate part of quantity `q`'s budget: the comparison surrogates (`coarse`: their
/// kept draws) that count for it, a smooth fit only where it follows the runs.
pub(super) fn surrogate_part<'a>(
    drawn: &DrawnValues<'a>,
    q: usize,
    coarse: &'a [Vec<f64>],
    mine: &[f64],
) -> SurrogatePart<'a> {
    match drawn.comparisons {
        Ok(cs) => {
            // A smooth fit counts for this quantity only where it follows the runs.
            let kept: Vec<usize> = (0..cs.len())
                .filter(|&i| {
                    !cs[i].smooth
                        || budget::credible_fit(
                            &drawn.fits_at_runs[i]
                                .iter()
                                .map(|v| v[q])
                                .collect::<Vec<_>>(),
                            &drawn.values[q],
                            &coarse[i],
                            mine,
                        )
                })
                .collect();
            SurrogatePart::Comparison(
                kept.iter()
                    .map(|&i| (coarse[i].as_slice(), cs[i].coarser, cs[i].sees_mean))
                    .collect(),
                kept.iter()
                    .map(|&i| cs[i].description.as_str())
                    .collect::<Vec<_>>()
                    .join(" and "),
            )
        }
        Err(why) => SurrogatePart::Unavailable(why),
    }
}
