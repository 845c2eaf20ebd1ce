//! A certificate that no static equilibrium exists, for runs stopped by the iteration limit
//! out of balance (issue 21: a slow run must be "not converged", and "no equilibrium" only
//! when none exists).
//!
//! In any static solution every substructure `s` is in equilibrium in its free rigid modes `V`
//! (module [`crate::equilibrium`]) under its applied loads `g` and the interface forces on it:
//!
//! ```text
//! V^T ( g + sum_points m_p R_p^T F_p ) = 0,   F_p in C_p,
//! ```
//!
//! where `C_p` is the set of forces the interface law admits at point `p` on that side: any
//! force for a perfect interface; for Coulomb contact, with `Phi = F_2 = -F_1` and `n` the
//! outward normal of side 1 (module [`crate::law`]), the friction cone `Phi.n >= 0,
//! |Phi_t| <= mu Phi.n` (whatever the gap: a gap may close). So `-V^T g` must lie in the convex
//! cone spanned by the generators of the `C_p` mapped to the free modes. If it does not, no
//! static solution exists, whatever the elasticity and the gaps: that is the certificate.
//!
//! The cones are replaced by polyhedral cones that contain them: in 2D the two edges
//! `n +- mu t` (exact); in 3D eight edges `n + mu / cos(pi / 8) (cos th t_1 + sin th t_2)`,
//! whose cone circumscribes the circular one. A larger cone can only make the test answer
//! "maybe", never exclude a load the true cones balance. Membership is decided by non-negative
//! least squares (Lawson and Hanson's active-set method on at most 6 rows): the load is excluded
//! when the distance from `-V^T g` to the cone exceeds [`EXCLUSION`] times its norm.
//!
//! What the test cannot tell: a load inside the cones for which the elastic problem still has
//! no solution (the necessary condition holds, existence is not proven), and a run that is
//! merely slow. Both stay "not converged".

use crate::PointData;

use super::LatinSolver;

/// Relative distance from the cone above which a load is certified unbalanceable.
const EXCLUSION: f64 = 1e-6;

impl LatinSolver {
    /// True if some substructure carries, in its free rigid modes, an applied load (with the
    /// run's `load_factors`) that no interface forces admitted by the laws at `points` (the
    /// run's point data: its friction coefficients) can balance: then no static equilibrium
    /// exists (module doc).
    pub(super) fn equilibrium_excluded(
        &self,
        points: &[Vec<PointData>],
        load_factors: &[Vec<f64>],
    ) -> bool {
        self.subs.iter().enumerate().any(|(s, op)| {
            let rm = &op.rigid;
            let nf = rm.num_free();
            if nf == 0 {
                return false;
            }
            let (g, _) = rm.applied(load_factors.get(s).map(|v| v.as_slice()));
            let target: Vec<f64> = rm.free_components(&g).iter().map(|v| -v).collect();
            let size = target.iter().map(|v| v * v).sum::<f64>().sqrt();
            if !(size > 0.0) {
                return false;
            }
            let coords = &op.model.mesh.coords;
            let dim = op.model.mesh.dim;
            let mut columns: Vec<Vec<f64>> = Vec::new();
            for l in &op.links {
                let iface = &self.ifaces[l.iface];
                let perfect = iface.law.name() != "coulomb";
                // Force on this side: `Phi` on side 2, `-Phi` on side 1.
                let sign = if l.side == 1 { 1.0 } else { -1.0 };
                for (p, &m) in l.proj.weights.iter().enumerate() {
                    let Some(pd) = points.get(l.iface).and_then(|v| v.get(p)) else {
                        continue;
                    };
                    for d in generators(dim, pd, perfect) {
                        let mut column = vec![0.0; g.len()];
                        let mut scale = 0.0;
                        for (n, c) in l.proj.row(p) {
                            let f = [
                                sign * m * c * d[0],
                                sign * m * c * d[1],
                                sign * m * c * d[2],
                            ];
                            rm.add_force(&coords[n], &f, &mut column, &mut scale);
                        }
                        let col = rm.free_components(&column);
                        let norm = col.iter().map(|v| v * v).sum::<f64>().sqrt();
                        if norm > 0.0 {
                            columns.push(col.iter().map(|v| v / norm).collect());
                        }
                    }
                }
            }
            cone_distance(&columns, &target) > EXCLUSION * size
        })
    }
}

