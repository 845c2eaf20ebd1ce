//! Quadrature rules on reference cells.
//!
//! Reference cells: line and quadrilateral/hexahedron on `[-1, 1]^d`; triangle
//! `{r, s >= 0, r + s <= 1}` (area 1/2); tetrahedron `{r, s, t >= 0, r + s + t <= 1}` (volume 1/6).
//! Gauss-Legendre points come from Newton's method on the three-term recurrence. Triangle and
//! tetrahedron rules of arbitrary degree are collapsed (Duffy / Stroud conical) products of
//! Gauss-Legendre rules: with `x = u (1 - v)` the Jacobian `(1 - v)` (and `(1 - w)^2` in 3D) is
//! integrated exactly by taking one or two more points. Low degrees use the classical symmetric
//! rules (centroid; 3-point and 4-point degree-2 rules).

use alea_mesh::CellType;

/// A quadrature rule: points (always 3 coordinates, unused ones 0) and weights.
#[derive(Clone, Debug)]
pub struct Quadrature {
    /// Points in reference coordinates.
    pub points: Vec<[f64; 3]>,
    /// Weights (they sum to the reference measure).
    pub weights: Vec<f64>,
}

/// Gauss-Legendre rule with `n` points on `[-1, 1]` (exact for degree `2n - 1`).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1);
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        // Initial guess (Tricomi), then Newton on P_n.
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { z } else { p1 };
            let pnm1 = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (z * pn - pnm1) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-15 {
                break;
            }
        }
        if n == 1 {
            z = 0.0;
            dp = 1.0;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    if n == 1 {
        w[0] = 2.0;
    }
    (x, w)
}

impl Quadrature {
    /// Tensor Gauss rule with `n` points per direction on `[-1, 1]^dim`.
    pub fn tensor(dim: usize, n: usize) -> Self {
        let (x, w) = gauss_legendre(n);
        let mut points = Vec::new();
        let mut weights = Vec::new();
        let nk = if dim == 3 { n } else { 1 };
        let nj = if dim >= 2 { n } else { 1 };
        for k in 0..nk {
            for j in 0..nj {
                for i in 0..n {
                    let mut p = [x[i], 0.0, 0.0];
                    let mut wt = w[i];
                    if dim >= 2 {
                        p[1] = x[j];
                        wt *= w[j];
                    }
                    if dim == 3 {
                        p[2] = x[k];
                        wt *= w[k];
                    }
                    points.push(p);
                    weights.push(wt);
                }
            }
        }
        Quadrature { points, weights }
    }

    /// Rule on the reference triangle exact for polynomials of total degree `degree`.
    pub fn triangle(degree: usize) -> Self {
        match degree {
            0 | 1 => Quadrature {
                points: vec![[1.0 / 3.0, 1.0 / 3.0, 0.0]],
                weights: vec![0.5],
            },
            2 => Quadrature {
                points: vec![
                    [1.0 / 6.0, 1.0 / 6.0, 0.0],
                    [2.0 / 3.0, 1.0 / 6.0, 0.0],
                    [1.0 / 6.0, 2.0 / 3.0, 0.0],
                ],
                weights: vec![1.0 / 6.0; 3],
            },
            _ => {
                // Collapsed product: (u, v) in [0,1]^2, r = u (1 - v), s = v, Jacobian (1 - v).
                let n = (degree + 2).div_ceil(2);
                let (x, w) = gauss_legendre(n);
                let mut q = Quadrature {
                    points: vec![],
                    weights: vec![],
                };
                for j in 0..n {
                    let v = 0.5 * (x[j] + 1.0);
                    for i in 0..n {
                        let u = 0.5 * (x[i] + 1.0);
                        q.points.push([u * (1.0 - v), v, 0.0]);
                        q.weights.push(0.25 * w[i] * w[j] * (1.0 - v));
                    }
                }
                q
            }
        }
    }

