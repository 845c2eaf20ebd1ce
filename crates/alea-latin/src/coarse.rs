//! The coarse (macro) problem of the two-scale LATIN: interface resultants and moments.
//!
//! Single-scale LATIN propagates a load through the assembly one substructure per iteration and
//! leaves floating substructures' rigid motions to hundreds of iterations; the two-scale
//! strategy (Ladeveze and Dureisseix 2000; Ladeveze, Loiseau and Dureisseix 2001; the thesis's
//! platform, 5.1) makes the linear stage satisfy the interface equilibrium of the **macro**
//! forces at every iteration by a small global problem.
//!
//! # Macro space
//! On interface `G`, the macro basis `e_j` (`j < 3` in 2D, `< 6` in 3D) is its rigid modes at
//! the interface points: translations and rotations `omega_j x (x - c_G) / R_G` about the
//! centroid `c_G` of its points (weights `m_p`), scaled by their largest distance `R_G` to it.
//! The macro part of the forces of side `s` is their resultant and moment,
//! `(E^T M_s F_s)_j = sum_p m_sp e_j(p) . F_s(p)`.
//!
//! # Linear stage with the macro constraint
//! The linear stage of substructure `s` minimises its energy plus the search-direction term
//! subject to `E^T (M_1 F_1 + M_2 F_2) = 0` on every interface (macro admissibility, which the
//! exact solution satisfies, so the LATIN fixed point is unchanged). With one multiplier vector
//! `lambda_G` per interface (a macro displacement), the search direction becomes
//! `F_s = F_hat_s - k_s (W_s - W_hat_s) - k_s E lambda_G`, i.e.
//! `(K + k Pi^T M Pi) u_s = f + Pi^T M (F_hat + k W_hat) - k Pi^T M E lambda` (with a search
//! direction per point, module `solver::direction`, `k` multiplies each point's values and
//! stands inside the sums below: `E^T M k (...)`). By linearity
//! `u_s = u_s^0 + sum_{G, j} lambda_Gj u_s^(Gj)` with the plain linear stage `u_s^0` and, at the
//! E-scaled factorisation `A0 = K0 + sum k0 Pi^T M Pi` (module `solver`), the responses
//! `u_s^(Gj) = -A0^-1 (k0 Pi^T M e_j)`, **independent of the run's Young's-modulus factor**:
//! they are computed once at set-up (one block solve per substructure), like the factorisation,
//! so multiresolution and warm starts are untouched. The macro equations
//! `sum_s E^T M_s F_s = 0` become the small symmetric system
//!
//! ```text
//! L lambda = b,   b_G = sum_{s in G} E^T M_s F_s^0,
//! L = sum_s alpha_s k0 [ E^T M Pi u^(G'j) + delta_GG' E^T M E ]   (positive semi-definite),
//! ```
//! assembled per run from per-substructure blocks (times the Young's-modulus factors
//! `alpha_s`), solved by its eigendecomposition (a pseudo-inverse: a group of substructures
//! that floats as a whole leaves a null direction, which is left alone), and applied after each
//! plain linear stage: `F_s -= k (sum lambda Pi u^(Gj) + E lambda_G)`, `u_s += sum lambda
//! u^(Gj)`, `W_s += sum lambda Pi u^(Gj)`. Per iteration this costs one dense product of the
//! order of the number of macro unknowns and a few vector updates per substructure.
//!
//! # Floating substructures
//! For a substructure with free rigid modes `r`, the response to its interfaces' rigid modes is
//! (close to) a rigid motion, `u^(Gj) ~ -r_j`: the macro correction moves it rigidly by
//! `-lambda`. With the same search direction in both stages this rigid move overshoots: on a
//! floating block pressed on a clamped one the block's position is reflected about the solution
//! at every iteration (an iteration eigenvalue `-1`, measured: the run never converges), which
//! the literature damps by relaxing the whole linear stage (`mu = 0.8`; Ladeveze, Loiseau and
//! Dureisseix 2001). Here only the rigid part of the *displacement* correction is damped: the
//! displacement correction is `u_d + RIGID_SHARE (u - u_d)` with `u_d` the response without its
//! least-squares rigid part in the free modes (module `equilibrium`), `RIGID_SHARE = 1/2` (the
//! exact share in the two-body case); the forces use the whole response, so the linear stage
//! stays admissible (a rigid motion in free modes does no work) and the fixed point (where
//! `lambda = 0`) is unchanged. Measured (plane-strain chain of `N` unit squares, perfect
//! interfaces, clamped at one end, Anderson depth 5, `k = 3 E / L`): 11, 10, 9, 10 iterations
//! for `N = 2, 4, 8, 16` against 18, 108, > 400 without the coarse problem; with the whole
//! rigid move (`RIGID_SHARE = 1`) the runs with `N >= 4` never converge. Without Anderson
//! acceleration the remaining oscillation needs some relaxation: the solver then relaxes the
//! linear stage by at most 0.8 (`LatinOptions::coarse`).
//!
//! # Open interfaces
//! The macro constraint `E^T (M_1 F_1 + M_2 F_2) = 0` lets an interface carry a macro force
//! (`F_1 = -F_2 != 0`), which only a closed interface can: on a contact interface that is open
//! at every point (initial gap, or every point open in the last local stage) the exact
//! solution has `F_1 = F_2 = 0` there, and imposing the balance instead glues the sides at the
//! macro level across the gap. A floating block with a uniform initial gap pressed onto a base
//! was then moved rigidly by the macro correction against the drift that closes the gap, and
//! the run stalled far from the contact ("no equilibrium"; issue 21). Such an interface's macro
//! unknowns are therefore left out of the coarse problem (zero rows and columns in `L`, zero
//! `lambda`) until a point of it closes again; the macro operator is re-inverted when this
//! active set changes (a dense `n x n` eigendecomposition, `n` = 3 per interface in 2D, 6 in
//! 3D). The first iteration, before any local stage, counts an interface open when its initial
//! gap is positive at every point.
//!
//! # Cyclic interfaces
//! On a cyclic interface (module [`crate::cyclic`]) side 2's fields are in its own frame,
//! rotated by `R` from the points' frame: its macro basis is `R e_j`, so that the macro
//! constraint balances the rotated resultant and moment, `E^T (M_1 F_1 + M_2 R^T F_2) = 0`.
//! When both sides belong to one substructure, its two links' responses to the same macro
//! unknown are two columns of the same index, whose sum is its response.
//!
//! # Search direction
//! A large search direction `k` makes the micro (short-wavelength) interface modes converge in
//! a mesh-independent number of iterations but leaves the long-wavelength (macro) ones to a
//! slow exchange between neighbours; the coarse problem removes the latter, which is why the
//! two-scale iteration works with a larger `k` than the single-scale one (default factor 3;
//! measured on Hertz's cylinder, see `BENCHMARKS.md`).

