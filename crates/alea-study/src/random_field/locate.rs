//! Locating a point on a field's mesh: the nearest cell (segment, triangle or tetrahedron)
//! and the P1 weights of its closest point there.

use alea_mesh::vec3::{dot, sub};
use alea_uq::field::FieldMesh;

use super::FieldPoint;

/// The nearest cell of `mesh` to `x` (ties to the lowest cell index) and the P1 weights of its
/// point closest to `x`.
pub(super) fn locate_on(mesh: &FieldMesh, x: [f64; 3]) -> FieldPoint {
    let mut best = (f64::INFINITY, 0, Vec::new());
    if mesh.num_cells() == 0 {
        return FieldPoint {
            nodes: Vec::new(),
            weights: Vec::new(),
        };
    }
    for c in 0..mesh.num_cells() {
        let cell = mesh.cell(c);
        let pts: Vec<[f64; 3]> = cell.iter().map(|&i| mesh.nodes()[i]).collect();
        let (d2, w) = match pts.len() {
            2 => {
                let (d2, w) = closest_on_segment(&pts[0], &pts[1], &x);
                (d2, w[..2].to_vec())
            }
            3 => {
                let (d2, w) = closest_on_triangle(&pts, &x);
                (d2, w.to_vec())
            }
            _ => closest_on_tetrahedron(&pts, &x),
        };
        if d2 < best.0 {
            best = (d2, c, w);
        }
    }
    FieldPoint {
        nodes: mesh.cell(best.1).to_vec(),
        weights: best.2,
    }
}

/// Squared distance from `x` to the segment `[a, b]` and the P1 weights of the closest point.
fn closest_on_segment(a: &[f64; 3], b: &[f64; 3], x: &[f64; 3]) -> (f64, [f64; 3]) {
    let ab = sub(b, a);
    let t = (dot(&sub(x, a), &ab) / dot(&ab, &ab)).clamp(0.0, 1.0);
    let p = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
    let d = sub(x, &p);
    (dot(&d, &d), [1.0 - t, t, 0.0])
}

/// Squared distance from `x` to the triangle `pts` and the barycentric weights of the closest
/// point: the projection onto the plane when it falls inside, else the closest point of the
/// nearest edge.
fn closest_on_triangle(pts: &[[f64; 3]], x: &[f64; 3]) -> (f64, [f64; 3]) {
    let (e1, e2, r) = (
        sub(&pts[1], &pts[0]),
        sub(&pts[2], &pts[0]),
        sub(x, &pts[0]),
    );
    let (a, b, c) = (dot(&e1, &e1), dot(&e1, &e2), dot(&e2, &e2));
    let (d, e) = (dot(&r, &e1), dot(&r, &e2));
    let det = a * c - b * b;
    let s = (c * d - b * e) / det;
    let t = (a * e - b * d) / det;
    if s >= 0.0 && t >= 0.0 && s + t <= 1.0 {
        let p: Vec<f64> = (0..3).map(|k| pts[0][k] + s * e1[k] + t * e2[k]).collect();
        let q = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
        return (dot(&q, &q), [1.0 - s - t, s, t]);
    }
    let mut best = (f64::INFINITY, [0.0; 3]);
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let (d2, w) = closest_on_segment(&pts[i], &pts[j], x);
        if d2 < best.0 {
            let mut bw = [0.0; 3];
            bw[i] = w[0];
            bw[j] = w[1];
            best = (d2, bw);
        }
    }
    best
}

/// Squared distance from `x` to the tetrahedron `pts` and the barycentric weights of the closest
/// point: `x` itself when inside, else the closest point of the nearest face.
fn closest_on_tetrahedron(pts: &[[f64; 3]], x: &[f64; 3]) -> (f64, Vec<f64>) {
    let (e1, e2, e3, r) = (
        sub(&pts[1], &pts[0]),
        sub(&pts[2], &pts[0]),
        sub(&pts[3], &pts[0]),
        sub(x, &pts[0]),
    );
    let det = |a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    };
    let d = det(&e1, &e2, &e3);
    let (l1, l2, l3) = (
        det(&r, &e2, &e3) / d,
        det(&e1, &r, &e3) / d,
        det(&e1, &e2, &r) / d,
    );
    let l0 = 1.0 - l1 - l2 - l3;
    if l0 >= 0.0 && l1 >= 0.0 && l2 >= 0.0 && l3 >= 0.0 {
        return (0.0, vec![l0, l1, l2, l3]);
    }
    let mut best = (f64::INFINITY, vec![0.0; 4]);
    for face in [[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]] {
        let tri: Vec<[f64; 3]> = face.iter().map(|&k| pts[k]).collect();
        let (d2, w) = closest_on_triangle(&tri, x);
        if d2 < best.0 {
            let mut bw = vec![0.0; 4];
            for (k, &v) in face.iter().enumerate() {
                bw[v] = w[k];
            }
            best = (d2, bw);
        }
    }
    best
}
