//! Locating physical points in a 2D mesh: the cell that holds a point and the point's
//! reference coordinates in that cell, to evaluate a finite-element field of one mesh at points
//! of another (e.g. a coarse solution at the quadrature points of a finer reference mesh, the
//! efficiency index of the thesis's 3.3.3).
//!
//! **Candidates.** A uniform grid of buckets covers the mesh's bounding box (about one cell per
//! bucket, cells of similar size assumed); each bucket lists, in increasing order, the cells
//! whose bounding box overlaps it. A point is tested against the cells of its bucket only.
//!
//! **Inverse isoparametric map.** In a candidate cell, Newton's method solves
//! `x(xi) = sum_i N_i(xi) x_i = x` for the reference coordinates `xi` (shape functions of
//! [`crate::reference`]), from the reference centre, `xi <- xi - J^-T (x(xi) - x)` with
//! `J_kl = dx_l / dxi_k`: exact in one step on affine cells (Tri3, parallelogram Quad4, straight
//! Tri6 / Quad8), a few steps on distorted or curved ones. The point is inside when `xi` lies in
//! the reference cell (`[-1, 1]^2`, or `r, s >= 0, r + s <= 1`) within `1e-9`; the first such
//! cell in increasing id wins (a point on a shared edge goes to the lower id, deterministically).
//!
//! [`PointLocator::locate_nearest`] also accepts points slightly outside the mesh (a polygonal
//! boundary of one mesh against a curved one of another): `xi` is clamped onto the reference
//! cell and the closest such image within the given distance is returned.
//!
//! Written here because the task is small and specific (a few dozen lines over the crate's own
//! shape functions); spatial-index crates would add a dependency for the bucket grid alone.

use alea_mesh::{CellType, Mesh};

use crate::FemError;
use crate::reference::{MAX_NODES, shape};

/// A located point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Location {
    /// Cell index.
    pub cell: usize,
    /// Reference coordinates in the cell (third one 0).
    pub xi: [f64; 3],
    /// Distance from the point to `x(xi)` (0 up to round-off when the point is inside).
    pub distance: f64,
}

/// Point location in a 2D mesh (module doc).
#[derive(Clone, Debug)]
pub struct PointLocator<'a> {
    mesh: &'a Mesh,
    lo: [f64; 2],
    size: [f64; 2],
    n: [usize; 2],
    /// Bucket `b`'s cells are `cells[start[b]..start[b + 1]]`.
    start: Vec<usize>,
    cells: Vec<u32>,
}

/// Tolerance on reference coordinates for "inside".
const INSIDE: f64 = 1e-9;

fn is_quad(kind: CellType) -> bool {
    matches!(kind, CellType::Quad4 | CellType::Quad8)
}

/// `xi` clamped onto the reference cell of `kind`.
fn clamp(kind: CellType, xi: [f64; 2]) -> [f64; 2] {
    if is_quad(kind) {
        [xi[0].clamp(-1.0, 1.0), xi[1].clamp(-1.0, 1.0)]
    } else {
        let (mut r, mut s) = (xi[0].max(0.0), xi[1].max(0.0));
        let excess = r + s - 1.0;
        if excess > 0.0 {
            // Closest point of the hypotenuse, then back onto the legs.
            r -= 0.5 * excess;
            s -= 0.5 * excess;
            if r < 0.0 {
                (r, s) = (0.0, 1.0);
            } else if s < 0.0 {
                (r, s) = (1.0, 0.0);
            }
        }
        [r, s]
    }
}

/// How far `xi` lies outside the reference cell (0 inside).
fn outside(kind: CellType, xi: [f64; 2]) -> f64 {
    if is_quad(kind) {
        (xi[0].abs() - 1.0).max(xi[1].abs() - 1.0).max(0.0)
    } else {
        (-xi[0]).max(-xi[1]).max(xi[0] + xi[1] - 1.0).max(0.0)
    }
}

