//! The multiresolution estimator (`LatinEstimator`: run-independent matrices cached) gives the
//! direct path's estimate (`estimate_latin_direct`: every matrix rebuilt from the run's scaled
//! models) to round-off:
//!
//! - a frictional contact run (block pressed and sheared on a plane, distorted Q4 meshes,
//!   stick and slip zones), the context reused for a second run with other Young's factors and
//!   a load factor;
//! - a 2 x 1 assembly with a perfect interface (distorted Q8 and T6 meshes: quadratic edges, a
//!   non-zero FE energy outside the local spaces), an affine body force (constant +
//!   centrifugal-like gradient) and a traction in one load case, run with Young's factors
//!   [1.7, 0.6] and load factor 1.35: the context with the body force given as an
//!   `AffineBody` (cached moments) and as a general closure (quadrature), estimates of other
//!   runs in between, against the direct path.
//!
//! The context's estimate is bit-identical with 1 and 2 threads.
//!
//! Compared: theta, relative error, energy norm, per-substructure theta, every element's
//! `theta_E`, every phase-2 coefficient and the admissible stress at every cell node, every edge
//! density, the compatibility defects and the interface terms. Round-off is amplified by the
//! condition numbers of the local problems (measured up to 5e7 for the degree-5 problems of
//! distorted T6 cells, 1e4 for Q8, 1e3 for Q4): measured, every `theta_E` agrees within 1e-13
//! of itself on the Q4 and Q8 cells and 6e-12 on the T6 cells, the coefficients within 2e-9 and
//! the nodal stresses within 2e-10 on the T6 cells (1e-12 elsewhere). The balance defects are defined with other quadratures of the absolute
//! loads (a normalisation) and are only checked to be small in both.

mod common;

use alea_cre::{
    AffineBody, CreOptions, CreResult, LatinEstimator, LoadData, estimate_latin,
    estimate_latin_direct,
};
use alea_fem::{Analysis, Constraints, Loads, Model};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunResult, RunStatus,
    Substructure,
};
use alea_mesh::CellType;
use common::*;

const PS: Analysis = Analysis::PlaneStrain { thickness: 1.0 };

/// Largest absolute difference of two slices relative to the largest magnitude of `b`.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

fn assert_same(ctx: &CreResult, direct: &CreResult, asm: &Assembly, what: &str) {
    let close = |a: f64, b: f64, tol: f64, name: &str| {
        assert!(
            (a - b).abs() <= tol * b.abs().max(f64::MIN_POSITIVE),
            "{what}: {name} {a:e} vs direct {b:e}"
        );
    };
    close(ctx.theta, direct.theta, 1e-10, "theta");
    close(ctx.relative, direct.relative, 1e-10, "relative");
    close(ctx.energy_norm, direct.energy_norm, 1e-12, "energy norm");
    for (s, (a, b)) in ctx
        .substructures
        .iter()
        .zip(&direct.substructures)
        .enumerate()
    {
        close(
            a.theta,
            b.theta,
            1e-10,
            &format!("theta of substructure {s}"),
        );
        let d_theta = a
            .element_theta
            .iter()
            .zip(&b.element_theta)
            .fold(0.0f64, |m, (x, y)| {
                m.max((x - y).abs() / y.max(f64::MIN_POSITIVE))
            });
        assert!(
            d_theta < 1e-9,
            "{what}: element theta of {s} differ by {d_theta:e} (relative to each)"
        );
        let (sa, sb) = (a.plane_stresses().unwrap(), b.plane_stresses().unwrap());
        let (mut worst_c, mut worst_s) = (0.0f64, 0.0f64);
        for (c, (x, y)) in sa.iter().zip(sb).enumerate() {
            // The coefficients of the degree-(p + 3) bases amplify round-off by the local
            // problems' condition numbers (up to 5e7 for the degree-5 problems of the
            // distorted T6 cells: coefficients within ~2e-9, stresses within ~1e-10 there,
            // ~1e-12 on the other cells).
            let d = rel_diff(&x.coeffs, &y.coeffs);
            worst_c = worst_c.max(d);
            assert!(
                d < 1e-7,
                "{what}: coefficients of cell {c} of {s} differ by {d:e}"
            );
            let nodes = asm.subs[s].model.cell_coords(c);
            let sx: Vec<f64> = nodes.iter().flat_map(|p| x.stress(*p)).collect();
            let sy: Vec<f64> = nodes.iter().flat_map(|p| y.stress(*p)).collect();
            let d = rel_diff(&sx, &sy);
            worst_s = worst_s.max(d);
            assert!(
                d < 1e-9,
                "{what}: stresses of cell {c} of {s} differ by {d:e}"
            );
            let dh = rel_diff(x.hooke.as_flattened(), y.hooke.as_flattened());
            assert!(dh < 1e-14, "{what}: Hooke matrix of cell {c}");
        }
        println!(
            "  {what}, substructure {s}: theta_E within {d_theta:.1e}, coefficients within {worst_c:.1e}, stresses within {worst_s:.1e}"
        );
        let (ta, tb) = (a.edge_tractions().unwrap(), b.edge_tractions().unwrap());
        let flat = |t: &alea_cre::eet::phase1::EdgeTractions| -> Vec<f64> {
            t.density
                .iter()
                .flat_map(|d| d.lin.as_flattened().to_vec())
                .collect()
        };
        let d = rel_diff(&flat(ta), &flat(tb));
        assert!(d < 1e-9, "{what}: edge densities of {s} differ by {d:e}");
        assert!(
            (a.compatibility_defect - b.compatibility_defect).abs() < 1e-9,
            "{what}: compatibility defects {} and {}",
            a.compatibility_defect,
            b.compatibility_defect
        );
        assert!(a.balance_defect < 1e-6 && b.balance_defect < 1e-6);
    }
    for (a, b) in ctx.interfaces.iter().zip(&direct.interfaces) {
        assert_eq!(a.term, b.term, "{what}: interface term");
        assert_eq!(a.violations, b.violations);
    }
}

