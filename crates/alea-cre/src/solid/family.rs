//! The 3D cell family of the EET kernel (`crate::kernel`): Tet4/Tet10/Hex8 cells with their
//! faces ([`FaceTopology`]) as sides; densities of the face's degree (linear on Tri3 faces,
//! bilinear on Quad4, quadratic on Tri6) stored as values at the face nodes.

use alea_fem::Model;
use alea_mesh::Mesh;

use super::projections::{add_prescribed_tractions, averaged_projections};
use super::sides::interface_densities;
use super::topology::{Face, FaceTopology, face_mass};
use crate::CreError;
use crate::data::{SideForces, TractionField};
use crate::kernel::family::CellFamily;
use crate::kernel::loads::SideLoads;
use crate::kernel::topology::{Incidence, Side, SideTopology};
use crate::kernel::vector::{Frame, dot, identity};
use crate::linalg::cholesky_solve;

/// `a x b` (by value, for the frames below).
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    alea_mesh::vec3::cross(&a, &b)
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

/// A unit vector orthogonal to the unit vector `t`.
fn orthogonal(t: [f64; 3]) -> [f64; 3] {
    let k = (0..3)
        .min_by(|&a, &b| t[a].abs().total_cmp(&t[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    unit(cross(t, e))
}

impl Side for Face {
    fn cells(&self) -> &[(usize, usize)] {
        &self.cells
    }

    fn nodes(&self) -> impl Iterator<Item = usize> + '_ {
        self.nodes.iter().copied()
    }
}

impl SideTopology<3> for FaceTopology {
    type Side = Face;
    const SIDE: &'static str = "face";

    fn sides(&self) -> &[Face] {
        &self.faces
    }

    fn incidence(&self) -> Incidence<'_> {
        Incidence {
            cell_sides: &self.cell_faces,
            node_cells: &self.node_cells,
            node_sides: &self.node_faces,
        }
    }

    fn measure(&self, _mesh: &Mesh, s: usize) -> f64 {
        self.faces[s].area
    }

    /// One free direction `t`: `(t, o, t x o)` with `o` orthogonal to `t`; two `t1`, `t2`:
    /// `(t1, t2, t1 x t2)` (normalised).
    fn complete_frame(free: [[f64; 3]; 3], nfree: usize) -> Frame<3> {
        match nfree {
            0 => (identity(), 0),
            1 => {
                let t = unit(free[0]);
                let o = orthogonal(t);
                ([t, o, cross(t, o)], 1)
            }
            2 => {
                let (t1, t2) = (unit(free[0]), unit(free[1]));
                ([t1, t2, unit(cross(t1, t2))], 2)
            }
            _ => (identity(), 3),
        }
    }
}

impl CellFamily<3> for FaceTopology {
    type Values = Vec<[f64; 3]>;

    fn build(mesh: &Mesh) -> Result<Self, CreError> {
        FaceTopology::new(mesh)
    }

    fn zero_values(&self) -> Vec<Vec<[f64; 3]>> {
        self.faces
            .iter()
            .map(|f| vec![[0.0; 3]; f.nodes.len()])
            .collect()
    }

    fn thickness(_model: &Model) -> f64 {
        1.0
    }

    fn side_mass(&self, mesh: &Mesh, s: usize) -> Vec<f64> {
        face_mass(mesh, &self.faces[s])
    }

    fn add_prescribed(
        &self,
        mesh: &Mesh,
        frames: &[Frame<3>],
        tractions: &[(String, TractionField)],
        loads: &mut SideLoads<Vec<[f64; 3]>, 3>,
    ) -> Result<(), CreError> {
        add_prescribed_tractions(mesh, self, frames, tractions, loads)
    }

    fn averaged_projections(
        &self,
        model: &Model,
        u: &[f64],
    ) -> Result<Vec<Vec<[f64; 3]>>, CreError> {
        averaged_projections(model, self, u)
    }

    fn interface_densities(
        &self,
        mesh: &Mesh,
        side: &SideForces,
        _thickness: f64,
        b_bar: &[Vec<[f64; 3]>],
        frames: Option<&[Frame<3>]>,
    ) -> Result<Vec<(usize, Vec<[f64; 3]>)>, CreError> {
        interface_densities(mesh, self, side, b_bar, frames)
    }

    /// `M F = b` (faces without unknown projections are skipped).
    fn add_recovered(
        &self,
        _mesh: &Mesh,
        s: usize,
        mass: &[f64],
        b: &Vec<[f64; 3]>,
        values: &mut Vec<[f64; 3]>,
    ) -> Result<(), CreError> {
        if b.iter().all(|v| *v == [0.0; 3]) {
            return Ok(());
        }
        let n = b.len();
        for c in 0..3 {
            let mut a = mass.to_vec();
            let mut x: Vec<f64> = b.iter().map(|v| v[c]).collect();
            if !cholesky_solve(&mut a, &mut x, n) {
                return Err(CreError::Invalid(format!("degenerate face {s}")));
            }
            for k in 0..n {
                values[k][c] += x[k];
            }
        }
        Ok(())
    }
}
