//! Multiplier functions of a side-1 facet (module doc): the dual basis
//! `psi_i = sum_j A_ij phi_j`, `A = D_e M_e^-1` (Wohlmuth 2000; Popp, Gee and Wall 2009) on fully
//! covered facets, the Lagrange functions on partly covered ones, the functions of nodes held by
//! the constraints shared among the facet's other multiplier nodes; and a facet's contributions
//! `m_p = int psi_i dS`, `m_p Pi_s(p, a) = int psi_i N_a^s dS` to the weights and projection
//! rows.

use std::collections::BTreeMap;

use alea_fem::Quadrature;
use alea_fem::kinematics::facet_geometry;
use alea_fem::reference::{MAX_NODES, shape};
use alea_mesh::CellType;

use super::clipping::IPoint;
use super::geometry::SideFacet;

/// The contributions of one side-1 facet: per multiplier node, `(node, m, row1, row2)`.
pub(super) type Contribution = Vec<(usize, f64, Vec<(usize, f64)>, Vec<(usize, f64)>)>;

/// Multiplier functions of a side-1 facet: kind of the Lagrange functions `phi` (on the
/// facet's first nodes, same reference cell) and whether the dual basis is used.
pub(super) fn multiplier_kind(kind: CellType, full: bool) -> CellType {
    match (kind, full) {
        (CellType::Tri6, _) => CellType::Tri3,
        (CellType::Line3, false) => CellType::Line2,
        (k, _) => k,
    }
}

/// Dual-basis coefficients `A = D M^-1` (row-major `nm x nm`) of a facet's functions `phi` of
/// kind `mk`.
pub(super) fn dual_coefficients(f: &SideFacet, mk: CellType) -> Option<Vec<f64>> {
    let nm = mk.num_nodes();
    let q = Quadrature::for_cell(f.kind, 2 * f.kind.order() + 4);
    let mut m = vec![0.0; nm * nm];
    let mut d = vec![0.0; nm];
    let mut phi = [0.0; MAX_NODES];
    let mut dphi = [[0.0; 3]; MAX_NODES];
    for (xi, w) in q.points.iter().zip(&q.weights) {
        let g = facet_geometry(f.kind, &f.x, *xi);
        shape(mk, *xi, &mut phi, &mut dphi);
        let dm = w * g.jac;
        for i in 0..nm {
            d[i] += dm * phi[i];
            for j in 0..nm {
                m[i * nm + j] += dm * phi[i] * phi[j];
            }
        }
    }
    let inv = invert(&m, nm)?;
    Some(
        (0..nm * nm)
            .map(|k| d[k / nm] * inv[k])
            .collect::<Vec<f64>>(),
    )
}

/// Inverse of a small dense matrix (Gauss-Jordan with partial pivoting).
pub(super) fn invert(a: &[f64], n: usize) -> Option<Vec<f64>> {
    let mut m = a.to_vec();
    let mut inv: Vec<f64> = (0..n * n)
        .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
        .collect();
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for c in 0..n {
        let p = (c..n).max_by(|&i, &j| m[i * n + c].abs().total_cmp(&m[j * n + c].abs()))?;
        if m[p * n + c].abs() <= 1e-14 * scale {
            return None;
        }
        for k in 0..n {
            m.swap(c * n + k, p * n + k);
            inv.swap(c * n + k, p * n + k);
        }
        let piv = m[c * n + c];
        for k in 0..n {
            m[c * n + k] /= piv;
            inv[c * n + k] /= piv;
        }
        for r in 0..n {
            if r != c {
                let f = m[r * n + c];
                if f != 0.0 {
                    for k in 0..n {
                        m[r * n + k] -= f * m[c * n + k];
                        inv[r * n + k] -= f * inv[c * n + k];
                    }
                }
            }
        }
    }
    Some(inv)
}

/// The contributions of one side-1 facet to the weights and projection rows.
pub(super) fn facet_contributions(
    f1: &SideFacet,
    side2: &[SideFacet],
    ips: &[IPoint],
    coverage: f64,
    fixed: &(dyn Fn(usize) -> bool + Sync),
) -> Contribution {
    let full = coverage >= 1.0 - 1e-8;
    let mk = multiplier_kind(f1.kind, full);
    let nm = mk.num_nodes();
    // Multiplier nodes held in every direction by side 1's constraints carry no point: their
    // functions are shared among the facet's other multiplier nodes (module doc), unless every
    // multiplier node of the facet is held.
    let mut removed: Vec<bool> = f1.nodes[..nm].iter().map(|&n| fixed(n)).collect();
    if removed.iter().all(|&r| r) {
        removed.fill(false);
    }
    let kept = removed.iter().filter(|&&r| !r).count() as f64;
    // Dual basis on fully covered facets (fall back to the Lagrange functions if the facet's
    // mass matrix is singular, a degenerate facet).
    let dual = if full {
        dual_coefficients(f1, mk)
    } else {
        None
    };
    let mut acc: Vec<NodeAcc> = vec![NodeAcc::default(); nm];
    let mut phi = [0.0; MAX_NODES];
    let mut dphi = [[0.0; 3]; MAX_NODES];
    let mut n1 = [0.0; MAX_NODES];
    let mut n2 = [0.0; MAX_NODES];
    let mut dn = [[0.0; 3]; MAX_NODES];
    let mut psi = [0.0; MAX_NODES];
    for ip in ips {
        shape(mk, ip.xi1, &mut phi, &mut dphi);
        match &dual {
            Some(a) => {
                for i in 0..nm {
                    psi[i] = (0..nm).map(|j| a[i * nm + j] * phi[j]).sum();
                }
            }
            None => psi[..nm].copy_from_slice(&phi[..nm]),
        }
        let share: f64 = (0..nm).filter(|&i| removed[i]).map(|i| psi[i]).sum::<f64>() / kept;
        for i in 0..nm {
            psi[i] = if removed[i] { 0.0 } else { psi[i] + share };
        }
        shape(f1.kind, ip.xi1, &mut n1, &mut dn);
        let f2 = &side2[ip.e2];
        shape(f2.kind, ip.xi2, &mut n2, &mut dn);
        for i in 0..nm {
            let wp = ip.w * psi[i];
            let a = &mut acc[i];
            a.m += wp;
            for (b, &node) in f1.nodes.iter().enumerate() {
                *a.row1.entry(node).or_insert(0.0) += wp * n1[b];
            }
            for (b, &node) in f2.nodes.iter().enumerate() {
                *a.row2.entry(node).or_insert(0.0) += wp * n2[b];
            }
        }
    }
    acc.into_iter()
        .enumerate()
        .filter(|(i, _)| !removed[*i])
        .map(|(i, a)| {
            (
                f1.nodes[i],
                a.m,
                a.row1.into_iter().collect(),
                a.row2.into_iter().collect(),
            )
        })
        .collect()
}

/// Accumulated weight and rows of one multiplier node.
#[derive(Clone, Default)]
pub(super) struct NodeAcc {
    pub(super) m: f64,
    pub(super) row1: BTreeMap<usize, f64>,
    pub(super) row2: BTreeMap<usize, f64>,
}
