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

use alea_latin::split::Split;
use alea_latin::{LatinOptions, LatinSolver, RunInput, RunStatus};
use common::*;

fn options() -> LatinOptions {
    LatinOptions {
        tolerance: 1e-10,
        max_iterations: 4000,
        coarse: true,
        ..Default::default()
    }
}

fn compare(dim: usize, parts: [usize; 2]) {
    let asm = press_and_shear(dim, false);
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

/// The solver cuts the model by itself (`LatinOptions::subdomains`) and speaks of the user's
/// model: its accessors, a run's input and result, a warm start, a modulus varying from cell
/// to cell - all as the undivided solver's, to the solver tolerance.
#[test]
fn the_solver_cuts_the_model_by_itself_and_speaks_of_the_users_model() {
    let asm = press_and_shear(3, false);
    let mut whole = LatinSolver::new(asm.clone(), options()).unwrap();
    assert!(
        whole.split().is_none(),
        "a small model is not cut by default"
    );
    let cut = LatinSolver::new(
        asm.clone(),
        LatinOptions {
            subdomains: alea_latin::Subdomains::Always,
            subdomain_dofs: 150,
            ..options()
        },
    )
    .unwrap();
    // 972 and 300 unknowns in parts of about 150.
    assert_eq!(cut.split().unwrap().parts(), vec![6, 2]);
    assert_eq!(cut.num_subs(), 2);
    assert_eq!(cut.num_solved_subs(), 8);
    assert_eq!(cut.num_interfaces(), 1);
    assert_eq!(cut.sub_name(1), "block");
    assert_eq!(cut.interface_name(0), "contact");
    assert_eq!(cut.interface_law(0), whole.interface_law(0));
    assert_eq!(cut.interface_nodes(0), whole.interface_nodes(0));
    assert_eq!(cut.interface_weights(0), whole.interface_weights(0));
    let xs =
        |s: &LatinSolver| -> Vec<[f64; 3]> { s.interface_points(0).iter().map(|p| p.x).collect() };
    assert_eq!(xs(&cut), xs(&whole));
    assert_eq!(
        cut.model(0).mesh.num_cells(),
        whole.model(0).mesh.num_cells()
    );

    // A modulus varying from cell to cell: each part takes its cells' factors.
    let cells = asm.subs[0].model.mesh.num_cells();
    let factors: Vec<f64> = (0..cells).map(|c| 0.5 + (c % 7) as f64 / 6.0).collect();
    let input = RunInput {
        cell_young: vec![Some(std::sync::Arc::new(factors)), None],
        ..RunInput::default()
    };
    let reference = whole.run(&input).unwrap();
    let r = cut.run_shared(&input).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    assert!(cut.equilibrium_report(&r).is_none());
    assert_eq!(r.cell_young, input.cell_young);
    let rel = |a: &[f64], b: &[f64]| {
        let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
        let den: f64 = b.iter().map(|y| y * y).sum();
        (num / den).sqrt()
    };
    for s in 0..2 {
        let e = rel(&r.displacements[s], &reference.displacements[s]);
        assert!(e < 1e-6, "substructure {s}: {e:.2e}");
    }
    let flat = |v: &[[f64; 3]]| v.iter().flatten().copied().collect::<Vec<_>>();
    let (a, b) = (&r.interfaces[0], &reference.interfaces[0]);
    assert!(rel(&flat(&a.fhat[0]), &flat(&b.fhat[0])) < 1e-6);
    assert_eq!(a.status, b.status);
    // Its energy is that of the varying modulus.
    let vm = |res: &alea_latin::RunResult, solver: &LatinSolver| {
        let m = res.scaled_model(solver.model(0), 0);
        alea_fem::post::strain_energy(&m, &res.displacements[0]).unwrap()
    };
    let (v1, v0) = (vm(&r, &cut), vm(&reference, &whole));
    assert!((v1 - v0).abs() < 1e-5 * v0, "{v1} against {v0}");

    // Its end state keeps the cuts: the shape the solver takes, and a warm start from it
    // starts at the answer.
    let end = r.end_state();
    assert_eq!(
        end.what.iter().map(|w| w[0].len()).collect::<Vec<_>>(),
        cut.interface_sizes()
    );
    assert!(cut.interface_sizes().len() > 1);
    let warm = cut
        .run_shared(&RunInput {
            initial: Some(std::sync::Arc::new(end)),
            ..input.clone()
        })
        .unwrap();
    assert!(warm.iterations <= 2, "{} iterations", warm.iterations);
    // A start state of the user's interfaces is taken too.
    let user_state = reference.end_state();
    let from_user = cut
        .run_shared(&RunInput {
            initial: Some(std::sync::Arc::new(user_state)),
            ..input
        })
        .unwrap();
    assert_eq!(from_user.status, RunStatus::Converged);
}

/// A model cut into subdomains runs a deeper Anderson history by default
/// (`split::SPLIT_ACCELERATION`: the cuts are perfect interfaces, on which the iteration is
/// linear), the same iterates as asking for that depth; an explicit depth is kept.
#[test]
fn a_cut_model_runs_the_split_anderson_depth_unless_told_otherwise() {
    use alea_latin::DEFAULT_ACCELERATION;
    use alea_latin::split::SPLIT_ACCELERATION;
    let asm = press_and_shear(3, false);
    let cut_with = |acceleration: Option<usize>| {
        LatinSolver::new(
            asm.clone(),
            LatinOptions {
                subdomains: alea_latin::Subdomains::Always,
                subdomain_dofs: 150,
                acceleration,
                ..options()
            },
        )
        .unwrap()
    };
    let whole = LatinSolver::new(asm.clone(), options()).unwrap();
    assert_eq!(whole.acceleration(), DEFAULT_ACCELERATION);
    let by_default = cut_with(None);
    assert_eq!(by_default.acceleration(), SPLIT_ACCELERATION);
    assert_eq!(cut_with(Some(3)).acceleration(), 3);
    let run = |s: &LatinSolver| s.run_shared(&RunInput::default()).unwrap();
    let (d, told) = (run(&by_default), run(&cut_with(Some(SPLIT_ACCELERATION))));
    assert_eq!(d.status, RunStatus::Converged);
    assert_eq!(d.iterations, told.iterations);
    assert_eq!(d.displacements, told.displacements);
    let shallow = run(&cut_with(Some(DEFAULT_ACCELERATION)));
    eprintln!(
        "cut model: {} iterations at depth {SPLIT_ACCELERATION}, {} at {DEFAULT_ACCELERATION}",
        d.iterations, shallow.iterations
    );
    assert_ne!(d.displacements, shallow.displacements);
}
