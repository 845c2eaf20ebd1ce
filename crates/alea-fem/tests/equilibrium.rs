//! Global equilibrium, the energy identity, rotation invariance of skew constraints, and error
//! handling of bad input.
//!
//! Reference: any FE text on the discrete equilibrium of a conforming displacement model, e.g.
//! Zienkiewicz, Taylor & Zhu, *The Finite Element Method: Its Basis and Fundamentals* (7th ed.),
//! 2.5 and 4.6; Cook et al., *Concepts and Applications of FEA* (4th ed.), 2.10 (reactions),
//! 9.3 (skew supports). Exact statements used:
//!
//! - Consistent loads reproduce the resultants of the distributed loads exactly (isoparametric
//!   cells with straight sides: `sum_a N_a = 1`, `sum_a N_a x_a = x`), so `Loads::resultant`
//!   equals the closed-form integrals below (round-off, relative 1e-12).
//! - `K` annihilates rigid translations and (linearised) rotations, so the reactions
//!   `R = K u - f` balance the applied loads in force and moment: `sum R + sum f = 0` and
//!   `sum x x (R + f) = 0`; and `R = 0` at free dofs (the solve), so the balance holds with the
//!   reactions of the constrained nodes alone (relative 1e-10 of `sum |f|`).
//! - With homogeneous constraints the reactions do no work, so the strain energy
//!   `1/2 int sigma : eps = 1/2 u^T K u = 1/2 f . u` (relative 1e-10).
//! - A skew (normal) constraint on a rotated side is the same constraint as a component one on
//!   the axis-aligned side: rotating the whole model by 30 degrees rotates `u` and `sigma` and
//!   changes nothing else (relative 1e-9); uniaxial tension `s0` then gives `sigma = s0 e e`,
//!   `e` the rotated x axis, exactly. Imposing `u . n = d` (a non-zero skew constraint) on the
//!   rotated far side instead gives `s0 = E d / L`, `u = R (d x / L, -nu d y / L)` exactly, and a
//!   purely normal reaction of resultant `s0 h t e`.
//!
//! ```text
//!  2D: [0, 4] x [0, 1], plane stress t = 2         3D: [0, 2] x [0, 1] x [0, 1]
//!  xmin clamped, ymin: u_y = 0                      xmin clamped, zmin: u_z = 0
//!  xmax: traction (10 + 2 y, 3 y)                   xmax: traction (10 + 2 y, 3 z, -y)
//!  ymax: pressure 5                                 ymax: pressure 5
//!  body: (1 + x, -2), centrifugal about (-1, 0.5)   body: (1 + x, -2, z), centrifugal
//! ```
//! Also: per-group materials (a bar of two materials in series with nu = 0 is reproduced
//! exactly), `Model::scale_young` (u scales like 1 / E, reactions do not change), and von Mises
//! of a uniaxial state equals its magnitude. A floating body (a rigid-body mode left free) must be
//! `NotPositiveDefinite` even when round-off leaves a tiny positive pivot, on small and large 2D
//! and 3D meshes, without a false alarm on a 200:1 cantilever with a 1000:1 stiffness contrast.
//!
//! Goal: the statements above to round-off on every element type, and every bad input (E <= 0,
//! nu >= 0.5, unknown group, floating body, conflicting constraints, inverted cell, 2D/3D
//! mismatch) gives a `FemError` naming the problem, never a panic.

use alea_fem::{
    Analysis, Constraints, FemError, Loads, Material, Model, Ordering, post::nodal_stresses,
    post::strain_energy, solve_elastic, von_mises,
};
use alea_mesh::{CellType, Mesh, generate};

const E: f64 = 70e3;
const NU: f64 = 0.33;
const RHO: f64 = 2.7e-9;
const OMEGA: f64 = 2000.0;

fn rel_close(got: f64, want: f64, scale: f64, tol: f64) -> bool {
    (got - want).abs() <= tol * scale
}

/// Cross product `x x f` for 3-vectors.
fn cross(x: [f64; 3], f: [f64; 3]) -> [f64; 3] {
    [
        x[1] * f[2] - x[2] * f[1],
        x[2] * f[0] - x[0] * f[2],
        x[0] * f[1] - x[1] * f[0],
    ]
}