    /// Rule on the reference tetrahedron exact for polynomials of total degree `degree`.
    pub fn tetrahedron(degree: usize) -> Self {
        match degree {
            0 | 1 => Quadrature {
                points: vec![[0.25, 0.25, 0.25]],
                weights: vec![1.0 / 6.0],
            },
            2 => {
                let a = 0.138_196_601_125_010_5;
                let b = 0.585_410_196_624_968_5;
                Quadrature {
                    points: vec![[a, a, a], [b, a, a], [a, b, a], [a, a, b]],
                    weights: vec![1.0 / 24.0; 4],
                }
            }
            _ => {
                // r = u (1 - v)(1 - w), s = v (1 - w), t = w; Jacobian (1 - v)(1 - w)^2.
                let n = (degree + 3).div_ceil(2);
                let (x, wg) = gauss_legendre(n);
                let mut q = Quadrature {
                    points: vec![],
                    weights: vec![],
                };
                for k in 0..n {
                    let w = 0.5 * (x[k] + 1.0);
                    for j in 0..n {
                        let v = 0.5 * (x[j] + 1.0);
                        for i in 0..n {
                            let u = 0.5 * (x[i] + 1.0);
                            q.points.push([u * (1.0 - v) * (1.0 - w), v * (1.0 - w), w]);
                            q.weights.push(
                                0.125 * wg[i] * wg[j] * wg[k] * (1.0 - v) * (1.0 - w) * (1.0 - w),
                            );
                        }
                    }
                }
                q
            }
        }
    }

    /// Rule exact for polynomials of degree `degree` (per direction on tensor cells) on the
    /// reference cell of `kind`.
    pub fn for_cell(kind: CellType, degree: usize) -> Self {
        let n = (degree + 2) / 2; // 2n - 1 >= degree
        match kind {
            CellType::Line2 | CellType::Line3 => Self::tensor(1, n.max(1)),
            CellType::Quad4 | CellType::Quad8 => Self::tensor(2, n.max(1)),
            CellType::Hex8 => Self::tensor(3, n.max(1)),
            CellType::Tri3 | CellType::Tri6 => Self::triangle(degree),
            CellType::Tet4 | CellType::Tet10 => Self::tetrahedron(degree),
        }
    }

    /// The rule used for stiffness matrices and body loads: exact for `B^T D B` on affine
    /// simplices, full integration (2x2, 3x3, 2x2x2) on tensor cells.
    pub fn stiffness(kind: CellType) -> Self {
        match kind {
            CellType::Tri3 | CellType::Tet4 => Self::for_cell(kind, 2),
            CellType::Tri6 => Self::triangle(4),
            CellType::Tet10 => Self::tetrahedron(4),
            CellType::Quad4 | CellType::Hex8 | CellType::Line2 => Self::for_cell(kind, 3),
            CellType::Quad8 | CellType::Line3 => Self::for_cell(kind, 5),
        }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// True if the rule has no points.
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn quadrature_integrates_monomials_exactly() {
        use crate::quadrature::Quadrature;
        // Triangle: int r^a s^b = a! b! / (a + b + 2)!.
        let fact = |n: usize| (1..=n).product::<usize>() as f64;
        for deg in 1..=8 {
            let q = Quadrature::triangle(deg);
            for a in 0..=deg {
                let b = deg - a;
                let got: f64 = q
                    .points
                    .iter()
                    .zip(&q.weights)
                    .map(|(p, w)| w * p[0].powi(a as i32) * p[1].powi(b as i32))
                    .sum();
                let want = fact(a) * fact(b) / fact(a + b + 2);
                assert!((got - want).abs() < 1e-14, "tri deg {deg} r^{a} s^{b}");
            }
            let q = Quadrature::tetrahedron(deg);
            for a in 0..=deg {
                for b in 0..=deg - a {
                    let c = deg - a - b;
                    let got: f64 = q
                        .points
                        .iter()
                        .zip(&q.weights)
                        .map(|(p, w)| {
                            w * p[0].powi(a as i32) * p[1].powi(b as i32) * p[2].powi(c as i32)
                        })
                        .sum();
                    let want = fact(a) * fact(b) * fact(c) / fact(a + b + c + 3);
                    assert!((got - want).abs() < 1e-14, "tet deg {deg}");
                }
            }
        }
        for n in 1..8 {
            let (x, w) = crate::quadrature::gauss_legendre(n);
            for d in 0..2 * n {
                let got: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(d as i32)).sum();
                let want = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d as f64 + 1.0)
                };
                assert!((got - want).abs() < 1e-13, "GL n={n} x^{d}");
            }
        }
    }
}
