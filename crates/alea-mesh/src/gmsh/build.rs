//! Assembly of the parsed file into a [`Mesh`]: cells of the top dimension (re-oriented to a
//! positive Jacobian), used nodes renumbered in file order, physical groups as cell, facet and
//! node groups.

use std::collections::HashMap;
use std::path::Path;

use super::{ElementBlock, FileData};
use crate::geometry::jacobian_det;
use crate::{CellType, Mesh, MeshError};

fn gmsh_to_vtk(kind: CellType, nodes: &mut [usize]) {
    if kind == CellType::Tet10 {
        nodes.swap(8, 9);
    }
}

/// Node permutation that reverses a cell's orientation (VTK order).
fn reversal(kind: CellType) -> &'static [usize] {
    use CellType::*;
    match kind {
        Tri3 => &[0, 2, 1],
        Tri6 => &[0, 2, 1, 5, 4, 3],
        Quad4 => &[0, 3, 2, 1],
        Quad8 => &[0, 3, 2, 1, 7, 6, 5, 4],
        Tet4 => &[0, 2, 1, 3],
        Tet10 => &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
        Hex8 => &[0, 3, 2, 1, 4, 7, 6, 5],
        Line2 => &[1, 0],
        Line3 => &[1, 0, 2],
    }
}

pub(super) fn build(f: FileData, path: &Path) -> Result<Mesh, MeshError> {
    let perr =
        |line: usize, offset: Option<usize>, section: &str, message: String| MeshError::Parse {
            path: path.to_path_buf(),
            line,
            section: section.into(),
            message: match offset {
                Some(o) => format!("at byte offset {o}: {message}"),
                None => message,
            },
        };
    if !f.nodes_seen {
        return Err(perr(
            0,
            None,
            "$Nodes",
            "the file has no $Nodes section".into(),
        ));
    }
    if !f.elements_seen {
        return Err(perr(
            0,
            None,
            "$Elements",
            "the file has no $Elements section".into(),
        ));
    }
    let dim = f.blocks.iter().map(|b| b.dim).max().unwrap_or(0);
    if dim < 2 {
        return Err(perr(
            0,
            None,
            "$Elements",
            "no 2D or 3D elements: nothing to make cells of".into(),
        ));
    }
    let mut tag_index: HashMap<u64, usize> = HashMap::with_capacity(f.node_tags.len());
    for (i, &t) in f.node_tags.iter().enumerate() {
        if tag_index.insert(t, i).is_some() {
            return Err(perr(
                0,
                None,
                "$Nodes",
                format!("node tag {t} appears twice"),
            ));
        }
    }
    let block_where = |b: &ElementBlock| {
        // Binary blocks have no meaningful line: report the offset.
        if b.line == 0 {
            (0, Some(b.offset))
        } else {
            (b.line, None)
        }
    };
    let lookup = |b: &ElementBlock, t: u64| -> Result<usize, MeshError> {
        tag_index.get(&t).copied().ok_or_else(|| {
            let (l, o) = block_where(b);
            perr(
                l,
                o,
                "$Elements",
                format!("element block (entity {} of dimension {}) refers to node tag {t}, which $Nodes does not define", b.entity, b.dim),
            )
        })
    };
    // Nodes used by cells, in file order.
    let mut used = vec![false; f.node_tags.len()];
    for b in f.blocks.iter().filter(|b| b.dim == dim) {
        for &t in &b.tags {
            used[lookup(b, t)?] = true;
        }
    }
    let mut new_index = vec![usize::MAX; f.node_tags.len()];
    let mut mesh = Mesh::new(dim as usize);
    for (i, u) in used.iter().enumerate() {
        if *u {
            let x = f.coords[i];
            if dim == 2 && x[2] != 0.0 {
                return Err(MeshError::Invalid(format!(
                    "{}: a 2D mesh must lie in the xy plane, but node {} has z = {}",
                    path.display(),
                    f.node_tags[i],
                    x[2]
                )));
            }
            new_index[i] = mesh.add_node(x);
        }
    }
    let name = |d: i32, p: i32| {
        f.names
            .get(&(d, p))
            .cloned()
            .unwrap_or_else(|| p.to_string())
    };
    let phys = |b: &ElementBlock| {
        f.entity_phys
            .get(&(b.dim, b.entity))
            .cloned()
            .unwrap_or_default()
    };
    let mapped = |b: &ElementBlock, e: usize| -> Result<Vec<usize>, MeshError> {
        b.tags[e * b.nodes_per..(e + 1) * b.nodes_per]
            .iter()
            .map(|&t| {
                let i = lookup(b, t)?;
                if new_index[i] == usize::MAX {
                    let (l, o) = block_where(b);
                    Err(perr(
                        l,
                        o,
                        "$Elements",
                        format!(
                            "an element of dimension {} uses node tag {t}, which no {dim}D cell uses",
                            b.dim
                        ),
                    ))
                } else {
                    Ok(new_index[i])
                }
            })
            .collect()
    };
    let centre = |kind: CellType| -> [f64; 3] {
        match kind {
            CellType::Tri3 | CellType::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
            CellType::Tet4 | CellType::Tet10 => [0.25; 3],
            _ => [0.0; 3],
        }
    };
    let mut group_cells: HashMap<String, (Vec<usize>, Vec<usize>)> = HashMap::new();
    for b in f.blocks.iter().filter(|b| b.dim == dim) {
        let Some(kind) = b.kind else { continue };
        let nel = b.tags.len() / b.nodes_per;
        let groups: Vec<String> = phys(b).iter().map(|&p| name(dim, p)).collect();
        for e in 0..nel {
            let mut nodes = mapped(b, e)?;
            gmsh_to_vtk(kind, &mut nodes);
            let x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            let det = jacobian_det(kind, &x, centre(kind));
            if det.is_nan() || det == 0.0 {
                return Err(MeshError::Invalid(format!(
                    "{}: a {kind} cell (entity {}) is degenerate (zero Jacobian)",
                    path.display(),
                    b.entity
                )));
            }
            if det < 0.0 {
                nodes = reversal(kind).iter().map(|&i| nodes[i]).collect();
            }
            let c = mesh.add_cell(kind, &nodes);
            for g in &groups {
                let e = group_cells.entry(g.clone()).or_default();
                e.0.push(c);
                e.1.extend(nodes.iter().copied());
            }
        }
    }
    // Collected first: `Mesh::add_*_to_group` sorts the whole group on each call.
    for (g, (cells, nodes)) in group_cells {
        mesh.add_cells_to_group(&g, cells);
        mesh.add_nodes_to_group(&g, nodes);
    }
    for b in f.blocks.iter().filter(|b| b.dim < dim) {
        let groups: Vec<String> = phys(b).iter().map(|&p| name(b.dim, p)).collect();
        if groups.is_empty() {
            continue;
        }
        let nel = b.tags.len() / b.nodes_per;
        let mut facets = Vec::new();
        let mut nodes_all = Vec::new();
        for e in 0..nel {
            let mut nodes = mapped(b, e)?;
            nodes_all.extend(nodes.iter().copied());
            if let (true, Some(kind)) = (b.dim == dim - 1, b.kind) {
                gmsh_to_vtk(kind, &mut nodes);
                facets.push(crate::Facet { kind, nodes });
            }
        }
        if !facets.is_empty() {
            let attached = mesh.attach_facets(&facets, None).map_err(|e| {
                let (l, o) = block_where(b);
                perr(
                    l,
                    o,
                    "$Elements",
                    format!("entity {} of dimension {}: {e}", b.entity, b.dim),
                )
            })?;
            for g in &groups {
                mesh.add_facets_to_group(g, attached.iter().map(|a| a.facet.clone()));
            }
        }
        for g in &groups {
            mesh.add_nodes_to_group(g, nodes_all.iter().copied());
        }
    }
    Ok(mesh)
}
