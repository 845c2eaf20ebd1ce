//! Interface sides of a substructure: the discrete interface forces `g_i` of a LATIN linear
//! stage turned into side densities whose consistent nodal forces are those forces (the known
//! data of phase 1 on the interface sides).
//!
//! Node by node, the projections `b_(i,Gamma) = int_Gamma F phi_i dS` on the interface sides
//! around node `i` are the closest to the targets `b_bar` with `sum_Gamma b_(i,Gamma) = g_i`:
//! `b_(i,Gamma) = b_bar_(i,Gamma) + (g_i - sum_Gamma b_bar_(i,Gamma)) / n_i` (`n_i` sides around
//! the node), in each free direction of the node's constraint frame (in the constrained ones the
//! discrete force holds a reaction: the targets are kept and the node systems take the rest).
//! Each side's density is then recovered from its projections through the side mass matrix
//! `M_ab = int_Gamma N_a N_b dS` (discontinuous across the side boundaries).

use std::collections::{BTreeMap, HashMap};

use alea_mesh::{Facet, Mesh};

use super::topology::SideTopology;
use super::vector::{Frame, dot, head, identity};
use crate::CreError;
use crate::data::SideForces;
use crate::linalg::cholesky_solve;

/// Densities (values at the side nodes) on the sides of the interface `side` of `mesh`:
/// `locate(facet)` gives the side of a facet of the group, its target projections and the
/// side's reference projections `(node, b)` of that facet if any (they replace the targets),
/// `mass(side)` the side mass matrix (row-major),
/// the forces are per unit `thickness` (1 in 3D), `frames` the constraint frames of the nodes
/// (all directions free without). Returns `(side, values)` per facet of the group.
pub(crate) fn split_interface_forces<'a, T, B, const D: usize>(
    mesh: &Mesh,
    topo: &T,
    side: &SideForces,
    thickness: f64,
    frames: Option<&[Frame<D>]>,
    locate: impl Fn(&Facet) -> Result<(usize, B, Option<&'a Vec<(usize, [f64; D])>>), CreError>,
    mass: impl Fn(usize) -> Vec<f64>,
) -> Result<Vec<(usize, B)>, CreError>
where
    T: SideTopology<D>,
    B: AsRef<[[f64; D]]> + AsMut<[[f64; D]]> + Clone,
{
    let facets = mesh.facet_group(&side.group)?;
    if side.forces.len() != side.nodes.len() {
        return Err(CreError::Invalid(format!(
            "side '{}': {} forces for {} nodes",
            side.group,
            side.forces.len(),
            side.nodes.len()
        )));
    }
    let force: HashMap<usize, [f64; 3]> = side
        .nodes
        .iter()
        .copied()
        .zip(side.forces.iter().copied())
        .collect();
    // Target projections per (side, slot), and the interface sides around each node.
    let mut targets: Vec<(usize, B)> = Vec::new();
    let mut around: BTreeMap<usize, Vec<(usize, usize)>> = BTreeMap::new();
    for facet in facets {
        let (s, mut t, reference) = locate(facet)?;
        for &(nd, v) in reference.into_iter().flatten() {
            if let Some(k) = topo.slot(s, nd) {
                t.as_mut()[k] = v;
            }
        }
        let k = targets.len();
        for (slot, nd) in topo.side_nodes(s).enumerate() {
            if !force.contains_key(&nd) {
                return Err(CreError::Invalid(format!(
                    "facet {:?} of '{}' has node {nd} without interface force",
                    facet.nodes, side.group
                )));
            }
            around.entry(nd).or_default().push((k, slot));
        }
        targets.push((s, t));
    }
    let mut proj: Vec<B> = targets.iter().map(|t| t.1.clone()).collect();
    for (nd, list) in &around {
        let g = head::<D>(force[nd]);
        let (basis, nfree) = frames.map_or((identity(), D), |f| f[*nd]);
        for r in basis.iter().take(nfree) {
            let sum: f64 = list
                .iter()
                .map(|&(k, slot)| dot(targets[k].1.as_ref()[slot], *r))
                .sum();
            let corr = (dot(g, *r) / thickness - sum) / list.len() as f64;
            for &(k, slot) in list {
                let p = &mut proj[k].as_mut()[slot];
                for c in 0..D {
                    p[c] += corr * r[c];
                }
            }
        }
    }
    let mut out = Vec::with_capacity(targets.len());
    for (k, (s, _)) in targets.iter().enumerate() {
        let n = topo.side_nodes(*s).count();
        let m = mass(*s);
        let mut v = proj[k].clone();
        v.as_mut().fill([0.0; D]);
        for c in 0..D {
            let mut a = m.clone();
            let mut b: Vec<f64> = (0..n).map(|i| proj[k].as_ref()[i][c]).collect();
            if !cholesky_solve(&mut a, &mut b, n) {
                return Err(CreError::Invalid(format!("degenerate {} {s}", T::SIDE)));
            }
            for i in 0..n {
                v.as_mut()[i][c] = b[i];
            }
        }
        out.push((*s, v));
    }
    Ok(out)
}