use faer::{Mat, Side};

use crate::equilibrium::RigidModes;
use crate::interface::SideProjection;
use crate::solver::direction::PointDirection;
use alea_fem::{Cholesky, DofMap};
use alea_mesh::vec3;

type V3 = [f64; 3];

/// The macro basis of one interface.
#[derive(Clone)]
pub(crate) struct InterfaceModes {
    /// First index of its unknowns in the macro vector.
    pub offset: usize,
    /// `modes[j][p]`: mode `j` at point `p`.
    pub modes: Vec<Vec<V3>>,
}

impl InterfaceModes {
    /// Rigid modes (`dim` = 2: 3 modes, 3: 6) at points `x` with weights `m`, orthonormalised
    /// in the weighted inner product `sum_p m_p e_i(p) . e_j(p)` (a mode that depends on the
    /// earlier ones, e.g. the rotation about the line of a straight 3D interface, is dropped).
    pub fn new(dim: usize, x: &[V3], m: &[f64], offset: usize) -> Self {
        let total: f64 = m.iter().sum();
        let mut c = [0.0; 3];
        for (xp, mp) in x.iter().zip(m) {
            for k in 0..3 {
                c[k] += mp * xp[k] / total.max(f64::MIN_POSITIVE);
            }
        }
        let radius = x
            .iter()
            .map(|p| ((0..3).map(|k| (p[k] - c[k]).powi(2)).sum::<f64>()).sqrt())
            .fold(0.0f64, f64::max);
        let radius = if radius > 0.0 { radius } else { 1.0 };
        let r = |p: &V3| {
            [
                (p[0] - c[0]) / radius,
                (p[1] - c[1]) / radius,
                (p[2] - c[2]) / radius,
            ]
        };
        let mut cands: Vec<Vec<V3>> = Vec::new();
        for k in 0..dim {
            let mut e = [0.0; 3];
            e[k] = 1.0;
            cands.push(vec![e; x.len()]);
        }
        // Rotations about the axes (2D: z only).
        let axes: &[usize] = if dim == 2 { &[2] } else { &[0, 1, 2] };
        for &k in axes {
            cands.push(
                x.iter()
                    .map(|p| {
                        let v = r(p);
                        match k {
                            0 => [0.0, -v[2], v[1]],
                            1 => [v[2], 0.0, -v[0]],
                            _ => [-v[1], v[0], 0.0],
                        }
                    })
                    .collect(),
            );
        }
        let dot = |u: &[V3], v: &[V3]| -> f64 {
            u.iter()
                .zip(v)
                .zip(m)
                .map(|((a, b), w)| w * vec3::dot(a, b))
                .sum()
        };
        let mut modes: Vec<Vec<V3>> = Vec::new();
        for mut e in cands {
            let n0 = dot(&e, &e).sqrt();
            for q in &modes {
                let s = dot(&e, q);
                for (ep, qp) in e.iter_mut().zip(q) {
                    for k in 0..3 {
                        ep[k] -= s * qp[k];
                    }
                }
            }
            let n = dot(&e, &e).sqrt();
            if n > 1e-6 * n0 && n > 0.0 {
                for ep in e.iter_mut() {
                    for v in ep.iter_mut() {
                        *v /= n;
                    }
                }
                modes.push(e);
            }
        }
        InterfaceModes { offset, modes }
    }

