//! Equilibrium of each substructure: the test that separates a converged LATIN state from a
//! state that merely stopped changing.
//!
//! The LATIN indicator `eta` (module `solver`) is relative to the size of the iterates. When no
//! static solution exists (a body pushed beyond its sliding limit, a root pulled out of its
//! slot), a floating substructure drifts as a rigid body by a growing amount each iteration:
//! `||s||` grows without bound and `eta` falls below any tolerance although the state is not in
//! equilibrium. So a run is called converged only when, in addition, every substructure is in
//! equilibrium under its applied loads and the **local-stage** interface forces (the ones that
//! satisfy the interface law), and no floating substructure has moved rigidly by more than a
//! fraction of the model size.
//!
//! # Free rigid modes
//! For a substructure with nodes `x_n`, centroid `c` and radius `L = max |x_n - c|`, the rigid
//! modes are the translations `e_i` and the rotations `omega_i x (x - c) / L` (2D: `t_x, t_y,
//! r_z`; 3D: three of each), scaled so that every mode is of order one. Its constraints
//! (component or skew) block the combinations of modes that violate them at some node: with
//! `P_n` the projector on the constrained directions of node `n` and `R_n` the `dim x m` matrix of
//! the modes at `x_n`, the **free modes** span the null space of `G = sum_n R_n^T P_n R_n`
//! (eigenvalues below `1e-9`). A clamped substructure has none; a floating one has all of them;
//! a symmetry condition leaves some.
//!
//! # Unbalanced load
//! With `g = sum_n R_n^T f_n + sum_i m_i R_i^T F_hat_i` (applied nodal loads `f` with the run's
//! load factors, lumped interface forces `m_i F_hat_i` of every interface side of the
//! substructure), the unbalanced generalised force is the projection `V V^T g` on the free modes
//! (`V`: orthonormal basis of the null space). Reactions of constraints do no work in free modes,
//! so `V^T g = 0` is exactly the equilibrium of the substructure in its free directions. Its
//! translation part is the unbalanced **force** and `L` times its rotation part the unbalanced
//! **moment** about `c`. The **relative imbalance** is `|V^T g| / S` with the load scale
//! `S = sum_n |f_n| + sum_i m_i |F_hat_i|` (all load factors' contributions added in absolute
//! value): `0` is perfect balance, `1` means nothing holds the load.
//! At a true LATIN solution the linear-stage forces `F` balance the loads exactly in free modes
//! (`R^T K = 0`), so `V^T g = V^T sum_i m_i R_i^T (F_hat_i - F_i)`: the imbalance is the
//! part of the search-direction gap `F_hat - F` that the rigid modes see, small when the run
//! has converged, of the order of the excess load when no equilibrium exists.
//!
//! # Rigid motion
//! For a substructure without prescribed non-zero displacements (a substructure the user moves
//! is not checked): the least-squares rigid part of the displacement in the free modes, `a = argmin sum_n |u_n -
//! R_n V a|^2`, and its largest nodal value `max_n |R_n V a|`, divided by the model size (the
//! diagonal of the assembly's bounding box). Small-displacement theory holds only when this is
//! small; a drifting substructure makes it grow at every iteration.

use alea_mesh::vec3::{self, cross, dot};
use faer::{Mat, Side};

/// Per-substructure data of the check, computed once at set-up.
#[derive(Clone, Debug)]
pub(crate) struct RigidModes {
    dim: usize,
    /// Number of rigid modes (3 in 2D, 6 in 3D).
    modes: usize,
    centroid: [f64; 3],
    radius: f64,
    /// Orthonormal basis of the free modes, column-major `modes x free`.
    free: Vec<f64>,
    num_free: usize,
    /// Generalised forces `R^T f` of each load case (`modes` each).
    case_forces: Vec<Vec<f64>>,
    /// `sum_n |f_n|` of each load case.
    case_scale: Vec<f64>,
    /// Some constraint prescribes a non-zero displacement: the substructure is moved by the
    /// user, and its rigid motion is not checked.
    driven: bool,
}

/// The equilibrium of one substructure at the end of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SubEquilibrium {
    /// Number of rigid modes its constraints leave free (0: fully held by its constraints).
    pub free_modes: usize,
    /// Unbalanced force in the free directions (applied loads + local-stage interface forces).
    pub force: [f64; 3],
    /// Unbalanced moment about the substructure's centroid, free directions (2D: `z` only).
    pub moment: [f64; 3],
    /// `|unbalanced generalised force| / load scale` (module doc); 0 with no free mode.
    pub relative_imbalance: f64,
    /// Largest rigid displacement in the free modes divided by the model size (0 for a
    /// substructure with a non-zero prescribed displacement, which the user moves).
    pub relative_rigid_motion: f64,
}

