//! Contact results a user can work with: per interface point, everything needed to integrate
//! resultants and moments without rebuilding weights, as a table ([`contact_rows`]) and a CSV
//! file per interface ([`write_interface_csv`]); the same fields go into the run's VTU files
//! ([`crate::output`]).
//!
//! With `n` the outward normal of side 1 and `Phi = F_hat_2` the traction on side 2 (the
//! conventions of [`crate::law`]), each point gives
//! - `weight`: the lumped interface weight `m_i` (length x thickness in 2D, area in 3D), so that
//!   `int f dS = sum_i m_i f_i`;
//! - `gap = [W_hat].n + g0` (>= 0; 0 where closed) and the initial gap `g0`;
//! - `pressure = Phi.n` (>= 0 in compression);
//! - `traction_t = Phi - (Phi.n) n`, the tangential traction on side 2 (side 1 carries its
//!   opposite);
//! - `slip = [W_hat] - ([W_hat].n) n`, the tangential displacement of side 2 relative to side 1
//!   (zero where sticking, opposite to `traction_t` where slipping); in a load history
//!   ([`crate::steps`]) the **slip of the step**, `[W_hat]_t - j0` with `j0` the tangential jump
//!   at the start of the step (the origin the incremental law measures slip from,
//!   [`crate::steps::step_origins`]), and `total_slip = [W_hat]_t` the tangential jump since the
//!   unloaded state (the CSV of a history step has both: `slip_*` then, after `status`,
//!   `total_slip_*`; a single solve's CSV has `slip_*` only, which is then both);
//! - `status`: `perfect`, `open`, `stick` or `slip`.
//!
//! The resultant on side 2 is `sum_i m_i (pressure_i n_i + traction_t_i)`
//! (= [`InterfaceResult::resultant`]) and its moment about `x0` is
//! `sum_i m_i (x_i - x0) x (pressure_i n_i + traction_t_i)`. Numbers are written with the
//! shortest representation that reads back to the same `f64` (full precision).

use std::io::Write;
use std::path::Path;

use alea_mesh::vec3::dot;

use crate::{InterfaceResult, PointStatus};

/// The contact fields of one interface point (module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactRow {
    /// Mesh node on side 1.
    pub node1: usize,
    /// Mesh node on side 2.
    pub node2: usize,
    /// Position (nominal geometry).
    pub x: [f64; 3],
    /// Lumped interface weight.
    pub weight: f64,
    /// Outward unit normal of side 1.
    pub normal: [f64; 3],
    /// Friction coefficient.
    pub mu: f64,
    /// Initial gap `g0`.
    pub g0: f64,
    /// Normal gap `[W_hat].n + g0`.
    pub gap: f64,
    /// Normal pressure `Phi.n`.
    pub pressure: f64,
    /// Tangential traction on side 2.
    pub traction_t: [f64; 3],
    /// Slip of the step: the tangential jump `[W_hat]_t` less its value at the start of the
    /// step (module doc; a single solve: `[W_hat]_t`).
    pub slip: [f64; 3],
    /// Tangential jump since the unloaded state, `[W_hat]_t`.
    pub total_slip: [f64; 3],
    /// Contact status.
    pub status: PointStatus,
}

fn tangential(v: [f64; 3], n: &[f64; 3]) -> [f64; 3] {
    let vn = dot(&v, n);
    [v[0] - vn * n[0], v[1] - vn * n[1], v[2] - vn * n[2]]
}

/// The contact rows of an interface, in interface point order.
pub fn contact_rows(it: &InterfaceResult) -> Vec<ContactRow> {
    contact_rows_since(it, None)
}

