//! Segment-to-segment integration (module doc, "Integration"): the corners of a side-1 facet
//! and of every side-2 facet facing it are projected on the side-1 facet's auxiliary plane
//! (line), the side-2 polygons clipped by the side-1 polygon (Sutherland-Hodgman; intervals in
//! 2D), the pieces within the search distance triangulated and integrated with Gauss rules (6
//! points per segment in 2D, degree 6 per triangle in 3D) whose points are mapped back to both
//! facets, with the surface factor `1 / |n_1(xi) . n_0|` (and the thickness in 2D).

use alea_fem::Quadrature;
use alea_fem::kinematics::facet_geometry;
use alea_fem::quadrature::gauss_legendre;
use alea_mesh::vec3::{dot, sub};

use super::V3;
use super::geometry::{SideFacet, centre, frame, position, project};

/// One integration point of a side-1 facet: the side-2 facet, both reference points, weight.
pub(super) struct IPoint {
    pub(super) e2: usize,
    pub(super) xi1: V3,
    pub(super) xi2: V3,
    pub(super) w: f64,
}

/// Signed area of a plane polygon.
pub(super) fn area(poly: &[[f64; 2]]) -> f64 {
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
pub(super) fn clip_polygon(subject: &[[f64; 2]], clip: &[[f64; 2]]) -> Vec<[f64; 2]> {
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

/// The integration points of side-1 facet `f1` against the side-2 facets `cands` (indices into
/// `side2`), and the covered fraction of the facet.
pub(super) fn integration_points(
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
