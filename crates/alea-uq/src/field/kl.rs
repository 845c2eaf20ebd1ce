//! Galerkin Karhunen-Loeve discretisation of a covariance kernel on a P1 mesh.
//!
//! The KL eigenpairs solve the Fredholm problem `int_D k(x, y) phi(y) dy = lambda phi(x)`.
//! With `phi = sum_j v_j phi_j` in the P1 basis and Galerkin test functions `phi_i`, this becomes
//! the generalised symmetric eigenproblem
//!
//! ```text
//! C v = lambda M v,   C_ij = int_D int_D k(x, y) phi_i(x) phi_j(y) dx dy,   M_ij = int_D phi_i phi_j.
//! ```
//!
//! `C` is assembled cell pair by cell pair with a tensor quadrature (Gauss-Legendre on segments,
//! the 6-point degree-4 rule on triangles). On a diagonal pair of segments the kernel has a kink
//! at `x = y`, so the square is split along its diagonal and each half integrated with a
//! Duffy-collapsed Gauss rule (smooth integrand); a diagonal pair of triangles uses the rule on
//! the 4 midpoint sub-triangles. With `M = L L^T` (Cholesky), the problem is reduced to the
//! standard one `(L^-1 C L^-T) w = lambda w` solved by a dense self-adjoint eigensolver, and
//! `v = L^-T w`, so the modes are M-orthonormal: `int phi_k phi_l = delta_kl`.
//!
//! Galerkin eigenvalues bound the exact ones from below and converge as `h^4` with P1 elements
//! (the square of the `h^2` L2 error of the modes); tests/kl_field.rs measures both rates
//! against the closed-form KL of the exponential kernel.
//!
//! Determinism: the cell-pair blocks are computed in parallel but assembled in a fixed order,
//! and the dense Cholesky, products and eigensolver run sequentially, so the expansion is
//! bit-identical whatever the number of threads.
//!
//! Truncation keeps the `m` largest eigenvalues, `m` given or the smallest count with
//! `sum_{k<m} lambda_k >= f int_D sigma^2(x) dx` for a stated variance fraction `f` (the total
//! `int_D k(x, x) dx = sigma^2 |D|` is the trace of the covariance operator).
//!
//! A realisation at the nodes from independent standard normal KL variables `xi_k` is
//! `g(x) = mean + sum_k sqrt(lambda_k) phi_k(x) xi_k`; its covariance is the truncated kernel
//! `k_m(x, y) = sum_{k<m} lambda_k phi_k(x) phi_k(y)`.

use super::covariance::Covariance;
use super::mesh::{CellRule, FieldCells, FieldMesh, gauss_legendre01};
use crate::error::{Result, UqError, check_len, invalid};
use faer::diag::Diag;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{cholesky_in_place, cholesky_in_place_scratch};
use faer::linalg::evd::{ComputeEigenvectors, self_adjoint_evd, self_adjoint_evd_scratch};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Accum, Mat, Par};
use rayon::prelude::*;

/// Where to cut the KL series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Truncation {
    /// Keep exactly this many modes (at least 1).
    Modes(usize),
    /// Keep the fewest modes whose eigenvalues sum to at least this fraction (in (0, 1]) of
    /// `int_D sigma^2`.
    VarianceFraction(f64),
}

/// A truncated Karhunen-Loeve expansion on a P1 mesh.
#[derive(Debug, Clone)]
pub struct KlExpansion {
    mesh: FieldMesh,
    eigenvalues: Vec<f64>,
    /// Mode `k` at node `i` is `modes[k * n + i]`.
    modes: Vec<f64>,
    total_variance: f64,
    discrete_variance: f64,
}

/// Quadrature points of one cell in physical space with P1 shape values.
struct CellPoints {
    x: Vec<[f64; 3]>,
    w: Vec<f64>,
    shape: Vec<[f64; 4]>,
}

fn physical(mesh: &FieldMesh, c: usize, bary: &[[f64; 4]], w: &[f64]) -> CellPoints {
    let cell = mesh.cell(c);
    let nodes = mesh.nodes();
    let mut x = Vec::with_capacity(bary.len());
    for b in bary {
        let mut p = [0.0; 3];
        for (a, &i) in cell.iter().enumerate() {
            for d in 0..3 {
                p[d] += b[a] * nodes[i][d];
            }
        }
        x.push(p);
    }
    CellPoints {
        x,
        w: w.iter().map(|wq| wq * mesh.cell_measure(c)).collect(),
        shape: bary.to_vec(),
    }
}

