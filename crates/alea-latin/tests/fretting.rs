//! Fretting quantities over a load cycle (module `alea_latin::fretting`) against the closed
//! forms of a cylinder on a flat under constant normal load `P'` and a tangential load cycled
//! between `+Q*` and `-Q*`, `Q* < mu P'` (partial slip), with the mesh refined twice.
//!
//! References: D. A. Hills, D. Nowell, *Mechanics of Fretting Fatigue*, 1994, ch. 2-3;
//! K. L. Johnson, *Contact Mechanics*, 1985, 2.2 (Flamant), 4.2 (Hertz), 7.1 (Cattaneo-Mindlin)
//! and 7.2 (Mindlin-Deresiewicz). Set-up of `tests/load_history.rs` (two identical steel bodies,
//! so normal and tangential problems decouple; curvature in the initial gap; the tangential
//! load through the contact centre; `E* = E / (2 (1 - nu^2))`). Hertz: `b = sqrt(4 P' R / (pi
//! E*))`, `p0 = 2 P' / (pi b)`, `p(x) = p0 sqrt(1 - x^2/b^2)`. History: press, `+Q*`, then the
//! cycle `(-Q*, +Q*)` twice (once on the finest mesh); the quantities are those of the last
//! cycle, its origin the step before it. The bodies are `l = 560 = 970 b` wide and deep (with
//! `l = 97 b`, the size of the other contact tests, the far-field stresses of the finite
//! bodies, of order `P'/l`, put the largest SWT 8.3 % above the closed form at the finest mesh,
//! against 1.7 % below at `970 b`).
//!
//! **Closed forms** (derived here from the half-plane relations, Johnson eq. 2.25, and the 2D
//! Hertz equation `(2 / (pi E*)) int p(s) / (x - s) ds = x / R`; `c = b sqrt(1 - Q*/(mu P'))`):
//!
//! - *Stick zone.* At `+-Q*` the tractions are `+-q_L(x)`, `q_L = mu p0 [sqrt(1 - x^2/b^2) -
//!   (c/b) sqrt(1 - x^2/c^2) 1{|x| < c}]` (Cattaneo-Mindlin, then Mindlin-Deresiewicz: the loop
//!   closes on `-q_L` and `+q_L`), so the zone that sticks throughout the cycle is `|x| < c`:
//!   length `2 c`, `c / b = sqrt(1 - Q*/(mu P'))`.
//! - *Slip.* The relative tangential displacement `s(x)` of identical bodies obeys
//!   `s'(x) = -(2 / (pi E*)) int q(t) / (x - t) dt`; with `int_{-a}^{a} sqrt(1 - t^2/a^2) / (x - t)
//!   dt = pi (x/a - sgn(x) sqrt(x^2/a^2 - 1) 1{|x| > a})` and `p0 / (b E*) = 1 / (2 R)`,
//!   `s'(x) = -(mu / R) sgn(x) sqrt(x^2 - c^2)` in `c < |x| < b` and 0 in the stick zone. The jump
//!   at `+Q*` minus that at `-Q*` is `2 s_L`, so the **slip amplitude** is
//!   `delta(x) = (mu / (2 R)) [ |x| sqrt(x^2 - c^2) - c^2 arccosh(|x| / c) ]` for `c < |x| < b`.
//! - *Work.* A point of the slip zone slips over each half cycle by `2 delta` under `|q| = mu p`
//!   in a fixed direction: `W(x) = 4 mu p(x) delta(x)` per cycle, `tau(x) = mu p(x)`, so
//!   `F1(x) = mu p(x) delta(x)`.
//! - *Surface stress* of the block (Flamant: a tangential line load `Q` in `+x` gives `sigma_xx =
//!   -2 Q / (pi x)` on the surface; a normal pressure gives `sigma_xx = -p` under it): at `+Q*`
//!   (traction `+q_L` on the block)
//!   `sigma_xx(x, 0) = -p(x) - (2/pi) int q_L(t) / (x - t) dt`, i.e.
//!   `-p(x) - 2 mu p0 sgn(x) sqrt(x^2 - c^2) / b` in `c < |x| <= b`, `-p(x)` in `|x| < c`, and
//!   `-2 mu p0 sgn(x) [sqrt(x^2 - c^2) - sqrt(x^2 - b^2)] / b` outside. At the trailing edge
//!   `x = -b`: `sigma_xx = 2 mu p0 sqrt(Q*/(mu P'))` (Hills & Nowell), at `-Q*` the opposite: the
//!   range at `x = +-b` is `4 mu p0 sqrt(Q*/(mu P'))`; `F2 = max(0, sigma_xx) F1`.
//! - *Below the surface* (point method, depth `L`): the Flamant kernels integrated over the
//!   tractions, `sigma_x = -(2/pi) int (p X^2 z + q X^3) / r^4`, `sigma_z = -(2/pi) int (p z^3
//!   + q X z^2) / r^4`, `tau_xz = -(2/pi) int (p X z^2 + q X^2 z) / r^4` (`X = x - t`, `z` the
//!   depth, `r^2 = X^2 + z^2`), by the midpoint rule in `t = b sin(phi)` (resp. `c sin(phi)` for
//!   the stick correction), and `sigma_zz = nu (sigma_xx + sigma_yy)` (plane strain). SWT from
//!   those states at `+-Q*` with the module's own formula on the same planes.
//!
//! What is asserted (module `fretting`'s computations on the FE steps, at the FE nodes, against
//! the closed forms at the same points): see [`fretting_cycle_against_closed_forms`].

