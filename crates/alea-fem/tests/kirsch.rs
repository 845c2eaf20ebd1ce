//! Kirsch: an infinite plate with a circular hole under remote uniaxial tension.
//!
//! Reference: G. Kirsch, *Die Theorie der Elastizitaet und die Beduerfnisse der
//! Festigkeitslehre*, Z. VDI 42 (1898); closed form as in Timoshenko & Goodier, *Theory of
//! Elasticity* (3rd ed., 1970), section 35, and Barber, *Elasticity* (3rd ed.), section 8.4.1.
//! With remote stress `s` along x, hole radius `a`, polar coordinates `(r, theta)`:
//!
//! ```text
//! s_rr = s/2 (1 - a^2/r^2) + s/2 (1 - 4 a^2/r^2 + 3 a^4/r^4) cos 2theta
//! s_tt = s/2 (1 + a^2/r^2) - s/2 (1 + 3 a^4/r^4) cos 2theta
//! s_rt = -s/2 (1 + 2 a^2/r^2 - 3 a^4/r^4) sin 2theta
//! u_r  = s/(4 mu) [ r ((kappa - 1)/2 + cos 2theta) + a^2/r (1 + (1 + kappa) cos 2theta)
//!                   - a^4/r^3 cos 2theta ]
//! u_t  = s/(4 mu) [ (1 - kappa) a^2/r - r - a^4/r^3 ] sin 2theta
//! ```
//! with `kappa = (3 - nu)/(1 + nu)` in plane stress. At the top of the hole (`r = a`,
//! `theta = 90 deg`) `s_xx = s_tt = 3 s`; along the ligament `x = 0`,
//! `s_xx(y) = s (1 + a^2/(2 y^2) + 3 a^4/(2 y^4))`. `exact_fields_are_consistent` checks that the
//! displacement above gives the stress above (central differences + Hooke) and that the stress
//! is divergence-free and traction-free on the hole, so the two formulas cannot disagree
//! silently.
//!
//! Set-up: the symmetric quarter `[0, L]^2` minus the hole (`generate::plate_with_hole`),
//! plane stress. Symmetry: `u_x = 0` on `xsym` (x = 0), `u_y = 0` on `ysym` (y = 0). Instead of
//! a large plate, the exact Kirsch traction `t = sigma_exact(x) n` is applied on the outer edges
//! `right` and `top`, so the finite quarter has exactly the infinite-plate solution and every
//! remaining error is discretisation error.
//!
//! ```text
//!   y  L +--- top: t = sigma(x) n ---+
//!        |                           |
//!   xsym |                           | right: t = sigma(x) n
//!   u_x=0|                           |
//!      a +.                          |
//!        |  '. hole (free)           |
//!        +----+----------------------+ x
//!        0    a   ysym: u_y = 0      L
//! ```
//! Goal: stress concentration factor `s_xx(0, a) / s = 3` within 2 % (issue 2) - we get much closer
//! and assert 0.5 % on Q8 and T6 (32 cells along the quarter arc, 20 radially, grading 5: Q8
//! 3.0045, T6 3.0032, and the same for von Mises, the hole edge being uniaxial) - the stresses
//! `s_xx(0, y)` and `s_yy(x, 0)` along both symmetry lines at every node within 1 % of `s` on Q8
//! (observed 0.45 %) and 2 % on T6 (0.92 %), and every nodal displacement within 0.1 % of the
//! largest (observed 2e-5 and 9e-5). On Q4 the SCF error must fall like `h` (the hole-top node is a
//! domain corner, where a Q4 stress is first-order: 3.049, 3.029, 3.016) and be below 1 % with 128
//! x 80 cells (arc x radial).

use alea_fem::{
    Analysis, Constraints, Loads, Material, Model, Ordering, post::nodal_stresses, solve_elastic,
};
use alea_mesh::{CellType, generate};

const E: f64 = 210e3;
const NU: f64 = 0.3;
const S: f64 = 100.0;
const A: f64 = 10.0;
const L: f64 = 50.0;

/// Cartesian Kirsch stress `[xx, yy, xy]` at `x`.
fn kirsch_stress(x: [f64; 3]) -> [f64; 3] {
    let r2 = x[0] * x[0] + x[1] * x[1];
    let (a2, a4) = (A * A, A * A * A * A);
    let th = x[1].atan2(x[0]);
    let (c2, s2) = ((2.0 * th).cos(), (2.0 * th).sin());
    let srr =
        S / 2.0 * (1.0 - a2 / r2) + S / 2.0 * (1.0 - 4.0 * a2 / r2 + 3.0 * a4 / (r2 * r2)) * c2;
    let stt = S / 2.0 * (1.0 + a2 / r2) - S / 2.0 * (1.0 + 3.0 * a4 / (r2 * r2)) * c2;
    let srt = -S / 2.0 * (1.0 + 2.0 * a2 / r2 - 3.0 * a4 / (r2 * r2)) * s2;
    let (c, s) = (th.cos(), th.sin());
    [
        srr * c * c - 2.0 * srt * s * c + stt * s * s,
        srr * s * s + 2.0 * srt * s * c + stt * c * c,
        (srr - stt) * s * c + srt * (c * c - s * s),
    ]
}