/// `int_e int_f k(x, y) phi_a(x) phi_b(y)` with tensor quadrature on `(p, q)`.
fn pair_block(cov: &Covariance, p: &CellPoints, q: &CellPoints, nv: usize) -> [[f64; 4]; 4] {
    let mut blk = [[0.0; 4]; 4];
    for (ip, xp) in p.x.iter().enumerate() {
        let mut row = [0.0; 4];
        for (iq, yq) in q.x.iter().enumerate() {
            let kw = cov.eval(xp, yq) * q.w[iq];
            for (b, r) in row.iter_mut().enumerate().take(nv) {
                *r += kw * q.shape[iq][b];
            }
        }
        for a in 0..nv {
            let f = p.w[ip] * p.shape[ip][a];
            for b in 0..nv {
                blk[a][b] += f * row[b];
            }
        }
    }
    blk
}

/// The diagonal block of a segment: the unit square split along `s = t`, each triangle mapped
/// from `(u, v)` in `[0, 1]^2` by `s = u, t = u v` (and symmetrically), Jacobian `u`.
fn segment_self_block(cov: &Covariance, mesh: &FieldMesh, c: usize, n: usize) -> [[f64; 4]; 4] {
    let cell = mesh.cell(c);
    let (x0, x1) = (mesh.nodes()[cell[0]], mesh.nodes()[cell[1]]);
    let at = |s: f64| {
        [
            x0[0] + s * (x1[0] - x0[0]),
            x0[1] + s * (x1[1] - x0[1]),
            x0[2] + s * (x1[2] - x0[2]),
        ]
    };
    let h2 = mesh.cell_measure(c).powi(2);
    let (g, gw) = gauss_legendre01(n);
    let mut blk = [[0.0; 4]; 4];
    for (iu, &u) in g.iter().enumerate() {
        for (iv, &v) in g.iter().enumerate() {
            let w = gw[iu] * gw[iv] * u * h2;
            // Triangle t < s: (s, t) = (u, u v); its mirror s < t: (s, t) = (u v, u).
            for (s, t) in [(u, u * v), (u * v, u)] {
                let k = cov.eval(&at(s), &at(t)) * w;
                let ns = [1.0 - s, s];
                let nt = [1.0 - t, t];
                for a in 0..2 {
                    for b in 0..2 {
                        blk[a][b] += k * ns[a] * nt[b];
                    }
                }
            }
        }
    }
    blk
}

/// How the double integral `C_ij` is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelIntegration {
    /// Quadrature per cell pair with the kink-aware rule on diagonal pairs (the default;
    /// eigenvalue error `O(h^4)`).
    Quadrature,
    /// The kernel replaced by its P1 interpolant `k_h(x, y) = sum_ij k(x_i, x_j) phi_i(x)
    /// phi_j(y)`, so `C = M K M` with `K_ij = k(x_i, x_j)`: the formulation of OpenTURNS's
    /// `KarhunenLoeveP1Algorithm` (eigenvalue error `O(h^2)`), kept for comparisons.
    NodalInterpolation,
}

/// `C` by quadrature over cell pairs (dense `n x n`).
fn assemble_by_quadrature(mesh: &FieldMesh, cov: &Covariance) -> Mat<f64> {
    let n = mesh.num_nodes();
    let nc = mesh.num_cells();
    let (rule, self_rule, segments) = match mesh.cells() {
        FieldCells::Segments(_) => (CellRule::segment(4), None, true),
        FieldCells::Triangles(_) => (
            CellRule::triangle(),
            Some(CellRule::triangle_subdivided()),
            false,
        ),
        FieldCells::Tetrahedra(_) => (
            CellRule::tetrahedron(),
            Some(CellRule::tetrahedron_subdivided()),
            false,
        ),
    };
    let nv = mesh.cell(0).len();
    let points: Vec<CellPoints> = (0..nc)
        .map(|c| physical(mesh, c, &rule.bary, &rule.weights))
        .collect();
    // Blocks (c, d) for d >= c, computed in parallel, assembled in a fixed order.
    let blocks: Vec<Vec<[[f64; 4]; 4]>> = (0..nc)
        .into_par_iter()
        .map(|c| {
            (c..nc)
                .map(|d| {
                    if d != c {
                        pair_block(cov, &points[c], &points[d], nv)
                    } else if segments {
                        segment_self_block(cov, mesh, c, 5)
                    } else {
                        let r = self_rule
                            .as_ref()
                            .expect("triangle and tetrahedron meshes have a self rule");
                        let p = physical(mesh, c, &r.bary, &r.weights);
                        pair_block(cov, &p, &p, nv)
                    }
                })
                .collect()
        })
        .collect();
    let mut cmat = Mat::<f64>::zeros(n, n);
    for (c, row) in blocks.iter().enumerate() {
        let ci = mesh.cell(c);
        for (off, blk) in row.iter().enumerate() {
            let d = c + off;
            let di = mesh.cell(d);
            for (a, &i) in ci.iter().enumerate() {
                for (b, &j) in di.iter().enumerate() {
                    cmat[(i, j)] += blk[a][b];
                    if d != c {
                        cmat[(j, i)] += blk[a][b];
                    }
                }
            }
        }
    }
    cmat
}

