//! The FE-only energy samples (`FeEnergySampler`, the normalisation of a study estimate whose
//! substructures carry no admissible stress): `|y(sigma_h)|^2 / alpha = u^T K(alpha) u = 2 x` the
//! strain energy of `alea_fem::post::strain_energy` (an independent evaluation through the
//! material's stress), for 3D (Hex8, Tet4, Tet10, distorted) and 2D (Quad4, Quad8) cells and a
//! Young's modulus scaled by `alpha`; a rigid motion has zero samples; the samples agree with
//! the 2D `EnergySampler`'s FE samples in energy on affine cells; wrong sizes are refused.

mod common;

use alea_cre::{CreOptions, EnergySampler, FeEnergySampler};
use alea_fem::{Analysis, Model};
use alea_mesh::CellType;

fn field(x: [f64; 3], dim: usize) -> Vec<f64> {
    let v = [
        (1.3 * x[0] + 0.4 * x[1]).sin() + 0.2 * x[2] * x[2],
        (0.7 * x[1] - 0.5 * x[2]).cos() * x[0],
        x[0] * x[1] * x[2] + 0.1 * (2.0 * x[0]).sin(),
    ];
    v[..dim].to_vec()
}

fn check(reference: &Model) {
    let dim = reference.mesh.dim;
    let sampler = FeEnergySampler::new(reference).unwrap();
    let u: Vec<f64> = reference
        .mesh
        .coords
        .iter()
        .flat_map(|x| field(*x, dim))
        .collect();
    let alpha = 1.7;
    let mut scaled = reference.clone();
    scaled.scale_young(alpha);
    let y = sampler.fe_stress(reference, &u, alpha).unwrap();
    assert_eq!(y.len(), sampler.len());
    assert_eq!(sampler.cell_offsets().len(), reference.mesh.num_cells() + 1);
    let energy: f64 = y.iter().map(|v| v * v).sum::<f64>() / alpha;
    let exact = 2.0 * alea_fem::post::strain_energy(&scaled, &u).unwrap();
    assert!(
        (energy - exact).abs() < 1e-12 * exact,
        "{:?}: {energy} vs {exact}",
        reference.mesh.cell_types_present()
    );
    // A rigid motion (translation + small rotation field, linear) has no stress.
    let rigid: Vec<f64> = reference
        .mesh
        .coords
        .iter()
        .flat_map(|x| {
            let w = [0.3, -0.2, 0.5];
            let r = [
                w[1] * x[2] - w[2] * x[1],
                w[2] * x[0] - w[0] * x[2],
                w[0] * x[1] - w[1] * x[0],
            ];
            let v = [1.0 + r[0], -2.0 + r[1], 0.5 + r[2]];
            if dim == 2 {
                vec![1.0 - 0.4 * x[1], -2.0 + 0.4 * x[0]]
            } else {
                v.to_vec()
            }
        })
        .collect();
    let z = sampler.fe_stress(reference, &rigid, alpha).unwrap();
    let scale = y.iter().map(|v| v.abs()).fold(0.0, f64::max);
    assert!(z.iter().all(|v| v.abs() < 1e-12 * scale.max(1.0)));
    assert!(sampler.fe_stress(reference, &u[1..], alpha).is_err());
}

#[test]
fn samples_reproduce_the_fe_energy_in_3d() {
    for kind in [CellType::Hex8, CellType::Tet4, CellType::Tet10] {
        let mut m = Model::new(common::solid::cube(3, kind, 0.1), Analysis::Solid).unwrap();
        m.set_material_all(alea_fem::Material::new(1000.0, 0.3, 0.0).unwrap());
        check(&m);
    }
}

#[test]
fn samples_reproduce_the_fe_energy_in_2d_as_the_eet_sampler() {
    let analysis = Analysis::PlaneStrain { thickness: 2.0 };
    for kind in [CellType::Quad4, CellType::Quad8] {
        let m = common::model(common::square(4, kind, 0.2), analysis);
        check(&m);
        // The EET sampler's FE samples (a finer rule) give the same energy on affine cells,
        // where both rules integrate the polynomial energy density exactly.
        let m = common::model(common::square(4, kind, 0.0), analysis);
        let u: Vec<f64> = m.mesh.coords.iter().flat_map(|x| field(*x, 2)).collect();
        let eet = EnergySampler::new(&m, &CreOptions::default()).unwrap();
        let fe = FeEnergySampler::new(&m).unwrap();
        let e1: f64 = eet.fe_stress(&m, &u, 1.0).iter().map(|v| v * v).sum();
        let e2: f64 = fe
            .fe_stress(&m, &u, 1.0)
            .unwrap()
            .iter()
            .map(|v| v * v)
            .sum();
        assert!((e1 - e2).abs() < 1e-10 * e1, "{kind}: {e1} vs {e2}");
    }
}
