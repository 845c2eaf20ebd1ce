//! The statistics of one quantity under one method as [`super::result::StudyResult`] holds
//! them, with the total intervals (issue 40, item 3) beside the fields that readers already
//! use (none renamed): every budget row has `estimate` (the statistic corrected by the
//! validation runs where there are some, else its `value`) and `interval` (`[lo, hi]`, the
//! total interval about it); every failure probability has `sampling_interval` (its Wilson
//! interval, the same bounds as `ci_low` / `ci_high`, which are sampling only), and `estimate`
//! and `interval` from its budget row (`null` without a budget).

use alea_study::analysis::{Distribution, FailureStat, QoiStats};
use alea_study::budget::validation::PointwiseErrors;
use alea_study::budget::{BudgetRow, QoiBudget, Statistic};
use alea_study::sensitivity::SobolStats;
use serde::Serialize;

/// The statistics of one quantity of interest under one method
/// (`alea_study::analysis::QoiStats` without its samples, with the total intervals; the
/// same [`Distribution`]).
#[derive(Clone, Debug, Serialize)]
pub struct QuantityStatistics {
    /// Name.
    pub name: String,
    /// Unit.
    pub unit: String,
    /// Moments, range, quantiles, density.
    #[serde(flatten)]
    pub distribution: Distribution,
    /// Failure probabilities.
    pub failure: Vec<FailureProbability>,
    /// The error budget of each statistic (none for a study without random parameters).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub budget: Option<Budget>,
    /// Sobol' indices of every parameter (studies with random fields).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sobol: Option<SobolStats>,
}

/// `P(q > threshold)` with its sampling and total intervals.
#[derive(Clone, Debug, Serialize)]
pub struct FailureProbability {
    /// Threshold.
    pub threshold: f64,
    /// Estimate from the draws.
    pub probability: f64,
    /// Lower bound of the (sampling) confidence interval.
    pub ci_low: f64,
    /// Upper bound.
    pub ci_high: f64,
    /// `[ci_low, ci_high]`.
    pub sampling_interval: [f64; 2],
    /// Its budget row's estimate (`None`: no budget row).
    pub estimate: Option<f64>,
    /// Its budget row's total interval (`None`: no budget row).
    pub interval: Option<[f64; 2]>,
}

/// The error budget of one quantity under one method (`alea_study::budget::QoiBudget` with
/// the total intervals).
#[derive(Clone, Debug, Serialize)]
pub struct Budget {
    /// One row per statistic: mean, std, the quantiles, each `P(q > t)`.
    pub rows: Vec<BudgetInterval>,
    /// How the surrogate part was estimated, or why it was not.
    pub surrogate_basis: String,
    /// How the validation runs corrected the statistics (`None`: no validation runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validation_basis: Option<String>,
    /// The surrogate's residuals at the validation runs (`None`: no validation runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub validation_errors: Option<PointwiseErrors>,
    /// How the mesh part was estimated, or why it was not.
    pub mesh_basis: String,
    /// How the sliding part was estimated, or why it was not (`None`: not asked for).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sliding_basis: Option<String>,
    /// Monte Carlo draws behind the statistics.
    pub draws: usize,
}

/// A budget row with its estimate and total interval.
#[derive(Clone, Debug, Serialize)]
pub struct BudgetInterval {
    /// The row.
    #[serde(flatten)]
    pub row: BudgetRow,
    /// [`BudgetRow::estimate`].
    pub estimate: f64,
    /// [`BudgetRow::interval`].
    pub interval: [f64; 2],
}

impl From<&BudgetRow> for BudgetInterval {
    fn from(row: &BudgetRow) -> Self {
        let (lo, hi) = row.interval();
        BudgetInterval {
            row: row.clone(),
            estimate: row.estimate(),
            interval: [lo, hi],
        }
    }
}

impl From<&QoiBudget> for Budget {
    fn from(b: &QoiBudget) -> Self {
        Budget {
            rows: b.rows.iter().map(BudgetInterval::from).collect(),
            surrogate_basis: b.surrogate_basis.clone(),
            validation_basis: b.validation_basis.clone(),
            validation_errors: b.validation_errors.clone(),
            mesh_basis: b.mesh_basis.clone(),
            sliding_basis: b.sliding_basis.clone(),
            draws: b.draws,
        }
    }
}