/// `C = M K M` with `K_ij = k(x_i, x_j)`.
fn assemble_by_nodal_interpolation(mesh: &FieldMesh, cov: &Covariance, mass: &[f64]) -> Mat<f64> {
    let n = mesh.num_nodes();
    let nodes = mesh.nodes();
    let kmat = Mat::<f64>::from_fn(n, n, |i, j| cov.eval(&nodes[i], &nodes[j]));
    let mmat = Mat::<f64>::from_fn(n, n, |i, j| mass[i * n + j]);
    let mut km = Mat::<f64>::zeros(n, n);
    matmul(
        km.as_mut(),
        Accum::Replace,
        kmat.as_ref(),
        mmat.as_ref(),
        1.0,
        Par::Seq,
    );
    let mut c = Mat::<f64>::zeros(n, n);
    matmul(
        c.as_mut(),
        Accum::Replace,
        mmat.as_ref(),
        km.as_ref(),
        1.0,
        Par::Seq,
    );
    c
}

impl KlExpansion {
    /// Galerkin KL of `cov` on `mesh`, truncated by `truncation` (`C` by quadrature).
    pub fn galerkin(mesh: &FieldMesh, cov: &Covariance, truncation: Truncation) -> Result<Self> {
        Self::galerkin_with(mesh, cov, truncation, KernelIntegration::Quadrature)
    }

