//! Automatic subdomains (module `alea_latin::split`): a frictional contact between two bodies,
//! each body split into parts by METIS, against the same bodies undivided. The cuts are
//! perfect interfaces, so the split model's answer is the undivided model's: displacements
//! and contact tractions equal to the solver tolerance, with the contact interface crossing
//! the cuts.
//!
//! ```text
//!        traction (0.25, 0.1, -1) on top
//!          +-----------+
//!          |   block   |      block split in 2 (3D) / 2 (2D)
//!    +-----+-----------+-----+   Coulomb contact, mu = 0.3 (partial slip)
//!    |          base         |   base split in 3 (3D: mortar pairing, the block's face
//!    +-----------------------+   smaller than the base's; 2D: node to node)
//!          clamped
//! ```

mod common;

use alea_fem::Constraints;
use alea_latin::split::Split;
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus};
use alea_mesh::CellType;
use common::*;

fn options() -> LatinOptions {
    LatinOptions {
        tolerance: 1e-10,
        max_iterations: 4000,
        coarse: true,
        ..Default::default()
    }
}

fn press_and_shear(dim: usize) -> Assembly {
    let (base, block) = if dim == 3 {
        (
            solid(
                cuboid([0.0; 3], [4.0, 4.0, 1.0], [8, 8, 3], CellType::Hex8),
                200e3,
                0.3,
            ),
            solid(
                cuboid([1.0, 1.0, 1.0], [2.0, 2.0, 1.0], [4, 4, 3], CellType::Hex8),
                70e3,
                0.3,
            ),
        )
    } else {
        (
            model(rect(0.0, 0.0, 4.0, 1.0, 24, 6, CellType::Quad4), 200e3, 0.3),
            model(rect(0.0, 1.0, 4.0, 1.0, 24, 6, CellType::Quad4), 70e3, 0.3),
        )
    };
    let (bottom, top) = if dim == 3 {
        ("zmin", "zmax")
    } else {
        ("ymin", "ymax")
    };
    let mut c = Constraints::new();
    c.clamp(&base.mesh, bottom).unwrap();
    let base = sub("base", base, c);
    let block = with_load(sub("block", block, Constraints::new()), |m, l| {
        l.traction(m, top, |_, _| {
            if dim == 3 {
                [25.0, 10.0, -100.0]
            } else {
                [25.0, -100.0, 0.0]
            }
        })
        .unwrap();
    });
    let mut contact = InterfaceSpec::coulomb("contact", 0, top, 1, bottom, 0.3);
    contact.pairing = if dim == 3 {
        alea_latin::Pairing::Mortar
    } else {
        alea_latin::Pairing::NodeToNode
    };
    Assembly {
        subs: vec![base, block],
        interfaces: vec![contact],
    }
}

fn compare(dim: usize, parts: [usize; 2]) {
    let asm = press_and_shear(dim);
    let mut whole = LatinSolver::new(asm.clone(), options()).unwrap();
    let reference = whole.run(&RunInput::default()).unwrap();
    assert_eq!(reference.status, RunStatus::Converged);
    let split = Split::new(&asm, &parts).unwrap();
    assert_eq!(split.parts(), parts.to_vec());
    let solver = split.solver(options()).unwrap();
    let input = split.input(&solver, &RunInput::default()).unwrap();
    let inner = solver.run_shared(&input).unwrap();
    let end = std::sync::Arc::new(inner.end_state());
    let r = split.merge(&input, inner);
    assert_eq!(r.status, RunStatus::Converged);
    // Warm-started from the split assembly's own end state (cuts included), a run of the
    // same input starts at its answer.
    let again = split
        .input(
            &solver,
            &RunInput {
                initial: Some(end),
                ..RunInput::default()
            },
        )
        .unwrap();
    let rerun = solver.run_shared(&again).unwrap();
    assert!(rerun.iterations <= 2, "{} iterations", rerun.iterations);
    let rel = |a: &[f64], b: &[f64]| {
        let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
        let den: f64 = b.iter().map(|y| y * y).sum();
        (num / den).sqrt()
    };
    let mut worst = 0.0f64;
    for s in 0..2 {
        worst = worst.max(rel(&r.displacements[s], &reference.displacements[s]));
    }
    let (a, b) = (&r.interfaces[0], &reference.interfaces[0]);
    assert_eq!(a.points.len(), b.points.len());
    let flat = |v: &[[f64; 3]]| v.iter().flatten().copied().collect::<Vec<_>>();
    let traction = rel(&flat(&a.fhat[0]), &flat(&b.fhat[0]));
    let jump = rel(&flat(&a.what[1]), &flat(&b.what[1]));
    let slipping = |s: &[alea_latin::PointStatus]| {
        s.iter()
            .filter(|&&p| p == alea_latin::PointStatus::Slip)
            .count()
    };
    eprintln!(
        "{dim}D, parts {parts:?}: {} inner substructures, {} inner interfaces; iterations {} \
         (undivided {}); displacements {worst:.2e}, tractions {traction:.2e}, W_hat {jump:.2e}; \
         slipping points {} (undivided {})",
        split.inner.subs.len(),
        split.inner.interfaces.len(),
        r.iterations,
        reference.iterations,
        slipping(&a.status),
        slipping(&b.status)
    );
    assert!(slipping(&b.status) > 0, "the case has slip");
    assert!(worst < 1e-6 && traction < 1e-6 && jump < 1e-6);
    assert_eq!(a.status, b.status);
}

#[test]
fn a_split_contact_model_gives_the_undivided_answer_in_2d() {
    compare(2, [3, 2]);
}

#[test]
fn a_split_contact_model_gives_the_undivided_answer_in_3d() {
    compare(3, [3, 2]);
}
