//! Multi-block mapped quadrilateral meshes (2D) with transfinite (Coons) interpolation.
//!
//! A [`Block`] is a curvilinear quadrilateral given by its four corners `c0 c1 c2 c3` and four
//! edges `e_k` from corner `k` to corner `k + 1 (mod 4)`, each a [`Curve`] parametrised by
//! `u in [0, 1]` from its start corner to its end corner. Block coordinates `(s, t) in [0, 1]^2`
//! run along `e0` (s, from `c0` to `c1`) and along `e1` (t, from `c1` to `c2`):
//!
//! ```text
//!        c3 <------ e2 ------- c2          bottom B(s) = e0(s)       right R(t) = e1(t)
//!        |                      ^          top    T(s) = e2(1 - s)   left  L(t) = e3(1 - t)
//!    e3  |     t ^              |  e1
//!        v       |--> s         |
//!        c0 ------- e0 ------> c1
//! ```
//! The point of block coordinates `(s, t)` is the Coons patch (bilinearly blended transfinite
//! interpolation)
//!
//! ```text
//! X(s,t) = (1-t) B(s) + t T(s) + (1-s) L(t) + s R(t)
//!        - [ (1-s)(1-t) c0 + s(1-t) c1 + s t c2 + (1-s) t c3 ]
//! ```
//! which reproduces the four edges exactly. Each block is divided into `n[0] x n[1]` cells along
//! s and t; the node parameters follow a geometric progression whose ratio of last to first cell
//! size is `grading[d]` (1 = uniform; in s the first cell touches `e3`, in t it touches `e0`).
//! Quadratic cells (`Quad8`, `Tri6`) get their mid-side nodes at the parametric mid-points mapped
//! by X, so they lie on curved edges. Triangles split each quad `(a, b, c, d)` along the diagonal
//! a-c into `(a, b, c)` and `(a, c, d)`.
//!
//! Blocks whose corners are given clockwise are re-ordered (counter-clockwise cells are produced
//! in all cases); a cell with a non-positive Jacobian after that means the mapping folds, and is an
//! error. Corners closer than `1e-9` times the size of the model are merged. Two blocks share an
//! edge when its two end corners coincide and its curves' mid-points coincide; the shared edge must
//! then have the same number of cells in both blocks and the same node positions (gradings
//! mirrored if the edge is traversed in opposite directions), and the two blocks must lie on
//! opposite sides of it (no overlap, at most two blocks per edge), otherwise [`multiblock`]
//! returns [`MeshError::Invalid`]. Nodes are merged along shared edges, so the mesh is conforming;
//! distinct nodes at the same position after that (an edge met twice with different curves or
//! parametrisations) are reported as an error. Parts that must stay un-merged along an interface
//! (contact) are generated separately and joined with [`Mesh::append`].
//!
//! Groups: a block's cells join the cell group `Block::cell_group` (if set); an edge tagged with a
//! name gives a facet group of that name (the edge's cell facets, outward from the block) and a
//! node group with the same name holding the edge's nodes.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::Arc;

use crate::{CellType, Facet, Mesh, MeshError};

/// A parametric closure for [`Curve::Param`]: `u in [0, 1] -> [x, y]`.
pub type CurveFn = Arc<dyn Fn(f64) -> [f64; 2] + Send + Sync>;

/// The shape of a block edge between its start corner `a` and end corner `b`.
#[derive(Clone)]
pub enum Curve {
    /// Straight segment, uniform in u.
    Line,
    /// Circular arc of centre `center` and radius `radius` (both ends must lie on it, relative
    /// tolerance 1e-7) going counter-clockwise (`ccw`) or clockwise from `a` to `b`, uniform in
    /// angle. Any sweep in (0, 2 pi) can be described.
    Arc {
        /// Centre of the circle.
        center: [f64; 2],
        /// Radius.
        radius: f64,
        /// Counter-clockwise from `a` to `b` (else clockwise).
        ccw: bool,
    },
    /// Circular arc from `a` through this point to `b`, uniform in angle.
    ArcThrough([f64; 2]),
    /// Polyline `a, p_1, ..., p_m, b` through the given interior points, uniform in arc length.
    Polyline(Vec<[f64; 2]>),
    /// Centripetal Catmull-Rom spline through `a`, the given interior points and `b` (end
    /// tangents by reflection), parametrised by its centripetal knots (sqrt of chord lengths).
    Spline(Vec<[f64; 2]>),
    /// Any parametric curve with `f(0) = a` and `f(1) = b` (checked, relative tolerance 1e-6).
    Param(CurveFn),
}

