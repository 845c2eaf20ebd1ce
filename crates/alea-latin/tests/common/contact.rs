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
