//! Interface sides of a 3D substructure: the discrete interface forces turned into face
//! densities for phase 1 ([`interface_densities`]), and the FE traction projections on a facet
//! group used as the targets of the split ([`face_projections`]). The 3D counterpart of
//! [`crate::eet::sides`].

use alea_fem::{Model, Quadrature};
use alea_mesh::{Facet, Mesh};

use super::topology::{FaceTopology, face_mass};
use crate::CreError;
use crate::data::{FaceProjections, SideForces};
use crate::kernel::split::split_interface_forces;
use crate::kernel::vector::Frame;

/// A node's orthonormal frame (rows: free directions first, then constrained ones) and its
/// number of free directions.
pub type NodeFrame3 = Frame<3>;

/// A polynomial density on one face: `(face, values at the face's nodes)`.
pub type FaceValues = (usize, Vec<[f64; 3]>);

/// Densities of the faces' degree on the faces of an interface side whose consistent nodal
/// forces equal the given discrete forces `g_i`: the split of `crate::kernel::split` with the
/// face mass matrices.
///
/// `b_bar[f]` are the projections of face `f` (face order); entries of `side.face_reference`
/// replace them. With node `frames` (constraint frames of the domain), the force is imposed only
/// in each node's free directions. Returns, per face of the side, the nodal values.
pub fn interface_densities(
    mesh: &Mesh,
    topo: &FaceTopology,
    side: &SideForces,
    b_bar: &[Vec<[f64; 3]>],
    frames: Option<&[NodeFrame3]>,
) -> Result<Vec<FaceValues>, CreError> {
    let locate = |fc: &Facet| {
        let corners = &fc.nodes[..fc.kind.num_corners()];
        let f = topo.find(corners).ok_or_else(|| {
            CreError::Invalid(format!(
                "facet {:?} of '{}' is not a mesh face",
                fc.nodes, side.group
            ))
        })?;
        let face = &topo.faces[f];
        let t = b_bar
            .get(f)
            .cloned()
            .ok_or_else(|| CreError::Invalid(format!("face {f} has no reference projection")))?;
        let reference = side
            .face_reference
            .as_ref()
            .and_then(|r| r.get(&face.key()));
        Ok((f, t, reference))
    };
    let mass = |f: usize| face_mass(mesh, &topo.faces[f]);
    split_interface_forces(mesh, topo, side, 1.0, frames, locate, mass)
}

/// Projections `int_facet (sigma_h n) phi_node dS` (`n` outward) of the FE traction of `u` on
/// every facet of group `group` of a 3D model, keyed by the facet's sorted corner nodes.
pub fn face_projections(
    model: &Model,
    u: &[f64],
    group: &str,
) -> Result<FaceProjections, CreError> {
    let mesh = &model.mesh;
    if mesh.dim != 3 || u.len() != 3 * mesh.num_nodes() {
        return Err(CreError::Invalid(format!(
            "face projections need a 3D mesh and 3 components per node (displacement of length {} for {} nodes)",
            u.len(),
            mesh.num_nodes()
        )));
    }
    let mut out = FaceProjections::new();
    for bf in mesh.attach_facets(mesh.facet_group(group)?, None)? {
        let kind = bf.facet.kind;
        let fnodes = &bf.facet.nodes;
        let coords: Vec<[f64; 3]> = fnodes.iter().map(|&n| mesh.coords[n]).collect();
        let cell_kind = mesh.cell_type(bf.cell);
        let refs = alea_fem::reference::node_coords(cell_kind);
        let loc = cell_kind.facets()[bf.local].1;
        let lin = if kind == alea_mesh::CellType::Quad4 {
            alea_mesh::CellType::Quad4
        } else {
            alea_mesh::CellType::Tri3
        };
        let rule = Quadrature::for_cell(kind, 2 * kind.order() + 3);
        let mut proj = vec![[0.0; 3]; fnodes.len()];
        let mut nl = [0.0; alea_fem::reference::MAX_NODES];
        let mut dnl = [[0.0; 3]; alea_fem::reference::MAX_NODES];
        for (rs, w) in rule.points.iter().zip(&rule.weights) {
            let g = alea_fem::kinematics::facet_geometry(kind, &coords, *rs);
            alea_fem::reference::shape(lin, *rs, &mut nl, &mut dnl);
            let mut xi = [0.0; 3];
            for a in 0..lin.num_nodes() {
                for d in 0..3 {
                    xi[d] += nl[a] * refs[loc[a]][d];
                }
            }
            let t = fe_traction(model, bf.cell, u, xi, g.normal)?;
            for (a, p) in proj.iter_mut().enumerate() {
                for c in 0..3 {
                    p[c] += w * g.jac * g.n[a] * t[c];
                }
            }
        }
        let mut key = fnodes[..kind.num_corners()].to_vec();
        key.sort_unstable();
        out.insert(key, fnodes.iter().copied().zip(proj).collect());
    }
    Ok(out)
}

/// FE traction `sigma_h n` of cell `c` at its reference point `xi`.
pub(crate) fn fe_traction(
    model: &Model,
    c: usize,
    u: &[f64],
    xi: [f64; 3],
    n: [f64; 3],
) -> Result<[f64; 3], CreError> {
    let s = alea_fem::post::stress_at(model, c, u, xi)?;
    // [xx, yy, zz, yz, xz, xy]
    Ok([
        s[0] * n[0] + s[5] * n[1] + s[4] * n[2],
        s[5] * n[0] + s[1] * n[1] + s[3] * n[2],
        s[4] * n[0] + s[3] * n[1] + s[2] * n[2],
    ])
}
