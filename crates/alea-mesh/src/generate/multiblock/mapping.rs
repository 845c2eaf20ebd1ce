//! A block validated and made counter-clockwise ([`Ready`]), the node distributions along its
//! sides (geometric grading) and its Coons-patch mapping `X(s, t)`.

use super::block::Block;
use super::curve::{Prepared, dist, finite2};
use crate::MeshError;

/// Node parameters in [0, 1] of `n` cells with ratio `g` of last to first cell size.
pub(crate) fn distribution(n: usize, g: f64) -> Vec<f64> {
    if n == 1 || (g - 1.0).abs() < 1e-14 {
        return (0..=n).map(|i| i as f64 / n as f64).collect();
    }
    let r = g.powf(1.0 / (n as f64 - 1.0));
    let mut x = vec![0.0];
    let mut h = 1.0;
    for _ in 0..n {
        x.push(x.last().copied().unwrap_or(0.0) + h);
        h *= r;
    }
    let total = x[n];
    x.iter_mut().for_each(|v| *v /= total);
    x[n] = 1.0;
    x
}

/// Half-step lattice: node parameters at even indices, parametric mid-points at odd ones.
pub(super) fn half_lattice(n: usize, g: f64) -> Vec<f64> {
    let d = distribution(n, g);
    let mut h = Vec::with_capacity(2 * n + 1);
    for i in 0..n {
        h.push(d[i]);
        h.push(0.5 * (d[i] + d[i + 1]));
    }
    h.push(1.0);
    h
}

/// A block after validation, counter-clockwise.
pub(super) struct Ready {
    pub(super) index: usize,
    pub(super) corners: [[f64; 2]; 4],
    pub(super) edges: [(Prepared, bool); 4], // (curve, evaluated reversed)
    pub(super) n: [usize; 2],
    pub(super) grading: [f64; 2],
    pub(super) cell_group: Option<String>,
    pub(super) edge_groups: [Option<String>; 4],
    /// The user's number of each edge (they differ when a clockwise block was re-ordered).
    pub(super) user_edge: [usize; 4],
}

impl Ready {
    pub(super) fn edge_at(&self, k: usize, u: f64) -> [f64; 2] {
        let (c, rev) = &self.edges[k];
        c.eval(if *rev { 1.0 - u } else { u })
    }

    /// The Coons patch X(s, t).
    pub(super) fn coons(&self, s: f64, t: f64) -> [f64; 2] {
        let b = self.edge_at(0, s);
        let r = self.edge_at(1, t);
        let tp = self.edge_at(2, 1.0 - s);
        let l = self.edge_at(3, 1.0 - t);
        let c = &self.corners;
        let mut x = [0.0; 2];
        for d in 0..2 {
            x[d] = (1.0 - t) * b[d] + t * tp[d] + (1.0 - s) * l[d] + s * r[d]
                - ((1.0 - s) * (1.0 - t) * c[0][d]
                    + s * (1.0 - t) * c[1][d]
                    + s * t * c[2][d]
                    + (1.0 - s) * t * c[3][d]);
        }
        x
    }

    /// Signed area of the block's boundary polygon (edges sampled).
    fn signed_area(&self) -> f64 {
        let mut pts = Vec::new();
        for k in 0..4 {
            for i in 0..32 {
                pts.push(self.edge_at(k, i as f64 / 32.0));
            }
        }
        let m = pts.len();
        (0..m)
            .map(|i| {
                let (p, q) = (pts[i], pts[(i + 1) % m]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            * 0.5
    }
}

pub(super) fn prepare(index: usize, b: &Block) -> Result<Ready, MeshError> {
    let what = |m: &str| format!("block {index}: {m}");
    if b.n[0] == 0 || b.n[1] == 0 {
        return Err(MeshError::Invalid(what(&format!(
            "needs at least one cell per direction, got {:?}",
            b.n
        ))));
    }
    if b.grading.iter().any(|g| !(g.is_finite() && *g > 0.0)) {
        return Err(MeshError::Invalid(what(&format!(
            "gradings must be positive and finite, got {:?}",
            b.grading
        ))));
    }
    if b.corners.iter().any(|&p| !finite2(p)) {
        return Err(MeshError::Invalid(what(&format!(
            "corners must be finite, got {:?}",
            b.corners
        ))));
    }
    let c = b.corners;
    let mut edges = Vec::new();
    for k in 0..4 {
        let e = Prepared::new(
            &b.edges[k],
            c[k],
            c[(k + 1) % 4],
            &what(&format!("edge {k}")),
        )?;
        edges.push((e, false));
    }
    let mut edges_it = edges.into_iter();
    let mut next = || edges_it.next().expect("four edges");
    let mut r = Ready {
        index,
        corners: c,
        edges: [next(), next(), next(), next()],
        n: b.n,
        grading: b.grading,
        cell_group: b.cell_group.clone(),
        edge_groups: b.edge_groups.clone(),
        user_edge: [0, 1, 2, 3],
    };
    let area = r.signed_area();
    let scale = (0..4)
        .map(|k| dist(c[k], c[(k + 1) % 4]))
        .fold(0.0, f64::max);
    if area.is_nan() || area.abs() <= 1e-12 * scale * scale {
        return Err(MeshError::Invalid(what("has (nearly) zero area")));
    }
    if area < 0.0 {
        // Re-order clockwise corners c0 c1 c2 c3 as c0 c3 c2 c1: new edges are the old ones
        // reversed, s and t swap.
        let [e0, e1, e2, e3] = r.edges;
        let rev = |(p, f): (Prepared, bool)| (p, !f);
        r.edges = [rev(e3), rev(e2), rev(e1), rev(e0)];
        r.corners = [c[0], c[3], c[2], c[1]];
        r.n = [b.n[1], b.n[0]];
        r.grading = [b.grading[1], b.grading[0]];
        let g = &b.edge_groups;
        r.edge_groups = [g[3].clone(), g[2].clone(), g[1].clone(), g[0].clone()];
        r.user_edge = [3, 2, 1, 0];
    }
    Ok(r)
}
