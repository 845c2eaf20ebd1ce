//! Extrusion of a 2D quadrilateral mesh along z into hexahedra.
//!
//! Node `i` of the 2D mesh gives nodes `k * N + i` at `z = k * thickness / layers`,
//! `k = 0..=layers` (N = number of 2D nodes); cell `c` gives the hexahedra `k * C + c` of layers
//! `k = 0..layers` (C = number of 2D cells), each `[a_k b_k c_k d_k a_k+1 b_k+1 c_k+1 d_k+1]` for
//! the counter-clockwise quad `(a b c d)`, hence right-handed. A 2D facet `(a, b)` becomes the
//! faces `[a_k, b_k, b_k+1, a_k+1]` (outward when `(a, b)` was outward in 2D).

use crate::{CellType, Facet, Mesh, MeshError};

/// Extrudes a 2D `Quad4` mesh over `z in [0, thickness]` in `layers` layers of hexahedra.
///
/// Groups: cell groups are carried over (all layers); each 2D facet group becomes a group of
/// `Quad4` faces (all layers); node groups are carried over (the nodes of all layers);
/// new facet and node groups `"zmin"` (z = 0) and `"zmax"` (z = thickness) hold the end faces.
///
/// # Errors
/// [`MeshError::Invalid`] if the mesh is not 2D, holds cells other than `Quad4` (triangles would
/// need wedges, quadratic cells 20-node hexahedra: neither is supported), facets other than
/// `Line2`, already has a `"zmin"` or `"zmax"` facet group, or if `layers == 0` or the thickness is
/// not positive.
pub fn extrude(mesh: &Mesh, layers: usize, thickness: f64) -> Result<Mesh, MeshError> {
    if mesh.dim != 2 {
        return Err(MeshError::Invalid(format!(
            "extrude() takes a 2D mesh, got a {}D one",
            mesh.dim
        )));
    }
    if layers == 0 || !(thickness.is_finite() && thickness > 0.0) {
        return Err(MeshError::Invalid(format!(
            "extrude() needs layers >= 1 and a positive thickness, got {layers} and {thickness}"
        )));
    }
    if let Some(t) = mesh
        .cell_types_present()
        .into_iter()
        .find(|&t| t != CellType::Quad4)
    {
        return Err(MeshError::Invalid(format!(
            "extrude() supports QUAD4 cells only (to HEX8), the mesh has {t} cells"
        )));
    }
    for name in ["zmin", "zmax"] {
        if mesh.facet_groups.contains_key(name) {
            return Err(MeshError::Invalid(format!(
                "the 2D mesh already has a facet group '{name}', which extrusion creates"
            )));
        }
    }
    mesh.validate()?;
    let n = mesh.num_nodes();
    let c = mesh.num_cells();
    let mut out = Mesh::new(3);
    for k in 0..=layers {
        let z = thickness * k as f64 / layers as f64;
        for x in &mesh.coords {
            out.add_node([x[0], x[1], z]);
        }
    }
    let at = |k: usize, i: usize| k * n + i;
    for k in 0..layers {
        for (_, _, q) in mesh.cells() {
            let mut h = [0usize; 8];
            for j in 0..4 {
                h[j] = at(k, q[j]);
                h[j + 4] = at(k + 1, q[j]);
            }
            out.add_cell(CellType::Hex8, &h);
        }
    }
    for (name, cells) in &mesh.cell_groups {
        out.add_cells_to_group(
            name,
            (0..layers).flat_map(|k| cells.iter().map(move |&cc| k * c + cc)),
        );
    }
    for (name, facets) in &mesh.facet_groups {
        let mut faces = Vec::with_capacity(facets.len() * layers);
        for f in facets {
            if f.kind != CellType::Line2 || f.nodes.len() != 2 {
                return Err(MeshError::Invalid(format!(
                    "facet group '{name}' holds a {} facet with {} nodes; extrusion needs LINE2 (2 nodes)",
                    f.kind,
                    f.nodes.len()
                )));
            }
            let (a, b) = (f.nodes[0], f.nodes[1]);
            for k in 0..layers {
                faces.push(Facet {
                    kind: CellType::Quad4,
                    nodes: vec![at(k, a), at(k, b), at(k + 1, b), at(k + 1, a)],
                });
            }
        }
        out.add_facets_to_group(name, faces);
    }
    for (name, nodes) in &mesh.node_groups {
        out.add_nodes_to_group(
            name,
            (0..=layers).flat_map(|k| nodes.iter().map(move |&i| at(k, i))),
        );
    }
    let bottom: Vec<Facet> = mesh
        .cells()
        .map(|(_, _, q)| Facet {
            kind: CellType::Quad4,
            nodes: vec![at(0, q[0]), at(0, q[3]), at(0, q[2]), at(0, q[1])],
        })
        .collect();
    let top: Vec<Facet> = mesh
        .cells()
        .map(|(_, _, q)| Facet {
            kind: CellType::Quad4,
            nodes: q.iter().map(|&i| at(layers, i)).collect(),
        })
        .collect();
    out.add_nodes_to_group("zmin", (0..n).map(|i| at(0, i)));
    out.add_nodes_to_group("zmax", (0..n).map(|i| at(layers, i)));
    out.add_facets_to_group("zmin", bottom);
    out.add_facets_to_group("zmax", top);
    Ok(out)
}
