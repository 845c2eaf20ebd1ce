//! Small fixtures shared by the LATIN tests.
#![allow(dead_code)]

pub mod contact;
pub mod contact3d;

use alea_fem::{Analysis, Constraints, Loads, Material, Model};
use alea_latin::Substructure;
use alea_mesh::{CellType, Mesh, generate};

/// Structured rectangle `[x0, x0 + lx] x [y0, y0 + ly]`.
pub fn rect(x0: f64, y0: f64, lx: f64, ly: f64, nx: usize, ny: usize, kind: CellType) -> Mesh {
    let mut m = generate::rectangle(lx, ly, nx, ny, kind).unwrap();
    for x in m.coords.iter_mut() {
        x[0] += x0;
        x[1] += y0;
    }
    m
}

/// A plane-strain model with one material.
pub fn model(mesh: Mesh, young: f64, poisson: f64) -> Model {
    let mut m = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
    m.set_material_all(Material::new(young, poisson, 0.0).unwrap());
    m
}

/// A substructure with no load cases.
pub fn sub(name: &str, model: Model, constraints: Constraints) -> Substructure {
    Substructure {
        name: name.into(),
        model,
        constraints,
        load_cases: vec![],
    }
}

/// Adds one load case from a closure on the model.
pub fn with_load(mut s: Substructure, f: impl FnOnce(&Model, &mut Loads)) -> Substructure {
    let mut l = Loads::new(&s.model);
    f(&s.model, &mut l);
    s.load_cases.push(l.f);
    s
}

/// Energy norm squared `u^T K u` of a displacement on a model (via internal forces).
pub fn energy(model: &Model, u: &[f64]) -> f64 {
    let f = alea_fem::post::internal_forces(model, u).unwrap();
    f.iter().zip(u).map(|(a, b)| a * b).sum()
}

/// Displacement of `reference` (on `ref_mesh`) at the nodes of `mesh`, matched by position.
pub fn restrict(ref_mesh: &Mesh, reference: &[f64], mesh: &Mesh) -> Vec<f64> {
    let d = mesh.dim;
    let mut out = vec![0.0; mesh.num_nodes() * d];
    for (n, x) in mesh.coords.iter().enumerate() {
        let m = (0..ref_mesh.num_nodes())
            .min_by(|&a, &b| {
                let da: f64 = (0..3).map(|k| (ref_mesh.coords[a][k] - x[k]).powi(2)).sum();
                let db: f64 = (0..3).map(|k| (ref_mesh.coords[b][k] - x[k]).powi(2)).sum();
                da.total_cmp(&db)
            })
            .unwrap();
        let dist: f64 = (0..3)
            .map(|k| (ref_mesh.coords[m][k] - x[k]).powi(2))
            .sum::<f64>();
        assert!(dist.sqrt() < 1e-9, "node {n} has no reference partner");
        out[n * d..n * d + d].copy_from_slice(&reference[m * d..m * d + d]);
    }
    out
}

/// Structured box `[x0, x0 + l] ` (per direction) of `Hex8`, `Tet4` or `Tet10` cells.
pub fn cuboid(x0: [f64; 3], l: [f64; 3], n: [usize; 3], kind: CellType) -> Mesh {
    let mut m = generate::box_mesh(l, n, kind).unwrap();
    for x in m.coords.iter_mut() {
        for d in 0..3 {
            x[d] += x0[d];
        }
    }
    m
}

/// A 3D solid model with one material.
pub fn solid(mesh: Mesh, young: f64, poisson: f64) -> Model {
    let mut m = Model::new(mesh, Analysis::Solid).unwrap();
    m.set_material_all(Material::new(young, poisson, 0.0).unwrap());
    m
}
