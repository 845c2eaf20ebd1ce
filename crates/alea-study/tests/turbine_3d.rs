//! The shipped 3D turbine study (`examples/turbine-3d-wear.toml`, thesis 5.2.5-5.2.6) on a
//! coarse copy of its mesh (1 872 dof, 2 layers of Hex8): the trends the example's header
//! states must hold, none of them a snapshot.
//!
//! - Every run of the adaptive loop converges; the loop starts from the 16 corners and the
//!   centre of [0, 1]^4 and stops because i_sto reached its target, or i_sto decreased.
//! - The error terms are non-negative, `e~^2 = I_geo^2 + I_sto^2`, and the whole estimate is
//!   the interfaces' (3D substructures carry no admissible stress: their parts are 0) with
//!   the two contact faces carrying most of it; the per-cell error map (ParaView's
//!   `interface_cell_error`) adds up, on each side of each interface, to that interface's
//!   E[e^2] and E[geo^2], the facet shares being the side's lumped weights facet by facet;
//!   at the runs themselves every interface term vanishes (converged fields satisfy the laws).
//! - Equilibrium of the blade root A1 + A2: the in-plane (x, y) resultants of the contact
//!   faces I1, I2 on the root balance its loads (blade pull + centrifugal), whatever the
//!   wear; and at a = b the two faces are each other's mirror images in x = 0 (Fx opposite, Fy
//!   and Fz equal), as the example's mirrored wear profiles make the problem symmetric.

use alea_latin::{LatinSolver, RunStatus};
use alea_study::cre::StudyParameters;
use alea_study::runner::{NoProgress, Study, run_study};
use alea_study::{Source, estimate};

const FINE: &str = "n_flank = 16, n_runout = 5, n_fillet = 16, n_lobe = 10, n_slot = 6, n_below = 10, n_root = 15, n_shank = 12, depth = 20.0, n_z = 12";
const COARSE: &str = "n_flank = 4, n_runout = 2, n_fillet = 4, n_lobe = 3, n_slot = 2, n_below = 3, n_root = 4, n_shank = 3, depth = 20.0, n_z = 2";
/// The example's refined mesh (its disk's counts doubled), and the coarse copy's.
const FINE_REFINED: &str = "n_fillet = 32, n_lobe = 20, n_below = 20, n_slot = 12, n_runout = 10";
const COARSE_REFINED: &str = "n_fillet = 8, n_lobe = 6, n_below = 6, n_slot = 4, n_runout = 4";

fn coarse_study() -> Study {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/turbine-3d-wear.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(FINE), "the example's mesh line changed");
    assert!(
        text.contains(FINE_REFINED),
        "the example's refined mesh line changed"
    );
    let text = format!(
        "{}\n[statistics]\nsamples = 20000\n",
        text.replace(FINE, COARSE)
            .replace(FINE_REFINED, COARSE_REFINED)
    );
    Study::from_source(Source::from_text("turbine-3d-coarse.toml", &text)).unwrap()
}

