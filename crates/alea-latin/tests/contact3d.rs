//! Block on a plane in 3D: the stick / gross-slip / open thresholds of Coulomb contact and a
//! uniform gap closing, in a rotated frame (the contact normal and the slip directions have
//! three non-zero components, so a mixed-up component, sign or tangent-plane projection
//! shows).
//!
//! ```text
//!                 p n + traction / imposed tangential displacement on the top
//!          +-----------------+  z' = H      block (side 2), Hex8, nu = 0
//!          |      block      |
//!          +=================+  z' = 0      contact, n = e_z' (outward of the plane)
//!          |      plane      |
//!          +-----------------+  z' = -H     clamped
//!         x'=0              x'=L            (x', y', z') = Q^T (x, y, z), Q a generic rotation
//! ```
//! With `nu = 0` the uniform stress `sigma = -p n n + tau (n d + d n)` (`d` a unit tangent) is
//! an exact solution of both blocks when every side carries `sigma m` (`m` its outward normal):
//! the displacement is a simple shear `u = (2 tau d / E - p n / E) (n . x')` per block, which
//! the clamp allows and `Hex8` represents exactly. The interface then sees the force on the
//! block `Phi = sigma (-n) = p n - tau d` at every point:
//! - `tau < mu p` (loaded by tractions, block floating): stick everywhere, no slip;
//! - the top pushed along `d` by `delta` far beyond the elastic capacity, with the sides loaded
//!   for `tau = mu p`: slip everywhere with `Phi = p n - mu p d` (`|F_t| / F_n = mu`, friction
//!   opposite to the slip) and the slip `[W]_t = (delta - 4 mu p H / E) d` (the imposed motion
//!   minus the shear of the two blocks), for two directions `d`;
//! - the top pulled along `n`: open everywhere, zero force, gap = the pull;
//! - a uniform initial gap `g0` closes exactly when the imposed approach reaches `g0`, then
//!   `F_n = E (delta - g0) / (2 H)`; no point ever interpenetrates.

mod common;

use alea_fem::{Constraints, Model};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PointStatus, RunInput, RunResult,
    RunStatus, Substructure, constant,
};
use alea_mesh::{CellType, Mesh};
use common::*;

const E: f64 = 1000.0;
const L: f64 = 2.0;
const W: f64 = 1.5;
const H: f64 = 1.0;
const SIDES: [&str; 4] = ["xmin", "xmax", "ymin", "ymax"];

type M3 = [[f64; 3]; 3];

/// The rotation `Q = Rz(0.4) Ry(0.7) Rx(-0.3)`: columns are the images of the local axes.
fn rotation() -> M3 {
    let (a, b, c): (f64, f64, f64) = (0.4, 0.7, -0.3);
    let rz = [
        [a.cos(), -a.sin(), 0.0],
        [a.sin(), a.cos(), 0.0],
        [0.0, 0.0, 1.0],
    ];
    let ry = [
        [b.cos(), 0.0, b.sin()],
        [0.0, 1.0, 0.0],
        [-b.sin(), 0.0, b.cos()],
    ];
    let rx = [
        [1.0, 0.0, 0.0],
        [0.0, c.cos(), -c.sin()],
        [0.0, c.sin(), c.cos()],
    ];
    mul(&mul(&rz, &ry), &rx)
}

fn mul(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn col(q: &M3, j: usize) -> [f64; 3] {
    [q[0][j], q[1][j], q[2][j]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn comb(a: f64, u: [f64; 3], b: f64, v: [f64; 3]) -> [f64; 3] {
    [
        a * u[0] + b * v[0],
        a * u[1] + b * v[1],
        a * u[2] + b * v[2],
    ]
}

/// Local frame: `(t1, t2, n)` = images of the local x, y, z axes.
fn frame() -> ([f64; 3], [f64; 3], [f64; 3]) {
    let q = rotation();
    (col(&q, 0), col(&q, 1), col(&q, 2))
}

/// Tangent at angle `phi` from `t1` towards `t2`.
fn tangent(phi: f64) -> [f64; 3] {
    let (t1, t2, _) = frame();
    comb(phi.cos(), t1, phi.sin(), t2)
}

/// The box `[0, L] x [0, W] x [z0, z0 + H]` (local frame), rotated.
fn rotated_box(z0: f64) -> Mesh {
    let q = rotation();
    let mut m = cuboid([0.0, 0.0, z0], [L, W, H], [4, 3, 2], CellType::Hex8);
    for x in m.coords.iter_mut() {
        let y = *x;
        for i in 0..3 {
            x[i] = (0..3).map(|k| q[i][k] * y[k]).sum();
        }
    }
    m
}

/// `sigma = -p n n + tau (n d + d n)`.
fn stress(p: f64, tau: f64, d: [f64; 3]) -> M3 {
    let (_, _, n) = frame();
    let mut s = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            s[i][j] = -p * n[i] * n[j] + tau * (n[i] * d[j] + d[i] * n[j]);
        }
    }
    s
}

/// Loads the groups `groups` of a model with the tractions `sigma m` of a uniform stress.
fn load_uniform(s: Substructure, sigma: M3, groups: &'static [&'static str]) -> Substructure {
    with_load(s, move |m: &Model, l| {
        for g in groups {
            l.traction(m, g, move |_, nn| {
                [0, 1, 2].map(|i| (0..3).map(|j| sigma[i][j] * nn[j]).sum())
            })
            .unwrap();
        }
    })
}