impl std::fmt::Debug for Curve {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Curve::Line => write!(f, "Line"),
            Curve::Arc {
                center,
                radius,
                ccw,
            } => write!(
                f,
                "Arc {{ center: {center:?}, radius: {radius}, ccw: {ccw} }}"
            ),
            Curve::ArcThrough(p) => write!(f, "ArcThrough({p:?})"),
            Curve::Polyline(p) => write!(f, "Polyline({p:?})"),
            Curve::Spline(p) => write!(f, "Spline({p:?})"),
            Curve::Param(_) => write!(f, "Param(<closure>)"),
        }
    }
}

/// One curvilinear quadrilateral block. See the module documentation for the conventions.
#[derive(Clone, Debug)]
pub struct Block {
    /// Corners `c0 c1 c2 c3` (counter-clockwise preferred; clockwise is re-ordered).
    pub corners: [[f64; 2]; 4],
    /// Edges `e_k` from corner `k` to corner `k + 1 (mod 4)`.
    pub edges: [Curve; 4],
    /// Number of cells along s (edges 0 and 2) and along t (edges 1 and 3).
    pub n: [usize; 2],
    /// Ratio of the last to the first cell size along s (from e3 to e1) and t (from e0 to e2).
    pub grading: [f64; 2],
    /// Cell group the block's cells join.
    pub cell_group: Option<String>,
    /// Facet (and node) group of each edge.
    pub edge_groups: [Option<String>; 4],
}

impl Block {
    /// A block with straight edges, uniform spacing and no groups.
    pub fn new(corners: [[f64; 2]; 4], n: [usize; 2]) -> Self {
        Block {
            corners,
            edges: [Curve::Line, Curve::Line, Curve::Line, Curve::Line],
            n,
            grading: [1.0, 1.0],
            cell_group: None,
            edge_groups: [None, None, None, None],
        }
    }

    /// Sets the curve of edge `k` (0..4).
    ///
    /// # Panics
    /// If `k >= 4`.
    pub fn edge(mut self, k: usize, curve: Curve) -> Self {
        self.edges[k] = curve;
        self
    }

    /// Sets the gradings along s and t (ratio last / first cell size).
    pub fn grading(mut self, s: f64, t: f64) -> Self {
        self.grading = [s, t];
        self
    }

    /// Sets the cell group.
    pub fn group(mut self, name: &str) -> Self {
        self.cell_group = Some(name.to_string());
        self
    }

    /// Tags edge `k` (0..4) with a facet/node group name.
    ///
    /// # Panics
    /// If `k >= 4`.
    pub fn edge_group(mut self, k: usize, name: &str) -> Self {
        self.edge_groups[k] = Some(name.to_string());
        self
    }
}

/// A curve ready for evaluation between known ends.
enum Prepared {
    Line([f64; 2], [f64; 2]),
    Arc {
        c: [f64; 2],
        r: f64,
        th0: f64,
        sweep: f64,
    },
    Poly {
        pts: Vec<[f64; 2]>,
        cum: Vec<f64>,
    },
    Spline {
        pts: Vec<[f64; 2]>,
        knots: Vec<f64>,
    },
    Param(CurveFn),
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
}

fn lerp(a: [f64; 2], b: [f64; 2], u: f64) -> [f64; 2] {
    [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])]
}

fn finite2(p: [f64; 2]) -> bool {
    p[0].is_finite() && p[1].is_finite()
}

