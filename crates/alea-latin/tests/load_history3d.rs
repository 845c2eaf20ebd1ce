//! Mindlin-Deresiewicz unloading of a sphere on a flat (point contact, 3D) as a load history
//! (module `alea_latin::steps`), on the set-up of `tests/cattaneo3d.rs` (same meshes, loads and
//! references; Johnson, *Contact Mechanics*, 1985, 7.2).
//!
//! History: (1) press `P`; (2) tangential load `Q* = 0.6 mu P` along x (Cattaneo-Mindlin:
//! stick disc `c/a = (1 - Q*/(mu P))^(1/3)`); (3) unload to `Q = -0.3 mu P` (past zero, so
//! that the reverse-slip annulus, `0.18 a` wide, spans more than a cell: unloaded to 0 it is
//! `0.11 a`, under the cell size `0.125 a`, and its measured edge was 6 % off). Unloading superposes
//! `-2 x` the loading solution at `(Q* - Q)/2` (with `2 mu`): the contact slips back in the
//! annulus `e < r < a` with `e/a = (1 - (Q* - Q)/(2 mu P))^(1/3)` and sticks inside.
//!
//! Checked: the tangential resultant of every step; `c/a` at step 2 and `e/a` at step 3 within
//! 3 % (edges along +x, -x and +y, as in `cattaneo3d.rs`; mesh `n = 14`, `h = a/11.2`); in the reverse-slip annulus the
//! friction force on the sphere points along `+x` (against the sphere's slip back), while at
//! step 2 it points along `-x` everywhere it slips. Path dependence: the static solve at
//! `Q = -0.3 mu P` has the stick radius of a monotonic load, `(1 - 0.3)^(1/3) a`, not `e`.
//!
//! Observed (mesh refinement): `n = 10` (`h = 0.125 a`): c/a +0.55 %, e/a +6.06 %;
//! `n = 14` (`h = 0.089 a`, this test, 2 x 3 steps of 21-26 iterations, 9 s): c/a -0.75 %,
//! e/a +0.43 %; static solve at the final load c/a = 0.8948 against 0.8879 monotonic, history
//! e/a = 0.8228.

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
const LOAD: f64 = 0.6;
/// `Q / (mu P)` unloaded to.
const BACK: f64 = -0.3;

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

fn step(ratio: f64) -> RunInput {
    RunInput {
        load_factors: vec![vec![], vec![1.0, ratio]],
        ..Default::default()
    }
}

/// Mean closed radius `a` and stick radius around the centre, from the edges along +x, -x, +y.
fn radii(it: &InterfaceResult, h: f64) -> (f64, f64) {
    let closed = |p: &(f64, f64, f64, PointStatus)| p.3 != PointStatus::Open;
    let stick = |p: &(f64, f64, f64, PointStatus)| p.3 == PointStatus::Stick;
    let margin = |p: &(f64, f64, f64, PointStatus)| MU * p.1 - p.2;
    let (px, py) = (profile(it, 0, h), profile(it, 1, h));
    let a = (edge(&px, 1, closed, |p| p.1)
        + edge(&px, -1, closed, |p| p.1)
        + edge(&py, 1, closed, |p| p.1))
        / 3.0;
    let c =
        (edge(&px, 1, stick, margin) + edge(&px, -1, stick, margin) + edge(&py, 1, stick, margin))
            / 3.0;
    (a, c)
}

#[test]
fn sphere_unloading_slips_back_in_the_mindlin_deresiewicz_annulus() {
    let t0 = std::time::Instant::now();
    let a_th: f64 = 1.0;
    let e_star = E / (2.0 * (1.0 - NU * NU));
    let p_total = 4.0 * e_star * a_th.powi(3) / (3.0 * R);
    let lay = PointLayout {
        a: 1.25 * a_th,
        l: 8.0 * a_th,
        n: 14,
        m: 6,
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
    let mut iface = InterfaceSpec::coulomb("contact", 0, "contact", 1, "contact", MU);
    iface.gap = Arc::new(|x: [f64; 3]| (x[0] * x[0] + x[1] * x[1]) / (2.0 * R));
    let solver = LatinSolver::new(
        Assembly {
            subs: vec![flat, sphere],
            interfaces: vec![iface],
        },
        LatinOptions {
            tolerance: 1e-7,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap();
    let res = solver
        .run_steps(&[step(0.0), step(LOAD), step(BACK)])
        .unwrap();
    assert_eq!(res.len(), 3);
    for (k, r) in res.iter().enumerate() {
        assert_eq!(r.status, RunStatus::Converged, "step {}", k + 1);
        let f = r.interfaces[0].resultant();
        let want = [0.0, LOAD, BACK][k] * 0.5 * q;
        assert!(
            (f[0] + want).abs() < 1e-4 * q,
            "step {}: Q {}",
            k + 1,
            -f[0]
        );
    }
    let (a2, c2) = radii(&res[1].interfaces[0], h);
    let (a3, e3) = radii(&res[2].interfaces[0], h);
    let (cw, ew) = (
        (1.0 - LOAD).powf(1.0 / 3.0),
        (1.0 - 0.5 * (LOAD - BACK)).powf(1.0 / 3.0),
    );
    let iterations: Vec<usize> = res.iter().map(|r| r.iterations).collect();
    eprintln!(
        "iterations {iterations:?}; a = {a2:.4} / {a3:.4}; c/a = {:.4} vs {cw:.4} ({:+.2} %); \
         e/a = {:.4} vs {ew:.4} ({:+.2} %); {:.1}s",
        c2 / a2,
        100.0 * (c2 / a2 - cw) / cw,
        e3 / a3,
        100.0 * (e3 / a3 - ew) / ew,
        t0.elapsed().as_secs_f64()
    );
    assert!((c2 / a2 - cw).abs() < 0.03 * cw, "c/a");
    assert!((e3 / a3 - ew).abs() < 0.03 * ew, "e/a");
    // Friction on the sphere along x: -x while loading, +x in the annulus that slips back.
    let (mut back, mut fwd) = (0, 0);
    for (k, sign) in [(1, -1.0), (2, 1.0)] {
        let it = &res[k].interfaces[0];
        for i in 0..it.points.len() {
            if it.status[i] == PointStatus::Slip {
                assert!(sign * it.fhat[1][i][0] > 0.0, "step {}: point {i}", k + 1);
                if k == 2 {
                    back += 1;
                } else {
                    fwd += 1;
                }
            }
        }
    }
    assert!(back > 0 && fwd > 0);
    // One static solve at the final load: a monotonic load's stick radius, not e.
    let once = solver.run_shared(&step(BACK)).unwrap();
    assert_eq!(once.status, RunStatus::Converged);
    let (a1, c1) = radii(&once.interfaces[0], h);
    let mono = (1.0 + BACK).powf(1.0 / 3.0);
    eprintln!(
        "static solve at the final load: c/a = {:.4} (monotonic {mono:.4}), history e/a = {:.4}",
        c1 / a1,
        e3 / a3
    );
    assert!((c1 / a1 - mono).abs() < 0.05 * mono);
    assert!((e3 / a3 - c1 / a1).abs() > 0.05 * mono, "path dependence");
}
