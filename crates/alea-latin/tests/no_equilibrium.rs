//! A run is converged only if it is in equilibrium: a block pushed up an incline beyond its
//! sliding limit has no static solution, and the solver must say so instead of "converged".
//!
//! ```text
//!                     q (vertical weight on the top face)
//!                  ______________
//!      push t --> |    block     |        incline at angle a, friction mu
//!                 |______________|  <- contact (node to node)
//!            ____/   base, clamped at its bottom
//! ```
//! Both parts are axis-aligned rectangles rotated by `a` about the origin, so the contact face
//! rises at angle `a`. The floating block carries a vertical load `G = q L` on its top face and
//! a horizontal push `H = t h` on its uphill-facing (left) face. It slides up the slope as soon
//! as (textbook wedge / NAFEMS CGS-4 relation)
//! `H / G > (tan a + mu) / (1 - mu tan a)`.
//! Below that ratio a static solution exists (stick or partial slip) and the interface forces
//! on the block balance the applied load exactly; above it there is none, and the run must end
//! as `NoEquilibrium` whatever the excess (5 %, 10 %, 50 %), naming the block. Just above the
//! limit (0.1 %, 2 %) the run may also end as not converged, but never as converged.

mod common;

use alea_fem::Constraints;
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus, Substructure,
};
use alea_mesh::{CellType, Mesh};
use common::*;

const E: f64 = 1000.0;
const L: f64 = 2.0;
const H: f64 = 0.5;
const ANGLE: f64 = 0.35; // radians, about 20 degrees
const MU: f64 = 0.3;
const Q: f64 = 10.0;

fn rotated(mut m: Mesh) -> Mesh {
    let (c, s) = (ANGLE.cos(), ANGLE.sin());
    for x in m.coords.iter_mut() {
        let (a, b) = (x[0], x[1]);
        x[0] = c * a - s * b;
        x[1] = s * a + c * b;
    }
    m
}

/// The push at which the block starts to slide up.
fn sliding_push() -> f64 {
    let t = ANGLE.tan();
    Q * L * (t + MU) / (1.0 - MU * t)
}

fn solver(push: f64) -> LatinSolver {
    let base_model = model(
        rotated(rect(0.0, -1.0, L, 1.0, 12, 6, CellType::Quad4)),
        E,
        0.3,
    );
    let mut c = Constraints::new();
    c.clamp(&base_model.mesh, "ymin").unwrap();
    let base = sub("base", base_model, c);
    let t = push / H;
    let block: Substructure = with_load(
        sub(
            "block",
            model(
                rotated(rect(0.0, 0.0, L, H, 12, 3, CellType::Quad4)),
                E,
                0.3,
            ),
            Constraints::new(),
        ),
        move |m, l| {
            l.traction(m, "ymax", |_, _| [0.0, -Q, 0.0]).unwrap();
            l.traction(m, "xmin", move |_, _| [t, 0.0, 0.0]).unwrap();
        },
    );
    LatinSolver::new(
        Assembly {
            subs: vec![base, block],
            interfaces: vec![InterfaceSpec::coulomb("incline", 0, "ymax", 1, "ymin", MU)],
        },
        LatinOptions {
            tolerance: 1e-6,
            max_iterations: 4000,
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn below_the_sliding_limit_the_block_is_held_and_balanced() {
    let limit = sliding_push();
    for ratio in [0.2, 0.5, 0.9] {
        let push = ratio * limit;
        let s = solver(push);
        let r = s.run_shared(&RunInput::default()).unwrap();
        assert_eq!(r.status, RunStatus::Converged, "push ratio {ratio}");
        // Independent check: interface resultant on the block + applied load = 0.
        let f = r.interfaces[0].resultant();
        let applied = [push, -Q * L];
        let scale = push.hypot(Q * L);
        for c in 0..2 {
            assert!(
                (f[c] + applied[c]).abs() < 1e-4 * scale,
                "ratio {ratio}: resultant {f:?} against the load {applied:?}"
            );
        }
        let eq = &r.equilibrium[1];
        assert_eq!(eq.free_modes, 3, "the block floats");
        assert!(eq.relative_imbalance < 1e-5, "{eq:?}");
        assert_eq!(r.equilibrium[0].free_modes, 0, "the base is clamped");
        assert!(s.equilibrium_report(&r).is_none());
    }
}

#[test]
fn beyond_the_sliding_limit_there_is_no_static_equilibrium() {
    let limit = sliding_push();
    for excess in [0.05, 0.10, 0.50] {
        let s = solver((1.0 + excess) * limit);
        let r = s.run_shared(&RunInput::default()).unwrap();
        assert_eq!(
            r.status,
            RunStatus::NoEquilibrium,
            "{} % above the limit: {} iterations, last indicator {:?}",
            100.0 * excess,
            r.iterations,
            r.residuals.last()
        );
        let why = s.equilibrium_report(&r).expect("a diagnosis");
        assert!(why.contains("'block'"), "{why}");
        // The excess load is what the interface cannot carry: the reported imbalance is of
        // the order of the excess (relative to the block's load scale), far above tolerance.
        assert!(r.equilibrium[1].relative_imbalance > 1e-3, "{why}");
        assert!(!r.equilibrium[1].holds(1e-4, 10.0));
    }
    for excess in [0.001, 0.02] {
        let s = solver((1.0 + excess) * limit);
        let r = s.run_shared(&RunInput::default()).unwrap();
        assert_ne!(
            r.status,
            RunStatus::Converged,
            "{} % above the limit",
            100.0 * excess
        );
    }
}
