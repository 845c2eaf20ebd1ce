//! Phase 1 of the EET technique for any cell family ([`CellFamily`]): equilibrated traction
//! densities `F_hat` on the cell sides (thesis (3.20)-(3.22)).
//!
//! Steps: the prescribed tractions become data densities of their sides; the element residuals
//! `Q_E(i)` ([`super::residuals`]) and the averaged FE traction projections `b_bar` are
//! computed; the interface forces become known densities ([`super::split`]); the node systems
//! (3.22) give the unknown projections `b_(i,Gamma)` ([`super::node_system`]); each side's
//! density is recovered from its projections through the side mass matrix. Every element is
//! then in equilibrium with its body force and its side densities (3.20): a rigid mode is
//! `v = sum_i v(x_i) phi_i`, so `int_dE eta F_hat . v = sum_i v(x_i) . Q_E(i) = - int_E f . v`.

use alea_fem::{DofMap, Model};
use alea_mesh::Mesh;

use super::family::CellFamily;
use super::frames::node_frames;
use super::loads::{SideData, SideLoads};
use super::node_system::{gather_node_solutions, solve_node_systems};
use super::residuals::element_residuals;
use super::tractions::SideTractions;
use super::vector::Frame;
use crate::CreError;
use crate::data::{SideForces, TractionField, VectorField};

/// Inputs of phase 1 for one domain.
pub struct Phase1Input<'a> {
    /// Model (materials already scaled).
    pub model: &'a Model,
    /// Constraints of the domain.
    pub dofs: &'a DofMap,
    /// FE displacement, node-major.
    pub u: &'a [f64],
    /// Body force.
    pub body: Option<&'a VectorField>,
    /// Prescribed tractions by facet group.
    pub tractions: &'a [(String, TractionField)],
    /// Discrete interface forces by side.
    pub sides: &'a [SideForces],
}

/// Adds the interface sides' densities (targets `b_bar`) as known densities of their sides.
#[allow(clippy::too_many_arguments)]
pub(crate) fn add_interface_sides<F: CellFamily<D>, const D: usize>(
    mesh: &Mesh,
    topo: &F,
    frames: &[Frame<D>],
    sides: &[SideForces],
    thickness: f64,
    b_bar: &[F::Values],
    masses: &[Vec<f64>],
    loads: &mut SideLoads<F::Values, D>,
) -> Result<(), CreError> {
    for side in sides {
        let densities = topo.interface_densities(mesh, side, thickness, b_bar, Some(frames))?;
        loads.add_sides(topo, frames, &side.group, densities, masses)?;
    }
    Ok(())
}

/// Adds to the densities those recovered from the node systems' projections `b_unknown`.
pub(crate) fn add_recovered<F: CellFamily<D>, const D: usize>(
    mesh: &Mesh,
    topo: &F,
    masses: &[Vec<f64>],
    b_unknown: &[F::Values],
    values: &mut [F::Values],
) -> Result<(), CreError> {
    for (s, (b, v)) in b_unknown.iter().zip(values).enumerate() {
        topo.add_recovered(mesh, s, &masses[s], b, v)?;
    }
    Ok(())
}

/// Runs phase 1 on one domain of cell family `F`: the result holds `topology(F)` and, per side,
/// `density(polynomial values, prescribed data)`.
pub(crate) fn equilibrate<F: CellFamily<D>, T, S, const D: usize>(
    inp: &Phase1Input,
    topology: impl FnOnce(F) -> T,
    density: impl Fn(F::Values, Vec<SideData<D>>) -> S,
) -> Result<SideTractions<T, S>, CreError> {
    let model = inp.model;
    let mesh = &model.mesh;
    if mesh.dim != D {
        return Err(CreError::Invalid(format!(
            "the {D}D EET phase 1 needs a {D}D mesh"
        )));
    }
    let nn = mesh.num_nodes();
    if inp.u.len() != D * nn {
        return Err(CreError::Invalid(format!(
            "displacement of length {} for {nn} nodes",
            inp.u.len()
        )));
    }
    let topo = F::build(mesh)?;
    let th = F::thickness(model);
    let frames = node_frames::<F, D>(inp.dofs, nn);
    let mut loads = SideLoads::new(topo.zero_values());
    topo.add_prescribed(mesh, &frames, inp.tractions, &mut loads)?;
    let q_res = element_residuals::<D>(model, inp.u, inp.body, th)?;
    let b_bar = topo.averaged_projections(model, inp.u)?;
    let masses: Vec<Vec<f64>> = (0..topo.num_sides())
        .map(|s| topo.side_mass(mesh, s))
        .collect();
    // Interface sides (after b_bar, which they use as the minimisation target).
    add_interface_sides(
        mesh, &topo, &frames, inp.sides, th, &b_bar, &masses, &mut loads,
    )?;
    let per_node = solve_node_systems(mesh, &topo, &frames, &q_res, &loads.b_known, &b_bar);
    let mut b_unknown = topo.zero_values();
    let compatibility_defect = gather_node_solutions(per_node, &mut b_unknown);
    add_recovered(mesh, &topo, &masses, &b_unknown, &mut loads.values)?;
    Ok(SideTractions::from_parts(
        topology(topo),
        loads.values,
        loads.data,
        inp.tractions,
        compatibility_defect,
        density,
    ))
}
