//! The mesh of a random field over a substructure's cells (`[[field]] substructure = ...`) and
//! the value of the field on each finite-element cell, the Young's modulus of the cell then
//! being the substructure's `young` expression at that value (module `random_field`).
//!
//! Two discretisations, both P1 on simplices (the Galerkin KL of `alea_uq::field`):
//!
//! * **On the cells' corners** (default): the corner nodes of the substructure's cells, each
//!   cell split into simplices - a quadrilateral along its first diagonal into 2 triangles, a
//!   hexahedron along its main diagonal (VTK corners 0 - 6) into Kuhn's 6 tetrahedra, a wedge
//!   into 3 and a pyramid into 2 tetrahedra. The splits of neighbouring cells need not match:
//!   the Galerkin KL uses only `L2` products, for which discontinuous hat functions are a valid
//!   space. A cell's value is the **mean of the P1 field over the cell**, `u_c = sum_t |t| (sum_{i
//!   in t} u_i / k) / |c|` over its simplices `t` of `k` nodes.
//! * **On a grid** (`grid = [nx, ny(, nz)]`): boxes of a regular grid over the substructure's
//!   bounding box, those meeting the bounding box of at least one cell kept (their union `D'`
//!   covers the substructure), each split into Kuhn's 2 triangles or 6 tetrahedra (conforming:
//!   every box is split along its diagonal from its lowest corner). A cell's value is the **P1
//!   field at its centroid**: with `s_1 >= s_2 (>= s_3)` the centroid's coordinates in its box
//!   sorted, in the simplex of that axis order, weights `1 - s_1, s_1 - s_2, (s_2 - s_3,) s_last`.
//!   For a mesh too fine for the dense KL problem (at most `MAX_FIELD_NODES` nodes), or a 3D
//!   one. The restriction to the substructure of a field on `D'` has the stated covariance; the
//!   truncation's fraction is of `sigma^2 |D'|`.

use std::collections::BTreeMap;

use alea_mesh::Mesh;
use alea_uq::field::{FieldCells, FieldMesh};

/// Largest number of nodes of a field mesh, along an interface or over cells (the KL problem
/// is dense: three `n x n` matrices, about 100 MB at this size, and an `O(n^3)` eigensolver of a
/// few seconds).
pub const MAX_FIELD_NODES: usize = 2000;

/// A field mesh and, per finite-element cell, the field nodes and weights of the cell's value.
pub(crate) type CellField = (FieldMesh, Vec<Vec<(usize, f64)>>);

/// Volume (3 nodes: area) of the simplex `t` of `nodes`.
fn simplex_measure(nodes: &[[f64; 3]], t: &[usize]) -> f64 {
    let d = |k: usize| -> [f64; 3] {
        let (p, q) = (nodes[t[0]], nodes[t[k]]);
        [q[0] - p[0], q[1] - p[1], q[2] - p[2]]
    };
    if t.len() == 3 {
        let (a, b) = (d(1), d(2));
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
    } else {
        let (a, b, c) = (d(1), d(2), d(3));
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))
            .abs()
            / 6.0
    }
}

/// Kuhn's simplices of the unit box in `dim` dimensions: for each order of the axes, the
/// corners `(0, .., 0)` then one axis set to 1 at a time; corners as bit masks (bit `d`: axis
/// `d` at 1).
fn kuhn(dim: usize) -> Vec<(Vec<usize>, Vec<usize>)> {
    let orders: Vec<Vec<usize>> = if dim == 2 {
        vec![vec![0, 1], vec![1, 0]]
    } else {
        vec![
            vec![0, 1, 2],
            vec![0, 2, 1],
            vec![1, 0, 2],
            vec![1, 2, 0],
            vec![2, 0, 1],
            vec![2, 1, 0],
        ]
    };
    orders
        .into_iter()
        .map(|order| {
            let mut mask = 0;
            let mut corners = vec![0];
            for &a in &order {
                mask |= 1 << a;
                corners.push(mask);
            }
            (order, corners)
        })
        .collect()
}

/// The simplices of a cell with `corners` corner nodes (field indices) in a `dim`-D mesh.
fn split_cell(dim: usize, corners: &[usize]) -> Result<Vec<Vec<usize>>, String> {
    let c = corners;
    Ok(match (dim, c.len()) {
        (2, 3) | (3, 4) => vec![c.to_vec()],
        (2, 4) => vec![vec![c[0], c[1], c[2]], vec![c[0], c[2], c[3]]],
        (3, 5) => vec![vec![c[0], c[1], c[2], c[4]], vec![c[0], c[2], c[3], c[4]]],
        (3, 6) => vec![
            vec![c[0], c[1], c[2], c[3]],
            vec![c[1], c[2], c[3], c[4]],
            vec![c[2], c[3], c[4], c[5]],
        ],
        (3, 8) => {
            // VTK hexahedron corners by bit mask (x = 1, y = 2, z = 4).
            let vtk = [0, 1, 3, 2, 4, 5, 7, 6];
            kuhn(3)
                .into_iter()
                .map(|(_, masks)| masks.iter().map(|&m| c[vtk[m]]).collect())
                .collect()
        }
        (_, n) => {
            return Err(format!(
                "a {dim}D cell with {n} corners cannot carry a field"
            ));
        }
    })
}