/// Edges of a polyhedral cone containing the admissible forces `Phi` at a point (module doc):
/// every direction (`+-e_i`) for a perfect interface.
fn generators(dim: usize, p: &PointData, perfect: bool) -> Vec<[f64; 3]> {
    if perfect {
        return (0..dim)
            .flat_map(|i| {
                let mut e = [0.0; 3];
                e[i] = 1.0;
                [e, [-e[0], -e[1], -e[2]]]
            })
            .collect();
    }
    let n = p.normal;
    let mu = p.mu.max(0.0);
    if dim == 2 {
        let t = [-n[1], n[0], 0.0];
        return [1.0, -1.0]
            .iter()
            .map(|s| [n[0] + s * mu * t[0], n[1] + s * mu * t[1], 0.0])
            .collect();
    }
    let axis = (0..3)
        .min_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[axis] = 1.0;
    let t1 = alea_mesh::vec3::cross(&n, &e);
    let l1 = alea_mesh::vec3::norm(&t1);
    let t1 = [t1[0] / l1, t1[1] / l1, t1[2] / l1];
    let t2 = alea_mesh::vec3::cross(&n, &t1);
    let k = 8;
    let r = mu / (std::f64::consts::PI / k as f64).cos();
    (0..k)
        .map(|j| {
            let th = 2.0 * std::f64::consts::PI * j as f64 / k as f64;
            let (c, s) = (th.cos(), th.sin());
            [
                n[0] + r * (c * t1[0] + s * t2[0]),
                n[1] + r * (c * t1[1] + s * t2[1]),
                n[2] + r * (c * t1[2] + s * t2[2]),
            ]
        })
        .collect()
}