#[test]
fn coarse_3d_turbine_adaptive_study_converges_and_its_error_is_the_interfaces() {
    let study = coarse_study();
    let dir = std::env::temp_dir().join(format!("alea-turbine-3d-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    assert!(
        runs.records.iter().all(|r| r.converged()),
        "{:?}",
        runs.records
            .iter()
            .filter(|r| !r.converged())
            .map(|r| (&r.params, &r.status))
            .collect::<Vec<_>>()
    );
    let outcome = &runs.adaptive[0];
    assert!(outcome.error.is_none(), "{:?}", outcome.error);
    let steps = &outcome.steps;
    assert_eq!(steps[0].runs, 17, "16 corners and the centre");
    let target = 0.16;
    let i_sto: Vec<f64> = steps.iter().map(|s| s.error.estimate.i_sto()).collect();
    let last = *i_sto.last().unwrap();
    assert!(
        last <= target || last < i_sto[0],
        "i_sto over the steps {i_sto:?}, stop: {}",
        outcome.stop
    );
    for s in steps {
        let e = &s.error.estimate;
        assert!(!s.error.substructures_estimated);
        assert!(e.e2 >= 0.0 && e.geo2 >= 0.0 && e.sto2 >= 0.0 && e.norm2 > 0.0);
        assert!(
            (e.e2 - e.geo2 - e.sto2).abs() <= 1e-12 * e.e2,
            "{} != {} + {}",
            e.e2,
            e.geo2,
            e.sto2
        );
        // 3D substructures: FE-only, no error of their own.
        for sub in &e.subs {
            assert_eq!(sub.e2, 0.0, "substructure {}", sub.name);
        }
        // Non-negative up to round-off (the perfect interfaces' terms are ~0: differences of
        // nearly equal expectations).
        let eps = 1e-12 * e.e2;
        for it in &e.interfaces {
            assert!(it.e2 >= -eps && it.geo2 >= -eps, "{}: {it:?}", it.name);
        }
        let iface: f64 = e.interfaces.iter().map(|i| i.e2).sum();
        assert!((iface - e.e2).abs() <= 1e-9 * e.e2, "{iface} vs {}", e.e2);
        let contact: f64 = e
            .interfaces
            .iter()
            .filter(|i| i.name == "I1" || i.name == "I2")
            .map(|i| i.e2)
            .sum();
        assert!(
            contact >= 0.5 * e.e2,
            "contact faces' share {}",
            contact / e.e2
        );
        // A positive, finite relative error.
        let rel = e.relative();
        assert!(rel > 0.0 && rel < 1.0, "e~ = {rel}");
    }
    // The error map per cell (ParaView's `interface_cell_error`): on each side of each
    // interface the cells' shares add up to the interface's E[e^2] and E[geo^2].
    let method = &runs.methods[0];
    let points = method.points.clone();
    let sur = method.surrogate(&study.params, &points).unwrap();
    let settings = estimate::error_settings(&study).unwrap();
    let (_, rule) = estimate::integration_rule(&study, method, &settings).unwrap();
    let params = StudyParameters::new(&study.model.parametric, &runs.solver);
    let est = outcome
        .estimator
        .as_ref()
        .expect("the last step's estimator");
    let per_point = est.interface_point_terms(&rule, &sur, &params);
    let last = &steps.last().unwrap().error.estimate;
    let scale = last.e2;
    for (i, spec) in study.model.assembly.interfaces.iter().enumerate() {
        // This interface's point terms alone.
        let only: Vec<Vec<[f64; 2]>> = per_point
            .iter()
            .enumerate()
            .map(|(k, t)| {
                if k == i {
                    t.clone()
                } else {
                    vec![[0.0; 2]; t.len()]
                }
            })
            .collect();
        let cells = estimate::interface_cell_terms(&study, &runs.solver, &only).unwrap();
        let it = &last.interfaces[i];
        for s in [spec.sub1, spec.sub2] {
            let (e, g) = cells[s]
                .iter()
                .fold((0.0, 0.0), |(e, g), c| (e + c[0], g + c[1]));
            assert!(
                (e - it.e2).abs() <= 1e-9 * scale && (g - it.geo2).abs() <= 1e-9 * scale,
                "{} on {s}: cells ({e}, {g}) vs interface ({}, {})",
                spec.name,
                it.e2,
                it.geo2
            );
        }
    }
    // At the runs themselves the interpolated fields are the runs' converged fields, which
    // satisfy the laws: every interface term vanishes there (the whole interface error comes
    // from between the runs).
    let flat: Vec<f64> = points.iter().flatten().copied().collect();
    let at_runs = alea_estimate::rule::Rule::equal_weights(4, flat).unwrap();
    for (i, t) in est
        .interface_point_terms(&at_runs, &sur, &params)
        .iter()
        .enumerate()
    {
        let e: f64 = t.iter().map(|x| x[0]).sum::<f64>() / points.len() as f64;
        assert!(
            e.abs() <= 1e-9 * scale,
            "interface {i}: mean term {e:e} at the runs, expectation {scale:e}"
        );
    }
    // Facet shares are the side weights facet by facet.
    let d2 = study
        .model
        .assembly
        .subs
        .iter()
        .position(|s| s.name == "D2")
        .unwrap();
    let mesh = &runs.solver.model(d2).mesh;
    let side = alea_latin::interface::side_geometry(mesh, "I2_disk", 1.0).unwrap();
    let mut summed = vec![0.0; side.nodes.len()];
    for f in alea_latin::interface::facet_shares(mesh, "I2_disk", 1.0).unwrap() {
        for (n, w) in f.shares {
            summed[side.nodes.binary_search(&n).unwrap()] += w;
        }
    }
    for (a, b) in summed.iter().zip(&side.weights) {
        assert!((a - b).abs() <= 1e-12 * b, "{a} vs {b}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn coarse_3d_turbine_root_is_in_equilibrium_and_symmetric_at_equal_wear() {
    let study = coarse_study();
    let asm = &study.model.assembly;
    let solver = LatinSolver::new(asm.clone(), study.model.options.clone()).unwrap();
    let sub = |n: &str| asm.subs.iter().position(|s| s.name == n).unwrap();
    let iface = |n: &str| asm.interfaces.iter().position(|i| i.name == n).unwrap();
    let (a1, a2, i1, i2) = (sub("A1"), sub("A2"), iface("I1"), iface("I2"));
    assert_eq!((asm.interfaces[i1].sub2, asm.interfaces[i2].sub2), (a1, a2));
    for theta in [
        [0.5, 0.5, 0.5, 0.5],
        [1.0, 0.0, 0.0, 1.0],
        [0.0, 1.0, 1.0, 1.0],
    ] {
        let input = study.model.parametric.run_input(&theta);
        let res = solver.run_shared(&input).unwrap();
        assert_eq!(res.status, RunStatus::Converged, "{theta:?}");
        // Loads on the root (x, y): the blade pull and the centrifugal force.
        let mut load = [0.0; 3];
        for s in [a1, a2] {
            for (case, factor) in asm.subs[s].load_cases.iter().zip(&input.load_factors[s]) {
                for (k, v) in case.iter().enumerate() {
                    load[k % 3] += factor * v;
                }
            }
        }
        let (f1, f2) = (
            res.interfaces[i1].resultant(),
            res.interfaces[i2].resultant(),
        );
        let scale = load[0].hypot(load[1]);
        assert!(scale > 0.0);
        for c in 0..2 {
            let unbalance = load[c] + f1[c] + f2[c];
            assert!(
                unbalance.abs() <= 1e-5 * scale,
                "{theta:?}: component {c}: loads {} + I1 {} + I2 {} = {unbalance:e}",
                load[c],
                f1[c],
                f2[c]
            );
        }
        if theta[0] == theta[1] {
            let scale = f2[1].abs();
            assert!((f1[0] + f2[0]).abs() <= 1e-5 * scale, "Fx {f1:?} {f2:?}");
            assert!((f1[1] - f2[1]).abs() <= 1e-5 * scale, "Fy {f1:?} {f2:?}");
            assert!((f1[2] - f2[2]).abs() <= 1e-5 * scale, "Fz {f1:?} {f2:?}");
        }
    }
}
