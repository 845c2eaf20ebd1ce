//! The interface-condensed linear stage (issue 41): with the search direction fixed, the linear
//! stage of a substructure is an affine map from its interface data to its interface
//! displacements, computed once per set-up and applied as a dense product at every iteration.
//!
//! # Equations
//! The linear stage of substructure `s` (thesis 2.1, module `linear_stage`) solves
//! `A0 u = b + S v` with the factorised `A0 = T^T (K0 + sum Pi^T M k0 Pi) T`, the constant part
//! `b = r_presc + sum_j (l_j / alpha) r_j` (prescribed displacements, load cases `r_j` with the
//! run's load factors `l_j` and Young's-modulus factor `alpha`), and the interface data
//! `v_p = m_p (F_hat_p + k W_hat_p) / alpha` of every point `p` of every interface side of the
//! substructure, scattered by `S v = sum_p sum_a T_a^T Pi(p, a) v_p`. The next local stage only
//! reads `W = Pi (T u + u_p)` (and `F = F_hat - k (W - W_hat)` from it), so
//!
//! ```text
//! W = w_presc + sum_j (l_j / alpha) w_j + H v,
//! H = Pi T A0^-1 S            (the interface operator, n_i x n_i, n_i = dim x points),
//! w_presc = Pi (T A0^-1 r_presc + u_p),   w_j = Pi T A0^-1 r_j,
//! ```
//!
//! computed at set-up by one multi-column solve per substructure (`n_i + 1 + load cases`
//! columns, plus one per rigid mode of a floating substructure, below). An iteration then costs
//! `2 n_i^2` flops per substructure instead of a sparse triangular solve (`4 nnz(L)` flops on
//! an indirectly addressed factor). The iterates are those of the volume path up to the
//! rounding of the product (the same `v`, the same coarse correction, local stage and
//! acceleration, which read interface values only).
//!
//! # Where the volume solution is needed
//! * The run's displacement (stresses, quantities, the CRE): recovered once per run at its end
//!   by the solve `A0 u = b + S v` with the last linear stage's `v`, kept for that purpose. The
//!   right-hand side is assembled with the same operations as the volume path's, so the
//!   recovered `u` of a given iterate is the volume path's bit for bit; batched runs recover
//!   together with one multi-column solve per substructure (module `batch`).
//! * The rigid motion of a floating substructure in the equilibrium check (module
//!   `equilibrium`): it depends on `u` only through the moments `m_i = sum_n (R_n e_i) . u_n`
//!   of the rigid modes, linear in `u`: with `z_i = A0^-1 T^T R e_i`,
//!   `m_i = m_i(u_p) + z_i . b + (Pi T z_i) . v + sum_c lambda_c m_i(u_c)` (`u_c`: the coarse
//!   columns of the correction), computed from interface values and a few dot products.
//!
//! # When
//! Chosen per substructure ([`super::LinearStage`]): `Auto` condenses a substructure when the
//! dense product costs less than the sparse solve it replaces, `n_i^2 <= DENSE_PER_FACTOR
//! nnz(L)`, when its set-up (`n_i` solved columns, [`SETUP_PER_COLUMN`] single solves each) is
//! paid back by the iterations of the runs the solver is expected to serve
//! (`LatinOptions::expected_runs` times [`ITERATIONS_PER_RUN`]; measured, `BENCHMARKS.md`, issue
//! 41), and when the dense operators of the whole assembly fit in [`MEMORY_SHARE`] of the
//! available memory; the set-up of a solver re-paired
//! in a deformed configuration (large sliding) and the operators of a run whose modulus varies
//! from cell to cell (module `cell_young`) stay on the volume path, their operators change.

use std::sync::Arc;

use alea_fem::DofMap;
use rayon::prelude::*;

use super::{Link, SubOperator};
use crate::LatinError;
use crate::coarse::SubMacro;

type V3 = [f64; 3];

/// `Auto` condenses a substructure when `n_i^2 <= DENSE_PER_FACTOR * nnz(L)`: the dense
/// product's cost per entry over the sparse solve's per factor entry (module doc).
pub(super) const DENSE_PER_FACTOR: f64 = 4.0;

/// Cost of the set-up's solve of one column of `H`, in single-column solves of the same
/// factor (measured: the 3D turbine's set-up, 4 x 1 100 - 1 800 columns, cost the time of 360
/// of its volume iterations, 0.2 per column of its largest substructure; BENCHMARKS.md).
pub(super) const SETUP_PER_COLUMN: f64 = 0.25;