/// The four 2D load cases, each with its closed-form resultant.
fn loads_2d(model: &Model) -> Vec<(&'static str, Loads, [f64; 3])> {
    let (lx, ly, t) = (4.0, 1.0, model.analysis.thickness());
    let area = lx * ly;
    let mut out = Vec::new();
    let mut l = Loads::new(model);
    l.traction(model, "xmax", |x, _| [10.0 + 2.0 * x[1], 3.0 * x[1], 0.0])
        .unwrap();
    // int_0^1 (10 + 2y, 3y) dy = (11, 1.5).
    out.push(("traction", l, [11.0 * t, 1.5 * t, 0.0]));
    let mut l = Loads::new(model);
    l.pressure(model, "ymax", 5.0).unwrap();
    out.push(("pressure", l, [0.0, -5.0 * lx * t, 0.0]));
    let mut l = Loads::new(model);
    l.body_force(model, None, |x, _| [1.0 + x[0], -2.0, 0.0])
        .unwrap();
    // int (1 + x) dA = ly (lx + lx^2 / 2).
    out.push((
        "body",
        l,
        [ly * (lx + lx * lx / 2.0) * t, -2.0 * area * t, 0.0],
    ));
    let mut l = Loads::new(model);
    l.centrifugal(model, None, OMEGA, [-1.0, 0.5, 0.0], [0.0, 0.0, 1.0])
        .unwrap();
    // rho w^2 int (x - x0) dA = rho w^2 A (centroid - x0) = rho w^2 A (3, 0).
    let c = RHO * OMEGA * OMEGA * area * t;
    out.push(("centrifugal", l, [3.0 * c, 0.0, 0.0]));
    out
}

/// The four 3D load cases with their closed-form resultants.
fn loads_3d(model: &Model) -> Vec<(&'static str, Loads, [f64; 3])> {
    let (lx, ly, lz) = (2.0, 1.0, 1.0);
    let vol = lx * ly * lz;
    let mut out = Vec::new();
    let mut l = Loads::new(model);
    l.traction(model, "xmax", |x, _| [10.0 + 2.0 * x[1], 3.0 * x[2], -x[1]])
        .unwrap();
    out.push(("traction", l, [11.0, 1.5, -0.5]));
    let mut l = Loads::new(model);
    l.pressure(model, "ymax", 5.0).unwrap();
    out.push(("pressure", l, [0.0, -5.0 * lx * lz, 0.0]));
    let mut l = Loads::new(model);
    l.body_force(model, None, |x, _| [1.0 + x[0], -2.0, x[2]])
        .unwrap();
    out.push((
        "body",
        l,
        [ly * lz * (lx + lx * lx / 2.0), -2.0 * vol, 0.5 * vol],
    ));
    // Axis through p = (0, 0.5, 0.5) along (1, 1, 0)/sqrt2; the centroid c = (1, 0.5, 0.5), so
    // r = c - p = (1, 0, 0), its part across the axis (1, 0, 0) - (1/2)(1, 1, 0) = (1/2, -1/2, 0).
    let mut l = Loads::new(model);
    l.centrifugal(model, None, OMEGA, [0.0, 0.5, 0.5], [1.0, 1.0, 0.0])
        .unwrap();
    let c = RHO * OMEGA * OMEGA * vol;
    out.push(("centrifugal", l, [0.5 * c, -0.5 * c, 0.0]));
    out
}

fn model_of(mesh: Mesh, analysis: Analysis) -> Model {
    let mut model = Model::new(mesh, analysis).unwrap();
    model.set_material_all(Material::new(E, NU, RHO).unwrap());
    model
}