impl<'a> PointLocator<'a> {
    /// Builds the buckets of a 2D mesh of Tri3, Tri6, Quad4 and Quad8 cells.
    ///
    /// # Errors
    /// [`FemError::Setup`] for a 3D mesh, another cell type or an empty mesh.
    pub fn new(mesh: &'a Mesh) -> Result<Self, FemError> {
        if mesh.dim != 2 || mesh.num_cells() == 0 {
            return Err(FemError::Setup(format!(
                "point location needs a non-empty 2D mesh (dimension {}, {} cells)",
                mesh.dim,
                mesh.num_cells()
            )));
        }
        let mut boxes = Vec::with_capacity(mesh.num_cells());
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (c, kind, nodes) in mesh.cells() {
            if !matches!(
                kind,
                CellType::Tri3 | CellType::Tri6 | CellType::Quad4 | CellType::Quad8
            ) {
                return Err(FemError::Setup(format!(
                    "point location in {kind} cells (cell {c}) is not implemented"
                )));
            }
            let mut b = [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ];
            for &n in nodes {
                let x = mesh.coords[n];
                b[0] = b[0].min(x[0]);
                b[1] = b[1].min(x[1]);
                b[2] = b[2].max(x[0]);
                b[3] = b[3].max(x[1]);
            }
            // Curved (quadratic) edges may bulge past their nodes by a fraction of the cell.
            let pad = 0.25 * (b[2] - b[0]).max(b[3] - b[1]);
            let b = [b[0] - pad, b[1] - pad, b[2] + pad, b[3] + pad];
            lo = [lo[0].min(b[0]), lo[1].min(b[1])];
            hi = [hi[0].max(b[2]), hi[1].max(b[3])];
            boxes.push(b);
        }
        let ext = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
        let total = mesh.num_cells() as f64;
        let nx = ((total * ext[0] / ext[1]).sqrt().round() as usize).clamp(1, 4096);
        let ny = ((total / nx as f64).round() as usize).clamp(1, 4096);
        let n = [nx, ny];
        let size = [ext[0] / nx as f64, ext[1] / ny as f64];
        let range = |v0: f64, v1: f64, j: usize| -> (usize, usize) {
            let a = ((v0 - lo[j]) / size[j]).floor().max(0.0) as usize;
            let b = ((v1 - lo[j]) / size[j]).floor().max(0.0) as usize;
            (a.min(n[j] - 1), b.min(n[j] - 1))
        };
        let mut count = vec![0usize; nx * ny + 1];
        for b in &boxes {
            let (i0, i1) = range(b[0], b[2], 0);
            let (j0, j1) = range(b[1], b[3], 1);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    count[j * nx + i + 1] += 1;
                }
            }
        }
        for k in 1..count.len() {
            count[k] += count[k - 1];
        }
        let start = count.clone();
        let mut fill = count;
        let mut cells = vec![0u32; *start.last().unwrap_or(&0)];
        for (c, b) in boxes.iter().enumerate() {
            let (i0, i1) = range(b[0], b[2], 0);
            let (j0, j1) = range(b[1], b[3], 1);
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let k = j * nx + i;
                    cells[fill[k]] = c as u32;
                    fill[k] += 1;
                }
            }
        }
        Ok(PointLocator {
            mesh,
            lo,
            size,
            n,
            start,
            cells,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &Mesh {
        self.mesh
    }

    /// Newton's method for `x(xi) = x` in cell `c`: the reference point (unclamped) and whether
    /// it converged.
    pub fn inverse_map(&self, c: usize, x: [f64; 3]) -> ([f64; 2], bool) {
        let kind = self.mesh.cell_type(c);
        let nodes = self.mesh.cell_nodes(c);
        let mut xi = if is_quad(kind) {
            [0.0, 0.0]
        } else {
            [1.0 / 3.0, 1.0 / 3.0]
        };
        let mut n = [0.0; MAX_NODES];
        let mut dn = [[0.0; 3]; MAX_NODES];
        let scale = {
            let (a, b) = (self.mesh.coords[nodes[0]], self.mesh.coords[nodes[1]]);
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2))
                .sqrt()
                .max(1e-300)
        };
        for _ in 0..30 {
            shape(kind, [xi[0], xi[1], 0.0], &mut n, &mut dn);
            let mut r = [-x[0], -x[1]];
            let mut j = [[0.0; 2]; 2];
            for (i, &node) in nodes.iter().enumerate() {
                let p = self.mesh.coords[node];
                r[0] += n[i] * p[0];
                r[1] += n[i] * p[1];
                for k in 0..2 {
                    j[k][0] += dn[i][k] * p[0];
                    j[k][1] += dn[i][k] * p[1];
                }
            }
            // J^T d = -r with J_kl = dx_l / dxi_k: d_k solves sum_k J_kl d_k = -r_l.
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            if !(det.abs() > 0.0) || !det.is_finite() {
                return (xi, false);
            }
            let d0 = (-r[0] * j[1][1] + r[1] * j[1][0]) / det;
            let d1 = (-r[1] * j[0][0] + r[0] * j[0][1]) / det;
            xi = [xi[0] + d0, xi[1] + d1];
            if !(xi[0].is_finite() && xi[1].is_finite()) || xi[0].abs() > 1e3 || xi[1].abs() > 1e3 {
                return (xi, false);
            }
            if r[0].abs().max(r[1].abs()) < 1e-13 * scale {
                // The residual was of the previous iterate; the step made it smaller still.
                return (xi, true);
            }
        }
        let p = self.point(c, xi);
        let res = (p[0] - x[0]).abs().max((p[1] - x[1]).abs());
        (xi, res < 1e-11 * scale)
    }

    /// Physical point of cell `c` at reference point `xi`.
    pub fn point(&self, c: usize, xi: [f64; 2]) -> [f64; 2] {
        let kind = self.mesh.cell_type(c);
        let mut n = [0.0; MAX_NODES];
        let mut dn = [[0.0; 3]; MAX_NODES];
        shape(kind, [xi[0], xi[1], 0.0], &mut n, &mut dn);
        let mut p = [0.0; 2];
        for (i, &node) in self.mesh.cell_nodes(c).iter().enumerate() {
            p[0] += n[i] * self.mesh.coords[node][0];
            p[1] += n[i] * self.mesh.coords[node][1];
        }
        p
    }

    fn bucket(&self, i: usize, j: usize) -> &[u32] {
        let k = j * self.n[0] + i;
        &self.cells[self.start[k]..self.start[k + 1]]
    }

    fn bucket_index(&self, x: [f64; 3]) -> Option<(usize, usize)> {
        let fi = (x[0] - self.lo[0]) / self.size[0];
        let fj = (x[1] - self.lo[1]) / self.size[1];
        if !(fi >= 0.0 && fj >= 0.0 && fi < self.n[0] as f64 && fj < self.n[1] as f64) {
            return None;
        }
        Some((fi as usize, fj as usize))
    }

    /// The cell that holds `x` and the reference coordinates of `x` in it; `None` outside the
    /// mesh.
    pub fn locate(&self, x: [f64; 3]) -> Option<Location> {
        let (i, j) = self.bucket_index(x)?;
        for &c in self.bucket(i, j) {
            let c = c as usize;
            let (xi, ok) = self.inverse_map(c, x);
            if ok && outside(self.mesh.cell_type(c), xi) <= INSIDE {
                let p = self.point(c, xi);
                return Some(Location {
                    cell: c,
                    xi: [xi[0], xi[1], 0.0],
                    distance: ((p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2)).sqrt(),
                });
            }
        }
        None
    }

    /// As [`PointLocator::locate`], and for a point outside every cell the closest image
    /// `x(xi)` of a clamped reference point within `max_distance` (cells of the buckets within
    /// that distance); `None` if there is none.
    pub fn locate_nearest(&self, x: [f64; 3], max_distance: f64) -> Option<Location> {
        if let Some(l) = self.locate(x) {
            return Some(l);
        }
        let lo = [x[0] - max_distance, x[1] - max_distance];
        let hi = [x[0] + max_distance, x[1] + max_distance];
        let idx = |v: f64, j: usize| -> isize {
            (((v - self.lo[j]) / self.size[j]).floor() as isize).clamp(-1, self.n[j] as isize)
        };
        let (i0, i1) = (
            idx(lo[0], 0).max(0),
            idx(hi[0], 0).min(self.n[0] as isize - 1),
        );
        let (j0, j1) = (
            idx(lo[1], 1).max(0),
            idx(hi[1], 1).min(self.n[1] as isize - 1),
        );
        let mut best: Option<Location> = None;
        for j in j0..=j1 {
            for i in i0..=i1 {
                for &c in self.bucket(i as usize, j as usize) {
                    let c = c as usize;
                    let (xi, _) = self.inverse_map(c, x);
                    let xi = clamp(self.mesh.cell_type(c), xi);
                    let p = self.point(c, xi);
                    let dist = ((p[0] - x[0]).powi(2) + (p[1] - x[1]).powi(2)).sqrt();
                    if dist <= max_distance
                        && best
                            .is_none_or(|b| dist < b.distance || (dist == b.distance && c < b.cell))
                    {
                        best = Some(Location {
                            cell: c,
                            xi: [xi[0], xi[1], 0.0],
                            distance: dist,
                        });
                    }
                }
            }
        }
        best
    }
}