/// The field on the corners of `mesh`'s cells (module doc).
pub(crate) fn on_corners(mesh: &Mesh) -> Result<CellField, String> {
    let dim = mesh.dim;
    let mut index = BTreeMap::new();
    let mut nodes = Vec::new();
    let mut simplices: Vec<Vec<usize>> = Vec::new();
    let mut means = Vec::with_capacity(mesh.num_cells());
    for c in 0..mesh.num_cells() {
        let kind = mesh.cell_type(c);
        let corners: Vec<usize> = mesh.cell_nodes(c)[..kind.num_corners()]
            .iter()
            .map(|&g| {
                *index.entry(g).or_insert_with(|| {
                    nodes.push(mesh.coords[g]);
                    nodes.len() - 1
                })
            })
            .collect();
        let split = split_cell(dim, &corners).map_err(|m| format!("cell {c}: {m}"))?;
        let measures: Vec<f64> = split.iter().map(|t| simplex_measure(&nodes, t)).collect();
        let total: f64 = measures.iter().sum();
        let mut w: BTreeMap<usize, f64> = BTreeMap::new();
        for (t, m) in split.iter().zip(&measures) {
            let share = if total > 0.0 {
                m / total
            } else {
                1.0 / split.len() as f64
            };
            for &i in t {
                *w.entry(i).or_insert(0.0) += share / t.len() as f64;
            }
        }
        means.push(w.into_iter().collect());
        simplices.extend(split);
    }
    if nodes.len() > MAX_FIELD_NODES {
        return Err(format!(
            "the field's mesh (the substructure's cell corners) has {} nodes; at most {MAX_FIELD_NODES} (the KL problem is dense): give grid = [nx, ny{}] to discretise the field on a coarser grid",
            nodes.len(),
            if dim == 3 { ", nz" } else { "" }
        ));
    }
    Ok((field_mesh(dim, nodes, simplices)?, means))
}

fn field_mesh(
    dim: usize,
    nodes: Vec<[f64; 3]>,
    simplices: Vec<Vec<usize>>,
) -> Result<FieldMesh, String> {
    let cells = if dim == 2 {
        FieldCells::Triangles(simplices.iter().map(|t| [t[0], t[1], t[2]]).collect())
    } else {
        FieldCells::Tetrahedra(simplices.iter().map(|t| [t[0], t[1], t[2], t[3]]).collect())
    };
    FieldMesh::new(nodes, cells).map_err(|e| e.to_string())
}

/// Number of grid nodes of `counts` boxes per axis (an upper bound of the kept ones).
pub(crate) fn grid_nodes(counts: &[usize]) -> usize {
    counts
        .iter()
        .map(|n| n.saturating_add(1))
        .fold(1usize, usize::saturating_mul)
}

