//! Hertz line contact: an elastic cylinder pressed on an elastic block, frictionless, plane
//! strain.
//!
//! Reference: K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, section 4.2
//! (two-dimensional contact of cylindrical bodies, eqs. 4.43-4.45). For a load `P'` per unit
//! length between bodies of relative curvature `1/R` (cylinder on a flat),
//!
//! ```text
//!   b  = sqrt(4 P' R / (pi E*)),      1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
//!   p(x) = p0 sqrt(1 - x^2 / b^2),    p0 = 2 P' / (pi b).
//! ```
//!
//! Set-up (half model `x >= 0`, symmetry `u_x = 0` on `x = 0` for both bodies):
//!
//! ```text
//!            uniform traction  P'/(2 l)  on y = +l (total P'/2 on the half model)
//!        +----------v-v-v-v-v-v---------+  y = +l
//!        |  "cylinder" (E2, nu2),       |   floating in y: held only by the contact
//!  u_x=0 |   flat bottom, curvature     |
//!        |   in g0(x) = R - sqrt(R^2-x^2)
//!        +=====contact=====+------------+  y = 0   contact group: 0 <= x <= a ~ 2.1 b,
//!        |  block (E1, nu1)             |           coincident nodes, h = a/50 ~ b/24
//!  u_x=0 |                              |
//!        +------------------------------+  y = -l  clamped          (l ~ 25 b)
//!       x=0                            x=l
//! ```
//!
//! **Geometry choice.** The solver pairs interface nodes one to one, so both contact faces are
//! meshed flat on `y = 0` with coincident nodes, and the cylinder's curvature enters as the
//! initial normal gap (the shape-defect mechanism of the interface law, thesis 2.17-2.19)
//! `g0(x) = R - sqrt(R^2 - x^2)`. This is exactly Hertz's own model: each body is treated as an
//! elastic half-space loaded on its flat boundary, the profile entering only through the
//! initial separation; it is valid for `b << R` (here `b / R = 0.02` and `0.029`; the circle
//! differs from Hertz's parabola `x^2 / (2R)` by `x^4 / (8 R^3)`, a relative change of `b^2 / (4 R^2) ~ 2e-4`
//! of the gap over the contact). Both bodies are squares of half-size `l ~ 25 b`: in 2D the
//! contact width does not depend on the body size (only the approach does), and the finite
//! bodies change the surface slope over the contact by `O((b / l)^2)`. The mesh is uniform
//! (`h ~ b / 24`, with `b` between nodes) in a square `a x a` around the contact and graded
//! outward (multiblock, [`common::contact`]).
//!
//! Goal: with dissimilar materials (steel block, aluminium cylinder) and with identical ones,
//! the contact half-width from the contact status (edge interpolated between the last closed and
//! the first open node by extrapolating `p^2`, linear in `x` near the edge, to zero) and from
//! a least-squares fit of `p^2 = p0^2 (1 - x^2/b^2)` are within 2 % of Hertz's `b`; the peak
//! pressure (fitted, and at the node `x = 0`) is within 3 % of `p0`; the total contact force
//! equals the applied load (round-off for the linear-stage tractions, the LATIN tolerance for
//! the local-stage ones). Obtained (h ~ b/24): b within 0.8 % (status) and 0.06 % (fit), p0
//! within 0.03 %.

mod common;

use alea_fem::{Constraints, Loads};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PairingKind, PointStatus, RunInput,
    RunStatus, Substructure,
};
use common::contact::{Layout, linear_fit};
use common::*;
use std::sync::Arc;

/// Materials `(E, nu)` of the block and of the cylinder, radius `R` and load `P'` (N, mm).
struct Case {
    block: (f64, f64),
    cylinder: (f64, f64),
    radius: f64,
    load: f64,
    layout: Layout,
    /// True geometry: the cylinder meshed with its curved bottom and this many cells across
    /// the fine strip (non-matching, mortar pairing); `None`: flat faces with coincident nodes
    /// and the curvature in `g0`.
    curved: Option<usize>,
}

impl Case {
    fn e_star(&self) -> f64 {
        let ((e1, nu1), (e2, nu2)) = (self.block, self.cylinder);
        1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
    }
}

