//! A Young's modulus varying from cell to cell (`RunInput::cell_young`): the run is solved on
//! operators assembled and factorised for it, and must give the single-domain finite-element
//! solution of the same heterogeneous material (2 x 2 substructures joined by perfect
//! interfaces, as `tests/perfect.rs`), while the set-up's own factorisations keep serving
//! homogeneous runs; uniform cell factors `c` are the substructure factor `c`; a batch with such
//! runs gives each run's own result.

mod common;

use std::sync::Arc;

use alea_fem::{Constraints, Loads, Model, Ordering, solve_elastic};
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus};
use alea_mesh::CellType;
use common::*;

const E: f64 = 210e3;

fn traction(x: [f64; 3], _n: [f64; 3]) -> [f64; 3] {
    [50.0 + 10.0 * x[1], 20.0, 0.0]
}

/// A modulus factor varying by a factor 4 over the plate, smooth in x and y.
fn factor(x: [f64; 3]) -> f64 {
    1.0 + 0.6 * (2.0 * x[0]).sin() * (3.0 * x[1]).cos() + 0.4 * x[0] * x[1]
}

fn centroid(m: &Model, c: usize) -> [f64; 3] {
    let xs = m.cell_coords(c);
    let n = xs.len() as f64;
    let mut p = [0.0; 3];
    for x in &xs {
        for k in 0..3 {
            p[k] += x[k] / n;
        }
    }
    p
}

fn cell_factors(m: &Model) -> Vec<f64> {
    (0..m.mesh.num_cells())
        .map(|c| factor(centroid(m, c)))
        .collect()
}

fn assembly(n: usize) -> Assembly {
    let mut subs = Vec::new();
    for (i, j) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        let m = model(
            rect(i as f64, 0.5 * j as f64, 1.0, 0.5, n, n, CellType::Quad4),
            E,
            0.3,
        );
        let mut c = Constraints::new();
        if i == 0 {
            c.clamp(&m.mesh, "xmin").unwrap();
        }
        subs.push(with_load(sub(&format!("S{i}{j}"), m, c), |m, l| {
            if i == 1 {
                l.traction(m, "xmax", traction).unwrap();
            }
        }));
    }
    let interfaces = vec![
        InterfaceSpec::perfect("S00-S10", 0, "xmax", 1, "xmin"),
        InterfaceSpec::perfect("S01-S11", 2, "xmax", 3, "xmin"),
        InterfaceSpec::perfect("S00-S01", 0, "ymax", 2, "ymin"),
        InterfaceSpec::perfect("S10-S11", 1, "ymax", 3, "ymin"),
    ];
    Assembly { subs, interfaces }
}

/// Relative energy-norm distance of the run's displacements to the single-domain solution of
/// `whole` (energy in the run's own materials).
fn distance(solver: &LatinSolver, res: &alea_latin::RunResult, whole: &Model, u: &[f64]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for s in 0..4 {
        let m = res.scaled_model(solver.model(s), s);
        let uref = restrict(&whole.mesh, u, &m.mesh);
        let diff: Vec<f64> = res.displacements[s]
            .iter()
            .zip(&uref)
            .map(|(a, b)| a - b)
            .collect();
        num += energy(&m, &diff);
        den += energy(&m, &uref);
    }
    (num / den).sqrt()
}

fn reference(n: usize, heterogeneous: bool) -> (Model, Vec<f64>) {
    let mut whole = model(
        rect(0.0, 0.0, 2.0, 1.0, 2 * n, 2 * n, CellType::Quad4),
        E,
        0.3,
    );
    if heterogeneous {
        let f = cell_factors(&whole);
        whole.scale_young_per_cell(&f).unwrap();
    }
    let mut cons = Constraints::new();
    cons.clamp(&whole.mesh, "xmin").unwrap();
    let mut loads = Loads::new(&whole);
    loads.traction(&whole, "xmax", traction).unwrap();
    let sol = solve_elastic(&whole, &cons, &loads, Ordering::Metis).unwrap();
    (whole, sol.u)
}

