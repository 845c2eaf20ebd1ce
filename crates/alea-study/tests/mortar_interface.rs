//! A study on a mortar interface: `examples/punch-on-base.toml`, a punch and a base meshed
//! separately in Gmsh (the contact faces' nodes do not coincide), random friction coefficient
//! `mu ~ U(0.2, 0.5)` and load factor `P ~ N(1, 0.05^2)` on the punch's top traction
//! `(15, -100)` MPa over 20 mm.
//!
//! Checked: the interface is paired by the mortar method; every run converges; each run's
//! contact resultant on the base is exactly the applied load, `-2000 P` N/mm in y (equilibrium
//! of the floating punch: to the LATIN tolerance); the friction dissipation is `>= 0`; the warm
//! starts of the multiresolution runner give the quantities of cold solves in fewer iterations; the
//! stored local-stage states have the mortar interface's point count; a resumed study
//! recomputes nothing and returns identical records.

use std::path::PathBuf;

use alea_latin::PairingKind;
use alea_study::runner::{NoProgress, Study, run_study};

#[test]
fn punch_on_base_study_with_a_mortar_interface() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/punch-on-base.toml");
    let study = Study::load(&path).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-mortar-study-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let pairing = runs.solver.interface_pairing(0);
    assert_eq!(pairing.kind, PairingKind::Mortar);
    let points = pairing.len();
    assert_eq!(runs.solver.interface_sizes(), vec![points]);
    // 16 design runs and 5 validation runs.
    assert_eq!(runs.records.len(), 21);
    for r in &runs.records {
        assert!(r.converged(), "{:?}: {}", r.params, r.status);
        assert_eq!(r.state.len(), 12 * points);
        let p = r.params[1];
        let force_y = r.qois[0];
        assert!(
            (force_y + 2000.0 * p).abs() < 1e-5 * 2000.0 * p,
            "resultant {force_y} vs {}",
            -2000.0 * p
        );
        assert!(r.qois[1] >= -1e-9, "dissipation {}", r.qois[1]);
    }
    // Multiresolution: the same points solved cold (no warm start) give the same quantities
    // (to the LATIN tolerance) in more iterations in all.
    let (mut warm, mut cold) = (0, 0);
    for r in &runs.records {
        let res = runs
            .solver
            .run_shared(&study.model.parametric.run_input(&r.params))
            .unwrap();
        for (q, &v) in study.qois.iter().zip(&r.qois) {
            let c = q.eval(&runs.solver, &res).unwrap();
            let scale = match q.name.as_str() {
                "dissipation" => 1e-2, // N.mm/mm: dissipations range over 0 - 0.6
                _ => c.abs(),
            };
            assert!(
                (c - v).abs() < 1e-4 * scale,
                "{}: warm {v}, cold {c}",
                q.name
            );
        }
        warm += r.iterations;
        cold += res.iterations;
    }
    eprintln!("{points} mortar points; iterations: warm {warm}, cold {cold}");
    assert!(warm < cold, "warm {warm} vs cold {cold}");
    // The runs hold the study directory's lock: release it before resuming.
    let records = runs.records.clone();
    drop(runs);
    let again = run_study(&study, &dir, false, &NoProgress).unwrap();
    assert_eq!(again.computed, 0);
    assert_eq!(again.records, records);
    let _ = std::fs::remove_dir_all(&dir);
}