/// Checks resultants, force and moment balance of the reactions, zero residual at free nodes,
/// and the energy identity.
fn check_equilibrium(model: &Model, cons: &Constraints, cases: Vec<(&str, Loads, [f64; 3])>) {
    let dim = model.mesh.dim;
    let kind = model.mesh.cell_type(0);
    let mut total = Loads::new(model);
    for (name, l, want) in &cases {
        let got = l.resultant();
        let scale = want.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for c in 0..dim {
            assert!(
                rel_close(got[c], want[c], scale, 1e-12),
                "{kind} {name}: resultant {got:?}, closed form {want:?}"
            );
        }
        for (a, b) in total.f.iter_mut().zip(&l.f) {
            *a += b;
        }
    }
    let sol = solve_elastic(model, cons, &total, Ordering::Metis).unwrap();
    let constrained: std::collections::HashSet<usize> = ["xmin", "ymin", "zmin"]
        .iter()
        .filter_map(|g| model.mesh.group_nodes(g).ok())
        .flatten()
        .collect();
    let fscale: f64 = total.f.iter().map(|v| v.abs()).sum();
    let mut force = [0.0; 3];
    let mut moment = [0.0; 3];
    let mut free_residual: f64 = 0.0;
    for (n, x) in model.mesh.coords.iter().enumerate() {
        let mut f = [0.0; 3];
        let mut r = [0.0; 3];
        for c in 0..dim {
            f[c] = total.f[n * dim + c];
            r[c] = sol.reactions[n * dim + c];
        }
        if !constrained.contains(&n) {
            free_residual = free_residual.max(r.iter().map(|v| v.abs()).fold(0.0, f64::max));
            r = [0.0; 3];
        }
        let m = cross(*x, [f[0] + r[0], f[1] + r[1], f[2] + r[2]]);
        for c in 0..3 {
            force[c] += f[c] + r[c];
            moment[c] += m[c];
        }
    }
    let lscale = model
        .mesh
        .coords
        .iter()
        .map(|x| x[0].abs().max(x[1].abs()).max(x[2].abs()))
        .fold(0.0, f64::max);
    let fmt = |v: [f64; 3]| format!("[{:.1e}, {:.1e}, {:.1e}]", v[0], v[1], v[2]);
    eprintln!(
        "{kind}: force imbalance {}, moment imbalance {}, max free-node residual \
         {free_residual:.1e} (sum |f| = {fscale:.3e})",
        fmt(force),
        fmt(moment)
    );
    assert!(
        free_residual < 1e-10 * fscale,
        "{kind}: residual at free nodes {free_residual:e}"
    );
    for c in 0..dim {
        assert!(
            force[c].abs() < 1e-10 * fscale,
            "{kind}: force balance {c}: {:e}",
            force[c]
        );
    }
    let moment_comps: &[usize] = if dim == 2 { &[2] } else { &[0, 1, 2] };
    for &c in moment_comps {
        assert!(
            moment[c].abs() < 1e-10 * fscale * lscale,
            "{kind}: moment balance {c}: {:e}",
            moment[c]
        );
    }
    // Energy identity (homogeneous constraints: reactions do no work).
    let u_energy = strain_energy(model, &sol.u).unwrap();
    let work = 0.5 * total.f.iter().zip(&sol.u).map(|(f, u)| f * u).sum::<f64>();
    eprintln!("{kind}: strain energy {u_energy:.10e}, 1/2 f.u {work:.10e}");
    assert!(u_energy > 0.0);
    assert!(
        (u_energy - work).abs() < 1e-10 * work.abs(),
        "{kind}: strain energy {u_energy:e} vs 1/2 f.u {work:e}"
    );
}

#[test]
fn reactions_balance_loads_2d() {
    for kind in [
        CellType::Tri3,
        CellType::Tri6,
        CellType::Quad4,
        CellType::Quad8,
    ] {
        let mesh = generate::rectangle(4.0, 1.0, 8, 3, kind).unwrap();
        let model = model_of(mesh, Analysis::PlaneStress { thickness: 2.0 });
        let mut cons = Constraints::new();
        cons.clamp(&model.mesh, "xmin").unwrap();
        cons.fix_component(&model.mesh, "ymin", 1, 0.0).unwrap();
        let cases = loads_2d(&model);
        check_equilibrium(&model, &cons, cases);
    }
    // Plane strain, with the roller on ymin as a normal (skew-capable) constraint.
    let mesh = generate::rectangle(4.0, 1.0, 8, 3, CellType::Quad8).unwrap();
    let model = model_of(mesh, Analysis::PlaneStrain { thickness: 1.0 });
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    cons.fix_normal(&model.mesh, "ymin", 0.0).unwrap();
    let cases = loads_2d(&model);
    check_equilibrium(&model, &cons, cases);
}

#[test]
fn reactions_balance_loads_3d() {
    for kind in [CellType::Tet4, CellType::Tet10, CellType::Hex8] {
        let mesh = generate::box_mesh([2.0, 1.0, 1.0], [4, 2, 2], kind).unwrap();
        let model = model_of(mesh, Analysis::Solid);
        let mut cons = Constraints::new();
        cons.clamp(&model.mesh, "xmin").unwrap();
        cons.fix_normal(&model.mesh, "zmin", 0.0).unwrap();
        let cases = loads_3d(&model);
        check_equilibrium(&model, &cons, cases);
    }
}