mod common;

use alea_latin::fretting::{
    Regularisation, fatemi_socie, fs_of_stresses, plane_normals, slip_cycle, stress_cycle,
    swt_of_stresses,
};
use alea_latin::{LatinSolver, RunInput, RunStatus};
use common::contact::{CylinderLoad, Layout, cylinder_on_block};
use std::f64::consts::PI;

const E: f64 = 210e3;
const NU: f64 = 0.3;
const R: f64 = 20.0;
const P: f64 = 1500.0;
const MU: f64 = 0.3;
/// `Q* / (mu P')`.
const LOAD: f64 = 0.6;
/// Number of planes scanned by SWT.
const PLANES: usize = 180;

/// The closed-form fields (module doc).
struct Closed {
    b: f64,
    c: f64,
    p0: f64,
}

impl Closed {
    fn new() -> Self {
        let e_star = E / (2.0 * (1.0 - NU * NU));
        let b = (4.0 * P * R / (PI * e_star)).sqrt();
        Closed {
            b,
            c: b * (1.0 - LOAD).sqrt(),
            p0: 2.0 * P / (PI * b),
        }
    }

    fn p(&self, x: f64) -> f64 {
        if x.abs() < self.b {
            self.p0 * (1.0 - (x / self.b).powi(2)).sqrt()
        } else {
            0.0
        }
    }

    fn delta(&self, x: f64) -> f64 {
        let (ax, c) = (x.abs(), self.c);
        if ax <= c || ax > self.b {
            return 0.0;
        }
        MU / (2.0 * R) * (ax * (ax * ax - c * c).sqrt() - c * c * (ax / c).acosh())
    }

    /// Surface `sigma_xx` of the block at `+Q*`.
    fn sxx_surface(&self, x: f64) -> f64 {
        let (ax, b, c) = (x.abs(), self.b, self.c);
        let s = x.signum();
        let k = 2.0 * MU * self.p0 / b;
        if ax < c {
            -self.p(x)
        } else if ax <= b {
            -self.p(x) - k * s * (ax * ax - c * c).sqrt()
        } else {
            -k * s * ((ax * ax - c * c).sqrt() - (ax * ax - b * b).sqrt())
        }
    }

    /// Surface stress of the block at `sign Q*`: `sigma_yy = -p`, `sigma_xy = +-q_L` (the
    /// traction on the block's surface, outward normal `+y`), `sigma_xx` as above.
    fn stress_surface(&self, x: f64, sign: f64) -> [f64; 6] {
        let stick = if x.abs() < self.c {
            (self.c / self.b) * (1.0 - (x / self.c).powi(2)).sqrt()
        } else {
            0.0
        };
        let q = MU * (self.p(x) - self.p0 * stick);
        let t = self.sxx_surface(x) + self.p(x);
        let (sx, sy) = (-self.p(x) + sign * t, -self.p(x));
        [sx, sy, NU * (sx + sy), 0.0, 0.0, sign * q]
    }

