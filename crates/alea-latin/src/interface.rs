//! Interface geometry: the interface points of a paired interface and how each side sees them
//! ([`InterfacePairing`], [`SideProjection`]); node-to-node pairing of matching sides, lumped
//! interface weights and nodal normals. Non-matching sides are paired by [`crate::mortar`].
//!
//! An interface carries its fields `(W_s, F_s, W_hat_s, F_hat_s)` at points `p` with weights
//! `m_p`. Side `s` sees them through a projection: `W_s(p) = sum_a Pi_s(p, a) u_a`, its nodes
//! are loaded by `f_a = sum_p m_p Pi_s(p, a) F_s(p)` (`Pi^T M F`), and the LATIN linear stage's
//! operator receives `k Pi^T M Pi` (module `solver`). Node to node is the special case of
//! identity rows, one node per point and side (the fast path: same operator and right-hand side
//! as a diagonal interface mass).
//!
//! **Node-to-node pairing.** Side nodes come from a facet group of each substructure's mesh.
//! Each side-1 node is paired with the nearest side-2 node; the pairing must be one-to-one and
//! every distance within the tolerance (default `1e-6` times the interface's bounding-box
//! diagonal), otherwise [`LatinError::Unmatched`] names the interface and the worst distance
//! ([`Pairing::Auto`] then falls back to the mortar pairing). Both sides of a node-to-node
//! pairing carry side 1's weights, so paired forces are exactly equal and opposite also when
//! the nodes only nearly coincide (within the tolerance; each side's own weights then differ
//! slightly and the LATIN iteration had no fixed point, issue 21).
//!
//! **Cyclic interfaces** (module `cyclic`): `sides::pair_sides` pairs side 1 with side 2's
//! mesh mapped back by the interface's rotation, and the pairing records the rotation
//! ([`InterfacePairing::rotation`]); side 2's fields stay in its own frame.
//!
//! The interface mass `M_Gamma,ij = int N_i N_j dS` (times the thickness in 2D) is lumped with
//! the HRZ rule (diagonal proportional to the consistent diagonal, scaled to the facet measure),
//! which keeps every weight positive for quadratic facets too. The normal at a node is the
//! measure-weighted mean of the outward normals (with respect to side 1's cells) of the side-1
//! facets around it.

use alea_fem::{Quadrature, kinematics::facet_geometry};
use alea_mesh::Mesh;
use alea_mesh::vec3::norm;

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

/// One facet of a side: the cell it bounds, its measure (times the thickness in 2D) and the
/// HRZ-lumped share of that measure at each of its nodes (the shares add up to the measure;
/// summed over the facets around a node they give its [`SideGeometry`] weight).
#[derive(Clone, Debug, PartialEq)]
pub struct FacetShare {
    /// Cell the facet bounds.
    pub cell: usize,
    /// Facet measure.
    pub measure: f64,
    /// `(mesh node, share)` per facet node.
    pub shares: Vec<(usize, f64)>,
}

/// The facets of group `group` of `mesh` with their lumped node shares (the weights of
/// [`side_geometry`] facet by facet: error maps distribute nodal values to cells with them).
///
/// # Errors
/// An unknown group or a facet bounding no cell.
pub fn facet_shares(
    mesh: &Mesh,
    group: &str,
    thickness: f64,
) -> Result<Vec<FacetShare>, alea_mesh::MeshError> {
    let facets = mesh.attach_facets(mesh.facet_group(group)?, None)?;
    let th = if mesh.dim == 2 { thickness } else { 1.0 };
    Ok(facets
        .iter()
        .map(|bf| {
            let f = &bf.facet;
            let coords: Vec<[f64; 3]> = f.nodes.iter().map(|&n| mesh.coords[n]).collect();
            let q = Quadrature::for_cell(f.kind, 2 * f.kind.order() + 1);
            let mut diag = vec![0.0; f.nodes.len()];
            let mut measure = 0.0;
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = facet_geometry(f.kind, &coords, *xi);
                let dm = w * g.jac * th;
                measure += dm;
                for (d, n) in diag.iter_mut().zip(&g.n) {
                    *d += dm * n * n;
                }
            }
            let dsum: f64 = diag.iter().sum();
            FacetShare {
                cell: bf.cell,
                measure,
                shares: f
                    .nodes
                    .iter()
                    .zip(&diag)
                    .map(|(&node, d)| (node, d * measure / dsum))
                    .collect(),
            }
        })
        .collect())
}

