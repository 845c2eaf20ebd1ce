//! Global equilibrium of every substructure of a frictional assembly, and invalid inputs.
//!
//! Reference: the admissibility conditions of the LATIN linear stage (P. Ladeveze, *Nonlinear
//! Computational Structural Mechanics*, Springer 1999, ch. 6; thesis section 2.1): each
//! substructure `s` is in equilibrium under its external loads `f_s`, its interface tractions
//! `F_s` (lumped: nodal forces `m_i F_s,i`) and the reactions `r_s` of its supports,
//!
//! ```text
//!   K_s u_s = f_s + M_Gamma F_s + r_s,     r_s = 0 at free dofs,
//!   sum over nodes (f_s + M_Gamma F_s + r_s) = 0,   same for the moments,
//! ```
//! with `K_s` the stiffness at this run's Young's modulus. The check is independent of the
//! solver's internals: `K_s u_s` comes from `alea_fem::post::internal_forces` on the run's
//! scaled model.
//!
//! ```text
//!   y = 1    +-------------------+  cap (S2): traction (tau, -p(x)) on top, floating
//!            |        cap        |
//!   y = 0.5  +-------------------+  perfect interface "cap-block"
//!            |       block       |  block (S1): body force, floating
//!   y = 0    +===================+  Coulomb contact "contact" (mu = 0.3): partial slip
//!            |       plane       |  plane (S0): clamped on y = -1, side traction
//!   y = -1   +-------------------+
//!           x=0                 x=2
//! ```
//! Run with Young's-modulus factors (1, 1.3, 0.8) and load factors, converged to 1e-10: the
//! nodal residual `K u - f - M F` vanishes at every free dof to 1e-8 relative (it is round-off:
//! the linear stage solves exactly this), and loads + interface forces + reactions have zero
//! resultant and moment. The second part checks that invalid set-ups and run inputs come back
//! as `LatinError`s (never panics) that name what is wrong.

mod common;

use alea_fem::{Constraints, DofMap, Loads};
use alea_latin::{
    Assembly, InterfaceSpec, LatinError, LatinOptions, LatinSolver, Pairing, PointStatus, RunInput,
    RunStatus, Substructure, constant,
};
use alea_mesh::CellType;
use common::*;

const E: f64 = 1000.0;

fn plane() -> Substructure {
    let m = model(rect(0.0, -1.0, 2.0, 1.0, 16, 8, CellType::Quad4), E, 0.3);
    let mut c = Constraints::new();
    c.clamp(&m.mesh, "ymin").unwrap();
    with_load(sub("plane", m, c), |m, l| {
        l.traction(m, "xmax", |x, _| [0.0, -2.0 * (1.0 + x[1]), 0.0])
            .unwrap();
    })
}

fn block() -> Substructure {
    let m = model(
        rect(0.0, 0.0, 2.0, 0.5, 16, 4, CellType::Quad4),
        2.0 * E,
        0.25,
    );
    with_load(sub("block", m, Constraints::new()), |m, l| {
        l.body_force(m, None, |_, _| [0.5, -1.0, 0.0]).unwrap();
    })
}

fn cap() -> Substructure {
    let m = model(rect(0.0, 0.5, 2.0, 0.5, 16, 4, CellType::Quad4), E, 0.3);
    let s = with_load(sub("cap", m, Constraints::new()), |m, l| {
        l.traction(m, "ymax", |x, _| {
            [0.0, -10.0 * (1.0 + 0.3 * (x[0] - 1.0)), 0.0]
        })
        .unwrap();
    });
    with_load(s, |m, l| {
        l.traction(m, "ymax", |_, _| [1.0, 0.0, 0.0]).unwrap();
    })
}

fn assembly() -> Assembly {
    Assembly {
        subs: vec![plane(), block(), cap()],
        interfaces: vec![
            InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", 0.3),
            InterfaceSpec::perfect("cap-block", 1, "ymax", 2, "ymin"),
        ],
    }
}

fn constraints(s: usize, mesh: &alea_mesh::Mesh) -> Constraints {
    let mut c = Constraints::new();
    if s == 0 {
        c.clamp(mesh, "ymin").unwrap();
    }
    c
}

