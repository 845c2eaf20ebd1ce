//! Structured meshes of a rectangle `[0, lx] x [0, ly]` and a box `[0, lx] x [0, ly] x [0, lz]`.
//!
//! Nodes live on a lattice of half-steps (so that mid-edge nodes of quadratic cells are lattice
//! points) and are created only when a cell uses them. Triangles split each quad along the
//! diagonal (0,0)-(1,1); tetrahedra split each hexahedron into the six Kuhn simplices around the
//! main diagonal, which is conforming across neighbouring hexahedra.
//!
//! Groups: cell group `"domain"`; facet groups `"xmin"`, `"xmax"`, `"ymin"`, `"ymax"` (and
//! `"zmin"`, `"zmax"` for boxes); node groups of the same names hold their nodes.

use std::collections::HashMap;

use crate::{CellType, Facet, Mesh, MeshError};

struct Lattice {
    h: [f64; 3],
    index: HashMap<[usize; 3], usize>,
}

impl Lattice {
    /// Node at lattice point `p` (in half-steps), created on first use.
    fn node(&mut self, mesh: &mut Mesh, p: [usize; 3]) -> usize {
        *self.index.entry(p).or_insert_with(|| {
            mesh.add_node([
                p[0] as f64 * self.h[0] * 0.5,
                p[1] as f64 * self.h[1] * 0.5,
                p[2] as f64 * self.h[2] * 0.5,
            ])
        })
    }
}

fn mid(a: [usize; 3], b: [usize; 3]) -> [usize; 3] {
    [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2]
}

/// Builds the cell from lattice corner points (in half-steps) and adds mid-edge nodes for
/// quadratic types.
fn add_lattice_cell(mesh: &mut Mesh, lat: &mut Lattice, kind: CellType, corners: &[[usize; 3]]) {
    let mut pts: Vec<[usize; 3]> = corners.to_vec();
    match kind {
        CellType::Tri6 => {
            for (a, b) in [(0, 1), (1, 2), (2, 0)] {
                pts.push(mid(corners[a], corners[b]));
            }
        }
        CellType::Quad8 => {
            for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 0)] {
                pts.push(mid(corners[a], corners[b]));
            }
        }
        CellType::Tet10 => {
            for (a, b) in [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)] {
                pts.push(mid(corners[a], corners[b]));
            }
        }
        _ => {}
    }
    let nodes: Vec<usize> = pts.iter().map(|&p| lat.node(mesh, p)).collect();
    mesh.add_cell(kind, &nodes);
}

fn check(n: &[usize], l: &[f64]) -> Result<(), MeshError> {
    if n.contains(&0) {
        return Err(MeshError::Invalid(format!(
            "structured mesh needs at least one cell per direction, got {n:?}"
        )));
    }
    if l.iter().any(|&v| !(v > 0.0 && v.is_finite())) {
        return Err(MeshError::Invalid(format!(
            "structured mesh needs positive finite lengths, got {l:?}"
        )));
    }
    Ok(())
}

/// Adds the boundary facet groups named by side (`xmin`, ... ) and their node groups.
fn add_side_groups(mesh: &mut Mesh, lo: [f64; 3], hi: [f64; 3]) {
    let names = [["xmin", "xmax"], ["ymin", "ymax"], ["zmin", "zmax"]];
    let tol = 1e-9 * (0..mesh.dim).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let boundary = mesh.boundary_facets();
    for d in 0..mesh.dim {
        for (s, name) in names[d].iter().enumerate() {
            let target = if s == 0 { lo[d] } else { hi[d] };
            let facets: Vec<Facet> = boundary
                .iter()
                .filter(|b| {
                    b.facet
                        .nodes
                        .iter()
                        .all(|&n| (mesh.coords[n][d] - target).abs() <= tol)
                })
                .map(|b| b.facet.clone())
                .collect();
            let nodes: Vec<usize> = facets.iter().flat_map(|f| f.nodes.clone()).collect();
            mesh.add_facets_to_group(name, facets);
            mesh.add_nodes_to_group(name, nodes);
        }
    }
    let all: Vec<usize> = (0..mesh.num_cells()).collect();
    mesh.add_cells_to_group("domain", all);
}

