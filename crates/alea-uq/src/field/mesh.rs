//! The mesh a random field lives on: nodes and P1 cells (segments along a line, triangles, or
//! tetrahedra), with the quadrature rules used by the Galerkin Karhunen-Loeve discretisation.
//!
//! A P1 function is `u(x) = sum_i u_i phi_i(x)` with `phi_i` the hat function of node `i`. On a
//! simplex of `k` nodes and measure `|e|` the local mass matrix is `|e| (1 + delta_ab) / (k (k +
//! 1))`: `|e| / 6 [[2, 1], [1, 2]]` for a segment, `|e| / 12 (1 + delta_ab)` for a triangle,
//! `|e| / 20 (1 + delta_ab)` for a tetrahedron. The Galerkin KL needs only `L2` products, so
//! the hat functions need not be continuous across cells (a hexahedron split into tetrahedra
//! without matching its neighbours' diagonals is still a valid space).

use crate::error::{Result, UqError};

/// The cells of a [`FieldMesh`].
#[derive(Debug, Clone, PartialEq)]
pub enum FieldCells {
    /// Two-node segments (a curve in the plane or in space, e.g. a contact line).
    Segments(Vec<[usize; 2]>),
    /// Three-node triangles (a surface in the plane or in space).
    Triangles(Vec<[usize; 3]>),
    /// Four-node tetrahedra (a volume).
    Tetrahedra(Vec<[usize; 4]>),
}

/// Nodes and P1 cells; every node belongs to at least one cell and no cell is degenerate.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldMesh {
    nodes: Vec<[f64; 3]>,
    cells: FieldCells,
    measures: Vec<f64>,
}

/// Points of a quadrature rule on the reference cell: barycentric coordinates and weights
/// summing to 1 (the weight of a point in a physical cell is `w |e|`).
pub(crate) struct CellRule {
    /// Barycentric coordinates (4 entries; the unused ones 0 for segments and triangles).
    pub(crate) bary: Vec<[f64; 4]>,
    /// Weights (sum 1).
    pub(crate) weights: Vec<f64>,
}

/// Gauss-Legendre nodes and weights on [0, 1] with `n` = 1 to 5 points.
pub(crate) fn gauss_legendre01(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (x, w): (&[f64], &[f64]) = match n {
        1 => (&[0.0], &[2.0]),
        2 => (
            &[-0.577_350_269_189_625_8, 0.577_350_269_189_625_8],
            &[1.0, 1.0],
        ),
        3 => (
            &[-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4],
            &[5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0],
        ),
        4 => (
            &[
                -0.861_136_311_594_052_6,
                -0.339_981_043_584_856_3,
                0.339_981_043_584_856_3,
                0.861_136_311_594_052_6,
            ],
            &[
                0.347_854_845_137_453_9,
                0.652_145_154_862_546_1,
                0.652_145_154_862_546_1,
                0.347_854_845_137_453_9,
            ],
        ),
        _ => (
            &[
                -0.906_179_845_938_664,
                -0.538_469_310_105_683,
                0.0,
                0.538_469_310_105_683,
                0.906_179_845_938_664,
            ],
            &[
                0.236_926_885_056_189_1,
                0.478_628_670_499_366_5,
                0.568_888_888_888_888_9,
                0.478_628_670_499_366_5,
                0.236_926_885_056_189_1,
            ],
        ),
    };
    (
        x.iter().map(|t| 0.5 * (t + 1.0)).collect(),
        w.iter().map(|t| 0.5 * t).collect(),
    )
}

impl CellRule {
    /// Gauss-Legendre rule with `n` points on a segment (exact to degree `2n - 1`).
    pub(crate) fn segment(n: usize) -> Self {
        let (x, w) = gauss_legendre01(n);
        Self {
            bary: x.iter().map(|&t| [1.0 - t, t, 0.0, 0.0]).collect(),
            weights: w,
        }
    }

    /// Strang-Fix / Dunavant 6-point rule on a triangle (exact to degree 4).
    pub(crate) fn triangle() -> Self {
        let (a1, b1, w1) = (
            0.445_948_490_915_965,
            0.108_103_018_168_070,
            0.223_381_589_678_011,
        );
        let (a2, b2, w2) = (
            0.091_576_213_509_771,
            0.816_847_572_980_459,
            0.109_951_743_655_322,
        );
        Self {
            bary: vec![
                [a1, a1, b1, 0.0],
                [a1, b1, a1, 0.0],
                [b1, a1, a1, 0.0],
                [a2, a2, b2, 0.0],
                [a2, b2, a2, 0.0],
                [b2, a2, a2, 0.0],
            ],
            weights: vec![w1, w1, w1, w2, w2, w2],
        }
    }

