//! Mortar pairing of non-matching interface sides: dual mortar with segment-to-segment
//! integration, 2D and 3D, small sliding.
//!
//! # Variant
//! The interface fields `(W_s, F_s, W_hat_s, F_hat_s)` live on the **multiplier nodes** of one
//! side, the *point side*: the nodes of its facets (for `Tri6` facets only the corners). Below,
//! "side 1" is the point side and "side 2" the other one; [`pair_mortar`] pairs both ways and
//! keeps the way with fewer points - the **coarser side carries the points** - and returns the
//! result in the user's conventions (normals outward of the user's side 1). The reason is the
//! LATIN iteration, not the accuracy (both choices are optimal mortar discretisations): the
//! other side sees the point values only through `Pi_2`, and where it is coarser than the point
//! side the components of `W_hat_2` outside the range of `Pi_2` are invisible to its linear
//! stage; at open contact points nothing else acts on them, and they flip sign at every
//! iteration (`W_hat' = 2 W - W_hat`), so the error indicator stalls (measured: plain LATIN on a
//! 40-cell cylinder on a 50-cell block stalled at 5.6e-4; with the points on the cylinder it
//! converges). On a side-1 facet `e` the
//! multiplier functions are the **dual basis** (Wohlmuth 2000; Popp, Gee and Wall 2009)
//! `psi_i = sum_j A_ij phi_j` of the facet's Lagrange functions `phi` (its own shape functions;
//! the linear corner functions for `Tri6`), with `A = D_e M_e^-1`,
//! `M_e,ij = int_e phi_i phi_j dS`, `D_e = diag(int_e phi_i dS)`: biorthogonal,
//! `int_e psi_i phi_j dS = delta_ij D_e,i`, and a partition of unity, `sum_i psi_i = 1`.
//! An interface point `p` (multiplier node `i`) gets the weight and the rows of both sides'
//! projections (module [`crate::interface`], [`SideProjection`])
//!
//! ```text
//! m_p = int_Gamma psi_i dS,     Pi_s(p, a) = (1 / m_p) int_Gamma psi_i N_a^s dS,
//! ```
//! so `W_s(p) = sum_a Pi_s(p, a) u_a` and the nodal forces are `f_a = sum_p m_p Pi_s(p, a) F(p)`.
//! On side 1, biorthogonality makes `Pi_1` the identity wherever `phi = N^1` (a node-to-node
//! side). At convergence the perfect law `W_1(p) = W_2(p)` is the dual-mortar constraint
//! `int psi_i (u_1 - u_2) dS = 0`, and the contact law acts on the weighted gaps
//! `g_p = (Pi_2 (x_2 + u_2) - Pi_1 (x_1 + u_1))(p) . n_p` (Hueber and Wohlmuth 2005): the
//! nominal part `(Pi_2 x_2 - Pi_1 x_1)(p) . n_p` is the point's **geometric gap**, added to the
//! gap field of contact interfaces. The force on side 2 is `lambda = sum_p F(p) psi_p` integrated
//! against side 2's shape functions: a uniform traction gives exactly the consistent nodal
//! forces on both sides (`sum_i psi_i = 1`), and every row sums to 1, so rigid motions and the
//! total force are transmitted exactly - the patch test holds to round-off on flat interfaces.
//!
//! # Integration (segment to segment)
//! Each side-1 facet `e` has an auxiliary plane (line in 2D) through its centre, normal to its
//! centre normal `n_0`. The facet's corners and those of every side-2 facet facing it
//! (`n_2 . n_0 < -1/2`) are projected on it along `n_0`; the side-2 polygons are clipped by the
//! side-1 polygon (Sutherland-Hodgman; intervals in 2D), the pieces triangulated, and each piece
//! integrated with a Gauss rule (6 points per segment in 2D, degree 6 per triangle in 3D) whose
//! points are mapped back to both facets by projection along `n_0` (Newton on
//! `x_s(xi) + t n_0 = p`), with the surface factor `1 / |n_1(xi) . n_0|` (and the thickness in
//! 2D). This is exact for flat interfaces with affine facets. A piece whose sides are farther
//! apart than the **search distance** (along `n_0`, at its centre) is not paired: side-1 points
//! beyond it are free boundary.
//!
//! # Nodes held by constraints
//! A side-1 multiplier node held in every direction by side 1's constraints (a clamped edge of
//! the interface) carries no point: its `W_1` cannot move, so a point there would only add the
//! constraint `W_2 = W_1` on side 2, which over-constrains side 2 near the edge and slows the
//! LATIN iteration by orders of magnitude (measured: 5133 instead of 88 iterations on a
//! clamped 8 | 12-cell Q4 interface). As in the standard mortar treatment of Dirichlet ends
//! (Wohlmuth 2000), its function is shared equally among the other multiplier nodes of each
//! facet (`psi_q <- psi_q + psi_p / (kept nodes)`, which keeps `sum psi = 1`); side 1's row of
//! those points then involves the held node (`Pi_1` is no longer the identity there), and the
//! point's position is `Pi_1 x_1`.
//!
//! # Partial coverage
//! A side-1 facet covered by side 2 over less than all of its area (edges of a contact zone,
//! sides of different extent) uses the linear corner functions themselves (non-negative, a
//! partition of unity) instead of the dual basis on the covered part: the weights stay positive
//! and rows still sum to 1, at the price of first-order consistency on those facets only. A
//! multiplier node with no covered facet is not an interface point. A side-1 facet covered more
//! than once (two layers of side 2 within the search distance) is an error.

