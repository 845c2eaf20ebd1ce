//! The interface term of the CRE in 3D: the bipotential density with a two-dimensional
//! tangential plane (and the gap), first on hand-made interface states with known values, then
//! along the LATIN iterations of a 3D frictional contact problem.
//!
//! Conventions of `alea_latin::law`: `n` outward of side 1, `F = F_hat_2`, jump `[W] = W_2 -
//! W_1`, `w = [W] + g0 n`; density `e = mu F_n |w_t| + w_n F_n + w_t . F_t` (3.26) with
//! `w_t`, `F_t` the projections on the tangent plane, and the strict-admissibility checks (3.27).
//!
//! LATIN problem (`nu = 0.3`, Hex8):
//! ```text
//!        t = (0.2 P d, -p(x)),  p(x) = P (0.5 + x / 2),  d = (cos 0.6, sin 0.6, 0),  mu = 0.3
//!        +-----------------+  z = 1      block [0,2] x [0,1] x [0,1] (side 2), floating
//!        |      block      |
//!        +=================+  z = 0      Coulomb contact, n = +z
//!        |      plane      |
//!        +-----------------+  z = -1     clamped
//!       x=0               x=2
//! ```
//! The block slips near `x = 0` (`0.2 P > mu p`) along an oblique direction and sticks
//! elsewhere. Along the LATIN iterations (runs stopped after 2, 3, ... iterations, then at
//! convergence) the interface density is `>= 0` at every point, no admissibility violation
//! occurs, the term is visible in the first iterations, decays with the LATIN residual once
//! the statuses have settled (the slip directions still turn: a 3D effect) and is zero to
//! round-off at convergence; the substructure estimates of the converged run are compatible.

mod common;

use alea_cre::{CreOptions, LoadData, estimate_latin, interface_term};
use alea_fem::{Constraints, Loads, Model};
use alea_latin::{
    Assembly, InterfacePairing, InterfaceResult, InterfaceSpec, LatinOptions, LatinSolver,
    PairingKind, PointData, PointStatus, RunInput, RunResult, SideProjection, Substructure,
};
use alea_mesh::{CellType, generate};
use common::solid::solid_model;

/// A generic 3D frame: normal `n` and an orthonormal tangent basis `(t1, t2)`.
fn frame() -> ([f64; 3], [f64; 3], [f64; 3]) {
    let n = [0.48, 0.64, -0.6];
    let t1 = [0.8, -0.6, 0.0];
    let t2 = [
        n[1] * t1[2] - n[2] * t1[1],
        n[2] * t1[0] - n[0] * t1[2],
        n[0] * t1[1] - n[1] * t1[0],
    ];
    (n, t1, t2)
}

/// Interface states `(mu, g0, [w_n, w_t1, w_t2] of stage n - 1 without the gap, [F_n, F_t1,
/// F_t2] of stage n)`.
type State = (f64, f64, [f64; 3], [f64; 3]);

fn result(points: Vec<State>, law: &'static str) -> InterfaceResult {
    let (n, t1, t2) = frame();
    let np = points.len();
    let z = || [vec![[0.0; 3]; np], vec![[0.0; 3]; np]];
    let mut r = InterfaceResult {
        name: "i".into(),
        law,
        subs: [0, 1],
        nodes: [(0..np).collect(), (0..np).collect()],
        pairing: std::sync::Arc::new(InterfacePairing {
            kind: PairingKind::NodeToNode,
            x: vec![],
            normals: vec![],
            weights: vec![],
            geometric_gap: vec![],
            sides: [
                SideProjection::identity(vec![], vec![]),
                SideProjection::identity(vec![], vec![]),
            ],
            rotation: None,
            point_nodes: Vec::new(),
        }),
        points: vec![],
        weights: vec![],
        w: z(),
        f: z(),
        what: z(),
        what_prev: z(),
        fhat: z(),
        status: vec![PointStatus::Stick; np],
    };
    for (i, (mu, g0, j, f)) in points.into_iter().enumerate() {
        r.points.push(PointData {
            x: [i as f64, 0.0, 0.0],
            normal: n,
            mu,
            gap: g0,
        });
        r.weights.push(0.5 + i as f64);
        let base = [0.3, -0.1, 0.2];
        r.what_prev[0][i] = base;
        for c in 0..3 {
            r.what_prev[1][i][c] = base[c] + j[0] * n[c] + j[1] * t1[c] + j[2] * t2[c];
            r.fhat[1][i][c] = f[0] * n[c] + f[1] * t1[c] + f[2] * t2[c];
            r.fhat[0][i][c] = -r.fhat[1][i][c];
        }
    }
    r
}