    /// The same macro unknowns seen from the other side of a cyclic interface: every mode
    /// rotated, `R e_j(p)` (module [`crate::cyclic`]).
    pub fn rotated(&self, r: &crate::cyclic::Mat3) -> Self {
        InterfaceModes {
            offset: self.offset,
            modes: self
                .modes
                .iter()
                .map(|e| e.iter().map(|v| crate::cyclic::apply(r, v)).collect())
                .collect(),
        }
    }

    /// Number of modes.
    pub fn len(&self) -> usize {
        self.modes.len()
    }

    /// `sum_p m_p e_j(p) . f(p)` for every mode `j`, added into `out`.
    pub fn add_resultants(&self, m: &[f64], f: &[V3], out: &mut [f64]) {
        for (j, e) in self.modes.iter().enumerate() {
            let mut s = 0.0;
            for ((mp, ep), fp) in m.iter().zip(e).zip(f) {
                s += mp * vec3::dot(ep, fp);
            }
            out[self.offset + j] += s;
        }
    }
}

/// Share of the rigid part (in the free rigid modes) of a substructure's macro response that
/// moves its displacement (module doc, "Floating substructures").
pub(crate) const RIGID_SHARE: f64 = 0.5;

/// The response of one substructure to one macro unknown of one of its interfaces.
#[derive(Clone)]
pub(crate) struct MacroColumn {
    /// Index in the macro vector.
    pub index: usize,
    /// Displacement correction (free unknowns) per unit macro unknown, with `RIGID_SHARE` of
    /// its rigid part in the substructure's free rigid modes.
    pub u: Vec<f64>,
    /// `Pi u` of that correction at the points of every link of the substructure.
    pub w: Vec<Vec<V3>>,
    /// `Pi u^(Gj)` of the whole response (rigid part included), for the forces.
    pub w_full: Vec<Vec<V3>>,
}

/// One side of an interface as the coarse problem sees it from its substructure.
pub(crate) struct MacroLink<'a> {
    /// Projection of the side.
    pub proj: &'a SideProjection,
    /// Reference search direction at every point (module `solver::direction`).
    pub dir: &'a [PointDirection],
    /// Macro basis of the interface.
    pub modes: &'a InterfaceModes,
}

