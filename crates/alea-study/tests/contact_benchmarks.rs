//! The shipped two-body contact benchmarks (`examples/full-slip.toml`,
//! `examples/incline-cgs4.toml`, `examples/shrink-fit.toml`, `examples/hertz-line-contact.toml`,
//! meshed by the `stacked_blocks`, `block_on_incline`, `concentric_rings` and
//! `cylinder_on_block` generators) against their known answers, and the
//! contact results users work with (per-point table and CSV, reactions) against invariants:
//!
//! - full slip: every point slips, `|T| = mu N` for the resultant and pointwise, `N = p w t`;
//! - block on an incline (after NAFEMS CGS-4): the interface resultant equals the statics of the
//!   block (`N = G cos a + F sin a`, `T = F cos a - G sin a`) below the threshold
//!   `F/G = (tan a + mu) / (1 - mu tan a)`, and no static equilibrium is found above it;
//! - Hertz line contact (`examples/hertz-line-contact.toml`, generator `cylinder_on_block`): the
//!   contact half-width within one cell of Johnson's `b`, the peak pressure within 3 % of `p0`,
//!   the contact force equal to the load;
//! - shrink fit: the mean contact pressure is Lame's `E delta (b^2 - a^2)(c^2 - b^2) / (2 b^3
//!   (c^2 - a^2))` (plane stress, one material) within the discretisation error, the gap is
//!   closed everywhere;
//! - the contact table integrates to the solver's resultant, the CSV reads back bit for bit,
//!   and reactions balance the loads and interface forces of each substructure (zero on free
//!   dofs) and of the whole assembly.

use std::path::PathBuf;

use alea_latin::contact::{contact_rows, csv_header, write_interface_csv};
use alea_latin::reactions::{group_sum, nodal_reactions};
use alea_latin::{LatinSolver, PointStatus, RunResult, RunStatus};
use alea_study::spec::ModelFile;
use alea_study::{BuiltModel, Source, build_model, build_params};

fn example(name: &str) -> (BuiltModel, ModelFile) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let src = Source::read(&path).unwrap();
    let file: ModelFile = src.parse().unwrap();
    let params = build_params(&src, &file).unwrap();
    let built = build_model(&src, &file, &params).unwrap();
    (built, file)
}

