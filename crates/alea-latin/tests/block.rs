//! Block on a plane: the stick / slip / open thresholds of Coulomb contact.
//!
//! ```text
//!            P (pressure) + tau or imposed displacement
//!        +-----------------+  y = H      upper block (side 2), plane strain, nu = 0
//!        |      block      |
//!        +=================+  y = 0      contact interface, n = +y (outward of the plane)
//!        |      plane      |
//!        +-----------------+  y = -H     clamped
//!       x=0               x=L
//! ```
//! With `nu = 0` a uniform stress state `sigma_yy = -P, sigma_xy = tau` is an exact solution of
//! both blocks (clamped base included) when the sides carry the matching shear tractions, so the
//! interface sees `F_n = P`, `F_t = tau` at every point: it must stick for `tau < mu P`
//! (no slip anywhere). With the top displaced tangentially by much more than the elastic
//! capacity, every point must slip with `|F_t| / F_n = mu` (the linear-stage tractions,
//! which converge to the local-stage ones). Pulled up, the contact opens with zero force.
//! A uniform initial gap `g0` closes exactly when the imposed approach reaches `g0`, and the
//! contact force then follows the series compression of the two blocks,
//! `sigma = E (delta - g0) / (2 H)`; no point ever interpenetrates.

mod common;

use alea_fem::Constraints;
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PointStatus, RunInput, RunStatus,
    Substructure, constant,
};
use alea_mesh::CellType;
use common::*;

const E: f64 = 1000.0;
const L: f64 = 2.0;
const H: f64 = 1.0;

fn plane() -> Substructure {
    let m = model(rect(0.0, -H, L, H, 8, 4, CellType::Quad4), E, 0.0);
    let mut c = Constraints::new();
    c.clamp(&m.mesh, "ymin").unwrap();
    sub("plane", m, c)
}

