//! The side densities of phase 1 while they are built, and the known projections
//! `b_known[side][slot] = int_Gamma F_hat phi_slot dS` of the boundary sides whose traction is
//! data (prescribed tractions, interface densities): the right-hand sides of the node systems
//! (3.22). A density is a polynomial part (values at the side's nodes, interpolated with the
//! side's shape functions) plus prescribed-traction fields, each through the projector of its
//! side ([`super::frames::side_projector`]).

use super::frames::side_projector;
use super::topology::SideTopology;
use super::vector::{Frame, apply};
use crate::CreError;

/// A prescribed-traction field on one side.
#[derive(Clone, Copy, Debug)]
pub struct SideData<const D: usize> {
    /// Index of the traction field in the domain's load data.
    pub field: usize,
    /// Projector applied to the field (removes directions constrained on the whole side).
    pub projector: [[f64; D]; D],
}

/// Densities and known projections of every side (`B`: the per-slot values of one side).
pub(crate) struct SideLoads<B, const D: usize> {
    /// Polynomial part of each side's density (values at its nodes).
    pub values: Vec<B>,
    /// Prescribed-traction part of each side's density.
    pub data: Vec<Vec<SideData<D>>>,
    /// Known projections on boundary sides (prescribed tractions, interface densities).
    pub b_known: Vec<B>,
}

impl<B: AsRef<[[f64; D]]> + AsMut<[[f64; D]]> + Clone, const D: usize> SideLoads<B, D> {
    /// No load; `zero` holds the zero values of each side.
    pub fn new(zero: Vec<B>) -> Self {
        SideLoads {
            data: vec![Vec::new(); zero.len()],
            b_known: zero.clone(),
            values: zero,
        }
    }

    /// Adds the interface densities `densities` (`(side, values at its nodes)`) as known
    /// polynomial densities of their boundary sides, projected on the unconstrained directions:
    /// `values += P t`, `b_known += M (P t)` with `masses[side]` the side mass matrix
    /// `int N_a N_b dS` (row-major, nodes x nodes).
    pub fn add_sides<T: SideTopology<D>>(
        &mut self,
        topo: &T,
        frames: &[Frame<D>],
        group: &str,
        densities: Vec<(usize, B)>,
        masses: &[Vec<f64>],
    ) -> Result<(), CreError> {
        for (s, t) in densities {
            if !topo.is_boundary(s) {
                return Err(CreError::Invalid(format!(
                    "interface side '{group}' contains an interior {}",
                    T::SIDE
                )));
            }
            let p = side_projector(topo, frames, s);
            let m = &masses[s];
            let n = topo.side_nodes(s).count();
            let pt: Vec<[f64; D]> = t.as_ref()[..n].iter().map(|v| apply(&p, *v)).collect();
            let values = self.values[s].as_mut();
            let b_known = self.b_known[s].as_mut();
            for a in 0..n {
                for c in 0..D {
                    values[a][c] += pt[a][c];
                    b_known[a][c] += (0..n).map(|b| m[a * n + b] * pt[b][c]).sum::<f64>();
                }
            }
        }
        Ok(())
    }

    /// Adds a prescribed-traction field to side `s` (a boundary side of a traction group) and
    /// returns its projector; the caller adds its projections to `b_known`.
    pub fn add_field<T: SideTopology<D>>(
        &mut self,
        topo: &T,
        frames: &[Frame<D>],
        s: usize,
        field: usize,
    ) -> [[f64; D]; D] {
        let projector = side_projector(topo, frames, s);
        self.data[s].push(SideData { field, projector });
        projector
    }
}
