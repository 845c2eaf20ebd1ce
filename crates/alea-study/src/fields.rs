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

use std::path::{Path, PathBuf};

use alea_fem::{post, von_mises};
use alea_mesh::vtu::{VtuWriter, write_vtm};
use rayon::prelude::*;

use crate::StudyError;
use crate::method::MethodKind;
use crate::runner::{Study, StudyRuns};
use crate::store::{Store, point_key};

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
        return Err(StudyError::Other(
            "Monte Carlo on the model has no surrogate for fields".into(),
        ));
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
    let sur = method
        .surrogate(&study.params, &used)
        .map_err(StudyError::Other)?;
    let k = used.len();
    let d = study.params.names.len();
    if d == 0 || draws.is_empty() {
        return Err(StudyError::Other(
            "no Monte Carlo draws for the field statistics".into(),
        ));
    }
    // Weight moments, in fixed chunks summed in order (thread-count independent); 16 chunks
    // at a time, so that at most 16 `k x k` partial sums are alive (`limits::mean_fields_memory`).
    let n = (draws.len() / d) as f64;
    let mut ew = vec![0.0; k];
    let mut ew2 = vec![0.0; k * k];
    let chunks: Vec<&[f64]> = draws.chunks(d * 4096).collect();
    for group in chunks.chunks(16) {
        let parts: Vec<(Vec<f64>, Vec<f64>)> = group
            .par_iter()
            .map(|block| {
                let mut e1 = vec![0.0; k];
                let mut e2 = vec![0.0; k * k];
                let (mut t, mut w) = (vec![0.0; d], Vec::new());
                for x in block.chunks_exact(d) {
                    sur.weights(x, &mut t, &mut w);
                    for &(a, wa) in &w {
                        e1[a] += wa;
                        for &(b, wb) in &w {
                            e2[a * k + b] += wa * wb;
                        }
                    }
                }
                (e1, e2)
            })
            .collect();
        for (e1, e2) in &parts {
            for (a, b) in ew.iter_mut().zip(e1) {
                *a += b / n;
            }
            for (a, b) in ew2.iter_mut().zip(e2) {
                *a += b / n;
            }
        }
    }
    let store = Store::open(dir, &study.hash, false)?;
    let solver = &runs.solver;
    let nsub = solver.num_subs();
    let sizes: Vec<usize> = (0..nsub)
        .map(|s| solver.model(s).mesh.num_nodes() * solver.model(s).mesh.dim)
        .collect();
    // Per substructure: run fields (K x n) of displacements and nodal von Mises.
    let mut disp: Vec<Vec<f64>> = sizes.iter().map(|&sz| Vec::with_capacity(k * sz)).collect();
    let mut vm: Vec<Vec<f64>> = (0..nsub)
        .map(|s| Vec::with_capacity(k * solver.model(s).mesh.num_nodes()))
        .collect();
    for p in &used {
        let all = store.fields(p)?;
        if all.len() != sizes.iter().sum::<usize>() {
            return Err(StudyError::Other(format!(
                "field file of the run at {p:?} has {} values, expected {}",
                all.len(),
                sizes.iter().sum::<usize>()
            )));
        }
        let factors = study.model.parametric.run_input(p, vec![]).young_factors;
        let mut off = 0;
        for s in 0..nsub {
            let u = &all[off..off + sizes[s]];
            off += sizes[s];
            disp[s].extend_from_slice(u);
            let mut model = solver.model(s).clone();
            model.scale_young(factors[s]);
            let st = post::nodal_stresses(&model, u)?;
            vm[s].extend(st.iter().map(von_mises));
        }
    }
    let moments = |data: &[f64], width: usize| -> (Vec<f64>, Vec<f64>) {
        let mut mean = vec![0.0; width];
        let mut std = vec![0.0; width];
        for j in 0..width {
            let v: Vec<f64> = (0..k).map(|a| data[a * width + j]).collect();
            let m1: f64 = (0..k).map(|a| ew[a] * v[a]).sum();
            let m2: f64 = (0..k)
                .map(|a| v[a] * (0..k).map(|b| ew2[a * k + b] * v[b]).sum::<f64>())
                .sum();
            mean[j] = m1;
            std[j] = (m2 - m1 * m1).max(0.0).sqrt();
        }
        (mean, std)
    };
    Ok((0..nsub)
        .map(|s| {
            let nn = solver.model(s).mesh.num_nodes();
            let (displacement_mean, displacement_std) = moments(&disp[s], sizes[s]);
            let (von_mises_mean, von_mises_std) = moments(&vm[s], nn);
            MeanStdFields {
                displacement_mean,
                displacement_std,
                von_mises_mean,
                von_mises_std,
            }
        })
        .collect())
}