/// Rotation by `deg` degrees about z.
fn rot(deg: f64) -> [[f64; 2]; 2] {
    let (c, s) = (deg.to_radians().cos(), deg.to_radians().sin());
    [[c, -s], [s, c]]
}

fn apply(r: &[[f64; 2]; 2], v: [f64; 3]) -> [f64; 3] {
    [
        r[0][0] * v[0] + r[0][1] * v[1],
        r[1][0] * v[0] + r[1][1] * v[1],
        v[2],
    ]
}

/// Solves the rectangle `[0, 2] x [0, 1]` rotated by `deg`, rollers on `xmin` and `ymin`
/// (normal constraints if rotated, component ones otherwise), traction on `xmax` given in the
/// body frame, body force in the body frame.
fn solve_rotated(kind: CellType, deg: f64, uniaxial: bool) -> (Model, Vec<f64>, Vec<[f64; 6]>) {
    let r = rot(deg);
    let rt = rot(-deg);
    let mut mesh = generate::rectangle(2.0, 1.0, 6, 3, kind).unwrap();
    for x in &mut mesh.coords {
        *x = apply(&r, *x);
    }
    let model = model_of(mesh, Analysis::PlaneStress { thickness: 1.0 });
    let mut cons = Constraints::new();
    if deg == 0.0 {
        cons.fix_component(&model.mesh, "xmin", 0, 0.0).unwrap();
        cons.fix_component(&model.mesh, "ymin", 1, 0.0).unwrap();
    } else {
        cons.fix_normal(&model.mesh, "xmin", 0.0).unwrap();
        cons.fix_normal(&model.mesh, "ymin", 0.0).unwrap();
    }
    let mut loads = Loads::new(&model);
    loads
        .traction(&model, "xmax", |x, _| {
            let xb = apply(&rt, x); // body-frame position
            let t = if uniaxial {
                [100.0, 0.0, 0.0]
            } else {
                [100.0 * (1.0 + xb[1]), 20.0 * xb[1], 0.0]
            };
            apply(&r, t)
        })
        .unwrap();
    if !uniaxial {
        loads
            .body_force(&model, None, |x, _| {
                let xb = apply(&rt, x);
                apply(&r, [5.0 * xb[1], -3.0 - xb[0], 0.0])
            })
            .unwrap();
    }
    let sol = solve_elastic(&model, &cons, &loads, Ordering::Metis).unwrap();
    let s = nodal_stresses(&model, &sol.u).unwrap();
    (model, sol.u, s)
}

#[test]
fn skew_constraints_are_rotation_invariant() {
    let deg = 30.0;
    let r = rot(deg);
    for kind in [CellType::Quad4, CellType::Quad8, CellType::Tri6] {
        for uniaxial in [true, false] {
            let (model0, u0, s0) = solve_rotated(kind, 0.0, uniaxial);
            let (_, u1, s1) = solve_rotated(kind, deg, uniaxial);
            let umax = u0.iter().map(|v| v.abs()).fold(0.0, f64::max);
            let smax = s0
                .iter()
                .flat_map(|s| s.iter())
                .map(|v| v.abs())
                .fold(0.0, f64::max);
            let (mut du, mut ds) = (0.0f64, 0.0f64);
            for n in 0..model0.mesh.num_nodes() {
                let ur = apply(&r, [u0[2 * n], u0[2 * n + 1], 0.0]);
                du = du.max((ur[0] - u1[2 * n]).abs().max((ur[1] - u1[2 * n + 1]).abs()));
                // sigma_rot = R sigma R^T (in-plane part).
                let [sxx, syy, _, _, _, sxy] = s0[n];
                let (c, s) = (r[0][0], r[1][0]);
                let rxx = c * c * sxx - 2.0 * c * s * sxy + s * s * syy;
                let ryy = s * s * sxx + 2.0 * c * s * sxy + c * c * syy;
                let rxy = c * s * (sxx - syy) + (c * c - s * s) * sxy;
                ds = ds.max(
                    (rxx - s1[n][0])
                        .abs()
                        .max((ryy - s1[n][1]).abs())
                        .max((rxy - s1[n][5]).abs()),
                );
                if uniaxial {
                    // Closed form: sigma = 100 e e with e = (cos 30, sin 30).
                    let want = [100.0 * c * c, 100.0 * s * s, 100.0 * c * s];
                    let got = [s1[n][0], s1[n][1], s1[n][5]];
                    for k in 0..3 {
                        assert!(
                            (got[k] - want[k]).abs() < 1e-9 * 100.0,
                            "{kind}: uniaxial stress {got:?} vs {want:?}"
                        );
                    }
                    // Von Mises of a uniaxial state is its magnitude, whatever the direction.
                    let vm = von_mises(&s1[n]);
                    assert!((vm - 100.0).abs() < 1e-9 * 100.0, "{kind}: von Mises {vm}");
                }
            }
            eprintln!(
                "{kind} uniaxial={uniaxial}: rotated vs aligned, max |du| {:.1e} |u|, max |ds| \
                 {:.1e} |s|",
                du / umax,
                ds / smax
            );
            assert!(du < 1e-9 * umax, "{kind}: displacement not rotated: {du:e}");
            assert!(ds < 1e-9 * smax, "{kind}: stress not rotated: {ds:e}");
        }
    }
}

