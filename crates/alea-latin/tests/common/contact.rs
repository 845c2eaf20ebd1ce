//! Meshes for the line-contact tests (Hertz, Cattaneo-Mindlin): two bodies whose contact faces
//! are meshed **flat** on `y = 0` with node-for-node coincident nodes over `|x| <= a`, strongly
//! refined there and graded outward; the curvature of the cylinder goes into the initial gap
//! field `g0(x)` of the interface (see the test headers).
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

use alea_mesh::generate::{Block, multiblock};
use alea_mesh::{CellType, Mesh};

/// Mesh layout.
#[derive(Clone, Copy, Debug)]
pub struct Layout {
    /// Half-length of the refined contact strip (and depth of the fine block).
    pub a: f64,
    /// Half-size of each body.
    pub l: f64,
    /// Cells across the fine block (so `h = a / n`).
    pub n: usize,
    /// Cells of the graded blocks from the fine block to the far boundary.
    pub m: usize,
    /// Whole width (`true`) or half model `x >= 0` (`false`).
    pub full: bool,
}

impl Layout {
    /// Fine cell size.
    pub fn h(&self) -> f64 {
        self.a / self.n as f64
    }

    /// Grading (last / first cell) of the outer blocks so that their first cell is `h`.
    fn grading(&self) -> f64 {
        let (len, h, m) = (self.l - self.a, self.h(), self.m as i32);
        assert!(
            len > m as f64 * h,
            "outer blocks would be finer than the contact strip"
        );
        // sum_{i<m} h r^i = len  <=>  h (r^m - 1) / (r - 1) = len; bisection on r > 1.
        let (mut lo, mut hi) = (1.0 + 1e-12, 2.0f64);
        while h * (hi.powi(m) - 1.0) / (hi - 1.0) < len {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let r = 0.5 * (lo + hi);
            if h * (r.powi(m) - 1.0) / (r - 1.0) < len {
                lo = r;
            } else {
                hi = r;
            }
        }
        (0.5 * (lo + hi)).powi(m - 1)
    }

    /// Blocks of the lower body, `x >= 0`.
    fn lower_half(&self) -> Vec<Block> {
        let (a, l, n, m) = (self.a, self.l, self.n, self.m);
        let g = self.grading();
        let mut inner = Block::new([[0.0, -a], [a, -a], [a, 0.0], [0.0, 0.0]], [n, n])
            .group("body")
            .edge_group(2, "contact");
        let right = Block::new([[a, -a], [l, -l], [l, 0.0], [a, 0.0]], [m, n])
            .grading(g, 1.0)
            .group("body")
            .edge_group(1, "far_side")
            .edge_group(2, "free");
        let mut below = Block::new([[0.0, -l], [l, -l], [a, -a], [0.0, -a]], [n, m])
            .grading(1.0, 1.0 / g)
            .group("body")
            .edge_group(0, "far");
        if !self.full {
            inner = inner.edge_group(3, "sym");
            below = below.edge_group(3, "sym");
        }
        vec![inner, right, below]
    }

    fn blocks(&self, upper: bool) -> Vec<Block> {
        let mut blocks = self.lower_half();
        if self.full {
            let mirrored: Vec<Block> = blocks.iter().map(|b| map(b, |p| [-p[0], p[1]])).collect();
            blocks.extend(mirrored);
        }
        if upper {
            blocks = blocks.iter().map(|b| map(b, |p| [p[0], -p[1]])).collect();
        }
        blocks
    }

    /// The lower body (`y <= 0`, the flat "block").
    pub fn lower(&self) -> Mesh {
        multiblock(&self.blocks(false), CellType::Quad4).unwrap()
    }

    /// The upper body (`y >= 0`, the "cylinder" with its curvature in `g0`).
    pub fn upper(&self) -> Mesh {
        multiblock(&self.blocks(true), CellType::Quad4).unwrap()
    }

    /// The upper body with its true curved bottom: the cylinder of radius `r` touching `y = 0`
    /// at `x = 0`. The nodes of [`Layout::upper`] are moved up by
    /// `g(x) (1 - y / l)`, `g(x) = r - sqrt(r^2 - x^2)`, so the bottom nodes lie on the circle,
    /// the top `y = l` stays flat and the cells shear by at most `g'(l) = l / sqrt(r^2 - l^2)`.
    pub fn upper_curved(&self, r: f64) -> Mesh {
        assert!(self.l < r, "the body must be narrower than the cylinder");
        let mut m = self.upper();
        for x in m.coords.iter_mut() {
            let g = r - (r * r - x[0] * x[0]).sqrt();
            x[1] += g * (1.0 - x[1] / self.l);
        }
        m
    }
}

/// A straight-edged block with its corners mapped by a reflection (the generator re-orders
/// clockwise blocks, gradings and edge groups included).
fn map(b: &Block, f: impl Fn([f64; 2]) -> [f64; 2]) -> Block {
    let mut out = b.clone();
    out.corners = b.corners.map(f);
    out
}

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
