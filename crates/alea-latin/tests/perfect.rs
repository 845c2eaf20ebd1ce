//! Perfect interfaces: an assembly of substructures joined by perfect interfaces must
//! reproduce the single-domain finite-element solution of the same mesh (the LATIN iteration
//! converges to the discrete solution of the assembled problem; with lumped interface weights
//! the converged interface tractions are the discrete interface forces).
//!
//! ```text
//!  y=1 +---------+---------+        2 x 2 substructures; S00 clamped on x = 0, S01 too;
//!      |   S01   |   S11   |        S10 and S11 are floating (held only by interfaces);
//!      +---------+---------+        traction (shear + tension) on x = 2, body force
//!      |   S00   |   S10   |        everywhere.
//!  y=0 +---------+---------+
//!     x=0       x=1       x=2
//! ```
//! Goal: relative energy-norm difference < 1e-8 after convergence to a tight tolerance.

mod common;

use alea_fem::{Constraints, Loads, Ordering, solve_elastic};
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus};
use alea_mesh::CellType;
use common::*;

const E: f64 = 210e3;

fn traction(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    [50.0 + 10.0 * x[1], 20.0, 0.0]
}

fn body(_x: [f64; 3], _rho: f64) -> [f64; 3] {
    [3.0, -7.0, 0.0]
}

fn check_2x2(kind: CellType, n: usize) {
    // Reference single domain.
    let whole = model(rect(0.0, 0.0, 2.0, 1.0, 2 * n, 2 * n, kind), E, 0.3);
    let mut cons = Constraints::new();
    cons.clamp(&whole.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&whole);
    loads.traction(&whole, "xmax", traction).unwrap();
    loads.body_force(&whole, None, body).unwrap();
    let reference = solve_elastic(&whole, &cons, &loads, Ordering::Metis).unwrap();

    let mut subs = Vec::new();
    for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let m = model(rect(i as f64, 0.5 * j as f64, 1.0, 0.5, n, n, kind), E, 0.3);
        let mut c = Constraints::new();
        if i == 0 {
            c.clamp(&m.mesh, "xmin").unwrap();
        }
        let s = with_load(sub(&format!("S{i}{j}"), m, c), |m, l| {
            l.body_force(m, None, body).unwrap();
            if i == 1 {
                l.traction(m, "xmax", traction).unwrap();
            }
        });
        subs.push(s);
    }
    // Indices: 0 = S00, 1 = S10, 2 = S01, 3 = S11.
    let interfaces = vec![
        InterfaceSpec::perfect("S00-S10", 0, "xmax", 1, "xmin"),
        InterfaceSpec::perfect("S01-S11", 2, "xmax", 3, "xmin"),
        InterfaceSpec::perfect("S00-S01", 0, "ymax", 2, "ymin"),
        InterfaceSpec::perfect("S10-S11", 1, "ymax", 3, "ymin"),
    ];
    let opts = LatinOptions {
        tolerance: 1e-11,
        max_iterations: 20000,
        ..Default::default()
    };
    let mut solver = LatinSolver::new(Assembly { subs, interfaces }, opts).unwrap();
    let res = solver.run(&RunInput::default()).unwrap();
    assert_eq!(
        res.status,
        RunStatus::Converged,
        "{:?}",
        res.residuals.last()
    );
    let mut num = 0.0;
    let mut den = 0.0;
    for s in 0..4 {
        let m = solver.model(s);
        let uref = restrict(&whole.mesh, &reference.u, &m.mesh);
        let diff: Vec<f64> = res.displacements[s]
            .iter()
            .zip(&uref)
            .map(|(a, b)| a - b)
            .collect();
        num += energy(m, &diff);
        den += energy(m, &uref);
    }
    let rel = (num / den).sqrt();
    eprintln!(
        "{kind}: {} iterations, relative energy difference {rel:e}",
        res.iterations
    );
    assert!(
        rel < 1e-8,
        "{kind}: relative energy-norm difference {rel:e}"
    );
    // Equilibrium of each substructure: sum of interface forces + external loads = reactions.
    for it in &res.interfaces {
        let r = it.resultant();
        let r1: [f64; 3] = it
            .weights
            .iter()
            .zip(&it.fhat[0])
            .fold([0.0; 3], |a, (m, f)| {
                [a[0] + m * f[0], a[1] + m * f[1], a[2] + m * f[2]]
            });
        for c in 0..2 {
            assert!(
                (r[c] + r1[c]).abs() < 1e-9 * (1.0 + r[c].abs()),
                "action = -reaction"
            );
        }
    }
}

#[test]
fn four_substructures_q4_match_single_domain() {
    check_2x2(CellType::Quad4, 6);
}

#[test]
fn four_substructures_t6_match_single_domain() {
    check_2x2(CellType::Tri6, 4);
}
