//! The pairing of two sides (module doc): both ways, the coarser side carrying the points;
//! candidate side-2 facets by bounding boxes, per side-1 facet integration points and
//! contributions (in parallel), their sum per multiplier node, and the interface points with
//! weights, side-1 normals, geometric gaps and both sides' projection rows.

use std::collections::BTreeMap;

use alea_fem::kinematics::facet_geometry;
use alea_mesh::Mesh;
use alea_mesh::vec3::{dot, sub};
use rayon::prelude::*;

use super::clipping::integration_points;
use super::dual::{Contribution, NodeAcc, facet_contributions};
use super::geometry::{bbox, centre, facets_of};
use super::{DEFAULT_SEARCH_FRACTION, V3};
use crate::LatinError;
use crate::interface::{InterfacePairing, PairingKind, SideProjection, side_geometry};

/// Pairs facet group `sides[0] = (mesh, group, thickness)` (side 1) with `sides[1]` by the dual
/// mortar method (module doc), with the interface points on the **coarser** side (the one that
/// gives fewer points; side 1 on a tie). `search`: largest normal distance between the sides
/// (default [`DEFAULT_SEARCH_FRACTION`] times the interface size); `with_gap`: store the
/// geometric gap (contact interfaces); `fixed[s](node)`: node of side `s` held in every
/// direction by its substructure's constraints (no interface point there). Whichever side
/// carries the points, the normals are side 1's outward ones and `sides[0]` is side 1's
/// projection.
///
/// # Errors
/// [`LatinError::Pairing`] naming the interface if a group is missing, the meshes differ in
/// dimension, a facet kind is not supported, no part of side 2 faces side 1 within the search
/// distance, or side 2 covers a side-1 facet more than once (the errors of the pairing with the
/// points on side 1 are reported when neither way succeeds).
pub fn pair_mortar(
    name: &str,
    sides: [(&Mesh, &str, f64); 2],
    search: Option<f64>,
    with_gap: bool,
    fixed: [&(dyn Fn(usize) -> bool + Sync); 2],
) -> Result<InterfacePairing, LatinError> {
    pair_mortar_sided(name, sides, search, with_gap, fixed, None).map(|(p, _)| p)
}

/// [`pair_mortar`] with the side that carries the points chosen by the caller
/// (`point_side`: 0 for side 1, 1 for side 2; `None`: the coarser side, as in
/// [`pair_mortar`]). Returns the pairing and the side that carries its points (re-pairings
/// of a sliding interface keep the side of the first pairing, module
/// [`crate::large_sliding`]).
///
/// # Errors
/// As [`pair_mortar`]; with a given side, the errors of that way.
pub fn pair_mortar_sided(
    name: &str,
    sides: [(&Mesh, &str, f64); 2],
    search: Option<f64>,
    with_gap: bool,
    fixed: [&(dyn Fn(usize) -> bool + Sync); 2],
    point_side: Option<usize>,
) -> Result<(InterfacePairing, usize), LatinError> {
    let fail = |message: String| LatinError::Pairing {
        interface: name.to_string(),
        message,
    };
    if sides[0].0.dim != sides[1].0.dim {
        return Err(fail(format!(
            "side 1 is {}D and side 2 is {}D",
            sides[0].0.dim, sides[1].0.dim
        )));
    }
    let forward = || {
        one_way(
            name,
            sides,
            search,
            with_gap,
            fixed[0],
            ["side 1", "side 2"],
        )
    };
    let backward = || {
        one_way(
            name,
            [sides[1], sides[0]],
            search,
            with_gap,
            fixed[1],
            ["side 2", "side 1"],
        )
    };
    match point_side {
        Some(0) => return forward().map(|f| (f, 0)),
        Some(_) => return backward().map(|b| (reversed(b), 1)),
        None => {}
    }
    match (forward(), backward()) {
        (Ok(f), Ok(b)) if b.len() < f.len() => Ok((reversed(b), 1)),
        (Ok(f), _) => Ok((f, 0)),
        (Err(_), Ok(b)) => Ok((reversed(b), 1)),
        (Err(e), Err(_)) => Err(e),
    }
}

