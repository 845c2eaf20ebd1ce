//! Press-then-slide load histories (module `alea_latin::steps`) of an elastic block on an
//! elastic base, with the top of the block moved by imposed displacements step by step (one
//! solver per set of imposed values, the same meshes and interface).
//!
//! Closed forms (Coulomb's law, resultants over the contact): while the contact slips at every
//! closed point, the tangential resultant is `|Q| = mu N` with `N` the normal resultant and `Q`
//! opposite to the slip increment of the step; before that, part of the contact sticks and
//! `|Q| < mu N`. The answers are path-dependent, and each check below is one that a single
//! static solve at the same final loads gets wrong:
//! - 2D: press by `p`, move the top by a small `d` (stick inside, `|Q| < mu N`), then by `D`
//!   (full slip, `Q = +mu N`), then back to `0` (full reverse slip, `Q = -mu N`; the static solve
//!   at `d = 0` gives `Q = 0`, and so does the static law started from the slid state);
//! - 3D: press, move the top by `D` along `x` (`Q = mu N` along `x`), then by `D` along `y`
//!   (the slip increment of the step is along `y`, so `Q` turns to `y`: `Q_y = mu N` up to the
//!   elastic recoil of the step; the static total-slip law would put `Q` along the total slip,
//!   at 45 degrees). In 3D every slipping point carries `mu` times its normal force, but the
//!   points' slip directions differ slightly near the edges, so the vector resultant is
//!   `|Q| = mu N` within 1e-3.

mod common;

use alea_fem::{Constraints, Loads};
use alea_latin::steps::run_history;
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PointStatus, RunInput, RunResult, RunStatus,
};
use alea_mesh::CellType;
use common::*;

const E: f64 = 210e3;
const NU: f64 = 0.3;
const MU: f64 = 0.3;
const PRESSURE: f64 = 10.0;

fn options() -> LatinOptions {
    LatinOptions {
        tolerance: 1e-8,
        max_iterations: 20000,
        ..Default::default()
    }
}

/// 2D: base `[0, 20] x [-10, 0]` clamped below, block `[0, 20] x [0, 10]` pressed by
/// `PRESSURE` on its top, whose `x` displacement is imposed to `d`.
fn solver_2d(d: f64) -> LatinSolver {
    let base = {
        let m = model(rect(0.0, -10.0, 20.0, 10.0, 20, 10, CellType::Quad4), E, NU);
        let mut c = Constraints::new();
        c.clamp(&m.mesh, "ymin").unwrap();
        sub("base", m, c)
    };
    let block = {
        let m = model(rect(0.0, 0.0, 20.0, 10.0, 20, 10, CellType::Quad4), E, NU);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "ymax", 0, d).unwrap();
        with_load(sub("block", m, c), |m, ld: &mut Loads| {
            ld.traction(m, "ymax", |_, _| [0.0, -PRESSURE, 0.0])
                .unwrap();
        })
    };
    LatinSolver::new(
        Assembly {
            subs: vec![base, block],
            interfaces: vec![InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", MU)],
        },
        options(),
    )
    .unwrap()
}

/// 3D: base `[0, 10]^2 x [-5, 0]` clamped below, block `[0, 10]^2 x [0, 5]` pressed on its
/// top, whose `x` and `y` displacements are imposed to `d`.
fn solver_3d(d: [f64; 2]) -> LatinSolver {
    let n = [8, 8, 4];
    let base = {
        let m = solid(
            cuboid([0.0, 0.0, -5.0], [10.0, 10.0, 5.0], n, CellType::Hex8),
            E,
            NU,
        );
        let mut c = Constraints::new();
        c.clamp(&m.mesh, "zmin").unwrap();
        sub("base", m, c)
    };
    let block = {
        let m = solid(
            cuboid([0.0, 0.0, 0.0], [10.0, 10.0, 5.0], n, CellType::Hex8),
            E,
            NU,
        );
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "zmax", 0, d[0]).unwrap();
        c.fix_component(&m.mesh, "zmax", 1, d[1]).unwrap();
        with_load(sub("block", m, c), |m, ld: &mut Loads| {
            ld.traction(m, "zmax", |_, _| [0.0, 0.0, -PRESSURE])
                .unwrap();
        })
    };
    LatinSolver::new(
        Assembly {
            subs: vec![base, block],
            interfaces: vec![InterfaceSpec::coulomb("contact", 0, "zmax", 1, "zmin", MU)],
        },
        options(),
    )
    .unwrap()
}

/// Friction resultant on the block (`Q`, opposite to the interface force on it) and the normal
/// resultant `N` pressing it, with the normal along `axis`.
fn resultants(r: &RunResult, axis: usize) -> ([f64; 3], f64) {
    let f = r.interfaces[0].resultant();
    let mut q = [-f[0], -f[1], -f[2]];
    let n = f[axis];
    q[axis] = 0.0;
    (q, n)
}

fn counts(r: &RunResult) -> (usize, usize) {
    let s = &r.interfaces[0].status;
    (
        s.iter().filter(|&&x| x == PointStatus::Stick).count(),
        s.iter().filter(|&&x| x == PointStatus::Slip).count(),
    )
}