#[test]
fn prescribed_normal_displacement_on_rotated_sides() {
    // [0, 2] x [0, 1] rotated by 30 degrees, rollers (u . n = 0) on xmin and ymin, and
    // u . n = d imposed on xmax: uniaxial stress s = E d / L along e = (cos 30, sin 30), exact
    // displacement u = R (d x / L, -nu d y / L) in body coordinates, reaction on xmax
    // = s * height * thickness along e, purely normal at every node.
    let (l, hgt, t, d) = (2.0, 1.0, 1.5, 1e-3);
    let r = rot(30.0);
    let rt = rot(-30.0);
    for kind in [CellType::Quad4, CellType::Quad8, CellType::Tri6] {
        let mut mesh = generate::rectangle(l, hgt, 6, 3, kind).unwrap();
        for x in &mut mesh.coords {
            *x = apply(&r, *x);
        }
        let model = model_of(mesh, Analysis::PlaneStress { thickness: t });
        let mut cons = Constraints::new();
        cons.fix_normal(&model.mesh, "xmin", 0.0).unwrap();
        cons.fix_normal(&model.mesh, "ymin", 0.0).unwrap();
        cons.fix_normal(&model.mesh, "xmax", d).unwrap();
        let sol = solve_elastic(&model, &cons, &Loads::new(&model), Ordering::Metis).unwrap();
        let s0 = E * d / l;
        let e = [r[0][0], r[1][0]];
        for (n, x) in model.mesh.coords.iter().enumerate() {
            let xb = apply(&rt, *x);
            let ue = apply(&r, [d * xb[0] / l, -NU * d * xb[1] / l, 0.0]);
            for c in 0..2 {
                assert!(
                    (sol.u[2 * n + c] - ue[c]).abs() < 1e-12,
                    "{kind}: u at {xb:?} = {:?}, exact {ue:?}",
                    &sol.u[2 * n..2 * n + 2]
                );
            }
        }
        let sig = nodal_stresses(&model, &sol.u).unwrap();
        for s in &sig {
            let want = [s0 * e[0] * e[0], s0 * e[1] * e[1], s0 * e[0] * e[1]];
            for (k, w) in [s[0], s[1], s[5]].iter().zip(want) {
                assert!(
                    (k - w).abs() < 1e-9 * s0,
                    "{kind}: stress {s:?}, want {want:?}"
                );
            }
        }
        let mut total = [0.0; 2];
        for n in model.mesh.group_nodes("xmax").unwrap() {
            let (rx, ry) = (sol.reactions[2 * n], sol.reactions[2 * n + 1]);
            // Tangential part of each nodal reaction vanishes.
            assert!((-rx * e[1] + ry * e[0]).abs() < 1e-9 * s0 * hgt * t);
            total[0] += rx;
            total[1] += ry;
        }
        let want = s0 * hgt * t;
        eprintln!("{kind}: reaction on xmax {total:?}, closed form {want} along {e:?}");
        assert!((total[0] - want * e[0]).abs() < 1e-10 * want);
        assert!((total[1] - want * e[1]).abs() < 1e-10 * want);
    }
}