use std::collections::BTreeMap;

use alea_fem::Quadrature;
use alea_fem::kinematics::facet_geometry;
use alea_fem::quadrature::gauss_legendre;
use alea_fem::reference::{MAX_NODES, shape};
use alea_mesh::{CellType, Mesh};
use rayon::prelude::*;

use crate::LatinError;
use crate::interface::{InterfacePairing, PairingKind, SideProjection, side_geometry};

type V3 = [f64; 3];

/// Default search distance as a fraction of the interface size (the diagonal of the bounding
/// box of both sides).
pub const DEFAULT_SEARCH_FRACTION: f64 = 0.05;

/// A facet of one side with its coordinates.
struct SideFacet {
    kind: CellType,
    nodes: Vec<usize>,
    x: Vec<V3>,
}

/// One integration point of a side-1 facet: the side-2 facet, both reference points, weight.
struct IPoint {
    e2: usize,
    xi1: V3,
    xi2: V3,
    w: f64,
}

/// The contributions of one side-1 facet: per multiplier node, `(node, m, row1, row2)`.
type Contribution = Vec<(usize, f64, Vec<(usize, f64)>, Vec<(usize, f64)>)>;

fn dot(a: &V3, b: &V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: &V3, b: &V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: &V3, b: &V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalise(a: V3) -> V3 {
    let l = dot(&a, &a).sqrt();
    if l > 0.0 {
        [a[0] / l, a[1] / l, a[2] / l]
    } else {
        a
    }
}

fn facets_of(mesh: &Mesh, group: &str) -> Result<Vec<SideFacet>, String> {
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
fn centre(kind: CellType) -> V3 {
    match kind {
        CellType::Tri3 | CellType::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
        _ => [0.0; 3],
    }
}

/// Position and derivatives `dx/dxi_k` of a facet at `xi`.
fn position(f: &SideFacet, xi: V3) -> (V3, [V3; 2], [f64; MAX_NODES]) {
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
fn project(f: &SideFacet, p: &V3, d: &V3) -> Option<V3> {
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
fn clamp(kind: CellType, mut xi: V3) -> V3 {
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

/// Signed area of a plane polygon.
fn area(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        * 0.5
}

/// Sutherland-Hodgman: the part of `subject` inside the convex counter-clockwise `clip`.
fn clip_polygon(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = subject.to_vec();
    let n = clip.len();
    for k in 0..n {
        if out.is_empty() {
            break;
        }
        let (a, b) = (clip[k], clip[(k + 1) % n]);
        let side = |p: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        let input = std::mem::take(&mut out);
        let m = input.len();
        for i in 0..m {
            let (p, q) = (input[i], input[(i + 1) % m]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
        }
    }
    out
}

/// Multiplier functions of a side-1 facet: kind of the Lagrange functions `phi` (on the
/// facet's first nodes, same reference cell) and whether the dual basis is used.
fn multiplier_kind(kind: CellType, full: bool) -> CellType {
    match (kind, full) {
        (CellType::Tri6, _) => CellType::Tri3,
        (CellType::Line3, false) => CellType::Line2,
        (k, _) => k,
    }
}

/// Dual-basis coefficients `A = D M^-1` (row-major `nm x nm`) of a facet's functions `phi` of
/// kind `mk`.
fn dual_coefficients(f: &SideFacet, mk: CellType) -> Option<Vec<f64>> {
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
fn invert(a: &[f64], n: usize) -> Option<Vec<f64>> {
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

/// Axis-aligned bounding box of a facet, enlarged by `pad`.
fn bbox(f: &SideFacet, pad: f64) -> (V3, V3) {
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
fn frame(f: &SideFacet) -> (V3, V3, V3, V3) {
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

/// The integration points of side-1 facet `f1` against the side-2 facets `cands` (indices into
/// `side2`), and the covered fraction of the facet.
fn integration_points(
    f1: &SideFacet,
    side2: &[SideFacet],
    cands: &[usize],
    search: f64,
    thickness: f64,
) -> (Vec<IPoint>, f64) {
    let (c, n0, t1, t2) = frame(f1);
    let plane = |x: &V3| -> [f64; 2] {
        let r = sub(x, &c);
        [dot(&r, &t1), dot(&r, &t2)]
    };
    let at = |q: [f64; 2]| -> V3 {
        [
            c[0] + q[0] * t1[0] + q[1] * t2[0],
            c[1] + q[0] * t1[1] + q[1] * t2[1],
            c[2] + q[0] * t1[2] + q[1] * t2[2],
        ]
    };
    let nc1 = f1.kind.num_corners();
    let mut p1: Vec<[f64; 2]> = f1.x[..nc1].iter().map(&plane).collect();
    let line = f1.kind.dim() == 1;
    let measure1 = if line {
        (p1[1][0] - p1[0][0]).abs()
    } else {
        if area(&p1) < 0.0 {
            p1.reverse();
        }
        area(&p1)
    };
    let mut out = Vec::new();
    let mut covered = 0.0;
    if measure1 <= 0.0 {
        return (out, 0.0);
    }
    // A piece is paired if its two sides, at its centre, are within the search distance.
    let within = |e2: usize, q: [f64; 2]| -> Option<(V3, V3)> {
        let p = at(q);
        let xi1 = project(f1, &p, &n0)?;
        let xi2 = project(&side2[e2], &p, &n0)?;
        let d = dot(
            &sub(&position(&side2[e2], xi2).0, &position(f1, xi1).0),
            &n0,
        );
        (d.abs() <= search).then_some((xi1, xi2))
    };
    let emit = |e2: usize, q: [f64; 2], wq: f64, out: &mut Vec<IPoint>| {
        let p = at(q);
        if let (Some(xi1), Some(xi2)) = (project(f1, &p, &n0), project(&side2[e2], &p, &n0)) {
            let g = facet_geometry(f1.kind, &f1.x, xi1);
            let cosine = dot(&g.normal, &n0).abs().max(1e-3);
            out.push(IPoint {
                e2,
                xi1,
                xi2,
                w: wq * thickness / cosine,
            });
        }
    };
    for &e2 in cands {
        let f2 = &side2[e2];
        let g2 = facet_geometry(f2.kind, &f2.x, centre(f2.kind));
        if dot(&g2.normal, &n0) >= -0.5 {
            continue;
        }
        let nc2 = f2.kind.num_corners();
        let p2: Vec<[f64; 2]> = f2.x[..nc2].iter().map(&plane).collect();
        if line {
            let (a1, b1) = (p1[0][0].min(p1[1][0]), p1[0][0].max(p1[1][0]));
            let (a2, b2) = (p2[0][0].min(p2[1][0]), p2[0][0].max(p2[1][0]));
            let (lo, hi) = (a1.max(a2), b1.min(b2));
            if hi - lo <= 1e-12 * measure1 || within(e2, [0.5 * (lo + hi), 0.0]).is_none() {
                continue;
            }
            covered += hi - lo;
            let (gx, gw) = gauss_legendre(6);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for (x, w) in gx.iter().zip(&gw) {
                emit(e2, [mid + half * x, 0.0], half * w, &mut out);
            }
        } else {
            let mut p2 = p2;
            if area(&p2) < 0.0 {
                p2.reverse();
            }
            let piece = clip_polygon(&p2, &p1);
            if piece.len() < 3 {
                continue;
            }
            let a = area(&piece);
            if a <= 1e-12 * measure1 {
                continue;
            }
            let n = piece.len() as f64;
            let centroid = piece
                .iter()
                .fold([0.0, 0.0], |s, v| [s[0] + v[0] / n, s[1] + v[1] / n]);
            if within(e2, centroid).is_none() {
                continue;
            }
            covered += a;
            let rule = Quadrature::triangle(6);
            for k in 1..piece.len() - 1 {
                let (v0, v1, v2) = (piece[0], piece[k], piece[k + 1]);
                let at2 =
                    ((v1[0] - v0[0]) * (v2[1] - v0[1]) - (v1[1] - v0[1]) * (v2[0] - v0[0])).abs();
                for (r, w) in rule.points.iter().zip(&rule.weights) {
                    let q = [
                        v0[0] + r[0] * (v1[0] - v0[0]) + r[1] * (v2[0] - v0[0]),
                        v0[1] + r[0] * (v1[1] - v0[1]) + r[1] * (v2[1] - v0[1]),
                    ];
                    emit(e2, q, w * at2, &mut out);
                }
            }
        }
    }
    (out, covered / measure1)
}

/// The contributions of one side-1 facet to the weights and projection rows.
fn facet_contributions(
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
struct NodeAcc {
    m: f64,
    row1: BTreeMap<usize, f64>,
    row2: BTreeMap<usize, f64>,
}

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
    let forward = one_way(
        name,
        sides,
        search,
        with_gap,
        fixed[0],
        ["side 1", "side 2"],
    );
    let backward = one_way(
        name,
        [sides[1], sides[0]],
        search,
        with_gap,
        fixed[1],
        ["side 2", "side 1"],
    );
    match (forward, backward) {
        (Ok(f), Ok(b)) if b.len() < f.len() => Ok(reversed(b)),
        (Ok(f), _) => Ok(f),
        (Err(_), Ok(b)) => Ok(reversed(b)),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_of_overlapping_squares() {
        let a = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let b = [[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]];
        let c = clip_polygon(&b, &a);
        assert!((area(&c) - 1.0).abs() < 1e-14);
        let tri = [[0.5, -1.0], [1.5, -1.0], [1.0, 5.0]];
        let c = clip_polygon(&tri, &a);
        // The triangle's part inside the square: a trapezoid between y = 0 and y = 2.
        let width = |y: f64| 1.0 - (y + 1.0) / 6.0;
        assert!((area(&c) - 0.5 * (width(0.0) + width(2.0)) * 2.0).abs() < 1e-14);
    }

    #[test]
    fn dual_basis_is_biorthogonal() {
        for (kind, x) in [
            (CellType::Line2, vec![[0.0, 0.0, 0.0], [2.0, 0.5, 0.0]]),
            (
                CellType::Line3,
                vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.1, 0.0]],
            ),
            (
                CellType::Quad4,
                vec![
                    [0.0, 0.0, 0.0],
                    [2.0, 0.0, 0.0],
                    [2.0, 1.0, 0.0],
                    [0.0, 1.5, 0.0],
                ],
            ),
            (
                CellType::Tri6,
                vec![
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.5, 0.0, 0.0],
                    [0.5, 0.5, 0.0],
                    [0.0, 0.5, 0.0],
                ],
            ),
        ] {
            let f = SideFacet {
                kind,
                nodes: (0..x.len()).collect(),
                x,
            };
            let mk = multiplier_kind(kind, true);
            let nm = mk.num_nodes();
            let a = dual_coefficients(&f, mk).unwrap();
            let q = Quadrature::for_cell(kind, 8);
            let mut phi = [0.0; MAX_NODES];
            let mut dphi = [[0.0; 3]; MAX_NODES];
            let mut gram = vec![0.0; nm * nm];
            let mut d = vec![0.0; nm];
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = facet_geometry(kind, &f.x, *xi);
                shape(mk, *xi, &mut phi, &mut dphi);
                let psi: Vec<f64> = (0..nm)
                    .map(|i| (0..nm).map(|j| a[i * nm + j] * phi[j]).sum())
                    .collect();
                let s: f64 = psi.iter().sum();
                assert!((s - 1.0).abs() < 1e-12, "{kind:?}: partition of unity {s}");
                for i in 0..nm {
                    d[i] += w * g.jac * phi[i];
                    for j in 0..nm {
                        gram[i * nm + j] += w * g.jac * psi[i] * phi[j];
                    }
                }
            }
            for i in 0..nm {
                for j in 0..nm {
                    let want = if i == j { d[i] } else { 0.0 };
                    assert!(
                        (gram[i * nm + j] - want).abs() < 1e-12,
                        "{kind:?} ({i}, {j}): {} vs {want}",
                        gram[i * nm + j]
                    );
                }
            }
        }
    }
}