#[test]
fn press_then_slide_then_back_in_2d() {
    let (small, big) = (2e-5, 1e-2);
    let (s0, s1, s2) = (solver_2d(0.0), solver_2d(small), solver_2d(big));
    let input = RunInput::default;
    let res = run_history(&[
        (&s0, input()),
        (&s1, input()),
        (&s2, input()),
        (&s0, input()),
    ])
    .unwrap();
    assert_eq!(res.len(), 4);
    let mut qs = Vec::new();
    for (k, r) in res.iter().enumerate() {
        assert_eq!(r.status, RunStatus::Converged, "step {}", k + 1);
        let (q, n) = resultants(r, 1);
        let (stick, slip) = counts(r);
        eprintln!(
            "step {}: {} iterations, N = {n:.4}, Q = {:+.5} = {:+.5} mu N; stick {stick}, slip \
             {slip}",
            k + 1,
            r.iterations,
            q[0],
            q[0] / (MU * n)
        );
        assert!((n - PRESSURE * 20.0).abs() < 1e-4 * n, "N = the load");
        qs.push((q[0], n, stick, slip));
    }
    // Press: no net friction.
    assert!(qs[0].0.abs() < 1e-4 * MU * qs[0].1);
    // Small move: stick inside, |Q| below the limit.
    assert!(qs[1].2 > 0 && qs[1].0 > 0.0 && qs[1].0 < 0.99 * MU * qs[1].1);
    // Large move: every closed point slips, Q = mu N.
    assert_eq!(qs[2].2, 0, "no stick point once sliding");
    assert!((qs[2].0 - MU * qs[2].1).abs() < 1e-4 * MU * qs[2].1);
    // Back to d = 0: full reverse slip, Q = -mu N.
    assert_eq!(qs[3].2, 0, "no stick point when sliding back");
    assert!((qs[3].0 + MU * qs[3].1).abs() < 1e-4 * MU * qs[3].1);
    // The same final loads in one static step (and the static law started from the slid
    // state) give no friction: the history is what sets Q.
    let once = s0.run_shared(&RunInput::default()).unwrap();
    let from_slid = s0
        .run_shared(&RunInput {
            initial: Some(std::sync::Arc::new(res[2].end_state())),
            ..Default::default()
        })
        .unwrap();
    for r in [&once, &from_slid] {
        assert_eq!(r.status, RunStatus::Converged);
        let (q, n) = resultants(r, 1);
        assert!(q[0].abs() < 1e-3 * MU * n, "static Q = {}", q[0]);
    }
    // The block stays where it slid to: the tangential jump at the end is about D - 2 mu N /
    // k_t, positive and below D.
    let it = &res[3].interfaces[0];
    let mean_jump: f64 = (0..it.points.len())
        .map(|i| it.weights[i] * (it.what[1][i][0] - it.what[0][i][0]))
        .sum::<f64>()
        / it.weights.iter().sum::<f64>();
    let slid = &res[2].interfaces[0];
    let mean_slid: f64 = (0..slid.points.len())
        .map(|i| slid.weights[i] * (slid.what[1][i][0] - slid.what[0][i][0]))
        .sum::<f64>()
        / slid.weights.iter().sum::<f64>();
    eprintln!("mean tangential jump: after sliding {mean_slid:.4e}, after return {mean_jump:.4e}");
    assert!(mean_slid > 0.5 * big && mean_slid < big);
    assert!(mean_jump > 0.0 && mean_jump < mean_slid);
}

#[test]
fn press_slide_along_x_then_along_y_in_3d() {
    let big = 2e-2;
    let (s0, sx, sxy) = (
        solver_3d([0.0, 0.0]),
        solver_3d([big, 0.0]),
        solver_3d([big, big]),
    );
    let res = run_history(&[
        (&s0, RunInput::default()),
        (&sx, RunInput::default()),
        (&sxy, RunInput::default()),
    ])
    .unwrap();
    assert_eq!(res.len(), 3);
    for (k, r) in res.iter().enumerate() {
        assert_eq!(r.status, RunStatus::Converged, "step {}", k + 1);
        let (q, n) = resultants(r, 2);
        eprintln!(
            "step {}: {} iterations, N = {n:.3}, Q = ({:+.5}, {:+.5}) mu N, |Q| = {:.5} mu N; \
             stick/slip {:?}",
            k + 1,
            r.iterations,
            q[0] / (MU * n),
            q[1] / (MU * n),
            (q[0] * q[0] + q[1] * q[1]).sqrt() / (MU * n),
            counts(r)
        );
        assert!((n - PRESSURE * 100.0).abs() < 1e-4 * n, "N = the load");
    }
    // Every closed point slips, at mu times its normal force; the slip directions of the
    // points differ slightly (Poisson effects at the edges), so the vector sum |Q| is within
    // 1e-3 of mu N, not equal (observed 0.99973 mu N).
    let (q, n) = resultants(&res[1], 2);
    assert!((q[0] - MU * n).abs() < 1e-3 * MU * n && q[1].abs() < 1e-4 * MU * n);
    let (q, n) = resultants(&res[2], 2);
    let norm = (q[0] * q[0] + q[1] * q[1]).sqrt();
    assert_eq!(counts(&res[2]).0, 0, "every closed point slips");
    assert!((norm - MU * n).abs() < 1e-3 * MU * n, "|Q| = mu N");
    assert!(q[1] / norm > 0.99, "Q turned to y: {:?}", q);
    // One static step to (D, D): Q along the total slip, at 45 degrees.
    let once = sxy.run_shared(&RunInput::default()).unwrap();
    assert_eq!(once.status, RunStatus::Converged);
    let (q1, _) = resultants(&once, 2);
    assert!(
        (q1[0] - q1[1]).abs() < 1e-3 * MU * n,
        "static: Q along (1, 1)"
    );
}