#[test]
fn per_group_materials_bar_in_series() {
    // [0, 3] x [0, 1] with E1 on x < 1 and E2 = 4 E1 on x > 1, nu = 0 (no lateral coupling, so
    // the uniaxial state is exact): traction s0 on xmax, rollers on xmin and ymin. Exact:
    // s_xx = s0, u_x = s0 x / E1 for x <= 1, s0 (1 / E1 + (x - 1) / E2) beyond, u_y = 0.
    let (e1, e2, s0) = (1000.0, 4000.0, 10.0);
    for kind in [CellType::Tri3, CellType::Quad8, CellType::Tri6] {
        let mut mesh = generate::rectangle(3.0, 1.0, 6, 2, kind).unwrap();
        let left: Vec<usize> = (0..mesh.num_cells())
            .filter(|&c| {
                let nodes = mesh.cell_nodes(c);
                nodes.iter().map(|&n| mesh.coords[n][0]).sum::<f64>() / (nodes.len() as f64) < 1.0
            })
            .collect();
        mesh.add_cells_to_group("soft", left);
        let mut model = Model::new(mesh, Analysis::PlaneStress { thickness: 1.0 }).unwrap();
        model.set_material_all(Material::new(e2, 0.0, 0.0).unwrap());
        model
            .set_material("soft", Material::new(e1, 0.0, 0.0).unwrap())
            .unwrap();
        let mut cons = Constraints::new();
        cons.fix_component(&model.mesh, "xmin", 0, 0.0).unwrap();
        cons.fix_component(&model.mesh, "ymin", 1, 0.0).unwrap();
        let mut loads = Loads::new(&model);
        loads
            .traction(&model, "xmax", |_, _| [s0, 0.0, 0.0])
            .unwrap();
        let sol = solve_elastic(&model, &cons, &loads, Ordering::Metis).unwrap();
        for (n, x) in model.mesh.coords.iter().enumerate() {
            let ux = if x[0] <= 1.0 {
                s0 * x[0] / e1
            } else {
                s0 * (1.0 / e1 + (x[0] - 1.0) / e2)
            };
            assert!((sol.u[2 * n] - ux).abs() < 1e-12, "{kind}: u_x at {x:?}");
            assert!(sol.u[2 * n + 1].abs() < 1e-12, "{kind}: u_y at {x:?}");
        }
        for s in nodal_stresses(&model, &sol.u).unwrap() {
            assert!((s[0] - s0).abs() < 1e-10 * s0 && s[1].abs() < 1e-10 * s0);
        }
    }
}

#[test]
fn scaling_young_scales_displacements() {
    // Linear elasticity: u is proportional to 1 / E for given loads (Model::scale_young, used
    // when E is an uncertain parameter); the reactions do not change.
    let mesh = generate::rectangle(3.0, 1.0, 6, 2, CellType::Quad8).unwrap();
    let mut model = model_of(mesh, Analysis::PlaneStress { thickness: 1.0 });
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&model);
    loads.pressure(&model, "ymax", 2.0).unwrap();
    let u1 = solve_elastic(&model, &cons, &loads, Ordering::Amd).unwrap();
    model.scale_young(2.5);
    let u2 = solve_elastic(&model, &cons, &loads, Ordering::Amd).unwrap();
    let umax = u1.u.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for (a, b) in u1.u.iter().zip(&u2.u) {
        assert!((a - 2.5 * b).abs() < 1e-12 * umax);
    }
    let rmax = u1.reactions.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for (a, b) in u1.reactions.iter().zip(&u2.reactions) {
        assert!((a - b).abs() < 1e-10 * rmax);
    }
}

fn small_model() -> Model {
    let mesh = generate::rectangle(2.0, 1.0, 4, 2, CellType::Quad4).unwrap();
    model_of(mesh, Analysis::PlaneStrain { thickness: 1.0 })
}

#[test]
fn invalid_materials_are_errors() {
    for (e, nu, rho) in [
        (0.0, 0.3, 0.0),
        (-1.0, 0.3, 0.0),
        (f64::NAN, 0.3, 0.0),
        (1.0, 0.5, 0.0),
        (1.0, 0.7, 0.0),
        (1.0, -1.0, 0.0),
        (1.0, 0.3, -1.0),
    ] {
        match Material::new(e, nu, rho) {
            Err(FemError::InvalidMaterial(msg)) => eprintln!("E={e}, nu={nu}, rho={rho}: {msg}"),
            other => panic!("E={e}, nu={nu}, rho={rho} accepted: {other:?}"),
        }
    }
}

