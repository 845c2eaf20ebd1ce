//! Edge integrals of 2D phase 1: the projections `int_Gamma t phi_a dS` on the mesh edges of
//! the prescribed tractions (data of the node systems (3.22)) and of the averaged FE tractions
//! `b_bar = int_Gamma 1/2 (sigma_h|E + sigma_h|E') n phi_a dS` (the targets of the
//! Ladeveze-Leguillon minimisation), on straight and curved (isoparametric) edges: `x(s)`,
//! `n(s)`, `dS = J(s) ds` ([`crate::topology::Edge::point`]). Per unit thickness.

use alea_fem::{Model, Quadrature};
use alea_mesh::Mesh;
use rayon::prelude::*;

use crate::CreError;
use crate::data::TractionField;
use crate::fe::{cell_values, facet_point, gauss01, hooke, mul3, strain_h, traction_of};
use crate::kernel::loads::SideLoads;
use crate::kernel::vector::Frame;
use crate::topology::{EdgePoint, Topology};

/// Adds the prescribed tractions (projected on the unconstrained directions) as data
/// densities and their projections, integrated with the rule of `alea_fem::Loads::traction`
/// so that they are those of the FE load vector.
pub(crate) fn add_prescribed_tractions(
    mesh: &Mesh,
    topo: &Topology,
    frames: &[Frame<2>],
    tractions: &[(String, TractionField)],
    loads: &mut SideLoads<[[f64; 2]; 3], 2>,
) -> Result<(), CreError> {
    for (fi, (group, field)) in tractions.iter().enumerate() {
        for f in mesh.facet_group(group)? {
            let e = topo.find(f.nodes[0], f.nodes[1]).ok_or_else(|| {
                CreError::Invalid(format!(
                    "facet {:?} of '{group}' is not a mesh edge",
                    f.nodes
                ))
            })?;
            if !topo.edges[e].is_boundary() {
                return Err(CreError::Invalid(format!(
                    "traction group '{group}' contains the interior edge {:?}",
                    f.nodes
                )));
            }
            let projector = loads.add_field(topo, frames, e, fi);
            let edge = &topo.edges[e];
            let line_rule = Quadrature::for_cell(
                alea_mesh::CellType::Line2,
                2 * (1 + edge.mid.is_some() as usize) + 2,
            );
            for (xi, w) in line_rule.points.iter().zip(&line_rule.weights) {
                let s = 0.5 * (xi[0] + 1.0);
                // The FE load vector's facet geometry (isoparametric: curved edges too).
                let EdgePoint { x, n, jac } = edge.point(s);
                let v = field(x, [n[0], n[1], 0.0]);
                let pv = [
                    projector[0][0] * v[0] + projector[0][1] * v[1],
                    projector[1][0] * v[0] + projector[1][1] * v[1],
                ];
                let dl = 0.5 * w * jac;
                let sh = edge.shape(s);
                for k in 0..3 {
                    for c in 0..2 {
                        loads.b_known[e][k][c] += dl * sh[k] * pv[c];
                    }
                }
            }
        }
    }
    Ok(())
}

/// The averaged FE traction projections `b_bar` of every edge of `topo` (first-cell
/// orientation; slots: ends, mid) for the FE displacement `u` of `model`.
pub(crate) fn averaged_projections(
    model: &Model,
    topo: &Topology,
    u: &[f64],
) -> Result<Vec<[[f64; 2]; 3]>, CreError> {
    let mesh = &model.mesh;
    let rule = gauss01(4);
    topo.edges
        .par_iter()
        .map(|edge| -> Result<[[f64; 2]; 3], CreError> {
            let mut bb = [[0.0; 2]; 3];
            let pts: Vec<EdgePoint> = rule.iter().map(|&(s, _)| edge.point(s)).collect();
            let share = 1.0 / edge.cells.len() as f64;
            for (k, &(c, l)) in edge.cells.iter().enumerate() {
                let kind = mesh.cell_type(c);
                let coords = model.cell_coords(c);
                let nodes = mesh.cell_nodes(c);
                let ue: Vec<f64> = cell_values::<2>(u, nodes);
                let d = hooke(model.material(c)?, model.analysis);
                for (&(s, w), p) in rule.iter().zip(&pts) {
                    // The second cell runs along the edge in the opposite direction.
                    let s_cell = if k == 0 { s } else { 1.0 - s };
                    let (eps, _) = strain_h(kind, &coords, &ue, facet_point(kind, l, s_cell));
                    let t = traction_of(&mul3(&d, &eps), p.n);
                    let sh = edge.shape(s);
                    for kk in 0..3 {
                        for c2 in 0..2 {
                            bb[kk][c2] += share * w * p.jac * sh[kk] * t[c2];
                        }
                    }
                }
            }
            Ok(bb)
        })
        .collect()
}