/// LATIN iterations of a run, for the set-up's pay-back (warm-started study runs: 17 - 56 on
/// the 2D and 3D turbines; BENCHMARKS.md).
pub(super) const ITERATIONS_PER_RUN: f64 = 30.0;

/// Share of the available memory the dense operators may take (`Auto` and forced).
pub(super) const MEMORY_SHARE: f64 = 0.25;

/// Columns solved together at set-up.
const CHUNK: usize = 96;

/// The condensed linear stage of one substructure (module doc).
pub(super) struct Condensed {
    dim: usize,
    /// First interface unknown of each link (`dim` per point).
    offsets: Vec<usize>,
    /// Number of interface unknowns `n_i`.
    pub(super) n: usize,
    /// `H`, column-major `n x n`.
    h: Vec<f64>,
    /// `Pi (T A0^-1 r_presc + u_p)`.
    w_presc: Vec<f64>,
    /// `Pi T A0^-1 r_j` per load case.
    w_ext: Vec<Vec<f64>>,
    /// Moments of the rigid modes (floating substructures whose motion is checked).
    rigid: Option<RigidMoments>,
}

/// The affine map from a run's data to the moments of its displacement on the rigid modes.
struct RigidMoments {
    /// `A0^-1 T^T R e_i`, per mode.
    z: Vec<Vec<f64>>,
    /// `Pi T z_i` (interface unknowns), per mode.
    zs: Vec<Vec<f64>>,
    /// Moments of the prescribed part `u_p`.
    presc: Vec<f64>,
    /// Moments of each coarse column's displacement, per column.
    coarse: Vec<Vec<f64>>,
}

/// What a run keeps of a condensed substructure: its constant interface response and the
/// constant part of its rigid moments.
pub(super) struct RunCondensed {
    pub(super) w0: Vec<f64>,
    pub(super) moments0: Vec<f64>,
}

/// Number of interface unknowns of a substructure's links.
pub(super) fn interface_unknowns(dim: usize, links: &[Link]) -> usize {
    links.iter().map(|l| dim * l.proj.len()).sum()
}

/// Bytes of the dense operator of `n` interface unknowns.
pub(super) fn operator_bytes(n: usize) -> f64 {
    8.0 * (n as f64) * (n as f64)
}

