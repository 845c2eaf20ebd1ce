//! Load cycles (`[cycle]`) with large sliding (`sliding = "large"`: each cycle step re-paired
//! in its deformed configuration, module `alea_latin::large_sliding`), checked against truths,
//! not snapshots, on the block pressed on a base of `tests/fretting_cycle.rs` (mu uncertain,
//! a small Monte Carlo study):
//! - sheared by a load with partial slip, slides of 1e-8 of a cell: the quantities of the
//!   small-sliding cycle, to the solver tolerance;
//! - the same history written as plain `[[step]]`s (a cycle of one repetition over the last
//!   two): the same answers to round-off (large-sliding steps have no warm start, so the two
//!   are the same solves);
//! - slid by an imposed displacement of +-2.5 cells (gross slip): the frictional work per cycle
//!   equals the sum of the cycle steps' friction dissipations (two computations through
//!   different code), equals `4 mu N delta` (Coulomb's law in gross slip: the force `mu N` over
//!   the path `4 delta`) to a few percent, the cycle shakes down at two cycles (`until` gives
//!   the `repeat = 2` answers), and large sliding differs measurably from small sliding there
//!   (the block overhangs the base by 5 mm: its contact zone and pressure move);
//! - the load checks of the combinations refused with large sliding (file, line, field).

mod fretting_block;

use alea_study::Source;
use alea_study::runner::{NoProgress, Study, run_study};

/// The block on the base (`fretting_block`), its top loaded by `top`, with the interface's
/// `sliding`, then `steps`, `cycle` and `quantities`.
fn model(top: &str, sliding: &str, steps: &str, cycle: &str, quantities: &str) -> String {
    fretting_block::block_on_base(
        "fretting cycle, large sliding",
        top,
        sliding,
        steps,
        cycle,
        quantities,
        2,
    )
}

/// Pressed by `10 s` MPa and sheared by a load `+-2.2 s` MPa, `T / (mu N) <= 0.73`: partial
/// slip, the slides proportional to `s` (in small sliding every displacement is).
fn sheared(s: f64) -> String {
    format!(
        "load = [\n  {{ name = \"press\", group = \"upper_top\", traction = [0.0, {:?}] }},\n  \
         {{ name = \"shear\", group = \"upper_top\", traction = [{:?}, 0.0] }},\n]",
        -10.0 * s,
        2.2 * s
    )
}

const SHEAR_STEPS: &str = r#"
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

const CYCLE: &str = "[cycle]\nsteps = [\"down\", \"back\"]\nrepeat = 2";

/// The fretting quantities a cycle in large sliding gives, and the two steps' dissipations.
fn quantities(down: &str, back: &str) -> String {
    format!(
        r#"
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
step = "{down}"

[[quantity]]
name = "d_back"
kind = "friction_dissipation"
interface = "contact"
step = "{back}"

[[quantity]]
name = "f1"
kind = "ruiz_f1"
interface = "contact"

[[quantity]]
name = "swt"
kind = "swt"
interface = "contact"
substructure = "base"
critical_distance = 0.5

[[quantity]]
name = "fs"
kind = "fatemi_socie"
interface = "contact"
substructure = "block"
critical_distance = 0.5
normal_stress_factor = 0.5
yield_stress = 250.0

[[quantity]]
name = "stick"
kind = "stick_zone"
interface = "contact"
"#
    )
}

const NAMES: [&str; 8] = [
    "delta", "work", "d_down", "d_back", "f1", "swt", "fs", "stick",
];

/// The quantities of every run of the study `text`, and the seconds it took.
fn run(text: &str, name: &str) -> (Vec<Vec<f64>>, f64) {
    let (q, _, seconds) = run_with_params(text, name);
    (q, seconds)
}

/// [`run`], with the parameters of every run.
fn run_with_params(text: &str, name: &str) -> (Vec<Vec<f64>>, Vec<Vec<f64>>, f64) {
    let study = Study::from_source(Source::from_text("large.toml", text)).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-cycle-large-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let t = std::time::Instant::now();
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let seconds = t.elapsed().as_secs_f64();
    let _ = std::fs::remove_dir_all(&dir);
    let q = runs
        .records
        .iter()
        .map(|r| {
            assert!(r.converged(), "{}", r.status);
            r.qois.clone()
        })
        .collect();
    let params = runs.records.iter().map(|r| r.params.clone()).collect();
    (q, params, seconds)
}

/// Largest relative difference per quantity between the runs of `a` and `b`.
fn differences(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<f64> {
    (0..a[0].len())
        .map(|j| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x[j] - y[j]).abs() / y[j].abs().max(1e-300))
                .fold(0.0, f64::max)
        })
        .collect()
}