impl Prepared {
    fn new(curve: &Curve, a: [f64; 2], b: [f64; 2], what: &str) -> Result<Self, MeshError> {
        let bad = |m: String| MeshError::Invalid(format!("{what}: {m}"));
        Ok(match curve {
            Curve::Line => Prepared::Line(a, b),
            Curve::Arc {
                center,
                radius,
                ccw,
            } => {
                if !(radius.is_finite() && *radius > 0.0 && finite2(*center)) {
                    return Err(bad(format!(
                        "arc needs a finite centre and a positive radius, got {center:?}, {radius}"
                    )));
                }
                for (p, name) in [(a, "start"), (b, "end")] {
                    let d = dist(p, *center);
                    if (d - radius).abs() > 1e-7 * radius {
                        return Err(bad(format!(
                            "arc {name} corner {p:?} is at distance {d} from the centre {center:?}, not at the radius {radius}"
                        )));
                    }
                }
                let th0 = (a[1] - center[1]).atan2(a[0] - center[0]);
                let th1 = (b[1] - center[1]).atan2(b[0] - center[0]);
                let d = (th1 - th0).rem_euclid(2.0 * PI);
                if d < 1e-12 || 2.0 * PI - d < 1e-12 {
                    return Err(bad("arc ends coincide".into()));
                }
                let sweep = if *ccw { d } else { d - 2.0 * PI };
                Prepared::Arc {
                    c: *center,
                    r: *radius,
                    th0,
                    sweep,
                }
            }
            Curve::ArcThrough(m) => {
                // Circumcentre of a, m, b.
                let (ax, ay) = (a[0], a[1]);
                let (bx, by) = (m[0], m[1]);
                let (cx, cy) = (b[0], b[1]);
                let d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by));
                let scale = dist(a, *m).max(dist(*m, b)).max(dist(a, b));
                if !finite2(*m) || d.abs() <= 1e-12 * scale * scale {
                    return Err(bad(format!(
                        "arc through {m:?} is degenerate (the three points are collinear or coincide)"
                    )));
                }
                let sa = ax * ax + ay * ay;
                let sb = bx * bx + by * by;
                let sc = cx * cx + cy * cy;
                let ux = (sa * (by - cy) + sb * (cy - ay) + sc * (ay - by)) / d;
                let uy = (sa * (cx - bx) + sb * (ax - cx) + sc * (bx - ax)) / d;
                let c = [ux, uy];
                let r = dist(a, c);
                let ang = |p: [f64; 2]| (p[1] - uy).atan2(p[0] - ux);
                let th0 = ang(a);
                let dab = (ang(b) - th0).rem_euclid(2.0 * PI);
                let dam = (ang(*m) - th0).rem_euclid(2.0 * PI);
                let sweep = if dam < dab { dab } else { dab - 2.0 * PI };
                Prepared::Arc { c, r, th0, sweep }
            }
            Curve::Polyline(inner) => {
                let mut pts = vec![a];
                pts.extend(inner.iter().copied());
                pts.push(b);
                if pts.iter().any(|&p| !finite2(p)) {
                    return Err(bad("polyline point is not finite".into()));
                }
                let mut cum = vec![0.0];
                for w in pts.windows(2) {
                    let l = dist(w[0], w[1]);
                    if l <= 0.0 {
                        return Err(bad("polyline has two coincident consecutive points".into()));
                    }
                    cum.push(cum.last().copied().unwrap_or(0.0) + l);
                }
                Prepared::Poly { pts, cum }
            }
            Curve::Spline(inner) => {
                let mut pts = vec![a];
                pts.extend(inner.iter().copied());
                pts.push(b);
                if pts.iter().any(|&p| !finite2(p)) {
                    return Err(bad("spline point is not finite".into()));
                }
                let n = pts.len();
                let first = lerp(pts[1], pts[0], 2.0);
                let last = lerp(pts[n - 2], pts[n - 1], 2.0);
                let mut all = vec![first];
                all.extend(pts);
                all.push(last);
                let mut knots = vec![0.0];
                for w in all.windows(2) {
                    let l = dist(w[0], w[1]).sqrt();
                    if l <= 0.0 {
                        return Err(bad("spline has two coincident consecutive points".into()));
                    }
                    knots.push(knots.last().copied().unwrap_or(0.0) + l);
                }
                Prepared::Spline { pts: all, knots }
            }
            Curve::Param(f) => {
                let scale = dist(a, b).max(1e-300);
                for (u, p, name) in [(0.0, a, "start"), (1.0, b, "end")] {
                    let q = f(u);
                    if !finite2(q) || dist(p, q) > 1e-6 * scale {
                        return Err(bad(format!(
                            "parametric curve gives {q:?} at u = {u}, but the {name} corner is {p:?}"
                        )));
                    }
                }
                Prepared::Param(f.clone())
            }
        })
    }

    fn eval(&self, u: f64) -> [f64; 2] {
        match self {
            Prepared::Line(a, b) => lerp(*a, *b, u),
            Prepared::Arc { c, r, th0, sweep } => {
                let th = th0 + u * sweep;
                [c[0] + r * th.cos(), c[1] + r * th.sin()]
            }
            Prepared::Poly { pts, cum } => {
                let total = cum[cum.len() - 1];
                let l = (u * total).clamp(0.0, total);
                let i = cum.partition_point(|&c| c <= l).clamp(1, cum.len() - 1) - 1;
                let w = (l - cum[i]) / (cum[i + 1] - cum[i]);
                lerp(pts[i], pts[i + 1], w)
            }
            Prepared::Spline { pts, knots } => {
                // Real segments are between pts[1] .. pts[n-2] (the ends are ghosts).
                let n = pts.len();
                let (k1, kn) = (knots[1], knots[n - 2]);
                let t = (k1 + u * (kn - k1)).clamp(k1, kn);
                let i = (knots.partition_point(|&k| k <= t).clamp(2, n - 2)) - 1; // segment i..i+1
                let (t0, t1, t2, t3) = (knots[i - 1], knots[i], knots[i + 1], knots[i + 2]);
                let (p0, p1, p2, p3) = (pts[i - 1], pts[i], pts[i + 1], pts[i + 2]);
                // Barry-Goldman pyramidal evaluation.
                let mix =
                    |p: [f64; 2], q: [f64; 2], ta: f64, tb: f64| lerp(p, q, (t - ta) / (tb - ta));
                let a1 = mix(p0, p1, t0, t1);
                let a2 = mix(p1, p2, t1, t2);
                let a3 = mix(p2, p3, t2, t3);
                let b1 = mix(a1, a2, t0, t2);
                let b2 = mix(a2, a3, t1, t3);
                mix(b1, b2, t1, t2)
            }
            Prepared::Param(f) => f(u),
        }
    }
}