impl Condensed {
    /// The interface operator and responses of one substructure (one multi-column solve,
    /// in chunks of [`CHUNK`] columns); `coarse`: its coarse columns, whose displacements
    /// enter the rigid moments.
    pub(super) fn new(op: &SubOperator, coarse: Option<&SubMacro>) -> Result<Self, LatinError> {
        let dofs = &op.dofs;
        let dim = dofs.dim;
        let nf = dofs.num_free();
        let mut offsets = Vec::with_capacity(op.links.len());
        let mut n = 0;
        for l in &op.links {
            offsets.push(n);
            n += dim * l.proj.len();
        }
        let coords = &op.model.mesh.coords;
        let checks_motion = op.rigid.checks_motion();
        let modes = if checks_motion {
            op.rigid.num_modes()
        } else {
            0
        };
        // Columns: the unit interface data, r_presc, the load cases, T^T R e_i.
        let ncols = n + 1 + op.r_ext.len() + modes;
        let column = |j: usize, out: &mut [f64]| {
            if j < n {
                let (li, rest) = locate(&offsets, j);
                let (p, c) = (rest / dim, rest % dim);
                for (node, coef) in op.links[li].proj.row(p) {
                    let mut e = [0.0; 3];
                    e[c] = coef;
                    dofs.add_node_force(node, &e, out);
                }
            } else if j == n {
                out.copy_from_slice(&op.r_presc);
            } else if j < n + 1 + op.r_ext.len() {
                out.copy_from_slice(&op.r_ext[j - n - 1]);
            } else {
                let i = j - n - 1 - op.r_ext.len();
                for (node, r) in op.rigid.mode_at_nodes(coords, i).iter().enumerate() {
                    dofs.add_node_force(node, r, out);
                }
            }
        };
        let interface = |u: &[f64], homogeneous: bool| -> Vec<f64> {
            let mut w = vec![0.0; n];
            for (l, &off) in op.links.iter().zip(&offsets) {
                for p in 0..l.proj.len() {
                    let wp = project(dofs, l, p, u, homogeneous);
                    w[off + p * dim..off + (p + 1) * dim].copy_from_slice(&wp[..dim]);
                }
            }
            w
        };
        // Per chunk of columns: one multi-column solve, then only the interface values kept
        // (and the volume responses to the rigid modes), so that the set-up holds one block
        // per thread.
        let starts: Vec<usize> = (0..ncols).step_by(CHUNK).collect();
        let solved: Vec<Vec<Solved>> = starts
            .par_iter()
            .map(|&c0| {
                let c1 = (c0 + CHUNK).min(ncols);
                let mut block = vec![0.0; nf * (c1 - c0)];
                if nf > 0 {
                    for (j, out) in (c0..c1).zip(block.chunks_exact_mut(nf)) {
                        column(j, out);
                    }
                    if let Some(chol) = &op.chol {
                        let mut scratch = chol.solve_scratch(c1 - c0);
                        chol.solve_with(&mut block, &mut scratch);
                    }
                }
                (c0..c1)
                    .map(|j| {
                        let u = if nf == 0 {
                            &[][..]
                        } else {
                            &block[(j - c0) * nf..(j - c0 + 1) * nf]
                        };
                        let w = interface(u, j != n);
                        (w, (j > n + op.r_ext.len()).then(|| u.to_vec()))
                    })
                    .collect()
            })
            .collect();
        let mut cols: Vec<Solved> = solved.into_iter().flatten().collect();
        let rigid_cols: Vec<Solved> = cols.split_off(n + 1 + op.r_ext.len());
        let w_ext: Vec<Vec<f64>> = cols.drain(n + 1..).map(|c| c.0).collect();
        let w_presc = cols.pop().map_or_else(|| vec![0.0; n], |c| c.0);
        let mut h = Vec::with_capacity(n * n);
        for (w, _) in cols {
            h.extend_from_slice(&w);
        }
        let rigid = checks_motion.then(|| {
            let (zs, z): (Vec<Vec<f64>>, Vec<Vec<f64>>) = rigid_cols
                .into_iter()
                .map(|(w, u)| (w, u.unwrap_or_default()))
                .unzip();
            let presc = op.rigid.moments(coords, &dofs.expand(&vec![0.0; nf]));
            let coarse = coarse.map_or_else(Vec::new, |cm| {
                cm.columns
                    .iter()
                    .map(|c| op.rigid.moments(coords, &homogeneous(dofs, &c.u)))
                    .collect()
            });
            RigidMoments {
                z,
                zs,
                presc,
                coarse,
            }
        });
        Ok(Condensed {
            dim,
            offsets,
            n,
            h,
            w_presc,
            w_ext,
            rigid,
        })
    }

    /// A run's constant parts: `w0 = w_presc + sum_j (l_j / alpha) w_j` and the rigid moments
    /// of `A0^-1 b` plus `u_p` (`base`: the run's `b`).
    pub(super) fn for_run(
        &self,
        load_factors: Option<&[f64]>,
        alpha: f64,
        base: &[f64],
    ) -> RunCondensed {
        let mut w0 = self.w_presc.clone();
        for (j, wj) in self.w_ext.iter().enumerate() {
            let lf = load_factors.map_or(1.0, |v| v[j]);
            for (a, b) in w0.iter_mut().zip(wj) {
                *a += lf * b / alpha;
            }
        }
        let moments0 = self.rigid.as_ref().map_or_else(Vec::new, |r| {
            r.z.iter()
                .zip(&r.presc)
                .map(|(z, p)| p + z.iter().zip(base).map(|(a, b)| a * b).sum::<f64>())
                .collect()
        });
        RunCondensed { w0, moments0 }
    }

    /// The interface data `v` of the linear stage (module doc) from the local-stage state,
    /// with the operations of the volume path's right-hand side (module `linear_stage`).
    pub(super) fn gather(
        &self,
        links: &[Link],
        istate: &[super::InterfaceState],
        alpha: f64,
        v: &mut [f64],
    ) {
        for (l, &off) in links.iter().zip(&self.offsets) {
            let is = &istate[l.iface];
            for (p, &m) in l.proj.weights.iter().enumerate() {
                let vp = point_load(l, is, p, m, alpha);
                v[off + p * self.dim..off + (p + 1) * self.dim].copy_from_slice(&vp[..self.dim]);
            }
        }
    }

    /// `W` at point `p` of link `li` from the interface unknowns `w`.
    #[inline]
    pub(super) fn point(&self, w: &[f64], li: usize, p: usize) -> V3 {
        let o = self.offsets[li] + p * self.dim;
        let mut out = [0.0; 3];
        out[..self.dim].copy_from_slice(&w[o..o + self.dim]);
        out
    }