    /// The same rule applied on the 4 sub-triangles of the midpoint subdivision (used on the
    /// diagonal cell pairs, where the kernel has a kink).
    pub(crate) fn triangle_subdivided() -> Self {
        let (v0, v1, v2) = (
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        );
        let (m01, m12, m20) = (mid(v0, v1), mid(v1, v2), mid(v2, v0));
        let subs = [
            vec![v0, m01, m20],
            vec![m01, v1, m12],
            vec![m20, m12, v2],
            vec![m12, m20, m01],
        ];
        Self::triangle().on_subcells(&subs)
    }

    /// Keast's 4-point rule on a tetrahedron (exact to degree 2; points at `a = (5 + 3
    /// sqrt 5) / 20` and `b = (5 - sqrt 5) / 20`, weights 1/4).
    pub(crate) fn tetrahedron() -> Self {
        let a = 0.585_410_196_624_968_5;
        let b = 0.138_196_601_125_010_5;
        Self {
            bary: vec![[a, b, b, b], [b, a, b, b], [b, b, a, b], [b, b, b, a]],
            weights: vec![0.25; 4],
        }
    }

    /// The 4-point rule on the 8 sub-tetrahedra of the midpoint subdivision (the 4 corner
    /// tetrahedra and the inner octahedron split along the diagonal `m02 - m13`; all 8 of
    /// volume 1/8): the diagonal cell pairs.
    pub(crate) fn tetrahedron_subdivided() -> Self {
        let v: Vec<[f64; 4]> = (0..4)
            .map(|i| {
                let mut e = [0.0; 4];
                e[i] = 1.0;
                e
            })
            .collect();
        let m = |i: usize, j: usize| mid(v[i], v[j]);
        let subs = [
            vec![v[0], m(0, 1), m(0, 2), m(0, 3)],
            vec![m(0, 1), v[1], m(1, 2), m(1, 3)],
            vec![m(0, 2), m(1, 2), v[2], m(2, 3)],
            vec![m(0, 3), m(1, 3), m(2, 3), v[3]],
            vec![m(0, 2), m(1, 3), m(0, 1), m(1, 2)],
            vec![m(0, 2), m(1, 3), m(1, 2), m(2, 3)],
            vec![m(0, 2), m(1, 3), m(2, 3), m(0, 3)],
            vec![m(0, 2), m(1, 3), m(0, 3), m(0, 1)],
        ];
        Self::tetrahedron().on_subcells(&subs)
    }

    /// This rule applied on each of `subs` (sub-simplices of equal measure given by the
    /// barycentric coordinates of their corners in the parent).
    fn on_subcells(&self, subs: &[Vec<[f64; 4]>]) -> Self {
        let share = 1.0 / subs.len() as f64;
        let mut bary = Vec::new();
        let mut weights = Vec::new();
        for s in subs {
            for (b, w) in self.bary.iter().zip(&self.weights) {
                let mut p = [0.0; 4];
                for (k, corner) in s.iter().enumerate() {
                    for d in 0..4 {
                        p[d] += b[k] * corner[d];
                    }
                }
                bary.push(p);
                weights.push(share * w);
            }
        }
        Self { bary, weights }
    }
}

/// Midpoint of two barycentric points.
fn mid(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        0.5 * (a[0] + b[0]),
        0.5 * (a[1] + b[1]),
        0.5 * (a[2] + b[2]),
        0.5 * (a[3] + b[3]),
    ]
}

impl FieldMesh {
    /// Builds a mesh, checking node indices, degenerate cells and nodes in no cell.
    pub fn new(nodes: Vec<[f64; 3]>, cells: FieldCells) -> Result<Self> {
        let bad = |message: String| UqError::Invalid {
            what: "field mesh",
            message,
        };
        if nodes.is_empty() {
            return Err(bad("no nodes".into()));
        }
        if let Some((i, x)) = nodes
            .iter()
            .enumerate()
            .find(|(_, x)| x.iter().any(|c| !c.is_finite()))
        {
            return Err(bad(format!("node {i} has a non-finite coordinate {x:?}")));
        }
        let n = nodes.len();
        let conn: Vec<&[usize]> = match &cells {
            FieldCells::Segments(s) => s.iter().map(|c| &c[..]).collect(),
            FieldCells::Triangles(t) => t.iter().map(|c| &c[..]).collect(),
            FieldCells::Tetrahedra(t) => t.iter().map(|c| &c[..]).collect(),
        };
        if conn.is_empty() {
            return Err(bad("no cells".into()));
        }
        let mut used = vec![false; n];
        let mut measures = Vec::with_capacity(conn.len());
        for (c, cell) in conn.iter().enumerate() {
            for &i in cell.iter() {
                if i >= n {
                    return Err(bad(format!(
                        "cell {c} refers to node {i}, the mesh has {n}"
                    )));
                }
                used[i] = true;
            }
            let measure = cell_measure(&nodes, cell);
            let scale = cell
                .iter()
                .flat_map(|&i| nodes[i].iter())
                .fold(0.0f64, |a, c| a.max(c.abs()))
                .max(1.0);
            if !(measure > 1e-13 * scale.powi(cell.len() as i32 - 1)) {
                return Err(bad(format!("cell {c} is degenerate (measure {measure:e})")));
            }
            measures.push(measure);
        }
        if let Some(i) = used.iter().position(|u| !u) {
            return Err(bad(format!("node {i} belongs to no cell")));
        }
        Ok(Self {
            nodes,
            cells,
            measures,
        })
    }

