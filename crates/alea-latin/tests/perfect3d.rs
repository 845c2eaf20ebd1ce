//! Perfect interfaces in 3D: a bar cut into 2 x 2 x 2 substructures joined by 12 perfect
//! interfaces must reproduce the single-domain finite-element solution of the same mesh (the
//! 3D counterpart of `perfect.rs`).
//!
//! ```text
//!            z
//!            |  +-------+-------+      [0, 2] x [0, 1] x [0, 1], cut at x = 1, y = 1/2, z = 1/2.
//!            | /       /       /|      The four substructures on x <= 1 are clamped on x = 0;
//!            +-------+-------+  |      the four on x >= 1 float (held by interfaces only).
//!            |       |       |  +      Traction (shear in y and z, tension, varying with y
//!            |       |       | /       and z) on x = 2, body force everywhere.
//!            +-------+-------+----- x
//!           x=0     x=1     x=2
//! ```
//! Goal: relative energy-norm difference < 1e-8 after convergence to a tight tolerance (Hex8
//! with 4-node faces, Tet10 with 6-node faces whose HRZ-lumped interface weights the LATIN
//! interface mass uses), and action = -reaction on every interface.

mod common;

use alea_fem::{Constraints, Loads, Ordering, solve_elastic};
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus};
use alea_mesh::CellType;
use common::*;

const E: f64 = 210e3;

fn traction(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    [
        50.0 + 10.0 * x[1],
        20.0 - 5.0 * x[2],
        -15.0 + 8.0 * x[1] * x[2],
    ]
}

fn body(_x: [f64; 3], _rho: f64) -> [f64; 3] {
    [3.0, -7.0, 4.0]
}

fn check_2x2x2(kind: CellType, n: usize) {
    let size = [1.0, 0.5, 0.5];
    let whole = solid(cuboid([0.0; 3], [2.0, 1.0, 1.0], [2 * n; 3], kind), E, 0.3);
    let mut cons = Constraints::new();
    cons.clamp(&whole.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&whole);
    loads.traction(&whole, "xmax", traction).unwrap();
    loads.body_force(&whole, None, body).unwrap();
    let reference = solve_elastic(&whole, &cons, &loads, Ordering::Metis).unwrap();

    // Substructure (i, j, k) has index i + 2 j + 4 k.
    let index = |i: usize, j: usize, k: usize| i + 2 * j + 4 * k;
    let mut subs = Vec::new();
    for k in 0..2 {
        for j in 0..2 {
            for i in 0..2 {
                let x0 = [i as f64 * size[0], j as f64 * size[1], k as f64 * size[2]];
                let m = solid(cuboid(x0, size, [n; 3], kind), E, 0.3);
                let mut c = Constraints::new();
                if i == 0 {
                    c.clamp(&m.mesh, "xmin").unwrap();
                }
                subs.push(with_load(sub(&format!("S{i}{j}{k}"), m, c), |m, l| {
                    l.body_force(m, None, body).unwrap();
                    if i == 1 {
                        l.traction(m, "xmax", traction).unwrap();
                    }
                }));
            }
        }
    }
    let mut interfaces = Vec::new();
    for a in 0..2 {
        for b in 0..2 {
            let pairs = [
                (index(0, a, b), index(1, a, b), "xmax", "xmin"),
                (index(a, 0, b), index(a, 1, b), "ymax", "ymin"),
                (index(a, b, 0), index(a, b, 1), "zmax", "zmin"),
            ];
            for (s1, s2, g1, g2) in pairs {
                interfaces.push(InterfaceSpec::perfect(
                    &format!("{s1}-{s2}"),
                    s1,
                    g1,
                    s2,
                    g2,
                ));
            }
        }
    }
    assert_eq!(interfaces.len(), 12);
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
    let (mut num, mut den) = (0.0, 0.0);
    for s in 0..8 {
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
        "{kind}: {} iterations ({:.2} s), relative energy difference {rel:e}",
        res.iterations, res.timings.total
    );
    assert!(
        rel < 1e-8,
        "{kind}: relative energy-norm difference {rel:e}"
    );
    for it in &res.interfaces {
        let r = it.resultant();
        let r1 = it
            .weights
            .iter()
            .zip(&it.fhat[0])
            .fold([0.0; 3], |a, (m, f)| {
                [a[0] + m * f[0], a[1] + m * f[1], a[2] + m * f[2]]
            });
        for c in 0..3 {
            assert!(
                (r[c] + r1[c]).abs() < 1e-9 * (1.0 + r[c].abs()),
                "{}: action = -reaction",
                it.name
            );
        }
    }
    // The load goes through the x-interfaces: their resultants balance the applied load and
    // the body force of the floating half (x >= 1).
    let applied = {
        let mut l = Loads::new(&whole);
        l.traction(&whole, "xmax", traction).unwrap();
        l.resultant()
    };
    let mut through = [0.0; 3];
    for it in res
        .interfaces
        .iter()
        .filter(|it| it.subs[0] % 2 == 0 && it.subs[1] % 2 == 1)
    {
        let r = it.resultant();
        for c in 0..3 {
            through[c] += r[c];
        }
    }
    // Equilibrium of the floating half: interface forces on it + traction + body force = 0
    // (volume of the half: 1 x 1 x 1).
    let b = body([0.0; 3], 0.0);
    for c in 0..3 {
        let sum = through[c] + applied[c] + b[c];
        assert!(
            sum.abs() < 1e-7 * (applied[c].abs() + 1.0),
            "component {c}: floating half out of balance by {sum}"
        );
    }
}

#[test]
fn eight_substructures_hex8_match_single_domain() {
    check_2x2x2(CellType::Hex8, 3);
}

#[test]
fn eight_substructures_tet10_match_single_domain() {
    check_2x2x2(CellType::Tet10, 2);
}
