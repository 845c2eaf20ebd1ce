//! A factor stored in single precision with iterative refinement (module `single` of
//! alea-fem): against the double-precision solve of the same matrix.
//!
//! Reference: Higham, *Accuracy and Stability of Numerical Algorithms* (2002), ch. 12:
//! mixed-precision refinement with an `f32` factor and `f64` residuals converges when
//! `c eps_32 kappa(A) < 1`, each step contracting the error by about that factor, to the accuracy
//! of the `f64` solve. Exact statements used:
//! * the refined solve equals the `f64` solve to 1e-11 relative (a well-conditioned 3D Hex8
//!   cantilever, clamped, Young 210 000 MPa, and a slender one);
//! * one step from a nearby `x_prev` has error at most `10 rate |x* - x_prev|`, `rate` the
//!   contraction measured when the factor was stored (asserted below 1e-2);
//! * refactorising a single-precision factor gives a double-precision one again;
//! * an ill-conditioned matrix (`kappa` ~ 1e9: a cantilever tied by a spring of 1e-6 of its
//!   stiffness) stays in double precision;
//! * the factor's memory halves (plus the 12 bytes an entry of the kept matrix).
//!
//! ```text
//!   A: Hex8 box [0, L] x [0, 1] x [0, 1], clamped at x = 0, traction (100, 10, 0) at x = L
//! ```

use alea_fem::{
    Analysis, Cholesky, Constraints, DofMap, FactorKind, Loads, Material, Model, Ordering, SymCsc,
    assemble_stiffness,
};
use alea_mesh::{CellType, generate};

fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
    let den: f64 = b.iter().map(|y| y * y).sum();
    (num / den).sqrt()
}

/// Stiffness and load of a clamped Hex8 box of length `len` with `cells` cells.
fn cantilever(len: f64, cells: [usize; 3]) -> (SymCsc, Vec<f64>, Vec<usize>) {
    let mesh = generate::box_mesh([len, 1.0, 1.0], cells, CellType::Hex8).unwrap();
    let mut model = Model::new(mesh, Analysis::Solid).unwrap();
    model.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    let dofs = DofMap::for_mesh(&model.mesh, &cons).unwrap();
    let asm = assemble_stiffness(&model, &dofs).unwrap();
    let mut loads = Loads::new(&model);
    loads
        .traction(&model, "xmax", |_, _| [100.0, 10.0, 0.0])
        .unwrap();
    (asm.k, dofs.reduce(&loads.f), dofs.node_of_dof())
}

fn factor(a: &SymCsc, blocks: &[usize]) -> Cholesky {
    let mut c =
        Cholesky::with_kind(a, Ordering::Metis, Some(blocks), FactorKind::Supernodal).unwrap();
    c.factorize(a).unwrap();
    c
}

#[test]
fn refined_solves_match_double_precision() {
    for (len, cells) in [(1.0, [8, 8, 8]), (8.0, [32, 4, 4])] {
        let (a, b, blocks) = cantilever(len, cells);
        let n = a.n;
        let double = factor(&a, &blocks);
        let mut single = factor(&a, &blocks);
        let bytes_double = single.factor_bytes();
        assert!(
            single.store_single(&a),
            "length {len}: kept in double precision"
        );
        assert!(single.is_single());
        let rate = single.refinement_rate().unwrap();
        eprintln!("length {len}: n {n}, refinement rate {rate:.1e}");
        assert!(rate < 1e-2, "rate {rate:e}");
        // Half the factor, plus the matrix (12 bytes an entry).
        let expected = bytes_double / 2 + 12 * a.nnz() + 4 * (n + 1);
        assert_eq!(single.factor_bytes(), expected);
        assert_eq!(single.nnz_factor(), double.nnz_factor());

        // Three columns: the load, the load times 2 and a body-force-like vector.
        let third: Vec<f64> = (0..n).map(|i| ((i % 17) as f64 - 8.0) * 1e-3).collect();
        let block: Vec<f64> = b
            .iter()
            .copied()
            .chain(b.iter().map(|v| 2.0 * v))
            .chain(third)
            .collect();
        let mut x64 = block.clone();
        double.solve_with(&mut x64, &mut double.solve_scratch(3));
        let mut x32 = block.clone();
        single.solve_with(&mut x32, &mut single.solve_scratch(3));
        for c in 0..3 {
            let d = rel_diff(&x32[c * n..(c + 1) * n], &x64[c * n..(c + 1) * n]);
            assert!(d < 1e-11, "length {len}, column {c}: {d:e}");
        }

        // One step from a nearby solution: error at most 10 rate |x* - x_prev|.
        let exact = &x64[..n];
        let previous: Vec<f64> = exact
            .iter()
            .enumerate()
            .map(|(i, v)| v * (1.0 + 1e-3 * ((i % 7) as f64 - 3.0)))
            .collect();
        let mut near = b.clone();
        single.solve_near(&mut near, &[&previous], &mut single.solve_scratch(1));
        let before = rel_diff(&previous, exact);
        let after = rel_diff(&near, exact);
        eprintln!("  one step: {before:.1e} -> {after:.1e}");
        assert!(after <= 10.0 * rate * before, "{before:e} -> {after:e}");
        assert!(after < 1e-2 * before);
        // In double precision, solve_near is the plain solve.
        let mut one = b.clone();
        double.solve_with(&mut one, &mut double.solve_scratch(1));
        let mut plain = b.clone();
        double.solve_near(&mut plain, &[&previous], &mut double.solve_scratch(1));
        assert_eq!(plain, one);

        // Refactorising gives double precision again, the same solve.
        single.factorize(&a).unwrap();
        assert!(!single.is_single());
        let mut again = b.clone();
        single.solve_in_place(&mut again);
        assert_eq!(again, one);
        assert_eq!(single.same_pattern().nnz_factor(), double.nnz_factor());
    }
}

#[test]
fn ill_conditioned_matrix_stays_in_double_precision() {
    // A free box tied to the ground by springs of 1e-6 of its stiffness on every dof of its
    // first node layer: kappa ~ 1e9, beyond the f32 factor (eps_32 kappa ~ 60).
    let mesh = generate::box_mesh([4.0, 1.0, 1.0], [16, 4, 4], CellType::Hex8).unwrap();
    let mut model = Model::new(mesh, Analysis::Solid).unwrap();
    model.set_material_all(Material::new(210e3, 0.3, 7.85e-9).unwrap());
    let dofs = DofMap::for_mesh(&model.mesh, &Constraints::new()).unwrap();
    let mut a = assemble_stiffness(&model, &dofs).unwrap().k;
    let scale = a.diagonal().iter().fold(0.0f64, |m, v| m.max(*v));
    for j in 0..a.n {
        a.add(j, j, 1e-9 * scale);
    }
    let blocks = dofs.node_of_dof();
    let mut c = factor(&a, &blocks);
    assert!(!c.store_single(&a));
    assert!(!c.is_single());
    assert_eq!(c.refinement_rate(), None);
    // Still the double-precision solve.
    let b: Vec<f64> = (0..a.n).map(|i| ((i % 5) as f64 - 2.0) * 1e-3).collect();
    let mut x = b.clone();
    c.solve_in_place(&mut x);
    let mut ax = vec![0.0; a.n];
    a.mul_vec(&x, &mut ax);
    assert!(rel_diff(&ax, &b) < 1e-6);
}
