//! The total intervals in `summary.json` (issue 40, item 3), added beside the fields that
//! readers already use (none renamed): every budget row gets `estimate` (the statistic
//! corrected by the validation runs where there are some, else its `value`) and `interval`
//! (`[lo, hi]`, the total interval about it); every failure probability gets
//! `sampling_interval` (its Wilson interval, the same bounds as `ci_low` / `ci_high`, which are
//! sampling only), and `estimate` and `interval` from its budget row (`null` without a budget).

use alea_study::analysis::QoiStats;
use alea_study::budget::BudgetRow;
use serde_json::{Value, json};

/// Adds the fields to `qois`, the JSON array of `stats` (same order).
pub(super) fn add_intervals(qois: &mut Value, stats: &[QoiStats]) {
    let Some(list) = qois.as_array_mut() else {
        return;
    };
    for (q, s) in list.iter_mut().zip(stats) {
        let rows: &[BudgetRow] = s.budget.as_ref().map_or(&[], |b| &b.rows);
        if let Some(json_rows) = q.pointer_mut("/budget/rows").and_then(Value::as_array_mut) {
            for (j, row) in json_rows.iter_mut().zip(rows) {
                let (lo, hi) = row.interval();
                j["estimate"] = json!(row.estimate());
                j["interval"] = json!([lo, hi]);
            }
        }
        if let Some(failures) = q.get_mut("failure").and_then(Value::as_array_mut) {
            for (j, f) in failures.iter_mut().zip(&s.failure) {
                j["sampling_interval"] = json!([f.ci_low, f.ci_high]);
                let statistic = format!("P(> {})", f.threshold);
                let row = rows.iter().find(|r| r.statistic == statistic);
                j["estimate"] = json!(row.map(BudgetRow::estimate));
                j["interval"] = json!(row.map(|r| {
                    let (lo, hi) = r.interval();
                    [lo, hi]
                }));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use alea_study::analysis::FailureStat;
    use alea_study::budget::QoiBudget;
    use alea_study::budget::validation::Corrected;

    use super::*;

    fn row(statistic: &str, value: f64, sampling: f64, surrogate: f64) -> BudgetRow {
        BudgetRow {
            statistic: statistic.into(),
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
            mean: 10.0,
            std: 2.0,
            skewness: 0.0,
            min: 0.0,
            max: 20.0,
            mean_ci_half_width: 0.01,
            quantiles: vec![],
            bandwidth: 0.1,
            kde: vec![],
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
        let mut v = serde_json::to_value(vec![&stats]).unwrap();
        add_intervals(&mut v, std::slice::from_ref(&stats));
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