fn solve(solver: &LatinSolver, input: &RunInput) -> RunResult {
    let r = solver.run_shared(input).unwrap();
    assert_eq!(r.status, RunStatus::Converged);
    r
}

/// Block (floating, side 2) on a clamped plane (side 1), distorted Q4 meshes of `2 x 1`.
fn contact_problem(n: usize) -> (Assembly, impl Fn(f64) -> Vec<LoadData>) {
    let part = |y0: f64| {
        let mut mesh = square(n, CellType::Quad4, 0.2);
        for x in mesh.coords.iter_mut() {
            x[0] *= 2.0;
            x[1] += y0;
        }
        model(mesh, PS)
    };
    let top = |x: [f64; 3], _: [f64; 3]| [2.0, -10.0 * (0.5 + 0.5 * x[0]), 0.0];
    let plane = part(-1.0);
    let mut c = Constraints::new();
    c.clamp(&plane.mesh, "ymin").unwrap();
    let block = part(0.0);
    let mut loads = Loads::new(&block);
    loads.traction(&block, "ymax", top).unwrap();
    let asm = Assembly {
        subs: vec![
            Substructure {
                name: "plane".into(),
                model: plane,
                constraints: c,
                load_cases: vec![],
            },
            Substructure {
                name: "block".into(),
                model: block,
                constraints: Constraints::new(),
                load_cases: vec![loads.f],
            },
        ],
        interfaces: vec![InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", 0.3)],
    };
    let data = move |f: f64| {
        vec![
            LoadData::new(),
            LoadData::new().traction("ymax", move |x, n| top(x, n).map(|v| f * v)),
        ]
    };
    (asm, data)
}

#[test]
fn contact_runs_match_the_direct_path() {
    let (asm, data) = contact_problem(8);
    let solver = LatinSolver::new(
        asm.clone(),
        LatinOptions {
            tolerance: 1e-10,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap();
    let run1 = solve(&solver, &RunInput::default());
    let counts = run1.interfaces[0].status_counts();
    assert!(counts[2] > 0 && counts[3] > 0, "stick and slip: {counts:?}");
    let run2 = solve(
        &solver,
        &RunInput {
            young_factors: vec![0.8, 1.25],
            load_factors: vec![vec![], vec![1.4]],
            ..Default::default()
        },
    );
    let ctx = LatinEstimator::new(&asm, &CreOptions::default()).unwrap();
    let opts = CreOptions::default();
    for (run, f, what) in [
        (&run1, 1.0, "run 1"),
        (&run2, 1.4, "run 2"),
        (&run1, 1.0, "run 1 again"),
    ] {
        let a = ctx.estimate(&data(f), run).unwrap();
        let b = estimate_latin_direct(&asm, &data(f), run, &opts).unwrap();
        println!(
            "{what}: theta {:.6e} (direct {:.6e}), subs {:?}, compat {:.1e}, balance {:.1e} / {:.1e}",
            a.theta,
            b.theta,
            a.substructure_theta(),
            a.compatibility_defect(),
            a.substructures[1].balance_defect,
            b.substructures[1].balance_defect
        );
        assert!(a.compatibility_defect() < 1e-6);
        assert_same(&a, &b, &asm, what);
    }
    // Bit-identical with 1 and 2 threads.
    let with = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| ctx.estimate(&data(1.4), &run2).unwrap())
    };
    let (one, two) = (with(1), with(2));
    assert_eq!(one.theta.to_bits(), two.theta.to_bits());
    for (a, b) in one.substructures.iter().zip(&two.substructures) {
        assert_eq!(a.element_theta, b.element_theta);
        let (sa, sb) = (a.plane_stresses().unwrap(), b.plane_stresses().unwrap());
        assert!(sa.iter().zip(sb).all(|(x, y)| x.coeffs == y.coeffs));
    }
    // The one-run entry point is the context.
    let c = estimate_latin(&asm, &data(1.4), &run2, &opts).unwrap();
    assert_eq!(c.theta, ctx.estimate(&data(1.4), &run2).unwrap().theta);
    println!("cache: {} bytes", ctx.cache_bytes());
}

/// Part `i` (x in [i, i + 1]) of a 2 x 1 strip, distorted quadratic cells.
fn strip_part(i: usize, kind: CellType) -> Model {
    let mut mesh = square(4, kind, 0.25);
    for x in mesh.coords.iter_mut() {
        x[0] += i as f64;
    }
    model(mesh, PS)
}

#[test]
fn young_and_load_factors_and_affine_body_match_the_direct_path() {
    // b(x) = beta + A x: a constant part and a centrifugal-like gradient about (1, -3).
    let affine = AffineBody {
        constant: [30.0, -120.0 + 300.0 * 3.0 * 0.2, 0.0],
        gradient: [[300.0 * 0.2, 0.0, 0.0], [0.0, 300.0 * 0.2, 0.0], [0.0; 3]],
    };
    let traction = |_: [f64; 3], n: [f64; 3]| [-50.0 * n[0] + 20.0, -50.0 * n[1], 0.0];
    let mut subs = Vec::new();
    for (i, kind) in [(0, CellType::Quad8), (1, CellType::Tri6)] {
        let m = strip_part(i, kind);
        let mut c = Constraints::new();
        let mut loads = Loads::new(&m);
        loads
            .body_force(&m, None, move |x, _| affine.eval(x))
            .unwrap();
        if i == 0 {
            c.clamp(&m.mesh, "xmin").unwrap();
        } else {
            loads.traction(&m, "xmax", traction).unwrap();
        }
        subs.push(Substructure {
            name: format!("S{i}"),
            model: m,
            constraints: c,
            load_cases: vec![loads.f],
        });
    }
    let asm = Assembly {
        subs,
        interfaces: vec![InterfaceSpec::perfect("cut", 0, "xmax", 1, "xmin")],
    };
    let scaled = |f: f64| AffineBody {
        constant: affine.constant.map(|v| f * v),
        gradient: affine.gradient.map(|r| r.map(|v| f * v)),
    };
    // The loads with load factor f: affine body (cached moments) or closure (quadrature).
    let data = |f: f64, as_affine: bool| -> Vec<LoadData> {
        (0..2)
            .map(|i| {
                let b = scaled(f);
                let d = if as_affine {
                    LoadData::new().affine_body(b)
                } else {
                    LoadData::new().body(move |x| b.eval(x))
                };
                if i == 1 {
                    d.traction("xmax", move |x, n| traction(x, n).map(|v| f * v))
                } else {
                    d
                }
            })
            .collect()
    };
    let solver = LatinSolver::new(
        asm.clone(),
        LatinOptions {
            tolerance: 1e-11,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap();
    let lf = 1.35;
    let run1 = solve(&solver, &RunInput::default());
    let run2 = solve(
        &solver,
        &RunInput {
            young_factors: vec![1.7, 0.6],
            load_factors: vec![vec![lf], vec![lf]],
            ..Default::default()
        },
    );
    let opts = CreOptions::default();
    let ctx = LatinEstimator::new(&asm, &opts).unwrap();
    let direct2 = estimate_latin_direct(&asm, &data(lf, false), &run2, &opts).unwrap();
    let direct1 = estimate_latin_direct(&asm, &data(1.0, false), &run1, &opts).unwrap();
    for (as_affine, what) in [(false, "closure body"), (true, "affine body")] {
        let a = ctx.estimate(&data(lf, as_affine), &run2).unwrap();
        println!(
            "{what}: theta {:.8e} (direct {:.8e}), relative {:.3e}, compat {:.1e}, balance {:?}",
            a.theta,
            direct2.theta,
            a.relative,
            a.compatibility_defect(),
            a.substructures
                .iter()
                .map(|d| d.balance_defect)
                .collect::<Vec<_>>()
        );
        assert!(a.compatibility_defect() < 1e-6);
        assert_same(&a, &direct2, &asm, what);
        let b = ctx.estimate(&data(1.0, as_affine), &run1).unwrap();
        assert_same(&b, &direct1, &asm, what);
    }
    // The Young's factors change the estimate: theta^2 is not that of the unit factors.
    let unit = ctx
        .estimate(
            &data(lf, true),
            &RunResult {
                young_factors: vec![1.0, 1.0],
                ..run2.clone()
            },
        )
        .unwrap();
    assert!((unit.theta - direct2.theta).abs() > 1e-3 * direct2.theta);
}