fn plane(sigma: Option<M3>) -> Substructure {
    let m = solid(rotated_box(-H), E, 0.0);
    let mut c = Constraints::new();
    c.clamp(&m.mesh, "zmin").unwrap();
    let s = sub("plane", m, c);
    match sigma {
        Some(sg) => load_uniform(s, sg, &SIDES),
        None => s,
    }
}

fn solve(block: Substructure, plane: Substructure, mu: f64, gap: f64, tol: f64) -> RunResult {
    let mut iface = InterfaceSpec::coulomb("contact", 0, "zmax", 1, "zmin", mu);
    iface.gap = constant(gap);
    let mut s = LatinSolver::new(
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
    .unwrap();
    let r = s.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged, "{:?}", r.residuals.last());
    let (_, _, n) = frame();
    for p in &r.interfaces[0].points {
        assert!(
            (dot(p.normal, n) - 1.0).abs() < 1e-12,
            "interface normal {:?}",
            p.normal
        );
    }
    r
}

/// Imposes `u . dir = value` on every node of `group`.
fn fix_along(c: &mut Constraints, mesh: &Mesh, group: &str, dir: [f64; 3], value: f64) {
    for n in mesh.group_nodes(group).unwrap() {
        c.fix_direction(n, dir, value);
    }
}

#[test]
fn sticks_below_threshold_with_a_floating_block() {
    let (p, mu) = (10.0, 0.5);
    let tau = 0.6 * mu * p;
    let d = tangent(0.6);
    let sigma = stress(p, tau, d);
    let block = load_uniform(
        sub("block", solid(rotated_box(0.0), E, 0.0), Constraints::new()),
        sigma,
        &["zmax", "xmin", "xmax", "ymin", "ymax"],
    );
    let r = solve(block, plane(Some(sigma)), mu, 0.0, 1e-10);
    let (_, _, n) = frame();
    let want = comb(p, n, -tau, d);
    let it = &r.interfaces[0];
    for i in 0..it.points.len() {
        assert_eq!(it.status[i], PointStatus::Stick, "point {i}");
        for c in 0..3 {
            assert!(
                (it.fhat[1][i][c] - want[c]).abs() < 1e-6 * p,
                "point {i}: Phi = {:?}, want {want:?}",
                it.fhat[1][i]
            );
        }
        let j = it.jump(i);
        assert!(dot(j, j).sqrt() < 1e-9, "point {i}: jump {j:?}");
    }
}