#[test]
fn a_cell_varying_modulus_gives_the_single_domain_solution() {
    let n = 6;
    let opts = LatinOptions {
        tolerance: 1e-11,
        max_iterations: 20000,
        ..Default::default()
    };
    let solver = LatinSolver::new(assembly(n), opts).unwrap();
    let cell_young: Vec<Option<Arc<Vec<f64>>>> = (0..4)
        .map(|s| Some(Arc::new(cell_factors(solver.model(s)))))
        .collect();
    let input = RunInput {
        cell_young: cell_young.clone(),
        ..Default::default()
    };
    let res = solver.run_shared(&input).unwrap();
    assert_eq!(res.status, RunStatus::Converged);
    let (whole, u) = reference(n, true);
    let rel = distance(&solver, &res, &whole, &u);
    let (homog, uh) = reference(n, false);
    let rel_homog = distance(&solver, &res, &homog, &uh);
    eprintln!(
        "heterogeneous: {} iterations, relative energy distance {rel:e} (to the homogeneous solution: {rel_homog:e})",
        res.iterations
    );
    assert!(rel < 1e-8, "{rel:e}");
    // The heterogeneity matters: the homogeneous answer is far.
    assert!(rel_homog > 1e-2, "{rel_homog:e}");
    // The set-up's operators are untouched: a homogeneous run is the homogeneous solution.
    let plain = solver.run_shared(&RunInput::default()).unwrap();
    let rel_plain = distance(&solver, &plain, &homog, &uh);
    assert!(rel_plain < 1e-8, "{rel_plain:e}");
    // Multiresolution: a run with cell factors starts from the state it is given (here its own
    // answer) and converges faster from it.
    let first = solver.run_shared(&input).unwrap();
    let located = RunInput {
        initial: Some(std::sync::Arc::new(first.end_state())),
        ..input.clone()
    };
    let again = solver.run_shared(&located).unwrap();
    assert!(
        again.iterations < first.iterations,
        "{} vs {}",
        again.iterations,
        first.iterations
    );
    // A batch holding the heterogeneous run gives it its own result.
    let batch = solver.run_batch(&[RunInput::default(), input.clone()]);
    let b = batch[1].as_ref().unwrap();
    assert_eq!(b.displacements, res.displacements);
    assert_eq!(b.cell_young.len(), 4);
}

#[test]
fn uniform_cell_factors_are_the_substructure_factor() {
    let n = 4;
    let opts = LatinOptions {
        tolerance: 1e-11,
        max_iterations: 20000,
        ..Default::default()
    };
    let solver = LatinSolver::new(assembly(n), opts).unwrap();
    let c = 1.7;
    let by_cells = RunInput {
        cell_young: (0..4)
            .map(|s| Some(Arc::new(vec![c; solver.model(s).mesh.num_cells()])))
            .collect(),
        ..Default::default()
    };
    let by_factor = RunInput {
        young_factors: vec![c; 4],
        ..Default::default()
    };
    let a = solver.run_shared(&by_cells).unwrap();
    let b = solver.run_shared(&by_factor).unwrap();
    let (mut num, mut den) = (0.0f64, 0.0f64);
    for s in 0..4 {
        for (x, y) in a.displacements[s].iter().zip(&b.displacements[s]) {
            num = num.max((x - y).abs());
            den = den.max(y.abs());
        }
        let m = a.scaled_model(solver.model(s), s);
        assert!((m.material(0).unwrap().young - c * E).abs() < 1e-9 * E);
    }
    assert!(num < 1e-8 * den, "{num:e} vs {den:e}");
}

#[test]
fn bad_cell_factors_are_refused() {
    let solver = LatinSolver::new(assembly(2), LatinOptions::default()).unwrap();
    for bad in [vec![1.0; 3], vec![-1.0; 4], vec![f64::NAN; 4]] {
        let input = RunInput {
            cell_young: vec![Some(Arc::new(bad.clone()))],
            ..Default::default()
        };
        assert!(solver.run_shared(&input).is_err(), "{bad:?}");
    }
}
