//! Element stiffness kernels and global assembly.
//!
//! `K_e = int_e B^T D B t dV` (t = thickness in 2D, 1 in 3D) with the rule of
//! [`Quadrature::stiffness`]; global `K = sum_e T_e^T K_e T_e` on the free unknowns of a
//! [`DofMap`] (see `dofs`), stored as the upper triangle of a [`SymCsc`]. Element matrices are
//! computed in parallel (rayon) by chunks and scattered sequentially, so the result does not
//! depend on the thread count.

use std::sync::OnceLock;

use alea_mesh::CellType;
use rayon::prelude::*;

use crate::kinematics::point_geometry;
use crate::reference::MAX_NODES;
use crate::{DofMap, FemError, Model, Quadrature, SymCsc};

/// The stiffness rule of `kind`, built once per process (Gauss points come from Newton
/// iterations, too costly to redo for every cell).
fn stiffness_rule(kind: CellType) -> &'static Quadrature {
    const N: usize = 16;
    static RULES: [OnceLock<Quadrature>; N] = [const { OnceLock::new() }; N];
    let i = kind as usize;
    assert!(i < N, "more cell types than stiffness-rule slots");
    RULES[i].get_or_init(|| Quadrature::stiffness(kind))
}

/// `K_e = int_e B^T D B t dV` for cell `c`: row-major, node-major dofs (`nn dim` square).
///
/// Computed node block by node block, `K_ab = int B_a^T (D B_b)`, using the sparsity of the
/// nodal strain operators `B_a` (`n_voigt x dim`, at most two non-zeros per row): about a
/// tenth of the flops of the dense product, for any `D`.
pub fn element_stiffness(model: &Model, c: usize, ke: &mut Vec<f64>) -> Result<(), FemError> {
    let kind = model.mesh.cell_type(c);
    let dim = model.mesh.dim;
    let nodes = model.mesh.cell_nodes(c);
    let nn = nodes.len();
    let m = nn * dim;
    let nv = model.analysis.n_voigt();
    let mut coords = [[0.0; 3]; MAX_NODES];
    for (x, &n) in coords.iter_mut().zip(nodes) {
        *x = model.mesh.coords[n];
    }
    let mat = model.material(c)?;
    let d = mat.hooke(model.analysis);
    let dd = |r: usize, k: usize| d[r * nv + k];
    let t = model.analysis.thickness();
    let q = stiffness_rule(kind);
    ke.clear();
    ke.resize(m * m, 0.0);
    for (xi, w) in q.points.iter().zip(&q.weights) {
        let g = point_geometry(kind, &coords[..nn], *xi);
        if g.det <= 0.0 {
            return Err(FemError::BadJacobian {
                cell: c,
                kind: kind.to_string(),
                det: g.det,
            });
        }
        let f = w * g.det * t;
        for b in 0..nn {
            let [bx, by, bz] = g.grad[b];
            if dim == 2 {
                // Voigt [xx, yy, xy]; B_b columns [bx, 0, by] and [0, by, bx]; db = D B_b.
                let mut db = [[0.0; 2]; 3];
                for (r, row) in db.iter_mut().enumerate() {
                    row[0] = dd(r, 0) * bx + dd(r, 2) * by;
                    row[1] = dd(r, 1) * by + dd(r, 2) * bx;
                }
                for a in 0..=b {
                    let [ax, ay, _] = g.grad[a];
                    for j in 0..2 {
                        ke[2 * a * m + 2 * b + j] += f * (ax * db[0][j] + ay * db[2][j]);
                        ke[(2 * a + 1) * m + 2 * b + j] += f * (ay * db[1][j] + ax * db[2][j]);
                    }
                }
            } else {
                // Voigt [xx, yy, zz, yz, xz, xy]; B_b columns [bx,0,0,0,bz,by],
                // [0,by,0,bz,0,bx], [0,0,bz,by,bx,0]; db = D B_b.
                let mut db = [[0.0; 3]; 6];
                for (r, row) in db.iter_mut().enumerate() {
                    row[0] = dd(r, 0) * bx + dd(r, 4) * bz + dd(r, 5) * by;
                    row[1] = dd(r, 1) * by + dd(r, 3) * bz + dd(r, 5) * bx;
                    row[2] = dd(r, 2) * bz + dd(r, 3) * by + dd(r, 4) * bx;
                }
                for a in 0..=b {
                    let [ax, ay, az] = g.grad[a];
                    for j in 0..3 {
                        ke[3 * a * m + 3 * b + j] +=
                            f * (ax * db[0][j] + az * db[4][j] + ay * db[5][j]);
                        ke[(3 * a + 1) * m + 3 * b + j] +=
                            f * (ay * db[1][j] + az * db[3][j] + ax * db[5][j]);
                        ke[(3 * a + 2) * m + 3 * b + j] +=
                            f * (az * db[2][j] + ay * db[3][j] + ax * db[4][j]);
                    }
                }
            }
        }
    }
    // Upper node blocks are computed; mirror (also inside diagonal blocks, for exact symmetry).
    for i in 0..m {
        for j in 0..i {
            ke[i * m + j] = ke[j * m + i];
        }
    }
    Ok(())
}

