//! Issue 21, bug 2: interfaces whose nodes nearly coincide (1e-7 apart on a unit mesh, well
//! within the node-to-node matching tolerance) are paired node to node by `Pairing::Auto`; the
//! run must converge to a tight tolerance (it stalled at an indicator of ~5e-8 for 20 000
//! iterations: the two sides transmitted forces with their own, slightly different, lumped
//! weights, so no fixed point balanced them).

mod common;

use alea_fem::Constraints;
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus};
use alea_mesh::CellType;
use common::*;

#[test]
fn nearly_matching_interface_converges() {
    let n = 8;
    let left = model(rect(0.0, 0.0, 1.0, 1.0, n, n, CellType::Quad4), 210e3, 0.3);
    let mut right_mesh = rect(1.0, 0.0, 1.0, 1.0, n, n, CellType::Quad4);
    // Move the interior nodes of the right side's interface by +-1e-7 along it.
    for (i, x) in right_mesh.coords.iter_mut().enumerate() {
        if x[0] == 1.0 && x[1] > 0.0 && x[1] < 1.0 {
            x[1] += if i % 2 == 0 { 1e-7 } else { -0.7e-7 };
        }
    }
    let right = model(right_mesh, 210e3, 0.3);
    let mut c = Constraints::new();
    c.clamp(&left.mesh, "xmin").unwrap();
    let s0 = sub("L", left, c);
    let s1 = with_load(sub("R", right, Constraints::new()), |m, l| {
        l.traction(m, "xmax", |x, _| [100.0, 20.0 + 10.0 * x[1], 0.0])
            .unwrap();
    });
    let opts = LatinOptions {
        tolerance: 1e-10,
        max_iterations: 3000,
        ..Default::default()
    };
    let assembly = Assembly {
        subs: vec![s0, s1],
        interfaces: vec![InterfaceSpec::perfect("G", 0, "xmax", 1, "xmin")],
    };
    let mut solver = LatinSolver::new(assembly, opts).unwrap();
    let res = solver.run(&RunInput::default()).unwrap();
    eprintln!(
        "{:?} after {} iterations, indicator {:?}",
        res.status,
        res.iterations,
        res.residuals.last()
    );
    assert_eq!(
        res.status,
        RunStatus::Converged,
        "{:?}",
        res.residuals.last()
    );
    // The forces on both sides balance: equal and opposite resultants.
    let it = &res.interfaces[0];
    let r = it.resultant();
    assert!((r[0] + 100.0).abs() < 1e-6 * 100.0, "{r:?}");
}
