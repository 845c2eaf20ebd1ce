//! The mesh a random field lives on: nodes and P1 cells (segments along a line, or triangles),
//! with the quadrature rules used by the Galerkin Karhunen-Loeve discretisation.
//!
//! A P1 function is `u(x) = sum_i u_i phi_i(x)` with `phi_i` the hat function of node `i`. On a
//! cell of measure `|e|` the local mass matrix is `|e| / 6 [[2, 1], [1, 2]]` for a segment and
//! `|e| / 12 (1 + delta_ab)` for a triangle.

use crate::error::{Result, UqError};

/// The cells of a [`FieldMesh`].
#[derive(Debug, Clone, PartialEq)]
pub enum FieldCells {
    /// Two-node segments (a curve in the plane or in space, e.g. a contact line).
    Segments(Vec<[usize; 2]>),
    /// Three-node triangles (a surface in the plane or in space).
    Triangles(Vec<[usize; 3]>),
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
    /// Barycentric coordinates (3 entries; the third is 0 for segments).
    pub(crate) bary: Vec<[f64; 3]>,
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
            bary: x.iter().map(|&t| [1.0 - t, t, 0.0]).collect(),
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
                [a1, a1, b1],
                [a1, b1, a1],
                [b1, a1, a1],
                [a2, a2, b2],
                [a2, b2, a2],
                [b2, a2, a2],
            ],
            weights: vec![w1, w1, w1, w2, w2, w2],
        }
    }

    /// The same rule applied on the 4 sub-triangles of the midpoint subdivision (used on the
    /// diagonal cell pairs, where the kernel has a kink).
    pub(crate) fn triangle_subdivided() -> Self {
        let base = Self::triangle();
        // Sub-triangles in barycentric coordinates of the parent.
        let m = |a: [f64; 3], b: [f64; 3]| {
            [
                0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * (a[2] + b[2]),
            ]
        };
        let (v0, v1, v2) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        let (m01, m12, m20) = (m(v0, v1), m(v1, v2), m(v2, v0));
        let subs = [
            [v0, m01, m20],
            [m01, v1, m12],
            [m20, m12, v2],
            [m12, m20, m01],
        ];
        let mut bary = Vec::new();
        let mut weights = Vec::new();
        for s in &subs {
            for (b, w) in base.bary.iter().zip(&base.weights) {
                let mut p = [0.0; 3];
                for (k, corner) in s.iter().enumerate() {
                    for d in 0..3 {
                        p[d] += b[k] * corner[d];
                    }
                }
                bary.push(p);
                weights.push(0.25 * w);
            }
        }
        Self { bary, weights }
    }
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
        }
    }

    /// Length (segments) or area (triangles) of cell `c`.
    pub fn cell_measure(&self, c: usize) -> f64 {
        self.measures[c]
    }

    /// Total length or area of the mesh.
    pub fn measure(&self) -> f64 {
        self.measures.iter().sum()
    }

    /// The P1 mass matrix `M_ij = int phi_i phi_j` as a dense row-major `n x n` array.
    pub fn mass_matrix(&self) -> Vec<f64> {
        let n = self.num_nodes();
        let mut m = vec![0.0; n * n];
        for c in 0..self.num_cells() {
            let cell = self.cell(c);
            let k = cell.len();
            let (diag, off) = if k == 2 {
                (2.0 / 6.0, 1.0 / 6.0)
            } else {
                (2.0 / 12.0, 1.0 / 12.0)
            };
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
