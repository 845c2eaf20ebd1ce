//! The user's description of a block: corners, edge [`Curve`]s, cell counts, gradings, groups.

use std::sync::Arc;

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