    /// `w_j += H v_j` for the columns `v_j` of `v` and `w_j` of `w` (`n` each). Every column's
    /// entries are summed in the same order whatever the number of columns, so a run batched
    /// with others gets the bits of the run alone.
    pub(super) fn apply(&self, v: &[f64], w: &mut [f64]) {
        let n = self.n;
        if n == 0 {
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the feature was detected at run time.
            unsafe { apply_avx2(&self.h, n, v, w) };
            return;
        }
        apply_generic(&self.h, n, v, w);
    }

    /// The substructure's rigid moments with interface data `v` and the coarse correction
    /// `coarse_u` ((column, lambda) pairs), from the run's constant part `moments0`.
    pub(super) fn moments(
        &self,
        moments0: &[f64],
        v: &[f64],
        coarse_u: &[(usize, f64)],
    ) -> Vec<f64> {
        let Some(r) = &self.rigid else {
            return Vec::new();
        };
        moments0
            .iter()
            .zip(&r.zs)
            .enumerate()
            .map(|(i, (m0, zs))| {
                let mut m = m0 + zs.iter().zip(v).map(|(a, b)| a * b).sum::<f64>();
                for &(c, a) in coarse_u {
                    if let Some(cm) = r.coarse.get(c) {
                        m += a * cm[i];
                    }
                }
                m
            })
            .collect()
    }

    /// Adds `S v` (the interface data scattered to the free unknowns) to `rhs` with the
    /// operations of the volume path's right-hand side: the recovered `u` of an iterate is the
    /// volume path's bit for bit.
    pub(super) fn scatter(&self, op: &SubOperator, v: &[f64], rhs: &mut [f64]) {
        for (l, &off) in op.links.iter().zip(&self.offsets) {
            for p in 0..l.proj.len() {
                let o = off + p * self.dim;
                let mut vp = [0.0; 3];
                vp[..self.dim].copy_from_slice(&v[o..o + self.dim]);
                for (node, c) in l.proj.row(p) {
                    let cv = [c * vp[0], c * vp[1], c * vp[2]];
                    op.dofs.add_node_force(node, &cv, rhs);
                }
            }
        }
    }

    /// Bytes held (the operator and the responses).
    pub(super) fn bytes(&self) -> f64 {
        let r = self.rigid.as_ref().map_or(0, |r| {
            r.z.iter().map(Vec::len).sum::<usize>() + r.zs.iter().map(Vec::len).sum::<usize>()
        });
        operator_bytes(self.n) + 8.0 * (self.n * (1 + self.w_ext.len()) + r) as f64
    }
}

/// The interface data `v_p = m_p (F_hat_p + k W_hat_p) / alpha` of point `p` of link `l`.
#[inline(always)]
pub(super) fn point_load(
    l: &Link,
    is: &super::InterfaceState,
    p: usize,
    m: f64,
    alpha: f64,
) -> [f64; 3] {
    let fh = is.fhat[l.side][p];
    let kw = l.dir[p].apply(alpha, &is.what[l.side][p]);
    [
        m * (fh[0] + kw[0]) / alpha,
        m * (fh[1] + kw[1]) / alpha,
        m * (fh[2] + kw[2]) / alpha,
    ]
}

/// A solved set-up column: its interface values, and its volume response when kept (the
/// rigid modes' columns).
type Solved = (Vec<f64>, Option<Vec<f64>>);

/// The link and offset inside it of interface unknown `j`.
fn locate(offsets: &[usize], j: usize) -> (usize, usize) {
    let li = offsets.partition_point(|&o| o <= j) - 1;
    (li, j - offsets[li])
}

/// `Pi(p) (T u + u_p)` at point `p` of link `l` (without `u_p` when `homogeneous`).
fn project(dofs: &DofMap, l: &Link, p: usize, u: &[f64], homogeneous: bool) -> V3 {
    let mut w = [0.0; 3];
    for (node, c) in l.proj.row(p) {
        let d = dofs.node_displacement(node, u);
        let up = if homogeneous {
            dofs.prescribed(node)
        } else {
            [0.0; 3]
        };
        for k in 0..3 {
            w[k] += c * (d[k] - up[k]);
        }
    }
    w
}

