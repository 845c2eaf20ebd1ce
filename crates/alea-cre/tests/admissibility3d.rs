//! Statical admissibility of the 3D EET stress field (the 3D counterpart of
//! `admissibility.rs`).
//!
//! Problem with polynomial data on the unit cube (clamped on `x = 0`, quadratic body force,
//! quadratic traction on `x = 1`, linear on `z = 1`, mildly distorted 3 x 3 x 3 meshes), so
//! that every phase-1 integral is exact:
//! - phase 1: every element is in equilibrium under its face densities and body force (force
//!   and moment resultants vanish to round-off, (3.20)), the node systems are compatible;
//! - phase 2 on the EET problem: the mismatch between `sigma_hat n` and the phase-1 densities
//!   decreases with the degree `p + 1 ... p + 4`, and `theta` converges in the degree;
//! - phase 2 on a single element whose exact local solution is a polynomial (tractions and body
//!   force of a quadratic displacement): `sigma_hat` is exact to round-off, so `theta_E =
//!   ||sigma(u_ex) - sigma_h||`;
//! - interface sides: the face densities reproduce given nodal forces exactly.

mod common;

use std::sync::Arc;

use alea_cre::solid::phase1::{FaceDensity, FaceTractions};
use alea_cre::solid::phase2::{SolidRules, element};
use alea_cre::solid::sides::interface_densities;
use alea_cre::solid::topology::{FaceTopology, face_mass};
use alea_cre::{CreOptions, DomainEstimate, LoadData, SideForces, estimate_domain};
use alea_fem::{
    Analysis, Constraints, Loads, Material, Model, Ordering, Quadrature, solve_elastic,
};
use alea_mesh::{CellType, Mesh};
use common::solid::cube;

fn body(x: [f64; 3]) -> [f64; 3] {
    [
        100.0 * (1.0 + x[0] * x[1]),
        100.0 * (x[0] * x[0] - x[2]),
        50.0 * x[1] * x[2],
    ]
}

fn right(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    [50.0 * (1.0 - x[1] * x[1]), 30.0 * x[2], -20.0 * x[1] * x[2]]
}

fn top(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    [10.0 * x[1], 0.0, -40.0 * x[0]]
}

fn model(mesh: Mesh) -> Model {
    let mut m = Model::new(mesh, Analysis::Solid).unwrap();
    m.set_material_all(Material::new(1000.0, 0.3, 0.0).unwrap());
    m
}

/// The 3 x 3 x 3 test mesh: Tet4 with randomly moved interior nodes; Hex8 and Tet10 graded
/// per direction (`x -> x (1 + x) / 2`, ...) and sheared, so that every face stays planar (the
/// area element of a warped bilinear face is not polynomial, and no rule integrates it
/// exactly: on a randomly distorted Hex8 mesh the balance below is 1e-8, not round-off) and
/// Tet10 edges straight (mid nodes put back at the middle).
fn mesh(kind: CellType) -> Mesh {
    if kind == CellType::Tet4 {
        return cube(3, kind, 0.1);
    }
    let mut m = cube(3, kind, 0.0);
    for x in m.coords.iter_mut() {
        let g = [0, 1, 2].map(|d| x[d] * (1.0 + x[d]) / 2.0);
        *x = [g[0] + 0.2 * g[1], g[1] + 0.1 * g[2], g[2] - 0.15 * g[0]];
    }
    if kind == CellType::Tet10 {
        let mut mids = Vec::new();
        for (_, _, nodes) in m.cells() {
            for (a, b, c) in [
                (0, 1, 4),
                (1, 2, 5),
                (2, 0, 6),
                (0, 3, 7),
                (1, 3, 8),
                (2, 3, 9),
            ] {
                mids.push((nodes[a], nodes[b], nodes[c]));
            }
        }
        for (a, b, c) in mids {
            let (xa, xb) = (m.coords[a], m.coords[b]);
            m.coords[c] = [0, 1, 2].map(|d| 0.5 * (xa[d] + xb[d]));
        }
    }
    m
}

fn setup(kind: CellType, extra: usize) -> (Model, DomainEstimate) {
    let m = model(mesh(kind));
    let mut c = Constraints::new();
    c.clamp(&m.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&m);
    loads.body_force(&m, None, |x, _| body(x)).unwrap();
    loads.traction(&m, "xmax", right).unwrap();
    loads.traction(&m, "zmax", top).unwrap();
    let sol = solve_elastic(&m, &c, &loads, Ordering::Metis).unwrap();
    let data = LoadData::new()
        .body(body)
        .traction("xmax", right)
        .traction("zmax", top);
    let opts = CreOptions {
        extra_degree: extra,
        ..Default::default()
    };
    let est = estimate_domain(&m, &c, &data, &sol.u, &opts).unwrap();
    (m, est)
}