/// The field on a grid of `counts` boxes over `mesh`'s bounding box (module doc).
pub(crate) fn on_grid(mesh: &Mesh, counts: &[usize]) -> Result<CellField, String> {
    let dim = mesh.dim;
    if counts.len() != dim || counts.contains(&0) {
        return Err(format!(
            "a {dim}D substructure needs {dim} box counts >= 1, got {counts:?}"
        ));
    }
    if grid_nodes(counts) > MAX_FIELD_NODES {
        return Err(format!(
            "{} grid nodes; at most {MAX_FIELD_NODES} (the KL problem is dense)",
            grid_nodes(counts)
        ));
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for x in &mesh.coords {
        for d in 0..dim {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let h: Vec<f64> = (0..dim)
        .map(|d| (hi[d] - lo[d]) / counts[d] as f64)
        .collect();
    if h.iter().any(|v| !(*v > 0.0)) {
        return Err("the substructure is flat along an axis".into());
    }
    // Each cell's centroid: its box and its coordinates in the box.
    let mut located = Vec::with_capacity(mesh.num_cells());
    let mut kept: BTreeMap<Vec<usize>, ()> = BTreeMap::new();
    for c in 0..mesh.num_cells() {
        let nodes = mesh.cell_nodes(c);
        let kind = mesh.cell_type(c);
        let corners = &nodes[..kind.num_corners()];
        let mut x = [0.0; 3];
        for &g in corners {
            for d in 0..3 {
                x[d] += mesh.coords[g][d] / corners.len() as f64;
            }
        }
        let mut bx = Vec::with_capacity(dim);
        let mut s = Vec::with_capacity(dim);
        for d in 0..dim {
            let t = (x[d] - lo[d]) / h[d];
            let i = (t.floor().max(0.0) as usize).min(counts[d] - 1);
            bx.push(i);
            s.push((t - i as f64).clamp(0.0, 1.0));
        }
        // Every box the cell's bounding box meets, so that the kept boxes cover the cell.
        let mut range = Vec::with_capacity(dim);
        for d in 0..dim {
            let (mut a, mut b) = (f64::INFINITY, f64::NEG_INFINITY);
            for &g in nodes {
                a = a.min(mesh.coords[g][d]);
                b = b.max(mesh.coords[g][d]);
            }
            let box_of =
                |v: f64| (((v - lo[d]) / h[d]).floor().max(0.0) as usize).min(counts[d] - 1);
            range.push(box_of(a)..=box_of(b));
        }
        let mut stack = vec![Vec::new()];
        for r in &range {
            stack = stack
                .into_iter()
                .flat_map(|p: Vec<usize>| {
                    r.clone().map(move |i| {
                        let mut q = p.clone();
                        q.push(i);
                        q
                    })
                })
                .collect();
        }
        for b in stack {
            kept.insert(b, ());
        }
        located.push((bx, s));
    }
    // Nodes of the kept boxes, simplices by Kuhn's split.
    let mut index: BTreeMap<Vec<usize>, usize> = BTreeMap::new();
    let mut nodes = Vec::new();
    let mut node = |ix: Vec<usize>| -> usize {
        *index.entry(ix.clone()).or_insert_with(|| {
            let mut p = [0.0; 3];
            for d in 0..dim {
                p[d] = lo[d] + ix[d] as f64 * h[d];
            }
            nodes.push(p);
            nodes.len() - 1
        })
    };
    let corner = |bx: &[usize], mask: usize| -> Vec<usize> {
        (0..dim).map(|d| bx[d] + ((mask >> d) & 1)).collect()
    };
    let kuhn = kuhn(dim);
    let mut simplices = Vec::new();
    for bx in kept.keys() {
        for (_, masks) in &kuhn {
            simplices.push(
                masks
                    .iter()
                    .map(|&m| node(corner(bx, m)))
                    .collect::<Vec<_>>(),
            );
        }
    }
    // Each cell's value: the P1 field at its centroid, in the Kuhn simplex of its sorted
    // coordinates.
    let mut weights = Vec::with_capacity(located.len());
    for (bx, s) in &located {
        let mut order: Vec<usize> = (0..dim).collect();
        order.sort_by(|&a, &b| s[b].total_cmp(&s[a]).then(a.cmp(&b)));
        let mut mask = 0;
        let mut w = vec![(node(corner(bx, 0)), 1.0 - s[order[0]])];
        for (k, &a) in order.iter().enumerate() {
            mask |= 1 << a;
            let next = order.get(k + 1).map_or(0.0, |&b| s[b]);
            w.push((node(corner(bx, mask)), s[a] - next));
        }
        weights.push(w);
    }
    Ok((field_mesh(dim, nodes, simplices)?, weights))
}

#[cfg(test)]
mod tests {
    use super::*;
    use alea_mesh::CellType;

    /// The cell values reproduce a linear field exactly: on the corners (the mean of a linear
    /// function over a cell is its value at the cell's centroid, for simplices and for
    /// parallelepipeds split into simplices) and on a grid (P1 interpolation of a linear
    /// function is exact), in 2D and 3D.
    #[test]
    fn cell_values_are_exact_for_linear_fields() {
        let lin = |p: &[f64; 3]| 1.0 + 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2];
        let rect = alea_mesh::generate::rectangle(3.0, 2.0, 5, 3, CellType::Quad4).unwrap();
        let cube =
            alea_mesh::generate::box_mesh([2.0, 1.0, 1.5], [3, 2, 2], CellType::Hex8).unwrap();
        for mesh in [rect, cube] {
            let grid = vec![4; mesh.dim];
            for (fmesh, w) in [on_corners(&mesh).unwrap(), on_grid(&mesh, &grid).unwrap()] {
                let nodal: Vec<f64> = fmesh.nodes().iter().map(lin).collect();
                for c in 0..mesh.num_cells() {
                    let xs: Vec<[f64; 3]> =
                        mesh.cell_nodes(c).iter().map(|&g| mesh.coords[g]).collect();
                    let mut x = [0.0; 3];
                    for p in &xs {
                        for d in 0..3 {
                            x[d] += p[d] / xs.len() as f64;
                        }
                    }
                    let sum: f64 = w[c].iter().map(|(_, wi)| wi).sum();
                    let v: f64 = w[c].iter().map(|&(i, wi)| wi * nodal[i]).sum();
                    assert!((sum - 1.0).abs() < 1e-12, "cell {c}: weights sum to {sum}");
                    assert!((v - lin(&x)).abs() < 1e-12, "cell {c}: {v} vs {}", lin(&x));
                }
                let vol: f64 = if mesh.dim == 2 { 6.0 } else { 3.0 };
                assert!(
                    fmesh.measure() >= vol - 1e-9,
                    "field mesh measure {} below the substructure's {vol}",
                    fmesh.measure()
                );
            }
        }
    }

    #[test]
    fn too_many_nodes_and_bad_grids_are_refused() {
        let rect = alea_mesh::generate::rectangle(3.0, 2.0, 5, 3, CellType::Quad4).unwrap();
        assert!(on_grid(&rect, &[2]).is_err());
        assert!(on_grid(&rect, &[2, 0]).is_err());
        assert!(on_grid(&rect, &[100, 100]).is_err());
    }
}