/// Cartesian Kirsch displacement (plane stress) at `x`.
fn kirsch_displacement(x: [f64; 3]) -> [f64; 2] {
    let mu = E / (2.0 * (1.0 + NU));
    let kappa = (3.0 - NU) / (1.0 + NU);
    let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
    let th = x[1].atan2(x[0]);
    let (c2, s2) = ((2.0 * th).cos(), (2.0 * th).sin());
    let f = S / (4.0 * mu);
    let ur = f
        * (r * ((kappa - 1.0) / 2.0 + c2) + A * A / r * (1.0 + (1.0 + kappa) * c2)
            - A.powi(4) / r.powi(3) * c2);
    let ut = f * ((1.0 - kappa) * A * A / r - r - A.powi(4) / r.powi(3)) * s2;
    let (c, s) = (th.cos(), th.sin());
    [ur * c - ut * s, ur * s + ut * c]
}

#[test]
fn exact_fields_are_consistent() {
    let h = 1e-4;
    let c = E / (1.0 - NU * NU);
    for x in [[3.0, 11.0, 0.0], [12.0, 4.0, 0.0], [20.0, 30.0, 0.0]] {
        let d = |i: usize, j: usize| {
            let (mut xp, mut xm) = (x, x);
            xp[j] += h;
            xm[j] -= h;
            (kirsch_displacement(xp)[i] - kirsch_displacement(xm)[i]) / (2.0 * h)
        };
        let (exx, eyy, gxy) = (d(0, 0), d(1, 1), d(0, 1) + d(1, 0));
        let from_u = [
            c * (exx + NU * eyy),
            c * (NU * exx + eyy),
            c * (1.0 - NU) / 2.0 * gxy,
        ];
        let s = kirsch_stress(x);
        for k in 0..3 {
            assert!(
                (from_u[k] - s[k]).abs() < 1e-6 * S,
                "stress {k} at {x:?}: {} from u, {} closed form",
                from_u[k],
                s[k]
            );
        }
        // Equilibrium: d s_xx/dx + d s_xy/dy = 0, d s_xy/dx + d s_yy/dy = 0.
        let ds = |k: usize, j: usize| {
            let (mut xp, mut xm) = (x, x);
            xp[j] += h;
            xm[j] -= h;
            (kirsch_stress(xp)[k] - kirsch_stress(xm)[k]) / (2.0 * h)
        };
        assert!((ds(0, 0) + ds(2, 1)).abs() < 1e-6 * S);
        assert!((ds(2, 0) + ds(1, 1)).abs() < 1e-6 * S);
    }
    // Traction-free hole and the peak 3 s.
    for deg in [0.0f64, 20.0, 45.0, 80.0, 90.0] {
        let t = deg.to_radians();
        let (n0, n1) = (t.cos(), t.sin());
        let s = kirsch_stress([A * n0, A * n1, 0.0]);
        assert!((s[0] * n0 + s[2] * n1).abs() < 1e-12 * S);
        assert!((s[2] * n0 + s[1] * n1).abs() < 1e-12 * S);
    }
    assert!((kirsch_stress([0.0, A, 0.0])[0] - 3.0 * S).abs() < 1e-12 * S);
}