impl SubEquilibrium {
    /// True if both measures are within the bounds.
    pub fn holds(&self, imbalance_tolerance: f64, max_rigid_motion: f64) -> bool {
        self.relative_imbalance <= imbalance_tolerance
            && self.relative_rigid_motion <= max_rigid_motion
    }
}

impl RigidModes {
    /// Rigid modes at `x`: `out[j]` is mode `j`'s displacement (`modes` entries).
    fn at(&self, x: &[f64; 3], out: &mut [[f64; 3]; 6]) {
        let r = [
            (x[0] - self.centroid[0]) / self.radius,
            (x[1] - self.centroid[1]) / self.radius,
            (x[2] - self.centroid[2]) / self.radius,
        ];
        if self.dim == 2 {
            out[0] = [1.0, 0.0, 0.0];
            out[1] = [0.0, 1.0, 0.0];
            out[2] = [-r[1], r[0], 0.0];
        } else {
            for i in 0..3 {
                let mut e = [0.0; 3];
                e[i] = 1.0;
                out[i] = e;
                out[3 + i] = cross(&e, &r);
            }
        }
    }

    /// Builds the free-mode basis of a substructure from its mesh coordinates, the projector on
    /// the constrained directions of each node (`constrained(n, v)` = the part of `v` in
    /// constrained directions) and its full node-major load cases.
    pub(crate) fn new(
        dim: usize,
        coords: &[[f64; 3]],
        constrained: impl Fn(usize, [f64; 3]) -> [f64; 3],
        load_cases: &[Vec<f64>],
        driven: bool,
    ) -> Self {
        let n = coords.len().max(1);
        let mut centroid = [0.0; 3];
        for x in coords {
            for c in 0..3 {
                centroid[c] += x[c] / n as f64;
            }
        }
        let radius = coords
            .iter()
            .map(|x| {
                (0..3)
                    .map(|c| (x[c] - centroid[c]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max);
        let modes = if dim == 2 { 3 } else { 6 };
        let mut rm = RigidModes {
            dim,
            modes,
            centroid,
            radius: if radius > 0.0 { radius } else { 1.0 },
            free: Vec::new(),
            num_free: 0,
            case_forces: Vec::new(),
            case_scale: Vec::new(),
            driven,
        };
        let mut g = Mat::<f64>::zeros(modes, modes);
        let mut r = [[0.0; 3]; 6];
        for (node, x) in coords.iter().enumerate() {
            rm.at(x, &mut r);
            let p: Vec<[f64; 3]> = (0..modes).map(|j| constrained(node, r[j])).collect();
            if p.iter().all(|v| v.iter().all(|&c| c == 0.0)) {
                continue;
            }
            // P is an orthogonal projector: R^T P R = (P R)^T (P R).
            for a in 0..modes {
                for b in 0..modes {
                    g[(a, b)] += (0..3).map(|c| p[a][c] * p[b][c]).sum::<f64>();
                }
            }
        }
        let free: Vec<Vec<f64>> = match g.self_adjoint_eigen(Side::Lower) {
            Ok(evd) => {
                let (s, u) = (evd.S(), evd.U());
                (0..modes)
                    .filter(|&k| s[k] <= 1e-9)
                    .map(|k| (0..modes).map(|a| u[(a, k)]).collect())
                    .collect()
            }
            // An eigen-solver failure on a tiny symmetric matrix would be a bug; treat every
            // mode as free (the strictest check).
            Err(_) => (0..modes)
                .map(|k| (0..modes).map(|a| f64::from(u8::from(a == k))).collect())
                .collect(),
        };
        rm.num_free = free.len();
        rm.free = free.concat();
        for f in load_cases {
            let mut gf = vec![0.0; modes];
            let mut scale = 0.0;
            for (node, x) in coords.iter().enumerate() {
                let mut v = [0.0; 3];
                v[..dim].copy_from_slice(&f[node * dim..node * dim + dim]);
                scale += vec3::norm(&v);
                rm.at(x, &mut r);
                for j in 0..modes {
                    gf[j] += (0..3).map(|c| r[j][c] * v[c]).sum::<f64>();
                }
            }
            rm.case_forces.push(gf);
            rm.case_scale.push(scale);
        }
        rm
    }

    /// Number of free rigid modes.
    pub(crate) fn num_free(&self) -> usize {
        self.num_free
    }

    /// Starts an accumulation of the generalised force with the applied loads times
    /// `load_factors` (1 for missing entries): returns `(g, S)`.
    pub(crate) fn applied(&self, load_factors: Option<&[f64]>) -> (Vec<f64>, f64) {
        let mut g = vec![0.0; self.modes];
        let mut scale = 0.0;
        for (j, (gf, s)) in self.case_forces.iter().zip(&self.case_scale).enumerate() {
            let lf = load_factors.and_then(|v| v.get(j)).copied().unwrap_or(1.0);
            for (a, b) in g.iter_mut().zip(gf) {
                *a += lf * b;
            }
            scale += lf.abs() * s;
        }
        (g, scale)
    }

    /// Adds a nodal force `f` at `x` to `(g, S)`.
    pub(crate) fn add_force(&self, x: &[f64; 3], f: &[f64; 3], g: &mut [f64], scale: &mut f64) {
        let mut r = [[0.0; 3]; 6];
        self.at(x, &mut r);
        for j in 0..self.modes {
            g[j] += dot(&r[j], f);
        }
        *scale += vec3::norm(f);
    }

    /// The check, from the accumulated `(g, S)`, the full node-major displacement `u` (only
    /// read when a mode is free), the mesh coordinates and the model size.
    /// Coordinates `V^T g` of the generalised force `g` (mode coordinates) in the free-mode
    /// basis.
    pub(crate) fn free_components(&self, g: &[f64]) -> Vec<f64> {
        let m = self.modes;
        (0..self.num_free)
            .map(|k| {
                self.free[k * m..(k + 1) * m]
                    .iter()
                    .zip(g)
                    .map(|(a, b)| a * b)
                    .sum()
            })
            .collect()
    }

    pub(crate) fn finish(
        &self,
        g: &[f64],
        scale: f64,
        coords: &[[f64; 3]],
        moments: impl FnOnce() -> Vec<f64>,
        model_size: f64,
    ) -> SubEquilibrium {
        let (m, nf) = (self.modes, self.num_free);
        if nf == 0 {
            return SubEquilibrium::default();
        }
        let finite = |v: f64| if v.is_finite() { v } else { f64::INFINITY };
        let col = |k: usize| &self.free[k * m..(k + 1) * m];
        // Coordinates of g in the free basis, and its free part back in mode coordinates.
        let gv: Vec<f64> = (0..nf)
            .map(|k| col(k).iter().zip(g).map(|(a, b)| a * b).sum())
            .collect();
        let norm = gv.iter().map(|v| v * v).sum::<f64>().sqrt();
        let mut gfree = vec![0.0; m];
        for (k, v) in gv.iter().enumerate() {
            for (a, c) in gfree.iter_mut().zip(col(k)) {
                *a += v * c;
            }
        }
        let mut force = [0.0; 3];
        let mut moment = [0.0; 3];
        if self.dim == 2 {
            force[..2].copy_from_slice(&gfree[..2]);
            moment[2] = gfree[2] * self.radius;
        } else {
            force.copy_from_slice(&gfree[..3]);
            for c in 0..3 {
                moment[c] = gfree[3 + c] * self.radius;
            }
        }
        let relative_imbalance = if scale > 0.0 {
            finite(norm / scale)
        } else if norm > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        if self.driven || !(model_size > 0.0) {
            return SubEquilibrium {
                free_modes: nf,
                force,
                moment,
                relative_imbalance,
                relative_rigid_motion: 0.0,
            };
        }
        let mode = self.fit_moments(coords, &moments());
        let mut r = [[0.0; 3]; 6];
        let mut rigid = 0.0f64;
        for x in coords {
            self.at(x, &mut r);
            let mut v = [0.0; 3];
            for j in 0..m {
                for c in 0..3 {
                    v[c] += mode[j] * r[j][c];
                }
            }
            rigid = rigid.max(vec3::norm(&v));
        }
        SubEquilibrium {
            free_modes: nf,
            force,
            moment,
            relative_imbalance,
            relative_rigid_motion: finite(rigid / model_size),
        }
    }

    /// The least-squares rigid part of a full node-major displacement `u` in the free modes,
    /// in mode coordinates (`modes` entries; zero if no mode is free):
    /// `a = argmin sum_n |u_n - R_n V a|^2`, returned as `V a`.
    pub(crate) fn rigid_fit(&self, coords: &[[f64; 3]], u: &[f64]) -> Vec<f64> {
        self.fit_moments(coords, &self.moments(coords, u))
    }

    /// The moments `b = sum_n R_n^T u_n` of a full node-major displacement `u` on every rigid
    /// mode (`modes` entries): the only way the rigid fit depends on `u` (linear in `u`).
    pub(crate) fn moments(&self, coords: &[[f64; 3]], u: &[f64]) -> Vec<f64> {
        let (m, d) = (self.modes, self.dim);
        let mut b = vec![0.0; m];
        let mut r = [[0.0; 3]; 6];
        for (node, x) in coords.iter().enumerate() {
            self.at(x, &mut r);
            let mut un = [0.0; 3];
            un[..d].copy_from_slice(&u[node * d..node * d + d]);
            for i in 0..m {
                b[i] += (0..3).map(|c| r[i][c] * un[c]).sum::<f64>();
            }
        }
        b
    }

    /// Whether [`RigidModes::finish`] measures the rigid motion (some mode is free and no
    /// displacement is prescribed).
    pub(crate) fn checks_motion(&self) -> bool {
        self.num_free > 0 && !self.driven
    }

    /// Number of rigid modes (3 in 2D, 6 in 3D).
    pub(crate) fn num_modes(&self) -> usize {
        self.modes
    }

    /// Mode `i` at every node as a force-like nodal vector: `R_n e_i` at node `n` (the rows of
    /// [`RigidModes::moments`]: `b_i = sum_n (R_n e_i) . u_n`).
    pub(crate) fn mode_at_nodes(&self, coords: &[[f64; 3]], i: usize) -> Vec<[f64; 3]> {
        let mut r = [[0.0; 3]; 6];
        coords
            .iter()
            .map(|x| {
                self.at(x, &mut r);
                r[i]
            })
            .collect()
    }

    /// [`RigidModes::rigid_fit`] from the moments `b` of the displacement
    /// ([`RigidModes::moments`]).
    pub(crate) fn fit_moments(&self, coords: &[[f64; 3]], b: &[f64]) -> Vec<f64> {
        let (m, nf) = (self.modes, self.num_free);
        let col = |k: usize| &self.free[k * m..(k + 1) * m];
        // Least-squares rigid part in the free modes: (V^T A V) a = V^T b,
        // A = sum_n R_n^T R_n, b = sum_n R_n^T u_n.
        let mut a = vec![0.0; m * m];
        let mut r = [[0.0; 3]; 6];
        for x in coords {
            self.at(x, &mut r);
            for i in 0..m {
                for j in 0..m {
                    a[i * m + j] += (0..3).map(|c| r[i][c] * r[j][c]).sum::<f64>();
                }
            }
        }
        let mut vav = Mat::<f64>::zeros(nf, nf);
        let mut vb = Mat::<f64>::zeros(nf, 1);
        for k in 0..nf {
            vb[(k, 0)] = col(k).iter().zip(b).map(|(p, q)| p * q).sum();
            for l in 0..nf {
                let mut s = 0.0;
                for i in 0..m {
                    for j in 0..m {
                        s += col(k)[i] * a[i * m + j] * col(l)[j];
                    }
                }
                vav[(k, l)] = s;
            }
        }
        let coef: Vec<f64> = match vav.llt(Side::Lower) {
            Ok(llt) => {
                let sol = faer::linalg::solvers::Solve::solve(&llt, &vb);
                (0..nf).map(|k| sol[(k, 0)]).collect()
            }
            Err(_) => vec![0.0; nf],
        };
        let mut mode = vec![0.0; m];
        for (k, c) in coef.iter().enumerate() {
            for (a, v) in mode.iter_mut().zip(col(k)) {
                *a += c * v;
            }
        }
        mode
    }

    /// Subtracts from the full node-major displacement `u` its rigid part in the free modes
    /// ([`RigidModes::rigid_fit`]).
    pub(crate) fn remove_rigid_part(&self, coords: &[[f64; 3]], u: &mut [f64]) {
        if self.num_free == 0 {
            return;
        }
        let mode = self.rigid_fit(coords, u);
        let d = self.dim;
        let mut r = [[0.0; 3]; 6];
        for (node, x) in coords.iter().enumerate() {
            self.at(x, &mut r);
            for c in 0..d {
                u[node * d + c] -= (0..self.modes).map(|j| mode[j] * r[j][c]).sum::<f64>();
            }
        }
    }
}
