//! Cattaneo-Mindlin partial slip of a sphere on a flat (point contact, 3D).
//!
//! Reference: K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, section
//! 7.1 (tangential loading of spheres in contact: Cattaneo 1938, Mindlin 1949; eqs. 7.38-7.42).
//! Two bodies of the **same** material (so the normal and tangential problems decouple:
//! Dundurs' beta = 0) are pressed by `P` (Hertz: `a = (3 P R / (4 E*))^(1/3)`, `E* = E / (2 (1 -
//! nu^2))`, pressure `p(r) = p0 sqrt(1 - r^2/a^2)`), then loaded by a tangential force `Q < mu P`
//! along x. The contact sticks in a central disc `r < c` and slips (`|q| = mu p`) in the annulus
//! `c < r < a`, with
//!
//! ```text
//!   q(r) = mu p0 sqrt(1 - r^2/a^2) - mu p0 (c/a) sqrt(1 - r^2/c^2)   (r < c),
//!   c / a = (1 - Q / (mu P))^(1/3).
//! ```
//! (Mindlin's solution takes the traction parallel to `Q` everywhere, which neglects a small
//! transverse component of order `nu / (2 - nu)`; the stick radius is the classical result.)
//!
//! Set-up (half model `y >= 0`, `u_y = 0` on `y = 0` for both bodies: the load along x keeps the
//! plane y = 0 a symmetry plane; the tangential problem is antisymmetric in `x` and the normal
//! one symmetric, coupled by the law, so the whole x range is modelled):
//!
//! ```text
//!          P/(4 l^2) down + mu P/(4 l^2) along x + m x up, on z = +l   (half of each load)
//!        +--->--->--->--->--->--->--->--->--+  z = +l
//!        |  "sphere" (steel), floating:     |
//!        |  held in x, z and rotation about |
//!        |  y by the contact; curvature in  |
//!        |  g0 = r^2 / (2R)                 |
//!        +-------==contact (fine)==---------+  z = 0    fine square [-A, A] x [0, A], h = A/n
//!        |  flat (steel)                    |
//!        +----------------------------------+  z = -l   clamped
//!       x=-l                0              x=l
//! ```
//! Both bodies are the corner-refined octant mirrored in x (and in z for the sphere), Hex8;
//! the curvature is in the initial gap of flat, node-for-node coincident contact faces, as in
//! `hertz3d.rs`. The tangential load is a uniform shear on the sphere's top; its moment
//! `Q l` about the contact centre would tip the floating sphere, so the load case also carries
//! the statically equivalent linear normal traction `m x` with `m = 3 mu P / (4 l^3)` on the
//! half model's top `[-l, l] x [0, l]`, which makes the resultant of the top loads pass
//! through the contact centre, as the theory assumes (checked below from the nodal forces).
//!
//! **Static non-incremental law.** As argued in `cattaneo_mindlin.rs` (2D), along the path
//! "normal load, then tangential load increasing monotonically" with identical materials the
//! slip zone only grows and the slip direction never changes, so one static solve with both
//! load cases applied (load factors `[1, Q/(mu P)]`) gives the Cattaneo-Mindlin state.
//!
//! Goal: for `Q/(mu P) = 0.25, 0.5, 0.75` (three runs of one solver, each warm-started from
//! the previous one; the load factor is a run parameter, no refactorisation), the stick radius
//! `c` from the stick/slip status (edges interpolated between the last stick and the next node
//! by extrapolating the squared margin `(mu p - |q|)^2` to zero, along +x, -x and +y, averaged)
//! gives `c / a` within 5 % of `(1 - Q/(mu P))^(1/3)`, with `a` measured from the open/closed
//! status the same way (and within 2 % of Hertz's); the tangential resultant equals `Q`, and the
//! friction force opposes the slip at every slipping point.
//!
//! Observed (h = a/8, l = 8 a, 2 x 17 238 dof, mu = 0.3): a = 1.007 a_Hertz; c/a = 0.890, 0.774,
//! 0.627 against 0.909, 0.794, 0.630 (errors -2.1, -2.5, -0.4 %), 42-48 iterations to 1e-7 per
//! run. With h = a/9.6 (n = 12, m = 6; 2 x 29 109 dof, three times slower) the errors were
//! +0.7, -0.2, +0.9 %. The stick disc is slightly off-centre along x (by up to 0.01 a, in the
//! direction of Q), a finite-body effect as in 2D; the mean of the three edges is insensitive to
//! it to first order.

