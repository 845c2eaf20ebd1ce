//! The small-sliding check: how far each interface slid against what its pairing can represent.
//!
//! Every pairing (node to node or mortar, [`crate::interface`]) is built once, in the initial
//! configuration: point `p` of side 1 stays paired with the side-2 material that faced it
//! before the load. That represents the contact while the tangential slip `s_p = |[W_hat]_t|`
//! at every point stays small against the local mesh size `h_p` (2D: the point's interface
//! weight over the thickness, i.e. its share of the side's length; 3D: the square root of its
//! weight, an area). Beyond about half a cell the point faces other side-2 material than it
//! is paired with, and the answer (contact zone, gap, pressure) may be wrong: a block slid over
//! several elements keeps contact over its original face.
//!
//! [`slide_checks`] returns, per contact interface, the largest ratio `s_p / h_p` and its point;
//! [`SMALL_SLIDING_LIMIT`] (0.5) is where a solve warns. The slip is counted from the
//! configuration the pairing was found in: for a solver re-paired in a deformed configuration
//! `X + c` (module [`crate::large_sliding`]) it is `s_p = |[W_hat]_t - [Pi c]_t|`, with
//! `[Pi c] = Pi_2 c_2 - Pi_1 c_1` the jump of that configuration at the point, so the check
//! says whether the slide since the last pairing still fits it.
//!
//! What the check can and cannot tell apart: above the limit it says that the pairing no
//! longer pairs the points that face each other, not that the answer is wrong (flat faces that
//! stay in contact over the whole slide, such as two long flat faces, give the right answer
//! all the same); below the limit the pairing is the right one to within half a cell, which on
//! curved faces still leaves an error of order `s_p` times the change of the normal over the
//! slide. With small sliding (the default) the pairing is not updated during the solve;
//! interfaces with `Sliding::Large` are re-paired by [`crate::large_sliding`].

use alea_fem::Analysis;
use alea_mesh::vec3::dot;

use crate::{LatinSolver, RunResult};

/// Slip over the local mesh size beyond which a solve warns.
pub const SMALL_SLIDING_LIMIT: f64 = 0.5;

/// The largest slip of one contact interface against its local mesh size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlideCheck {
    /// Interface index.
    pub interface: usize,
    /// Point where `slip / h` is largest.
    pub point: usize,
    /// Its tangential slip `|[W_hat]_t|` (length).
    pub slip: f64,
    /// Its local mesh size `h_p` (length; not less than the median point size).
    pub h: f64,
    /// `slip / h`.
    pub ratio: f64,
}

impl SlideCheck {
    /// True if the slide exceeds [`SMALL_SLIDING_LIMIT`].
    pub fn beyond_small_sliding(&self) -> bool {
        self.ratio > SMALL_SLIDING_LIMIT
    }
}

/// The slip since the pairing and the local mesh size `(s_p, h_p)` of every point of interface
/// result `i` of a run of `solver` (module doc); non-finite or zero-size points are skipped.
pub fn point_slides(solver: &LatinSolver, res: &RunResult, i: usize) -> Vec<(usize, f64, f64)> {
    let it = &res.interfaces[i];
    let model = solver.model(it.subs[0]);
    let size = |w: f64| match model.analysis {
        Analysis::Solid => w.sqrt(),
        other => w / other.thickness(),
    };
    let dim = model.mesh.dim;
    let origin: [Vec<[f64; 3]>; 2] = match solver.pairing_configuration() {
        Some(c) => [0, 1].map(|s| it.pairing.sides[s].interpolate(&c[it.subs[s]], dim)),
        None => [
            vec![[0.0; 3]; it.points.len()],
            vec![[0.0; 3]; it.points.len()],
        ],
    };
    let mut out = Vec::with_capacity(it.points.len());
    for p in 0..it.points.len() {
        let n = it.points[p].normal;
        let (a, b) = (it.what[0][p], it.what[1][p]);
        let (ca, cb) = (origin[0][p], origin[1][p]);
        let j = [
            b[0] - a[0] - (cb[0] - ca[0]),
            b[1] - a[1] - (cb[1] - ca[1]),
            b[2] - a[2] - (cb[2] - ca[2]),
        ];
        let jn = dot(&j, &n);
        let t = [j[0] - jn * n[0], j[1] - jn * n[1], j[2] - jn * n[2]];
        let slip = dot(&t, &t).sqrt();
        let h = size(it.weights[p]);
        if h > 0.0 && slip.is_finite() {
            out.push((p, slip, h));
        }
    }
    out
}

/// The largest `slip / h` of every interface whose law uses a gap (contact), for a run of
/// `solver`, with `h` a point's size but not less than the median point size of the interface
/// (a mortar point at the edge of the covered zone may carry a sliver of weight).
pub fn slide_checks(solver: &LatinSolver, res: &RunResult) -> Vec<SlideCheck> {
    let mut out = Vec::new();
    for (i, it) in res.interfaces.iter().enumerate() {
        if it.law == "perfect" {
            continue;
        }
        let slides = point_slides(solver, res, i);
        let mut sizes: Vec<f64> = slides.iter().map(|s| s.2).collect();
        sizes.sort_by(f64::total_cmp);
        let median = sizes.get(sizes.len() / 2).copied().unwrap_or(0.0);
        let mut best: Option<SlideCheck> = None;
        for (point, slip, h) in slides {
            let h = h.max(median);
            let ratio = slip / h;
            if best.is_none_or(|b| ratio > b.ratio) {
                best = Some(SlideCheck {
                    interface: i,
                    point,
                    slip,
                    h,
                    ratio,
                });
            }
        }
        out.extend(best);
    }
    out
}