#[test]
fn every_substructure_is_in_equilibrium() {
    let asm = assembly();
    let cases: Vec<Vec<Vec<f64>>> = asm.subs.iter().map(|s| s.load_cases.clone()).collect();
    let mut solver = LatinSolver::new(
        asm,
        LatinOptions {
            tolerance: 1e-10,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap();
    let load_factors = vec![vec![1.5], vec![1.0], vec![1.0, 2.4]];
    let r = solver
        .run(&RunInput {
            young_factors: vec![1.0, 1.3, 0.8],
            load_factors: load_factors.clone(),
            ..Default::default()
        })
        .unwrap();
    assert_eq!(r.status, RunStatus::Converged, "{:?}", r.residuals.last());
    let counts = r.interfaces[0].status_counts();
    eprintln!(
        "{} iterations; contact [perfect, open, stick, slip] = {counts:?}",
        r.iterations
    );
    assert!(counts[2] > 0 && counts[3] > 0, "partial slip expected");
    for s in 0..3 {
        let model = r.scaled_model(solver.model(s), s);
        let mesh = &model.mesh;
        let n = mesh.num_nodes();
        let u = &r.displacements[s];
        let f_int = alea_fem::post::internal_forces(&model, u).unwrap();
        // External loads of this run.
        let mut f_ext = vec![0.0; 2 * n];
        for (case, lf) in cases[s].iter().zip(&load_factors[s]) {
            for (a, b) in f_ext.iter_mut().zip(case) {
                *a += lf * b;
            }
        }
        // Interface forces M_Gamma F (linear stage) on this substructure.
        let mut f_if = vec![0.0; 2 * n];
        for it in &r.interfaces {
            for side in 0..2 {
                if it.subs[side] != s {
                    continue;
                }
                for (i, &node) in it.nodes[side].iter().enumerate() {
                    for c in 0..2 {
                        f_if[2 * node + c] += it.weights[i] * it.f[side][i][c];
                    }
                }
            }
        }
        let residual: Vec<f64> = (0..2 * n).map(|k| f_int[k] - f_ext[k] - f_if[k]).collect();
        let scale = f_int
            .iter()
            .chain(&f_ext)
            .chain(&f_if)
            .fold(0.0f64, |a, v| a.max(v.abs()));
        // Free dofs: no reaction.
        let dofs = DofMap::for_mesh(mesh, &constraints(s, mesh)).unwrap();
        let free = dofs.reduce(&residual);
        let worst = free.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // Reactions where constrained; resultant and moment of everything.
        let mut sum = [0.0; 3];
        for k in 0..n {
            let x = mesh.coords[k];
            let fixed = !dofs.is_free_node(k);
            let mut t = [0.0; 2];
            for c in 0..2 {
                let reaction = if fixed { residual[2 * k + c] } else { 0.0 };
                t[c] = f_ext[2 * k + c] + f_if[2 * k + c] + reaction;
            }
            sum[0] += t[0];
            sum[1] += t[1];
            sum[2] += x[0] * t[1] - x[1] * t[0];
        }
        let total: f64 = f_ext.iter().map(|v| v.abs()).sum();
        eprintln!(
            "{}: free-dof residual {:.2e} (relative {:.2e}), resultant ({:.2e}, {:.2e}), moment {:.2e}, |loads| {total:.3e}",
            solver.sub_name(s),
            worst,
            worst / scale,
            sum[0],
            sum[1],
            sum[2]
        );
        assert!(
            worst < 1e-8 * scale,
            "{}: residual {worst:e}",
            solver.sub_name(s)
        );
        for v in sum {
            assert!(
                v.abs() < 1e-8 * scale * 2.0,
                "{}: {sum:?}",
                solver.sub_name(s)
            );
        }
    }
    // The converged local stage matches the linear stage (LATIN tolerance).
    for it in &r.interfaces {
        // Tractions are O(10) (the cap's pressure).
        for i in 0..it.points.len() {
            for c in 0..2 {
                assert!((it.f[1][i][c] - it.fhat[1][i][c]).abs() < 1e-6 * 10.0);
            }
        }
        if it.law == "perfect" {
            assert!(it.status.iter().all(|s| *s == PointStatus::Perfect));
        }
    }
}

fn err_of(r: Result<LatinSolver, LatinError>) -> LatinError {
    match r {
        Ok(_) => panic!("expected an error"),
        Err(e) => e,
    }
}

#[test]
fn unknown_facet_group_is_an_error() {
    let mut asm = assembly();
    asm.interfaces[0].group2 = "no_such_group".into();
    let e = err_of(LatinSolver::new(asm, LatinOptions::default()));
    let msg = e.to_string();
    eprintln!("{msg}");
    assert!(matches!(e, LatinError::Mesh { ref sub, .. } if sub == "block"));
    assert!(msg.contains("no_such_group"), "{msg}");
}

#[test]
fn mismatched_sides_name_the_interface_and_the_worst_distance() {
    // 16 cells on the plane's top, 14 on the block's bottom.
    let mut asm = assembly();
    let m = model(rect(0.0, 0.0, 2.0, 0.5, 14, 4, CellType::Quad4), E, 0.3);
    asm.subs[1] = sub("block", m, Constraints::new());
    asm.interfaces.truncate(1);
    asm.interfaces[0].pairing = Pairing::NodeToNode;
    let x1: Vec<f64> = (0..=16).map(|i| i as f64 / 8.0).collect();
    let x2: Vec<f64> = (0..=14).map(|i| i as f64 / 7.0).collect();
    // Worst distance from a plane node to its nearest block node.
    let want = x1
        .iter()
        .map(|a| {
            x2.iter()
                .map(|b| (a - b).abs())
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let e = err_of(LatinSolver::new(asm, LatinOptions::default()));
    let msg = e.to_string();
    eprintln!("{msg}");
    match e {
        LatinError::Unmatched {
            interface,
            side1,
            side2,
            worst,
            ..
        } => {
            assert_eq!(interface, "contact");
            assert_eq!((side1, side2), (17, 15));
            assert!((worst - want).abs() < 1e-12, "worst {worst} vs {want}");
        }
        other => panic!("expected Unmatched, got {other:?}"),
    }
    assert!(msg.contains("'contact'") && msg.contains("worst unmatched distance"));
    // Same node counts, but one side shifted by 0.01 along x.
    let mut asm = assembly();
    let m = model(rect(0.01, 0.0, 2.0, 0.5, 16, 4, CellType::Quad4), E, 0.3);
    asm.subs[1] = sub("block", m, Constraints::new());
    asm.interfaces.truncate(1);
    asm.interfaces[0].pairing = Pairing::NodeToNode;
    match err_of(LatinSolver::new(asm, LatinOptions::default())) {
        LatinError::Unmatched {
            interface, worst, ..
        } => {
            assert_eq!(interface, "contact");
            assert!((worst - 0.01).abs() < 1e-12, "worst {worst}");
        }
        other => panic!("expected Unmatched, got {other:?}"),
    }
}

#[test]
fn invalid_run_inputs_are_errors() {
    let mut solver = LatinSolver::new(assembly(), LatinOptions::default()).unwrap();
    let bad = |solver: &mut LatinSolver, input: RunInput, needle: &str| match solver.run(&input) {
        Ok(_) => panic!("expected an error containing '{needle}'"),
        Err(e) => {
            let msg = e.to_string();
            eprintln!("{msg}");
            assert!(matches!(e, LatinError::Invalid(_)), "{e:?}");
            assert!(msg.contains(needle), "'{msg}' should contain '{needle}'");
        }
    };
    // Negative friction coefficient (named interface).
    bad(
        &mut solver,
        RunInput {
            mu: vec![Some(constant(-0.1)), None],
            ..Default::default()
        },
        "interface 'contact': friction coefficient",
    );
    // Non-finite gap.
    bad(
        &mut solver,
        RunInput {
            gap: vec![Some(constant(f64::NAN)), None],
            ..Default::default()
        },
        "gap is not finite",
    );
    // Wrong number of load factors for the cap (two cases).
    bad(
        &mut solver,
        RunInput {
            load_factors: vec![vec![1.0], vec![1.0], vec![1.0]],
            ..Default::default()
        },
        "substructure 'cap': 2 finite load factors expected",
    );
    // Wrong number of Young's-modulus factors, and a negative one.
    bad(
        &mut solver,
        RunInput {
            young_factors: vec![1.0, 1.0],
            ..Default::default()
        },
        "2 Young's-modulus factors given for 3 substructures",
    );
    bad(
        &mut solver,
        RunInput {
            young_factors: vec![1.0, -1.0, 1.0],
            ..Default::default()
        },
        "substructure 'block' must be > 0",
    );
    // mu fields for the wrong number of interfaces.
    bad(
        &mut solver,
        RunInput {
            mu: vec![None],
            ..Default::default()
        },
        "mu fields given for 1 interfaces, there are 2",
    );
    // The solver is still usable after rejected inputs.
    let r = solver.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
}

#[test]
fn load_case_of_the_wrong_length_is_an_error() {
    let mut asm = assembly();
    asm.subs[2].load_cases.push(vec![0.0; 7]);
    let e = err_of(LatinSolver::new(asm, LatinOptions::default()));
    let msg = e.to_string();
    eprintln!("{msg}");
    assert!(matches!(e, LatinError::Invalid(_)));
    assert!(
        msg.contains("substructure 'cap': load case of length 7"),
        "{msg}"
    );
    // A load case built on another model (wrong number of nodes) is caught the same way.
    let mut asm = assembly();
    let other = model(rect(0.0, 0.0, 1.0, 1.0, 2, 2, CellType::Quad4), E, 0.3);
    asm.subs[1].load_cases.push(Loads::new(&other).f);
    let e = err_of(LatinSolver::new(asm, LatinOptions::default()));
    assert!(
        e.to_string()
            .contains("substructure 'block': load case of length 18")
    );
}