/// Distributes per-point terms of one interface side to the cells whose facets carry them:
/// point `p` (mesh node `nodes[p]`, weight `m_p = weights[p]`, terms `t_p = terms[p]`) has the
/// density `t_p / m_p` at its node (points of zero weight carry none); each facet of `facets`
/// (from [`facet_shares`] on that side) adds its measure to `cells[f.cell][2]` and
/// `share * t_p / m_p` at each of its nodes to `cells[f.cell][0..2]`. Over the cells of a side
/// the terms add up to `sum_p t_p` when the side's lumped weights are the points' weights.
pub fn distribute_to_cells(
    facets: Vec<FacetShare>,
    nodes: &[usize],
    terms: &[[f64; 2]],
    weights: &[f64],
    cells: &mut [[f64; 3]],
) {
    let mut density: std::collections::HashMap<usize, [f64; 2]> =
        std::collections::HashMap::with_capacity(nodes.len());
    for (p, (&node, t)) in nodes.iter().zip(terms).enumerate() {
        if weights[p] > 0.0 {
            density.insert(node, [t[0] / weights[p], t[1] / weights[p]]);
        }
    }
    for f in facets {
        let c = &mut cells[f.cell];
        c[2] += f.measure;
        for (node, share) in f.shares {
            if let Some(d) = density.get(&node) {
                c[0] += share * d[0];
                c[1] += share * d[1];
            }
        }
    }
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
        let l = norm(nrm);
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
            // Within the tolerance in every direction, not only in x (the window): mirror
            // images in y, z would otherwise pair.
            if d <= tol && d < best.0 {
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

/// How an interface's points are found from its two sides.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Pairing {
    /// Node to node when the sides match (same node count, every side-1 node within the match
    /// tolerance of a distinct side-2 node), mortar otherwise.
    #[default]
    Auto,
    /// Node to node only; sides that do not match are an error ([`LatinError::Unmatched`]).
    NodeToNode,
    /// Mortar (module [`crate::mortar`]) even if the sides match.
    Mortar,
}

/// The pairing actually used for an interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PairingKind {
    /// One point per pair of coincident nodes, identity projections.
    NodeToNode,
    /// One point per side-1 multiplier node, dual-mortar projections (module [`crate::mortar`]).
    Mortar,
}

/// How the values of one side at the interface points come from that side's nodal
/// displacements, and how the point forces go back to its nodes.
///
/// Row `p` (entries `ptr[p]..ptr[p + 1]` of `nodes` and `coef`) gives
/// `W(p) = sum_a coef_pa u_a` (mesh nodes `a` of the side's substructure); the interface forces
/// `F(p)` load the side's nodes with `f_a = sum_p weights_p coef_pa F(p)` (`Pi^T M F`), and the
/// linear stage's operator receives `k Pi^T M Pi`. Every row sums to 1 (rigid motions are
/// transmitted exactly). A node-to-node side has one entry of coefficient 1 per row.
#[derive(Clone, Debug, PartialEq)]
pub struct SideProjection {
    /// Weight `m_p` of each point in this side's forces (length in 2D x thickness, area in 3D).
    pub weights: Vec<f64>,
    /// Row pointers (`points + 1`).
    pub ptr: Vec<usize>,
    /// Mesh nodes of the entries.
    pub nodes: Vec<usize>,
    /// Coefficients of the entries.
    pub coef: Vec<f64>,
}