/// Slides of 1e-8 of a cell (loads scaled by 1e-6): large sliding is small sliding to the
/// solver tolerance. The difference is geometric, of the order of the slide over the cell for
/// the integrals (measured: 3e-5 at loads scaled by 1e-3, slides of 1e-5 cell; 3 % at the
/// loads of `tests/fretting_cycle.rs`, slides of 0.8 % of a cell, for the slip amplitude of
/// 3e-4 of the slide), so the tolerance here is that of the solver: 1e-9 on states whose
/// cycle increments are 1e-2 - 1e-4 of them (the slip amplitude is 3e-4 of the slip, the work
/// per cycle 1 % of the first loading's dissipation), so 1e-5 (measured: 2.5e-6 at most, on
/// the dissipation of a step).
/// The stick zone is compared to a cell only: the points of a slip zone at the friction limit
/// with no slip increment in a step (`|q| = mu p`, slip 1e-17) are stick or slip by
/// round-off, in either model.
#[test]
fn tiny_slides_give_the_small_sliding_cycle() {
    let q = quantities("down", "back");
    let tiny = sheared(1e-6);
    let (small, ts) = run(&model(&tiny, "small", SHEAR_STEPS, CYCLE, &q), "tiny-small");
    let (large, tl) = run(&model(&tiny, "large", SHEAR_STEPS, CYCLE, &q), "tiny-large");
    let d = differences(&large, &small);
    for ((name, e), (s, l)) in NAMES.iter().zip(&d).zip(small[0].iter().zip(&large[0])) {
        eprintln!("{name:>7}: small {s:.6e}, large {l:.6e}, largest relative difference {e:.2e}");
    }
    eprintln!("seconds: small {ts:.2}, large {tl:.2}");
    for (r, s) in large.iter().zip(&small) {
        // The work per cycle is the sum of the cycle steps' dissipations.
        assert!((r[1] - (r[2] + r[3])).abs() <= 1e-9 * r[1], "{r:?}");
        assert!(
            r[0] > 0.0 && r[1] > 0.0 && r[7] > 0.0 && r[7] < 40.0,
            "{r:?}"
        );
        assert!(
            (r[7] - s[7]).abs() <= 2.0,
            "stick zone {} against {}",
            r[7],
            s[7]
        );
    }
    for (name, e) in NAMES.iter().zip(&d).take(7) {
        assert!(*e <= 1e-5, "{name}: {e:e}");
    }
}

/// With large sliding a cycle step has no warm start from the previous cycle (each starts
/// from its predicted configuration, `alea_study::steps::run_large_sliding`): the cycle and the
/// same history written as plain steps are the same solves, so the same answers to round-off
/// (here on the block slid over 2.5 cells, re-paired in every step).
#[test]
fn a_large_sliding_cycle_gives_the_answers_of_its_steps_written_out() {
    let (cycle, _) = run(
        &model(
            SLID,
            "large",
            &slid_steps(5.0),
            "[cycle]\nsteps = [\"down\", \"back\"]\nrepeat = 3",
            &quantities("down", "back"),
        ),
        "cycle",
    );
    let written_steps = format!(
        "{}{}{}{}{}",
        slid_steps(5.0),
        slid_step("down2", -5.0),
        slid_step("back2", 5.0),
        slid_step("down3", -5.0),
        slid_step("back3", 5.0)
    );
    let (written, _) = run(
        &model(
            SLID,
            "large",
            &written_steps,
            "[cycle]\nsteps = [\"down3\", \"back3\"]\nrepeat = 1",
            &quantities("down3", "back3"),
        ),
        "written",
    );
    let d = differences(&cycle, &written);
    eprintln!("cycle against written out: {d:?}");
    for (name, e) in NAMES.iter().zip(&d) {
        assert!(*e <= 1e-12, "{name}: {e:e}");
    }
}

/// Slid by `+-5` mm (2.5 cells) by an imposed displacement of its top, pressed by 10 MPa.
const SLID: &str = r#"constraint = [ { group = "upper_top", x = 0.0 } ]
load = [ { name = "press", group = "upper_top", traction = [0.0, -10.0] } ]"#;

/// A step that moves the block's top to `x`.
fn slid_step(name: &str, x: f64) -> String {
    format!(
        "[[step]]\nname = \"{name}\"\nconstraint = [ {{ substructure = \"block\", group = \"upper_top\", x = {x:?} }} ]\n\n"
    )
}

/// Press, then slide the block's top to `d`, `-d` and `d`.
fn slid_steps(d: f64) -> String {
    [
        slid_step("press", 0.0),
        slid_step("up", d),
        slid_step("down", -d),
        slid_step("back", d),
    ]
    .concat()
}