fn solver(block: Substructure, plane: Substructure, mu: f64, tol: f64) -> LatinSolver {
    let iface = InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", mu);
    LatinSolver::new(
        Assembly {
            subs: vec![plane, block],
            interfaces: vec![iface],
        },
        LatinOptions {
            tolerance: tol,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn sticks_below_threshold_with_a_floating_block() {
    let (p, tau, mu) = (10.0, 3.0, 0.5); // tau < mu P
    let shear = move |m: &alea_fem::Model, l: &mut alea_fem::Loads| {
        l.traction(m, "xmax", move |_, _| [0.0, tau, 0.0]).unwrap();
        l.traction(m, "xmin", move |_, _| [0.0, -tau, 0.0]).unwrap();
    };
    let block = with_load(
        sub(
            "block",
            model(rect(0.0, 0.0, L, H, 8, 4, CellType::Quad4), E, 0.0),
            Constraints::new(),
        ),
        |m, l| {
            l.traction(m, "ymax", move |_, _| [tau, -p, 0.0]).unwrap();
            shear(m, l);
        },
    );
    let plane = with_load(plane(), shear);
    let mut s = solver(block, plane, mu, 1e-10);
    let r = s.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    let it = &r.interfaces[0];
    for i in 0..it.points.len() {
        assert_eq!(it.status[i], PointStatus::Stick, "point {i}");
        let (fn_, ft) = it.normal_tangential(i);
        assert!((fn_ - p).abs() < 1e-6 * p, "F_n = {fn_}");
        assert!((ft - tau).abs() < 1e-6 * p, "F_t = {ft}");
        let jump = it.jump(i);
        assert!(jump[0].abs() < 1e-9, "tangential slip {}", jump[0]);
    }
}

#[test]
fn gross_slip_above_threshold_saturates_the_cone() {
    let (p, mu, delta) = (10.0, 0.3, 0.2);
    let bm = model(rect(0.0, 0.0, L, H, 8, 4, CellType::Quad4), E, 0.0);
    let mut c = Constraints::new();
    c.fix_component(&bm.mesh, "ymax", 0, delta).unwrap();
    let block = with_load(sub("block", bm, c), |m, l| {
        l.pressure(m, "ymax", p).unwrap();
    });
    let mut s = solver(block, plane(), mu, 1e-9);
    let r = s.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    let it = &r.interfaces[0];
    let (mut sum_n, mut sum_t) = (0.0, 0.0);
    for i in 0..it.points.len() {
        assert_eq!(it.status[i], PointStatus::Slip, "point {i}");
        // Linear-stage traction on the block (side 2).
        let f = it.f[1][i];
        let (fn_, ft) = (f[1], f[0]);
        assert!(fn_ > 0.0);
        assert!(
            (ft.abs() / fn_ - mu).abs() < 1e-6,
            "point {i}: |F_t|/F_n = {}",
            ft.abs() / fn_
        );
        // Friction on the block opposes its +x slip.
        assert!(ft < 0.0);
        assert!(it.jump(i)[0] > 0.0);
        sum_n += it.weights[i] * fn_;
        sum_t += it.weights[i] * ft;
    }
    // Resultants: total normal force = P L, tangential = mu P L.
    assert!(
        (sum_n - p * L).abs() < 1e-6 * p * L,
        "normal resultant {sum_n}"
    );
    assert!(
        (sum_t + mu * p * L).abs() < 1e-6 * p * L,
        "tangential resultant {sum_t}"
    );
    assert!(r.interfaces[0].friction_dissipation() > 0.0);
}

#[test]
fn opens_under_tension() {
    let delta = 0.01;
    let bm = model(rect(0.0, 0.0, L, H, 8, 4, CellType::Quad4), E, 0.0);
    let mut c = Constraints::new();
    c.fix_component(&bm.mesh, "ymax", 1, delta).unwrap();
    c.fix_component(&bm.mesh, "ymax", 0, 0.0).unwrap();
    let mut s = solver(sub("block", bm, c), plane(), 0.5, 1e-10);
    let r = s.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    let it = &r.interfaces[0];
    for i in 0..it.points.len() {
        assert_eq!(it.status[i], PointStatus::Open);
        assert_eq!(it.fhat[1][i], [0.0; 3]);
        assert!(
            (it.jump(i)[1] - delta).abs() < 1e-8,
            "gap {}",
            it.jump(i)[1]
        );
    }
}

#[test]
fn uniform_gap_closes_exactly_at_the_closing_load() {
    let g0 = 0.01;
    let mut results = Vec::new();
    for factor in [0.999, 1.001, 1.5] {
        let delta = factor * g0;
        let bm = model(rect(0.0, 0.0, L, H, 8, 4, CellType::Quad4), E, 0.0);
        let mut c = Constraints::new();
        c.fix_component(&bm.mesh, "ymax", 1, -delta).unwrap();
        c.fix_component(&bm.mesh, "ymax", 0, 0.0).unwrap();
        // The plane's sides are free in x only through nu = 0 (no lateral strain).
        let mut iface = InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", 0.5);
        iface.gap = constant(g0);
        let mut s = LatinSolver::new(
            Assembly {
                subs: vec![plane(), sub("block", bm, c)],
                interfaces: vec![iface],
            },
            LatinOptions {
                tolerance: 1e-11,
                max_iterations: 20000,
                ..Default::default()
            },
        )
        .unwrap();
        let r = s.run(&RunInput::default()).unwrap();
        assert_eq!(r.status, RunStatus::Converged);
        let it = r.interfaces[0].clone();
        // No interpenetration anywhere: local stage exactly, linear stage to tolerance.
        for i in 0..it.points.len() {
            let g = it.jump(i)[1];
            assert!(g >= -1e-12, "local-stage gap {g}");
            let lin_gap = it.w[1][i][1] - it.w[0][i][1] + g0;
            assert!(lin_gap >= -1e-8 * g0, "linear-stage gap {lin_gap}");
        }
        results.push((factor, it));
    }
    // Just before closing: open everywhere, no force, remaining gap g0 - delta.
    let (_, before) = &results[0];
    for i in 0..before.points.len() {
        assert_eq!(before.status[i], PointStatus::Open);
        assert!((before.jump(i)[1] - 0.001 * g0).abs() < 1e-9);
    }
    // Just after and well after: closed everywhere, F_n = E (delta - g0) / (2 H).
    for (factor, it) in &results[1..] {
        let want = E * (factor - 1.0) * g0 / (2.0 * H);
        for i in 0..it.points.len() {
            assert_ne!(it.status[i], PointStatus::Open);
            let (fn_, _) = it.normal_tangential(i);
            assert!((fn_ - want).abs() < 1e-6 * want, "F_n {fn_} vs {want}");
        }
    }
}

#[test]
fn multiresolution_matches_cold_solves_on_a_parameter_series() {
    let p = 10.0;
    let make = || {
        let bm = model(rect(0.0, 0.0, L, H, 8, 4, CellType::Quad4), E, 0.0);
        let mut c = Constraints::new();
        c.fix_component(&bm.mesh, "ymax", 0, 0.02).unwrap();
        let block = with_load(sub("block", bm, c), |m, l| {
            l.pressure(m, "ymax", p).unwrap();
        });
        solver(block, plane(), 0.5, 1e-8)
    };
    // The warm series starts each run from the previous one's end state (the caller's warm
    // start, as a study's runner gives it); the cold series from zero.
    let mut warm = make();
    let mut cold = make();
    let mut iters = (0, 0);
    let mut works = Vec::new();
    let mut previous: Option<std::sync::Arc<alea_latin::LocalState>> = None;
    for k in 0..9 {
        let mu = 0.1 + 0.1 * k as f64;
        let e2 = 0.8 + 0.05 * k as f64;
        let input = RunInput {
            young_factors: vec![1.0, e2],
            mu: vec![Some(constant(mu))],
            ..Default::default()
        };
        let rw = warm
            .run(&RunInput {
                initial: previous.clone(),
                ..input.clone()
            })
            .unwrap();
        let rc = cold.run(&input).unwrap();
        previous = Some(std::sync::Arc::new(rw.end_state()));
        assert_eq!(rw.status, RunStatus::Converged);
        assert_eq!(rc.status, RunStatus::Converged);
        if k > 0 {
            iters.0 += rw.iterations;
            iters.1 += rc.iterations;
        }
        let (a, b) = (&rw.interfaces[0], &rc.interfaces[0]);
        let scale = p;
        for i in 0..a.points.len() {
            for c in 0..2 {
                assert!((a.fhat[1][i][c] - b.fhat[1][i][c]).abs() < 1e-5 * scale);
            }
        }
        let (wa, wc) = (a.work(), b.work());
        assert!(
            (wa - wc).abs() < 1e-5 * (wc.abs() + p * 0.02 * L * 1e-3),
            "work {wa} vs {wc}"
        );
        works.push(wc);
    }
    eprintln!(
        "iterations warm {} vs cold {}; works {works:?}",
        iters.0, iters.1
    );
    // The series crosses the slip threshold: friction work is non-zero at low mu and
    // (nearly) zero once everything sticks.
    assert!(works[0] < -1e-3 && works[8].abs() < 1e-3 * works[0].abs());
    assert!(iters.0 < iters.1, "warm starts must save iterations");
}

#[test]
fn anderson_acceleration_matches_plain_iterations_with_fewer_of_them() {
    // Partial slip: the top is pushed sideways by less than the gross-slip displacement.
    let p = 10.0;
    let mut results = Vec::new();
    for depth in [0, 5] {
        let bm = model(rect(0.0, 0.0, L, H, 16, 8, CellType::Quad4), E, 0.3);
        let mut c = Constraints::new();
        c.fix_component(&bm.mesh, "ymax", 0, 0.035).unwrap();
        let block = with_load(sub("block", bm, c), |m, l| {
            l.pressure(m, "ymax", p).unwrap();
        });
        let plane = {
            let m = model(rect(0.0, -H, L, H, 16, 8, CellType::Quad4), E, 0.3);
            let mut c = Constraints::new();
            c.clamp(&m.mesh, "ymin").unwrap();
            sub("plane", m, c)
        };
        let mut s = LatinSolver::new(
            Assembly {
                subs: vec![plane, block],
                interfaces: vec![InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", 0.3)],
            },
            LatinOptions {
                tolerance: 1e-10,
                max_iterations: 20000,
                acceleration: Some(depth),
                ..Default::default()
            },
        )
        .unwrap();
        let r = s.run(&RunInput::default()).unwrap();
        assert_eq!(r.status, RunStatus::Converged, "depth {depth}");
        results.push(r);
    }
    let (plain, fast) = (&results[0], &results[1]);
    let counts = fast.interfaces[0].status_counts();
    eprintln!(
        "plain {:?} {:?}, fast {counts:?}",
        plain.interfaces[0].status_counts(),
        plain.interfaces[0].resultant()
    );
    assert!(
        counts[2] > 0 && counts[3] > 0,
        "partial slip expected: {counts:?}"
    );
    assert_eq!(plain.interfaces[0].status, fast.interfaces[0].status);
    for i in 0..plain.interfaces[0].points.len() {
        for c in 0..2 {
            let (a, b) = (
                plain.interfaces[0].fhat[1][i][c],
                fast.interfaces[0].fhat[1][i][c],
            );
            assert!((a - b).abs() < 1e-6 * p, "point {i}: {a} vs {b}");
        }
    }
    eprintln!(
        "iterations plain {} vs accelerated {}",
        plain.iterations, fast.iterations
    );
    // Measured with the defaults (coarse problem, k = 3 E / L): 89 plain, 35 accelerated.
    assert!(2 * fast.iterations < plain.iterations);
}