#[test]
fn gross_slip_in_any_tangential_direction_saturates_the_cone() {
    let (p, mu, delta) = (10.0, 0.3, 0.2);
    let (t1, t2, n) = frame();
    for phi in [0.6, 2.8, -1.9] {
        let d = tangent(phi);
        let sigma = stress(p, mu * p, d);
        let bm = solid(rotated_box(0.0), E, 0.0);
        let mut c = Constraints::new();
        fix_along(&mut c, &bm.mesh, "zmax", t1, delta * phi.cos());
        fix_along(&mut c, &bm.mesh, "zmax", t2, delta * phi.sin());
        let block = with_load(sub("block", bm, c), |m, l| {
            l.pressure(m, "zmax", p).unwrap();
        });
        let block = load_uniform(block, sigma, &SIDES);
        let r = solve(block, plane(Some(sigma)), mu, 0.0, 1e-10);
        let it = &r.interfaces[0];
        let want = comb(p, n, -mu * p, d);
        let slip = delta - 4.0 * mu * p * H / E;
        let (mut res_n, mut res_t) = (0.0, [0.0; 3]);
        for i in 0..it.points.len() {
            assert_eq!(it.status[i], PointStatus::Slip, "phi {phi}, point {i}");
            // Linear-stage traction on the block (side 2): on the cone, opposite to d.
            let f = it.f[1][i];
            let fn_ = dot(f, n);
            let ft = comb(1.0, f, -fn_, n);
            assert!(fn_ > 0.0);
            let ratio = dot(ft, ft).sqrt() / fn_;
            assert!((ratio - mu).abs() < 1e-6, "phi {phi}: |F_t|/F_n = {ratio}");
            for c in 0..3 {
                assert!(
                    (f[c] - want[c]).abs() < 1e-6 * p,
                    "phi {phi}, point {i}: F = {f:?}, want {want:?}"
                );
            }
            // Local-stage slip along +d by the imposed motion minus the shear of the blocks,
            // opposite to the friction force on the block.
            let j = it.jump(i);
            let jt = comb(1.0, j, -dot(j, n), n);
            for c in 0..3 {
                assert!(
                    (jt[c] - slip * d[c]).abs() < 1e-6 * delta,
                    "phi {phi}, point {i}: slip {jt:?}, want {slip} x {d:?}"
                );
            }
            assert!(dot(j, n).abs() < 1e-9 * delta, "closed: zero gap");
            let fh = it.fhat[1][i];
            let fht = comb(1.0, fh, -dot(fh, n), n);
            assert!(dot(fht, jt) < 0.0, "friction opposes slip");
            res_n += it.weights[i] * fn_;
            for c in 0..3 {
                res_t[c] += it.weights[i] * ft[c];
            }
        }
        let area = L * W;
        assert!((res_n - p * area).abs() < 1e-6 * p * area, "{res_n}");
        for c in 0..3 {
            assert!((res_t[c] + mu * p * area * d[c]).abs() < 1e-6 * p * area);
        }
        assert!(it.friction_dissipation() > 0.0);
        let expected_dissipation = mu * p * area * slip;
        assert!(
            (it.friction_dissipation() - expected_dissipation).abs() < 1e-5 * expected_dissipation
        );
    }
}

#[test]
fn opens_under_tension() {
    let delta = 0.01;
    let (t1, t2, n) = frame();
    let bm = solid(rotated_box(0.0), E, 0.0);
    let mut c = Constraints::new();
    fix_along(&mut c, &bm.mesh, "zmax", n, delta);
    fix_along(&mut c, &bm.mesh, "zmax", t1, 0.0);
    fix_along(&mut c, &bm.mesh, "zmax", t2, 0.0);
    let r = solve(sub("block", bm, c), plane(None), 0.5, 0.0, 1e-10);
    let it = &r.interfaces[0];
    for i in 0..it.points.len() {
        assert_eq!(it.status[i], PointStatus::Open);
        assert_eq!(it.fhat[1][i], [0.0; 3]);
        let j = it.jump(i);
        for c in 0..3 {
            assert!((j[c] - delta * n[c]).abs() < 1e-8, "jump {j:?}");
        }
    }
}

#[test]
fn uniform_gap_closes_exactly_at_the_closing_load() {
    let g0 = 0.01;
    let (t1, t2, n) = frame();
    let mut results = Vec::new();
    for factor in [0.999, 1.001, 1.5] {
        let delta = factor * g0;
        let bm = solid(rotated_box(0.0), E, 0.0);
        let mut c = Constraints::new();
        fix_along(&mut c, &bm.mesh, "zmax", n, -delta);
        fix_along(&mut c, &bm.mesh, "zmax", t1, 0.0);
        fix_along(&mut c, &bm.mesh, "zmax", t2, 0.0);
        let r = solve(sub("block", bm, c), plane(None), 0.5, g0, 1e-11);
        let it = r.interfaces[0].clone();
        for i in 0..it.points.len() {
            let g = dot(it.jump(i), n);
            assert!(g >= -1e-12, "local-stage gap {g}");
            let lin = comb(1.0, it.w[1][i], -1.0, it.w[0][i]);
            let lin_gap = dot(lin, n) + g0;
            assert!(lin_gap >= -1e-8 * g0, "linear-stage gap {lin_gap}");
        }
        results.push((factor, it));
    }
    let (_, before) = &results[0];
    for i in 0..before.points.len() {
        assert_eq!(before.status[i], PointStatus::Open);
        let j = before.jump(i);
        for c in 0..3 {
            assert!((j[c] - 0.001 * g0 * n[c]).abs() < 1e-9, "jump {j:?}");
        }
    }
    for (factor, it) in &results[1..] {
        let want = E * (factor - 1.0) * g0 / (2.0 * H);
        for i in 0..it.points.len() {
            assert_eq!(it.status[i], PointStatus::Stick);
            let (fn_, ft) = it.normal_tangential(i);
            assert!((fn_ - want).abs() < 1e-6 * want, "F_n {fn_} vs {want}");
            assert!(ft < 1e-6 * want, "F_t {ft}");
        }
    }
}
