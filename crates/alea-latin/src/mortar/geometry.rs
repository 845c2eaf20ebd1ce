//! Geometry of the mortar pairing: the facets of a side with their
//! coordinates, the position `x(xi)` and tangents of a facet, the projection of a point on a
//! facet along a direction (Newton on `x_s(xi) + t n_0 = p`), bounding boxes and the
//! auxiliary plane (line) frame of a side-1 facet.

use alea_fem::kinematics::facet_geometry;
use alea_fem::reference::{MAX_NODES, shape};
use alea_mesh::{CellType, Mesh};

use alea_mesh::vec3::{cross, dot, normalise, sub};

use super::V3;

/// A facet of one side with its coordinates.
pub(super) struct SideFacet {
    pub(super) kind: CellType,
    pub(super) nodes: Vec<usize>,
    pub(super) x: Vec<V3>,
}

pub(super) fn facets_of(mesh: &Mesh, group: &str) -> Result<Vec<SideFacet>, String> {
    let attached = mesh
        .attach_facets(mesh.facet_group(group).map_err(|e| e.to_string())?, None)
        .map_err(|e| e.to_string())?;
    attached
        .into_iter()
        .map(|b| {
            let kind = b.facet.kind;
            if !matches!(
                kind,
                CellType::Line2
                    | CellType::Line3
                    | CellType::Tri3
                    | CellType::Tri6
                    | CellType::Quad4
            ) {
                return Err(format!(
                    "facet kind {kind:?} is not supported by the mortar pairing"
                ));
            }
            let x = b.facet.nodes.iter().map(|&n| mesh.coords[n]).collect();
            Ok(SideFacet {
                kind,
                nodes: b.facet.nodes,
                x,
            })
        })
        .collect()
}

/// Reference centre of a facet kind.
pub(super) fn centre(kind: CellType) -> V3 {
    match kind {
        CellType::Tri3 | CellType::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
        _ => [0.0; 3],
    }
}

/// Position and derivatives `dx/dxi_k` of a facet at `xi`.
pub(super) fn position(f: &SideFacet, xi: V3) -> (V3, [V3; 2], [f64; MAX_NODES]) {
    let mut n = [0.0; MAX_NODES];
    let mut dn = [[0.0; 3]; MAX_NODES];
    shape(f.kind, xi, &mut n, &mut dn);
    let mut x = [0.0; 3];
    let mut t = [[0.0; 3]; 2];
    for (i, xi_) in f.x.iter().enumerate() {
        for c in 0..3 {
            x[c] += n[i] * xi_[c];
            t[0][c] += dn[i][0] * xi_[c];
            t[1][c] += dn[i][1] * xi_[c];
        }
    }
    (x, t, n)
}

/// Reference point of facet `f` whose image lies on the line `p + t d` (Newton); `None` if the
/// iteration fails. The result is clamped to the reference cell (the callers only ask for
/// points of the facet's projection).
pub(super) fn project(f: &SideFacet, p: &V3, d: &V3) -> Option<V3> {
    let fd = f.kind.dim();
    let mut xi = centre(f.kind);
    let mut t = 0.0;
    for _ in 0..40 {
        let (x, dx, _) = position(f, xi);
        let r = [
            x[0] + t * d[0] - p[0],
            x[1] + t * d[1] - p[1],
            x[2] + t * d[2] - p[2],
        ];
        // Columns: dx/dxi_0, (dx/dxi_1), d. Solve J delta = -r by Cramer's rule.
        let delta = if fd == 1 {
            let (a, b) = (dx[0], *d);
            let det = a[0] * b[1] - a[1] * b[0];
            if det.abs() < 1e-300 {
                return None;
            }
            [
                (-r[0] * b[1] + r[1] * b[0]) / det,
                (-a[0] * r[1] + a[1] * r[0]) / det,
                0.0,
            ]
        } else {
            let (a, b, c) = (dx[0], dx[1], *d);
            let det = dot(&a, &cross(&b, &c));
            if det.abs() < 1e-300 {
                return None;
            }
            let mr = [-r[0], -r[1], -r[2]];
            [
                dot(&mr, &cross(&b, &c)) / det,
                dot(&a, &cross(&mr, &c)) / det,
                dot(&a, &cross(&b, &mr)) / det,
            ]
        };
        xi[0] += delta[0];
        if fd == 1 {
            t += delta[1];
        } else {
            xi[1] += delta[1];
            t += delta[2];
        }
        let step = delta[0].abs() + if fd == 2 { delta[1].abs() } else { 0.0 };
        if !step.is_finite() {
            return None;
        }
        // Newton converges quadratically (in one step on affine facets); reference
        // coordinates are resolved to round-off times the facet's aspect, far above 1e-14.
        if step < 1e-11 {
            return Some(clamp(f.kind, xi));
        }
    }
    None
}

/// Clamps a reference point into its reference cell.
pub(super) fn clamp(kind: CellType, mut xi: V3) -> V3 {
    match kind {
        CellType::Tri3 | CellType::Tri6 => {
            xi[0] = xi[0].max(0.0);
            xi[1] = xi[1].max(0.0);
            let s = xi[0] + xi[1];
            if s > 1.0 {
                xi[0] /= s;
                xi[1] /= s;
            }
        }
        _ => {
            xi[0] = xi[0].clamp(-1.0, 1.0);
            xi[1] = xi[1].clamp(-1.0, 1.0);
        }
    }
    xi
}

/// Axis-aligned bounding box of a facet, enlarged by `pad`.
pub(super) fn bbox(f: &SideFacet, pad: f64) -> (V3, V3) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for x in &f.x {
        for c in 0..3 {
            lo[c] = lo[c].min(x[c] - pad);
            hi[c] = hi[c].max(x[c] + pad);
        }
    }
    (lo, hi)
}

/// Plane (line) frame of a side-1 facet: centre, normal and in-plane axes.
pub(super) fn frame(f: &SideFacet) -> (V3, V3, V3, V3) {
    let g = facet_geometry(f.kind, &f.x, centre(f.kind));
    let n0 = g.normal;
    if f.kind.dim() == 1 {
        (g.x, n0, [-n0[1], n0[0], 0.0], [0.0; 3])
    } else {
        let e = sub(&f.x[1], &f.x[0]);
        let t1 = normalise(sub(&e, &{
            let s = dot(&e, &n0);
            [s * n0[0], s * n0[1], s * n0[2]]
        }));
        (g.x, n0, t1, cross(&n0, &t1))
    }
}