    /// A uniform mesh of the segment `[a, b]` of the x axis with `cells` cells.
    pub fn interval(a: f64, b: f64, cells: usize) -> Result<Self> {
        if !(a.is_finite() && b.is_finite() && b > a) {
            return Err(crate::error::invalid(
                "interval mesh",
                "b - a",
                "finite and > 0",
                b - a,
            ));
        }
        if cells == 0 {
            return Err(crate::error::invalid("interval mesh", "cells", ">= 1", 0.0));
        }
        let nodes = (0..=cells)
            .map(|i| [a + (b - a) * i as f64 / cells as f64, 0.0, 0.0])
            .collect();
        let segs = (0..cells).map(|i| [i, i + 1]).collect();
        Self::new(nodes, FieldCells::Segments(segs))
    }

    /// Node coordinates.
    pub fn nodes(&self) -> &[[f64; 3]] {
        &self.nodes
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// The cells.
    pub fn cells(&self) -> &FieldCells {
        &self.cells
    }

    /// Number of cells.
    pub fn num_cells(&self) -> usize {
        self.measures.len()
    }

    /// Node indices of cell `c`.
    pub fn cell(&self, c: usize) -> &[usize] {
        match &self.cells {
            FieldCells::Segments(s) => &s[c],
            FieldCells::Triangles(t) => &t[c],
            FieldCells::Tetrahedra(t) => &t[c],
        }
    }

    /// Length (segments), area (triangles) or volume (tetrahedra) of cell `c`.
    pub fn cell_measure(&self, c: usize) -> f64 {
        self.measures[c]
    }

    /// Total length, area or volume of the mesh.
    pub fn measure(&self) -> f64 {
        self.measures.iter().sum()
    }

    /// The P1 mass matrix `M_ij = int phi_i phi_j` as a dense row-major `n x n` array.
    pub fn mass_matrix(&self) -> Vec<f64> {
        let n = self.num_nodes();
        let mut m = vec![0.0; n * n];
        for c in 0..self.num_cells() {
            let cell = self.cell(c);
            let k = cell.len() as f64;
            let off = 1.0 / (k * (k + 1.0));
            let diag = 2.0 * off;
            for (a, &i) in cell.iter().enumerate() {
                for (b, &j) in cell.iter().enumerate() {
                    m[i * n + j] += self.measures[c] * if a == b { diag } else { off };
                }
            }
        }
        m
    }

    /// `int u v` for two P1 functions given by their node values.
    pub fn l2_product(&self, u: &[f64], v: &[f64]) -> f64 {
        let mut s = 0.0;
        for c in 0..self.num_cells() {
            let cell = self.cell(c);
            let k = cell.len() as f64;
            // int_e phi_a phi_b = |e| (1 + delta_ab) / ((k) (k + 1)) for a simplex with k nodes.
            let mut sum_u = 0.0;
            let mut sum_v = 0.0;
            let mut diag = 0.0;
            for &i in cell {
                sum_u += u[i];
                sum_v += v[i];
                diag += u[i] * v[i];
            }
            s += self.measures[c] * (sum_u * sum_v + diag) / (k * (k + 1.0));
        }
        s
    }
}

fn cell_measure(nodes: &[[f64; 3]], cell: &[usize]) -> f64 {
    let d = |a: usize, b: usize| -> [f64; 3] {
        let (p, q) = (nodes[cell[a]], nodes[cell[b]]);
        [q[0] - p[0], q[1] - p[1], q[2] - p[2]]
    };
    if cell.len() == 2 {
        let e = d(0, 1);
        (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
    } else if cell.len() == 4 {
        let (e1, e2, e3) = (d(0, 1), d(0, 2), d(0, 3));
        let det = e1[0] * (e2[1] * e3[2] - e2[2] * e3[1]) - e1[1] * (e2[0] * e3[2] - e2[2] * e3[0])
            + e1[2] * (e2[0] * e3[1] - e2[1] * e3[0]);
        det.abs() / 6.0
    } else {
        let (e1, e2) = (d(0, 1), d(0, 2));
        let c = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
    }
}