#[test]
fn unknown_groups_are_named_in_errors() {
    let mut model = small_model();
    let mesh = model.mesh.clone();
    let name = "no_such_group";
    let check = |what: &str, r: Result<(), FemError>| {
        let err = r.expect_err(what);
        let msg = err.to_string();
        assert!(
            msg.contains(name),
            "{what}: message '{msg}' does not name the group"
        );
        eprintln!("{what}: {msg}");
    };
    check(
        "fix_component",
        Constraints::new()
            .fix_component(&mesh, name, 0, 0.0)
            .map(|_| ()),
    );
    check(
        "fix_normal",
        Constraints::new().fix_normal(&mesh, name, 0.0).map(|_| ()),
    );
    check("clamp", Constraints::new().clamp(&mesh, name).map(|_| ()));
    let mut loads = Loads::new(&model);
    check(
        "traction",
        loads.traction(&model, name, |_, _| [1.0; 3]).map(|_| ()),
    );
    check("pressure", loads.pressure(&model, name, 1.0).map(|_| ()));
    check(
        "nodal_force",
        loads.nodal_force(&model, name, [1.0; 3]).map(|_| ()),
    );
    check(
        "body_force",
        loads
            .body_force(&model, Some(name), |_, _| [1.0; 3])
            .map(|_| ()),
    );
    check(
        "set_material",
        model
            .set_material(name, Material::new(1.0, 0.2, 0.0).unwrap())
            .map(|_| ()),
    );
}

#[test]
fn floating_bodies_are_not_positive_definite() {
    let model = small_model();
    let mut loads = Loads::new(&model);
    loads.pressure(&model, "xmax", 1.0).unwrap();
    // Nothing held, then only u_x on xmin (y translation free), then u_x on xmin and u_y at
    // one node (rotation blocked too: solvable, the control case).
    let none = Constraints::new();
    let mut partial = Constraints::new();
    partial.fix_component(&model.mesh, "xmin", 0, 0.0).unwrap();
    for (what, cons) in [("no constraint", &none), ("u_x on xmin only", &partial)] {
        match solve_elastic(&model, cons, &loads, Ordering::Metis) {
            Err(FemError::NotPositiveDefinite) => {}
            other => panic!(
                "{what}: expected NotPositiveDefinite, got {:?}",
                other.map(|s| s.u.len())
            ),
        }
        match solve_elastic(&model, cons, &loads, Ordering::Amd) {
            Err(FemError::NotPositiveDefinite) => {}
            other => panic!(
                "{what} (AMD): expected NotPositiveDefinite, got {:?}",
                other.map(|s| s.u.len())
            ),
        }
    }
    let mut ok = partial.clone();
    ok.fix_direction(0, [0.0, 1.0, 0.0], 0.0);
    assert!(solve_elastic(&model, &ok, &loads, Ordering::Metis).is_ok());

    // Larger meshes: round-off in the singular pivot grows with the size.
    let mesh = generate::rectangle(2.0, 1.0, 80, 40, CellType::Quad8).unwrap();
    let model = model_of(mesh, Analysis::PlaneStress { thickness: 1.0 });
    let mut cons = Constraints::new();
    cons.fix_component(&model.mesh, "xmin", 0, 0.0).unwrap();
    let loads = Loads::new(&model);
    assert!(matches!(
        solve_elastic(&model, &cons, &loads, Ordering::Metis),
        Err(FemError::NotPositiveDefinite)
    ));
    // 3D: x and y held on zmin, z free (one translation left).
    let mesh = generate::box_mesh([1.0; 3], [10, 10, 10], CellType::Hex8).unwrap();
    let model = model_of(mesh, Analysis::Solid);
    let mut cons = Constraints::new();
    cons.fix_component(&model.mesh, "zmin", 0, 0.0).unwrap();
    cons.fix_component(&model.mesh, "zmin", 1, 0.0).unwrap();
    let loads = Loads::new(&model);
    assert!(matches!(
        solve_elastic(&model, &cons, &loads, Ordering::Amd),
        Err(FemError::NotPositiveDefinite)
    ));
    // No false alarm on a legitimately ill-conditioned model: a 200:1 cantilever, with a
    // material 1000 times stiffer in one half (smallest pivot ratio 3e-10).
    let mesh = generate::rectangle(200.0, 1.0, 400, 2, CellType::Quad4).unwrap();
    let mut model = model_of(mesh, Analysis::PlaneStress { thickness: 1.0 });
    let cells: Vec<usize> = (0..model.mesh.num_cells())
        .filter(|&c| model.mesh.coords[model.mesh.cell_nodes(c)[0]][0] >= 100.0)
        .collect();
    model.mesh.add_cells_to_group("stiff", cells);
    model
        .set_material("stiff", Material::new(E * 1e3, NU, 0.0).unwrap())
        .unwrap();
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&model);
    loads
        .traction(&model, "xmax", |_, _| [0.0, 1.0, 0.0])
        .unwrap();
    assert!(solve_elastic(&model, &cons, &loads, Ordering::Metis).is_ok());
}

