//! The bipotential interface density on hand-made interface states with known values
//! (conventions of `alea_latin::law`: `n` outward of side 1, `F = F_hat_2`, jump `[W] = W_2 - W_1`,
//! `w = [W] + g0 n`): `e = mu F_n |w_t| + w_n F_n + w_t . F_t`, checked point by point, and the
//! strict-admissibility checks (3.27).

use alea_cre::interface_term;
use std::sync::Arc;

use alea_latin::{
    InterfacePairing, InterfaceResult, PairingKind, PointData, PointStatus, SideProjection,
};

fn result(points: Vec<(f64, f64, [f64; 2], [f64; 2])>, law: &'static str) -> InterfaceResult {
    // Tilted normal to catch component mix-ups: n = (sin a, cos a), t = (cos a, -sin a).
    let a: f64 = 0.4;
    let n = [a.sin(), a.cos(), 0.0];
    let t = [a.cos(), -a.sin(), 0.0];
    let np = points.len();
    let mut r = InterfaceResult {
        name: "i".into(),
        law,
        subs: [0, 1],
        nodes: [(0..np).collect(), (0..np).collect()],
        pairing: Arc::new(InterfacePairing {
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
        w: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
        f: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
        what: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
        what_prev: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
        fhat: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
        status: vec![PointStatus::Stick; np],
    };
    // (mu, g0, [jump_n, jump_t] of stage n - 1 without the gap, [F_n, F_t] of stage n)
    for (i, (mu, g0, j, f)) in points.into_iter().enumerate() {
        r.points.push(PointData {
            x: [i as f64, 0.0, 0.0],
            normal: n,
            mu,
            gap: g0,
        });
        r.weights.push(0.5 + i as f64);
        // Side 1 fixed at 0.3 (any value: only the jump matters), side 2 = side 1 + jump.
        let base = [0.3, -0.1, 0.0];
        r.what_prev[0][i] = base;
        for c in 0..3 {
            r.what_prev[1][i][c] = base[c] + j[0] * n[c] + j[1] * t[c];
            r.fhat[1][i][c] = f[0] * n[c] + f[1] * t[c];
            r.fhat[0][i][c] = -r.fhat[1][i][c];
        }
    }
    r
}

#[test]
fn contact_density_and_admissibility() {
    let pts = vec![
        // Slipping (w_t = 0.1) at n - 1, sticking inside the cone at n: 0.3 * 1 * 0.1 - 0.02.
        (0.3, 0.0, [0.0, 0.1], [1.0, -0.2]),
        // Open at n - 1 (g = 0.05 through the initial gap), closed at n: w_n F_n = 0.05 * 2.
        (0.3, 0.05, [0.0, 0.0], [2.0, 0.0]),
        // Same slip at both stages (anti-parallel, on the cone): 0.
        (0.5, 0.0, [0.0, -0.2], [1.0, 0.5]),
        // Open at both stages: 0.
        (0.5, 0.0, [0.1, 0.3], [0.0, 0.0]),
        // Slip reversed between stages (w_t parallel to F_t on the cone): 2 mu F_n |w_t|.
        (0.5, 0.0, [0.0, 0.2], [1.0, 0.5]),
    ];
    let want = [0.01, 0.1, 0.0, 0.0, 0.2];
    let r = result(pts, "coulomb");
    let est = interface_term(&r, 1e-8).unwrap();
    assert_eq!(est.violations, 0);
    let mut term = 0.0;
    for (i, (&e, &w)) in est.density.iter().zip(&want).enumerate() {
        assert!((e - w).abs() < 1e-14, "point {i}: {e} vs {w}");
        term += r.weights[i] * w;
    }
    assert!((est.term - term).abs() < 1e-14);

    // Violations of (3.27): interpenetration at n - 1, force outside the cone, tensile force.
    let bad = vec![
        (0.3, 0.0, [-0.01, 0.0], [1.0, 0.0]),
        (0.3, 0.0, [0.0, 0.0], [1.0, 0.4]),
        (0.3, 0.0, [0.1, 0.0], [-0.5, 0.0]),
        (0.3, 0.0, [0.0, 0.0], [1.0, 0.1]),
    ];
    let est = interface_term(&result(bad, "coulomb"), 1e-8).unwrap();
    assert_eq!(est.violations, 3);
    assert!(est.max_violation > 0.05);
}

#[test]
fn perfect_interface_density() {
    // Bonded: no jump -> zero density whatever the force; a jump is a violation.
    let est = interface_term(
        &result(vec![(0.0, 0.0, [0.0, 0.0], [3.0, -1.0])], "perfect"),
        1e-8,
    )
    .unwrap();
    assert_eq!(est.violations, 0);
    assert_eq!(est.density[0], 0.0);
    let est = interface_term(
        &result(vec![(0.0, 0.0, [0.0, 0.01], [3.0, -1.0])], "perfect"),
        1e-8,
    )
    .unwrap();
    assert_eq!(est.violations, 1);
    // Inconsistent arrays: typed error.
    let mut r = result(vec![(0.0, 0.0, [0.0, 0.0], [1.0, 0.0])], "perfect");
    r.weights.clear();
    assert!(interface_term(&r, 1e-8).is_err());
}