#[test]
fn hertz_steel_block_aluminium_cylinder() {
    // P' chosen for b = 1 mm with R = 50 mm (b / R = 0.02); contact strip a = 2.1 b, h = a / 50
    // (b / h = 23.8, so b does not fall on a node).
    let (e1, nu1, e2, nu2, r) = (210e3, 0.3, 70e3, 0.33, 50.0);
    let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    check(Case {
        block: (e1, nu1),
        cylinder: (e2, nu2),
        radius: r,
        load: std::f64::consts::PI * e_star / (4.0 * r),
        layout: Layout {
            a: 2.1,
            l: 25.0,
            n: 50,
            m: 35,
            full: false,
        },
        curved: None,
    });
}

#[test]
fn hertz_identical_materials() {
    // Same steel for both bodies, R = 20 mm, P' = 1500 N/mm: b = 0.5754 mm (b / R = 0.029),
    // b / h = 23.6.
    check(Case {
        block: (210e3, 0.3),
        cylinder: (210e3, 0.3),
        radius: 20.0,
        load: 1500.0,
        layout: Layout {
            a: 1.22,
            l: 14.0,
            n: 50,
            m: 35,
            full: false,
        },
        curved: None,
    });
}

#[test]
fn hertz_true_geometry_non_matching() {
    // The cylinder (aluminium, R = 50 mm) meshed as a curved body, 40 cells across the strip,
    // on the steel block with 50: no node of the cylinder's bottom faces a node of the block;
    // the interface points are on the coarser side, the cylinder.
    let (e1, nu1, e2, nu2, r) = (210e3, 0.3, 70e3, 0.33, 50.0);
    let e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2);
    check(Case {
        block: (e1, nu1),
        cylinder: (e2, nu2),
        radius: r,
        load: std::f64::consts::PI * e_star / (4.0 * r),
        layout: Layout {
            a: 2.1,
            l: 25.0,
            n: 50,
            m: 35,
            full: false,
        },
        curved: Some(40),
    });
}

#[test]
fn hertz_true_geometry_identical_materials() {
    // Steel on steel, R = 20 mm; the cylinder finer (60 cells) than the block (50): the
    // points are on the block.
    check(Case {
        block: (210e3, 0.3),
        cylinder: (210e3, 0.3),
        radius: 20.0,
        load: 1500.0,
        layout: Layout {
            a: 1.22,
            l: 14.0,
            n: 50,
            m: 35,
            full: false,
        },
        curved: Some(60),
    });
}