/// The full node-major displacement `T u` without the prescribed part.
fn homogeneous(dofs: &DofMap, u: &[f64]) -> Vec<f64> {
    let d = dofs.dim;
    let mut full = dofs.expand(u);
    for node in 0..dofs.num_nodes() {
        let up = dofs.prescribed(node);
        for c in 0..d {
            full[node * d + c] -= up[c];
        }
    }
    full
}

/// The product of [`Condensed::apply`]: per block of four columns of `H`, every column of `v`
/// (the block stays in the first-level cache), each entry summed in the order of `H`'s columns.
#[inline(always)]
fn apply_kernel(h: &[f64], n: usize, v: &[f64], w: &mut [f64]) {
    let ncols = v.len() / n;
    let mut k = 0;
    while k + 4 <= n {
        let (h0, h1, h2, h3) = (
            &h[k * n..(k + 1) * n],
            &h[(k + 1) * n..(k + 2) * n],
            &h[(k + 2) * n..(k + 3) * n],
            &h[(k + 3) * n..(k + 4) * n],
        );
        for j in 0..ncols {
            let vj = &v[j * n + k..j * n + k + 4];
            let (a0, a1, a2, a3) = (vj[0], vj[1], vj[2], vj[3]);
            let wj = &mut w[j * n..(j + 1) * n];
            for i in 0..n {
                wj[i] = wj[i] + h0[i] * a0 + h1[i] * a1 + h2[i] * a2 + h3[i] * a3;
            }
        }
        k += 4;
    }
    while k < n {
        let hk = &h[k * n..(k + 1) * n];
        for j in 0..ncols {
            let a = v[j * n + k];
            let wj = &mut w[j * n..(j + 1) * n];
            for i in 0..n {
                wj[i] += hk[i] * a;
            }
        }
        k += 1;
    }
}

