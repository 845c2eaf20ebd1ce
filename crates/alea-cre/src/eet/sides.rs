//! Interface sides of a substructure: the discrete interface forces turned into edge densities
//! for phase 1 ([`interface_densities`]), and the FE traction projections on a facet group used
//! as the targets of the split ([`facet_projections`]).

use alea_fem::Model;
use alea_mesh::Mesh;

use crate::CreError;
use crate::data::{FacetProjections, SideForces};
use crate::fe::{facet_point, gauss01, hooke, mul3, strain_h, traction_of};
use crate::linalg::cholesky_solve;
use crate::topology::{Topology, facet_point_at};

/// A node's orthonormal frame (rows) and its number of free directions (the first ones; the
/// rest are constrained).
pub type NodeFrame = ([[f64; 2]; 2], usize);

/// A polynomial density on one edge: `(edge, values at [nodes[0], nodes[1], mid])`.
pub type EdgeLinear = (usize, [[f64; 2]; 3]);

/// Consistent edge mass `int N_a N_b ds` (ends, mid) of an edge of length `len`.
pub(crate) fn edge_mass(quadratic: bool, len: f64) -> [[f64; 3]; 3] {
    if quadratic {
        let c = len / 30.0;
        [
            [4.0 * c, -c, 2.0 * c],
            [-c, 4.0 * c, 2.0 * c],
            [2.0 * c, 2.0 * c, 16.0 * c],
        ]
    } else {
        let c = len / 6.0;
        [[2.0 * c, c, 0.0], [c, 2.0 * c, 0.0], [0.0, 0.0, 0.0]]
    }
}

/// Densities of degree `p` on the edges of an interface side whose consistent nodal forces equal
/// the given discrete forces `g_i` (per unit thickness: `g_i / thickness`).
///
/// Node by node, the projections `b_(i,Gamma) = int_Gamma F phi_i` on the side edges around
/// node `i` (one or two) are the closest to the targets `b_bar` (the averaged FE traction
/// projections, see [`SideForces::reference`]) with `sum_Gamma b_(i,Gamma) = g_i`:
/// `b_(i,Gamma) = b_bar_(i,Gamma) + (g_i - sum b_bar) / n_i`. Each edge's density is then
/// recovered from its projections through the edge mass matrix (discontinuous at the nodes).
/// `b_bar[e]` are the projections of edge `e` (edge orientation, slots ends/mid); entries of
/// `side.reference` replace them. With node `frames` (constraint frames of the domain), the
/// force is imposed only in each node's free directions. Returns, per edge of the side, the
/// nodal values (ends, mid).
pub fn interface_densities(
    mesh: &Mesh,
    topo: &Topology,
    side: &SideForces,
    thickness: f64,
    b_bar: &[[[f64; 2]; 3]],
    frames: Option<&[NodeFrame]>,
) -> Result<Vec<EdgeLinear>, CreError> {
    let facets = mesh.facet_group(&side.group)?;
    if side.forces.len() != side.nodes.len() {
        return Err(CreError::Invalid(format!(
            "side '{}': {} forces for {} nodes",
            side.group,
            side.forces.len(),
            side.nodes.len()
        )));
    }
    let force: std::collections::HashMap<usize, [f64; 3]> = side
        .nodes
        .iter()
        .copied()
        .zip(side.forces.iter().copied())
        .collect();
    // Target projections per (edge, slot), and the side edges around each node.
    let mut targets: Vec<(usize, [[f64; 2]; 3])> = Vec::new();
    let mut around: std::collections::HashMap<usize, Vec<(usize, usize)>> = Default::default();
    for f in facets {
        let (a, b) = (f.nodes[0], f.nodes[1]);
        let e = topo.find(a, b).ok_or_else(|| {
            CreError::Invalid(format!(
                "facet ({a}, {b}) of '{}' is not a mesh edge",
                side.group
            ))
        })?;
        let edge = &topo.edges[e];
        let mut t = *b_bar
            .get(e)
            .ok_or_else(|| CreError::Invalid(format!("edge {e} has no reference projection")))?;
        if let Some(r) = side
            .reference
            .as_ref()
            .and_then(|r| r.get(&[a.min(b), a.max(b)]))
        {
            for &(nd, v) in r {
                if let Some(k) = edge.slot(nd) {
                    t[k] = v;
                }
            }
        }
        let k = targets.len();
        for (slot, nd) in edge.all_nodes().enumerate() {
            if !force.contains_key(&nd) {
                return Err(CreError::Invalid(format!(
                    "facet ({a}, {b}) of '{}' has node {nd} without interface force",
                    side.group
                )));
            }
            around.entry(nd).or_default().push((k, slot));
        }
        targets.push((e, t));
    }
    let mut proj: Vec<[[f64; 2]; 3]> = targets.iter().map(|t| t.1).collect();
    for (nd, list) in &around {
        let g = force[nd];
        // In the directions constrained at the node the discrete force holds a reaction: keep the
        // targets there (the Dirichlet edges of the node system take the rest).
        let (basis, nfree) = frames.map_or(([[1.0, 0.0], [0.0, 1.0]], 2), |f| f[*nd]);
        for r in basis.iter().take(nfree) {
            let sum: f64 = list
                .iter()
                .map(|&(k, slot)| targets[k].1[slot][0] * r[0] + targets[k].1[slot][1] * r[1])
                .sum();
            let corr = ((g[0] * r[0] + g[1] * r[1]) / thickness - sum) / list.len() as f64;
            for &(k, slot) in list {
                proj[k][slot][0] += corr * r[0];
                proj[k][slot][1] += corr * r[1];
            }
        }
    }
    let mut out = Vec::with_capacity(targets.len());
    for (k, &(e, _)) in targets.iter().enumerate() {
        let edge = &topo.edges[e];
        let (_, len, _) = topo.geometry(mesh, e);
        let n = if edge.mid.is_some() { 3 } else { 2 };
        let m = edge_mass(edge.mid.is_some(), len);
        let mut v = [[0.0; 2]; 3];
        for c in 0..2 {
            let mut a: Vec<f64> = (0..n)
                .flat_map(|i| (0..n).map(move |j| (i, j)))
                .map(|(i, j)| m[i][j])
                .collect();
            let mut b: Vec<f64> = (0..n).map(|i| proj[k][i][c]).collect();
            if !cholesky_solve(&mut a, &mut b, n) {
                return Err(CreError::Invalid(format!("degenerate edge {e}")));
            }
            for i in 0..n {
                v[i][c] = b[i];
            }
        }
        out.push((e, v));
    }
    Ok(out)
}

