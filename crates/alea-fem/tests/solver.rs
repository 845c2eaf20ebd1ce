//! Sparse Cholesky solver: ordering independence, refactorisation, multiple right-hand sides.
//!
//! Reference: George & Liu, *Computer Solution of Large Sparse Positive Definite Systems* (1981),
//! ch. 1-2: a symmetric permutation changes the fill of `L` but not the solution of `A x = b`;
//! the numeric factorisation can be redone on the same symbolic structure with new values.
//! Exact statements used: `x` is the same for METIS, AMD and the identity ordering (relative
//! 1e-10, the system's condition number times round-off); factorising `2 A` on the same pattern
//! gives `x / 2`; solving two right-hand sides at once gives the two single solves; the
//! residual `|A x - b| / |b|` is at round-off.
//!
//! ```text
//!   A: plane-stress Q8 stiffness of [0, 3] x [0, 1], 12 x 4 cells, xmin clamped
//!   b: a traction on xmax, and a body force
//! ```

use alea_fem::{
    Analysis, Cholesky, Constraints, DofMap, Loads, Material, Model, Ordering, assemble_stiffness,
};
use alea_mesh::{CellType, generate};

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    (num / den).sqrt()
}

#[test]
fn orderings_refactorisation_and_multiple_rhs() {
    let mesh = generate::rectangle(3.0, 1.0, 12, 4, CellType::Quad8).unwrap();
    let mut model = Model::new(mesh, Analysis::PlaneStress { thickness: 1.0 }).unwrap();
    model.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    let dofs = DofMap::for_mesh(&model.mesh, &cons).unwrap();
    let asm = assemble_stiffness(&model, &dofs).unwrap();
    let mut l1 = Loads::new(&model);
    l1.traction(&model, "xmax", |x, _| [10.0, 5.0 * x[1], 0.0])
        .unwrap();
    let mut l2 = Loads::new(&model);
    l2.body_force(&model, None, |x, _| [0.0, -1.0 - x[0], 0.0])
        .unwrap();
    let (b1, b2) = (dofs.reduce(&l1.f), dofs.reduce(&l2.f));
    let blocks = dofs.node_of_dof();

    let mut reference: Option<Vec<f64>> = None;
    for ordering in [Ordering::Identity, Ordering::Amd, Ordering::Metis] {
        let mut chol = Cholesky::new(&asm.k, ordering, Some(&blocks)).unwrap();
        chol.factorize(&asm.k).unwrap();
        let mut x = b1.clone();
        chol.solve_in_place(&mut x);
        let mut ax = vec![0.0; x.len()];
        asm.k.mul_vec(&x, &mut ax);
        let res = rel_diff(&ax, &b1);
        eprintln!(
            "{ordering:?}: nnz(L) = {}, residual {res:.1e}",
            chol.nnz_factor()
        );
        assert!(res < 1e-10, "{ordering:?}: residual {res:e}");
        match &reference {
            None => reference = Some(x.clone()),
            Some(r) => {
                let d = rel_diff(&x, r);
                assert!(
                    d < 1e-10,
                    "{ordering:?} differs from the identity ordering by {d:e}"
                );
            }
        }

        // Two right-hand sides at once (column-major n x 2).
        let n = b1.len();
        let mut xx = [b1.clone(), b2.clone()].concat();
        chol.solve_in_place(&mut xx);
        let mut x2 = b2.clone();
        chol.solve_in_place(&mut x2);
        assert!(rel_diff(&xx[..n], &x) < 1e-14);
        assert!(rel_diff(&xx[n..], &x2) < 1e-14);

        // Refactorisation with new values on the same pattern: 2 A x' = b gives x' = x / 2.
        let mut k2 = asm.k.clone();
        for v in &mut k2.values {
            *v *= 2.0;
        }
        chol.factorize(&k2).unwrap();
        let mut xh = b1.clone();
        chol.solve_in_place(&mut xh);
        let half: Vec<f64> = x.iter().map(|v| 0.5 * v).collect();
        assert!(
            rel_diff(&xh, &half) < 1e-12,
            "{ordering:?}: refactorisation"
        );
    }
}

#[test]
fn failed_factorisation_then_good_one() {
    // A singular matrix must be reported, and the same solver must then factorise a good matrix
    // on the same pattern.
    let mesh = generate::rectangle(2.0, 1.0, 4, 2, CellType::Quad4).unwrap();
    let mut model = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
    model.set_material_all(Material::new(1.0, 0.25, 0.0).unwrap());
    let dofs = DofMap::for_mesh(&model.mesh, &Constraints::new()).unwrap();
    let asm = assemble_stiffness(&model, &dofs).unwrap();
    let mut chol = Cholesky::new(&asm.k, Ordering::Metis, Some(&dofs.node_of_dof())).unwrap();
    assert!(chol.factorize(&asm.k).is_err(), "floating body factorised");
    // Add a spring to ground at every dof: K + I is positive definite.
    let mut k = asm.k.clone();
    for j in 0..k.n {
        let p = k.col_ptr[j + 1] - 1; // diagonal: last entry of an upper-triangular column
        assert_eq!(k.row_idx[p], j);
        k.values[p] += 1.0;
    }
    chol.factorize(&k).unwrap();
    let mut x = vec![1.0; k.n];
    chol.solve_in_place(&mut x);
    let mut ax = vec![0.0; k.n];
    k.mul_vec(&x, &mut ax);
    assert!(rel_diff(&ax, &vec![1.0; k.n]) < 1e-12);
}