/// Phase-1 element balance: max over elements of |resultant| / sum |contributions|.
fn phase1_balance(m: &Model, tr: &FaceTractions) -> f64 {
    let mut worst: f64 = 0.0;
    for c in 0..m.mesh.num_cells() {
        let kind = m.mesh.cell_type(c);
        let coords = m.cell_coords(c);
        let (mut r, mut abs) = ([0.0; 6], 0.0);
        let mut add = |w: f64, x: [f64; 3], f: [f64; 3]| {
            for k in 0..3 {
                r[k] += w * f[k];
            }
            r[3] += w * (x[1] * f[2] - x[2] * f[1]);
            r[4] += w * (x[2] * f[0] - x[0] * f[2]);
            r[5] += w * (x[0] * f[1] - x[1] * f[0]);
            abs += w.abs() * (f[0].abs() + f[1].abs() + f[2].abs());
        };
        let q = Quadrature::for_cell(kind, 6);
        for (xi, wq) in q.points.iter().zip(&q.weights) {
            let g = alea_fem::kinematics::point_geometry(kind, &coords, *xi);
            add(wq * g.det, g.x, body(g.x));
        }
        for &(f, eta) in &tr.topo.cell_faces[c] {
            let face = &tr.topo.faces[f];
            let fq = Quadrature::for_cell(face.kind, 8);
            for (rs, wq) in fq.points.iter().zip(&fq.weights) {
                let g = face.geometry(&m.mesh, *rs);
                let t = tr.traction(f, &g.n[..face.nodes.len()], g.x, g.normal);
                add(eta * wq * g.jac, g.x, t);
            }
        }
        worst = worst.max(r.iter().map(|v| v.abs()).sum::<f64>() / abs);
    }
    worst
}

/// Relative L2 mismatch between `sigma_hat n` and the densities over all element faces.
fn traction_mismatch(m: &Model, est: &DomainEstimate) -> f64 {
    let tr = est.face_tractions().unwrap();
    let st = est.solid_stresses().unwrap();
    let (mut mis, mut tot) = (0.0, 0.0);
    for c in 0..m.mesh.num_cells() {
        for &(f, eta) in &tr.topo.cell_faces[c] {
            let face = &tr.topo.faces[f];
            let fq = Quadrature::for_cell(face.kind, 8);
            for (rs, wq) in fq.points.iter().zip(&fq.weights) {
                let g = face.geometry(&m.mesh, *rs);
                let t = tr.traction(f, &g.n[..face.nodes.len()], g.x, g.normal);
                let s = st[c].stress(g.x);
                let n = g.normal.map(|v| eta * v);
                let sn = [
                    s[0] * n[0] + s[5] * n[1] + s[4] * n[2],
                    s[5] * n[0] + s[1] * n[1] + s[3] * n[2],
                    s[4] * n[0] + s[3] * n[1] + s[2] * n[2],
                ];
                for k in 0..3 {
                    mis += wq * g.jac * (sn[k] - eta * t[k]).powi(2);
                    tot += wq * g.jac * t[k] * t[k];
                }
            }
        }
    }
    (mis / tot).sqrt()
}

fn check(kind: CellType) {
    let (mut mism, mut thetas) = (Vec::new(), Vec::new());
    for extra in 1..=4 {
        let (m, est) = setup(kind, extra);
        let bal = phase1_balance(&m, est.face_tractions().unwrap());
        let mis = traction_mismatch(&m, &est);
        println!(
            "{kind} p+{extra}: phase-1 balance {bal:.1e}, compatibility {:.1e}, traction mismatch {mis:.3e}, theta {:.5e}",
            est.compatibility_defect, est.theta
        );
        assert!(bal < 1e-11, "phase-1 element balance {bal}");
        assert!(est.compatibility_defect < 1e-12);
        // Polynomial data: phase 2 integrates the loads exactly too.
        assert!(est.balance_defect < 1e-11, "{}", est.balance_defect);
        mism.push(mis);
        thetas.push(est.theta);
    }
    // The local Neumann problems have edge and corner singularities, so sigma_hat n -> F_hat
    // only slowly in the degree (for Tet10 the first step is flat: 0.3105 -> 0.3105).
    for w in mism.windows(2) {
        assert!(
            w[1] < 1.001 * w[0],
            "traction mismatch increasing: {mism:?}"
        );
    }
    assert!(mism[3] < 0.8 * mism[0], "{mism:?}");
    for w in thetas.windows(2) {
        assert!(w[1] > w[0], "{thetas:?}");
    }
    println!(
        "{kind}: theta(p+3) / theta(p+4) = {:.4}",
        thetas[2] / thetas[3]
    );
    assert!(thetas[2] > 0.9 * thetas[3], "{thetas:?}");
}

