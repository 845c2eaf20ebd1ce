//! The typed result of a study: one struct tree ([`StudyResult`]) with the study's header,
//! every method's statistics (their budgets with the total intervals: `summary_intervals.rs`),
//! error estimates and adaptive loop, the reliability tables, the runs and the warnings.
//! `summary.json` is this tree written by `serde_json` (`files.rs`).

use alea_estimate::{EntityEstimate, Estimate};
use alea_study::analysis::{MethodAccount, MethodResult};
use alea_study::estimate::SurrogateEstimate;
use alea_study::reliability::ReliabilityResult;
use alea_study::runner::{Study, StudyRuns};
use alea_study::store::{RunRecord, RunSlide};
use alea_study::study_runs::{AdaptiveOutcome, GoalRecord, StepQoi};
use serde::Serialize;

use super::estimate::MethodEstimate;
use super::results::Analysis;
use super::summary_intervals::QuantityStatistics;

/// Everything a study found, as `summary.json` holds it.
#[derive(Clone, Debug, Serialize)]
pub struct StudyResult {
    /// The study's title.
    pub title: String,
    /// The study file's name.
    pub study_file: String,
    /// The study's hash (its store's key).
    pub study_hash: String,
    /// The random seed.
    pub seed: u64,
    /// The units of lengths, forces, stresses and densities.
    pub units: Units,
    /// The random parameters.
    pub parameters: Vec<Parameter>,
    /// Every method, in study order.
    pub methods: Vec<MethodOutcome>,
    /// The results of the `[[reliability]]` tables, in table order.
    pub reliability: Vec<ReliabilityResult>,
    /// Every finished run.
    pub runs: Vec<Run>,
    /// The warnings.
    pub notes: Vec<String>,
}

/// The study's units.
#[derive(Clone, Debug, Serialize)]
pub struct Units {
    /// Length unit.
    pub length: String,
    /// Force unit.
    pub force: String,
    /// Stress unit.
    pub stress: String,
    /// Density unit (`None`: the study gives none).
    pub density: Option<String>,
}

/// One random parameter.
#[derive(Clone, Debug, Serialize)]
pub struct Parameter {
    /// Name.
    pub name: String,
    /// Its law, in words.
    pub law: String,
    /// Unit.
    pub unit: String,
    /// Lower end of its range.
    pub lo: f64,
    /// Upper end of its range.
    pub hi: f64,
    /// Nominal value.
    pub nominal: f64,
}

/// One method: its runs, its statistics, its error estimate and its adaptive loop.
#[derive(Clone, Debug, Serialize)]
pub struct MethodOutcome {
    /// The method and its runs.
    #[serde(flatten)]
    pub account: MethodAccount,
    /// Monte Carlo draws.
    pub draws: usize,
    /// Statistics per quantity of interest.
    pub qois: Vec<QuantityStatistics>,
    /// The error estimate of a method with a surrogate in a study that estimates its error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<ErrorEstimate>,
    /// The adaptive loop of an adaptive method.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adaptive: Option<AdaptiveLoop>,
}

/// A method's error estimate, or why it has none.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum ErrorEstimate {
    /// The estimate.
    Estimated(SurrogateError),
    /// Why there is none.
    Unavailable {
        /// The reason.
        unavailable: String,
    },
}

/// The error estimate of one surrogate (`alea_study::estimate::SurrogateEstimate`).
#[derive(Clone, Debug, Serialize)]
pub struct SurrogateError {
    /// Relative error `sqrt(e2 / norm2)`.
    pub relative: f64,
    /// Relative space-discretisation part.
    pub i_geo: f64,
    /// Relative stochastic part.
    pub i_sto: f64,
    /// Squared error.
    pub e2: f64,
    /// Squared space-discretisation part.
    pub geo2: f64,
    /// Squared stochastic part.
    pub sto2: f64,
    /// Squared norm the relative errors divide by.
    pub norm2: f64,
    /// Runs the surrogate is built on.
    pub runs: usize,
    /// Points of the integration rule.
    pub rule_points: usize,
    /// Largest relative error of the surrogate's load factors on the rule.
    pub load_defect: f64,
    /// Probability of a violated admissibility on the rule.
    pub violation_probability: f64,
    /// Largest relative violation over the rule.
    pub max_violation: f64,
    /// False when some substructure has no admissible-stress construction.
    pub substructures_estimated: bool,
    /// The parts that came out negative.
    pub negative_parts: Vec<String>,
    /// Per substructure, then per interface.
    pub entities: Vec<EntityError>,
}

