//! Load cycles (`[cycle]`, module `cycle`) and the fretting quantities (`qoi::fretting`) in a
//! study: a steel block pressed on an aluminium base (the set-up of
//! `examples/shear-unload-steps.toml`), then sheared back and forth by `+-T` with
//! `T / (mu N) <= 0.6` (partial slip at the edges of the contact).
//!
//! Checked on every run of a small Monte Carlo study (mu uncertain):
//! - the frictional work of the last cycle (`friction_work_cycle`, integrated) equals the
//!   friction dissipations of the cycle's two steps (`friction_dissipation` with `step`, which
//!   with a cycle measures the step of the **last** cycle from the step before it): two
//!   computations through different code (module `alea_latin::fretting` and the step
//!   quantities of `alea_latin::steps`), equal to round-off;
//! - shakedown: with `until`, a cycle that repeats itself stops the history at two cycles
//!   (here elastic shakedown after the first loading, as Mindlin-Deresiewicz), so the study
//!   with `until` gives the values of the study with `repeat = 2`;
//! - bounds: the slip amplitude is positive (the edges slip) and at most the largest slip of
//!   the history; the stick zone lies in `(0, 40)` mm (the contact is 40 mm wide and its
//!   edges slip); F1 <= mu p_max delta (tau <= mu p); SWT and F2 are finite and >= 0.
//!
//! And the load checks: file, line and field of each refused input.

mod fretting_block;

use alea_study::Source;
use alea_study::runner::{NoProgress, Study, run_study};

/// The block on the base (`fretting_block`), pressed and sheared by the loads the steps
/// scale: pressed, then the shear up, down and back up.
fn model(cycle: &str, quantities: &str) -> String {
    fretting_block::block_on_base(
        "fretting cycle",
        "load = [\n  { name = \"press\", group = \"upper_top\", traction = [0.0, -10.0] },\n  \
         { name = \"shear\", group = \"upper_top\", traction = [2.2, 0.0] },\n]",
        "small",
        STEPS,
        cycle,
        quantities,
        3,
    )
}

const STEPS: &str = r#"
[[step]]
name = "press"
load = { shear = 0.0 }

[[step]]
name = "up"
load = { shear = 1.0 }

[[step]]
name = "down"
load = { shear = -1.0 }

[[step]]
name = "back"
load = { shear = 1.0 }
"#;

const QUANTITIES: &str = r#"
[[quantity]]
name = "delta"
kind = "slip_amplitude"
interface = "contact"

[[quantity]]
name = "work"
kind = "friction_work_cycle"
interface = "contact"

[[quantity]]
name = "d_down"
kind = "friction_dissipation"
interface = "contact"
step = "down"

[[quantity]]
name = "d_back"
kind = "friction_dissipation"
interface = "contact"
step = "back"

[[quantity]]
name = "f1"
kind = "ruiz_f1"
interface = "contact"

[[quantity]]
name = "f2"
kind = "ruiz_f2"
interface = "contact"

[[quantity]]
name = "swt"
kind = "swt"
interface = "contact"
substructure = "base"
critical_distance = 0.5

[[quantity]]
name = "stick"
kind = "stick_zone"
interface = "contact"

[[quantity]]
name = "slip_left"
kind = "contact_slip"
interface = "contact"
point = [0.0, 0.0]

"#;

/// Fatemi-Socie at the interface point `(10, 0)`, with normal-stress sensitivity `k` and
/// yield stress 250 MPa.
fn fatemi_socie(k: f64) -> String {
    format!(
        "[[quantity]]\nname = \"fs{k}\"\nkind = \"fatemi_socie\"\ninterface = \"contact\"\n\
         substructure = \"base\"\npoint = [10.0, 0.0]\ncritical_distance = 0.5\n\
         normal_stress_factor = {k:?}\nyield_stress = 250.0\n\n"
    )
}