#[test]
fn hex8_equilibrium_and_convergence_in_the_degree() {
    check(CellType::Hex8);
}

#[test]
fn tet4_equilibrium_and_convergence_in_the_degree() {
    check(CellType::Tet4);
}

#[test]
fn tet10_equilibrium_and_convergence_in_the_degree() {
    check(CellType::Tet10);
}

/// A single element whose exact local solution is in the phase-2 space: tractions and body
/// force of the quadratic displacement `u_ex`.
fn exact_local(kind: CellType) {
    let (lam, mu) = Material::new(1000.0, 0.3, 0.0).unwrap().lame();
    // u = (x^2 + 2yz - y^2, 3xy - z^2 + xz, y^2 / 2 + xz - 2 xy).
    let grad = |x: [f64; 3]| -> [[f64; 3]; 3] {
        let (a, b, c) = (x[0], x[1], x[2]);
        [
            [2.0 * a, 2.0 * c - 2.0 * b, 2.0 * b],
            [3.0 * b + c, 3.0 * a, -2.0 * c + a],
            [c - 2.0 * b, b - 2.0 * a, a],
        ]
    };
    let stress = move |x: [f64; 3]| -> [[f64; 3]; 3] {
        let g = grad(x);
        let tr = g[0][0] + g[1][1] + g[2][2];
        let mut s = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                s[i][j] = mu * (g[i][j] + g[j][i]);
            }
            s[i][i] += lam * tr;
        }
        s
    };
    // Second derivatives are constant: div u = 2x + 3x + x = 6x, grad div u = (6, 0, 0);
    // lap u = (2 - 2, -2, 1).
    let f = [-(lam + mu) * 6.0, 2.0 * mu, -mu];
    let mut mesh = Mesh::new(3);
    let corners: Vec<[f64; 3]> = match kind {
        CellType::Hex8 => vec![
            // A frustum: planar faces, not a parallelepiped.
            [0.0, 0.0, 0.0],
            [1.2, 0.0, 0.0],
            [1.2, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.2, 0.1, 0.9],
            [0.9, 0.1, 0.9],
            [0.9, 0.8, 0.9],
            [0.2, 0.8, 0.9],
        ],
        _ => vec![
            [0.1, 0.2, 0.0],
            [1.3, 0.4, 0.1],
            [0.5, 1.1, -0.1],
            [0.4, 0.5, 1.2],
        ],
    };
    let mut pts = corners.clone();
    if kind == CellType::Tet10 {
        for (a, b) in [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)] {
            pts.push([0, 1, 2].map(|d| 0.5 * (corners[a][d] + corners[b][d])));
        }
    }
    let ids: Vec<usize> = pts.iter().map(|&p| mesh.add_node(p)).collect();
    mesh.add_cell(kind, &ids);
    let m = model(mesh);
    let topo = FaceTopology::new(&m.mesh).unwrap();
    let density = topo
        .faces
        .iter()
        .map(|face| {
            // sigma(u_ex) n is linear on a planar face: the face's shape functions carry it.
            let g = face.geometry(&m.mesh, [0.25, 0.25, 0.0]);
            FaceDensity {
                values: face
                    .nodes
                    .iter()
                    .map(|&nd| {
                        let s = stress(m.mesh.coords[nd]);
                        [0, 1, 2].map(|i| (0..3).map(|j| s[i][j] * g.normal[j]).sum())
                    })
                    .collect(),
                data: vec![],
            }
        })
        .collect();
    let tr = FaceTractions {
        topo,
        density,
        fields: vec![],
        compatibility_defect: 0.0,
    };
    let bf: alea_cre::VectorField = Arc::new(move |_| f);
    // An arbitrary FE displacement.
    let u: Vec<f64> = (0..3 * pts.len())
        .map(|i| 1e-3 * ((i as f64) * 0.7).sin())
        .collect();
    let r = element(
        &m,
        0,
        &u,
        Some(&bf),
        &tr,
        &SolidRules::new(2 + kind.order(), kind.order()),
    )
    .unwrap();
    assert!(r.balance_defect < 1e-12, "{}", r.balance_defect);
    // sigma_hat = sigma(u_ex) and div sigma_hat + f = 0 at sample points; theta_E by quadrature.
    let kindq = Quadrature::for_cell(kind, 6);
    let coords = m.cell_coords(0);
    let scale = 1000.0;
    let mut theta2 = 0.0;
    for (xi, w) in kindq.points.iter().zip(&kindq.weights) {
        let g = alea_fem::kinematics::point_geometry(kind, &coords, *xi);
        let sh = r.stress.stress(g.x);
        let se = stress(g.x);
        let want = [se[0][0], se[1][1], se[2][2], se[1][2], se[0][2], se[0][1]];
        for k in 0..6 {
            assert!(
                (sh[k] - want[k]).abs() < 1e-9 * scale,
                "{kind}: sigma_hat {sh:?} vs {want:?}"
            );
        }
        let d = r.stress.divergence(g.x);
        for k in 0..3 {
            assert!((d[k] + f[k]).abs() < 1e-8 * scale, "div {d:?} vs {f:?}");
        }
        // sigma_h of the arbitrary displacement.
        let s_h = alea_fem::post::stress_at(&m, 0, &u, *xi).unwrap();
        let ds: Vec<f64> = (0..6).map(|k| want[k] - s_h[k]).collect();
        // Complementary energy density with the isotropic compliance.
        let e = 1000.0;
        let nu = 0.3;
        let tr3 = ds[0] + ds[1] + ds[2];
        let dev: f64 = ds[0] * ds[0] + ds[1] * ds[1] + ds[2] * ds[2];
        let shear: f64 = ds[3] * ds[3] + ds[4] * ds[4] + ds[5] * ds[5];
        theta2 +=
            w * g.det * (((1.0 + nu) * dev - nu * tr3 * tr3) / e + 2.0 * (1.0 + nu) / e * shear);
    }
    let theta = theta2.sqrt();
    let te = r.theta2.sqrt();
    assert!(
        (te - theta).abs() < 1e-8 * theta,
        "{kind}: theta_E {te} vs {theta}"
    );
}

