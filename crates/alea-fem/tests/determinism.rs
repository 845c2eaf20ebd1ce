//! Concurrent set-ups give bit-identical factorisations. METIS keeps its random state in
//! process globals, so orderings computed on several threads at once used to interleave it and
//! change the ordering (hence the rounding of every later solve) from run to run; the solver
//! serialises METIS calls. Reproducibility of whole studies whatever the thread count rests
//! on this.

use alea_fem::{
    Analysis, Cholesky, Constraints, DofMap, Material, Model, Ordering, assemble_stiffness,
};
use alea_mesh::{CellType, generate};
use rayon::prelude::*;

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn factorisations_on_concurrent_threads_are_bit_identical() {
    let mesh = generate::rectangle(3.0, 1.0, 90, 30, CellType::Quad4).unwrap();
    let mut model = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
    model.set_material_all(Material::new(210e3, 0.3, 0.0).unwrap());
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    let dofs = DofMap::for_mesh(&model.mesh, &cons).unwrap();
    let k = assemble_stiffness(&model, &dofs).unwrap().k;
    let blocks = dofs.node_of_dof();
    let solve = || {
        let mut chol = Cholesky::new(&k, Ordering::Metis, Some(&blocks)).unwrap();
        chol.factorize(&k).unwrap();
        let mut b: Vec<f64> = (0..k.n).map(|i| (i as f64 * 0.37).sin()).collect();
        chol.solve_in_place(&mut b);
        bits(&b)
    };
    let reference = solve();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap();
    for _ in 0..3 {
        let all: Vec<Vec<u64>> = pool.install(|| (0..8).into_par_iter().map(|_| solve()).collect());
        for (i, r) in all.iter().enumerate() {
            assert!(
                r == &reference,
                "concurrent factorisation {i} differs from the sequential one"
            );
        }
    }
}
