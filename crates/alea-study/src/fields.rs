//! Mean and standard-deviation fields of a study, for ParaView.
//!
//! Every surrogate is linear in the run data, `u~(x, xi) = sum_k w_k(xi) u_k(x)`, so
//! `E[u~](x) = sum_k E[w_k] u_k(x)` and `E[u~^2](x) = sum_kl E[w_k w_l] u_k(x) u_l(x)`, with the
//! weight moments `E[w_k]`, `E[w_k w_l]` estimated once on the Monte Carlo draws of the analysis
//! (so the field statistics agree with the scalar ones). The standard deviation is
//! `sqrt(max(E[u~^2] - E[u~]^2, 0))`, per component. Fields: displacement (vector: mean and
//! per-component std) and nodal von Mises stress (each run's nodal-averaged field, interpolated
//! by the same weights). Written as `<dir>/paraview/mean_std.vtm` with one `.vtu` per
//! substructure.
//!
//! **Cost linear in the runs where the surrogate is local.** `E[w_k w_l]` is non-zero only for
//! runs that are non-zero together at some draw: for piecewise multilinear interpolation, runs
//! of a common cell (at most `2^d` per draw), so the matrix has `O(K)` entries for `K` runs. It
//! is accumulated per *support* (the set of runs non-zero at a draw: one hash look-up per draw
//! and a `|S| x |S|` outer product), then assembled into a sparse symmetric matrix. The fields
//! then cost `O(nnz x n)` instead of `O(K^2 x n)` for `n` field values. Global surrogates
//! (chaos, polynomials) have one support of all `K` runs: the dense matrix, as before.
//!
//! **Streaming.** Runs are read in order, a block at a time (their fields from the study
//! database, one run at a time through its connection, which is not shared between threads;
//! each run's stresses then computed in parallel); run `b`'s field is dropped once
//! the last run `a` with `E[w_a w_b] != 0` has been read, so memory holds the matrix's profile
//! (about `sqrt(K)` runs for a 2D grid), not all `K` fields. Chunks of draws are summed in a
//! fixed order, and a bounded number of them is held at once: results do not depend on the
//! thread count.
use std::path::{Path, PathBuf};

use alea_fem::{post, von_mises};
use alea_mesh::vtu::{VtuWriter, write_vtm};
use rayon::prelude::*;

use crate::StudyError;
use crate::method::MethodKind;
use crate::store::{Store, point_key};
use crate::study::Study;
use crate::study_runs::StudyRuns;

/// Mean and standard deviation of the fields of one substructure (node-major, like the
/// solver's displacements).
#[derive(Clone, Debug)]
pub struct MeanStdFields {
    /// `E[u]`, `dim` components per node.
    pub displacement_mean: Vec<f64>,
    /// Standard deviation of each displacement component.
    pub displacement_std: Vec<f64>,
    /// `E[von Mises]` per node.
    pub von_mises_mean: Vec<f64>,
    /// Standard deviation of the nodal von Mises stress.
    pub von_mises_std: Vec<f64>,
}