impl FailureProbability {
    /// `f` with the total interval of its row among `rows`.
    fn of(f: &FailureStat, rows: &[BudgetRow]) -> Self {
        let row = rows
            .iter()
            .find(|r| r.statistic == Statistic::Exceedance(f.threshold));
        FailureProbability {
            threshold: f.threshold,
            probability: f.probability,
            ci_low: f.ci_low,
            ci_high: f.ci_high,
            sampling_interval: [f.ci_low, f.ci_high],
            estimate: row.map(BudgetRow::estimate),
            interval: row.map(|r| {
                let (lo, hi) = r.interval();
                [lo, hi]
            }),
        }
    }
}

impl From<&QoiStats> for QuantityStatistics {
    fn from(s: &QoiStats) -> Self {
        let rows: &[BudgetRow] = s.budget.as_ref().map_or(&[], |b| &b.rows);
        QuantityStatistics {
            name: s.name.clone(),
            unit: s.unit.clone(),
            distribution: s.distribution.clone(),
            failure: s
                .failure
                .iter()
                .map(|f| FailureProbability::of(f, rows))
                .collect(),
            budget: s.budget.as_ref().map(Budget::from),
            sobol: s.sobol.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use alea_study::budget::validation::Corrected;
    use serde_json::json;

    use super::*;

    fn row(statistic: &str, value: f64, sampling: f64, surrogate: f64) -> BudgetRow {
        BudgetRow {
            statistic: statistic.parse().expect("a statistic"),
            value,
            mesh: None,
            surrogate: Some(surrogate),
            sampling,
            sliding: None,
            total: sampling + surrogate,
            validation: None,
        }
    }

    /// A failure probability's JSON carries its sampling interval and its total interval,
    /// which contains it; a corrected row's estimate is the corrected value; a threshold
    /// without a budget row has `null`s.
    #[test]
    fn failure_and_budget_rows_carry_both_intervals() {
        let mut mean = row("mean", 10.0, 0.01, 0.04);
        mean.validation = Some(Corrected {
            value: 10.2,
            half_width: 0.05,
            runs: 30,
            detected: true,
            bound: 0.3,
            difference: 0.2,
            atom: false,
        });
        let stats = QoiStats {
            name: "q".into(),
            unit: "MPa".into(),
            distribution: Distribution {
                mean: 10.0,
                std: 2.0,
                skewness: 0.0,
                min: 0.0,
                max: 20.0,
                mean_ci_half_width: 0.01,
                quantiles: vec![],
                bandwidth: 0.1,
                kde: vec![],
            },
            failure: vec![
                FailureStat {
                    threshold: 14.0,
                    probability: 0.25,
                    ci_low: 0.24,
                    ci_high: 0.26,
                },
                FailureStat {
                    threshold: 40.0,
                    probability: 0.0,
                    ci_low: 0.0,
                    ci_high: 0.001,
                },
            ],
            budget: Some(QoiBudget {
                rows: vec![mean, row("P(> 14)", 0.25, 0.01, 0.09)],
                surrogate_basis: String::new(),
                validation_basis: None,
                validation_errors: None,
                mesh_basis: String::new(),
                sliding_basis: None,
                draws: 1000,
            }),
            sobol: None,
            samples: vec![],
            negative: (0.0, f64::INFINITY),
        };
        let v = serde_json::to_value(vec![QuantityStatistics::from(&stats)]).unwrap();
        let f = &v[0]["failure"][0];
        assert_eq!(f["ci_low"], json!(0.24), "old fields kept");
        assert_eq!(f["sampling_interval"], json!([0.24, 0.26]));
        assert_eq!(f["estimate"], json!(0.25));
        let (lo, hi) = (
            f["interval"][0].as_f64().unwrap(),
            f["interval"][1].as_f64().unwrap(),
        );
        assert!(
            (lo - 0.15).abs() < 1e-12 && (hi - 0.35).abs() < 1e-12,
            "{f}"
        );
        assert!(
            lo <= 0.24 && 0.26 <= hi,
            "the total contains the sampling interval"
        );
        let none = &v[0]["failure"][1];
        assert!(none["interval"].is_null() && none["estimate"].is_null());
        assert_eq!(none["sampling_interval"], json!([0.0, 0.001]));
        let m = &v[0]["budget"]["rows"][0];
        assert_eq!(m["value"], json!(10.0));
        assert_eq!(m["estimate"], json!(10.2));
        let (lo, hi) = (
            m["interval"][0].as_f64().unwrap(),
            m["interval"][1].as_f64().unwrap(),
        );
        assert!(
            (lo - 10.15).abs() < 1e-12 && (hi - 10.25).abs() < 1e-12,
            "{m}"
        );
    }
}
