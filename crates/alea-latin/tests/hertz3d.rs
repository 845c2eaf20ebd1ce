//! Hertz point contact: an elastic sphere pressed on a (nearly) rigid flat, frictionless.
//!
//! Reference: K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, section
//! 4.2 (eqs. 4.22-4.24, bodies of revolution). For a total load `P` between a sphere of radius
//! `R` and a flat,
//!
//! ```text
//!   a  = (3 P R / (4 E*))^(1/3),      1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
//!   p(r) = p0 sqrt(1 - r^2 / a^2),    p0 = 3 P / (2 pi a^2).
//! ```
//!
//! Set-up (quarter model `x, y >= 0`: `u_x = 0` on `x = 0`, `u_y = 0` on `y = 0`):
//!
//! ```text
//!              uniform traction P / (4 l^2) on z = +l  (total P/4 on the quarter)
//!          +------v-v-v-v-v-v-v-v-------+  z = +l
//!          |  "sphere" (E, nu), a box   |   floating in z: held only by the contact
//!          |  refined toward the origin,|   (corner-refined octant, Hex8)
//!          |  curvature in g0           |
//!          +==contact==+----free--------+  z = 0     contact: the fine square [0, A]^2,
//!          |  slab     |                              h = A / n
//!          +-----------+ z = -t  clamped (E_slab = 1000 E, t = h)
//!         x=0          A                x = l
//! ```
//! **Geometry choice.** As in the 2D Hertz test (`hertz.rs`), the solver pairs interface nodes
//! one to one, so both contact faces are meshed flat on `z = 0` with coincident nodes and the
//! sphere's curvature enters as the initial normal gap (shape defect, thesis 2.17-2.19)
//! `g0(r) = r^2 / (2R)`: exactly Hertz's own model (each body an elastic half-space loaded on its
//! flat boundary; the profile enters only through the initial separation; `a / R = 0.05`). The
//! flat is a slab of one layer of cells, 1000 times stiffer than the sphere and clamped on its
//! base: its compliance over the contact (`~ p0 t / E_slab`) is `1e-4` of the sphere's
//! indentation, so `E* = E / (1 - nu^2)` (rigid flat). In 3D the far boundary of a body of
//! size `l` changes the surface deflection over the contact only by a near-constant plus
//! `O((a / l)^3)` in curvature, so a box of `l = 10 a` is a half-space here. The sphere's mesh
//! is a uniform cube of `n^3` cells around the contact (`h ~ a / 9.6`, so `a` does not fall on a
//! node) joined to the far faces by graded frusta (`alea_mesh::generate::corner_refined_blocks`).
//!
//! Goal: the contact radius from the contact status (edge interpolated between the last closed
//! and the first open node along each symmetry axis, extrapolating `p^2`, linear in `r` near the
//! edge, to zero) and from a least-squares fit of `p^2 = p0^2 (1 - r^2/a^2)` over the closed nodes
//! inside `0.8 a` is within 2 % of Hertz's `a`; the peak pressure (fitted, and at the node
//! `r = 0`) is within 3 % of `p0`; the total contact force equals the applied load (round-off for
//! the linear-stage tractions, the LATIN tolerance for the local-stage ones); no point
//! interpenetrates. Obtained (h = a/9.6, 17 847 + 1 014 dof, 33 iterations to 1e-7): a within
//! -0.6 % (status) and -0.1 % (fit), p0 within +0.15 % (fit) and +0.16 % (node r = 0), pressure
//! within 1 % of p0 pointwise over r <= 0.9 a.

mod common;

use alea_fem::{Constraints, Loads};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PointStatus, RunInput, RunStatus,
};
use common::contact::linear_fit;
use common::contact3d::PointLayout;
use common::*;
use std::sync::Arc;

const E: f64 = 210e3;
const NU: f64 = 0.3;
const R: f64 = 20.0;

