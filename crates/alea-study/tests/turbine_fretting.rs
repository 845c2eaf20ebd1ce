//! `examples/turbine-2d-fretting.toml` on its coarsened copy (every mesh count halved;
//! piecewise linear 5 x 5, no error budget; 2 s): what its header states, and an invariant
//! nobody tuned.
//!
//! - Mirror symmetry: I1's wear is I2's mirrored (its neck carries `b`, its bottom `a`) on a
//!   mesh whose halves are mirror images, so every quantity of I1 at `(a, b)` equals that of
//!   I2 at `(b, a)`: two runs solved from different starts, equal to the solver tolerance
//!   (the 5 x 5 grid is symmetric in `a <-> b`; measured 4.3e-4 at worst, F1, at the
//!   tolerance 1e-7).
//! - The header's story: without wear both flanks slide over their whole length (gross slip,
//!   a slip amplitude above 8 um); wear at the root's bottom end (`b = 1`) makes I2 stick but
//!   near its ends (1 - 4 um) and the work per cycle falls at least 5x; the Sobol' indices
//!   put the work and the slip on `b` and the root's SWT on `a`.

use alea_study::Source;
use alea_study::runner::{NoProgress, Study, run_study};

/// The example with every `n_*` count halved (the fillet's kept even), 5 x 5 runs, no budget,
/// and the quantities of I1 beside those of I2.
fn coarsened() -> Study {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/turbine-2d-fretting.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut doc: toml::Table = toml::from_str(&text).unwrap();
    let params = doc["mesh"]["params"].as_table_mut().unwrap();
    for (k, v) in params.iter_mut() {
        if let (true, Some(n)) = (k.starts_with("n_"), v.as_integer()) {
            let half = (n / 2).max(1);
            *v = toml::Value::Integer(if k == "n_fillet" {
                half + half % 2
            } else {
                half
            });
        }
    }
    doc.remove("budget");
    doc.remove("method");
    let text = format!(
        "{}\n{}",
        toml::to_string(&doc).unwrap(),
        r#"
[[quantity]]
name = "work_I1"
kind = "friction_work_cycle"
interface = "I1"

[[quantity]]
name = "slip_I1"
kind = "slip_amplitude"
interface = "I1"

[[quantity]]
name = "f1_I1"
kind = "ruiz_f1"
interface = "I1"

[[quantity]]
name = "swt_disk_I1"
kind = "swt"
interface = "I1"
substructure = "D1"
critical_distance = 0.3

[[quantity]]
name = "swt_root_I1"
kind = "swt"
interface = "I1"
substructure = "A1"
critical_distance = 0.3

[[method]]
type = "piecewise_linear"
points_per_dim = 5

[budget]
validation_runs = 0

[statistics]
samples = 20000
"#
    );
    Study::from_source(Source::from_text("turbine-2d-fretting.toml", &text)).unwrap()
}

#[test]
fn the_fretting_example_is_mirror_symmetric_and_tells_its_story() {
    let study = coarsened();
    let names: Vec<&str> = study.qois.iter().map(|q| q.name.as_str()).collect();
    let at = |n: &str| names.iter().position(|&m| m == n).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-turbine-fretting-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(runs.records.len(), 25);
    let run = |a: f64, b: f64| {
        runs.records
            .iter()
            .find(|r| (r.params[0] - a).abs() < 1e-12 && (r.params[1] - b).abs() < 1e-12)
            .unwrap_or_else(|| panic!("no run at ({a}, {b})"))
    };
    for r in &runs.records {
        assert!(r.converged(), "{:?}: {}", r.params, r.status);
        let mirror = run(r.params[1], r.params[0]);
        for (i1, i2) in [
            ("work_I1", "work_I2"),
            ("slip_I1", "slip_I2"),
            ("f1_I1", "f1_I2"),
            ("swt_disk_I1", "swt_disk"),
            ("swt_root_I1", "swt_root"),
        ] {
            let (x, y) = (r.qois[at(i1)], mirror.qois[at(i2)]);
            assert!(
                (x - y).abs() <= 1e-3 * y.abs(),
                "{i1} at {:?} = {x}, {i2} at the mirror point = {y}",
                r.params
            );
        }
    }
    let (work, slip) = (at("work_I2"), at("slip_I2"));
    let unworn = run(0.0, 0.0);
    assert!(unworn.qois[slip] > 8e-3, "gross slip {}", unworn.qois[slip]);
    for a in [0.0, 0.5, 1.0] {
        let worn = run(a, 1.0);
        assert!(
            (1e-3..4e-3).contains(&worn.qois[slip]),
            "partial slip at ({a}, 1): {}",
            worn.qois[slip]
        );
        assert!(
            worn.qois[work] * 5.0 < unworn.qois[work],
            "work {} at ({a}, 1) against {} unworn",
            worn.qois[work],
            unworn.qois[work]
        );
    }
    let stats = alea_study::analysis::analyse_method(
        &study,
        &study.methods[0],
        &runs.records,
        &alea_study::analysis::AnalysisSettings {
            samples: 20_000,
            bandwidth: alea_uq::kde::Bandwidth::Silverman,
            kde_points: 64,
            confidence: 0.95,
        },
    );
    let first = |q: &str, p: usize| stats.qois[at(q)].sobol.as_ref().expect("Sobol'").first[p];
    for q in ["work_I2", "slip_I2", "f1_I2"] {
        assert!(first(q, 1) > 0.6, "{q}: S_b = {}", first(q, 1));
    }
    assert!(
        first("swt_root", 0) > 0.6,
        "swt_root: S_a = {}",
        first("swt_root", 0)
    );
}