/// Distance from `b` to the cone `{A x : x >= 0}` spanned by `columns` (each of `b`'s length),
/// by Lawson and Hanson's non-negative least squares.
fn cone_distance(columns: &[Vec<f64>], b: &[f64]) -> f64 {
    let k = b.len();
    let n = columns.len();
    let mut x = vec![0.0; n];
    let mut passive: Vec<usize> = Vec::new();
    let residual = |x: &[f64]| -> Vec<f64> {
        let mut r = b.to_vec();
        for (xj, col) in x.iter().zip(columns) {
            if *xj != 0.0 {
                for (ri, ci) in r.iter_mut().zip(col) {
                    *ri -= xj * ci;
                }
            }
        }
        r
    };
    let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
    let scale = norm(b).max(f64::MIN_POSITIVE);
    for _ in 0..(3 * n + 10).min(10_000) {
        let r = residual(&x);
        let dual = |j: usize| columns[j].iter().zip(&r).map(|(a, b)| a * b).sum::<f64>();
        let Some((j, w)) = (0..n)
            .filter(|j| !passive.contains(j))
            .map(|j| (j, dual(j)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            break;
        };
        if w <= 1e-14 * scale {
            break;
        }
        passive.push(j);
        // Inner loop: least squares on the passive columns, kept feasible.
        loop {
            let Some(z) = least_squares(columns, &passive, b, k) else {
                passive.pop();
                return norm(&residual(&x));
            };
            if z.iter().all(|&v| v > 0.0) {
                for (&i, &v) in passive.iter().zip(&z) {
                    x[i] = v;
                }
                break;
            }
            let alpha = passive
                .iter()
                .zip(&z)
                .filter(|(_, v)| **v <= 0.0)
                .map(|(&i, &v)| x[i] / (x[i] - v))
                .fold(f64::INFINITY, f64::min);
            for (&i, &v) in passive.iter().zip(&z) {
                x[i] += alpha * (v - x[i]);
            }
            passive.retain(|&i| x[i] > 1e-15);
            for (i, xi) in x.iter_mut().enumerate() {
                if !passive.contains(&i) {
                    *xi = 0.0;
                }
            }
            if passive.is_empty() {
                break;
            }
        }
    }
    norm(&residual(&x))
}

/// `argmin |A_P z - b|` over the columns `passive` (normal equations, pivoted elimination);
/// `None` when they are linearly dependent.
fn least_squares(columns: &[Vec<f64>], passive: &[usize], b: &[f64], k: usize) -> Option<Vec<f64>> {
    let m = passive.len();
    if m > k {
        return None;
    }
    let mut a = vec![0.0; m * m];
    let mut rhs = vec![0.0; m];
    for (r, &i) in passive.iter().enumerate() {
        for (c, &j) in passive.iter().enumerate() {
            a[r * m + c] = columns[i].iter().zip(&columns[j]).map(|(p, q)| p * q).sum();
        }
        rhs[r] = columns[i].iter().zip(b).map(|(p, q)| p * q).sum();
    }
    let floor = 1e-12 * (0..m).map(|i| a[i * m + i]).fold(0.0, f64::max);
    crate::dense::solve_pivoted(&mut a, &mut rhs, m, floor)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The distance to the cone of the two edges `(1, 0)` and `(1, 1)` in the plane: zero
    /// inside, the distance to the nearest edge or the apex outside.
    #[test]
    fn cone_distance_is_zero_inside_and_the_euclidean_distance_outside() {
        let s = 1.0 / 2f64.sqrt();
        let cols = vec![vec![1.0, 0.0], vec![s, s]];
        assert!(cone_distance(&cols, &[2.0, 1.0]) < 1e-12);
        assert!(cone_distance(&cols, &[1.0, 0.0]) < 1e-12);
        // Below the first edge: distance to it.
        assert!((cone_distance(&cols, &[1.0, -0.5]) - 0.5).abs() < 1e-12);
        // Opposite: the apex.
        assert!((cone_distance(&cols, &[-3.0, -4.0]) - 5.0).abs() < 1e-12);
        // Beyond the second edge: distance to the line x = y.
        assert!((cone_distance(&cols, &[0.0, 1.0]) - s).abs() < 1e-12);
        // A redundant, non-generic set of 3D columns.
        let cols3 = vec![
            vec![1.0, 0.0, 0.0],
            vec![0.0, 1.0, 0.0],
            vec![s, s, 0.0],
            vec![0.0, 0.0, 1.0],
        ];
        assert!(cone_distance(&cols3, &[1.0, 2.0, 3.0]) < 1e-12);
        assert!((cone_distance(&cols3, &[1.0, 2.0, -3.0]) - 3.0).abs() < 1e-12);
    }

    /// The 3D polyhedral cone contains the circular friction cone: every direction on its
    /// boundary is a non-negative combination of the edges.
    #[test]
    fn the_3d_edges_circumscribe_the_friction_cone() {
        let p = PointData {
            x: [0.0; 3],
            normal: [0.36, 0.48, 0.8],
            mu: 0.4,
            gap: 0.0,
        };
        let cols: Vec<Vec<f64>> = generators(3, &p, false)
            .into_iter()
            .map(|d| d.to_vec())
            .collect();
        let n = p.normal;
        let t1 = {
            let v = alea_mesh::vec3::cross(&n, &[1.0, 0.0, 0.0]);
            let l = alea_mesh::vec3::norm(&v);
            [v[0] / l, v[1] / l, v[2] / l]
        };
        let t2 = alea_mesh::vec3::cross(&n, &t1);
        for j in 0..97 {
            let th = j as f64 * 0.0647;
            let d: Vec<f64> = (0..3)
                .map(|i| n[i] + p.mu * (th.cos() * t1[i] + th.sin() * t2[i]))
                .collect();
            assert!(cone_distance(&cols, &d) < 1e-12, "{th}");
        }
        // Just outside the circumscribed cone: excluded.
        let wide: Vec<f64> = (0..3).map(|i| n[i] + 0.5 * t1[i]).collect();
        assert!(cone_distance(&cols, &wide) > 1e-3);
    }
}