/// Edge of the closed zone along the axis where `pts` (sorted `(abscissa, pressure, status)`)
/// were taken: between the last closed node `x_c` and the next one, by extrapolating `p^2`
/// linearly from the last two closed nodes to zero.
fn edge(pts: &[(f64, f64, PointStatus)]) -> f64 {
    let last = pts
        .iter()
        .rposition(|p| p.2 != PointStatus::Open)
        .expect("a closed point");
    assert!(
        pts[..=last].iter().all(|p| p.2 != PointStatus::Open),
        "the contact zone is one interval along the axis"
    );
    let (xc, xo) = (pts[last].0, pts[last + 1].0);
    let (pc, pp) = (pts[last].1, pts[last - 1].1);
    let h = xc - pts[last - 1].0;
    (xc + h * pc * pc / (pp * pp - pc * pc)).clamp(xc, xo)
}

#[test]
fn hertz_sphere_on_a_flat() {
    let t0 = std::time::Instant::now();
    let a_th: f64 = 1.0;
    let e_star = E / (1.0 - NU * NU);
    let p_total = 4.0 * e_star * a_th.powi(3) / (3.0 * R);
    let p0_th = 3.0 * p_total / (2.0 * std::f64::consts::PI * a_th * a_th);
    let lay = PointLayout {
        a: 1.25 * a_th,
        l: 10.0 * a_th,
        n: 12,
        m: 8,
        quarter: true,
    };
    let h = lay.h();
    let flat = {
        let m = solid(lay.slab(h), 1000.0 * E, NU);
        let mut c = Constraints::new();
        c.clamp(&m.mesh, "base").unwrap();
        c.fix_component(&m.mesh, "sym_x", 0, 0.0).unwrap();
        c.fix_component(&m.mesh, "sym_y", 1, 0.0).unwrap();
        sub("flat", m, c)
    };
    let q = 0.25 * p_total / (lay.l * lay.l);
    let sphere = {
        let m = solid(lay.upper(), E, NU);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "sym_x", 0, 0.0).unwrap();
        c.fix_component(&m.mesh, "sym_y", 1, 0.0).unwrap();
        with_load(sub("sphere", m, c), |m, l: &mut Loads| {
            l.traction(m, "far_z", move |_, _| [0.0, 0.0, -q]).unwrap();
        })
    };
    let mut iface = InterfaceSpec::coulomb("contact", 0, "contact", 1, "contact", 0.0);
    iface.gap = Arc::new(|x: [f64; 3]| (x[0] * x[0] + x[1] * x[1]) / (2.0 * R));
    let tol = 1e-7;
    let mut solver = LatinSolver::new(
        Assembly {
            subs: vec![flat, sphere],
            interfaces: vec![iface],
        },
        LatinOptions {
            tolerance: tol,
            max_iterations: 5000,
            ..Default::default()
        },
    )
    .unwrap();
    let setup = solver.setup_seconds;
    let r = solver.run(&RunInput::default()).unwrap();
    eprintln!(
        "dofs {} + {}; setup {setup:.2}s, {} iterations, run {:.2}s, eta {:?}",
        solver.model(0).mesh.num_nodes() * 3,
        solver.model(1).mesh.num_nodes() * 3,
        r.iterations,
        r.timings.total,
        r.residuals.last()
    );
    assert_eq!(r.status, RunStatus::Converged, "{:?}", r.residuals.last());
    let it = &r.interfaces[0];

    // Total force on the sphere (side 2): linear stage exactly, local stage to tolerance.
    let quarter = 0.25 * p_total;
    let lin: f64 = (0..it.points.len())
        .map(|i| it.weights[i] * it.f[1][i][2])
        .sum();
    let loc = it.resultant()[2];
    eprintln!("force: applied {quarter}, linear {lin}, local {loc}");
    assert!(
        (lin - quarter).abs() < 1e-9 * quarter,
        "linear-stage force {lin} vs {quarter}"
    );
    assert!(
        (loc - quarter).abs() < 10.0 * tol * quarter,
        "local-stage force {loc} vs {quarter}"
    );
    let local_tangential = it.resultant();
    assert!(
        local_tangential[0].abs() < 1e-9 * quarter && local_tangential[1].abs() < 1e-9 * quarter
    );

    // Pressure profiles along both symmetry axes.
    let axis = |d: usize| {
        let mut v: Vec<(f64, f64, PointStatus)> = (0..it.points.len())
            .filter(|&i| it.points[i].x[1 - d].abs() < 1e-9 * h)
            .map(|i| (it.points[i].x[d], it.normal_tangential(i).0, it.status[i]))
            .collect();
        v.sort_by(|p, q| p.0.total_cmp(&q.0));
        v
    };
    let (ax, ay) = (edge(&axis(0)), edge(&axis(1)));
    let a_status = 0.5 * (ax + ay);
    // Fit p^2 = p0^2 - (p0^2 / a^2) r^2 over the closed nodes inside 0.8 a.
    let (mut t, mut y) = (Vec::new(), Vec::new());
    for i in 0..it.points.len() {
        let x = it.points[i].x;
        let r2 = x[0] * x[0] + x[1] * x[1];
        if it.status[i] != PointStatus::Open && r2 <= (0.8 * a_status).powi(2) {
            t.push(r2);
            y.push(it.normal_tangential(i).0.powi(2));
        }
    }
    let (c0, c1) = linear_fit(&t, &y);
    let (p0_fit, a_fit) = (c0.sqrt(), (-c0 / c1).sqrt());
    let centre = (0..it.points.len())
        .find(|&i| it.points[i].x[0].abs() < 1e-12 && it.points[i].x[1].abs() < 1e-12)
        .expect("node at the origin");
    let p_centre = it.normal_tangential(centre).0;
    let err = |v: f64, w: f64| (v - w) / w;
    eprintln!(
        "a: Hertz {a_th:.5}, status x {ax:.5} y {ay:.5} -> {a_status:.5} ({:+.2} %), fit {a_fit:.5} \
         ({:+.2} %); p0: Hertz {p0_th:.1}, fit {p0_fit:.1} ({:+.2} %), node r=0 {p_centre:.1} \
         ({:+.2} %); {} fitted nodes, h/a = {:.3}; total {:.2}s",
        100.0 * err(a_status, a_th),
        100.0 * err(a_fit, a_th),
        100.0 * err(p0_fit, p0_th),
        100.0 * err(p_centre, p0_th),
        t.len(),
        h / a_th,
        t0.elapsed().as_secs_f64()
    );
    // Pointwise pressure profile against Hertz inside 0.9 a.
    let worst = (0..it.points.len())
        .filter_map(|i| {
            let x = it.points[i].x;
            let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
            (r <= 0.9 * a_th).then(|| {
                let want = p0_th * (1.0 - r * r / (a_th * a_th)).sqrt();
                (it.normal_tangential(i).0 - want).abs() / p0_th
            })
        })
        .fold(0.0, f64::max);
    eprintln!(
        "worst pressure deviation over r <= 0.9 a: {:.2} % of p0",
        100.0 * worst
    );
    assert!(err(ax, a_th).abs() < 0.02, "status radius along x {ax}");
    assert!(err(ay, a_th).abs() < 0.02, "status radius along y {ay}");
    assert!(err(a_fit, a_th).abs() < 0.02, "fitted radius {a_fit}");
    assert!(
        err(p0_fit, p0_th).abs() < 0.03,
        "fitted peak pressure {p0_fit}"
    );
    assert!(
        err(p_centre, p0_th).abs() < 0.03,
        "centre pressure {p_centre}"
    );
    // Axisymmetry of the closed zone: x and y edges agree, and the status is a function of r.
    assert!((ax - ay).abs() < 0.01 * a_th);
    for i in 0..it.points.len() {
        let x = it.points[i].x;
        let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
        if r < a_th - h {
            assert_ne!(it.status[i], PointStatus::Open, "open at r = {r}");
        }
        if r > a_th + h {
            assert_eq!(it.status[i], PointStatus::Open, "closed at r = {r}");
        }
        // No interpenetration in the local stage.
        assert!(it.jump(i)[2] >= -1e-12 * a_th, "gap {}", it.jump(i)[2]);
    }
}