/// Structured mesh of `[0, lx] x [0, ly]` with `nx x ny` quads (or `2 nx ny` triangles).
/// `kind` is one of `Tri3`, `Tri6`, `Quad4`, `Quad8`.
pub fn rectangle(
    lx: f64,
    ly: f64,
    nx: usize,
    ny: usize,
    kind: CellType,
) -> Result<Mesh, MeshError> {
    check(&[nx, ny], &[lx, ly])?;
    if !matches!(
        kind,
        CellType::Tri3 | CellType::Tri6 | CellType::Quad4 | CellType::Quad8
    ) {
        return Err(MeshError::Invalid(format!(
            "rectangle() makes 2D cells, not {kind}"
        )));
    }
    let mut mesh = Mesh::new(2);
    let mut lat = Lattice {
        h: [lx / nx as f64, ly / ny as f64, 0.0],
        index: HashMap::new(),
    };
    for j in 0..ny {
        for i in 0..nx {
            let p = |a: usize, b: usize| [2 * (i + a), 2 * (j + b), 0];
            let (p00, p10, p11, p01) = (p(0, 0), p(1, 0), p(1, 1), p(0, 1));
            match kind {
                CellType::Quad4 | CellType::Quad8 => {
                    add_lattice_cell(&mut mesh, &mut lat, kind, &[p00, p10, p11, p01])
                }
                _ => {
                    add_lattice_cell(&mut mesh, &mut lat, kind, &[p00, p10, p11]);
                    add_lattice_cell(&mut mesh, &mut lat, kind, &[p00, p11, p01]);
                }
            }
        }
    }
    add_side_groups(&mut mesh, [0.0; 3], [lx, ly, 0.0]);
    Ok(mesh)
}

/// Structured mesh of `[0, lx] x [0, ly] x [0, lz]` with `nx ny nz` hexahedra (or six
/// tetrahedra per hexahedron). `kind` is one of `Hex8`, `Tet4`, `Tet10`.
pub fn box_mesh(l: [f64; 3], n: [usize; 3], kind: CellType) -> Result<Mesh, MeshError> {
    check(&n, &l)?;
    if !matches!(kind, CellType::Hex8 | CellType::Tet4 | CellType::Tet10) {
        return Err(MeshError::Invalid(format!(
            "box_mesh() makes 3D cells, not {kind}"
        )));
    }
    let mut mesh = Mesh::new(3);
    let mut lat = Lattice {
        h: [l[0] / n[0] as f64, l[1] / n[1] as f64, l[2] / n[2] as f64],
        index: HashMap::new(),
    };
    // The six Kuhn tetrahedra: paths 000 -> e_a -> e_a + e_b -> 111.
    const PERMS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                let p = |a: usize, b: usize, c: usize| [2 * (i + a), 2 * (j + b), 2 * (k + c)];
                if kind == CellType::Hex8 {
                    let c = [
                        p(0, 0, 0),
                        p(1, 0, 0),
                        p(1, 1, 0),
                        p(0, 1, 0),
                        p(0, 0, 1),
                        p(1, 0, 1),
                        p(1, 1, 1),
                        p(0, 1, 1),
                    ];
                    add_lattice_cell(&mut mesh, &mut lat, kind, &c);
                    continue;
                }
                for perm in PERMS {
                    let mut off = [0usize; 3];
                    let mut corners = vec![p(0, 0, 0)];
                    for &axis in &perm {
                        off[axis] = 1;
                        corners.push(p(off[0], off[1], off[2]));
                    }
                    // Orient positively: the sign of det[c1-c0, c2-c0, c3-c0] follows the
                    // parity of the permutation.
                    let even = matches!(perm, [0, 1, 2] | [1, 2, 0] | [2, 0, 1]);
                    if !even {
                        corners.swap(1, 2);
                    }
                    add_lattice_cell(&mut mesh, &mut lat, kind, &corners);
                }
            }
        }
    }
    add_side_groups(&mut mesh, [0.0; 3], l);
    Ok(mesh)
}