#[test]
fn exact_local_solution_is_reproduced() {
    for kind in [CellType::Tet4, CellType::Hex8, CellType::Tet10] {
        exact_local(kind);
    }
}

#[test]
fn interface_densities_reproduce_the_nodal_forces() {
    for kind in [CellType::Hex8, CellType::Tet4, CellType::Tet10] {
        let m = model(cube(2, kind, 0.0));
        let topo = FaceTopology::new(&m.mesh).unwrap();
        let nodes = m.mesh.group_nodes("zmin").unwrap();
        let forces: Vec<[f64; 3]> = nodes
            .iter()
            .map(|&n| {
                let t = n as f64;
                [(0.3 * t).sin(), (0.7 * t).cos(), 1.0 + 0.1 * t]
            })
            .collect();
        let side = SideForces {
            group: "zmin".into(),
            nodes: nodes.clone(),
            forces: forces.clone(),
            reference: None,
            face_reference: None,
        };
        // Arbitrary targets: the split changes, the nodal forces must not.
        let b_bar: Vec<Vec<[f64; 3]>> = topo
            .faces
            .iter()
            .enumerate()
            .map(|(f, face)| {
                (0..face.nodes.len())
                    .map(|a| {
                        let t = (f * 7 + a) as f64;
                        [t.sin(), (2.0 * t).cos(), 0.5 * t.sin()]
                    })
                    .collect()
            })
            .collect();
        let dens = interface_densities(&m.mesh, &topo, &side, &b_bar, None).unwrap();
        let mut got = vec![[0.0; 3]; m.mesh.num_nodes()];
        for (f, v) in &dens {
            let face = &topo.faces[*f];
            let nn = face.nodes.len();
            let mm = face_mass(&m.mesh, face);
            for a in 0..nn {
                for c in 0..3 {
                    got[face.nodes[a]][c] += (0..nn).map(|b| mm[a * nn + b] * v[b][c]).sum::<f64>();
                }
            }
        }
        for (i, &n) in nodes.iter().enumerate() {
            for c in 0..3 {
                assert!(
                    (got[n][c] - forces[i][c]).abs() < 1e-12,
                    "{kind} node {n}: {:?} vs {:?}",
                    got[n],
                    forces[i]
                );
            }
        }
    }
}
