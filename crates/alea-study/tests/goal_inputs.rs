//! A goal-oriented adaptive method's bad inputs are refused when the study is loaded, before
//! any run, naming the file, the line and the field (issue 19).

use alea_study::runner::Study;
use alea_study::{Source, StudyError};

const BASE: &str = r#"
[study]
title = "goal inputs"

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [10.0, 2.0]
cells = [2, 1]

[analysis]
type = "plane_stress"

[[parameter]]
name = "E"
law = "uniform"
lo = 150e3
hi = 250e3

[[substructure]]
name = "plate"
young = "E"
poisson = 0.0
constraint = [ { group = "xmin", x = 0.0 }, { group = "ymin", y = 0.0 } ]
load = [ { group = "xmax", traction = [1.0, 0.0] } ]

[[quantity]]
name = "tip"
kind = "displacement"
substructure = "plate"
point = [10.0, 2.0]
component = 0

[error]

[[method]]
"#;

fn load(method: &str) -> Result<Study, StudyError> {
    Study::from_source(Source::from_text("goal.toml", &format!("{BASE}{method}")))
}

fn refused(method: &str, field: &str, words: &str) {
    let e = load(method).expect_err("refused");
    let text = e.to_string();
    assert!(text.contains("goal.toml:"), "{text}");
    assert!(text.contains(field), "{field} in {text}");
    assert!(text.contains(words), "'{words}' in {text}");
}

#[test]
fn a_goal_naming_an_unknown_quantity_is_refused() {
    refused(
        "type = \"adaptive\"\ngoal = { quantity = \"tipp\", tolerance = 0.01 }\n",
        "method[0].goal.quantity",
        "unknown quantity 'tipp'",
    );
}

#[test]
fn a_goal_needs_one_tolerance_below_one_for_a_probability() {
    refused(
        "type = \"adaptive\"\ngoal = { quantity = \"tip\" }\n",
        "method[0].goal",
        "needs tolerance",
    );
    refused(
        "type = \"adaptive\"\ngoal = { quantity = \"tip\", threshold = 0.01, tolerance = 2.0 }\n",
        "method[0].goal.tolerance",
        "below 1",
    );
    refused(
        "type = \"adaptive\"\ngoal = { quantity = \"tip\", tolerance = 0.1, relative_tolerance = 0.1 }\n",
        "method[0].goal.relative_tolerance",
        "not both",
    );
}

#[test]
fn only_an_adaptive_method_has_a_goal() {
    refused(
        "type = \"piecewise_linear\"\ngoal = { quantity = \"tip\", tolerance = 0.01 }\n",
        "method[0].goal",
        "only an adaptive method",
    );
}

#[test]
fn a_valid_goal_is_accepted_and_described() {
    let s = load(
        "type = \"adaptive\"\ngoal = { quantity = \"tip\", threshold = 1e-4, relative_tolerance = 0.05 }\n",
    )
    .unwrap();
    assert!(
        s.methods[0]
            .description
            .contains("goal: the error budget of P(tip > 0.0001)"),
        "{}",
        s.methods[0].description
    );
}

/// The threshold of `P(tip > t) = 0.4` (`tip = 10 / E` mm, `E ~ U(150e3, 250e3)` MPa).
const TIP_THRESHOLD: f64 = 10.0 / 190e3;

/// Runs the study whose method is a goal on `P(tip > TIP_THRESHOLD)` with `tolerance` and
/// `max_runs`, in a fresh directory named after `name` (removed after): the study and its runs.
fn run_tip_goal(
    name: &str,
    tolerance: f64,
    max_runs: usize,
) -> (Study, alea_study::runner::StudyRuns) {
    use alea_study::runner::{NoProgress, run_study};
    let s = load(&format!(
        "type = \"adaptive\"\ngoal = {{ quantity = \"tip\", threshold = {TIP_THRESHOLD:e}, tolerance = {tolerance:e} }}\nmax_runs = {max_runs}\n"
    ))
    .unwrap();
    let dir = std::env::temp_dir().join(format!("alea-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&s, &dir, false, &NoProgress).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (s, runs)
}

/// End to end against an exact failure probability: `tip = s L / E` exactly (a linear field,
/// traction s = 1 MPa, L = 10 mm), `E ~ U(150e3, 250e3)`, so
/// `P(tip > t) = (s L / t - 150e3) / 100e3`. The goal-oriented loop stops when its budget is
/// within the tolerance, and the exact probability lies within the reported total of the value;
/// the loop's last budget is the one the analysis reports (same comparisons, same draws).
#[test]
fn a_goal_oriented_loop_reaches_an_exact_failure_probability_within_its_budget() {
    let (s, runs) = run_tip_goal("goal", 0.01, 40);
    let t = TIP_THRESHOLD;
    let a = &runs.adaptive[0];
    assert!(a.stop.starts_with("goal reached"), "{}", a.stop);
    let last = a.steps.last().unwrap();
    let g = &last.goal[0];
    let exact = (10.0 / t - 150e3) / 100e3;
    assert!(
        (g.value - exact).abs() <= g.total && g.total <= 0.01,
        "P = {} +- {} vs exact {exact}",
        g.value,
        g.total
    );
    let settings = alea_study::analysis::analysis_settings(&s).unwrap();
    let method = &runs.methods[0];
    let res = alea_study::analysis::analyse_method(&s, method, &runs.records, &settings);
    let row = res.qois[0]
        .budget
        .as_ref()
        .unwrap()
        .rows
        .last()
        .unwrap()
        .clone();
    assert!(row.statistic.is_probability(), "{}", row.statistic);
    assert_eq!((row.value, row.total), (g.value, g.total), "report vs loop");
}

/// A tolerance below the sampling half-width of the goal statistic cannot be met by runs: the
/// loop stops on its run budget and its stop message says that the sampling part alone exceeds
/// the tolerance (250 000 draws give about 2e-3 on a probability of 0.4).
#[test]
fn a_tolerance_below_the_sampling_part_is_named_when_the_loop_stops() {
    let (_, runs) = run_tip_goal("goal-floor", 1e-5, 6);
    let a = &runs.adaptive[0];
    assert!(a.stop.starts_with("run budget of 6 reached"), "{}", a.stop);
    assert!(
        a.stop.contains("the sampling part of P(> ") && a.stop.contains("more runs do not"),
        "{}",
        a.stop
    );
}

/// A threshold outside the quantity's range over the start design (`tip` lies in
/// `[10 / 250e3, 10 / 150e3] = [4e-5, 6.7e-5]` mm) is an input error at the threshold's line,
/// raised after the start design's three runs, before any refinement (the range is not known
/// before a run); those runs are stored.
#[test]
fn a_threshold_outside_the_quantity_range_is_refused_at_its_line() {
    use alea_study::runner::{NoProgress, run_study};
    let s = load(
        "type = \"adaptive\"\ngoal = { quantity = \"tip\", threshold = 1.0, tolerance = 0.01 }\nmax_runs = 20\n",
    )
    .unwrap();
    let dir = std::env::temp_dir().join(format!("alea-goal-range-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let Err(e) = run_study(&s, &dir, false, &NoProgress) else {
        panic!("a threshold outside the range was accepted");
    };
    let text = e.to_string();
    let line = BASE.lines().count() + 2; // the goal is the second line of the method
    assert!(matches!(e, StudyError::Input { .. }), "{text}");
    assert!(
        text.contains(&format!("goal.toml:{line}")),
        "line {line} in {text}"
    );
    assert!(text.contains("method[0].goal.threshold"), "{text}");
    assert!(text.contains("outside the range"), "{text}");
    assert_eq!(e.exit_code(), 2, "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