/// Writes the mean / std fields of method `m` estimated on `draws` (row-major physical points).
/// Returns the `.vtm` path.
pub fn write_mean_std_fields(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    m: usize,
    draws: &[f64],
) -> Result<PathBuf, StudyError> {
    let fields = mean_std_fields(study, runs, dir, m, draws)?;
    let solver = &runs.solver;
    let nsub = solver.num_subs();
    let names: Vec<String> = (0..nsub).map(|s| solver.sub_name(s).to_string()).collect();
    let parts: Vec<(&str, VtuWriter<'_>)> = (0..nsub)
        .map(|s| {
            let mesh = &solver.model(s).mesh;
            let f = &fields[s];
            let w = VtuWriter::new(mesh)
                .point_vector("displacement_mean", mesh.dim, &f.displacement_mean)
                .point_vector("displacement_std", mesh.dim, &f.displacement_std)
                .point_scalar("von_mises_mean", &f.von_mises_mean)
                .point_scalar("von_mises_std", &f.von_mises_std);
            (names[s].as_str(), w)
        })
        .collect();
    let path = dir.join("paraview").join("mean_std.vtm");
    std::fs::create_dir_all(dir.join("paraview")).map_err(|source| StudyError::Io {
        path: dir.join("paraview"),
        source,
    })?;
    write_vtm(&path, &parts)?;
    Ok(path)
}

/// The mean / std fields of method `m` on every substructure (see the module doc).
pub fn mean_std_fields(
    study: &Study,
    runs: &StudyRuns,
    dir: &Path,
    m: usize,
    draws: &[f64],
) -> Result<Vec<MeanStdFields>, StudyError> {
    let method = &runs.methods[m];
    if method.kind == MethodKind::MonteCarlo {
        return Err(StudyError::MonteCarloFields);
    }
    let by_key: std::collections::HashMap<String, &crate::store::RunRecord> = runs
        .records
        .iter()
        .map(|r| (point_key(&r.params), r))
        .collect();
    let used: Vec<Vec<f64>> = method
        .points
        .iter()
        .filter(|p| by_key.get(&point_key(p)).is_some_and(|r| r.converged()))
        .cloned()
        .collect();
    let sur = method.surrogate(&study.params, &used)?;
    let k = used.len();
    let d = study.params.names.len();
    if d == 0 || draws.is_empty() {
        return Err(StudyError::NoFieldDraws);
    }
    let moments = WeightMoments::estimate(&|x, t, w| sur.weights(x, t, w), k, d, draws);
    let store = Store::open(dir, &study.hash, false)?;
    let solver = &runs.solver;
    let nsub = solver.num_subs();
    let sizes: Vec<usize> = (0..nsub)
        .map(|s| solver.model(s).mesh.num_nodes() * solver.model(s).mesh.dim)
        .collect();
    let nodes: Vec<usize> = (0..nsub)
        .map(|s| solver.model(s).mesh.num_nodes())
        .collect();
    let total: usize = sizes.iter().sum();
    // Run `a`'s data: its displacements of every substructure, then its nodal von Mises
    // stresses of every substructure.
    let width = total + nodes.iter().sum::<usize>();
    // The runs' fields are read from the database one at a time (a connection is not shared
    // between threads), then their stresses computed in parallel.
    let store = std::sync::Mutex::new(store);
    let load = |a: usize| -> Result<Vec<f64>, StudyError> {
        let p = &used[a];
        let all = store
            .lock()
            .map_err(|_| StudyError::Poisoned("store"))?
            .fields(p)?;
        if all.len() != total {
            return Err(StudyError::FieldSize {
                params: p.clone(),
                found: all.len(),
                expected: total,
            });
        }
        let mut row = Vec::with_capacity(width);
        row.extend_from_slice(&all);
        let mut off = 0;
        for s in 0..nsub {
            let u = &all[off..off + sizes[s]];
            off += sizes[s];
            let model = study.model.parametric.scaled_model(solver.model(s), s, p)?;
            let st = post::nodal_stresses(&model, u)?;
            row.extend(st.iter().map(von_mises));
        }
        Ok(row)
    };
    let (m1, m2) = moments.field_moments(width, load)?;
    let std: Vec<f64> = m1
        .iter()
        .zip(&m2)
        .map(|(a, b)| (b - a * a).max(0.0).sqrt())
        .collect();
    let mut out = Vec::with_capacity(nsub);
    let (mut off_u, mut off_v) = (0, total);
    for s in 0..nsub {
        out.push(MeanStdFields {
            displacement_mean: m1[off_u..off_u + sizes[s]].to_vec(),
            displacement_std: std[off_u..off_u + sizes[s]].to_vec(),
            von_mises_mean: m1[off_v..off_v + nodes[s]].to_vec(),
            von_mises_std: std[off_v..off_v + nodes[s]].to_vec(),
        });
        off_u += sizes[s];
        off_v += nodes[s];
    }
    Ok(out)
}

/// Draws per chunk of the weight-moment sums (fixed: the sums do not depend on the threads).
const CHUNK: usize = 4096;

/// `E[w_a]` and the sparse symmetric `E[w_a w_b]` of a surrogate's weights on a set of draws.
#[derive(Clone, Debug, PartialEq)]
pub struct WeightMoments {
    /// `E[w_a]`.
    pub mean: Vec<f64>,
    /// Row starts of `E[w_a w_b]` (compressed rows, full symmetric pattern, columns sorted).
    pub row_start: Vec<usize>,
    /// Columns.
    pub cols: Vec<usize>,
    /// Values.
    pub vals: Vec<f64>,
}

/// Non-zero weights of a surrogate at a point: `(x, scratch, out)`.
pub type Weigher<'a> = dyn Fn(&[f64], &mut [f64], &mut Vec<(usize, f64)>) + Sync + 'a;

/// Sums over the draws of one chunk, per support: `sum w_S` and `sum w_S w_S^T`.
type SupportSums = std::collections::HashMap<Vec<usize>, (Vec<f64>, Vec<f64>)>;

impl WeightMoments {
    /// Estimates the moments of the weights of a surrogate on `k` runs on `draws` (row-major,
    /// `d` per draw); `weights(x, scratch, w)` sets the non-zero weights `w` at `x` (`scratch`
    /// has `d` values), as [`crate::method::Surrogate::weights`] does.
    pub fn estimate(weights: &Weigher<'_>, k: usize, d: usize, draws: &[f64]) -> WeightMoments {
        let n = draws.len() / d;
        // Memory of one chunk's sums: bound the chunks held at once to about 256 MB.
        let support = {
            let (mut t, mut w) = (vec![0.0; d], Vec::new());
            weights(&draws[..d], &mut t, &mut w);
            w.len().max(1)
        };
        let per_chunk = 8 * support * support * if support >= k { 1 } else { CHUNK };
        let group = (256usize << 20)
            .checked_div(per_chunk.max(1))
            .unwrap_or(1)
            .clamp(1, 64);
        let chunks: Vec<&[f64]> = draws.chunks(d * CHUNK).collect();
        let mut total: SupportSums = SupportSums::new();
        for block in chunks.chunks(group) {
            let parts: Vec<SupportSums> = block
                .par_iter()
                .map(|chunk| {
                    let mut sums = SupportSums::new();
                    let (mut t, mut w) = (vec![0.0; d], Vec::new());
                    let mut key = Vec::new();
                    for x in chunk.chunks_exact(d) {
                        weights(x, &mut t, &mut w);
                        w.sort_unstable_by_key(|p| p.0);
                        key.clear();
                        key.extend(w.iter().map(|p| p.0));
                        if !sums.contains_key(&key) {
                            let m = key.len();
                            sums.insert(key.clone(), (vec![0.0; m], vec![0.0; m * m]));
                        }
                        if let Some((s1, s2)) = sums.get_mut(&key) {
                            let m = w.len();
                            for (i, &(_, wi)) in w.iter().enumerate() {
                                s1[i] += wi;
                                for (j, &(_, wj)) in w.iter().enumerate() {
                                    s2[i * m + j] += wi * wj;
                                }
                            }
                        }
                    }
                    sums
                })
                .collect();
            // In chunk order: each support's sums are added in a fixed order.
            for part in parts {
                for (key, (s1, s2)) in part {
                    match total.get_mut(&key) {
                        Some((t1, t2)) => {
                            t1.iter_mut().zip(&s1).for_each(|(a, b)| *a += b);
                            t2.iter_mut().zip(&s2).for_each(|(a, b)| *a += b);
                        }
                        None => {
                            total.insert(key, (s1, s2));
                        }
                    }
                }
            }
        }
        // Assemble in the order of the sorted supports, then sort the entries (stable) and add
        // duplicates in that order.
        let mut supports: Vec<_> = total.into_iter().collect();
        supports.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        let inv = 1.0 / n as f64;
        let mut mean = vec![0.0; k];
        let mut entries: Vec<(usize, usize, f64)> = Vec::new();
        for (key, (s1, s2)) in &supports {
            let m = key.len();
            for (i, &a) in key.iter().enumerate() {
                mean[a] += s1[i] * inv;
                for (j, &b) in key.iter().enumerate() {
                    entries.push((a, b, s2[i * m + j] * inv));
                }
            }
        }
        entries.sort_by_key(|x| (x.0, x.1));
        let mut row_start = vec![0; k + 1];
        let mut cols: Vec<usize> = Vec::new();
        let mut vals: Vec<f64> = Vec::new();
        let mut last: Option<(usize, usize)> = None;
        for (a, b, v) in entries {
            if last == Some((a, b)) {
                if let Some(x) = vals.last_mut() {
                    *x += v;
                }
            } else {
                cols.push(b);
                vals.push(v);
                row_start[a + 1] += 1;
                last = Some((a, b));
            }
        }
        for a in 0..k {
            row_start[a + 1] += row_start[a];
        }
        WeightMoments {
            mean,
            row_start,
            cols,
            vals,
        }
    }

    /// Runs whose data [`WeightMoments::field_moments`] holds at once at most (besides the
    /// block being loaded): the profile of the matrix in run order.
    pub fn max_held(&self) -> usize {
        let (_, evict_at) = self.evictions();
        let mut held = 0usize;
        let mut peak = 0;
        for ev in &evict_at {
            held += 1;
            peak = peak.max(held);
            held -= ev.len();
        }
        peak
    }

    /// For each run `a`, the runs whose last use is row `a`.
    fn evictions(&self) -> (Vec<usize>, Vec<Vec<usize>>) {
        let k = self.mean.len();
        // Last row that needs run b (the pattern is symmetric: its largest column).
        let last_use: Vec<usize> = (0..k)
            .map(|b| {
                self.cols[self.row_start[b]..self.row_start[b + 1]]
                    .last()
                    .map_or(b, |&c| c.max(b))
            })
            .collect();
        let mut evict_at: Vec<Vec<usize>> = vec![Vec::new(); k];
        for (b, &a) in last_use.iter().enumerate() {
            evict_at[a].push(b);
        }
        (last_use, evict_at)
    }

    /// Non-zeros of `E[w_a w_b]`.
    pub fn nnz(&self) -> usize {
        self.cols.len()
    }

    /// `sum_a E[w_a] v_a` and `sum_ab E[w_a w_b] v_a v_b`, component by component, for run
    /// data `v_a` of `width` values given by `load(a)`. Runs are loaded in order, in parallel
    /// blocks, and dropped after their last use (see the module doc).
    pub fn field_moments<F>(
        &self,
        width: usize,
        load: F,
    ) -> Result<(Vec<f64>, Vec<f64>), StudyError>
    where
        F: Fn(usize) -> Result<Vec<f64>, StudyError> + Sync,
    {
        let k = self.mean.len();
        let (_, evict_at) = self.evictions();
        let mut held: std::collections::HashMap<usize, Vec<f64>> = Default::default();
        let mut m1 = vec![0.0; width];
        let mut m2 = vec![0.0; width];
        let block = 2 * rayon::current_num_threads().max(1);
        let mut a0 = 0;
        while a0 < k {
            let a1 = (a0 + block).min(k);
            let rows: Vec<Result<Vec<f64>, StudyError>> =
                (a0..a1).into_par_iter().map(&load).collect();
            for (a, row) in (a0..a1).zip(rows) {
                let va = row?;
                if va.len() != width {
                    return Err(StudyError::RunFieldSize {
                        run: a,
                        found: va.len(),
                        expected: width,
                    });
                }
                let ea = self.mean[a];
                for (m, v) in m1.iter_mut().zip(&va) {
                    *m += ea * v;
                }
                // E[u~^2] += E[w_a^2] v_a^2 + 2 sum_{b < a} E[w_a w_b] v_a v_b.
                for p in self.row_start[a]..self.row_start[a + 1] {
                    let (b, g) = (self.cols[p], self.vals[p]);
                    if b > a {
                        break;
                    }
                    let (vb, f) = if b == a {
                        (&va, g)
                    } else {
                        let vb = held.get(&b).ok_or_else(|| {
                            StudyError::Internal(format!("run {b} was dropped before its last use"))
                        })?;
                        (vb, 2.0 * g)
                    };
                    for ((m, x), y) in m2.iter_mut().zip(&va).zip(vb.iter()) {
                        *m += f * x * y;
                    }
                }
                held.insert(a, va);
                for b in &evict_at[a] {
                    held.remove(b);
                }
            }
            a0 = a1;
        }
        Ok((m1, m2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alea_uq::surrogate::{LinearSurrogate, StochasticMesh};

    use crate::test_rng::lcg;

    /// Draws in the box `[0, 1] x [0, 2]`.
    fn draws(n: usize) -> Vec<f64> {
        let mut s = 3u64;
        (0..n)
            .flat_map(|_| [lcg(&mut s), 2.0 * lcg(&mut s)])
            .collect()
    }

    #[test]
    fn sparse_moments_equal_the_dense_sums_and_fields_need_only_the_profile() {
        let mesh = StochasticMesh::new(&[0.0, 0.0], &[1.0, 2.0], &[9, 9]).unwrap();
        let k = mesh.num_runs();
        let x = draws(10_000);
        let n = x.len() / 2;
        let weigh = |p: &[f64], _: &mut [f64], w: &mut Vec<(usize, f64)>| mesh.weights(p, w);
        let m = WeightMoments::estimate(&weigh, k, 2, &x);
        // Dense brute force.
        let mut e1 = vec![0.0; k];
        let mut e2 = vec![0.0; k * k];
        let mut w = Vec::new();
        for p in x.chunks_exact(2) {
            mesh.weights(p, &mut w);
            for &(a, wa) in &w {
                e1[a] += wa / n as f64;
                for &(b, wb) in &w {
                    e2[a * k + b] += wa * wb / n as f64;
                }
            }
        }
        for a in 0..k {
            assert!((m.mean[a] - e1[a]).abs() <= 1e-14);
            for b in 0..k {
                let sparse = (m.row_start[a]..m.row_start[a + 1])
                    .find(|&p| m.cols[p] == b)
                    .map_or(0.0, |p| m.vals[p]);
                assert!((sparse - e2[a * k + b]).abs() <= 1e-14, "({a}, {b})");
            }
        }
        // At most the 3 x 3 neighbourhood of a node, and the mean weights sum to 1.
        assert!(m.nnz() <= 9 * k);
        assert!((m.mean.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        // Streaming holds about two grid rows, not the 100 runs.
        assert!(m.max_held() <= 2 * 10 + 2, "{}", m.max_held());
    }

    #[test]
    fn field_statistics_of_a_linear_response_are_its_sample_statistics() {
        // u(x, xi) = a(x) + b(x) xi_1 + c(x) xi_2 is reproduced exactly by multilinear
        // interpolation, so the field mean and variance equal the sample ones on the draws.
        let mesh = StochasticMesh::new(&[0.0, 0.0], &[1.0, 2.0], &[6, 4]).unwrap();
        let k = mesh.num_runs();
        let width = 5;
        let field = |xi: &[f64]| -> Vec<f64> {
            (0..width)
                .map(|j| 1.0 + j as f64 + (0.5 - 0.1 * j as f64) * xi[0] + 0.3 * j as f64 * xi[1])
                .collect()
        };
        let x = draws(20_000);
        let weigh = |p: &[f64], _: &mut [f64], w: &mut Vec<(usize, f64)>| mesh.weights(p, w);
        let m = WeightMoments::estimate(&weigh, k, 2, &x);
        let (m1, m2) = m
            .field_moments(width, |a| Ok(field(mesh.run_point(a))))
            .unwrap();
        let n = (x.len() / 2) as f64;
        for j in 0..width {
            let vals: Vec<f64> = x.chunks_exact(2).map(|p| field(p)[j]).collect();
            let mean = vals.iter().sum::<f64>() / n;
            let var = vals.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
            assert!((m1[j] - mean).abs() < 1e-12 * mean.abs(), "{j}");
            assert!(
                ((m2[j] - m1[j] * m1[j]) - var).abs() < 1e-9 * var.max(1e-3),
                "{j}"
            );
        }
    }
}