#[test]
fn density_with_a_two_dimensional_tangent_plane() {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let pts = vec![
        // Slipping along t1 at n - 1, sticking at n with a force along t2: mu F_n |w_t| + 0.
        (0.3, 0.0, [0.0, 0.1, 0.0], [1.0, 0.0, 0.2]),
        // Slip direction turned by 90 degrees on the cone: mu F_n |w_t| = 0.5 * 1 * 0.2.
        (0.5, 0.0, [0.0, 0.2, 0.0], [1.0, 0.0, 0.5]),
        // Same oblique slip at both stages (anti-parallel, on the cone): 0.
        (0.5, 0.0, [0.0, -0.2 * s, -0.2 * s], [1.0, 0.5 * s, 0.5 * s]),
        // Oblique slip at n - 1, force at 135 degrees from it on the cone:
        // mu F_n |w_t| + w_t . F_t = 0.5 * 2 * 0.2 + 0.2 * 1.0 * cos(135 deg).
        (0.5, 0.0, [0.0, 0.2 * s, 0.2 * s], [2.0, -1.0, 0.0]),
        // Open at n - 1 through the initial gap (g = 0.05), closed at n: w_n F_n = 0.05 * 2.
        (0.3, 0.05, [0.0, 0.0, 0.0], [2.0, 0.1, -0.2]),
        // Open at both stages: 0.
        (0.5, 0.0, [0.1, 0.3, -0.2], [0.0, 0.0, 0.0]),
    ];
    let want = [0.03, 0.1, 0.0, 0.2 - 0.2 * s, 0.1, 0.0];
    let r = result(pts, "coulomb");
    let est = interface_term(&r, 1e-8).unwrap();
    assert_eq!(est.violations, 0, "{}", est.max_violation);
    let mut term = 0.0;
    for (i, (&e, &w)) in est.density.iter().zip(&want).enumerate() {
        assert!((e - w).abs() < 1e-14, "point {i}: {e} vs {w}");
        term += r.weights[i] * w;
    }
    assert!((est.term - term).abs() < 1e-14);
    // Violations of (3.27): interpenetration at n - 1, an oblique force outside the cone, a
    // tensile force; the last point is inside the cone (|F_t| = 0.2 sqrt(2) < 0.3).
    let bad = vec![
        (0.3, 0.0, [-0.01, 0.0, 0.0], [1.0, 0.0, 0.0]),
        (0.3, 0.0, [0.0, 0.0, 0.0], [1.0, 0.3 * s, 0.3]),
        (0.3, 0.0, [0.1, 0.0, 0.0], [-0.5, 0.0, 0.0]),
        (0.3, 0.0, [0.0, 0.0, 0.0], [1.0, 0.2, -0.2]),
    ];
    let est = interface_term(&result(bad, "coulomb"), 1e-8).unwrap();
    assert_eq!(est.violations, 3);
    // A perfect interface: zero density without jump, a violation with one.
    let est = interface_term(
        &result(
            vec![(0.0, 0.0, [0.0, 0.0, 0.0], [3.0, -1.0, 2.0])],
            "perfect",
        ),
        1e-8,
    )
    .unwrap();
    assert_eq!((est.violations, est.density[0]), (0, 0.0));
    let est = interface_term(
        &result(
            vec![(0.0, 0.0, [0.0, 0.0, 0.01], [3.0, -1.0, 2.0])],
            "perfect",
        ),
        1e-8,
    )
    .unwrap();
    assert_eq!(est.violations, 1);
}

const E: f64 = 1000.0;
const P: f64 = 10.0;
const MU: f64 = 0.3;

fn top(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    let phi: f64 = 0.6;
    [
        0.2 * P * phi.cos(),
        0.2 * P * phi.sin(),
        -P * (0.5 + 0.5 * x[0]),
    ]
}