fn run(cycle: &str, name: &str) -> Vec<Vec<f64>> {
    let quantities = format!("{QUANTITIES}{}", [0.0, 0.5, 1.0].map(fatemi_socie).concat());
    let study = Study::from_source(Source::from_text(
        "fretting.toml",
        &model(cycle, &quantities),
    ))
    .unwrap();
    let dir = std::env::temp_dir().join(format!("alea-fretting-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    runs.records
        .iter()
        .map(|r| {
            assert!(r.converged(), "{}", r.status);
            r.qois.clone()
        })
        .collect()
}

#[test]
fn cycle_quantities_are_consistent_and_shake_down() {
    let until = run(
        "[cycle]\nsteps = [\"down\", \"back\"]\nuntil = 1e-6\nrepeat = 6",
        "until",
    );
    let twice = run("[cycle]\nsteps = [\"down\", \"back\"]\nrepeat = 2", "twice");
    for (a, b) in until.iter().zip(&twice) {
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 1e-9 * x.abs().max(1e-12), "{a:?} vs {b:?}");
        }
    }
    for q in &until {
        let [
            delta,
            work,
            d_down,
            d_back,
            f1,
            f2,
            swt,
            stick,
            _,
            fs0,
            fs05,
            fs1,
        ] = q[..]
        else {
            panic!("12 quantities");
        };
        // Fatemi-Socie at one point: its critical plane does not depend on the material
        // constants, so the parameter is linear in k there (the factor 1 + k sigma_n / sigma_y
        // is far from its floor at these stresses): the constants reach the quantity.
        assert!(fs0 > 0.0 && fs0.is_finite(), "FS {fs0}");
        assert!(
            ((fs1 - fs0) - 2.0 * (fs05 - fs0)).abs() <= 1e-9 * fs0,
            "FS {fs0}, {fs05}, {fs1}"
        );
        eprintln!(
            "delta {delta:.4e} mm, work {work:.4e} N mm/mm (steps {d_down:.4e} + {d_back:.4e}), \
             F1 {f1:.4e}, F2 {f2:.4e}, SWT {swt:.4e}, stick {stick:.3} mm"
        );
        assert!(
            (work - (d_down + d_back)).abs() <= 1e-9 * work,
            "{work} vs {d_down} + {d_back}"
        );
        assert!(delta > 0.0 && work > 0.0 && f1 > 0.0);
        assert!(stick > 0.0 && stick < 40.0, "stick zone {stick}");
        assert!(f2 >= 0.0 && swt > 0.0 && f2.is_finite() && swt.is_finite());
    }
}

