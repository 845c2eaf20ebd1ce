//! Face integrals of 3D phase 1: the projections `int_Gamma t phi_a dS` on the mesh faces of
//! the prescribed tractions (data of the node systems (3.22), integrated with the rule and
//! facet geometry of `alea_fem::Loads::traction`, so that the node systems are compatible to
//! round-off) and of the averaged FE tractions `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E')
//! n phi_a dS` (the targets of the Ladeveze-Leguillon minimisation). On a warped Hex8 face the
//! area element is not polynomial: these are quadratures.

use alea_fem::{Model, Quadrature};
use alea_mesh::Mesh;
use rayon::prelude::*;

use super::sides::fe_traction;
use super::topology::FaceTopology;
use crate::CreError;
use crate::data::TractionField;
use crate::kernel::loads::SideLoads;
use crate::kernel::vector::{Frame, apply};

/// Adds the prescribed tractions (projected on the unconstrained directions) as data
/// densities and their projections.
pub(crate) fn add_prescribed_tractions(
    mesh: &Mesh,
    topo: &FaceTopology,
    frames: &[Frame<3>],
    tractions: &[(String, TractionField)],
    loads: &mut SideLoads<Vec<[f64; 3]>, 3>,
) -> Result<(), CreError> {
    for (fi, (group, field)) in tractions.iter().enumerate() {
        // The facets as `Loads::traction` sees them (outward, in the cell's local order).
        for bf in mesh.attach_facets(mesh.facet_group(group)?, None)? {
            let fnodes = &bf.facet.nodes;
            let f = topo
                .find(&fnodes[..bf.facet.kind.num_corners()])
                .ok_or_else(|| {
                    CreError::Invalid(format!("facet {fnodes:?} of '{group}' is not a mesh face"))
                })?;
            let face = &topo.faces[f];
            if !face.is_boundary() {
                return Err(CreError::Invalid(format!(
                    "traction group '{group}' contains the interior face {fnodes:?}"
                )));
            }
            let projector = loads.add_field(topo, frames, f, fi);
            let coords: Vec<[f64; 3]> = fnodes.iter().map(|&n| mesh.coords[n]).collect();
            let kind = bf.facet.kind;
            let rule = Quadrature::for_cell(kind, 2 * kind.order() + 2);
            for (rs, w) in rule.points.iter().zip(&rule.weights) {
                let g = alea_fem::kinematics::facet_geometry(kind, &coords, *rs);
                let v = apply(&projector, field(g.x, g.normal));
                for (a, &node) in fnodes.iter().enumerate() {
                    let slot = face.slot(node).unwrap_or(0);
                    for c in 0..3 {
                        loads.b_known[f][slot][c] += w * g.jac * g.n[a] * v[c];
                    }
                }
            }
        }
    }
    Ok(())
}

/// The averaged FE traction projections `b_bar` of every face of `topo` (first-cell
/// orientation, face node order) for the FE displacement `u` of `model`.
pub(crate) fn averaged_projections(
    model: &Model,
    topo: &FaceTopology,
    u: &[f64],
) -> Result<Vec<Vec<[f64; 3]>>, CreError> {
    let mesh = &model.mesh;
    topo.faces
        .par_iter()
        .map(|face| -> Result<Vec<[f64; 3]>, CreError> {
            let mut bb = vec![[0.0; 3]; face.nodes.len()];
            let share = 1.0 / face.cells.len() as f64;
            let rule = Quadrature::for_cell(face.kind, 2 * face.kind.order() + 3);
            for (rs, w) in rule.points.iter().zip(&rule.weights) {
                let g = face.geometry(mesh, *rs);
                for k in 0..face.cells.len() {
                    let xi = face.cell_point(mesh, k, *rs);
                    let t = fe_traction(model, face.cells[k].0, u, xi, g.normal)?;
                    for (a, b) in bb.iter_mut().enumerate() {
                        for c in 0..3 {
                            b[c] += share * w * g.jac * g.n[a] * t[c];
                        }
                    }
                }
            }
            Ok(bb)
        })
        .collect()
}
