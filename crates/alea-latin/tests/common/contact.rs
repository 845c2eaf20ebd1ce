//! Meshes for the line-contact tests (Hertz, Cattaneo-Mindlin): the layout of
//! [`alea_latin::samples::ContactLayout`] (shared with the benchmarks), and small fitting
//! helpers. Two bodies whose contact faces are meshed **flat** on `y = 0` with node-for-node
//! coincident nodes over `|x| <= a`, strongly refined there and graded outward; the curvature
//! of the cylinder goes into the initial gap field `g0(x)` of the interface (see the test
//! headers), or into the mesh itself (`upper_curved`, mortar pairing).
//!
//! ```text
//!   y = +l  +----------------------+   upper body ("cylinder") = mirror image in y = 0
//!           |   R'  .      .   R'  |
//!   y = 0   +------+==contact==+---+   <- fine uniform square blocks [-a, a] x [-a, a]
//!           |   R   '  I   '   R   |      (h = a / n), graded blocks R, B around them
//!           |     .     B     .    |
//!   y = -l  +----------------------+   lower body ("block"): group "far" on y = -l
//!          -l        0              l
//! ```
//! Half model (`full = false`): only `x >= 0`, with facet group `"sym"` on `x = 0`.
//! Groups of each body: cell group `"body"`; facet/node groups `"contact"` (`|x| <= a` on
//! `y = 0`), `"free"` (the rest of `y = 0`), `"far"` (`y = -l` below, `y = +l` above),
//! `"far_side"` (`|x| = l`) and `"sym"` (half model).

#[allow(unused_imports)]
pub use alea_latin::samples::ContactLayout as Layout;

/// Sorted `(x, value)` samples along an interface.
pub fn sorted_by_x(xs: &[f64], v: &[f64]) -> Vec<(f64, f64)> {
    let mut s: Vec<(f64, f64)> = xs.iter().copied().zip(v.iter().copied()).collect();
    s.sort_by(|a, b| a.0.total_cmp(&b.0));
    s
}

/// Least-squares fit of `y = c0 + c1 t`; returns `(c0, c1)`.
pub fn linear_fit(t: &[f64], y: &[f64]) -> (f64, f64) {
    let n = t.len() as f64;
    let (st, sy) = (t.iter().sum::<f64>(), y.iter().sum::<f64>());
    let stt: f64 = t.iter().map(|v| v * v).sum();
    let sty: f64 = t.iter().zip(y).map(|(a, b)| a * b).sum();
    let c1 = (n * sty - st * sy) / (n * stt - st * st);
    ((sy - c1 * st) / n, c1)
}

/// Elastic constants and loading of [`cylinder_on_block`].
pub struct CylinderLoad {
    /// Young's modulus and Poisson's ratio of both bodies.
    pub young: f64,
    pub poisson: f64,
    /// Normal load per unit length `P'`, friction coefficient, cylinder radius.
    pub p: f64,
    pub mu: f64,
    pub radius: f64,
}

/// The cylinder (upper body) on the block clamped at its far face, on `lay`: load case 0 of
/// the cylinder presses it by `P'` (uniform traction on its far face), load case 1 pushes it
/// along `x` by `mu P'` through the contact centre (the traction's linear part balances the
/// moment); a Coulomb interface whose initial gap is the cylinder's curvature
/// `R - sqrt(R^2 - x^2)`. LATIN to `1e-8`, at most 20 000 iterations.
pub fn cylinder_on_block(lay: &Layout, c: &CylinderLoad) -> alea_latin::LatinSolver {
    use alea_fem::{Constraints, Loads};
    let (l, p, q, r) = (lay.l, c.p, c.mu * c.p, c.radius);
    let block = {
        let m = super::model(lay.lower().unwrap(), c.young, c.poisson);
        let mut cs = Constraints::new();
        cs.clamp(&m.mesh, "far").unwrap();
        super::sub("block", m, cs)
    };
    let cylinder = {
        let s = super::sub(
            "cylinder",
            super::model(lay.upper().unwrap(), c.young, c.poisson),
            Constraints::new(),
        );
        let s = super::with_load(s, |m, ld: &mut Loads| {
            ld.traction(m, "far", move |_, _| [0.0, -p / (2.0 * l), 0.0])
                .unwrap();
        });
        super::with_load(s, |m, ld: &mut Loads| {
            let slope = 3.0 * q / (2.0 * l * l);
            ld.traction(m, "far", move |x, _| [q / (2.0 * l), slope * x[0], 0.0])
                .unwrap();
        })
    };
    let mut iface = alea_latin::InterfaceSpec::coulomb("contact", 0, "contact", 1, "contact", c.mu);
    iface.gap = std::sync::Arc::new(move |x: [f64; 3]| r - (r * r - x[0] * x[0]).sqrt());
    alea_latin::LatinSolver::new(
        alea_latin::Assembly {
            subs: vec![block, cylinder],
            interfaces: vec![iface],
        },
        alea_latin::LatinOptions {
            tolerance: 1e-8,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap()
}