mod common;

use alea_fem::{Constraints, Loads};
use alea_latin::{
    Assembly, InterfaceResult, InterfaceSpec, LatinOptions, LatinSolver, PointStatus, RunInput,
    RunStatus,
};
use common::contact3d::PointLayout;
use common::*;
use std::sync::Arc;

const E: f64 = 210e3;
const NU: f64 = 0.3;
const R: f64 = 20.0;
const MU: f64 = 0.3;

/// `(abscissa, F_n, |F_t|, status)` of the local stage along the axis `d` (0 = x, 1 = y),
/// sorted.
type Profile = Vec<(f64, f64, f64, PointStatus)>;

fn profile(it: &InterfaceResult, d: usize, h: f64) -> Profile {
    let mut v: Profile = (0..it.points.len())
        .filter(|&i| it.points[i].x[1 - d].abs() < 1e-9 * h)
        .map(|i| {
            let (n, t) = it.normal_tangential(i);
            (it.points[i].x[d], n, t, it.status[i])
        })
        .collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

/// Edge of the zone where `inside` holds around the origin, in direction `dir` (+1 / -1):
/// between the last inside node and the next one, by extrapolating `margin^2` (which vanishes
/// linearly at the edge) to zero from the last two inside nodes.
fn edge(
    prof: &Profile,
    dir: i32,
    inside: impl Fn(&(f64, f64, f64, PointStatus)) -> bool,
    margin: impl Fn(&(f64, f64, f64, PointStatus)) -> f64,
) -> f64 {
    zone_edge(prof, |p| p.0, dir, inside, margin, EdgeStep::Inward)
}

#[test]
fn stick_radius_follows_cattaneo_mindlin() {
    let t0 = std::time::Instant::now();
    let a_th: f64 = 1.0;
    let e_star = E / (2.0 * (1.0 - NU * NU));
    let p_total = 4.0 * e_star * a_th.powi(3) / (3.0 * R);
    let lay = PointLayout {
        a: 1.25 * a_th,
        l: 8.0 * a_th,
        n: 10,
        m: 5,
        quarter: false,
    };
    let (h, l) = (lay.h(), lay.l);
    let flat = {
        let m = solid(lay.lower(), E, NU);
        let mut c = Constraints::new();
        c.clamp(&m.mesh, "far_z").unwrap();
        c.fix_component(&m.mesh, "sym_y", 1, 0.0).unwrap();
        sub("flat", m, c)
    };
    // Case 0: the normal load P/2. Case 1: the tangential load mu P / 2 through the centre.
    let q = MU * p_total;
    let sphere = {
        let m = solid(lay.upper(), E, NU);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "sym_y", 1, 0.0).unwrap();
        let s = with_load(sub("sphere", m, c), |m, ld: &mut Loads| {
            let pn = p_total / (4.0 * l * l);
            ld.traction(m, "far_z", move |_, _| [0.0, 0.0, -pn])
                .unwrap();
        });
        with_load(s, |m, ld: &mut Loads| {
            let (tau, slope) = (q / (4.0 * l * l), 3.0 * q / (4.0 * l.powi(3)));
            ld.traction(m, "far_z", move |x, _| [tau, 0.0, slope * x[0]])
                .unwrap();
        })
    };
    {
        // Resultant and moment (about the contact centre) of the tangential case.
        let f = &sphere.load_cases[1];
        let mesh = &sphere.model.mesh;
        let (mut r, mut mom) = ([0.0; 3], [0.0; 3]);
        for (nd, x) in mesh.coords.iter().enumerate() {
            let fv = [f[3 * nd], f[3 * nd + 1], f[3 * nd + 2]];
            for c in 0..3 {
                r[c] += fv[c];
            }
            mom[0] += x[1] * fv[2] - x[2] * fv[1];
            mom[1] += x[2] * fv[0] - x[0] * fv[2];
            mom[2] += x[0] * fv[1] - x[1] * fv[0];
        }
        assert!((r[0] - 0.5 * q).abs() < 1e-10 * q && r[1].abs() + r[2].abs() < 1e-10 * q);
        assert!(
            mom[1].abs() < 1e-10 * q * l,
            "moment of the tangential case {mom:?}"
        );
    }
    let mut iface = InterfaceSpec::coulomb("contact", 0, "contact", 1, "contact", MU);
    iface.gap = Arc::new(|x: [f64; 3]| (x[0] * x[0] + x[1] * x[1]) / (2.0 * R));
    let tol = 1e-7;
    let mut solver = LatinSolver::new(
        Assembly {
            subs: vec![flat, sphere],
            interfaces: vec![iface],
        },
        LatinOptions {
            tolerance: tol,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap();
    eprintln!(
        "dofs {} + {}; setup {:.2}s",
        solver.model(0).mesh.num_nodes() * 3,
        solver.model(1).mesh.num_nodes() * 3,
        solver.setup_seconds
    );
    for ratio in [0.25, 0.5, 0.75] {
        let r = solver
            .run(&RunInput {
                load_factors: vec![vec![], vec![1.0, ratio]],
                ..Default::default()
            })
            .unwrap();
        assert_eq!(r.status, RunStatus::Converged, "{:?}", r.residuals.last());
        let it = &r.interfaces[0];
        let res = it.resultant();
        let closed = |p: &(f64, f64, f64, PointStatus)| p.3 != PointStatus::Open;
        let stick = |p: &(f64, f64, f64, PointStatus)| p.3 == PointStatus::Stick;
        let stick_margin = |p: &(f64, f64, f64, PointStatus)| MU * p.1 - p.2;
        let (px, py) = (profile(it, 0, h), profile(it, 1, h));
        let a_edges = [
            edge(&px, 1, closed, |p| p.1),
            edge(&px, -1, closed, |p| p.1),
            edge(&py, 1, closed, |p| p.1),
        ];
        let c_edges = [
            edge(&px, 1, stick, stick_margin),
            edge(&px, -1, stick, stick_margin),
            edge(&py, 1, stick, stick_margin),
        ];
        let a = a_edges.iter().sum::<f64>() / 3.0;
        let c = c_edges.iter().sum::<f64>() / 3.0;
        let want = (1.0 - ratio).powf(1.0 / 3.0);
        let err = (c / a - want) / want;
        let counts = it.status_counts();
        eprintln!(
            "Q/(mu P) = {ratio}: {} iterations ({:.2}s); resultant ({:.3}, {:.3}, {:.3}); \
             a = {a:.4} ({:.4} {:.4} {:.4}; Hertz {a_th:.4}); c = {c:.4} ({:.4} {:.4} {:.4}); \
             c/a = {:.4} vs {want:.4} ({:+.2} %); stick {} slip {} open {}",
            r.iterations,
            r.timings.total,
            res[0],
            res[1],
            res[2],
            a_edges[0],
            a_edges[1],
            a_edges[2],
            c_edges[0],
            c_edges[1],
            c_edges[2],
            c / a,
            100.0 * err,
            counts[2],
            counts[3],
            counts[1],
        );
        // Force on the sphere (side 2) from the flat: minus the applied load.
        assert!(
            (res[0] + 0.5 * ratio * q).abs() < 1e-4 * q,
            "tangential resultant {} vs {}",
            -res[0],
            0.5 * ratio * q
        );
        assert!((res[2] - 0.5 * p_total).abs() < 1e-4 * p_total);
        assert!((a - a_th).abs() < 0.02 * a_th, "a = {a} vs Hertz {a_th}");
        assert!(err.abs() < 0.05, "c/a = {} vs {want}", c / a);
        assert!(
            (c_edges[0] - c_edges[1]).abs() < 0.04 * a,
            "stick disc off-centre by {}",
            0.5 * (c_edges[0] - c_edges[1])
        );
        for i in 0..it.points.len() {
            if it.status[i] == PointStatus::Slip {
                let (j, f, n) = (it.jump(i), it.fhat[1][i], it.points[i].normal);
                let jn: f64 = (0..3).map(|k| j[k] * n[k]).sum();
                let fnn: f64 = (0..3).map(|k| f[k] * n[k]).sum();
                let work: f64 = (0..3)
                    .map(|k| (j[k] - jn * n[k]) * (f[k] - fnn * n[k]))
                    .sum();
                assert!(work < 0.0, "friction must oppose the slip at point {i}");
            }
        }
    }
    eprintln!("total {:.2}s", t0.elapsed().as_secs_f64());
}
