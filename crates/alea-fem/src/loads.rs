//! External loads as consistent nodal force vectors (full, node-major `n_nodes x dim`).
//!
//! - Nodal forces on a node group: added as given.
//! - Tractions on a facet group: `f_a = int_facet N_a t(x, n) t_h dS` (t_h = thickness in 2D),
//!   with `n` the outward unit normal of the facet with respect to the cell it bounds; a
//!   pressure `p` is the traction `t = -p n` (positive pressure pushes on the surface).
//! - Body forces: `f_a = int_e N_a b(x) t_h dV`; gravity `b = rho g`; centrifugal inertia
//!   `b = rho omega^2 r_perp(x)` with `r_perp` the vector from the rotation axis to `x`,
//!   perpendicular to the axis (`rho` from each cell's material).

use alea_mesh::CellType;
use alea_mesh::vec3::{dot, norm};

use crate::kinematics::{facet_geometry, point_geometry};
use crate::{FemError, Model, Quadrature};

/// Accumulates external forces into a full node-major vector.
#[derive(Clone, Debug)]
pub struct Loads {
    /// Node-major force components (`num_nodes * dim`).
    pub f: Vec<f64>,
    dim: usize,
}

impl Loads {
    /// Zero loads for `model`.
    pub fn new(model: &Model) -> Self {
        Loads {
            f: vec![0.0; model.mesh.num_nodes() * model.mesh.dim],
            dim: model.mesh.dim,
        }
    }

    /// Adds a force vector (per node, `dim` components) to every node of `group`.
    pub fn nodal_force(
        &mut self,
        model: &Model,
        group: &str,
        force: [f64; 3],
    ) -> Result<&mut Self, FemError> {
        for n in model.mesh.group_nodes(group)? {
            for c in 0..self.dim {
                self.f[n * self.dim + c] += force[c];
            }
        }
        Ok(self)
    }

    /// Adds a traction `t(x, n)` (force per area) on facet group `group`.
    pub fn traction(
        &mut self,
        model: &Model,
        group: &str,
        traction: impl Fn([f64; 3], [f64; 3]) -> [f64; 3],
    ) -> Result<&mut Self, FemError> {
        let mesh = &model.mesh;
        let facets = mesh.attach_facets(mesh.facet_group(group)?, None)?;
        let th = model.analysis.thickness();
        for bf in facets {
            let f = &bf.facet;
            let coords: Vec<[f64; 3]> = f.nodes.iter().map(|&n| mesh.coords[n]).collect();
            let q = Quadrature::for_cell(f.kind, 2 * f.kind.order() + 2);
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = facet_geometry(f.kind, &coords, *xi);
                let t = traction(g.x, g.normal);
                let s = w * g.jac * if self.dim == 2 { th } else { 1.0 };
                for (a, &n) in f.nodes.iter().enumerate() {
                    for c in 0..self.dim {
                        self.f[n * self.dim + c] += s * g.n[a] * t[c];
                    }
                }
            }
        }
        Ok(self)
    }

    /// Adds a uniform pressure `p` on facet group `group` (traction `-p n`).
    pub fn pressure(&mut self, model: &Model, group: &str, p: f64) -> Result<&mut Self, FemError> {
        self.traction(model, group, |_, n| [-p * n[0], -p * n[1], -p * n[2]])
    }

    /// Adds a body force `b(x, rho)` (force per volume) over the cells of `group` (all cells
    /// if `None`); `rho` is the cell's density.
    pub fn body_force(
        &mut self,
        model: &Model,
        group: Option<&str>,
        body: impl Fn([f64; 3], f64) -> [f64; 3],
    ) -> Result<&mut Self, FemError> {
        let cells: Vec<usize> = match group {
            Some(g) => model.mesh.cell_group(g)?.to_vec(),
            None => (0..model.mesh.num_cells()).collect(),
        };
        let th = model.analysis.thickness();
        for c in cells {
            let kind: CellType = model.mesh.cell_type(c);
            let rho = model.material(c)?.density;
            let coords = model.cell_coords(c);
            let nodes = model.mesh.cell_nodes(c);
            let q = Quadrature::for_cell(kind, 2 * kind.order() + 2);
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = point_geometry(kind, &coords, *xi);
                let b = body(g.x, rho);
                let s = w * g.det * th;
                for (a, &n) in nodes.iter().enumerate() {
                    for c in 0..self.dim {
                        self.f[n * self.dim + c] += s * g.n[a] * b[c];
                    }
                }
            }
        }
        Ok(self)
    }

    /// Adds centrifugal inertia `rho omega^2 r_perp` for a rotation at `omega` (rad/s) about
    /// the axis through `point` with direction `axis` (in 2D use `axis = [0, 0, 1]`).
    pub fn centrifugal(
        &mut self,
        model: &Model,
        group: Option<&str>,
        omega: f64,
        point: [f64; 3],
        axis: [f64; 3],
    ) -> Result<&mut Self, FemError> {
        let len = norm(&axis);
        if !(len > 0.0) {
            return Err(FemError::Setup("rotation axis must be non-zero".into()));
        }
        let e = [axis[0] / len, axis[1] / len, axis[2] / len];
        self.body_force(model, group, move |x, rho| {
            let r = [x[0] - point[0], x[1] - point[1], x[2] - point[2]];
            let s = dot(&r, &e);
            let w2 = rho * omega * omega;
            [
                w2 * (r[0] - s * e[0]),
                w2 * (r[1] - s * e[1]),
                w2 * (r[2] - s * e[2]),
            ]
        })
    }

    /// Sum of the force components (the resultant).
    pub fn resultant(&self) -> [f64; 3] {
        let mut r = [0.0; 3];
        for (i, v) in self.f.iter().enumerate() {
            r[i % self.dim] += v;
        }
        r
    }
}
