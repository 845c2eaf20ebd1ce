//! 3D assembly with perfect interfaces: the unit cube of the 3D manufactured solution (see
//! `manufactured3d.rs`) cut into 2 x 2 x 1 substructures joined by perfect interfaces,
//! clamped on `x = 0` and loaded by the exact tractions on the five other faces (the two
//! substructures on `x >= 1/2` float, held by the interfaces only). The exact solution is known,
//! so the true error of the LATIN solution is `(sum_s ||u_ex - u_h^s||^2_K)^(1/2)`.
//!
//! ```text
//!  y=1 +-----+-----+
//!      | S01 | S11 |     (z from 0 to 1)
//!      +-----+-----+     2 = S01, 3 = S11
//!      | S00 | S10 |     0 = S00, 1 = S10
//!  y=0 +-----+-----+
//!     x=0         x=1
//! ```
//! Checks (Hex8, Tet4, Tet10): the substructured estimate (substructures loaded by the lumped
//! interface forces of the converged linear stage, split between the interface faces around
//! each node) bounds the true error, its phase-1 node systems are compatible (the lumped
//! interface forces are reproduced exactly), the perfect interface terms vanish, and the global
//! estimate is within 5 % of the single-domain estimate of the same mesh.

mod common;

use alea_cre::{CreOptions, LoadData, estimate_domain, estimate_latin, write_error_vtu};
use alea_fem::{Constraints, Loads, Ordering, solve_elastic};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus, Substructure,
};
use alea_mesh::{CellType, generate};
use common::solid::*;

fn sub_mesh(i: usize, j: usize, n: usize, kind: CellType) -> alea_mesh::Mesh {
    let mut m = generate::box_mesh([0.5, 0.5, 1.0], [n, n, 2 * n], kind).unwrap();
    for x in m.coords.iter_mut() {
        x[0] += 0.5 * i as f64;
        x[1] += 0.5 * j as f64;
    }
    m
}

fn check(kind: CellType, n: usize) {
    let t0 = std::time::Instant::now();
    let mut subs = Vec::new();
    let mut data = Vec::new();
    for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let m = solid_model(sub_mesh(i, j, n, kind));
        let mut c = Constraints::new();
        let mut loads = Loads::new(&m);
        loads.body_force(&m, None, |x, _| body3(x)).unwrap();
        let mut d = LoadData::new().body(body3);
        if i == 0 {
            c.clamp(&m.mesh, "xmin").unwrap();
        }
        let mut loaded = vec!["zmin", "zmax", if j == 0 { "ymin" } else { "ymax" }];
        if i == 1 {
            loaded.push("xmax");
        }
        for g in loaded {
            loads.traction(&m, g, exact_traction3).unwrap();
            d = d.traction(g, exact_traction3);
        }
        subs.push(Substructure {
            name: format!("S{i}{j}"),
            model: m,
            constraints: c,
            load_cases: vec![loads.f],
        });
        data.push(d);
    }
    let interfaces = vec![
        InterfaceSpec::perfect("S00-S10", 0, "xmax", 1, "xmin"),
        InterfaceSpec::perfect("S01-S11", 2, "xmax", 3, "xmin"),
        InterfaceSpec::perfect("S00-S01", 0, "ymax", 2, "ymin"),
        InterfaceSpec::perfect("S10-S11", 1, "ymax", 3, "ymin"),
    ];
    let assembly = Assembly { subs, interfaces };
    let opts = LatinOptions {
        tolerance: 1e-11,
        max_iterations: 20000,
        ..Default::default()
    };
    let mut solver = LatinSolver::new(assembly.clone(), opts).unwrap();
    let run = solver.run(&RunInput::default()).unwrap();
    assert_eq!(run.status, RunStatus::Converged);
    let t_solve = t0.elapsed().as_secs_f64();
    let t1 = std::time::Instant::now();
    let est = estimate_latin(&assembly, &data, &run, &CreOptions::default()).unwrap();
    let t_est = t1.elapsed().as_secs_f64();
    let err = (0..4)
        .map(|s| true_error3(&assembly.subs[s].model, &run.displacements[s]).powi(2))
        .sum::<f64>()
        .sqrt();
    let eff = est.theta / err;

    // Single domain on the same global mesh.
    let whole = solid_model(generate::box_mesh([1.0; 3], [2 * n; 3], kind).unwrap());
    let mut cons = Constraints::new();
    cons.clamp(&whole.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&whole);
    loads.body_force(&whole, None, |x, _| body3(x)).unwrap();
    let mut d = LoadData::new().body(body3);
    for g in ["xmax", "ymin", "ymax", "zmin", "zmax"] {
        loads.traction(&whole, g, exact_traction3).unwrap();
        d = d.traction(g, exact_traction3);
    }
    let sol = solve_elastic(&whole, &cons, &loads, Ordering::Metis).unwrap();
    let single = estimate_domain(&whole, &cons, &d, &sol.u, &CreOptions::default()).unwrap();
    let ratio = est.theta / single.theta;
    println!(
        "{kind} n={n}: {} iterations; theta={:.5e} (subs {:?}) err={err:.4e} eff={eff:.3}; \
         single-domain theta={:.5e} eff={:.3}; ratio {ratio:.4}; compat={:.1e}; \
         iface terms {:?}; solve {t_solve:.2}s, estimate {t_est:.2}s",
        run.iterations,
        est.theta,
        est.substructure_theta(),
        single.theta,
        single.theta / err,
        est.compatibility_defect(),
        est.interfaces.iter().map(|i| i.term).collect::<Vec<_>>(),
    );
    assert!(eff >= 1.0, "efficiency {eff}");
    assert!(
        est.compatibility_defect() < 1e-6,
        "{}",
        est.compatibility_defect()
    );
    for it in &est.interfaces {
        assert_eq!(it.violations, 0, "{}", it.name);
        assert!(
            it.term.abs() < 1e-8 * est.theta * est.theta,
            "{}: {}",
            it.name,
            it.term
        );
    }
    assert!(ratio > 0.97 && ratio < 1.05, "ratio {ratio}");
    let path = std::env::temp_dir().join(format!(
        "alea_cre_perfect3d_{}_{kind}_{n}.vtu",
        std::process::id()
    ));
    write_error_vtu(&assembly.subs[1].model, &est.substructures[1], &path).unwrap();
    assert!(
        std::fs::read_to_string(&path)
            .unwrap()
            .contains("error_density")
    );
    let _ = std::fs::remove_file(&path);
}

#[test]
fn hex8_two_by_two_by_one() {
    check(CellType::Hex8, 3);
}

#[test]
fn tet4_two_by_two_by_one() {
    check(CellType::Tet4, 2);
}

#[test]
fn tet10_two_by_two_by_one() {
    check(CellType::Tet10, 1);
}