fn check(case: Case) {
    let t0 = std::time::Instant::now();
    let p_total = case.load;
    let lay = case.layout;
    let rad = case.radius;
    let b_th = (4.0 * p_total * rad / (std::f64::consts::PI * case.e_star())).sqrt();
    let p0_th = 2.0 * p_total / (std::f64::consts::PI * b_th);
    let block = {
        let m = model(lay.lower().unwrap(), case.block.0, case.block.1);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "sym", 0, 0.0).unwrap();
        c.clamp(&m.mesh, "far").unwrap();
        sub("block", m, c)
    };
    let load = 0.5 * p_total / lay.l;
    let cylinder: Substructure = {
        let mesh = match case.curved {
            Some(n) => Layout { n, ..lay }.upper_curved(rad).unwrap(),
            None => lay.upper().unwrap(),
        };
        let m = model(mesh, case.cylinder.0, case.cylinder.1);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "sym", 0, 0.0).unwrap();
        with_load(sub("cylinder", m, c), |m, l: &mut Loads| {
            l.traction(m, "far", move |_, _| [0.0, -load, 0.0]).unwrap();
        })
    };
    let mut iface = InterfaceSpec::coulomb("contact", 0, "contact", 1, "contact", 0.0);
    if case.curved.is_none() {
        iface.gap = Arc::new(move |x: [f64; 3]| rad - (rad * rad - x[0] * x[0]).sqrt());
    }
    let tol = 1e-7;
    let mut solver = LatinSolver::new(
        Assembly {
            subs: vec![block, cylinder],
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
        solver.model(0).mesh.num_nodes() * 2,
        solver.model(1).mesh.num_nodes() * 2,
        r.iterations,
        r.timings.total,
        r.residuals.last()
    );
    assert_eq!(r.status, RunStatus::Converged, "{:?}", r.residuals.last());
    let it = &r.interfaces[0];
    let want = if case.curved.is_some() {
        PairingKind::Mortar
    } else {
        PairingKind::NodeToNode
    };
    assert_eq!(it.pairing.kind, want);

    // Total force on the cylinder (side 2): linear stage exactly, local stage to tolerance.
    let half = 0.5 * p_total;
    let lin: f64 = (0..it.points.len())
        .map(|i| it.weights[i] * it.f[1][i][1])
        .sum();
    let loc = it.resultant()[1];
    eprintln!("force: applied {half}, linear {lin}, local {loc}");
    assert!(
        (lin - half).abs() < 1e-10 * half,
        "linear-stage force {lin} vs {half}"
    );
    assert!(
        (loc - half).abs() < 10.0 * tol * half,
        "local-stage force {loc} vs {half}"
    );

    // Pressure along x (nodal tractions), sorted.
    let mut pts: Vec<(f64, f64, PointStatus)> = (0..it.points.len())
        .map(|i| (it.points[i].x[0], it.normal_tangential(i).0, it.status[i]))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Point spacing: the fine cells of the side carrying the points (the block's with coincident
    // nodes, the coarser cylinder's with the mortar pairing).
    let h = pts[1].0 - pts[0].0;
    let coarser = case.curved.map_or(lay.n, |n| n.min(lay.n));
    assert!(
        (h - lay.a / coarser as f64).abs() < 1e-9 * h,
        "points on the coarser side"
    );
    // Contact zone from the status: closed up to x_c, open from x_o = x_c + h.
    let last_closed = pts
        .iter()
        .rposition(|p| p.2 != PointStatus::Open)
        .expect("some closed point");
    assert!(
        pts[..=last_closed].iter().all(|p| p.2 != PointStatus::Open),
        "the contact zone is one interval"
    );
    let (xc, xo) = (pts[last_closed].0, pts[last_closed + 1].0);
    assert!((xo - xc - h).abs() < 1e-9 * h);
    // Interpolated edge: p^2 ~ 2 p0^2 (b - x) / b is linear near the edge; extrapolate it to
    // zero from the last two closed nodes, within the bracket [x_c, x_o].
    let (pc, pp) = (pts[last_closed].1, pts[last_closed - 1].1);
    let b_status = (xc + h * pc * pc / (pp * pp - pc * pc)).clamp(xc, xo);
    // Fit p^2 = p0^2 - (p0^2 / b^2) x^2 over the closed nodes away from the edge.
    let inner: Vec<&(f64, f64, PointStatus)> =
        pts.iter().filter(|p| p.0 <= 0.8 * b_status).collect();
    let t: Vec<f64> = inner.iter().map(|p| p.0 * p.0).collect();
    let y: Vec<f64> = inner.iter().map(|p| p.1 * p.1).collect();
    let (c0, c1) = linear_fit(&t, &y);
    let p0_fit = c0.sqrt();
    let b_fit = (-c0 / c1).sqrt();
    let err_status = (b_status - b_th) / b_th;
    let err_fit = (b_fit - b_th) / b_th;
    let err_p0 = (p0_fit - p0_th) / p0_th;
    let err_p_center = (pts[0].1 - p0_th) / p0_th;
    eprintln!(
        "b: Hertz {b_th:.5}, status [{xc:.4}, {xo:.4}] -> {b_status:.5} ({:+.2} %), fit {b_fit:.5} ({:+.2} %); \
         p0: Hertz {p0_th:.2}, fit {p0_fit:.2} ({:+.2} %), node x=0 {:.2} ({:+.2} %); total {:.2}s",
        100.0 * err_status,
        100.0 * err_fit,
        100.0 * err_p0,
        pts[0].1,
        100.0 * err_p_center,
        t0.elapsed().as_secs_f64()
    );
    // Pointwise pressure profile against Hertz in the inner 90 %.
    let worst = pts
        .iter()
        .filter(|p| p.0 <= 0.9 * b_th)
        .map(|p| (p.1 - p0_th * (1.0 - p.0 * p.0 / (b_th * b_th)).sqrt()).abs() / p0_th)
        .fold(0.0, f64::max);
    eprintln!(
        "worst pressure deviation over |x| <= 0.9 b: {:.2} % of p0",
        100.0 * worst
    );
    assert!(
        err_status.abs() < 0.02,
        "status half-width error {err_status}"
    );
    assert!(err_fit.abs() < 0.02, "fitted half-width error {err_fit}");
    assert!(err_p0.abs() < 0.03, "peak pressure error {err_p0}");
    assert!(
        err_p_center.abs() < 0.03,
        "centre pressure error {err_p_center}"
    );
    // No interpenetration in the local stage: the separation along the normal is >= 0.
    for i in 0..it.points.len() {
        let (j, n) = (it.jump(i), it.points[i].normal);
        let g = j[0] * n[0] + j[1] * n[1];
        assert!(g >= -1e-12 * b_th, "gap {g}");
    }
}