/// Projections `int_facet (sigma_h n) phi_node dS` (per unit thickness, `n` outward) of the FE
/// traction of `u` on every facet of group `group`, keyed by the facet's sorted end nodes.
pub fn facet_projections(
    model: &Model,
    u: &[f64],
    group: &str,
) -> Result<FacetProjections, CreError> {
    let mesh = &model.mesh;
    if u.len() != 2 * mesh.num_nodes() {
        return Err(CreError::Invalid(format!(
            "displacement of length {} for {} nodes",
            u.len(),
            mesh.num_nodes()
        )));
    }
    let rule = gauss01(4);
    let mut out = FacetProjections::new();
    for bf in mesh.attach_facets(mesh.facet_group(group)?, None)? {
        let c = bf.cell;
        let kind = mesh.cell_type(c);
        let nodes = mesh.cell_nodes(c);
        let coords = model.cell_coords(c);
        let ue: Vec<f64> = nodes
            .iter()
            .flat_map(|&nd| [u[2 * nd], u[2 * nd + 1]])
            .collect();
        let d = hooke(model.material(c)?, model.analysis);
        let fnodes = &bf.facet.nodes;
        let quadratic = fnodes.len() == 3;
        let mut proj = vec![[0.0; 2]; fnodes.len()];
        for &(s, w) in &rule {
            // Isoparametric facet geometry (curved quadratic facets included).
            let ep = facet_point_at(mesh, fnodes, s);
            let (eps, _) = strain_h(kind, &coords, &ue, facet_point(kind, bf.local, s));
            let tr = traction_of(&mul3(&d, &eps), ep.n);
            let sh = if quadratic {
                [
                    (1.0 - s) * (1.0 - 2.0 * s),
                    s * (2.0 * s - 1.0),
                    4.0 * s * (1.0 - s),
                ]
            } else {
                [1.0 - s, s, 0.0]
            };
            for (k, p) in proj.iter_mut().enumerate() {
                for c2 in 0..2 {
                    p[c2] += w * ep.jac * sh[k] * tr[c2];
                }
            }
        }
        let (a, b) = (fnodes[0], fnodes[1]);
        out.insert(
            [a.min(b), a.max(b)],
            fnodes.iter().copied().zip(proj).collect(),
        );
    }
    Ok(out)
}