/// The coarse-problem data of one substructure: its columns and its block of `L` at
/// `alpha = 1` (triplets `(row, column, value)` in the macro numbering).
#[derive(Clone)]
pub(crate) struct SubMacro {
    pub columns: Vec<MacroColumn>,
    pub l0: Vec<(usize, usize, f64)>,
}

impl SubMacro {
    /// Computes the responses `u^(Gj) = -A0^-1 (k0 Pi^T M e_j)` of a substructure (one block
    /// solve) and its block of `L`.
    pub fn new(
        dofs: &DofMap,
        chol: &Cholesky,
        links: &[MacroLink<'_>],
        rigid: &RigidModes,
        coords: &[V3],
    ) -> Self {
        let nf = dofs.num_free();
        let cols: Vec<(usize, usize)> = links
            .iter()
            .enumerate()
            .flat_map(|(l, ml)| (0..ml.modes.len()).map(move |j| (l, j)))
            .collect();
        if cols.is_empty() || nf == 0 {
            return SubMacro {
                columns: Vec::new(),
                l0: Vec::new(),
            };
        }
        let mut rhs = vec![0.0; nf * cols.len()];
        for (c, &(l, j)) in cols.iter().enumerate() {
            let ml = &links[l];
            let e = &ml.modes.modes[j];
            let out = &mut rhs[c * nf..(c + 1) * nf];
            for p in 0..ml.proj.len() {
                let d = &ml.dir[p];
                // Isotropic: (k0 m_p) c e, as the scalar direction always made it.
                let (s, ke) = if d.is_isotropic() {
                    (d.kt * ml.proj.weights[p], e[p])
                } else {
                    (ml.proj.weights[p], d.apply(1.0, &e[p]))
                };
                for (n, coef) in ml.proj.row(p) {
                    let sc = s * coef;
                    dofs.add_node_force(n, &[sc * ke[0], sc * ke[1], sc * ke[2]], out);
                }
            }
        }
        let mut scratch = chol.solve_scratch(cols.len());
        chol.solve_with(&mut rhs, &mut scratch);
        for v in rhs.iter_mut() {
            *v = -*v;
        }
        let columns: Vec<MacroColumn> = cols
            .iter()
            .enumerate()
            .map(|(c, &(l, j))| {
                let u = rhs[c * nf..(c + 1) * nf].to_vec();
                let w_full: Vec<Vec<V3>> = links
                    .iter()
                    .map(|ml| interpolate_homogeneous(dofs, ml.proj, &u))
                    .collect();
                let (u, w) = if rigid.num_free() > 0 {
                    let mut full = homogeneous(dofs, &u);
                    let mut def = full.clone();
                    rigid.remove_rigid_part(coords, &mut def);
                    for (f, d) in full.iter_mut().zip(&def) {
                        *f = d + RIGID_SHARE * (*f - d);
                    }
                    let u = dofs.reduce(&full);
                    let w = links
                        .iter()
                        .map(|ml| interpolate_homogeneous(dofs, ml.proj, &u))
                        .collect();
                    (u, w)
                } else {
                    (u, w_full.clone())
                };
                MacroColumn {
                    index: links[l].modes.offset + j,
                    u,
                    w,
                    w_full,
                }
            })
            .collect();
        let mut l0 = Vec::new();
        for (col, &(l, j)) in columns.iter().zip(&cols) {
            for (lr, ml) in links.iter().enumerate() {
                let mut g = vec![0.0; ml.modes.len()];
                let shifted = InterfaceModes {
                    offset: 0,
                    modes: ml.modes.modes.clone(),
                };
                if let Some(k0) = uniform(ml.dir) {
                    // k0 E^T M (Pi u + E): the scalar direction's operations.
                    shifted.add_resultants(&ml.proj.weights, &col.w_full[lr], &mut g);
                    if lr == l {
                        shifted.add_resultants(&ml.proj.weights, &links[l].modes.modes[j], &mut g);
                    }
                    for v in g.iter_mut() {
                        *v *= k0;
                    }
                } else {
                    // E^T M k (Pi u + E), k per point.
                    let kw: Vec<V3> = (0..ml.proj.len())
                        .map(|p| {
                            let mut v = col.w_full[lr][p];
                            if lr == l {
                                let e = links[l].modes.modes[j][p];
                                for c in 0..3 {
                                    v[c] += e[c];
                                }
                            }
                            ml.dir[p].apply(1.0, &v)
                        })
                        .collect();
                    shifted.add_resultants(&ml.proj.weights, &kw, &mut g);
                }
                for (i, v) in g.into_iter().enumerate() {
                    if v != 0.0 {
                        l0.push((ml.modes.offset + i, col.index, v));
                    }
                }
            }
        }
        SubMacro { columns, l0 }
    }
}

/// The common `k` of a side whose direction is isotropic and the same at every point.
fn uniform(dir: &[PointDirection]) -> Option<f64> {
    let k = dir.first().map_or(1.0, |d| d.kt);
    dir.iter()
        .all(|d| d.is_isotropic() && d.kt == k)
        .then_some(k)
}

/// The full node-major displacement `T u` of free unknowns `u`, without the prescribed part.
fn homogeneous(dofs: &DofMap, u: &[f64]) -> Vec<f64> {
    let d = dofs.dim;
    let mut full = dofs.expand(u);
    for n in 0..dofs.num_nodes() {
        let up = dofs.prescribed(n);
        for c in 0..d {
            full[n * d + c] -= up[c];
        }
    }
    full
}

/// `W(p) = sum_a Pi(p, a) T_a u_a` without the prescribed part (a homogeneous correction).
fn interpolate_homogeneous(dofs: &DofMap, proj: &SideProjection, u: &[f64]) -> Vec<V3> {
    (0..proj.len())
        .map(|p| {
            let mut w = [0.0; 3];
            for (n, c) in proj.row(p) {
                let d = dofs.node_displacement(n, u);
                let up = dofs.prescribed(n);
                for k in 0..3 {
                    w[k] += c * (d[k] - up[k]);
                }
            }
            w
        })
        .collect()
}

/// The macro operator of a run: the pseudo-inverse of `L = sum_s alpha_s L_s^0` (row-major
/// `n x n`) restricted to the active macro unknowns (`active[j]`; the rows and columns of the
/// others are zero, so their `lambda` is zero: module doc, "Open interfaces"); eigenvalues
/// below `1e-10` of the largest are left out.
pub(crate) fn macro_inverse(
    n: usize,
    subs: &[SubMacro],
    alpha: &[f64],
    active: &[bool],
) -> Vec<f64> {
    let mut l = Mat::<f64>::zeros(n, n);
    for (s, sm) in subs.iter().enumerate() {
        for &(r, c, v) in &sm.l0 {
            if active[r] && active[c] {
                l[(r, c)] += alpha[s] * v;
            }
        }
    }
    // Symmetric up to round-off: use the symmetric part.
    for r in 0..n {
        for c in 0..r {
            let v = 0.5 * (l[(r, c)] + l[(c, r)]);
            l[(r, c)] = v;
            l[(c, r)] = v;
        }
    }
    let Ok(evd) = l.self_adjoint_eigen(Side::Lower) else {
        // No correction rather than a wrong one (an eigen-solver failure on a small symmetric
        // matrix would be a bug).
        return vec![0.0; n * n];
    };
    let (s, u) = (evd.S(), evd.U());
    let smax = (0..n).map(|k| s[k].abs()).fold(0.0f64, f64::max);
    // `L^+ = U_k D_k^-1 U_k^T` over the kept eigenpairs, one matrix product (with subdomains
    // the macro space has thousands of unknowns: a product, not a triple loop).
    let kept: Vec<usize> = (0..n).filter(|&k| s[k] > 1e-10 * smax).collect();
    let uk = Mat::<f64>::from_fn(n, kept.len(), |r, j| u[(r, kept[j])]);
    let scaled = Mat::<f64>::from_fn(n, kept.len(), |r, j| uk[(r, j)] / s[kept[j]]);
    let pinv = &scaled * uk.transpose();
    let mut inv = vec![0.0; n * n];
    for r in 0..n {
        for c in 0..n {
            inv[r * n + c] = pinv[(r, c)];
        }
    }
    inv
}