/// A cycle's steps from the second cycle on start their LATIN iterate from the same step of
/// the previous cycle, and the first cycle's return to an earlier step's loads from that step
/// (`alea_study::steps`): only the start of the iteration, so the answers are those of the
/// same history written as plain steps, each started from the step before, to the solver
/// tolerance (1e-9 here).
#[test]
fn a_cycle_gives_the_answers_of_its_steps_written_out() {
    let quantities = |down: &str, back: &str| {
        format!(
            "{DELTA}\n[[quantity]]\nname = \"d_down\"\nkind = \"friction_dissipation\"\n\
             interface = \"contact\"\nstep = \"{down}\"\n\n[[quantity]]\nname = \"d_back\"\n\
             kind = \"friction_dissipation\"\ninterface = \"contact\"\nstep = \"{back}\"\n"
        )
    };
    let solve = |text: String| {
        let study = Study::from_source(Source::from_text("written.toml", &text)).unwrap();
        let dir = std::env::temp_dir().join(format!(
            "alea-fretting-written-{}-{}",
            text.len(),
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        runs.records
            .iter()
            .map(|r| {
                assert!(r.converged(), "{}", r.status);
                r.qois.clone()
            })
            .collect::<Vec<_>>()
    };
    let cycle = solve(model(
        "[cycle]\nsteps = [\"down\", \"back\"]\nrepeat = 3",
        &quantities("down", "back"),
    ));
    let written = solve(model(
        "[[step]]\nname = \"down2\"\nload = { shear = -1.0 }\n\n\
         [[step]]\nname = \"back2\"\nload = { shear = 1.0 }\n\n\
         [[step]]\nname = \"down3\"\nload = { shear = -1.0 }\n\n\
         [[step]]\nname = \"back3\"\nload = { shear = 1.0 }\n",
        &quantities("down3", "back3").replace(DELTA, ""),
    ));
    for (c, w) in cycle.iter().zip(&written) {
        // The cycle's: slip amplitude, then the two dissipations of the last cycle.
        assert!(c[1] > 0.0 && c[2] > 0.0, "{c:?}");
        for (x, y) in c[1..].iter().zip(w) {
            assert!((x - y).abs() <= 1e-6 * y.abs(), "{c:?} against {w:?}");
        }
    }
}

fn refused(cycle: &str, quantities: &str, needle: &str, field: &str, words: &str) {
    let text = model(cycle, quantities);
    let e = Study::from_source(Source::from_text("checks.toml", &text)).expect_err("refused");
    let msg = e.to_string();
    let line = text
        .lines()
        .position(|l| l.contains(needle))
        .map(|i| i + 1)
        .unwrap();
    assert!(
        msg.contains(&format!("checks.toml:{line}:")),
        "line {line}: {msg}"
    );
    assert!(msg.contains(field), "{field}: {msg}");
    assert!(msg.contains(words), "'{words}': {msg}");
}

const DELTA: &str =
    "[[quantity]]\nname = \"delta\"\nkind = \"slip_amplitude\"\ninterface = \"contact\"\n";
const CYCLE: &str = "[cycle]\nsteps = [\"down\", \"back\"]\nrepeat = 2";

#[test]
fn bad_cycles_and_fretting_quantities_are_refused_at_load() {
    refused(
        "[cycle]\nsteps = []\nrepeat = 2",
        DELTA,
        "steps = []",
        "cycle.steps",
        "at least one step",
    );
    refused(
        "[cycle]\nsteps = [\"down\", \"nope\"]\nrepeat = 2",
        DELTA,
        "\"nope\"",
        "cycle.steps[1]",
        "no step is named 'nope'",
    );
    refused(
        "[cycle]\nsteps = [\"up\", \"down\"]\nrepeat = 2",
        DELTA,
        "steps = [\"up\"",
        "cycle.steps",
        "the last steps of the history",
    );
    refused(
        "[cycle]\nsteps = [\"back\"]\nrepeat = 0",
        DELTA,
        "repeat = 0",
        "cycle.repeat",
        "at least one cycle",
    );
    refused(
        "[cycle]\nsteps = [\"back\"]\nuntil = -1.0",
        DELTA,
        "until = -1.0",
        "cycle.until",
        "(0, 1)",
    );
    // Fretting quantities: no cycle, a step, a critical distance <= 0 or beyond the contact.
    refused(
        "",
        DELTA,
        "kind = \"slip_amplitude\"",
        "quantity[0].kind",
        "measured over a load cycle",
    );
    refused(
        CYCLE,
        &format!("{DELTA}step = \"back\"\n"),
        "step = \"back\"",
        "quantity[0].step",
        "leave out step",
    );
    let swt = |l: &str| {
        format!(
            "[[quantity]]\nname = \"s\"\nkind = \"swt\"\ninterface = \"contact\"\ncritical_distance = {l}\n"
        )
    };
    refused(
        CYCLE,
        &swt("0.0"),
        "critical_distance = 0.0",
        "quantity[0].critical_distance",
        "must be > 0",
    );
    refused(
        CYCLE,
        &swt("50.0"),
        "critical_distance = 50.0",
        "quantity[0].critical_distance",
        "not smaller than the contact zone",
    );
    refused(
        CYCLE,
        "[[quantity]]\nname = \"s\"\nkind = \"swt\"\ninterface = \"contact\"\n",
        "kind = \"swt\"",
        "quantity[0].critical_distance",
        "missing",
    );
    refused(
        CYCLE,
        &format!("{DELTA}critical_distance = 1.0\n"),
        "critical_distance = 1.0",
        "quantity[0].critical_distance",
        "not used by a 'slip_amplitude' quantity",
    );
    // Fatemi-Socie: both material constants required, k >= 0, yield stress > 0, and neither
    // on another kind.
    let fs = |extra: &str| {
        format!(
            "[[quantity]]\nname = \"f\"\nkind = \"fatemi_socie\"\ninterface = \"contact\"\ncritical_distance = 0.5\n{extra}"
        )
    };
    refused(
        CYCLE,
        &fs("normal_stress_factor = 0.5\n"),
        "kind = \"fatemi_socie\"",
        "quantity[0].yield_stress",
        "missing",
    );
    refused(
        CYCLE,
        &fs("normal_stress_factor = -0.5\nyield_stress = 250.0\n"),
        "normal_stress_factor = -0.5",
        "quantity[0].normal_stress_factor",
        ">= 0",
    );
    refused(
        CYCLE,
        &fs("normal_stress_factor = 0.5\nyield_stress = 0.0\n"),
        "yield_stress = 0.0",
        "quantity[0].yield_stress",
        "must be > 0",
    );
    refused(
        CYCLE,
        &format!("{}yield_stress = 250.0\n", swt("0.5")),
        "yield_stress = 250.0",
        "quantity[0].yield_stress",
        "not used by a 'swt' quantity",
    );
    // A perfect (bonded) interface has no slip.
    let text = model(CYCLE, DELTA).replace("law = \"coulomb\"\nmu = \"mu\"", "law = \"perfect\"");
    let e = Study::from_source(Source::from_text("checks.toml", &text)).expect_err("refused");
    let line = text
        .lines()
        .position(|l| l.starts_with("interface = \"contact\""))
        .unwrap()
        + 1;
    let msg = e.to_string();
    assert!(msg.contains(&format!("checks.toml:{line}:")), "{msg}");
    assert!(
        msg.contains("quantity[0].interface") && msg.contains("perfect"),
        "{msg}"
    );
}