    /// The line method's stress: the mean over the depth `[0, l]` (Simpson, 16 intervals as
    /// the module).
    fn stress_line(&self, x: f64, l: f64, sign: f64) -> [f64; 6] {
        let m = 16;
        let mut acc = [0.0; 6];
        for j in 0..=m {
            let w = match j {
                0 => 1.0,
                j if j == m => 1.0,
                j if j % 2 == 1 => 4.0,
                _ => 2.0,
            } / (3.0 * m as f64);
            let z = l * j as f64 / m as f64;
            let s = if j == 0 {
                self.stress_surface(x, sign)
            } else {
                self.stress_below(x, z, sign)
            };
            for k in 0..6 {
                acc[k] += w * s[k];
            }
        }
        acc
    }

    /// `sigma_T`: the tensile part of the largest surface `sigma_xx` over the cycle (at `-Q*`
    /// the tangential part changes sign, the pressure part does not).
    fn sigma_t_surface(&self, x: f64) -> f64 {
        let plus = self.sxx_surface(x);
        let minus = -2.0 * self.p(x) - plus;
        plus.max(minus).max(0.0)
    }

    /// Stress `[xx, yy, zz, yz, xz, xy]` of the block (`y <= 0`) at `(x, -z)`, `z > 0`, at
    /// `sign Q*` (`sign = +-1`), by the Flamant kernels.
    fn stress_below(&self, x: f64, z: f64, sign: f64) -> [f64; 6] {
        let n = 6000;
        let (mut sx, mut sz, mut txz) = (0.0, 0.0, 0.0);
        // Pressure and full-sliding shear over |t| < b, then the stick correction over |t| < c.
        for (half, pf, qf) in [
            (self.b, self.p0, sign * MU * self.p0),
            (self.c, 0.0, -sign * MU * self.p0 * self.c / self.b),
        ] {
            let dphi = PI / n as f64;
            for j in 0..n {
                let phi = -0.5 * PI + (j as f64 + 0.5) * dphi;
                let t = half * phi.sin();
                let w = half * phi.cos() * dphi;
                let shape = phi.cos();
                let (pp, qq) = (pf * shape, qf * shape);
                let xx = x - t;
                let r4 = (xx * xx + z * z).powi(2);
                sx += w * (pp * xx * xx * z + qq * xx.powi(3)) / r4;
                sz += w * (pp * z.powi(3) + qq * xx * z * z) / r4;
                txz += w * (pp * xx * z * z + qq * xx * xx * z) / r4;
            }
        }
        let k = -2.0 / PI;
        let (sx, sy, sxy) = (k * sx, k * sz, -k * txz);
        [sx, sy, NU * (sx + sy), 0.0, 0.0, sxy]
    }
}

fn build(n: usize, m: usize) -> (LatinSolver, f64) {
    let lay = Layout {
        a: 1.22,
        l: 560.0,
        n,
        m,
        full: true,
    };
    (cylinder_on_block(&lay, &LOADING), lay.h())
}

/// The bodies and loads of every mesh.
const LOADING: CylinderLoad = CylinderLoad {
    young: E,
    poisson: NU,
    p: P,
    mu: MU,
    radius: R,
};

fn step(ratio: f64) -> RunInput {
    RunInput {
        load_factors: vec![vec![], vec![1.0, ratio]],
        ..Default::default()
    }
}

/// Errors of one mesh against the closed forms (relative errors, signed).
#[derive(Debug)]
struct Measured {
    h_over_b: f64,
    /// Length of the zone that sticks throughout the cycle, against `2 c`.
    stick: f64,
    /// Length of the zone that sticks in each step of the last cycle (`-Q*`, `+Q*`), against
    /// `2 c` (the stick zone "through the cycle").
    stick_steps: [f64; 2],
    /// Largest nodal slip-amplitude error, relative to `delta(b)` (nodes closed in the closed
    /// form as in the model), and the largest nodal amplitude against the closed form there.
    slip: f64,
    slip_max: f64,
    /// Integrated work per cycle against `int 4 mu p delta dx`.
    work: f64,
    /// Largest F1 against the largest closed-form F1 at the same nodes.
    f1: f64,
    /// Range of `sigma_xx` over the cycle at the trailing edge `(-b, -L)` (point method).
    range_l: f64,
    /// Largest SWT (point method, depth `L`) against the closed form at the same points.
    swt_l: f64,
    /// Surface values, reported: the range of `sigma_xx` at `(-b, 0)` (stress of the cell
    /// holding the point), the largest F2 with the nodal surface stresses.
    range_surface: f64,
    f2_surface: f64,
    /// Largest SWT of the line method against the closed form averaged the same way.
    swt_line: f64,
    /// Largest Fatemi-Socie parameter (point method, depth `L`; `k = 0.5`, `sigma_y = 1000`)
    /// against the closed form at the same points.
    fs_l: f64,
    /// Change of the slip amplitude between the two cycles, relative to `delta(b)`.
    shakedown: f64,
    seconds: f64,
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b) / b
}