/// A pairing computed with the points on side 2 expressed in side 1's conventions: projections
/// swapped, normals reversed (the geometric gap `(Pi_2 x_2 - Pi_1 x_1) . n` is unchanged).
fn reversed(mut p: InterfacePairing) -> InterfacePairing {
    p.sides.swap(0, 1);
    for n in p.normals.iter_mut() {
        *n = [-n[0], -n[1], -n[2]];
    }
    p
}

/// The pairing with the points on `sides[0]` (`labels`: the user's names of the two sides,
/// for messages).
fn one_way(
    name: &str,
    sides: [(&Mesh, &str, f64); 2],
    search: Option<f64>,
    with_gap: bool,
    fixed: &(dyn Fn(usize) -> bool + Sync),
    labels: [&str; 2],
) -> Result<InterfacePairing, LatinError> {
    let fail = |message: String| LatinError::Pairing {
        interface: name.to_string(),
        message,
    };
    let (mesh1, group1, th1) = sides[0];
    let (mesh2, group2, _) = sides[1];
    let [l1, l2] = labels;
    let thickness = if mesh1.dim == 2 { th1 } else { 1.0 };
    let side1 = facets_of(mesh1, group1).map_err(|e| fail(format!("{l1}: {e}")))?;
    let side2 = facets_of(mesh2, group2).map_err(|e| fail(format!("{l2}: {e}")))?;
    if side1.is_empty() || side2.is_empty() {
        return Err(fail("a side has no facet".into()));
    }
    let geometry1 = side_geometry(mesh1, group1, th1).map_err(|e| fail(format!("{l1}: {e}")))?;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for f in side1.iter().chain(&side2) {
        let (a, b) = bbox(f, 0.0);
        for c in 0..3 {
            lo[c] = lo[c].min(a[c]);
            hi[c] = hi[c].max(b[c]);
        }
    }
    let size = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
    let search = search.unwrap_or(DEFAULT_SEARCH_FRACTION * size);
    if !(search.is_finite() && search >= 0.0) {
        return Err(fail(format!(
            "search distance must be finite and >= 0, got {search}"
        )));
    }
    // Side-2 facets sorted by the lower x of their boxes, to prune the candidate search.
    let boxes2: Vec<(V3, V3)> = side2.iter().map(|f| bbox(f, 0.0)).collect();
    let mut order: Vec<usize> = (0..side2.len()).collect();
    order.sort_by(|&a, &b| boxes2[a].0[0].total_cmp(&boxes2[b].0[0]));
    let xmin: Vec<f64> = order.iter().map(|&k| boxes2[k].0[0]).collect();
    let widest = boxes2
        .iter()
        .map(|b| b.1[0] - b.0[0])
        .fold(0.0f64, f64::max);
    let pad = search + 1e-9 * size;
    let per_facet: Vec<(Contribution, f64)> = side1
        .par_iter()
        .map(|f1| {
            let (qlo, qhi) = bbox(f1, pad);
            let start = xmin.partition_point(|&v| v < qlo[0] - widest);
            let cands: Vec<usize> = order[start..]
                .iter()
                .copied()
                .take_while(|&k| boxes2[k].0[0] <= qhi[0])
                .filter(|&k| (0..3).all(|c| boxes2[k].0[c] <= qhi[c] && boxes2[k].1[c] >= qlo[c]))
                .collect();
            let (ips, coverage) = integration_points(f1, &side2, &cands, search, thickness);
            (
                facet_contributions(f1, &side2, &ips, coverage, fixed),
                coverage,
            )
        })
        .collect();
    if let Some((k, (_, cov))) = per_facet
        .iter()
        .enumerate()
        .find(|(_, (_, cov))| *cov > 1.0 + 1e-6)
    {
        let g = facet_geometry(side1[k].kind, &side1[k].x, centre(side1[k].kind));
        return Err(fail(format!(
            "{l2} covers the {l1} facet at ({:.6}, {:.6}, {:.6}) {cov:.3} times within the \
             search distance {search:e}: two layers of {l2} face it (reduce the search \
             distance or split the facet group)",
            g.x[0], g.x[1], g.x[2]
        )));
    }
    let mut nodes: BTreeMap<usize, NodeAcc> = BTreeMap::new();
    for (contrib, _) in per_facet {
        for (node, m, r1, r2) in contrib {
            let acc = nodes.entry(node).or_default();
            acc.m += m;
            for (a, v) in r1 {
                *acc.row1.entry(a).or_insert(0.0) += v;
            }
            for (a, v) in r2 {
                *acc.row2.entry(a).or_insert(0.0) += v;
            }
        }
    }
    let max_m = nodes.values().map(|a| a.m).fold(0.0f64, f64::max);
    if max_m <= 0.0 {
        return Err(fail(format!(
            "no part of side 2 faces side 1 within the search distance {search:e} (set a larger \
             search distance, or check the facet groups and that side 2 faces side 1)"
        )));
    }
    let mut pairing = InterfacePairing {
        kind: PairingKind::Mortar,
        x: Vec::new(),
        normals: Vec::new(),
        weights: Vec::new(),
        geometric_gap: Vec::new(),
        sides: [
            SideProjection::identity(vec![], vec![]),
            SideProjection::identity(vec![], vec![]),
        ],
        rotation: None,
        point_nodes: Vec::new(),
    };
    let mut rows: [(Vec<usize>, Vec<usize>, Vec<f64>); 2] = Default::default();
    for r in rows.iter_mut() {
        r.0.push(0);
    }
    for (&node, acc) in &nodes {
        if !(acc.m > 1e-10 * max_m) {
            continue;
        }
        let m = acc.m;
        let scaled = |row: &BTreeMap<usize, f64>| -> Vec<(usize, f64)> {
            let big = row.values().fold(0.0f64, |s, v| s.max(v.abs()));
            row.iter()
                .filter(|(_, v)| v.abs() > 1e-14 * big)
                .map(|(&a, &v)| (a, v / m))
                .collect()
        };
        let mut r1 = scaled(&acc.row1);
        // Biorthogonality: side 1's own row is the identity up to round-off.
        if r1.iter().all(|&(a, c)| {
            if a == node {
                (c - 1.0).abs() < 1e-12
            } else {
                c.abs() < 1e-12
            }
        }) {
            r1 = vec![(node, 1.0)];
        }
        let r2 = scaled(&acc.row2);
        let interp = |row: &[(usize, f64)], mesh: &Mesh| -> V3 {
            let mut x = [0.0; 3];
            for &(a, c) in row {
                for k in 0..3 {
                    x[k] += c * mesh.coords[a][k];
                }
            }
            x
        };
        let x1 = interp(&r1, mesh1);
        let x2 = interp(&r2, mesh2);
        let normal = geometry1
            .nodes
            .binary_search(&node)
            .map(|i| geometry1.normals[i])
            .unwrap_or([0.0; 3]);
        pairing.x.push(x1);
        pairing.point_nodes.push(node);
        pairing.normals.push(normal);
        pairing.weights.push(m);
        pairing.geometric_gap.push(if with_gap {
            dot(&sub(&x2, &x1), &normal)
        } else {
            0.0
        });
        for (s, row) in [r1, r2].into_iter().enumerate() {
            for (a, c) in row {
                rows[s].1.push(a);
                rows[s].2.push(c);
            }
            let len = rows[s].1.len();
            rows[s].0.push(len);
        }
    }
    let weights = pairing.weights.clone();
    let [(p1, n1, c1), (p2, n2, c2)] = rows;
    pairing.sides = [
        SideProjection {
            weights: weights.clone(),
            ptr: p1,
            nodes: n1,
            coef: c1,
        },
        SideProjection {
            weights,
            ptr: p2,
            nodes: n2,
            coef: c2,
        },
    ];
    Ok(pairing)
}
