//! The reference distance of the efficiency index (`alea_estimate::reference`) against closed
//! forms: with one sample component `z(xi) = |xi - 1/2|` (uniform `xi` on `[0, 1]`), which a
//! reference on 64 cells reproduces exactly (a node at the kink) and a surrogate on the two end
//! nodes replaces by `1/2`: `E[(|xi - 1/2| - 1/2)^2] = 1/12` with Young's factor 1, and
//! `E[(1 + xi)(|xi - 1/2| - 1/2)^2] = 1/8` with `alpha = 1 + xi`, to round-off (the rule on the
//! product cells is exact for these piecewise polynomials); the distance of a surrogate to
//! itself is 0; and the streamed Gram blocks equal the one-block ones.

use std::sync::Arc;

use alea_estimate::gram::CrossGram;
use alea_estimate::reference::{efficiency, expected_distances};
use alea_estimate::{Parameters, Rule};
use alea_uq::joint::Independent;
use alea_uq::law::Uniform;
use alea_uq::surrogate::StochasticMesh;

struct Young(bool);
impl Parameters for Young {
    fn young(&self, xi: &[f64], out: &mut [f64]) {
        out.fill(if self.0 { 1.0 + xi[0] } else { 1.0 });
    }
    fn friction(&self, _xi: &[f64], _i: usize, _out: &mut [f64]) {}
}

/// Samples: one row, the value `|xi_k - 1/2|` at each run of `mesh`.
fn samples(mesh: &StochasticMesh) -> Vec<f64> {
    (0..mesh.num_runs())
        .map(|k| (mesh.run_point(k)[0] - 0.5).abs())
        .collect()
}

fn rule(breaks: Vec<f64>) -> Rule {
    let law = Independent::new(vec![Arc::new(Uniform::new(0.0, 1.0).unwrap())]).unwrap();
    let cells = Rule::product_cells(&[breaks]).unwrap();
    let tags: Vec<usize> = (0..cells.len()).collect();
    Rule::on_cells(&cells, &tags, 4, &law).unwrap()
}

#[test]
fn distance_of_a_coarse_surrogate_to_an_exact_reference_is_its_interpolation_error() {
    let reference = StochasticMesh::new(&[0.0], &[1.0], &[64]).unwrap();
    let coarse = StochasticMesh::new(&[0.0], &[1.0], &[1]).unwrap();
    let (za, zb) = (samples(&reference), samples(&coarse));
    let mut g = CrossGram::zeros(za.len(), zb.len());
    g.add_block(1, &za, &zb);
    let breaks: Vec<f64> = (0..=64).map(|i| i as f64 / 64.0).collect();
    let r = rule(breaks);
    for (random, exact) in [(false, 1.0 / 12.0), (true, 1.0 / 8.0)] {
        let d = expected_distances(&r, &reference, &coarse, &Young(random), &[Some(g.clone())]);
        assert!(
            (d[0] / exact - 1.0).abs() < 1e-12,
            "{} against {exact}",
            d[0]
        );
    }
    // A surrogate against itself.
    let mut self_gram = CrossGram::zeros(zb.len(), zb.len());
    self_gram.add_block(1, &zb, &zb);
    let d = expected_distances(&r, &coarse, &coarse, &Young(true), &[Some(self_gram), None]);
    assert!(d[0].abs() < 1e-15 && d[1] == 0.0);
    let (nu, ps) = efficiency(2.0, 0.5).unwrap();
    assert!((nu - 2.0).abs() < 1e-15 && (ps - 2.0 * 2f64.sqrt()).abs() < 1e-15);
    assert!(efficiency(1.0, 0.0).is_none());
}

#[test]
fn streamed_blocks_add_up_to_the_whole() {
    let (ka, kb, m) = (5, 3, 37);
    let val = |i: usize, j: usize| ((i * 7 + j * 3) % 11) as f64 - 4.5;
    let a: Vec<f64> = (0..ka)
        .flat_map(|k| (0..m).map(move |i| val(i, k)))
        .collect();
    let b: Vec<f64> = (0..kb)
        .flat_map(|k| (0..m).map(move |i| val(i + 5, k + 1)))
        .collect();
    let mut whole = CrossGram::zeros(ka, kb);
    whole.add_block(m, &a, &b);
    let mut parts = CrossGram::zeros(ka, kb);
    for (r0, r1) in [(0, 10), (10, 11), (11, 37)] {
        let rows = |v: &[f64], k: usize| -> Vec<f64> {
            (0..k)
                .flat_map(|c| v[c * m + r0..c * m + r1].to_vec())
                .collect()
        };
        let mut g = CrossGram::zeros(ka, kb);
        g.add_block(r1 - r0, &rows(&a, ka), &rows(&b, kb));
        parts.add(&g);
    }
    for (x, y) in whole
        .aa
        .iter()
        .chain(&whole.ab)
        .chain(&whole.bb)
        .zip(parts.aa.iter().chain(&parts.ab).chain(&parts.bb))
    {
        assert!((x - y).abs() < 1e-12 * x.abs().max(1.0));
    }
    let dot = |u: &[f64], v: &[f64]| u.iter().zip(v).map(|(p, q)| p * q).sum::<f64>();
    assert_eq!(whole.ab[2 * kb + 1], dot(&a[2 * m..3 * m], &b[m..2 * m]));
}

#[test]
fn product_cells_merge_the_breakpoints_of_two_grids() {
    let cells =
        Rule::product_cells(&[vec![0.0, 0.5, 1.0, 0.25, 0.5, 0.75], vec![2.0, 3.0]]).unwrap();
    assert_eq!(cells.len(), 4);
    assert_eq!(cells[1], (vec![0.25, 2.0], vec![0.5, 3.0]));
    assert!(Rule::product_cells(&[vec![1.0, 1.0]]).is_err());
}