/// Node parameters in [0, 1] of `n` cells with ratio `g` of last to first cell size.
pub(crate) fn distribution(n: usize, g: f64) -> Vec<f64> {
    if n == 1 || (g - 1.0).abs() < 1e-14 {
        return (0..=n).map(|i| i as f64 / n as f64).collect();
    }
    let r = g.powf(1.0 / (n as f64 - 1.0));
    let mut x = vec![0.0];
    let mut h = 1.0;
    for _ in 0..n {
        x.push(x.last().copied().unwrap_or(0.0) + h);
        h *= r;
    }
    let total = x[n];
    x.iter_mut().for_each(|v| *v /= total);
    x[n] = 1.0;
    x
}

/// Half-step lattice: node parameters at even indices, parametric mid-points at odd ones.
fn half_lattice(n: usize, g: f64) -> Vec<f64> {
    let d = distribution(n, g);
    let mut h = Vec::with_capacity(2 * n + 1);
    for i in 0..n {
        h.push(d[i]);
        h.push(0.5 * (d[i] + d[i + 1]));
    }
    h.push(1.0);
    h
}

/// A block after validation, counter-clockwise.
struct Ready {
    index: usize,
    corners: [[f64; 2]; 4],
    edges: [(Prepared, bool); 4], // (curve, evaluated reversed)
    n: [usize; 2],
    grading: [f64; 2],
    cell_group: Option<String>,
    edge_groups: [Option<String>; 4],
    /// The user's number of each edge (they differ when a clockwise block was re-ordered).
    user_edge: [usize; 4],
}

impl Ready {
    fn edge_at(&self, k: usize, u: f64) -> [f64; 2] {
        let (c, rev) = &self.edges[k];
        c.eval(if *rev { 1.0 - u } else { u })
    }

