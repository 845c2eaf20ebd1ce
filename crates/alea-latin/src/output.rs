//! ParaView output of a run: one `.vtm` multi-block file with a `.vtu` per substructure.
//!
//! Point fields: `displacement` (vector), `stress` (symmetric tensor, nodal averages),
//! `von_mises`, and on interface nodes `contact_status` (-1 off interfaces, then
//! [`PointStatus::code`]: 0 perfect, 1 open, 2 stick, 3 slip), `contact_normal_force`
//! (`F_hat . n` on this side, traction units), `contact_tangential_force` (`|F_hat_t|`) and
//! `interface_jump` (`[W_hat] + g0 n`, vector; the same on both sides). On a mortar side that is
//! not the identity (side 2) these nodal values are averages of the point values weighted by
//! `m_p Pi(p, a)`, and the status is that of the point that weighs most. Then the fields of the
//! contact CSV ([`crate::contact`], the same values on both sides of a node-to-node point; on
//! side 1 only for a mortar interface): `contact_weight`, `contact_normal` (side 1's outward
//! normal), `contact_gap`, `contact_pressure` (`Phi.n >= 0` in compression),
//! `contact_traction_t` (tangential traction on side 2), `contact_slip` (tangential jump of
//! side 2 relative to side 1; for a step of a load history, [`write_step`], the slip of the step,
//! and `contact_total_slip` the tangential jump since the unloaded state); with
//! [`write_run_with_reactions`], `reaction` (nodal reaction forces, [`crate::reactions`]). Cell fields: one `group_<name>` indicator per cell group.
//! Beside the `.vtu` files, one `interface_<name>.csv` per interface
//! ([`crate::contact::write_interface_csv`]).

use std::path::{Path, PathBuf};

use alea_fem::{post, von_mises};
use alea_mesh::vec3::{dot, norm};
use alea_mesh::vtu::{VtuWriter, write_vtm};

use crate::{LatinError, LatinSolver, RunResult};

/// Per-substructure point fields of a run.
struct SubFields {
    u: Vec<f64>,
    stress: Vec<f64>,
    vm: Vec<f64>,
    status: Vec<f64>,
    fnormal: Vec<f64>,
    ftangent: Vec<f64>,
    jump: Vec<f64>,
    weight: Vec<f64>,
    normal: Vec<f64>,
    gap: Vec<f64>,
    pressure: Vec<f64>,
    traction_t: Vec<f64>,
    slip: Vec<f64>,
    total_slip: Vec<f64>,
}

/// Weighted sums of point values at one node of a mortar side.
#[derive(Default)]
struct NodeAverage {
    weight: f64,
    force: [f64; 3],
    normal: [f64; 3],
    jump: [f64; 3],
    best: (f64, f64),
}

impl SubFields {
    /// Sets the interface fields of `node` from its status code, normal, traction and jump.
    fn set(&mut self, node: usize, status: f64, n: &[f64; 3], fh: &[f64; 3], jump: &[f64; 3]) {
        let fnn = dot(fh, n);
        let ft = [fh[0] - fnn * n[0], fh[1] - fnn * n[1], fh[2] - fnn * n[2]];
        self.status[node] = status;
        self.fnormal[node] = fnn;
        self.ftangent[node] = norm(&ft);
        self.jump[node * 3..node * 3 + 3].copy_from_slice(jump);
    }
}

/// Writes `path` (`.vtm`), one `.vtu` per substructure and one `interface_<name>.csv` per
/// interface beside it; returns the `.vtu` and `.csv` paths.
pub fn write_run(
    path: impl AsRef<Path>,
    solver: &LatinSolver,
    result: &RunResult,
) -> Result<Vec<PathBuf>, LatinError> {
    write_run_with_reactions(path, solver, result, None)
}

/// [`write_run`] with a `reaction` point field per substructure (node-major, `dim` per node).
pub fn write_run_with_reactions(
    path: impl AsRef<Path>,
    solver: &LatinSolver,
    result: &RunResult,
    reactions: Option<&[Vec<f64>]>,
) -> Result<Vec<PathBuf>, LatinError> {
    write_step(path, solver, result, reactions, None)
}

