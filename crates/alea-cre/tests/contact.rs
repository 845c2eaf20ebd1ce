//! Frictional contact: a block pressed on a plane (as in `alea-latin/tests/block.rs`) by a
//! linearly varying pressure and a uniform shear that make it slip near `x = 0` and stick
//! elsewhere; `nu = 0.3`, so the stress field is not uniform and the FE error is not zero.
//!
//! ```text
//!        t = (tau, -p(x)),  p(x) = P (0.5 + x / 2),  tau = 0.2 P,  mu = 0.3
//!        +-----------------+  y = 1      block (side 2), floating
//!        |      block      |
//!        +=================+  y = 0      Coulomb contact, n = +y
//!        |      plane      |
//!        +-----------------+  y = -1     clamped
//!       x=0               x=2
//! ```
//! Reference: the same problem on meshes refined 3 times (8x finer, nested), solved by LATIN
//! to 1e-9; the true error is approximated by `(sum_s ||u_ref - u_h||^2_K)^(1/2)`, integrated on
//! the fine cells. Checks: efficiency `theta / ||u_ref - u_h|| >= 1` on two coarse meshes and on
//! two non-matching pairs (plane and block with different cell counts: mortar interface);
//! along the LATIN iterations (runs stopped after 2, 3, ... iterations) the interface density
//! is `>= 0` at every point, there is no admissibility violation, the interface term is visible
//! in the first iterations and zero (to round-off) once converged.

mod common;

use alea_cre::{CreOptions, LoadData, estimate_latin};
use alea_fem::{Analysis, Constraints, Loads, Material, Model, kinematics::point_geometry};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, PairingKind, RunInput, RunResult,
    Substructure,
};
use alea_mesh::{CellType, generate};

const E: f64 = 1000.0;
const NU: f64 = 0.3;
const P: f64 = 10.0;
const MU: f64 = 0.3;
const PS: Analysis = Analysis::PlaneStrain { thickness: 1.0 };

fn top(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    [0.2 * P, -P * (0.5 + 0.5 * x[0]), 0.0]
}

fn rect_model(y0: f64, nx: usize, ny: usize) -> Model {
    let mut mesh = generate::rectangle(2.0, 1.0, nx, ny, CellType::Quad4).unwrap();
    for x in mesh.coords.iter_mut() {
        x[1] += y0;
    }
    let mut m = Model::new(mesh, PS).unwrap();
    m.set_material_all(Material::new(E, NU, 0.0).unwrap());
    m
}

fn problem(nx: usize, ny: usize) -> (Assembly, Vec<LoadData>) {
    problem_with(nx, nx, ny)
}

/// The plane with `nx_plane` cells across, the block with `nx_block` (different counts: a
/// mortar interface).
fn problem_with(nx_plane: usize, nx_block: usize, ny: usize) -> (Assembly, Vec<LoadData>) {
    let plane = rect_model(-1.0, nx_plane, ny);
    let mut c = Constraints::new();
    c.clamp(&plane.mesh, "ymin").unwrap();
    let block = rect_model(0.0, nx_block, ny);
    let mut loads = Loads::new(&block);
    loads.traction(&block, "ymax", top).unwrap();
    let subs = vec![
        Substructure {
            name: "plane".into(),
            model: plane,
            constraints: c,
            load_cases: vec![],
        },
        Substructure {
            name: "block".into(),
            model: block,
            constraints: Constraints::new(),
            load_cases: vec![loads.f],
        },
    ];
    let iface = InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", MU);
    (
        Assembly {
            subs,
            interfaces: vec![iface],
        },
        vec![LoadData::new(), LoadData::new().traction("ymax", top)],
    )
}

fn solve(assembly: &Assembly, tol: f64) -> RunResult {
    solve_n(assembly, tol, 50000)
}

fn solve_n(assembly: &Assembly, tol: f64, max_iterations: usize) -> RunResult {
    let mut s = LatinSolver::new(
        assembly.clone(),
        LatinOptions {
            tolerance: tol,
            max_iterations,
            ..Default::default()
        },
    )
    .unwrap();
    s.run(&RunInput::default()).unwrap()
}

/// `||u_ref - u_h||^2_K` over one substructure, on the fine (nested) mesh.
fn diff2(fine: &Model, u_ref: &[f64], coarse: &Model, u_h: &[f64], nx: usize, ny: usize) -> f64 {
    let d = alea_fem::Material::new(E, NU, 0.0).unwrap().hooke(PS);
    let (hx, hy) = (2.0 / nx as f64, 1.0 / ny as f64);
    let (x0, y0) = (coarse.mesh.coords[0][0], coarse.mesh.coords[0][1]);
    let q = alea_fem::Quadrature::tensor(2, 3);
    let strain = |m: &Model, u: &[f64], c: usize, xi: [f64; 3]| {
        let g = point_geometry(CellType::Quad4, &m.cell_coords(c), xi);
        let mut e = [0.0; 3];
        for (a, &n) in m.mesh.cell_nodes(c).iter().enumerate() {
            e[0] += g.grad[a][0] * u[2 * n];
            e[1] += g.grad[a][1] * u[2 * n + 1];
            e[2] += g.grad[a][1] * u[2 * n] + g.grad[a][0] * u[2 * n + 1];
        }
        (e, g)
    };
    let mut sum = 0.0;
    for c in 0..fine.mesh.num_cells() {
        for (xi, w) in q.points.iter().zip(&q.weights) {
            let (ef, g) = strain(fine, u_ref, c, *xi);
            let i = (((g.x[0] - x0) / hx).floor() as usize).min(nx - 1);
            let j = (((g.x[1] - y0) / hy).floor() as usize).min(ny - 1);
            let cc = j * nx + i;
            let cx = coarse.cell_coords(cc);
            let xi_c = [
                2.0 * (g.x[0] - cx[0][0]) / hx - 1.0,
                2.0 * (g.x[1] - cx[0][1]) / hy - 1.0,
                0.0,
            ];
            let (eh, _) = strain(coarse, u_h, cc, xi_c);
            let de: Vec<f64> = (0..3).map(|k| ef[k] - eh[k]).collect();
            let mut s = 0.0;
            for a in 0..3 {
                for b in 0..3 {
                    s += de[a] * d[a * 3 + b] * de[b];
                }
            }
            sum += w * g.det * s;
        }
    }
    sum
}

