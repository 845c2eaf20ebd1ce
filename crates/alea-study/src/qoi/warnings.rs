//! Warnings about maximum-type quantities that sit on a corner.
//!
//! A maximum of the nodal stress found on a node where two boundary groups meet (a re-entrant
//! corner, the end of a contact flank, a change of boundary condition) is usually the value of
//! a stress singularity: it grows without bound as the mesh is refined, and its statistics
//! describe the mesh rather than the part. After a study, [`corner_warnings`] re-evaluates
//! every maximum-type quantity from the runs' stored displacements (so resumed runs are
//! checked too) and reports each such node with the number of runs whose maximum sits there.

use std::collections::BTreeMap;
use std::path::Path;

use rayon::prelude::*;

use crate::StudyError;
use crate::qoi::QoiKind;
use crate::store::{RunRecord, Store};
use crate::study::Study;

/// A maximum-type quantity found on a node where two boundary groups meet.
#[derive(Clone, Debug, PartialEq)]
pub struct CornerWarning {
    /// The quantity.
    pub quantity: String,
    /// Its substructure.
    pub substructure: String,
    /// The node (numbered in the substructure's mesh, as in its ParaView file).
    pub node: usize,
    /// Its position.
    pub x: [f64; 3],
    /// The two boundary groups that meet there.
    pub groups: (String, String),
    /// Runs whose maximum sits on this node.
    pub runs: usize,
    /// Converged runs checked.
    pub of: usize,
}

impl std::fmt::Display for CornerWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "quantity '{}': in {} of {} runs the maximum sits on node {} of substructure '{}' at ({:.4}, {:.4}, {:.4}), where the boundary groups '{}' and '{}' meet; a maximum on such a corner is usually a stress singularity that grows as the mesh is refined. Leave it out (exclude_groups, exclude_nodes, or exclude_points with exclude_radius) or average over a small region (mean_von_mises)",
            self.quantity,
            self.runs,
            self.of,
            self.node,
            self.substructure,
            self.x[0],
            self.x[1],
            self.x[2],
            self.groups.0,
            self.groups.1
        )
    }
}

/// The corner warnings of `study` over its converged runs `records`, whose displacements are
/// stored in the study directory `dir`. Deterministic: warnings in quantity then node order.
pub fn corner_warnings(
    study: &Study,
    records: &[RunRecord],
    dir: &Path,
) -> Result<Vec<CornerWarning>, StudyError> {
    let maxima: Vec<usize> = study
        .qois
        .iter()
        .enumerate()
        .filter(|(_, q)| matches!(q.kind, QoiKind::MaxVonMises { .. }))
        .map(|(i, _)| i)
        .collect();
    if maxima.is_empty() {
        return Ok(Vec::new());
    }
    let store = Store::open(dir, &study.hash, false)?;
    let subs = &study.model.assembly.subs;
    let sizes: Vec<usize> = subs
        .iter()
        .map(|s| s.model.mesh.num_nodes() * s.model.mesh.dim)
        .collect();
    let runs: Vec<&RunRecord> = records.iter().filter(|r| r.converged()).collect();
    let fields: Vec<Vec<f64>> = runs
        .iter()
        .map(|r| store.fields(&r.params))
        .collect::<Result<_, _>>()?;
    // Per run: (quantity, node) of every maximum found on a junction.
    let hits: Vec<Vec<(usize, usize)>> = runs
        .par_iter()
        .zip(&fields)
        .map(|(r, all)| -> Result<Vec<(usize, usize)>, StudyError> {
            if all.len() != sizes.iter().sum::<usize>() {
                return Err(StudyError::FieldSize {
                    params: r.params.clone(),
                    found: all.len(),
                    expected: sizes.iter().sum::<usize>(),
                });
            }
            let mut out = Vec::new();
            for &q in &maxima {
                let QoiKind::MaxVonMises { sub, .. } = study.qois[q].kind else {
                    continue;
                };
                let off: usize = sizes[..sub].iter().sum();
                let model =
                    study
                        .model
                        .parametric
                        .scaled_model(&subs[sub].model, sub, &r.params)?;
                if let Some(m) = study.qois[q].max_location(&model, &all[off..off + sizes[sub]])?
                    && m.junction.is_some()
                {
                    out.push((q, m.node));
                }
            }
            Ok(out)
        })
        .collect::<Result<_, _>>()?;
    let mut count: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for h in hits.iter().flatten() {
        *count.entry(*h).or_default() += 1;
    }
    Ok(count
        .into_iter()
        .filter_map(|((q, node), n)| {
            let QoiKind::MaxVonMises { sub, set } = &study.qois[q].kind else {
                return None;
            };
            let i = set.nodes.binary_search(&node).ok()?;
            Some(CornerWarning {
                quantity: study.qois[q].name.clone(),
                substructure: subs[*sub].name.clone(),
                node,
                x: subs[*sub].model.mesh.coords[node],
                groups: set.junction[i].clone()?,
                runs: n,
                of: runs.len(),
            })
        })
        .collect())
}
