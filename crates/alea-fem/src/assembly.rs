//! Element stiffness kernels and global assembly.
//!
//! `K_e = int_e B^T D B t dV` (t = thickness in 2D, 1 in 3D) with the rule of
//! [`Quadrature::stiffness`]; global `K = sum_e T_e^T K_e T_e` on the free unknowns of a
//! [`DofMap`] (see `dofs`), stored as the upper triangle of a [`SymCsc`]. Element matrices are
//! computed in parallel (rayon) by chunks and scattered sequentially, so the result does not
//! depend on the thread count.

use rayon::prelude::*;

use crate::kinematics::{point_geometry, strain_operator};
use crate::{DofMap, FemError, Model, Quadrature, SymCsc};

/// `K_e = int_e B^T D B t dV` for cell `c`: row-major, node-major dofs (`nn dim` square).
pub fn element_stiffness(model: &Model, c: usize, ke: &mut Vec<f64>) -> Result<(), FemError> {
    let kind = model.mesh.cell_type(c);
    let dim = model.mesh.dim;
    let nn = kind.num_nodes();
    let m = nn * dim;
    let nv = model.analysis.n_voigt();
    let coords = model.cell_coords(c);
    let mat = model.material(c)?;
    let d = mat.hooke(model.analysis);
    let t = model.analysis.thickness();
    let q = Quadrature::stiffness(kind);
    ke.clear();
    ke.resize(m * m, 0.0);
    let mut b = vec![0.0; nv * m];
    let mut db = vec![0.0; nv * m];
    for (xi, w) in q.points.iter().zip(&q.weights) {
        let g = point_geometry(kind, &coords, *xi);
        if g.det <= 0.0 {
            return Err(FemError::BadJacobian {
                cell: c,
                kind: kind.to_string(),
                det: g.det,
            });
        }
        strain_operator(&g, dim, &mut b);
        let f = w * g.det * t;
        // db = D B
        for i in 0..nv {
            for j in 0..m {
                db[i * m + j] = (0..nv).map(|k| d[i * nv + k] * b[k * m + j]).sum();
            }
        }
        for i in 0..m {
            for j in i..m {
                let s: f64 = (0..nv).map(|k| b[k * m + i] * db[k * m + j]).sum();
                ke[i * m + j] += f * s;
            }
        }
    }
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
