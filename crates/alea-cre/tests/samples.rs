//! The energy-weighted samples of the stochastic estimator reproduce the deterministic estimate:
//! `|y(sigma_hat) - y(sigma_h)|^2 / alpha = theta^2` cell by cell and in total, and
//! `|y(sigma_h)|^2 / alpha = ||u_h||_K^2`, for every 2D cell type, a distorted mesh and a Young's
//! modulus scaled by `alpha` (the samples are in the compliance coordinates of the reference
//! material).

mod common;

use alea_cre::{CreOptions, EnergySampler, LoadData, estimate_domain};
use alea_fem::{Analysis, Constraints, Loads, Ordering, solve_elastic};
use alea_mesh::CellType;
use common::*;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[test]
fn samples_reproduce_the_deterministic_estimate() {
    let analysis = Analysis::PlaneStrain { thickness: 2.0 };
    for kind in [
        CellType::Tri3,
        CellType::Quad4,
        CellType::Tri6,
        CellType::Quad8,
    ] {
        let reference = model(square(6, kind, 0.2), analysis);
        let alpha = 1.7;
        let mut m = reference.clone();
        m.scale_young(alpha);
        let mut cons = Constraints::new();
        cons.clamp(&m.mesh, "xmin").unwrap();
        let mut loads = Loads::new(&m);
        let b = body(analysis);
        loads.body_force(&m, None, move |x, _| b(x)).unwrap();
        let mut data = LoadData::new().body(b);
        for g in ["xmax", "ymin", "ymax"] {
            loads.traction(&m, g, exact_traction(analysis)).unwrap();
            data = data.traction(g, exact_traction(analysis));
        }
        let sol = solve_elastic(&m, &cons, &loads, Ordering::Metis).unwrap();
        let est = estimate_domain(&m, &cons, &data, &sol.u, &CreOptions::default()).unwrap();
        let sampler = EnergySampler::new(&reference, &CreOptions::default()).unwrap();
        let ya = sampler.admissible_stress(&est).unwrap();
        let yh = sampler.fe_stress(&reference, &sol.u, alpha);
        assert_eq!(ya.len(), sampler.len());
        assert_eq!(yh.len(), sampler.len());
        let diff: Vec<f64> = ya.iter().zip(&yh).map(|(a, b)| a - b).collect();
        let theta2 = dot(&diff, &diff) / alpha;
        assert!(
            (theta2 - est.theta * est.theta).abs() < 1e-10 * est.theta * est.theta,
            "{kind}: {theta2} against {}",
            est.theta * est.theta
        );
        let energy2 = dot(&yh, &yh) / alpha;
        assert!(
            (energy2 - est.energy_norm.powi(2)).abs() < 1e-10 * est.energy_norm.powi(2),
            "{kind}: energy {energy2} against {}",
            est.energy_norm.powi(2)
        );
        // The compact form (phase-2 coefficients) gives the same samples.
        let coeffs = sampler.coefficients(&est).unwrap();
        assert_eq!(coeffs.len(), *sampler.coefficient_offsets().last().unwrap());
        let mut yc = Vec::new();
        sampler.admissible_from_coefficients(&coeffs, alpha, 0..m.mesh.num_cells(), &mut yc);
        assert_eq!(yc.len(), ya.len());
        for (a, b) in yc.iter().zip(&ya) {
            assert!(
                (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
                "{kind}: {a} vs {b}"
            );
        }
        let off = sampler.cell_offsets();
        for (c, t) in est.element_theta.iter().enumerate() {
            let d = &diff[off[c]..off[c + 1]];
            let t2 = dot(d, d) / alpha;
            assert!(
                (t2 - t * t).abs() < 1e-9 * (t * t).max(1e-14 * theta2),
                "{kind} cell {c}"
            );
        }
    }
}

/// Strain samples of a field of another mesh (the efficiency index's reference distance): an
/// affine displacement is exact on every mesh, so located on a coarse distorted mesh and sampled
/// at a fine mesh's points it gives the fine mesh's own FE samples (`fe_stress / alpha`), and
/// `strain_at` on the fine mesh's own cells does too.
#[test]
fn strain_samples_of_a_located_field_match_the_fe_samples() {
    let analysis = Analysis::PlaneStrain { thickness: 1.5 };
    for kind in [CellType::Quad4, CellType::Tri6] {
        let fine = model(square(8, kind, 0.15), analysis);
        let coarse = model(square(3, kind, 0.2), analysis);
        let affine = |x: [f64; 3]| {
            [
                1e-3 * (0.3 + 2.0 * x[0] - 0.7 * x[1]),
                1e-3 * (-0.1 + 0.4 * x[0] + 1.3 * x[1]),
            ]
        };
        let nodal = |m: &alea_fem::Model| -> Vec<f64> {
            (0..m.mesh.num_nodes())
                .flat_map(|n| affine(m.mesh.coords[n]))
                .collect()
        };
        let (uf, uc) = (nodal(&fine), nodal(&coarse));
        let sampler = EnergySampler::new(&fine, &CreOptions::default()).unwrap();
        let alpha = 1.3;
        let yh = sampler.fe_stress(&fine, &uf, alpha);
        let locator = alea_fem::PointLocator::new(&coarse.mesh).unwrap();
        let mut z_coarse = Vec::new();
        let cells = 0..fine.mesh.num_cells();
        sampler.strain_samples(
            cells.clone(),
            |_, _, x| {
                let loc = locator.locate_nearest(x, 1e-9).expect("inside");
                EnergySampler::strain_at(&coarse, &uc, loc.cell, loc.xi)
            },
            &mut z_coarse,
        );
        let mut z_own = Vec::new();
        sampler.strain_samples(
            cells,
            |c, xi, _| EnergySampler::strain_at(&fine, &uf, c, xi),
            &mut z_own,
        );
        let scale = dot(&yh, &yh).sqrt() / alpha;
        assert_eq!(z_coarse.len(), yh.len());
        for ((a, b), y) in z_coarse.iter().zip(&z_own).zip(&yh) {
            assert!((alpha * b - y).abs() <= 1e-12 * alpha * scale, "{kind}");
            assert!(
                (a - y / alpha).abs() <= 1e-9 * scale,
                "{kind}: {a} vs {}",
                y / alpha
            );
        }
        assert!((dot(&z_own, &z_own) - scale * scale).abs() <= 1e-12 * scale * scale);
        // The points are the sampler's: one per sample triple.
        let n: usize = (0..fine.mesh.num_cells())
            .map(|c| sampler.cell_points(c).count())
            .sum();
        assert_eq!(3 * n, sampler.len());
    }
}