    /// Galerkin KL with a chosen way of computing `C`.
    pub fn galerkin_with(
        mesh: &FieldMesh,
        cov: &Covariance,
        truncation: Truncation,
        integration: KernelIntegration,
    ) -> Result<Self> {
        match truncation {
            Truncation::Modes(m) if m == 0 || m > mesh.num_nodes() => {
                return Err(invalid(
                    "KL expansion",
                    "modes",
                    ">= 1 and <= the number of nodes",
                    m as f64,
                ));
            }
            Truncation::VarianceFraction(f) if !(f > 0.0 && f <= 1.0) => {
                return Err(invalid("KL expansion", "variance fraction", "in (0, 1]", f));
            }
            _ => {}
        }
        let n = mesh.num_nodes();
        let mass = mesh.mass_matrix();
        let mut cmat = match integration {
            KernelIntegration::Quadrature => assemble_by_quadrature(mesh, cov),
            KernelIntegration::NodalInterpolation => {
                assemble_by_nodal_interpolation(mesh, cov, &mass)
            }
        };
        // Sequential dense kernels throughout: the result does not depend on the thread count.
        let mut lmat = Mat::<f64>::from_fn(n, n, |i, j| if j <= i { mass[i * n + j] } else { 0.0 });
        cholesky_in_place(
            lmat.as_mut(),
            Default::default(),
            Par::Seq,
            MemStack::new(&mut MemBuffer::new(cholesky_in_place_scratch::<f64>(
                n,
                Par::Seq,
                Default::default(),
            ))),
            Default::default(),
        )
        .map_err(|_| UqError::Invalid {
            what: "KL expansion",
            message: "the P1 mass matrix is not positive definite".into(),
        })?;
        for i in 0..n {
            for j in i + 1..n {
                lmat[(i, j)] = 0.0;
            }
        }
        let l = lmat.as_ref();
        // A = L^-1 C L^-T: solve L X = C, then L A = X^T (C symmetric).
        solve_lower_triangular_in_place(l, cmat.as_mut(), Par::Seq);
        let mut a = cmat.transpose().to_owned();
        solve_lower_triangular_in_place(l, a.as_mut(), Par::Seq);
        for i in 0..n {
            for j in 0..i {
                let v = 0.5 * (a[(i, j)] + a[(j, i)]);
                a[(i, j)] = v;
                a[(j, i)] = v;
            }
        }
        let mut u = Mat::<f64>::zeros(n, n);
        let mut sdiag = Diag::<f64>::zeros(n);
        let compute = ComputeEigenvectors::Yes;
        self_adjoint_evd(
            a.as_ref(),
            sdiag.as_mut(),
            Some(u.as_mut()),
            Par::Seq,
            MemStack::new(&mut MemBuffer::new(self_adjoint_evd_scratch::<f64>(
                n,
                compute,
                Par::Seq,
                Default::default(),
            ))),
            Default::default(),
        )
        .map_err(|_| UqError::Invalid {
            what: "KL expansion",
            message: "the dense eigensolver did not converge".into(),
        })?;
        let s = sdiag.column_vector();
        // Descending order; only positive eigenvalues are kept.
        let order: Vec<usize> = (0..n).rev().filter(|&k| s[k] > 0.0).collect();
        let discrete_variance: f64 = order.iter().map(|&k| s[k]).sum();
        let total_variance = cov.variance() * mesh.measure();
        let m = match truncation {
            Truncation::Modes(m) => {
                if m > order.len() {
                    return Err(UqError::Invalid {
                        what: "KL expansion",
                        message: format!(
                            "{m} modes asked, only {} positive eigenvalues",
                            order.len()
                        ),
                    });
                }
                m
            }
            Truncation::VarianceFraction(f) => {
                let target = f * total_variance;
                let mut acc = 0.0;
                let pos = order.iter().position(|&k| {
                    acc += s[k];
                    acc >= target
                });
                match pos {
                    Some(p) => p + 1,
                    None => {
                        return Err(UqError::Invalid {
                            what: "KL expansion",
                            message: format!(
                                "variance fraction {f} cannot be reached on this mesh: all {} modes capture {:.6} of the variance (refine the mesh or lower the fraction)",
                                order.len(),
                                discrete_variance / total_variance
                            ),
                        });
                    }
                }
            }
        };
        let mut w = Mat::<f64>::from_fn(n, m, |i, k| u[(i, order[k])]);
        solve_upper_triangular_in_place(l.transpose(), w.as_mut(), Par::Seq);
        let mut modes = vec![0.0; m * n];
        for k in 0..m {
            let col: Vec<f64> = (0..n).map(|i| w[(i, k)]).collect();
            // Sign convention: the first node with |phi| >= 0.1 max |phi| is positive.
            let amax = col.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let sign = col
                .iter()
                .find(|v| v.abs() >= 0.1 * amax)
                .map_or(1.0, |v| v.signum());
            for (dst, v) in modes[k * n..(k + 1) * n].iter_mut().zip(&col) {
                *dst = sign * v;
            }
        }
        let eigenvalues = order[..m].iter().map(|&k| s[k]).collect();
        Ok(Self {
            mesh: mesh.clone(),
            eigenvalues,
            modes,
            total_variance,
            discrete_variance,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &FieldMesh {
        &self.mesh
    }

    /// Number of retained modes (the number of KL variables).
    pub fn num_modes(&self) -> usize {
        self.eigenvalues.len()
    }

    /// Retained eigenvalues, largest first.
    pub fn eigenvalues(&self) -> &[f64] {
        &self.eigenvalues
    }

    /// Node values of mode `k` (M-orthonormal: `int phi_k phi_l = delta_kl`).
    pub fn mode(&self, k: usize) -> &[f64] {
        let n = self.mesh.num_nodes();
        &self.modes[k * n..(k + 1) * n]
    }

    /// `int_D sigma^2 = sigma^2 |D|`, the trace of the covariance operator.
    pub fn total_variance(&self) -> f64 {
        self.total_variance
    }

    /// Sum of the retained eigenvalues.
    pub fn captured_variance(&self) -> f64 {
        self.eigenvalues.iter().sum()
    }

    /// Fraction of `int_D sigma^2` captured by the retained modes.
    pub fn captured_fraction(&self) -> f64 {
        self.captured_variance() / self.total_variance
    }

    /// Sum of all positive eigenvalues of the discrete problem (the most any truncation on this
    /// mesh can capture).
    pub fn discrete_variance(&self) -> f64 {
        self.discrete_variance
    }

    /// Truncated covariance `k_m(x_i, x_j) = sum_k lambda_k phi_k(x_i) phi_k(x_j)` between nodes.
    pub fn truncated_covariance(&self, i: usize, j: usize) -> f64 {
        let n = self.mesh.num_nodes();
        self.eigenvalues
            .iter()
            .enumerate()
            .map(|(k, l)| l * self.modes[k * n + i] * self.modes[k * n + j])
            .sum()
    }

    /// Gaussian realisation at the nodes: `g_i = mean + sum_k sqrt(lambda_k) phi_k(x_i) xi_k`.
    pub fn realise(&self, mean: f64, xi: &[f64], out: &mut [f64]) -> Result<()> {
        let n = self.mesh.num_nodes();
        check_len("KL realisation", "xi", self.num_modes(), xi.len())?;
        check_len("KL realisation", "out", n, out.len())?;
        if let Some(x) = xi.iter().find(|x| !x.is_finite()) {
            return Err(invalid("KL realisation", "xi", "finite", *x));
        }
        out.fill(mean);
        for (k, (l, x)) in self.eigenvalues.iter().zip(xi).enumerate() {
            let a = l.sqrt() * x;
            for (o, p) in out.iter_mut().zip(&self.modes[k * n..(k + 1) * n]) {
                *o += a * p;
            }
        }
        Ok(())
    }
}