    /// The Coons patch X(s, t).
    fn coons(&self, s: f64, t: f64) -> [f64; 2] {
        let b = self.edge_at(0, s);
        let r = self.edge_at(1, t);
        let tp = self.edge_at(2, 1.0 - s);
        let l = self.edge_at(3, 1.0 - t);
        let c = &self.corners;
        let mut x = [0.0; 2];
        for d in 0..2 {
            x[d] = (1.0 - t) * b[d] + t * tp[d] + (1.0 - s) * l[d] + s * r[d]
                - ((1.0 - s) * (1.0 - t) * c[0][d]
                    + s * (1.0 - t) * c[1][d]
                    + s * t * c[2][d]
                    + (1.0 - s) * t * c[3][d]);
        }
        x
    }

    /// Signed area of the block's boundary polygon (edges sampled).
    fn signed_area(&self) -> f64 {
        let mut pts = Vec::new();
        for k in 0..4 {
            for i in 0..32 {
                pts.push(self.edge_at(k, i as f64 / 32.0));
            }
        }
        let m = pts.len();
        (0..m)
            .map(|i| {
                let (p, q) = (pts[i], pts[(i + 1) % m]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            * 0.5
    }
}

fn prepare(index: usize, b: &Block) -> Result<Ready, MeshError> {
    let what = |m: &str| format!("block {index}: {m}");
    if b.n[0] == 0 || b.n[1] == 0 {
        return Err(MeshError::Invalid(what(&format!(
            "needs at least one cell per direction, got {:?}",
            b.n
        ))));
    }
    if b.grading.iter().any(|g| !(g.is_finite() && *g > 0.0)) {
        return Err(MeshError::Invalid(what(&format!(
            "gradings must be positive and finite, got {:?}",
            b.grading
        ))));
    }
    if b.corners.iter().any(|&p| !finite2(p)) {
        return Err(MeshError::Invalid(what(&format!(
            "corners must be finite, got {:?}",
            b.corners
        ))));
    }
    let c = b.corners;
    let mut edges = Vec::new();
    for k in 0..4 {
        let e = Prepared::new(
            &b.edges[k],
            c[k],
            c[(k + 1) % 4],
            &what(&format!("edge {k}")),
        )?;
        edges.push((e, false));
    }
    let mut edges_it = edges.into_iter();
    let mut next = || edges_it.next().expect("four edges");
    let mut r = Ready {
        index,
        corners: c,
        edges: [next(), next(), next(), next()],
        n: b.n,
        grading: b.grading,
        cell_group: b.cell_group.clone(),
        edge_groups: b.edge_groups.clone(),
        user_edge: [0, 1, 2, 3],
    };
    let area = r.signed_area();
    let scale = (0..4)
        .map(|k| dist(c[k], c[(k + 1) % 4]))
        .fold(0.0, f64::max);
    if area.is_nan() || area.abs() <= 1e-12 * scale * scale {
        return Err(MeshError::Invalid(what("has (nearly) zero area")));
    }
    if area < 0.0 {
        // Re-order clockwise corners c0 c1 c2 c3 as c0 c3 c2 c1: new edges are the old ones
        // reversed, s and t swap.
        let [e0, e1, e2, e3] = r.edges;
        let rev = |(p, f): (Prepared, bool)| (p, !f);
        r.edges = [rev(e3), rev(e2), rev(e1), rev(e0)];
        r.corners = [c[0], c[3], c[2], c[1]];
        r.n = [b.n[1], b.n[0]];
        r.grading = [b.grading[1], b.grading[0]];
        let g = &b.edge_groups;
        r.edge_groups = [g[3].clone(), g[2].clone(), g[1].clone(), g[0].clone()];
        r.user_edge = [3, 2, 1, 0];
    }
    Ok(r)
}

struct EdgeEntry {
    key: (usize, usize),
    mid: [f64; 2],
    nodes: Vec<usize>, // canonical direction (from the smaller vertex id), 2n+1 entries
    block: usize,
    side: usize,
    forward: bool, // direction of the first block's traversal
    users: usize,
}

/// Meshes a set of blocks (see the module documentation); `kind` is `Quad4`, `Quad8`, `Tri3` or
/// `Tri6`.
///
/// ```
/// use alea_mesh::CellType;
/// use alea_mesh::generate::{Block, Curve, multiblock};
///
/// // A 2 x 1 base and, on top of it, a block with an arched top edge (from (2, 2) through
/// // (1, 2.5) to (0, 2)) whose cells shrink toward the arch. They share the edge y = 1.
/// let base = Block::new([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], [4, 2])
///     .group("base")
///     .edge_group(0, "bottom");
/// let arch = Block::new([[0.0, 1.0], [2.0, 1.0], [2.0, 2.0], [0.0, 2.0]], [4, 3])
///     .edge(2, Curve::ArcThrough([1.0, 2.5]))
///     .grading(1.0, 0.5)
///     .group("arch")
///     .edge_group(2, "crown");
/// let mesh = multiblock(&[base, arch], CellType::Quad8)?;
/// assert_eq!(mesh.num_cells(), 8 + 12);
/// assert_eq!(mesh.facet_group("crown")?.len(), 4);
/// assert_eq!(mesh.group_nodes("bottom")?.len(), 9); // 5 corners + 4 mid-side nodes
/// # Ok::<(), alea_mesh::MeshError>(())
/// ```
///
/// # Errors
/// [`MeshError::Invalid`] for bad block input (zero counts, non-positive gradings, arcs whose
/// ends are not on the circle, degenerate blocks), shared edges with different counts or node
/// positions, unmerged coincident nodes, and folded mappings (non-positive Jacobian).
pub fn multiblock(blocks: &[Block], kind: CellType) -> Result<Mesh, MeshError> {
    if !matches!(
        kind,
        CellType::Quad4 | CellType::Quad8 | CellType::Tri3 | CellType::Tri6
    ) {
        return Err(MeshError::Invalid(format!(
            "the multi-block generator makes 2D cells (QUAD4, QUAD8, TRI3, TRI6), not {kind}"
        )));
    }
    if blocks.is_empty() {
        return Err(MeshError::Invalid("no blocks given".into()));
    }
    let ready: Vec<Ready> = blocks
        .iter()
        .enumerate()
        .map(|(i, b)| prepare(i, b))
        .collect::<Result<_, _>>()?;
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for b in &ready {
        for p in &b.corners {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    let tol = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]);

    let mut coords: Vec<[f64; 2]> = Vec::new();
    let mut vertices: Vec<usize> = Vec::new(); // node ids of distinct corners
    let mut edges: Vec<EdgeEntry> = Vec::new();
    let mut cells: Vec<(usize, Vec<usize>)> = Vec::new(); // (block, nodes)
    let mut facets: Vec<(String, Facet)> = Vec::new();
    let quadratic = kind.order() == 2;

    for b in &ready {
        let bi = b.index;
        let [ns, nt] = b.n;
        let hs = half_lattice(ns, b.grading[0]);
        let ht = half_lattice(nt, b.grading[1]);
        let (ms, mt) = (2 * ns + 1, 2 * nt + 1);
        let pos = |i: usize, j: usize| -> [f64; 2] {
            match (i, j) {
                (0, 0) => b.corners[0],
                (i, 0) if i == ms - 1 => b.corners[1],
                (i, j) if i == ms - 1 && j == mt - 1 => b.corners[2],
                (0, j) if j == mt - 1 => b.corners[3],
                _ => b.coons(hs[i], ht[j]),
            }
        };
        let mut id = vec![usize::MAX; ms * mt];
        let at = |i: usize, j: usize| i + ms * j;
        // Corners.
        let corner_lattice = [(0, 0), (ms - 1, 0), (ms - 1, mt - 1), (0, mt - 1)];
        let mut vid = [0usize; 4];
        for k in 0..4 {
            let p = b.corners[k];
            let v = match vertices.iter().position(|&n| dist(coords[n], p) <= tol) {
                Some(v) => v,
                None => {
                    coords.push(p);
                    vertices.push(coords.len() - 1);
                    vertices.len() - 1
                }
            };
            vid[k] = v;
            let (i, j) = corner_lattice[k];
            id[at(i, j)] = vertices[v];
        }
        // Edges: lattice points from corner k to corner k+1.
        let edge_lattice = |k: usize| -> Vec<(usize, usize)> {
            match k {
                0 => (0..ms).map(|i| (i, 0)).collect(),
                1 => (0..mt).map(|j| (ms - 1, j)).collect(),
                2 => (0..ms).rev().map(|i| (i, mt - 1)).collect(),
                _ => (0..mt).rev().map(|j| (0, j)).collect(),
            }
        };
        let mut edge_nodes: [Vec<usize>; 4] = Default::default();
        for k in 0..4 {
            let (va, vb) = (vid[k], vid[(k + 1) % 4]);
            let ku = b.user_edge[k];
            if va == vb {
                return Err(MeshError::Invalid(format!(
                    "block {bi}: edge {ku} has coincident end corners (collapsed edges are not supported)"
                )));
            }
            let lat = edge_lattice(k);
            let key = (va.min(vb), va.max(vb));
            let forward = va < vb;
            let mid = b.edge_at(k, 0.5);
            let existing = edges.iter_mut().find(|e| {
                e.key == key
                    && dist(e.mid, mid)
                        <= tol.max(1e-7 * dist(b.corners[k], b.corners[(k + 1) % 4]))
            });
            let nodes: Vec<usize> = if let Some(e) = existing {
                if e.users >= 2 || e.forward == forward {
                    return Err(MeshError::Invalid(format!(
                        "block {bi} edge {ku} coincides with block {} edge {} but the blocks overlap (an edge can be shared by two blocks lying on opposite sides of it)",
                        e.block, e.side
                    )));
                }
                e.users += 1;
                if e.nodes.len() != lat.len() {
                    return Err(MeshError::Invalid(format!(
                        "block {bi} edge {ku} is shared with block {} edge {}, but has {} cells there instead of {}",
                        e.block,
                        e.side,
                        (lat.len() - 1) / 2,
                        (e.nodes.len() - 1) / 2
                    )));
                }
                let mut n = e.nodes.clone();
                if !forward {
                    n.reverse();
                }
                for (q, &(i, j)) in lat.iter().enumerate() {
                    let p = pos(i, j);
                    if dist(p, coords[n[q]]) > 1e-6 * dist(b.corners[k], b.corners[(k + 1) % 4]) {
                        return Err(MeshError::Invalid(format!(
                            "block {bi} edge {ku} is shared with block {} edge {}, but its node {q} is at {p:?} instead of {:?} (different grading or curve parametrisation)",
                            e.block, e.side, coords[n[q]]
                        )));
                    }
                }
                n
            } else {
                let mut n = Vec::with_capacity(lat.len());
                for (q, &(i, j)) in lat.iter().enumerate() {
                    if q == 0 || q == lat.len() - 1 {
                        n.push(id[at(i, j)]);
                    } else {
                        coords.push(pos(i, j));
                        n.push(coords.len() - 1);
                    }
                }
                let mut canon = n.clone();
                if !forward {
                    canon.reverse();
                }
                edges.push(EdgeEntry {
                    key,
                    mid,
                    nodes: canon,
                    block: bi,
                    side: ku,
                    forward,
                    users: 1,
                });
                n
            };
            for (q, &(i, j)) in lat.iter().enumerate() {
                id[at(i, j)] = nodes[q];
            }
            edge_nodes[k] = nodes;
        }
        // Interior lattice points.
        for j in 1..mt - 1 {
            for i in 1..ms - 1 {
                let wanted = match kind {
                    CellType::Quad4 | CellType::Tri3 => i % 2 == 0 && j % 2 == 0,
                    CellType::Quad8 => i % 2 == 0 || j % 2 == 0,
                    _ => true,
                };
                if wanted {
                    coords.push(pos(i, j));
                    id[at(i, j)] = coords.len() - 1;
                }
            }
        }
        // Cells.
        for j in 0..nt {
            for i in 0..ns {
                let (i0, j0) = (2 * i, 2 * j);
                let n = |a: usize, c: usize| id[at(i0 + a, j0 + c)];
                let (a, bb, c, d) = (n(0, 0), n(2, 0), n(2, 2), n(0, 2));
                match kind {
                    CellType::Quad4 => cells.push((bi, vec![a, bb, c, d])),
                    CellType::Quad8 => {
                        cells.push((bi, vec![a, bb, c, d, n(1, 0), n(2, 1), n(1, 2), n(0, 1)]))
                    }
                    CellType::Tri3 => {
                        cells.push((bi, vec![a, bb, c]));
                        cells.push((bi, vec![a, c, d]));
                    }
                    _ => {
                        cells.push((bi, vec![a, bb, c, n(1, 0), n(2, 1), n(1, 1)]));
                        cells.push((bi, vec![a, c, d, n(1, 1), n(1, 2), n(0, 1)]));
                    }
                }
            }
        }
        // Facets of tagged edges, in the (outward) direction of the block edge.
        for (group, en) in b.edge_groups.iter().zip(&edge_nodes) {
            if let Some(name) = group {
                for q in (0..en.len() - 1).step_by(2) {
                    let f = if quadratic {
                        Facet {
                            kind: CellType::Line3,
                            nodes: vec![en[q], en[q + 2], en[q + 1]],
                        }
                    } else {
                        Facet {
                            kind: CellType::Line2,
                            nodes: vec![en[q], en[q + 2]],
                        }
                    };
                    facets.push((name.clone(), f));
                }
            }
        }
    }

    // Compact: drop lattice nodes no cell uses.
    let mut new_id = vec![usize::MAX; coords.len()];
    let mut mesh = Mesh::new(2);
    for (_, nodes) in &cells {
        for &n in nodes {
            if new_id[n] == usize::MAX {
                new_id[n] = mesh.add_node([coords[n][0], coords[n][1], 0.0]);
            }
        }
    }
    check_duplicates(&mesh, tol)?;
    // Groups are collected first: `Mesh::add_*_to_group` sorts the whole group on each call.
    let mut cell_groups: HashMap<&str, Vec<usize>> = HashMap::new();
    for (bi, nodes) in &cells {
        let n: Vec<usize> = nodes.iter().map(|&i| new_id[i]).collect();
        let c = mesh.add_cell(kind, &n);
        let jmin = mesh.cell_min_jacobian(c);
        if jmin.is_nan() || jmin <= 0.0 {
            return Err(MeshError::Invalid(format!(
                "block {bi}: cell with corners {:?} has a non-positive Jacobian ({jmin:e}): the block mapping folds (check the corners' order and the edge curves)",
                n[..kind.num_corners()]
                    .iter()
                    .map(|&i| mesh.coords[i])
                    .collect::<Vec<_>>()
            )));
        }
        if let Some(g) = &ready[*bi].cell_group {
            cell_groups.entry(g.as_str()).or_default().push(c);
        }
    }
    for (g, cells) in cell_groups {
        mesh.add_cells_to_group(g, cells);
    }
    let mut facet_groups: HashMap<String, Vec<Facet>> = HashMap::new();
    for (name, f) in facets {
        let f = Facet {
            kind: f.kind,
            nodes: f.nodes.iter().map(|&i| new_id[i]).collect(),
        };
        facet_groups.entry(name).or_default().push(f);
    }
    for (name, facets) in facet_groups {
        let nodes: Vec<usize> = facets.iter().flat_map(|f| f.nodes.clone()).collect();
        mesh.add_nodes_to_group(&name, nodes);
        mesh.add_facets_to_group(&name, facets);
    }
    Ok(mesh)
}

/// Error if two distinct nodes are closer than `tol` (hash grid of cell size `2 tol`: a close
/// pair lies in the same or a neighbouring cell).
fn check_duplicates(mesh: &Mesh, tol: f64) -> Result<(), MeshError> {
    let h = 2.0 * tol.max(f64::MIN_POSITIVE);
    let cell = |x: [f64; 3]| [(x[0] / h).floor() as i64, (x[1] / h).floor() as i64];
    let mut grid: HashMap<[i64; 2], Vec<usize>> = HashMap::with_capacity(mesh.num_nodes());
    for (i, &x) in mesh.coords.iter().enumerate() {
        let [cx, cy] = cell(x);
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(others) = grid.get(&[cx + dx, cy + dy]) {
                    for &j in others {
                        let y = mesh.coords[j];
                        if (x[0] - y[0]).abs() <= tol && (x[1] - y[1]).abs() <= tol {
                            return Err(MeshError::Invalid(format!(
                                "two distinct nodes at {x:?}: blocks meet along an edge without sharing it (different curves, counts or corners)"
                            )));
                        }
                    }
                }
            }
        }
        grid.entry([cx, cy]).or_default().push(i);
    }
    Ok(())
}