/// The error estimate of one substructure or interface.
#[derive(Clone, Debug, Serialize)]
pub struct EntityError {
    /// Its name.
    pub name: String,
    /// `substructure` or `interface`.
    pub kind: String,
    /// Squared error.
    pub e2: f64,
    /// Squared space-discretisation part.
    pub geo2: f64,
    /// Squared stochastic part.
    pub sto2: f64,
    /// `E[...]^2` part.
    pub mean2: f64,
    /// Variance part.
    pub std2: f64,
    /// Its error relative to the whole norm.
    pub relative: f64,
    /// Its space-discretisation part relative to the whole norm.
    pub i_geo: f64,
    /// Its stochastic part relative to the whole norm.
    pub i_sto: f64,
}

/// An adaptive method's loop.
#[derive(Clone, Debug, Serialize)]
pub struct AdaptiveLoop {
    /// Why the loop stopped.
    pub stop: String,
    /// Set when the loop could not go on.
    pub error: Option<String>,
    /// Every step, in order.
    pub steps: Vec<AdaptiveStep>,
    /// The final stochastic mesh's run points.
    pub runs: Vec<Vec<f64>>,
}

/// One step of an adaptive loop.
#[derive(Clone, Debug, Serialize)]
pub struct AdaptiveStep {
    /// Runs of the surrogate at this step.
    pub runs: usize,
    /// Runs added by the refinement that ended this step.
    pub new_runs: usize,
    /// Cumulative cost in the thesis's units.
    pub thesis_cost: f64,
    /// The error estimate at this step.
    pub estimate: SurrogateError,
    /// Statistics of each quantity of interest on this step's surrogate.
    pub qois: Vec<StepQuantity>,
    /// A goal-oriented method's goal statistics (left out when empty).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub goal: Vec<GoalRecord>,
}

/// Statistics of one quantity at one adaptive step.
#[derive(Clone, Debug, Serialize)]
pub struct StepQuantity {
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub std: f64,
    /// `P(q > threshold)` for each threshold of the quantity.
    pub failure: Vec<f64>,
}

/// One finished run.
#[derive(Clone, Debug, Serialize)]
pub struct Run {
    /// Parameter point.
    pub params: Vec<f64>,
    /// `converged`, or why not.
    pub status: String,
    /// LATIN iterations.
    pub iterations: usize,
    /// Final error indicator.
    pub residual: f64,
    /// Quantities of interest, in study order.
    pub qois: Vec<f64>,
    /// The run's largest slide (`None`: no contact interface, or not known).
    pub slide: Option<Slide>,
}

/// The largest slide of a run.
#[derive(Clone, Debug, Serialize)]
pub struct Slide {
    /// The interface's name.
    pub interface: String,
    /// The tangential slip there.
    pub slip: f64,
    /// The slip over the local mesh size.
    pub ratio: f64,
}

/// What a [`StudyResult`] is built from.
pub(super) struct ResultParts<'a> {
    /// The statistics of every method, in method order.
    pub results: &'a [MethodResult],
    /// The runs and adaptive loops.
    pub runs: &'a StudyRuns,
    /// The error estimates of the methods with a surrogate.
    pub estimates: &'a [MethodEstimate],
    /// The results of the reliability tables.
    pub reliability: &'a [ReliabilityResult],
    /// The warnings.
    pub notes: &'a [String],
}

