//! The mesh of a set of blocks: node numbering on each block's lattice, merging of the nodes of
//! shared edges (checked), cells, groups, and the final checks (duplicate nodes, folded cells).

use std::collections::HashMap;

use super::block::Block;
use super::curve::dist;
use super::mapping::{Ready, half_lattice, prepare};
use crate::{CellType, Facet, Mesh, MeshError};

struct EdgeEntry {
    key: (usize, usize),
    mid: [f64; 2],
    nodes: Vec<usize>, // canonical direction (from the smaller vertex id), 2n+1 entries
    block: usize,
    side: usize,
    forward: bool, // direction of the first block's traversal
    users: usize,
}

/// Meshes a set of blocks (see the module documentation); `kind` is `Quad4`, `Quad8`, `Tri3` or
/// `Tri6`.
///
/// ```
/// use alea_mesh::CellType;
/// use alea_mesh::generate::{Block, Curve, multiblock};
///
/// // A 2 x 1 base and, on top of it, a block with an arched top edge (from (2, 2) through
/// // (1, 2.5) to (0, 2)) whose cells shrink toward the arch. They share the edge y = 1.
/// let base = Block::new([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]], [4, 2])
///     .group("base")
///     .edge_group(0, "bottom");
/// let arch = Block::new([[0.0, 1.0], [2.0, 1.0], [2.0, 2.0], [0.0, 2.0]], [4, 3])
///     .edge(2, Curve::ArcThrough([1.0, 2.5]))
///     .grading(1.0, 0.5)
///     .group("arch")
///     .edge_group(2, "crown");
/// let mesh = multiblock(&[base, arch], CellType::Quad8)?;
/// assert_eq!(mesh.num_cells(), 8 + 12);
/// assert_eq!(mesh.facet_group("crown")?.len(), 4);
/// assert_eq!(mesh.group_nodes("bottom")?.len(), 9); // 5 corners + 4 mid-side nodes
/// # Ok::<(), alea_mesh::MeshError>(())
/// ```
///
/// # Errors
/// [`MeshError::Invalid`] for bad block input (zero counts, non-positive gradings, arcs whose
/// ends are not on the circle, degenerate blocks), shared edges with different counts or node
/// positions, unmerged coincident nodes, and folded mappings (non-positive Jacobian).
pub fn multiblock(blocks: &[Block], kind: CellType) -> Result<Mesh, MeshError> {
    if !matches!(
        kind,
        CellType::Quad4 | CellType::Quad8 | CellType::Tri3 | CellType::Tri6
    ) {
        return Err(MeshError::Invalid(format!(
            "the multi-block generator makes 2D cells (QUAD4, QUAD8, TRI3, TRI6), not {kind}"
        )));
    }
    if blocks.is_empty() {
        return Err(MeshError::Invalid("no blocks given".into()));
    }
    let ready: Vec<Ready> = blocks
        .iter()
        .enumerate()
        .map(|(i, b)| prepare(i, b))
        .collect::<Result<_, _>>()?;
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for b in &ready {
        for p in &b.corners {
            for d in 0..2 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    let tol = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]);

    let mut coords: Vec<[f64; 2]> = Vec::new();
    let mut vertices: Vec<usize> = Vec::new(); // node ids of distinct corners
    let mut edges: Vec<EdgeEntry> = Vec::new();
    let mut cells: Vec<(usize, Vec<usize>)> = Vec::new(); // (block, nodes)
    let mut facets: Vec<(String, Facet)> = Vec::new();
    let quadratic = kind.order() == 2;

    for b in &ready {
        let bi = b.index;
        let [ns, nt] = b.n;
        let hs = half_lattice(ns, b.grading[0]);
        let ht = half_lattice(nt, b.grading[1]);
        let (ms, mt) = (2 * ns + 1, 2 * nt + 1);
        let pos = |i: usize, j: usize| -> [f64; 2] {
            match (i, j) {
                (0, 0) => b.corners[0],
                (i, 0) if i == ms - 1 => b.corners[1],
                (i, j) if i == ms - 1 && j == mt - 1 => b.corners[2],
                (0, j) if j == mt - 1 => b.corners[3],
                _ => b.coons(hs[i], ht[j]),
            }
        };
        let mut id = vec![usize::MAX; ms * mt];
        let at = |i: usize, j: usize| i + ms * j;
        // Corners.
        let corner_lattice = [(0, 0), (ms - 1, 0), (ms - 1, mt - 1), (0, mt - 1)];
        let mut vid = [0usize; 4];
        for k in 0..4 {
            let p = b.corners[k];
            let v = match vertices.iter().position(|&n| dist(coords[n], p) <= tol) {
                Some(v) => v,
                None => {
                    coords.push(p);
                    vertices.push(coords.len() - 1);
                    vertices.len() - 1
                }
            };
            vid[k] = v;
            let (i, j) = corner_lattice[k];
            id[at(i, j)] = vertices[v];
        }
        // Edges: lattice points from corner k to corner k+1.
        let edge_lattice = |k: usize| -> Vec<(usize, usize)> {
            match k {
                0 => (0..ms).map(|i| (i, 0)).collect(),
                1 => (0..mt).map(|j| (ms - 1, j)).collect(),
                2 => (0..ms).rev().map(|i| (i, mt - 1)).collect(),
                _ => (0..mt).rev().map(|j| (0, j)).collect(),
            }
        };
        let mut edge_nodes: [Vec<usize>; 4] = Default::default();
        for k in 0..4 {
            let (va, vb) = (vid[k], vid[(k + 1) % 4]);
            let ku = b.user_edge[k];
            if va == vb {
                return Err(MeshError::Invalid(format!(
                    "block {bi}: edge {ku} has coincident end corners (collapsed edges are not supported)"
                )));
            }
            let lat = edge_lattice(k);
            let key = (va.min(vb), va.max(vb));
            let forward = va < vb;
            let mid = b.edge_at(k, 0.5);
            let existing = edges.iter_mut().find(|e| {
                e.key == key
                    && dist(e.mid, mid)
                        <= tol.max(1e-7 * dist(b.corners[k], b.corners[(k + 1) % 4]))
            });
            let nodes: Vec<usize> = if let Some(e) = existing {
                if e.users >= 2 || e.forward == forward {
                    return Err(MeshError::Invalid(format!(
                        "block {bi} edge {ku} coincides with block {} edge {} but the blocks overlap (an edge can be shared by two blocks lying on opposite sides of it)",
                        e.block, e.side
                    )));
                }
                e.users += 1;
                if e.nodes.len() != lat.len() {
                    return Err(MeshError::Invalid(format!(
                        "block {bi} edge {ku} is shared with block {} edge {}, but has {} cells there instead of {}",
                        e.block,
                        e.side,
                        (lat.len() - 1) / 2,
                        (e.nodes.len() - 1) / 2
                    )));
                }
                let mut n = e.nodes.clone();
                if !forward {
                    n.reverse();
                }
                for (q, &(i, j)) in lat.iter().enumerate() {
                    let p = pos(i, j);
                    if dist(p, coords[n[q]]) > 1e-6 * dist(b.corners[k], b.corners[(k + 1) % 4]) {
                        return Err(MeshError::Invalid(format!(
                            "block {bi} edge {ku} is shared with block {} edge {}, but its node {q} is at {p:?} instead of {:?} (different grading or curve parametrisation)",
                            e.block, e.side, coords[n[q]]
                        )));
                    }
                }
                n
            } else {
                let mut n = Vec::with_capacity(lat.len());
                for (q, &(i, j)) in lat.iter().enumerate() {
                    if q == 0 || q == lat.len() - 1 {
                        n.push(id[at(i, j)]);
                    } else {
                        coords.push(pos(i, j));
                        n.push(coords.len() - 1);
                    }
                }
                let mut canon = n.clone();
                if !forward {
                    canon.reverse();
                }
                edges.push(EdgeEntry {
                    key,
                    mid,
                    nodes: canon,
                    block: bi,
                    side: ku,
                    forward,
                    users: 1,
                });
                n
            };
            for (q, &(i, j)) in lat.iter().enumerate() {
                id[at(i, j)] = nodes[q];
            }
            edge_nodes[k] = nodes;
        }
        // Interior lattice points.
        for j in 1..mt - 1 {
            for i in 1..ms - 1 {
                let wanted = match kind {
                    CellType::Quad4 | CellType::Tri3 => i % 2 == 0 && j % 2 == 0,
                    CellType::Quad8 => i % 2 == 0 || j % 2 == 0,
                    _ => true,
                };
                if wanted {
                    coords.push(pos(i, j));
                    id[at(i, j)] = coords.len() - 1;
                }
            }
        }
        // Cells.
        for j in 0..nt {
            for i in 0..ns {
                let (i0, j0) = (2 * i, 2 * j);
                let n = |a: usize, c: usize| id[at(i0 + a, j0 + c)];
                let (a, bb, c, d) = (n(0, 0), n(2, 0), n(2, 2), n(0, 2));
                match kind {
                    CellType::Quad4 => cells.push((bi, vec![a, bb, c, d])),
                    CellType::Quad8 => {
                        cells.push((bi, vec![a, bb, c, d, n(1, 0), n(2, 1), n(1, 2), n(0, 1)]))
                    }
                    CellType::Tri3 => {
                        cells.push((bi, vec![a, bb, c]));
                        cells.push((bi, vec![a, c, d]));
                    }
                    _ => {
                        cells.push((bi, vec![a, bb, c, n(1, 0), n(2, 1), n(1, 1)]));
                        cells.push((bi, vec![a, c, d, n(1, 1), n(1, 2), n(0, 1)]));
                    }
                }
            }
        }
        // Facets of tagged edges, in the (outward) direction of the block edge.
        for (group, en) in b.edge_groups.iter().zip(&edge_nodes) {
            if let Some(name) = group {
                for q in (0..en.len() - 1).step_by(2) {
                    let f = if quadratic {
                        Facet {
                            kind: CellType::Line3,
                            nodes: vec![en[q], en[q + 2], en[q + 1]],
                        }
                    } else {
                        Facet {
                            kind: CellType::Line2,
                            nodes: vec![en[q], en[q + 2]],
                        }
                    };
                    facets.push((name.clone(), f));
                }
            }
        }
    }

    // Compact: drop lattice nodes no cell uses.
    let mut new_id = vec![usize::MAX; coords.len()];
    let mut mesh = Mesh::new(2);
    for (_, nodes) in &cells {
        for &n in nodes {
            if new_id[n] == usize::MAX {
                new_id[n] = mesh.add_node([coords[n][0], coords[n][1], 0.0]);
            }
        }
    }
    check_duplicates(&mesh, tol)?;
    // Groups are collected first: `Mesh::add_*_to_group` sorts the whole group on each call.
    let mut cell_groups: HashMap<&str, Vec<usize>> = HashMap::new();
    for (bi, nodes) in &cells {
        let n: Vec<usize> = nodes.iter().map(|&i| new_id[i]).collect();
        let c = mesh.add_cell(kind, &n);
        let jmin = mesh.cell_min_jacobian(c);
        if jmin.is_nan() || jmin <= 0.0 {
            return Err(MeshError::Invalid(format!(
                "block {bi}: cell with corners {:?} has a non-positive Jacobian ({jmin:e}): the block mapping folds (check the corners' order and the edge curves)",
                n[..kind.num_corners()]
                    .iter()
                    .map(|&i| mesh.coords[i])
                    .collect::<Vec<_>>()
            )));
        }
        if let Some(g) = &ready[*bi].cell_group {
            cell_groups.entry(g.as_str()).or_default().push(c);
        }
    }
    for (g, cells) in cell_groups {
        mesh.add_cells_to_group(g, cells);
    }
    let mut facet_groups: HashMap<String, Vec<Facet>> = HashMap::new();
    for (name, f) in facets {
        let f = Facet {
            kind: f.kind,
            nodes: f.nodes.iter().map(|&i| new_id[i]).collect(),
        };
        facet_groups.entry(name).or_default().push(f);
    }
    for (name, facets) in facet_groups {
        let nodes: Vec<usize> = facets.iter().flat_map(|f| f.nodes.clone()).collect();
        mesh.add_nodes_to_group(&name, nodes);
        mesh.add_facets_to_group(&name, facets);
    }
    Ok(mesh)
}

/// Error if two distinct nodes are closer than `tol` (hash grid of cell size `2 tol`: a close
/// pair lies in the same or a neighbouring cell).
fn check_duplicates(mesh: &Mesh, tol: f64) -> Result<(), MeshError> {
    let h = 2.0 * tol.max(f64::MIN_POSITIVE);
    let cell = |x: [f64; 3]| [(x[0] / h).floor() as i64, (x[1] / h).floor() as i64];
    let mut grid: HashMap<[i64; 2], Vec<usize>> = HashMap::with_capacity(mesh.num_nodes());
    for (i, &x) in mesh.coords.iter().enumerate() {
        let [cx, cy] = cell(x);
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(others) = grid.get(&[cx + dx, cy + dy]) {
                    for &j in others {
                        let y = mesh.coords[j];
                        if (x[0] - y[0]).abs() <= tol && (x[1] - y[1]).abs() <= tol {
                            return Err(MeshError::Invalid(format!(
                                "two distinct nodes at {x:?}: blocks meet along an edge without sharing it (different curves, counts or corners)"
                            )));
                        }
                    }
                }
            }
        }
        grid.entry([cx, cy]).or_default().push(i);
    }
    Ok(())
}
