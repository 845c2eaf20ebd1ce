//! Bad input gives typed errors, not panics.

use alea_cre::{CreError, CreOptions, LoadData, estimate_domain};
use alea_fem::{Analysis, Constraints, Material, Model};
use alea_mesh::{CellType, generate};

fn model(kind: CellType) -> Model {
    let mesh = generate::rectangle(1.0, 1.0, 2, 2, kind).unwrap();
    let mut m = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
    m.set_material_all(Material::new(1.0, 0.3, 0.0).unwrap());
    m
}

#[test]
fn typed_errors() {
    let m = model(CellType::Quad4);
    let mut c = Constraints::new();
    c.clamp(&m.mesh, "xmin").unwrap();
    let u = vec![0.0; 2 * m.mesh.num_nodes()];
    let opts = CreOptions::default();
    // Wrong displacement length.
    let r = estimate_domain(&m, &c, &LoadData::new(), &u[1..], &opts);
    assert!(matches!(r, Err(CreError::Invalid(_))), "{r:?}");
    // Non-finite displacement.
    let mut bad = u.clone();
    bad[3] = f64::NAN;
    let r = estimate_domain(&m, &c, &LoadData::new(), &bad, &opts);
    assert!(matches!(r, Err(CreError::Invalid(_))));
    // Unknown traction group.
    let data = LoadData::new().traction("nope", |_, _| [1.0, 0.0, 0.0]);
    let r = estimate_domain(&m, &c, &data, &u, &opts);
    assert!(matches!(r, Err(CreError::Mesh(_))), "{r:?}");
    // Bad options.
    let r = estimate_domain(
        &m,
        &c,
        &LoadData::new(),
        &u,
        &CreOptions {
            extra_degree: 0,
            ..Default::default()
        },
    );
    assert!(matches!(r, Err(CreError::Invalid(_))));
    // Model without material.
    let mesh = generate::rectangle(1.0, 1.0, 2, 2, CellType::Quad4).unwrap();
    let nm = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
    let r = estimate_domain(&nm, &c, &LoadData::new(), &u, &opts);
    assert!(matches!(r, Err(CreError::Fem(_))), "{r:?}");
    // A curved quadratic edge is supported in 2D (tests/curved.rs): zero displacement, no
    // load, zero estimate.
    let mut cm = model(CellType::Tri6);
    let f = cm.mesh.facet_group("ymin").unwrap()[0].clone();
    cm.mesh.coords[f.nodes[2]][1] -= 0.05;
    let cu = vec![0.0; 2 * cm.mesh.num_nodes()];
    let r = estimate_domain(&cm, &Constraints::new(), &LoadData::new(), &cu, &opts).unwrap();
    assert_eq!(r.theta, 0.0);
    // 3D: zero displacement and no load give a zero estimate; a displacement of the wrong
    // length and a curved Tet10 edge are typed errors.
    let bm = generate::box_mesh([1.0; 3], [1, 1, 1], CellType::Hex8).unwrap();
    let mut m3 = Model::new(bm, Analysis::Solid).unwrap();
    m3.set_material_all(Material::new(1.0, 0.3, 0.0).unwrap());
    let u3 = vec![0.0; 3 * m3.mesh.num_nodes()];
    let r = estimate_domain(&m3, &Constraints::new(), &LoadData::new(), &u3, &opts).unwrap();
    assert_eq!(r.theta, 0.0);
    let r = estimate_domain(&m3, &Constraints::new(), &LoadData::new(), &u3[1..], &opts);
    assert!(matches!(r, Err(CreError::Invalid(_))), "{r:?}");
    let tm = generate::box_mesh([1.0; 3], [1, 1, 1], CellType::Tet10).unwrap();
    let mut t3 = Model::new(tm, Analysis::Solid).unwrap();
    t3.set_material_all(Material::new(1.0, 0.3, 0.0).unwrap());
    let mid = t3.mesh.cell_nodes(0)[4];
    t3.mesh.coords[mid][2] += 0.05;
    let ut = vec![0.0; 3 * t3.mesh.num_nodes()];
    let r = estimate_domain(&t3, &Constraints::new(), &LoadData::new(), &ut, &opts);
    assert!(
        matches!(r, Err(CreError::Invalid(ref m)) if m.contains("curved")),
        "{r:?}"
    );
    // Zero displacement, no load: zero estimate.
    let r = estimate_domain(&m, &c, &LoadData::new(), &u, &opts).unwrap();
    assert_eq!(r.theta, 0.0);
}