impl StudyResult {
    /// The result of `study` from its parts.
    pub(super) fn new(study: &Study, parts: &ResultParts) -> Self {
        let units = &study.model.units;
        let p = &study.params;
        StudyResult {
            title: study.title(),
            study_file: study.file_name(),
            study_hash: study.hash.clone(),
            seed: study.seed,
            units: Units {
                length: units.length.clone(),
                force: units.force.clone(),
                stress: units.stress.clone(),
                density: units.density.clone(),
            },
            parameters: (0..p.names.len())
                .map(|j| Parameter {
                    name: p.names[j].clone(),
                    law: p.descriptions[j].clone(),
                    unit: p.units[j].clone(),
                    lo: p.lo[j],
                    hi: p.hi[j],
                    nominal: p.nominal[j],
                })
                .collect(),
            methods: (0..parts.results.len())
                .map(|m| MethodOutcome::new(m, parts))
                .collect(),
            reliability: parts.reliability.to_vec(),
            runs: parts.runs.records.iter().map(Run::from).collect(),
            notes: parts.notes.to_vec(),
        }
    }
}

impl StudyResult {
    /// The result of `study` analysed without its error estimates (Python's `alea.run`: no
    /// method has an `error_estimate`), with the warnings `notes`.
    pub fn of_analysis(
        study: &Study,
        runs: &StudyRuns,
        analysis: &Analysis,
        notes: &[String],
    ) -> Self {
        StudyResult::new(
            study,
            &ResultParts {
                results: &analysis.results,
                runs,
                estimates: &[],
                reliability: &analysis.reliability,
                notes,
            },
        )
    }
}

impl MethodOutcome {
    /// Method `m` of `parts`.
    fn new(m: usize, parts: &ResultParts) -> Self {
        let r = &parts.results[m];
        MethodOutcome {
            account: r.account.clone(),
            draws: r.draws,
            qois: r.qois.iter().map(QuantityStatistics::from).collect(),
            error_estimate: parts.estimates.iter().find(|e| e.method == m).map(|e| {
                match &e.result {
                    Ok(me) => ErrorEstimate::Estimated(SurrogateError::from(me)),
                    Err(why) => ErrorEstimate::Unavailable {
                        unavailable: why.clone(),
                    },
                }
            }),
            adaptive: parts
                .runs
                .adaptive
                .iter()
                .find(|a| a.method == m)
                .map(AdaptiveLoop::from),
        }
    }
}

impl From<&SurrogateEstimate> for SurrogateError {
    fn from(e: &SurrogateEstimate) -> Self {
        let est = &e.estimate;
        let entities = (est
            .subs
            .iter()
            .map(|x| EntityError::of(x, "substructure", est)))
        .chain(
            est.interfaces
                .iter()
                .map(|x| EntityError::of(x, "interface", est)),
        )
        .collect();
        SurrogateError {
            relative: est.relative(),
            i_geo: est.i_geo(),
            i_sto: est.i_sto(),
            e2: est.e2,
            geo2: est.geo2,
            sto2: est.sto2,
            norm2: est.norm2,
            runs: e.runs,
            rule_points: e.rule_points,
            load_defect: e.load_defect,
            violation_probability: est.violation_probability,
            max_violation: est.max_violation,
            substructures_estimated: e.substructures_estimated,
            negative_parts: est.negative_parts(),
            entities,
        }
    }
}

impl EntityError {
    /// Entity `e` of kind `kind` in the estimate `est`.
    fn of(e: &EntityEstimate, kind: &str, est: &Estimate) -> Self {
        EntityError {
            name: e.name.clone(),
            kind: kind.to_string(),
            e2: e.e2,
            geo2: e.geo2,
            sto2: e.sto2,
            mean2: e.mean2,
            std2: e.std2,
            relative: est.relative_of(e.e2),
            i_geo: est.relative_of(e.geo2),
            i_sto: est.relative_of(e.sto2),
        }
    }
}