fn apply_generic(h: &[f64], n: usize, v: &[f64], w: &mut [f64]) {
    apply_kernel(h, n, v, w);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn apply_avx2(h: &[f64], n: usize, v: &[f64], w: &mut [f64]) {
    apply_kernel(h, n, v, w);
}

/// The dense operators' memory of an assembly's substructures, checked against
/// [`MEMORY_SHARE`] of the available memory when the condensed stage is forced.
pub(super) fn check_memory(names: &[&str], sizes: &[usize]) -> Result<(), LatinError> {
    let total: f64 = sizes.iter().map(|&n| operator_bytes(n)).sum();
    let available = alea_mesh::input::available_memory() as f64;
    if total > MEMORY_SHARE * available {
        let (s, n) = sizes
            .iter()
            .enumerate()
            .max_by_key(|(_, n)| **n)
            .map_or((0, 0), |(s, n)| (s, *n));
        return Err(LatinError::CondensedMemory {
            bytes: total,
            available,
            largest: names.get(s).map_or_else(String::new, |v| v.to_string()),
            unknowns: n,
        });
    }
    Ok(())
}

/// Shared handle of a substructure's condensed stage.
pub(super) type SharedCondensed = Option<Arc<Condensed>>;

/// Which substructures are condensed as `mode` asks (module doc, "When"), from the entries
/// `nnz` of every substructure's factor; `deformed`: the interfaces were re-paired in a
/// deformed configuration (large sliding), kept on the volume path by `Auto`.
pub(super) fn choose(
    ops: &[Arc<SubOperator>],
    nnz: &[usize],
    mode: super::LinearStage,
    expected_runs: usize,
    deformed: bool,
) -> Result<Vec<bool>, LatinError> {
    let sizes: Vec<usize> = ops
        .iter()
        .map(|op| interface_unknowns(op.dofs.dim, &op.links))
        .collect();
    let want: Vec<bool> = match mode {
        super::LinearStage::Volume => vec![false; ops.len()],
        super::LinearStage::Condensed => {
            let names: Vec<&str> = ops.iter().map(|o| o.name.as_str()).collect();
            check_memory(&names, &sizes)?;
            vec![true; ops.len()]
        }
        super::LinearStage::Auto => {
            if deformed {
                vec![false; ops.len()]
            } else {
                let mut want: Vec<bool> = nnz
                    .iter()
                    .zip(&sizes)
                    .map(|(&nnz, &n)| pays(n, nnz, expected_runs))
                    .collect();
                // Within the memory share: the smallest operators first.
                let budget = MEMORY_SHARE * alea_mesh::input::available_memory() as f64;
                let mut order: Vec<usize> = (0..ops.len()).filter(|&s| want[s]).collect();
                order.sort_by_key(|&s| sizes[s]);
                let mut used = 0.0;
                for s in order {
                    used += operator_bytes(sizes[s]);
                    if used > budget {
                        want[s] = false;
                    }
                }
                want
            }
        }
    };
    Ok(want)
}

/// The condensed stage of the substructures with `want[s]` that this rank holds the factor of
/// (module `ranks`; every one in a single process).
pub(super) fn build_all(
    ops: &[Arc<SubOperator>],
    coarse: Option<&super::Coarse>,
    want: &[bool],
) -> Result<Vec<SharedCondensed>, LatinError> {
    ops.par_iter()
        .enumerate()
        .map(|(s, op)| {
            let n = interface_unknowns(op.dofs.dim, &op.links);
            if !want[s] || op.chol.is_none() || op.dofs.num_free() == 0 || n == 0 {
                return Ok(None);
            }
            let cm = coarse.map(|c| &c.subs[s]);
            Condensed::new(op, cm).map(|c| Some(Arc::new(c)))
        })
        .collect()
}

/// Whether `Auto` condenses a substructure of `n` interface unknowns whose factor has `nnz`
/// entries, for a set-up serving `runs` runs (module doc, "When").
pub(super) fn pays(n: usize, nnz: usize, runs: usize) -> bool {
    (n as f64) * (n as f64) <= DENSE_PER_FACTOR * nnz as f64
        && SETUP_PER_COLUMN * n as f64 <= ITERATIONS_PER_RUN * runs as f64
}

impl super::LatinSolver {
    /// Recovers the volume solution `u` (`rhs`) of every condensed substructure of `runs`
    /// whose last linear stage left it to be recovered (module doc): per substructure, one
    /// multi-column solve for all the runs, `A0 u = b + S v` with the last `v`.
    pub(super) fn recover_volumes(&self, runs: &mut [&mut super::Run<'_>]) {
        let nsub = self.subs.len();
        let mut per_sub: Vec<Vec<(&mut super::SubState, &[f64])>> =
            (0..nsub).map(|_| Vec::new()).collect();
        for run in runs.iter_mut() {
            let super::Run { sstate, base, .. } = &mut **run;
            for (s, st) in sstate.iter_mut().enumerate() {
                if st.stale {
                    per_sub[s].push((st, base[s].as_slice()));
                }
            }
        }
        self.subs
            .par_iter()
            .zip(self.condensed.par_iter())
            .zip(per_sub.par_iter_mut())
            .for_each(|((op, cd), cols)| {
                let (Some(cd), Some(chol), false) = (cd, &op.chol, cols.is_empty()) else {
                    return;
                };
                let nf = op.dofs.num_free();
                let mut block = vec![0.0; nf * cols.len()];
                for ((st, base), r) in cols.iter().zip(block.chunks_exact_mut(nf.max(1))) {
                    r.copy_from_slice(base);
                    cd.scatter(op, &st.v, r);
                }
                if nf > 0 {
                    let mut scratch = chol.solve_scratch(cols.len());
                    chol.solve_with(&mut block, &mut scratch);
                }
                for ((st, _), u) in cols.iter_mut().zip(block.chunks_exact(nf.max(1))) {
                    st.rhs.copy_from_slice(&u[..nf]);
                    st.stale = false;
                }
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `Auto` rule on the turbines' sizes (BENCHMARKS.md, issue 41): the 2D turbine's
    /// substructures (284 interface unknowns, factors of about 1.5e5 entries) condense for a
    /// study of a few runs, not for one solve; the 3D turbine's (1 794 unknowns, factors of
    /// several million entries) from about 15 runs; an interface larger than its factor never.
    #[test]
    fn auto_weighs_the_product_the_set_up_and_the_runs() {
        assert!(!pays(284, 150_000, 1));
        assert!(pays(284, 150_000, 3));
        assert!(!pays(1794, 5_000_000, 10));
        assert!(pays(1794, 5_000_000, 17));
        assert!(!pays(4000, 1_000_000, 100_000));
    }

    /// Forced condensation beyond the memory share is a typed error naming the largest
    /// substructure.
    #[test]
    fn operators_beyond_the_memory_share_are_refused() {
        let e = check_memory(&["small", "huge"], &[10, 10_000_000]).unwrap_err();
        assert!(
            matches!(&e, LatinError::CondensedMemory { largest, unknowns, .. }
                if largest == "huge" && *unknowns == 10_000_000),
            "{e}"
        );
        assert!(check_memory(&["a"], &[100]).is_ok());
    }
}