/// Solves with each substructure's load cases scaled by `factors` (empty: as in the file).
fn solve(built: &BuiltModel, factors: &[Vec<f64>]) -> (LatinSolver, RunResult, Vec<Vec<f64>>) {
    let solver = LatinSolver::new(built.assembly.clone(), built.options.clone()).unwrap();
    let mut input = built.parametric.run_input(&[]);
    if !factors.is_empty() {
        input.load_factors = factors.to_vec();
    }
    let res = solver.run_shared(&input).unwrap();
    let loads = built
        .assembly
        .subs
        .iter()
        .enumerate()
        .map(|(s, sub)| {
            let mut f = vec![0.0; sub.model.mesh.num_nodes() * sub.model.mesh.dim];
            for (case, k) in sub.load_cases.iter().zip(&input.load_factors[s]) {
                for (a, b) in f.iter_mut().zip(case) {
                    *a += k * b;
                }
            }
            f
        })
        .collect();
    (solver, res, loads)
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// Reactions balance each substructure (zero on free dofs; sum of reactions, loads and interface
/// forces zero) and the assembly (sum of reactions and loads zero, the interface forces cancel).
fn check_reactions(built: &BuiltModel, solver: &LatinSolver, res: &RunResult, loads: &[Vec<f64>]) {
    let dim = built.mesh.dim;
    let mut total = [0.0; 3];
    let mut scale = 0.0f64;
    for (s, sub) in built.assembly.subs.iter().enumerate() {
        let r = nodal_reactions(solver, res, s, &loads[s]).unwrap();
        let all: Vec<usize> = (0..sub.model.mesh.num_nodes()).collect();
        let sum_r = group_sum(&r, dim, &all);
        let sum_f = group_sum(&loads[s], dim, &all);
        let dofs = alea_fem::DofMap::for_mesh(&sub.model.mesh, &sub.constraints).unwrap();
        let constrained: Vec<bool> = (0..sub.model.mesh.num_nodes())
            .map(|n| !dofs.is_free_node(n))
            .collect();
        let rmax = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (n, &c) in constrained.iter().enumerate() {
            if !c {
                for k in 0..dim {
                    assert!(
                        r[n * dim + k].abs() <= 1e-7 * rmax.max(1.0),
                        "substructure {s}: residual {} at free node {n}",
                        r[n * dim + k]
                    );
                }
            }
        }
        for c in 0..dim {
            total[c] += sum_r[c] + sum_f[c];
            scale = scale.max(sum_f[c].abs()).max(sum_r[c].abs());
        }
    }
    for c in 0..dim {
        assert!(
            total[c].abs() <= 1e-6 * scale,
            "global balance, component {c}: {} (scale {scale})",
            total[c]
        );
    }
}

#[test]
fn full_slip_ratio_is_mu() {
    let (built, _) = example("full-slip.toml");
    let (solver, res, loads) = solve(&built, &[]);
    assert_eq!(res.status, RunStatus::Converged);
    let it = &res.interfaces[0];
    assert!(
        it.status.iter().all(|s| *s == PointStatus::Slip),
        "{:?}",
        it.status
    );
    let f = it.resultant();
    let (mu, n_expected) = (0.3, 10.0 * 40.0 * 1.0);
    assert!(close(f[1], n_expected, 1e-7), "N = {}", f[1]);
    assert!(close(-f[0], mu * f[1], 1e-7), "T = {}, N = {}", f[0], f[1]);
    // The table: pointwise Coulomb in full slip, and it integrates to the resultant.
    let rows = contact_rows(it);
    let mut sum = [0.0; 3];
    for r in &rows {
        let t = r.traction_t;
        let tn = (t[0] * t[0] + t[1] * t[1]).sqrt();
        assert!(
            r.pressure > 0.0 && close(tn, mu * r.pressure, 1e-6),
            "{r:?}"
        );
        let s = r.slip;
        assert!(
            t[0] * s[0] + t[1] * s[1] < 0.0,
            "slip opposes friction: {r:?}"
        );
        assert!(r.gap.abs() < 1e-9, "closed: {r:?}");
        for c in 0..3 {
            sum[c] += r.weight * (r.pressure * r.normal[c] + r.traction_t[c]);
        }
    }
    for c in 0..2 {
        assert!(
            close(sum[c], f[c], 1e-12),
            "component {c}: {} vs {}",
            sum[c],
            f[c]
        );
    }
    // The CSV reads back bit for bit.
    let path = std::env::temp_dir().join(format!("alea-contact-{}.csv", std::process::id()));
    write_interface_csv(&path, it, 2).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), csv_header(2));
    for (line, r) in lines.zip(&rows) {
        let v: Vec<&str> = line.split(',').collect();
        assert_eq!(v.len(), 17);
        let num = |k: usize| v[k].parse::<f64>().unwrap();
        assert_eq!(num(3).to_bits(), r.x[0].to_bits());
        assert_eq!(num(5).to_bits(), r.weight.to_bits());
        assert_eq!(num(11).to_bits(), r.pressure.to_bits());
        assert_eq!(num(12).to_bits(), r.traction_t[0].to_bits());
        assert_eq!(num(14).to_bits(), r.slip[0].to_bits());
        assert_eq!(v[16], "slip");
    }
    let _ = std::fs::remove_file(&path);
    // The same fields in the run's ParaView files, and the CSV beside them.
    let dir = std::env::temp_dir().join(format!("alea-contact-vtu-{}", std::process::id()));
    let written = alea_latin::output::write_run(dir.join("run.vtm"), &solver, &res).unwrap();
    assert!(
        written
            .iter()
            .any(|p| p.ends_with("run/interface_contact.csv"))
    );
    let vtu = std::fs::read_to_string(dir.join("run/block.vtu")).unwrap();
    for name in [
        "contact_weight",
        "contact_normal",
        "contact_gap",
        "contact_pressure",
        "contact_traction_t",
        "contact_slip",
        "contact_status",
    ] {
        assert!(
            vtu.contains(&format!("Name=\"{name}\"")),
            "{name} in the VTU"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    check_reactions(&built, &solver, &res, &loads);
    // The block's constraint pulls it along with the friction force.
    let r = nodal_reactions(&solver, &res, 1, &loads[1]).unwrap();
    let top = built.assembly.subs[1]
        .model
        .mesh
        .group_nodes("upper_top")
        .unwrap();
    let rt = group_sum(&r, 2, &top);
    assert!(close(rt[0], mu * n_expected, 1e-6), "{rt:?}");
}

#[test]
fn block_on_incline_follows_statics_up_to_the_cgs4_threshold() {
    let (mut built, _) = example("incline-cgs4.toml");
    built.options.max_iterations = 3000;
    let (a, mu) = (15f64.to_radians(), 0.1);
    let g = 800.0; // weight: body force 1 N/mm^3 over 40 x 20 x 1 mm^3
    let f_nominal = 300.0; // traction 15 MPa over the 20 mm face
    let threshold = g * (a.tan() + mu) / (1.0 - mu * a.tan());
    let (n_dir, t_dir) = ([-a.sin(), a.cos()], [a.cos(), a.sin()]);
    for ratio in [0.5, 0.9, 0.99] {
        let f = ratio * threshold;
        let (solver, res, loads) = solve(&built, &[vec![], vec![1.0, f / f_nominal]]);
        assert_eq!(res.status, RunStatus::Converged, "F = {ratio} x threshold");
        let r = res.interfaces[0].resultant();
        let n = r[0] * n_dir[0] + r[1] * n_dir[1];
        let t = r[0] * t_dir[0] + r[1] * t_dir[1];
        // Force on the block from the incline: pushes it off the slope and holds it back.
        assert!(close(n, g * a.cos() + f * a.sin(), 1e-6), "N = {n}");
        assert!(close(-t, f * a.cos() - g * a.sin(), 1e-6), "T = {t}");
        assert!(
            t.abs() < mu * n,
            "below the threshold: |T| = {t}, mu N = {}",
            mu * n
        );
        check_reactions(&built, &solver, &res, &loads);
    }
    // Just above the threshold the block slides away: no static equilibrium.
    let f = 1.05 * threshold;
    let (_, res, _) = solve(&built, &[vec![], vec![1.0, f / f_nominal]]);
    assert_ne!(
        res.status,
        RunStatus::Converged,
        "no equilibrium above the threshold"
    );
}

#[test]
fn shrink_fit_pressure_is_lames() {
    let (built, _) = example("shrink-fit.toml");
    let (solver, res, loads) = solve(&built, &[]);
    assert_eq!(res.status, RunStatus::Converged);
    let (a, b, c, delta, e) = (50.0f64, 80.0f64, 120.0f64, 0.05, 210e3);
    let lame = e * delta * (b * b - a * a) * (c * c - b * b) / (2.0 * b.powi(3) * (c * c - a * a));
    let rows = contact_rows(&res.interfaces[0]);
    let (mut pm, mut m) = (0.0, 0.0);
    for r in &rows {
        assert!(r.gap.abs() < 1e-6 * delta, "closed everywhere: {r:?}");
        pm += r.weight * r.pressure;
        m += r.weight;
    }
    let p = pm / m;
    assert!(close(p, lame, 5e-3), "mean pressure {p} vs Lame {lame}");
    // Uniform pressure: to 0.1 % away from the symmetry planes; the nodes on them (which also
    // carry a symmetry constraint) and their neighbours deviate by a few percent.
    for r in &rows {
        let to_plane = r.x[0].abs().min(r.x[1].abs());
        let tol = if to_plane < 1e-9 * b {
            0.06
        } else if to_plane < 0.1 * b {
            0.015
        } else {
            1e-3
        };
        assert!(
            close(r.pressure, lame, tol),
            "{} vs {lame} at {:?}",
            r.pressure,
            r.x
        );
    }
    check_reactions(&built, &solver, &res, &loads);
}

#[test]
fn hertz_line_contact_half_width_and_peak_pressure() {
    let (built, _) = example("hertz-line-contact.toml");
    let (solver, res, loads) = solve(&built, &[]);
    assert_eq!(res.status, RunStatus::Converged);
    let (e, nu, r, p) = (210e3f64, 0.3f64, 20.0f64, 1500.0f64);
    let e_star = e / (2.0 * (1.0 - nu * nu));
    let b = (4.0 * p * r / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * p / (std::f64::consts::PI * b);
    let h = 1.22 / 50.0;
    let mut rows = contact_rows(&res.interfaces[0]);
    rows.sort_by(|u, v| u.x[0].total_cmp(&v.x[0]));
    // Peak pressure at x = 0 and the edge of the contact zone (last closed point).
    assert!(
        close(rows[0].pressure, p0, 0.03),
        "p(0) = {} vs {p0}",
        rows[0].pressure
    );
    let edge = rows
        .iter()
        .filter(|q| q.status != PointStatus::Open)
        .map(|q| q.x[0])
        .fold(0.0, f64::max);
    assert!(edge <= b && b < edge + h, "edge {edge}, b {b}, h {h}");
    // Total contact force on the half model = P'/2.
    let total: f64 = rows.iter().map(|q| q.weight * q.pressure).sum();
    assert!(close(total, 0.5 * p, 1e-5), "{total}");
    check_reactions(&built, &solver, &res, &loads);
}