/// [`write_run_with_reactions`] for one step of a load history: with `origins` (per interface
/// and point, the tangential jump `j0` at the start of the step: [`crate::steps::step_origins`],
/// [`crate::large_sliding::step_origins`]) the slip fields are the step's own and the total
/// tangential jump is written beside them (`contact_total_slip`, the CSV's `total_slip_*`);
/// `None` is [`write_run_with_reactions`].
pub fn write_step(
    path: impl AsRef<Path>,
    solver: &LatinSolver,
    result: &RunResult,
    reactions: Option<&[Vec<f64>]>,
    origins: Option<&[Vec<[f64; 3]>]>,
) -> Result<Vec<PathBuf>, LatinError> {
    let origin = |i: usize| origins.and_then(|o| o.get(i)).map(Vec::as_slice);
    let mut fields = Vec::new();
    for s in 0..solver.num_subs() {
        let model = result.scaled_model(solver.model(s), s);
        let nn = model.mesh.num_nodes();
        let u = result.displacements[s].clone();
        let stresses = post::nodal_stresses(&model, &u).map_err(|source| LatinError::Fem {
            sub: solver.sub_name(s).to_string(),
            source,
        })?;
        let vm = stresses.iter().map(von_mises).collect();
        // Ours: [xx, yy, zz, yz, xz, xy]; the writer takes [xx, yy, zz, xy, yz, xz].
        let stress = stresses
            .iter()
            .flat_map(|s| [s[0], s[1], s[2], s[5], s[3], s[4]])
            .collect();
        fields.push(SubFields {
            u,
            stress,
            vm,
            status: vec![-1.0; nn],
            fnormal: vec![0.0; nn],
            ftangent: vec![0.0; nn],
            jump: vec![0.0; nn * 3],
            weight: vec![0.0; nn],
            normal: vec![0.0; nn * 3],
            gap: vec![0.0; nn],
            pressure: vec![0.0; nn],
            traction_t: vec![0.0; nn * 3],
            slip: vec![0.0; nn * 3],
            total_slip: vec![0.0; nn * 3],
        });
    }
    for (ii, it) in result.interfaces.iter().enumerate() {
        for side in 0..2 {
            let f = &mut fields[it.subs[side]];
            let proj = &it.pairing.sides[side];
            if proj.is_identity() {
                for (i, &node) in it.nodes[side].iter().enumerate() {
                    // Normal and jump in the side's own frame (a cyclic side 2's: rotated).
                    let n = it.pairing.to_side(side, it.points[i].normal);
                    let fh = it.fhat[side][i];
                    let j = it.pairing.to_side(side, it.jump(i));
                    f.set(node, it.status[i].code() as f64, &n, &fh, &j);
                }
                continue;
            }
            // Mortar side: nodal averages of the point values weighted by m_p Pi(p, a) (their
            // sum is the node's share of the interface measure); the status of the point that
            // weighs most.
            let mut acc: std::collections::BTreeMap<usize, NodeAverage> = Default::default();
            for p in 0..proj.len() {
                let m = proj.weights[p];
                for (node, c) in proj.row(p) {
                    let a = acc.entry(node).or_default();
                    let w = m * c;
                    a.weight += w;
                    let n = it.pairing.to_side(side, it.points[p].normal);
                    let j = it.pairing.to_side(side, it.jump(p));
                    for k in 0..3 {
                        a.force[k] += w * it.fhat[side][p][k];
                        a.normal[k] += w * n[k];
                        a.jump[k] += w * j[k];
                    }
                    if w > a.best.0 {
                        a.best = (w, it.status[p].code() as f64);
                    }
                }
            }
            for (node, a) in acc {
                if a.weight <= 0.0 {
                    continue;
                }
                let l = (a.normal.iter().map(|v| v * v).sum::<f64>())
                    .sqrt()
                    .max(1e-300);
                let n = a.normal.map(|v| v / l);
                let t = a.force.map(|v| v / a.weight);
                let j = a.jump.map(|v| v / a.weight);
                f.set(node, a.best.1, &n, &t, &j);
            }
        }
        let node_to_node = it.pairing.sides[1].is_identity();
        for r in crate::contact::contact_rows_since(it, origin(ii)) {
            let sides = [(it.subs[0], r.node1), (it.subs[1], r.node2)];
            for &(side, node) in &sides[..if node_to_node { 2 } else { 1 }] {
                let f = &mut fields[side];
                f.weight[node] = r.weight;
                f.gap[node] = r.gap;
                f.pressure[node] = r.pressure;
                f.normal[node * 3..node * 3 + 3].copy_from_slice(&r.normal);
                f.traction_t[node * 3..node * 3 + 3].copy_from_slice(&r.traction_t);
                f.slip[node * 3..node * 3 + 3].copy_from_slice(&r.slip);
                f.total_slip[node * 3..node * 3 + 3].copy_from_slice(&r.total_slip);
            }
        }
    }
    let names: Vec<String> = (0..solver.num_subs())
        .map(|s| solver.sub_name(s).to_string())
        .collect();
    let parts: Vec<(&str, VtuWriter<'_>)> = (0..solver.num_subs())
        .map(|s| {
            let m = solver.model(s);
            let f = &fields[s];
            let w = VtuWriter::new(&m.mesh)
                .point_vector("displacement", m.mesh.dim, &f.u)
                .point_tensor("stress", 6, &f.stress)
                .point_scalar("von_mises", &f.vm)
                .point_scalar("contact_status", &f.status)
                .point_scalar("contact_normal_force", &f.fnormal)
                .point_scalar("contact_tangential_force", &f.ftangent)
                .point_vector("interface_jump", 3, &f.jump)
                .point_scalar("contact_weight", &f.weight)
                .point_vector("contact_normal", 3, &f.normal)
                .point_scalar("contact_gap", &f.gap)
                .point_scalar("contact_pressure", &f.pressure)
                .point_vector("contact_traction_t", 3, &f.traction_t)
                .point_vector("contact_slip", 3, &f.slip);
            let w = match origins {
                Some(_) => w.point_vector("contact_total_slip", 3, &f.total_slip),
                None => w,
            };
            let w = match reactions.and_then(|r| r.get(s)) {
                Some(r) => w.point_vector("reaction", m.mesh.dim, r),
                None => w,
            };
            (names[s].as_str(), w)
        })
        .collect();
    let path = path.as_ref();
    let mut written = write_vtm(path, &parts).map_err(|source| LatinError::Mesh {
        sub: "output".into(),
        source,
    })?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "parts".into());
    let dir = path.parent().unwrap_or(Path::new("")).join(stem);
    for (ii, it) in result.interfaces.iter().enumerate() {
        let safe = alea_mesh::atomic::safe_file_name(&it.name);
        let csv = dir.join(format!("interface_{safe}.csv"));
        let dim = solver.model(it.subs[0]).mesh.dim;
        crate::contact::write_interface_csv_since(&csv, it, dim, origin(ii)).map_err(|source| {
            LatinError::Io {
                path: csv.clone(),
                source,
            }
        })?;
        written.push(csv);
    }
    Ok(written)
}
