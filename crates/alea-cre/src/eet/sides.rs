//! Interface sides of a substructure: the discrete interface forces turned into edge densities
//! for phase 1 ([`interface_densities`]), and the FE traction projections on a facet group used
//! as the targets of the split ([`facet_projections`]).

use alea_fem::Model;
use alea_mesh::{Facet, Mesh};

use crate::CreError;
use crate::data::{FacetProjections, SideForces};
use crate::fe::{cell_values, facet_point, gauss01, hooke, mul3, strain_h, traction_of};
use crate::kernel::family::CellFamily;
use crate::kernel::split::split_interface_forces;
use crate::kernel::vector::Frame;
use crate::topology::{Topology, facet_point_at};

/// A node's orthonormal frame (rows) and its number of free directions (the first ones; the
/// rest are constrained).
pub type NodeFrame = Frame<2>;

/// A polynomial density on one edge: `(edge, values at [nodes[0], nodes[1], mid])`.
pub type EdgeLinear = (usize, [[f64; 2]; 3]);

/// Consistent edge mass `int N_a N_b ds` (ends, mid) of an edge of length `len`.
pub(crate) fn edge_mass(quadratic: bool, len: f64) -> [[f64; 3]; 3] {
    if quadratic {
        let c = len / 30.0;
        [
            [4.0 * c, -c, 2.0 * c],
            [-c, 4.0 * c, 2.0 * c],
            [2.0 * c, 2.0 * c, 16.0 * c],
        ]
    } else {
        let c = len / 6.0;
        [[2.0 * c, c, 0.0], [c, 2.0 * c, 0.0], [0.0, 0.0, 0.0]]
    }
}

/// Densities of degree `p` on the edges of an interface side whose consistent nodal forces equal
/// the given discrete forces `g_i` (per unit thickness: `g_i / thickness`): the split of
/// `crate::kernel::split` with the edge mass matrices.
///
/// `b_bar[e]` are the projections of edge `e` (edge orientation, slots ends/mid); entries of
/// `side.reference` replace them. With node `frames` (constraint frames of the domain), the
/// force is imposed only in each node's free directions. Returns, per edge of the side, the
/// nodal values (ends, mid).
pub fn interface_densities(
    mesh: &Mesh,
    topo: &Topology,
    side: &SideForces,
    thickness: f64,
    b_bar: &[[[f64; 2]; 3]],
    frames: Option<&[NodeFrame]>,
) -> Result<Vec<EdgeLinear>, CreError> {
    let locate = |f: &Facet| {
        let (a, b) = (f.nodes[0], f.nodes[1]);
        let e = topo.find(a, b).ok_or_else(|| {
            CreError::Invalid(format!(
                "facet ({a}, {b}) of '{}' is not a mesh edge",
                side.group
            ))
        })?;
        let t = *b_bar
            .get(e)
            .ok_or_else(|| CreError::Invalid(format!("edge {e} has no reference projection")))?;
        let reference = side
            .reference
            .as_ref()
            .and_then(|r| r.get(&[a.min(b), a.max(b)]));
        Ok((e, t, reference))
    };
    let mass = |e: usize| topo.side_mass(mesh, e);
    split_interface_forces(mesh, topo, side, thickness, frames, locate, mass)
}

/// Projections `int_facet (sigma_h n) phi_node dS` (per unit thickness, `n` outward) of the FE
/// traction of `u` on every facet of group `group`, keyed by the facet's sorted end nodes.
pub fn facet_projections(
    model: &Model,
    u: &[f64],
    group: &str,
) -> Result<FacetProjections, CreError> {
    let mesh = &model.mesh;
    if u.len() != 2 * mesh.num_nodes() {
        return Err(CreError::Invalid(format!(
            "displacement of length {} for {} nodes",
            u.len(),
            mesh.num_nodes()
        )));
    }
    let rule = gauss01(4);
    let mut out = FacetProjections::new();
    for bf in mesh.attach_facets(mesh.facet_group(group)?, None)? {
        let c = bf.cell;
        let kind = mesh.cell_type(c);
        let nodes = mesh.cell_nodes(c);
        let coords = model.cell_coords(c);
        let ue: Vec<f64> = cell_values::<2>(u, nodes);
        let d = hooke(model.material(c)?, model.analysis);
        let fnodes = &bf.facet.nodes;
        let quadratic = fnodes.len() == 3;
        let mut proj = vec![[0.0; 2]; fnodes.len()];
        for &(s, w) in &rule {
            // Isoparametric facet geometry (curved quadratic facets included).
            let ep = facet_point_at(mesh, fnodes, s);
            let (eps, _) = strain_h(kind, &coords, &ue, facet_point(kind, bf.local, s));
            let tr = traction_of(&mul3(&d, &eps), ep.n);
            let sh = if quadratic {
                [
                    (1.0 - s) * (1.0 - 2.0 * s),
                    s * (2.0 * s - 1.0),
                    4.0 * s * (1.0 - s),
                ]
            } else {
                [1.0 - s, s, 0.0]
            };
            for (k, p) in proj.iter_mut().enumerate() {
                for c2 in 0..2 {
                    p[c2] += w * ep.jac * sh[k] * tr[c2];
                }
            }
        }
        let (a, b) = (fnodes[0], fnodes[1]);
        out.insert(
            [a.min(b), a.max(b)],
            fnodes.iter().copied().zip(proj).collect(),
        );
    }
    Ok(out)
}