fn box_model(z0: f64) -> Model {
    let mut mesh = generate::box_mesh([2.0, 1.0, 1.0], [8, 4, 4], CellType::Hex8).unwrap();
    for x in mesh.coords.iter_mut() {
        x[2] += z0;
    }
    let mut m = solid_model(mesh);
    m.set_material_all(alea_fem::Material::new(E, 0.3, 0.0).unwrap());
    m
}

fn problem() -> (Assembly, Vec<LoadData>) {
    let plane = box_model(-1.0);
    let mut c = Constraints::new();
    c.clamp(&plane.mesh, "zmin").unwrap();
    let block = box_model(0.0);
    let mut loads = Loads::new(&block);
    loads.traction(&block, "zmax", top).unwrap();
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
    (
        Assembly {
            subs,
            interfaces: vec![InterfaceSpec::coulomb("contact", 0, "zmax", 1, "zmin", MU)],
        },
        vec![LoadData::new(), LoadData::new().traction("zmax", top)],
    )
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

#[test]
fn interface_term_along_latin_iterations_in_3d() {
    let (asm, data) = problem();
    let mut shares = Vec::new();
    for iters in [2, 3, 4, 5, 6, 8, 10, 15, 20, 30, 50000] {
        let run = solve_n(&asm, 1e-9, iters);
        let est = estimate_latin(&asm, &data, &run, &CreOptions::default()).unwrap();
        let it = &est.interfaces[0];
        let ir = &run.interfaces[0];
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let wmax = (0..ir.points.len())
            .map(|i| norm([0, 1, 2].map(|c| ir.what_prev[1][i][c] - ir.what_prev[0][i][c])))
            .fold(0.0f64, f64::max);
        let fmax = ir.fhat[1].iter().map(|f| norm(*f)).fold(0.0f64, f64::max);
        for (i, e) in it.density.iter().enumerate() {
            assert!(
                *e >= -1e-12 * wmax * fmax,
                "{iters} iterations: density {e} at point {i}"
            );
        }
        assert_eq!(it.violations, 0, "max violation {}", it.max_violation);
        let share = 2.0 * it.term / (est.theta * est.theta);
        println!(
            "{} iterations ({:?}): interface term {:.3e}, theta {:.4e} (subs {:?}), share of theta^2 \
             {share:.2e}, statuses {:?}, compat {:.1e}",
            run.iterations,
            run.status,
            it.term,
            est.theta,
            est.substructure_theta(),
            ir.status_counts(),
            est.compatibility_defect()
        );
        shares.push(share);
        if run.status == alea_latin::RunStatus::Converged {
            let c = ir.status_counts();
            assert!(c[2] > 0 && c[3] > 0, "stick and slip both present: {c:?}");
            assert!(est.compatibility_defect() < 1e-6);
            // The slip is oblique: both in-plane components of the tangential jump are used.
            let slip = (0..ir.points.len())
                .filter(|&i| ir.status[i] == PointStatus::Slip)
                .map(|i| ir.jump(i))
                .fold([0.0f64; 2], |m, j| {
                    [m[0].max(j[0].abs()), m[1].max(j[1].abs())]
                });
            assert!(slip[0] > 0.0 && slip[1] > 0.0, "{slip:?}");
            // Larger iteration budgets would only repeat the converged run.
            break;
        }
    }
    assert_eq!(
        alea_latin::RunStatus::Converged,
        solve_n(&asm, 1e-9, 50000).status,
        "the problem converges"
    );
    let early = shares[..4].iter().fold(0.0f64, |m, v| m.max(*v));
    assert!(
        early > 1e-4,
        "the early iterations have a visible interface term: {shares:?}"
    );
    // In 3D the slip direction at a slipping point turns continuously along the iterations
    // (in 2D it can only flip), and the density `mu F_n |w_t| (1 - cos angle)` follows it: the
    // term decays with the LATIN residual once the statuses have settled, and vanishes at
    // convergence.
    let n = shares.len();
    for w in shares[n - 4..].windows(2) {
        assert!(w[1] < w[0], "{shares:?}");
    }
    assert!(shares[n - 2] < 1e-8, "{shares:?}");
    assert!(shares[n - 1].abs() < 1e-12, "converged: {shares:?}");
}