#[test]
fn a_cycle_slid_over_cells_dissipates_its_steps_work_and_shakes_down() {
    let q = quantities("down", "back");
    let steps = slid_steps(5.0);
    let until = "[cycle]\nsteps = [\"down\", \"back\"]\nuntil = 1e-6\nrepeat = 6";
    let (large, params, tl) =
        run_with_params(&model(SLID, "large", &steps, until, &q), "slid-until");
    let (twice, _) = run(&model(SLID, "large", &steps, CYCLE, &q), "slid-twice");
    // Small sliding needs many iterations for a block slid far (docs/study-file.md,
    // linear_stage).
    let small_model = model(SLID, "small", &steps, CYCLE, &q).replace(
        "tolerance = 1e-9\n",
        "tolerance = 1e-9\nmax_iterations = 20000\n",
    );
    let (small, ts) = run(&small_model, "slid-small");
    let d = differences(&large, &small);
    for ((name, e), (s, l)) in NAMES.iter().zip(&d).zip(small[0].iter().zip(&large[0])) {
        eprintln!("{name:>7}: small {s:.6e}, large {l:.6e}, relative difference {e:.2e}");
    }
    eprintln!("seconds: large (until) {tl:.2}, small {ts:.2}");
    // Shakedown: the history stops at two cycles.
    let same = differences(&large, &twice);
    assert!(same.iter().all(|&e| e <= 1e-12), "{same:?}");
    for (r, theta) in large.iter().zip(&params) {
        let [delta, work, d_down, d_back, ..] = r[..] else {
            panic!("8 quantities");
        };
        assert!((work - (d_down + d_back)).abs() <= 1e-9 * work, "{r:?}");
        // Gross slip: the stick zone is empty and the slip amplitude is the slide less the
        // elastic shear of the block and the base.
        assert!(r[7] == 0.0, "stick zone {}", r[7]);
        assert!(delta > 4.9 && delta <= 5.0, "delta {delta}");
        // Coulomb's law in gross slip: the force mu N (N = 10 MPa x 40 mm) over the path
        // 4 delta.
        let coulomb = 4.0 * theta[0] * 400.0 * delta;
        eprintln!(
            "mu {}: work {work:.6e}, 4 mu N delta {coulomb:.6e}",
            theta[0]
        );
        assert!(
            (work / coulomb - 1.0).abs() <= 1e-2,
            "{work} against {coulomb}"
        );
    }
    // Large sliding is measurably another model here: the block overhangs the base by 5 mm
    // at the ends of the cycle, its contact zone and the stresses under its edges move.
    assert!(d[4] > 0.1 && d[5] > 0.1, "F1 and SWT: {d:?}");
}

fn refused(quantity: &str, needle: &str, field: &str, words: &str) {
    let text = model(&sheared(1e-3), "large", SHEAR_STEPS, CYCLE, quantity);
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

#[test]
fn fretting_quantities_without_meaning_under_repairing_are_refused_at_load() {
    refused(
        "[[quantity]]\nname = \"f2\"\nkind = \"ruiz_f2\"\ninterface = \"contact\"\n",
        "kind = \"ruiz_f2\"",
        "quantity[0].kind",
        "slide apart",
    );
    refused(
        "[[quantity]]\nname = \"d\"\nkind = \"slip_amplitude\"\ninterface = \"contact\"\npoint = [10.0, 0.0]\n",
        "point = [10.0, 0.0]",
        "quantity[0].point",
        "leave out point",
    );
    // The sliding part of the budget of a small-sliding study with such a quantity: refused
    // at the quantity's line, saying why.
    let text = model(
        &sheared(1e-3),
        "small",
        SHEAR_STEPS,
        CYCLE,
        "[[quantity]]\nname = \"f2\"\nkind = \"ruiz_f2\"\ninterface = \"contact\"\n\n\
         [budget]\nlarge_sliding = true\n",
    );
    let msg = Study::from_source(Source::from_text("checks.toml", &text))
        .expect_err("refused")
        .to_string();
    let line = |needle: &str| text.lines().position(|l| l.contains(needle)).unwrap() + 1;
    assert!(
        msg.contains(&format!("checks.toml:{}:", line("kind = \"ruiz_f2\"")))
            && msg.contains("quantity[0].kind")
            && msg.contains("the sliding part of [budget]")
            && msg.contains("slide apart"),
        "{msg}"
    );
    // The same quantities in small sliding load.
    let text = model(
        &sheared(1e-3),
        "small",
        SHEAR_STEPS,
        CYCLE,
        "[[quantity]]\nname = \"f2\"\nkind = \"ruiz_f2\"\ninterface = \"contact\"\n",
    );
    assert!(Study::from_source(Source::from_text("ok.toml", &text)).is_ok());
}
