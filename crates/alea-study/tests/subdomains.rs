//! Automatic subdomains in a study (`[solver] subdomains`, `subdomain_dofs`; module
//! `alea_latin::split`): the shipped 3D turbine study on a coarse copy of its mesh (1 872 dof,
//! four substructures of 390 - 546 unknowns) with every substructure cut into parts of about
//! 150 unknowns, against the same study undivided. The cuts are perfect interfaces, so every
//! run's quantities are the undivided ones to the solver tolerance, the adaptive loop takes the
//! same steps, and the stochastic error estimate - computed from the runs on the user's
//! interfaces - is the same. Then the refusals at load, each with its file, line and field.

use alea_study::Source;
use alea_study::runner::{NoProgress, Study, run_study};

const FINE: &str = "n_flank = 16, n_runout = 5, n_fillet = 16, n_lobe = 10, n_slot = 6, n_below = 10, n_root = 15, n_shank = 12, depth = 20.0, n_z = 12";
const COARSE: &str = "n_flank = 4, n_runout = 2, n_fillet = 4, n_lobe = 3, n_slot = 2, n_below = 3, n_root = 4, n_shank = 3, depth = 20.0, n_z = 2";
const SOLVER: &str = "search_direction_factor = 0.5\n";
/// The example's refined mesh (its disk's counts doubled), and the coarse copy's.
const FINE_REFINED: &str = "n_fillet = 32, n_lobe = 20, n_below = 20, n_slot = 12, n_runout = 10";
const COARSE_REFINED: &str = "n_fillet = 8, n_lobe = 6, n_below = 6, n_slot = 4, n_runout = 4";

fn text(solver: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/turbine-3d-wear.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(FINE), "the example's mesh line changed");
    assert!(text.contains(SOLVER), "the example's [solver] changed");
    assert!(
        text.contains(FINE_REFINED),
        "the example's refined mesh changed"
    );
    text.replace(FINE, COARSE)
        .replace(FINE_REFINED, COARSE_REFINED)
        .replace(SOLVER, &format!("{SOLVER}{solver}\n"))
}

fn study(solver: &str) -> Study {
    Study::from_source(Source::from_text("turbine-3d-coarse.toml", &text(solver))).unwrap()
}

#[test]
fn a_study_cut_into_subdomains_gives_the_undivided_answers() {
    let tight = text("subdomains = \"never\"").replace("tolerance = 1e-6", "tolerance = 1e-10");
    let reference =
        Study::from_source(Source::from_text("turbine-3d-coarse.toml", &tight)).unwrap();
    let whole = study("subdomains = \"never\"");
    let cut = study("subdomains = \"always\"\nsubdomain_dofs = 150");
    let dir = |name: &str| {
        let d = std::env::temp_dir().join(format!("alea-subdomains-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    };
    let (dr, dw, dc) = (dir("reference"), dir("whole"), dir("cut"));
    let r = run_study(&reference, &dr, false, &NoProgress).unwrap();
    let a = run_study(&whole, &dw, false, &NoProgress).unwrap();
    let b = run_study(&cut, &dc, false, &NoProgress).unwrap();
    assert!(a.solver.split().is_none());
    let parts = b.solver.split().expect("the model is cut").parts();
    assert!(parts.iter().all(|&k| k >= 2), "{parts:?}");
    eprintln!(
        "parts {parts:?}; {} solved substructures, {} solved interfaces",
        b.solver.num_solved_subs(),
        b.solver.interface_sizes().len()
    );
    assert_eq!(a.records.len(), b.records.len());
    // The true error of each run's quantities (against the same run at tolerance 1e-10),
    // relative to the quantity's largest size over the runs.
    let nq = a.records[0].qois.len();
    let scale: Vec<f64> = (0..nq)
        .map(|q| {
            r.records
                .iter()
                .map(|x| x.qois[q].abs())
                .fold(0.0f64, f64::max)
        })
        .collect();
    let mut worst = [vec![0.0f64; nq], vec![0.0f64; nq]];
    for (k, runs) in [&a, &b].into_iter().enumerate() {
        for rec in &runs.records {
            assert!(rec.converged(), "{}", rec.status);
            let truth = r
                .records
                .iter()
                .find(|x| x.params == rec.params)
                .expect("the same runs");
            for q in 0..nq {
                let e = (rec.qois[q] - truth.qois[q]).abs() / scale[q];
                worst[k][q] = worst[k][q].max(e);
            }
        }
    }
    eprintln!("true error per quantity, undivided {:?}", worst[0]);
    eprintln!("true error per quantity, cut       {:?}", worst[1]);
    // At the same tolerance, the cut model's error is that of the undivided one, not more
    // than a few times (the indicator's scale is the user's interfaces', module
    // `alea_latin::split`).
    for q in 0..nq {
        assert!(
            worst[1][q] <= 5.0 * worst[0][q].max(1e-7),
            "quantity {q}: {:.2e} against {:.2e} undivided",
            worst[1][q],
            worst[0][q]
        );
    }
    // The adaptive loop and its stochastic error estimate, on the user's interfaces.
    let (sa, sb) = (&a.adaptive[0].steps, &b.adaptive[0].steps);
    assert_eq!(sa.len(), sb.len());
    for (x, y) in sa.iter().zip(sb) {
        assert_eq!(x.runs, y.runs);
        let (ex, ey) = (&x.error.estimate, &y.error.estimate);
        assert_eq!(ex.interfaces.len(), ey.interfaces.len());
        let d = (ex.i_sto() - ey.i_sto()).abs() / ex.i_sto();
        eprintln!("i_sto {:.5} / {:.5}", ex.i_sto(), ey.i_sto());
        assert!(d < 1e-2, "i_sto {} against {}", ey.i_sto(), ex.i_sto());
    }
    for d in [dr, dw, dc] {
        let _ = std::fs::remove_dir_all(&d);
    }
}

#[test]
fn bad_subdomain_settings_are_refused_at_load_with_file_line_and_field() {
    for (setting, field, says) in [
        (
            "subdomains = \"sometimes\"",
            "solver.subdomains",
            "\"never\"",
        ),
        (
            "subdomain_dofs = 10",
            "solver.subdomain_dofs",
            "at least 100",
        ),
        (
            "subdomains = \"never\"\nsubdomain_dofs = 5000",
            "solver.subdomain_dofs",
            "no effect",
        ),
        (
            "factor_precision = \"half\"",
            "solver.factor_precision",
            "\"single\"",
        ),
    ] {
        let text = text(setting);
        let err = Study::from_source(Source::from_text("turbine-3d-coarse.toml", &text))
            .err()
            .unwrap_or_else(|| panic!("{setting} accepted"))
            .to_string();
        let key = setting.lines().last().unwrap().split(' ').next().unwrap();
        let line = text.lines().position(|l| l.starts_with(key)).unwrap() + 1;
        assert!(
            err.contains(&format!("turbine-3d-coarse.toml:{line}"))
                && err.contains(field)
                && err.contains(says),
            "{setting}: {err}"
        );
    }
}

#[test]
fn factor_precision_reaches_the_solver() {
    for (setting, expected) in [
        ("", alea_latin::FactorPrecision::Auto),
        (
            "factor_precision = \"double\"",
            alea_latin::FactorPrecision::Double,
        ),
        (
            "factor_precision = \"single\"",
            alea_latin::FactorPrecision::Single,
        ),
    ] {
        let study = Study::from_source(Source::from_text("turbine-3d-coarse.toml", &text(setting)))
            .unwrap_or_else(|e| panic!("{setting}: {e}"));
        assert_eq!(study.model.options.factor_precision, expected, "{setting}");
    }
}