fn max_of(v: &[f64]) -> f64 {
    alea_latin::fretting::max_with_index(v).map_or(f64::NAN, |m| m.0)
}

/// The critical distance of the point method.
fn critical_distance(cf: &Closed) -> f64 {
    0.1 * cf.b
}

/// Range of the FE `sigma_xx` of the block at `x` over the last cycle (`+Q*` minus `-Q*`).
fn sxx_range(solver: &LatinSolver, res: &[alea_latin::RunResult], x: [f64; 3]) -> f64 {
    let last = res.len() - 1;
    let model = solver.model(0);
    let loc = alea_fem::PointLocator::new(&model.mesh)
        .unwrap()
        .locate_nearest(x, 1e-9)
        .unwrap();
    let s = |k: usize| {
        alea_fem::post::stress_at(model, loc.cell, &res[k].displacements[0], loc.xi).unwrap()[0]
    };
    s(last) - s(last - 1)
}

/// The errors of mesh `(n, m)` over the last of `cycles` cycles (the shakedown measure needs
/// two; 0 with one).
fn cycle_errors(n: usize, m: usize, cycles: usize) -> Measured {
    let t0 = std::time::Instant::now();
    let cf = Closed::new();
    let (solver, h) = build(n, m);
    let mut steps = vec![step(0.0), step(LOAD)];
    for _ in 0..cycles {
        steps.extend([step(-LOAD), step(LOAD)]);
    }
    let e = steps.len() - 1;
    let res = solver.run_steps(&steps).unwrap();
    assert_eq!(res.len(), steps.len());
    for (k, r) in res.iter().enumerate() {
        assert_eq!(r.status, RunStatus::Converged, "step {}", k + 1);
    }
    let it = |k: usize| &res[k].interfaces[0];
    let first = slip_cycle(Some(it(1)), &[it(2), it(3)]).unwrap();
    let sc = slip_cycle(Some(it(e - 2)), &[it(e - 1), it(e)]).unwrap();
    let dmax = cf.delta(cf.b);
    let shakedown = first
        .slip_amplitude
        .iter()
        .zip(&sc.slip_amplitude)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / dmax;
    let xs: Vec<f64> = sc.x.iter().map(|x| x[0]).collect();
    let stick = rel(
        0.5 * sc.stick_zone(&solver.model(0).mesh, &it(e).nodes[0]),
        cf.c,
    );
    let stick_steps = [e - 1, e].map(|k| {
        let one = slip_cycle(Some(it(k - 1)), &[it(k)]).unwrap();
        rel(
            0.5 * one.stick_zone(&solver.model(0).mesh, &it(k).nodes[0]),
            cf.c,
        )
    });
    // Slip amplitude at the nodes inside the closed-form contact (a node the coarse model
    // closes beyond b has no closed-form slip to compare with).
    let slip = xs
        .iter()
        .zip(&sc.slip_amplitude)
        .filter(|(x, _)| x.abs() <= cf.b)
        .map(|(&x, &d)| (d - cf.delta(x)).abs())
        .fold(0.0, f64::max)
        / dmax;
    let (dh, imax) = alea_latin::fretting::max_with_index(&sc.slip_amplitude).unwrap();
    let slip_max = rel(dh, cf.delta(xs[imax]));
    let nq = 20000;
    let wq: f64 = (0..nq)
        .map(|j| {
            let x = -cf.b + (j as f64 + 0.5) * 2.0 * cf.b / nq as f64;
            4.0 * MU * cf.p(x) * cf.delta(x) * 2.0 * cf.b / nq as f64
        })
        .sum();
    let work = rel(sc.total_work(), wq);
    let f1c = xs
        .iter()
        .map(|&x| MU * cf.p(x) * cf.delta(x))
        .fold(0.0, f64::max);
    let f1 = rel(max_of(&sc.f1()), f1c);
    let l = critical_distance(&cf);
    let cyc = [&res[e - 1], &res[e]];
    let point = stress_cycle(&solver, 0, 0, &cyc, Regularisation::Point(l), PLANES).unwrap();
    let line = stress_cycle(&solver, 0, 0, &cyc, Regularisation::Line(l), PLANES).unwrap();
    let surf = stress_cycle(&solver, 0, 0, &cyc, Regularisation::Surface, PLANES).unwrap();
    let normals = plane_normals(2, PLANES);
    let range_c = |z: f64| {
        if z == 0.0 {
            cf.sxx_surface(-cf.b) - cf.sxx_surface(cf.b)
        } else {
            cf.stress_below(-cf.b, z, 1.0)[0] - cf.stress_below(-cf.b, z, -1.0)[0]
        }
    };
    let range_l = rel(sxx_range(&solver, &res, [-cf.b, -l, 0.0]), range_c(l));
    let range_surface = rel(sxx_range(&solver, &res, [-cf.b, 0.0, 0.0]), range_c(0.0));
    let swt_c = xs
        .iter()
        .map(|&x| {
            let states = [cf.stress_below(x, l, -1.0), cf.stress_below(x, l, 1.0)];
            swt_of_stresses(&states, E, NU, &normals).0
        })
        .fold(0.0, f64::max);
    let swt_l = rel(max_of(&point.swt), swt_c);
    let swt_line_c = xs
        .iter()
        .map(|&x| {
            let states = [cf.stress_line(x, l, -1.0), cf.stress_line(x, l, 1.0)];
            swt_of_stresses(&states, E, NU, &normals).0
        })
        .fold(0.0, f64::max);
    // Fatemi-Socie with k = 0.5, sigma_y = 1000 MPa, from the FE stresses at depth L and from
    // the closed-form ones at the same points.
    let (k_fs, sy) = (0.5, 1000.0);
    let fs_fe: Vec<f64> = point
        .fs_shear
        .iter()
        .zip(&point.fs_normal)
        .map(|(&g, &sn)| fatemi_socie(g, sn, k_fs, sy))
        .collect();
    let fs_c = xs
        .iter()
        .map(|&x| {
            let states = [cf.stress_below(x, l, -1.0), cf.stress_below(x, l, 1.0)];
            let (g, sn, _) = fs_of_stresses(&states, E, NU, &normals, 2);
            fatemi_socie(g, sn, k_fs, sy)
        })
        .fold(0.0, f64::max);
    let fs_l = rel(max_of(&fs_fe), fs_c);
    let f2c = xs
        .iter()
        .map(|&x| cf.sigma_t_surface(x) * MU * cf.p(x) * cf.delta(x))
        .fold(0.0, f64::max);
    let f2_surface = rel(max_of(&sc.f2(&surf.sigma_t)), f2c);
    let m = Measured {
        h_over_b: h / cf.b,
        stick,
        stick_steps,
        slip,
        slip_max,
        work,
        f1,
        range_l,
        swt_l,
        range_surface,
        f2_surface,
        swt_line: rel(max_of(&line.swt), swt_line_c),
        fs_l,
        shakedown,
        seconds: t0.elapsed().as_secs_f64(),
    };
    eprintln!(
        "h = b/{:.1}: iterations {:?}; {m:?}",
        cf.b / h,
        res.iter().map(|r| r.iterations).collect::<Vec<_>>(),
    );
    m
}