/// The sparse pattern of the free unknowns: unknowns of nodes that share a cell are coupled.
/// `extra` adds node couplings (e.g. interface facets already inside cells add nothing).
pub fn stiffness_pattern(model: &Model, dofs: &DofMap) -> SymCsc {
    let mesh = &model.mesh;
    let mut node_adj: Vec<Vec<usize>> = vec![Vec::new(); mesh.num_nodes()];
    for (_, _, nodes) in mesh.cells() {
        for &a in nodes {
            node_adj[a].extend_from_slice(nodes);
        }
    }
    for l in node_adj.iter_mut() {
        l.sort_unstable();
        l.dedup();
    }
    let node_of = dofs.node_of_dof();
    SymCsc::from_couplings(dofs.num_free(), |j, out| {
        for &m in &node_adj[node_of[j]] {
            out.extend(dofs.node_dofs(m));
        }
    })
}

/// Assembled stiffness on the free unknowns and the load `-T^T K u_p` of prescribed
/// displacements.
#[derive(Clone, Debug)]
pub struct Assembled {
    /// Stiffness matrix (upper triangle).
    pub k: SymCsc,
    /// Load vector of the prescribed displacements, on the free unknowns.
    pub f_prescribed: Vec<f64>,
}

/// Assembles the stiffness matrix of `model` on the free unknowns of `dofs`.
pub fn assemble_stiffness(model: &Model, dofs: &DofMap) -> Result<Assembled, FemError> {
    model.check()?;
    let mut k = stiffness_pattern(model, dofs);
    let mut f_prescribed = vec![0.0; dofs.num_free()];
    let ncells = model.mesh.num_cells();
    const CHUNK: usize = 2048;
    let mut blocks: Vec<Result<Vec<f64>, FemError>> = Vec::with_capacity(CHUNK);
    let (mut dl, mut kr, mut fr) = (Vec::new(), Vec::new(), Vec::new());
    for start in (0..ncells).step_by(CHUNK) {
        let end = (start + CHUNK).min(ncells);
        blocks.clear();
        (start..end)
            .into_par_iter()
            .map(|c| {
                let mut ke = Vec::new();
                element_stiffness(model, c, &mut ke).map(|_| ke)
            })
            .collect_into_vec(&mut blocks);
        for (c, ke) in (start..end).zip(blocks.drain(..)) {
            let ke = ke?;
            let nodes = model.mesh.cell_nodes(c);
            dofs.reduce_block(nodes, &ke, &mut dl, &mut kr, &mut fr);
            k.add_block(&dl, &kr);
            for (i, &g) in dl.iter().enumerate() {
                f_prescribed[g] += fr[i];
            }
        }
    }
    Ok(Assembled { k, f_prescribed })
}