impl SideProjection {
    /// One node per point with coefficient 1.
    pub fn identity(nodes: Vec<usize>, weights: Vec<f64>) -> Self {
        SideProjection {
            ptr: (0..=nodes.len()).collect(),
            coef: vec![1.0; nodes.len()],
            nodes,
            weights,
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// True if there is no point.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// Entries `(node, coefficient)` of point `p`.
    pub fn row(&self, p: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let r = self.ptr[p]..self.ptr[p + 1];
        self.nodes[r.clone()]
            .iter()
            .copied()
            .zip(self.coef[r].iter().copied())
    }

    /// True if every row is a single node with coefficient 1.
    pub fn is_identity(&self) -> bool {
        self.ptr.windows(2).all(|w| w[1] == w[0] + 1) && self.coef.iter().all(|&c| c == 1.0)
    }

    /// The node with the largest coefficient in row `p` (the node of a node-to-node point).
    pub fn main_node(&self, p: usize) -> usize {
        self.row(p)
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(usize::MAX, |e| e.0)
    }

    /// The distinct nodes of the side (sorted).
    pub fn side_nodes(&self) -> Vec<usize> {
        let mut n = self.nodes.clone();
        n.sort_unstable();
        n.dedup();
        n
    }

    /// Nodal forces `f_a = sum_p m_p coef_pa F(p)` of point values `f` (one per point), on the
    /// nodes of [`SideProjection::side_nodes`] (same order).
    pub fn nodal_forces(&self, f: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let nodes = self.side_nodes();
        let mut out = vec![[0.0; 3]; nodes.len()];
        for (p, fp) in f.iter().enumerate().take(self.len()) {
            let m = self.weights[p];
            for (a, c) in self.row(p) {
                let i = nodes.binary_search(&a).expect("node of the side");
                for k in 0..3 {
                    out[i][k] += m * c * fp[k];
                }
            }
        }
        out
    }

    /// Point values `W(p) = sum_a coef_pa u_a` of a node-major displacement `u` of dimension
    /// `dim`.
    pub fn interpolate(&self, u: &[f64], dim: usize) -> Vec<[f64; 3]> {
        (0..self.len())
            .map(|p| {
                let mut w = [0.0; 3];
                for (a, c) in self.row(p) {
                    for k in 0..dim {
                        w[k] += c * u[a * dim + k];
                    }
                }
                w
            })
            .collect()
    }
}

/// The interface points of a paired interface and both sides' projections.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfacePairing {
    /// Node to node or mortar.
    pub kind: PairingKind,
    /// Position of each point (a side-1 node).
    pub x: Vec<[f64; 3]>,
    /// Unit normal at each point (outward of side 1).
    pub normals: Vec<[f64; 3]>,
    /// Weight of each point (side 1's `m_p`): the integration weight of interface integrals.
    pub weights: Vec<f64>,
    /// Normal distance from side 1 to side 2 at each point in the nominal geometry (mortar
    /// contact interfaces; 0 for node-to-node and perfect interfaces), added to the gap field.
    pub geometric_gap: Vec<f64>,
    /// Projections of side 1 and side 2.
    pub sides: [SideProjection; 2],
    /// Cyclic symmetry (module `cyclic`): the rotation `R` from side 1's frame, the
    /// frame of the points, to side 2's (side 2's fields are stored in its own frame); `None`
    /// for an ordinary interface (both sides in the same frame).
    pub rotation: Option<crate::rotation::Mat3>,
    /// The mesh node each point is, on the side carrying the points: a mortar pairing's
    /// multiplier node (whichever side carries them), a node-to-node pairing's side-1 node.
    /// Points of two pairings of one interface with the same side and node are the same
    /// material point (large sliding, `crate::fretting::slip_cycle_repaired`). Empty where
    /// unknown.
    pub point_nodes: Vec<usize>,
}

impl InterfacePairing {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True if there is no point.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// A vector of side `s`'s frame in the points' frame (side 1's): `R^T v` on side 2 of a
    /// cyclic interface, `v` otherwise.
    pub fn to_points(&self, s: usize, v: [f64; 3]) -> [f64; 3] {
        match (&self.rotation, s) {
            (Some(r), 1) => crate::rotation::apply_transpose(r, &v),
            _ => v,
        }
    }

    /// A vector of the points' frame in side `s`'s frame: `R v` on side 2 of a cyclic
    /// interface, `v` otherwise.
    pub fn to_side(&self, s: usize, v: [f64; 3]) -> [f64; 3] {
        match (&self.rotation, s) {
            (Some(r), 1) => crate::rotation::apply(r, &v),
            _ => v,
        }
    }
}

/// Node-to-node pairing of two facet groups (see [`pair_nodes`]).
pub fn pair_node_to_node(
    name: &str,
    sides: [(&Mesh, &str, f64); 2],
    tol: Option<f64>,
) -> Result<InterfacePairing, LatinError> {
    let mesh_err = |s: usize| {
        move |e: alea_mesh::MeshError| LatinError::Pairing {
            interface: name.to_string(),
            message: format!("side {}: {e}", s + 1),
        }
    };
    let g1 = side_geometry(sides[0].0, sides[0].1, sides[0].2).map_err(mesh_err(0))?;
    let g2 = side_geometry(sides[1].0, sides[1].1, sides[1].2).map_err(mesh_err(1))?;
    let x1: Vec<[f64; 3]> = g1.nodes.iter().map(|&n| sides[0].0.coords[n]).collect();
    let x2: Vec<[f64; 3]> = g2.nodes.iter().map(|&n| sides[1].0.coords[n]).collect();
    let partner = pair_nodes(name, &x1, &x2, tol)?;
    let nodes2: Vec<usize> = partner.iter().map(|&j| g2.nodes[j]).collect();
    // Both sides carry side 1's lumped weights: a pair's forces are then exactly equal and
    // opposite. Each side's own weights differ where the nodes only nearly coincide (within the
    // matching tolerance), and the run then had no fixed point (its indicator stalled at the
    // relative weight difference, issue 21); on exactly matching sides they are the same.
    let weights2 = g1.weights.clone();
    let n = x1.len();
    let point_nodes = g1.nodes.clone();
    Ok(InterfacePairing {
        kind: PairingKind::NodeToNode,
        x: x1,
        normals: g1.normals,
        weights: g1.weights.clone(),
        geometric_gap: vec![0.0; n],
        sides: [
            SideProjection::identity(g1.nodes, g1.weights),
            SideProjection::identity(nodes2, weights2),
        ],
        rotation: None,
        point_nodes,
    })
}