impl From<&AdaptiveOutcome> for AdaptiveLoop {
    fn from(a: &AdaptiveOutcome) -> Self {
        AdaptiveLoop {
            stop: a.stop.clone(),
            error: a.error.clone(),
            steps: a
                .steps
                .iter()
                .map(|s| AdaptiveStep {
                    runs: s.runs,
                    new_runs: s.new_runs,
                    thesis_cost: s.thesis_cost,
                    estimate: SurrogateError::from(&s.error),
                    qois: s.qois.iter().map(StepQuantity::from).collect(),
                    goal: s.goal.clone(),
                })
                .collect(),
            runs: (0..a.mesh.num_runs())
                .map(|r| a.mesh.run_point(r).to_vec())
                .collect(),
        }
    }
}

impl From<&StepQoi> for StepQuantity {
    fn from(q: &StepQoi) -> Self {
        StepQuantity {
            mean: q.mean,
            std: q.std,
            failure: q.failure.clone(),
        }
    }
}

impl From<&RunRecord> for Run {
    fn from(r: &RunRecord) -> Self {
        Run {
            params: r.params.clone(),
            status: r.status.clone(),
            iterations: r.iterations,
            residual: r.residual,
            qois: r.qois.clone(),
            slide: r.slide.as_ref().map(Slide::from),
        }
    }
}

impl From<&RunSlide> for Slide {
    fn from(s: &RunSlide) -> Self {
        Slide {
            interface: s.interface.clone(),
            slip: s.slip,
            ratio: s.ratio,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn method(error_estimate: Option<ErrorEstimate>) -> MethodOutcome {
        MethodOutcome {
            account: MethodAccount {
                label: "m".into(),
                description: "d".into(),
                design_runs: 3,
                runs_used: 3,
                left_out: vec![],
                error: None,
                failure_region: None,
            },
            draws: 10,
            qois: vec![],
            error_estimate,
            adaptive: None,
        }
    }

    /// The optional parts are left out when absent, `null` where the file always had them; an
    /// estimate that could not be made is `{"unavailable": why}`; a step without a goal has no
    /// `goal`.
    #[test]
    fn optional_parts_keep_the_shape_of_summary_json() {
        let v = serde_json::to_value(method(None)).unwrap();
        let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
        assert_eq!(
            keys,
            [
                "description",
                "design_runs",
                "draws",
                "error",
                "failure_region",
                "label",
                "left_out",
                "qois",
                "runs_used"
            ],
            "sorted, as summary.json has them"
        );
        assert!(v["error"].is_null() && v["failure_region"].is_null());
        let why = ErrorEstimate::Unavailable {
            unavailable: "no statistics".into(),
        };
        let v = serde_json::to_value(method(Some(why))).unwrap();
        assert_eq!(
            v["error_estimate"],
            serde_json::json!({ "unavailable": "no statistics" })
        );
        let estimate = SurrogateError {
            relative: 0.1,
            i_geo: 0.05,
            i_sto: 0.08,
            e2: 0.01,
            geo2: 0.0025,
            sto2: 0.0064,
            norm2: 1.0,
            runs: 5,
            rule_points: 9,
            load_defect: 0.0,
            violation_probability: 0.0,
            max_violation: 0.0,
            substructures_estimated: true,
            negative_parts: vec![],
            entities: vec![],
        };
        let step = AdaptiveStep {
            runs: 5,
            new_runs: 0,
            thesis_cost: 12.5,
            estimate,
            qois: vec![StepQuantity {
                mean: 1.0,
                std: 0.5,
                failure: vec![0.25],
            }],
            goal: vec![],
        };
        let v = serde_json::to_value(&step).unwrap();
        assert!(v.get("goal").is_none(), "{v}");
        assert_eq!(v["estimate"]["runs"], 5);
        assert_eq!(v["qois"][0]["failure"][0], 0.25);
    }
}