/// The contact rows of an interface of one step of a load history, with the step's slip
/// measured from `origin` (`j0` per point, [`crate::steps::step_origins`]; `None`: from the
/// unloaded state).
pub fn contact_rows_since(it: &InterfaceResult, origin: Option<&[[f64; 3]]>) -> Vec<ContactRow> {
    (0..it.points.len())
        .map(|i| {
            let p = &it.points[i];
            let n = p.normal;
            let phi = it.side2_force(i);
            let a = it.what[0][i];
            let b = it.pairing.to_points(1, it.what[1][i]);
            let jump = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let total_slip = tangential(jump, &n);
            let j0 = origin.and_then(|o| o.get(i)).copied().unwrap_or([0.0; 3]);
            ContactRow {
                node1: it.nodes[0][i],
                node2: it.nodes[1][i],
                x: p.x,
                weight: it.weights[i],
                normal: n,
                mu: p.mu,
                g0: p.gap,
                gap: dot(&jump, &n) + p.gap,
                pressure: dot(&phi, &n),
                traction_t: tangential(phi, &n),
                slip: [0, 1, 2].map(|k| total_slip[k] - j0[k]),
                total_slip,
                status: it.status[i],
            }
        })
        .collect()
}

/// Name of a status in the CSV.
pub fn status_name(s: PointStatus) -> &'static str {
    match s {
        PointStatus::Perfect => "perfect",
        PointStatus::Open => "open",
        PointStatus::Stick => "stick",
        PointStatus::Slip => "slip",
    }
}

/// The CSV header (`dim` = 2 leaves out the z components).
pub fn csv_header(dim: usize) -> String {
    let v = |name: &str| -> Vec<String> {
        ["x", "y", "z"][..dim]
            .iter()
            .map(|c| format!("{name}_{c}"))
            .collect()
    };
    let mut cols: Vec<String> = vec!["point".into(), "node1".into(), "node2".into()];
    cols.extend(["x", "y", "z"][..dim].iter().map(|s| s.to_string()));
    cols.push("weight".into());
    cols.extend(v("normal"));
    cols.extend(["mu", "g0", "gap", "pressure"].map(String::from));
    cols.extend(v("traction_t"));
    cols.extend(v("slip"));
    cols.push("status".into());
    cols.join(",")
}

/// The CSV header of a load-history step: [`csv_header`] then `total_slip_*`.
pub fn csv_header_history(dim: usize) -> String {
    let mut h = csv_header(dim);
    for c in &["x", "y", "z"][..dim] {
        h.push_str(&format!(",total_slip_{c}"));
    }
    h
}

/// Writes the CSV of one interface (`dim` components per vector), atomically.
///
/// # Errors
/// On I/O failure.
pub fn write_interface_csv(path: &Path, it: &InterfaceResult, dim: usize) -> std::io::Result<()> {
    write_interface_csv_since(path, it, dim, None)
}

/// [`write_interface_csv`] for one step of a load history: `slip_*` is the step's slip from
/// `origin` (`Some`: `j0` per point, [`crate::steps::step_origins`]), and the columns
/// `total_slip_*` ([`csv_header_history`]) are added; `None` is [`write_interface_csv`].
///
/// # Errors
/// On I/O failure.
pub fn write_interface_csv_since(
    path: &Path,
    it: &InterfaceResult,
    dim: usize,
    origin: Option<&[[f64; 3]]>,
) -> std::io::Result<()> {
    let rows = contact_rows_since(it, origin);
    let header = match origin {
        Some(_) => csv_header_history(dim),
        None => csv_header(dim),
    };
    alea_mesh::atomic::write_atomic(path, |w| {
        writeln!(w, "{header}")?;
        for (i, r) in rows.iter().enumerate() {
            let mut line = format!("{i},{},{}", r.node1, r.node2);
            let mut num = |v: f64| line.push_str(&format!(",{v:e}"));
            for c in 0..dim {
                num(r.x[c]);
            }
            num(r.weight);
            for c in 0..dim {
                num(r.normal[c]);
            }
            for v in [r.mu, r.g0, r.gap, r.pressure] {
                num(v);
            }
            for c in 0..dim {
                num(r.traction_t[c]);
            }
            for c in 0..dim {
                num(r.slip[c]);
            }
            line.push(',');
            line.push_str(status_name(r.status));
            if origin.is_some() {
                for c in 0..dim {
                    line.push_str(&format!(",{:e}", r.total_slip[c]));
                }
            }
            writeln!(w, "{line}")?;
        }
        Ok(())
    })
}