/// Solves the quarter plate in `kind` and checks the SCF (relative tolerance `tol_scf`), the
/// stresses along both symmetry lines (`tol_line` of `s`) and the displacements (`tol_u` of the
/// largest).
fn check_fine(kind: CellType, tol_scf: f64, tol_line: f64, tol_u: f64) {
    let mesh = generate::plate_with_hole(A, L, 32, 20, 5.0, kind).unwrap();
    let mut model = Model::new(mesh, Analysis::PlaneStress { thickness: 2.0 }).unwrap();
    model.set_material_all(Material::new(E, NU, 0.0).unwrap());
    let mut cons = Constraints::new();
    cons.fix_component(&model.mesh, "xsym", 0, 0.0).unwrap();
    cons.fix_component(&model.mesh, "ysym", 1, 0.0).unwrap();
    let mut loads = Loads::new(&model);
    let traction = |x: [f64; 3], n: [f64; 3]| {
        let s = kirsch_stress(x);
        [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1], 0.0]
    };
    loads.traction(&model, "right", traction).unwrap();
    loads.traction(&model, "top", traction).unwrap();
    let sol = solve_elastic(&model, &cons, &loads, Ordering::Metis).unwrap();
    let sig = nodal_stresses(&model, &sol.u).unwrap();
    let mesh = &model.mesh;

    // Peak at the top of the hole.
    let top = (0..mesh.num_nodes())
        .find(|&n| {
            let x = mesh.coords[n];
            x[0].abs() < 1e-9 && (x[1] - A).abs() < 1e-9
        })
        .expect("node at the top of the hole");
    let scf = sig[top][0] / S;
    eprintln!("{kind} Kirsch: s_xx(0, a) / s = {scf:.5}");
    assert!(
        (scf - 3.0).abs() < tol_scf * 3.0,
        "{kind}: SCF {scf}, expected 3"
    );
    // The hole edge is traction-free, so the state there is uniaxial (hoop): von Mises = 3 s.
    let vm = alea_fem::von_mises(&sig[top]) / S;
    assert!(
        (vm - 3.0).abs() < 0.005 * 3.0,
        "von Mises {vm} s, expected 3 s"
    );

    // Ligament x = 0 and the line y = 0: every node against the closed form.
    let mut worst: f64 = 0.0;
    for (group, comp) in [("xsym", 0), ("ysym", 1)] {
        for n in mesh.group_nodes(group).unwrap() {
            let x = mesh.coords[n];
            let exact = kirsch_stress(x);
            let k = if comp == 0 { 0 } else { 1 };
            let err = (sig[n][k] - exact[k]).abs() / S;
            worst = worst.max(err);
            assert!(
                err < tol_line,
                "{kind} {group} at {x:?}: s = {} vs {} (closed form)",
                sig[n][k],
                exact[k]
            );
        }
    }
    eprintln!("{kind} Kirsch: worst ligament stress error {:.2e} s", worst);

    // Displacements at every node, relative to the largest exact displacement.
    let umax = mesh
        .coords
        .iter()
        .map(|&x| {
            let u = kirsch_displacement(x);
            u[0].hypot(u[1])
        })
        .fold(0.0, f64::max);
    let mut uerr: f64 = 0.0;
    for (n, &x) in mesh.coords.iter().enumerate() {
        let u = kirsch_displacement(x);
        uerr = uerr.max((sol.u[2 * n] - u[0]).hypot(sol.u[2 * n + 1] - u[1]) / umax);
    }
    eprintln!("{kind} Kirsch: max displacement error {uerr:.2e} of max |u|");
    assert!(uerr < tol_u, "{kind}: displacement error {uerr:e}");
}

#[test]
fn stress_concentration_and_ligament_on_q8() {
    check_fine(CellType::Quad8, 0.005, 0.01, 1e-3);
}

#[test]
fn stress_concentration_and_ligament_on_t6() {
    check_fine(CellType::Tri6, 0.005, 0.02, 1e-3);
}

#[test]
fn stress_concentration_improves_with_refinement_on_q4() {
    // The hole-top node is a corner of the domain, in a single cell: its Q4 stress is the
    // cell's stress at a vertex, first-order accurate, so the SCF error should halve with h
    // (observed ratios 1.7 and 1.85, approaching 2).
    let mut errs = Vec::new();
    for (n_arc, n_rad) in [(32, 20), (64, 40), (128, 80)] {
        let mesh = generate::plate_with_hole(A, L, n_arc, n_rad, 5.0, CellType::Quad4).unwrap();
        let mut model = Model::new(mesh, Analysis::PlaneStress { thickness: 1.0 }).unwrap();
        model.set_material_all(Material::new(E, NU, 0.0).unwrap());
        let mut cons = Constraints::new();
        cons.fix_component(&model.mesh, "xsym", 0, 0.0).unwrap();
        cons.fix_component(&model.mesh, "ysym", 1, 0.0).unwrap();
        let mut loads = Loads::new(&model);
        let traction = |x: [f64; 3], n: [f64; 3]| {
            let s = kirsch_stress(x);
            [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1], 0.0]
        };
        loads.traction(&model, "right", traction).unwrap();
        loads.traction(&model, "top", traction).unwrap();
        let sol = solve_elastic(&model, &cons, &loads, Ordering::Amd).unwrap();
        let sig = nodal_stresses(&model, &sol.u).unwrap();
        let top = (0..model.mesh.num_nodes())
            .find(|&n| {
                let x = model.mesh.coords[n];
                x[0].abs() < 1e-9 && (x[1] - A).abs() < 1e-9
            })
            .unwrap();
        let scf = sig[top][0] / S;
        eprintln!("Q4 Kirsch {n_arc} x {n_rad}: SCF {scf:.4}");
        errs.push((scf - 3.0).abs());
    }
    assert!(
        errs[1] < errs[0] / 1.6 && errs[2] < errs[1] / 1.6,
        "SCF errors {errs:?} do not fall like h"
    );
    assert!(errs[2] < 0.01 * 3.0, "SCF errors {errs:?}");
}
