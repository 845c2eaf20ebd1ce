//! Interface geometry: node-to-node pairing of the two sides, lumped interface weights and
//! nodal normals.
//!
//! Side nodes come from a facet group of each substructure's mesh. Each side-1 node is paired
//! with the nearest side-2 node; the pairing must be one-to-one and every distance within the
//! tolerance (default `1e-6` times the interface's bounding-box diagonal), otherwise
//! [`LatinError::Unmatched`] names the interface and the worst distance.
//!
//! The interface mass `M_Gamma,ij = int N_i N_j dS` (times the thickness in 2D) is lumped with
//! the HRZ rule (diagonal proportional to the consistent diagonal, scaled to the facet measure),
//! which keeps every weight positive for quadratic facets too. The normal at a node is the
//! measure-weighted mean of the outward normals (with respect to side 1's cells) of the side-1
//! facets around it.

use alea_fem::{Quadrature, kinematics::facet_geometry};
use alea_mesh::Mesh;

use crate::LatinError;

/// Lumped weights and normals of the nodes of one facet group.
#[derive(Clone, Debug)]
pub struct SideGeometry {
    /// Mesh nodes of the side (sorted).
    pub nodes: Vec<usize>,
    /// Lumped interface weight of each node (length in 2D x thickness, area in 3D).
    pub weights: Vec<f64>,
    /// Unit outward normal at each node.
    pub normals: Vec<[f64; 3]>,
}

/// Computes the side geometry of facet group `group` of `mesh`.
pub fn side_geometry(
    mesh: &Mesh,
    group: &str,
    thickness: f64,
) -> Result<SideGeometry, alea_mesh::MeshError> {
    let facets = mesh.attach_facets(mesh.facet_group(group)?, None)?;
    let mut nodes: Vec<usize> = facets.iter().flat_map(|b| b.facet.nodes.clone()).collect();
    nodes.sort_unstable();
    nodes.dedup();
    let pos = |n: usize| nodes.binary_search(&n).expect("node of the group");
    let mut weights = vec![0.0; nodes.len()];
    let mut normals = vec![[0.0; 3]; nodes.len()];
    let th = if mesh.dim == 2 { thickness } else { 1.0 };
    for bf in &facets {
        let f = &bf.facet;
        let coords: Vec<[f64; 3]> = f.nodes.iter().map(|&n| mesh.coords[n]).collect();
        let q = Quadrature::for_cell(f.kind, 2 * f.kind.order() + 1);
        let nn = f.nodes.len();
        let mut diag = vec![0.0; nn];
        let mut measure = 0.0;
        let mut nsum = [0.0; 3];
        for (xi, w) in q.points.iter().zip(&q.weights) {
            let g = facet_geometry(f.kind, &coords, *xi);
            let dm = w * g.jac * th;
            measure += dm;
            for a in 0..nn {
                diag[a] += dm * g.n[a] * g.n[a];
            }
            for c in 0..3 {
                nsum[c] += dm * g.normal[c];
            }
        }
        let dsum: f64 = diag.iter().sum();
        for (a, &node) in f.nodes.iter().enumerate() {
            let i = pos(node);
            weights[i] += diag[a] * measure / dsum;
            for c in 0..3 {
                normals[i][c] += nsum[c] * diag[a] / dsum;
            }
        }
    }
    for nrm in normals.iter_mut() {
        let l = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
        if l > 0.0 {
            for v in nrm.iter_mut() {
                *v /= l;
            }
        }
    }
    Ok(SideGeometry {
        nodes,
        weights,
        normals,
    })
}

/// Pairs side-1 nodes with side-2 nodes by position: returns, for each side-1 node index `i`,
/// the index `j` into `side2` of its partner.
pub fn pair_nodes(
    name: &str,
    x1: &[[f64; 3]],
    x2: &[[f64; 3]],
    tol: Option<f64>,
) -> Result<Vec<usize>, LatinError> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for x in x1.iter().chain(x2) {
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let diag = (0..3)
        .map(|d| (hi[d] - lo[d]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt();
    let tol = tol.unwrap_or(1e-6 * diag.max(f64::MIN_POSITIVE));
    // Sort side 2 by x to prune the search.
    let mut order: Vec<usize> = (0..x2.len()).collect();
    order.sort_by(|&a, &b| x2[a][0].total_cmp(&x2[b][0]));
    let xs: Vec<f64> = order.iter().map(|&j| x2[j][0]).collect();
    let mut partner = Vec::with_capacity(x1.len());
    let mut used = vec![false; x2.len()];
    let mut worst = (0.0, [0.0; 3]);
    let mut failed = x1.len() != x2.len();
    for p in x1 {
        let start = xs.partition_point(|&v| v < p[0] - tol);
        let mut best = (f64::INFINITY, usize::MAX);
        for &j in &order[start..] {
            if x2[j][0] > p[0] + tol {
                break;
            }
            let d = (0..3)
                .map(|k| (x2[j][k] - p[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            if d < best.0 {
                best = (d, j);
            }
        }
        if best.1 == usize::MAX || used[best.1] {
            failed = true;
            // Report the true nearest distance.
            let d = x2
                .iter()
                .map(|q| (0..3).map(|k| (q[k] - p[k]).powi(2)).sum::<f64>().sqrt())
                .fold(f64::INFINITY, f64::min);
            if d >= worst.0 {
                worst = (d, *p);
            }
            partner.push(usize::MAX);
            continue;
        }
        used[best.1] = true;
        partner.push(best.1);
    }
    if failed {
        return Err(LatinError::Unmatched {
            interface: name.to_string(),
            side1: x1.len(),
            side2: x2.len(),
            worst: worst.0,
            at: worst.1,
            tol,
        });
    }
    Ok(partner)
}