/// Slope of `log |e|` against `log h` between the first and the last mesh.
fn rate(ms: &[Measured], e: impl Fn(&Measured) -> f64) -> f64 {
    let (a, b) = (&ms[0], &ms[ms.len() - 1]);
    (e(a).abs() / e(b).abs()).ln() / (a.h_over_b / b.h_over_b).ln()
}

/// The closed-form comparisons on three meshes, `h = b/11.8, b/23.6, b/47.2` (`l = 970 b`):
/// - stick zone of the cycle, and of each of its steps, within 1 % at the finest mesh, the
///   cycle's error decreasing at a rate >= 1;
/// - slip amplitude within 2 % at every node (relative to its peak `delta(b)`) on the two finer
///   meshes, and the largest amplitude within 2 % of the closed form at its node;
/// - frictional work per cycle and the largest F1 within 2 %, converging at a rate >= 1.5;
/// - the range of `sigma_xx` over the cycle below the trailing edge at the critical distance
///   `L = b/10` within 2 % at the finest mesh, and the largest SWT (point method) within 3 %,
///   both errors smaller at the finest mesh than at the coarsest; the largest SWT of the line
///   method (stresses averaged over `[0, L]`) within 3 %, its error decreasing mesh by mesh;
/// - shakedown: the second cycle repeats the first (Mindlin-Deresiewicz: the loop is closed
///   after the first loading), on the two coarser meshes (the finest runs one cycle).
///
/// Measured: see BENCHMARKS.md ("Fretting quantities against closed forms").
#[test]
fn fretting_cycle_against_closed_forms() {
    let ms: Vec<Measured> = [(25, 23, 2), (50, 45, 2), (100, 90, 1)]
        .iter()
        .map(|&(n, m, cycles)| cycle_errors(n, m, cycles))
        .collect();
    let fine = &ms[2];
    assert!(fine.stick.abs() < 0.01, "stick zone {:+.4}", fine.stick);
    for s in fine.stick_steps {
        assert!(s.abs() < 0.01, "stick zone of a step {s:+.4}");
    }
    let r = rate(&ms, |m| m.stick);
    assert!(r >= 1.0, "stick-zone rate {r:.2}");
    for m in &ms[1..] {
        assert!(m.slip < 0.02, "slip amplitude {:.4}", m.slip);
        assert!(m.slip_max.abs() < 0.02, "largest slip amplitude");
    }
    for (name, e) in [
        (
            "work",
            &(|m: &Measured| m.work) as &dyn Fn(&Measured) -> f64,
        ),
        ("F1", &|m: &Measured| m.f1),
    ] {
        assert!(e(fine).abs() < 0.02, "{name} {:+.4}", e(fine));
        let r = rate(&ms, e);
        assert!(r >= 1.5, "{name} rate {r:.2}");
    }
    assert!(fine.range_l.abs() < 0.02, "sigma_xx range at L");
    assert!(
        fine.range_l.abs() < ms[0].range_l.abs(),
        "sigma_xx range converges"
    );
    assert!(fine.swt_l.abs() < 0.03, "SWT at L");
    assert!(fine.swt_l.abs() < ms[0].swt_l.abs(), "SWT converges");
    assert!(
        fine.fs_l.abs() < 0.03,
        "Fatemi-Socie at L {:+.4}",
        fine.fs_l
    );
    assert!(fine.fs_l.abs() < ms[0].fs_l.abs(), "Fatemi-Socie converges");
    assert!(fine.swt_line.abs() < 0.03, "SWT, line method");
    assert!(
        fine.swt_line.abs() < ms[1].swt_line.abs() && ms[1].swt_line.abs() < ms[0].swt_line.abs(),
        "SWT, line method, converges"
    );
    for m in &ms[..2] {
        assert!(m.shakedown < 1e-4, "the second cycle repeats the first");
    }
    for m in &ms {
        eprintln!(
            "h/b = {:.4}: stick {:+.3} % (steps {:+.3} %, {:+.3} %), slip {:.3} % (max {:+.3} %), work {:+.3} %, F1 {:+.3} %, \
             range(sxx) at L {:+.3} %, SWT at L {:+.3} %; surface: range(sxx) {:+.3} %, F2 {:+.3} %; \
             SWT line {:+.3} %; FS at L {:+.3} %; {:.1}s",
            m.h_over_b,
            100.0 * m.stick,
            100.0 * m.stick_steps[0],
            100.0 * m.stick_steps[1],
            100.0 * m.slip,
            100.0 * m.slip_max,
            100.0 * m.work,
            100.0 * m.f1,
            100.0 * m.range_l,
            100.0 * m.swt_l,
            100.0 * m.range_surface,
            100.0 * m.f2_surface,
            100.0 * m.swt_line,
            100.0 * m.fs_l,
            m.seconds
        );
    }
}