#[test]
fn conflicting_constraints_are_errors() {
    let model = small_model();
    let loads = Loads::new(&model);
    // Same component, two values.
    let mut cons = Constraints::new();
    cons.fix_component(&model.mesh, "xmin", 0, 0.0).unwrap();
    cons.fix_component(&model.mesh, "xmin", 0, 1e-3).unwrap();
    match solve_elastic(&model, &cons, &loads, Ordering::Metis) {
        Err(e @ FemError::ConflictingConstraints { .. }) => eprintln!("{e}"),
        other => panic!(
            "expected ConflictingConstraints, got {:?}",
            other.map(|s| s.u.len())
        ),
    }
    // A skew direction implied by two component constraints, with another value.
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    cons.fix_direction(0, [1.0, 1.0, 0.0], 0.5);
    match solve_elastic(&model, &cons, &loads, Ordering::Metis) {
        Err(e @ FemError::ConflictingConstraints { .. }) => eprintln!("{e}"),
        other => panic!(
            "expected ConflictingConstraints, got {:?}",
            other.map(|s| s.u.len())
        ),
    }
    // The same constraint twice, or a consistent redundant one, is fine.
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    cons.clamp(&model.mesh, "xmin").unwrap();
    cons.fix_direction(0, [1.0, 1.0, 0.0], 0.0);
    assert!(solve_elastic(&model, &cons, &loads, Ordering::Metis).is_ok());
}

#[test]
fn setup_errors_are_errors() {
    // Component 2 in 2D.
    let model = small_model();
    assert!(matches!(
        Constraints::new().fix_component(&model.mesh, "xmin", 2, 0.0),
        Err(FemError::Setup(_))
    ));
    // 2D mesh with a 3D analysis and the reverse; zero thickness.
    let mesh2 = generate::rectangle(1.0, 1.0, 2, 2, CellType::Tri3).unwrap();
    let mesh3 = generate::box_mesh([1.0; 3], [1, 1, 1], CellType::Hex8).unwrap();
    assert!(matches!(
        Model::new(mesh2.clone(), Analysis::Solid),
        Err(FemError::Setup(_))
    ));
    assert!(matches!(
        Model::new(mesh3, Analysis::PlaneStress { thickness: 1.0 }),
        Err(FemError::Setup(_))
    ));
    assert!(matches!(
        Model::new(mesh2.clone(), Analysis::PlaneStress { thickness: 0.0 }),
        Err(FemError::Setup(_))
    ));
    // No material assigned.
    let bare = Model::new(mesh2, Analysis::PlaneStress { thickness: 1.0 }).unwrap();
    let mut cons = Constraints::new();
    cons.clamp(&bare.mesh, "xmin").unwrap();
    assert!(matches!(
        solve_elastic(&bare, &cons, &Loads::new(&bare), Ordering::Metis),
        Err(FemError::Setup(_))
    ));
    // Zero rotation axis.
    let mut loads = Loads::new(&model);
    assert!(
        loads
            .centrifugal(&model, None, 1.0, [0.0; 3], [0.0; 3])
            .is_err()
    );
}

#[test]
fn inverted_cells_are_bad_jacobians() {
    // Mirroring x -> -x turns every cell clockwise.
    let mut mesh = generate::rectangle(2.0, 1.0, 4, 2, CellType::Quad8).unwrap();
    for x in &mut mesh.coords {
        x[0] = -x[0];
    }
    let model = model_of(mesh, Analysis::PlaneStress { thickness: 1.0 });
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    match solve_elastic(&model, &cons, &Loads::new(&model), Ordering::Metis) {
        Err(e @ FemError::BadJacobian { .. }) => eprintln!("{e}"),
        other => panic!("expected BadJacobian, got {:?}", other.map(|s| s.u.len())),
    }
}