#[test]
fn block_on_plane_with_friction() {
    let (nxr, nyr) = (64, 32);
    let (ref_asm, _) = problem(nxr, nyr);
    let reference = solve(&ref_asm, 1e-9);
    assert_eq!(reference.status, alea_latin::RunStatus::Converged);
    let counts = reference.interfaces[0].status_counts();
    assert!(
        counts[2] > 0 && counts[3] > 0,
        "stick and slip both present: {counts:?}"
    );
    // Matching meshes, then non-matching ones (mortar interface, both ways round).
    for (nxs, ny) in [([8, 8], 4), ([16, 16], 8), ([16, 8], 8), ([8, 16], 8)] {
        let (asm, data) = problem_with(nxs[0], nxs[1], ny);
        let run = solve(&asm, 1e-9);
        let kind = run.interfaces[0].pairing.kind;
        assert_eq!(kind == PairingKind::Mortar, nxs[0] != nxs[1]);
        let est = estimate_latin(&asm, &data, &run, &CreOptions::default()).unwrap();
        let err = (0..2)
            .map(|s| {
                diff2(
                    &ref_asm.subs[s].model,
                    &reference.displacements[s],
                    &asm.subs[s].model,
                    &run.displacements[s],
                    nxs[s],
                    ny,
                )
            })
            .sum::<f64>()
            .sqrt();
        let nx = format!("{kind:?} {}|{}", nxs[0], nxs[1]);
        let it = &est.interfaces[0];
        println!(
            "{nx}x{ny}: theta={:.4e} subs={:?} iface term={:.3e} err_ref={err:.4e} eff={:.3} compat={:.1e} rel={:.3e} status {:?}",
            est.theta,
            est.substructure_theta(),
            it.term,
            est.theta / err,
            est.compatibility_defect(),
            est.relative,
            run.interfaces[0].status_counts()
        );
        assert!(est.theta / err >= 1.0, "efficiency {}", est.theta / err);
        assert!(est.compatibility_defect() < 1e-6);
        assert_eq!(it.violations, 0);
        assert!(
            it.density
                .iter()
                .all(|&e| e >= -1e-9 * est.theta * est.theta)
        );
    }
    // Interface term along the LATIN iterations: stop after 2, 3, ... iterations, then at
    // convergence. The pointwise density vanishes wherever the status (open / stick / slip and
    // slip direction) is the same at local stages n - 1 and n, so it is non-zero only while the
    // statuses are still changing.
    let (asm, data) = problem(16, 8);
    let mut shares = Vec::new();
    for iters in [2, 3, 4, 5, 6, 8, 10, 15, 20, 30, 50000] {
        let run = solve_n(&asm, 1e-8, iters);
        let est = estimate_latin(&asm, &data, &run, &CreOptions::default()).unwrap();
        let it = &est.interfaces[0];
        // Round-off scale of the density (a product of jump and force magnitudes).
        let ir = &run.interfaces[0];
        let wmax = (0..ir.points.len())
            .map(|i| {
                (0..2)
                    .map(|c| (ir.what_prev[1][i][c] - ir.what_prev[0][i][c]).abs())
                    .sum::<f64>()
            })
            .fold(0.0f64, f64::max);
        let fmax = ir.fhat[1]
            .iter()
            .map(|f| f[0].abs() + f[1].abs())
            .fold(0.0f64, f64::max);
        for (i, e) in it.density.iter().enumerate() {
            assert!(
                *e >= -1e-12 * wmax * fmax,
                "{iters} iterations: density {e} at point {i}"
            );
        }
        assert_eq!(it.violations, 0, "max violation {}", it.max_violation);
        let share = 2.0 * it.term / (est.theta * est.theta);
        println!(
            "{} iterations ({:?}): interface term {:.3e}, theta {:.4e}, share of theta^2 {share:.2e}, statuses {:?}",
            run.iterations,
            run.status,
            it.term,
            est.theta,
            ir.status_counts()
        );
        shares.push(share);
    }
    let early = shares[..4].iter().fold(0.0f64, |m, v| m.max(*v));
    assert!(
        early > 1e-4,
        "the early iterations have a visible interface term: {shares:?}"
    );
    let last = *shares.last().unwrap();
    assert!(last.abs() < 1e-12, "converged: {shares:?}");
    // Once the statuses have settled the term is zero to round-off.
    assert!(
        shares[shares.len() - 3..].iter().all(|s| s.abs() < 1e-12),
        "{shares:?}"
    );
}
