//! The expectations of the stochastic estimator against independent evaluations of the same
//! integrals, on synthetic run data (random sample vectors, a contact interface whose runs
//! satisfy the Coulomb law): exact weight moments of polynomial chaos, tensor Gauss quadrature
//! of increasing order, brute-force Monte Carlo with its confidence interval; the zero-variance
//! limit; the split `e~^2 = I_geo^2 + I_sto^2`; and the interpolation rate of `I_sto` for a
//! response `~ 1/E`.

use std::sync::Arc;

use alea_estimate::rule::Rule;
use alea_estimate::{
    Estimator, EstimatorOptions, InterfaceKind, InterfaceLayout, Layout, Parameters, RunData,
    SubLayout, SubstructureMoments,
};
use alea_uq::basis::PcBasis;
use alea_uq::joint::{Independent, JointLaw};
use alea_uq::law::{Marginal, Uniform};
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::{LinearSurrogate, PcSurrogate, StochasticMesh};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const N: usize = 36;
const NP: usize = 6;

/// Young's factor `1.3` or `1 + 0.5 xi_0`, friction `0.3 + 0.2 xi_1 + 0.01 p`.
struct Params {
    random_young: bool,
}

impl Params {
    fn alpha(&self, xi: &[f64]) -> f64 {
        if self.random_young {
            1.0 + 0.5 * xi[0]
        } else {
            1.3
        }
    }
    fn mu(xi: &[f64], p: usize) -> f64 {
        0.3 + 0.2 * xi[1] + 0.01 * p as f64
    }
}

impl Parameters for Params {
    fn young(&self, xi: &[f64], out: &mut [f64]) {
        out[0] = self.alpha(xi);
    }
    fn friction(&self, xi: &[f64], _interface: usize, out: &mut [f64]) {
        for (p, o) in out.iter_mut().enumerate() {
            *o = Params::mu(xi, p);
        }
    }
}

fn layout() -> Layout {
    Layout {
        subs: vec![SubLayout {
            name: "S".into(),
            cell_offsets: (0..=N / 6).map(|c| 6 * c).collect(),
            admissible: true,
        }],
        interfaces: vec![InterfaceLayout {
            name: "I".into(),
            kind: InterfaceKind::Contact,
            weights: (0..NP).map(|p| 0.5 + 0.1 * p as f64).collect(),
            normals: vec![[0.0, 1.0, 0.0]; NP],
        }],
    }
}

/// Synthetic run data at `xi`: samples varying smoothly with `xi` plus noise, interface
/// points open / sticking / slipping depending on `xi`, each satisfying the law at `xi`.
fn run_at(xi: &[f64], params: &Params, rng: &mut ChaCha8Rng) -> RunData {
    let alpha = params.alpha(xi);
    let h: Vec<f64> = (0..N)
        .map(|i| (1.0 + 0.2 * i as f64).sin() * (1.0 + xi[0]) + 0.05 * rng.random::<f64>())
        .collect();
    let a: Vec<f64> = h
        .iter()
        .enumerate()
        .map(|(i, v)| v + 0.1 * ((i as f64) * (1.0 + xi[1])).cos())
        .collect();
    let mut jump = Vec::new();
    let mut force = Vec::new();
    for p in 0..NP {
        let mu = Params::mu(xi, p);
        let load = p as f64 - 1.5 + 2.0 * xi[0];
        if load < 0.0 {
            // Open: a positive gap, no force.
            jump.push([0.1 * rng.random::<f64>(), -load, 0.0]);
            force.push([0.0; 3]);
        } else {
            let fnormal = load;
            let ft = (0.5 + xi[1]) * 0.6 * fnormal;
            if ft <= mu * fnormal {
                jump.push([0.0, 0.0, 0.0]);
                force.push([ft, fnormal, 0.0]);
            } else {
                let slip = 0.2 * (ft - mu * fnormal);
                jump.push([-slip, 0.0, 0.0]);
                force.push([mu * fnormal, fnormal, 0.0]);
            }
        }
    }
    RunData {
        young: vec![alpha],
        admissible: vec![a],
        fe: vec![h],
        jump: vec![jump],
        force: vec![force],
    }
}

fn marginals() -> Vec<Arc<dyn Marginal>> {
    vec![
        Arc::new(Uniform::new(0.0, 1.0).unwrap()),
        Arc::new(Uniform::new(0.0, 1.0).unwrap()),
    ]
}

/// PC of degree 2 by regression on a 3 x 3 grid.
fn setup(params: &Params) -> (PcSurrogate, Estimator) {
    let (sur, est, _) = setup_with_runs(params);
    (sur, est)
}

/// The 3 x 3 design of [`setup_with_runs`], one point per run.
fn grid_points() -> Vec<Vec<f64>> {
    let mut pts = Vec::new();
    for j in 0..3 {
        for i in 0..3 {
            pts.push(vec![0.1 + 0.4 * i as f64, 0.1 + 0.4 * j as f64]);
        }
    }
    pts
}

fn setup_with_runs(params: &Params) -> (PcSurrogate, Estimator, Vec<RunData>) {
    let pts: Vec<f64> = grid_points().concat();
    let basis = PcBasis::total_degree(&marginals(), 2).unwrap();
    let sur = PcSurrogate::regression(basis, &pts).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let runs: Vec<RunData> = pts.chunks(2).map(|x| run_at(x, params, &mut rng)).collect();
    let run_points: Vec<Vec<f64>> = pts.chunks(2).map(|x| x.to_vec()).collect();
    let est = Estimator::new(
        layout(),
        &runs,
        &run_points,
        params,
        EstimatorOptions::default(),
    )
    .unwrap();
    (sur, est, runs)
}

fn gauss(order: usize) -> Rule {
    Rule::from_quadrature(&QuadratureRule::tensor_gauss(&marginals(), &[order, order]).unwrap())
        .unwrap()
}

#[test]
fn exact_pc_moments_equal_the_quadrature_of_the_pointwise_terms() {
    let params = Params {
        random_young: false,
    };
    let (sur, est) = setup(&params);
    let m = sur.weight_second_moments();
    let a = 1.3;
    let exact = est
        .substructure_moments(&[SubstructureMoments {
            inv_alpha: m.iter().map(|v| v / a).collect(),
            one: m.clone(),
            alpha: m.iter().map(|v| v * a).collect(),
        }])
        .unwrap()[0];
    // The substructure integrand is a polynomial of degree 4 per direction: 3 points are exact.
    let q = est.expectation(&gauss(3), &sur, &params);
    let s = &q.subs[0];
    for (x, y) in [(s.e2, exact[0]), (s.geo2, exact[1]), (q.norm2, exact[2])] {
        assert!((x - y).abs() < 1e-12 * y.abs(), "{x} against {y}");
    }
    // Deterministic Young's modulus: sigma_h1 = sigma_h2, no stochastic substructure error.
    assert!(s.sto2.abs() < 1e-12 * s.e2, "{}", s.sto2);
    assert!(s.e2 > 0.0 && s.mean2 > 0.0 && s.std2 > 0.0 && s.mean2 < s.e2);
    // The split holds by construction, per entity and in total.
    let tot: f64 = q.subs.iter().chain(&q.interfaces).map(|e| e.e2).sum();
    assert!((tot - q.e2).abs() < 1e-12 * q.e2);
    assert!((q.geo2 + q.sto2 - q.e2).abs() < 1e-12 * q.e2);
}

#[test]
fn random_young_moments_converge_and_match_the_pointwise_expectation() {
    let params = Params { random_young: true };
    let (sur, est) = setup(&params);
    let reference = est
        .substructure_moments(&est.moments(&gauss(24), &sur, &params))
        .unwrap()[0];
    let coarse = est
        .substructure_moments(&est.moments(&gauss(10), &sur, &params))
        .unwrap()[0];
    for c in 0..3 {
        assert!(
            (coarse[c] - reference[c]).abs() < 1e-8 * reference[c].abs(),
            "term {c}: {} against {}",
            coarse[c],
            reference[c]
        );
    }
    // The pointwise expectation on a rule equals the moments on the same rule.
    let rule = gauss(10);
    let q = est.expectation(&rule, &sur, &params);
    let mo = est
        .substructure_moments(&est.moments(&rule, &sur, &params))
        .unwrap()[0];
    assert!((q.subs[0].e2 - mo[0]).abs() < 1e-12 * mo[0]);
    assert!((q.subs[0].geo2 - mo[1]).abs() < 1e-12 * mo[1]);
    assert!((q.norm2 - mo[2]).abs() < 1e-12 * mo[2]);
    // Random Young's modulus: the displacements interpolated then Hooke differ from the
    // interpolated stresses - a stochastic substructure part.
    assert!(q.subs[0].sto2.abs() > 1e-6 * q.subs[0].e2);
}

#[test]
fn quadrature_agrees_with_brute_force_monte_carlo() {
    let params = Params { random_young: true };
    let (sur, est) = setup(&params);
    let law = Independent::new(marginals()).unwrap();
    let n = 20_000;
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut w = Vec::new();
    let mut xi = [0.0; 2];
    let (mut s1, mut s2) = (0.0, 0.0);
    let (mut t1, mut t2) = (0.0, 0.0);
    for _ in 0..n {
        law.sample(&mut rng, &mut xi);
        LinearSurrogate::weights(&sur, &xi, &mut w);
        let p = est.at(&xi, &w, &params);
        let (e, i) = (p.e2(), p.interfaces[0].e);
        s1 += e;
        s2 += e * e;
        t1 += i;
        t2 += i * i;
    }
    let nf = n as f64;
    let q = est.expectation(&gauss(40), &sur, &params);
    for (sum, sq, exact, what) in [
        (s1, s2, q.e2, "e^2"),
        (t1, t2, q.interfaces[0].e2, "interface"),
    ] {
        let mean = sum / nf;
        let sd = ((sq / nf - mean * mean).max(0.0) / nf).sqrt();
        assert!(
            (mean - exact).abs() < 4.0 * sd,
            "{what}: Monte Carlo {mean} +- {sd}, quadrature {exact}"
        );
    }
    // The interface has a stochastic part (interpolated forces leave the Coulomb disk of
    // mu(xi)) and a space part.
    assert!(q.interfaces[0].sto2.abs() > 0.0);
}

#[test]
fn zero_variance_reduces_to_the_deterministic_estimate() {
    let params = Params {
        random_young: false,
    };
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let xi = [0.7, 0.4];
    let mut run = run_at(&xi, &params, &mut rng);
    // The estimate's jump comes from the stage before the force: a slip along the friction
    // force at every closed point makes the deterministic interface term non-zero.
    for p in 0..NP {
        if run.force[0][p][1] > 0.0 {
            run.jump[0][p][0] = 0.05 + run.jump[0][p][0].abs();
        }
    }
    let est = Estimator::new(
        layout(),
        std::slice::from_ref(&run),
        &[xi.to_vec()],
        &params,
        EstimatorOptions::default(),
    )
    .unwrap();
    // A surrogate on one run: weight 1 everywhere.
    struct One;
    impl alea_estimate::Weights for One {
        fn weights(&self, _xi: &[f64], w: &mut Vec<(usize, f64)>) {
            w.clear();
            w.push((0, 1.0));
        }
    }
    let rule = Rule::new(2, xi.to_vec(), vec![1.0], vec![0]).unwrap();
    let q = est.expectation(&rule, &One, &params);
    // Deterministic CRE: 1/2 |y(sigma_hat) - y(sigma_h)|^2 / alpha + sum m rho(w, F).
    let d2: f64 = run.admissible[0]
        .iter()
        .zip(&run.fe[0])
        .map(|(a, h)| (a - h) * (a - h))
        .sum();
    let lay = layout();
    let mut iface = 0.0;
    for p in 0..NP {
        let (w, f) = (run.jump[0][p], run.force[0][p]);
        let mu = Params::mu(&xi, p);
        iface +=
            lay.interfaces[0].weights[p] * (mu * f[1] * w[0].abs() + w[1] * f[1] + w[0] * f[0]);
    }
    let det = 0.5 * d2 / 1.3 + iface;
    assert!((q.e2 - det).abs() < 1e-14 * det, "{} against {det}", q.e2);
    assert_eq!(q.sto2, 0.0);
    assert!(iface > 0.0, "a non-zero deterministic interface term");
}

#[test]
fn the_law_holds_at_the_runs_of_an_interpolating_surrogate() {
    // Piecewise multilinear on a 3 x 3 grid interpolates: at a run point the interface fields
    // are the run's, which satisfy the law at that point, so the interface has no stochastic
    // error there.
    let params = Params { random_young: true };
    let mesh = StochasticMesh::new(&[0.0, 0.0], &[1.0, 1.0], &[2, 2]).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let runs: Vec<RunData> = (0..mesh.num_runs())
        .map(|k| run_at(mesh.run_point(k), &params, &mut rng))
        .collect();
    let run_points: Vec<Vec<f64>> = (0..mesh.num_runs())
        .map(|k| mesh.run_point(k).to_vec())
        .collect();
    let est = Estimator::new(
        layout(),
        &runs,
        &run_points,
        &params,
        EstimatorOptions::default(),
    )
    .unwrap();
    let mut w = Vec::new();
    for k in 0..mesh.num_runs() {
        let xi = mesh.run_point(k).to_vec();
        LinearSurrogate::weights(&mesh, &xi, &mut w);
        let p = est.at(&xi, &w, &params);
        assert!(
            p.sto2().abs() < 1e-12 * p.e2().max(1e-30),
            "run {k}: {}",
            p.sto2()
        );
        assert_eq!(p.violation, 0.0);
    }
}

#[test]
fn the_interface_stochastic_density_vanishes_continuously_at_a_run_whose_neighbour_opens() {
    // Two runs of a one-point contact interface: at xi = 0 the point is closed and slips
    // (F_t = -mu F_n, slip against it), at xi = 1 it is open (positive normal jump, no force).
    // Between them the interpolated jump is open while the interpolated force still presses:
    // the stochastic part must go to 0 as xi -> 0 (the fields tend to the run's, which
    // satisfies the law), not jump to |w_t . F_t| of the closed run.
    struct Linear;
    impl alea_estimate::Weights for Linear {
        fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
            w.clear();
            w.extend([(0, 1.0 - xi[0]), (1, xi[0])]);
        }
    }
    struct Mu;
    impl Parameters for Mu {
        fn young(&self, _xi: &[f64], out: &mut [f64]) {
            out.fill(1.0);
        }
        fn friction(&self, xi: &[f64], _i: usize, out: &mut [f64]) {
            out.fill(0.3 - 0.2 * xi[0]);
        }
    }
    let layout = Layout {
        subs: vec![],
        interfaces: vec![InterfaceLayout {
            name: "I".into(),
            kind: InterfaceKind::Contact,
            weights: vec![1.0],
            normals: vec![[0.0, 1.0, 0.0]],
        }],
    };
    let run = |jump: [f64; 3], force: [f64; 3]| RunData {
        young: vec![],
        admissible: vec![],
        fe: vec![],
        jump: vec![vec![jump]],
        force: vec![vec![force]],
    };
    let (fnormal, slip) = (2.0, 0.4);
    let runs = [
        run([-slip, 0.0, 0.0], [0.3 * fnormal, fnormal, 0.0]),
        run([-0.1, 0.05, 0.0], [0.0; 3]),
    ];
    let est = Estimator::new(
        layout,
        &runs,
        &[vec![0.0], vec![1.0]],
        &Mu,
        EstimatorOptions::default(),
    )
    .unwrap();
    let sto = |x: f64| {
        let mut w = Vec::new();
        alea_estimate::Weights::weights(&Linear, &[x], &mut w);
        est.at(&[x], &w, &Mu).sto2()
    };
    let jump_size = slip * 0.3 * fnormal;
    assert!(sto(0.0).abs() < 1e-14 && sto(1.0).abs() < 1e-14);
    // Between the runs: w~ = (-0.4 + 0.3 x, 0.05 x), F~ = (1 - x) (0.6, 2), mu = 0.3 - 0.2 x.
    // The interpolated normal jump opens while the normal force presses (|w_n F_n| =
    // 0.1 x (1 - x)), and the tangential force leaves the disk of mu F_n by 0.4 x (1 - x),
    // charged as work along the slip: rho* = 0.1 x (1 - x) + |w_t| 0.4 x (1 - x). Both runs
    // obey their law (rho_k = 0), so all of it is stochastic, and it vanishes like xi.
    for x in [0.5, 1e-1, 1e-2, 1e-3, 1e-4, 1e-6] {
        let s = sto(x);
        let exact = 0.1 * x * (1.0 - x) + (0.4 - 0.3 * x) * 0.4 * x * (1.0 - x);
        assert!(
            (s - exact).abs() < 1e-9 * exact + 1e-15,
            "sto({x}) = {s} against {exact}"
        );
        assert!(
            s > 0.0 && s < 1.1 * x * jump_size,
            "sto({x}) = {s}: does not vanish like xi (|w_t . F_t| = {jump_size})"
        );
    }
}

#[test]
fn stochastic_error_of_a_response_in_one_over_e_converges_at_the_interpolation_rate() {
    // One substructure, random Young's factor alpha = xi in [1, 2], traction loads: the stress
    // does not depend on E, the displacement goes as 1/E. With sigma_h,k = s0 and
    // sigma_hat_k = s0 + d (d orthogonal to s0, Prager-Synge), the stochastic part is
    // 1/2 |s0|^2 (alpha sum_k w_k / alpha_k - 1)^2 / alpha: the interpolation error of 1/alpha,
    // O(h^2) for piecewise-linear weights.
    struct Young;
    impl Parameters for Young {
        fn young(&self, xi: &[f64], out: &mut [f64]) {
            out[0] = xi[0];
        }
        fn friction(&self, _xi: &[f64], _i: usize, _out: &mut [f64]) {}
    }
    let s0 = vec![1.0, -2.0, 0.5, 3.0];
    let d = vec![0.2, 0.1, 0.0, 0.0]; // s0 . d = 0
    let lay = Layout {
        subs: vec![SubLayout {
            name: "S".into(),
            cell_offsets: vec![0, 4],
            admissible: true,
        }],
        interfaces: vec![],
    };
    let law = Independent::new(vec![Arc::new(Uniform::new(1.0, 2.0).unwrap())]).unwrap();
    let (mut hs, mut isto) = (Vec::new(), Vec::new());
    for cells in [2usize, 4, 8, 16, 32] {
        let mesh = StochasticMesh::new(&[1.0], &[2.0], &[cells]).unwrap();
        let runs: Vec<RunData> = (0..mesh.num_runs())
            .map(|k| RunData {
                young: vec![mesh.run_point(k)[0]],
                admissible: vec![s0.iter().zip(&d).map(|(a, b)| a + b).collect()],
                fe: vec![s0.clone()],
                jump: vec![],
                force: vec![],
            })
            .collect();
        let run_points: Vec<Vec<f64>> = (0..mesh.num_runs())
            .map(|k| mesh.run_point(k).to_vec())
            .collect();
        let est = Estimator::new(
            lay.clone(),
            &runs,
            &run_points,
            &Young,
            EstimatorOptions::default(),
        )
        .unwrap();
        let leaves = mesh.leaves();
        let boxes: Vec<_> = leaves.iter().map(|&c| mesh.cell_bounds(c)).collect();
        let rule = Rule::on_cells(&boxes, &leaves, 6, &law).unwrap();
        let q = est.expectation(&rule, &mesh, &Young);
        hs.push(1.0 / cells as f64);
        isto.push(q.i_sto());
        // The space part does not depend on the stochastic mesh: |d|^2 / (2 alpha).
        let geo_exact = 0.5 * 0.05 * (2.0f64).ln();
        assert!(
            (q.geo2 - geo_exact).abs() < 1e-10,
            "{} against {geo_exact}",
            q.geo2
        );
    }
    let n = hs.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = (
        hs.iter().map(|h| h.ln()).collect(),
        isto.iter().map(|v| v.ln()).collect(),
    );
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let slope = lx
        .iter()
        .zip(&ly)
        .map(|(x, y)| (x - mx) * (y - my))
        .sum::<f64>()
        / lx.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
    assert!((slope - 2.0).abs() < 0.1, "i_sto {isto:?}: slope {slope}");
}

#[test]
fn run_data_round_trips_through_bytes() {
    let params = Params { random_young: true };
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let run = run_at(&[0.3, 0.6], &params, &mut rng);
    let b = run.to_bytes();
    assert_eq!(RunData::from_bytes(&b).unwrap(), run);
    assert!(RunData::from_bytes(&b[..b.len() - 3]).is_err());
    assert!(RunData::from_bytes(b"garbage!").is_err());
    let mut bad = b.clone();
    bad[8] = 0xff; // an absurd count
    assert!(RunData::from_bytes(&bad).is_err());
}

#[test]
fn cell_terms_add_up_to_the_substructure_expectations() {
    let params = Params { random_young: true };
    let (sur, est, runs) = setup_with_runs(&params);
    let rule = gauss(8);
    let q = est.expectation(&rule, &sur, &params);
    let m = est.moments(&rule, &sur, &params);
    let a: Vec<&[f64]> = runs.iter().map(|r| r.admissible[0].as_slice()).collect();
    let h: Vec<&[f64]> = runs.iter().map(|r| r.fe[0].as_slice()).collect();
    let y: Vec<f64> = runs.iter().map(|r| r.young[0]).collect();
    let cells = alea_estimate::cell_terms(&a, &h, &y, &layout().subs[0].cell_offsets, &m[0]);
    assert_eq!(cells.len(), N / 6);
    let geo: f64 = cells.iter().map(|c| c.0).sum();
    let e2: f64 = cells.iter().map(|c| c.1).sum();
    assert!(
        (geo - q.subs[0].geo2).abs() < 1e-10 * geo,
        "{geo} vs {}",
        q.subs[0].geo2
    );
    assert!(
        (e2 - q.subs[0].e2).abs() < 1e-10 * e2,
        "{e2} vs {}",
        q.subs[0].e2
    );
    assert!(cells.iter().all(|c| c.0 >= 0.0));
}

#[test]
fn the_maximum_error_search_copes_with_leaves_at_the_finest_level() {
    // A stochastic mesh refined at its centre, again and again, around one point down to the
    // finest level: the candidates of the deepest leaves must stay within the mesh's levels
    // (shallower sub-cells), and the chosen point's leaf must be one the mesh can refine.
    use alea_uq::surrogate::MAX_LEVEL;
    let params = Params { random_young: true };
    let mut mesh = StochasticMesh::new(&[0.0, 0.0], &[1.0, 1.0], &[1, 1]).unwrap();
    let target = [0.3, 0.3];
    loop {
        let leaf = mesh.locate(&target).unwrap();
        if mesh.level(leaf) >= MAX_LEVEL - 1 {
            break;
        }
        mesh.refine_centred(&[leaf]).unwrap();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let runs: Vec<RunData> = (0..mesh.num_runs())
        .map(|k| run_at(mesh.run_point(k), &params, &mut rng))
        .collect();
    let run_points: Vec<Vec<f64>> = (0..mesh.num_runs())
        .map(|k| mesh.run_point(k).to_vec())
        .collect();
    let est = Estimator::new(
        layout(),
        &runs,
        &run_points,
        &params,
        EstimatorOptions::default(),
    )
    .unwrap();
    let law = Independent::new(marginals()).unwrap();
    let best = alea_estimate::refine::max_error_point(&mesh, &est, &mesh, &params, &law, 3)
        .expect("no level error")
        .expect("a positive density somewhere");
    match best.enrich {
        alea_estimate::refine::Enrich::Centre(cell) => {
            let (lo, hi) = mesh.cell_bounds(cell);
            assert!((0..2).all(|j| best.point[j] > lo[j] && best.point[j] < hi[j]));
            mesh.refine_centred(&[cell])
                .expect("a leaf the mesh can refine");
        }
        alea_estimate::refine::Enrich::Node => {
            mesh.promote(&best.point)
                .expect("a node the mesh can promote");
        }
    }
}

/// The same runs with the substructure's admissible samples withheld: no substructure error
/// term, the interface terms unchanged, and the normalisation the FE energy of the interpolated
/// displacement, `E[||sigma_h1||^2] = E[alpha |sum_k w_k y(sigma_h,k) / alpha_k|^2]`, checked
/// against a direct sum over the rule and against the weight moments.
#[test]
fn fe_samples_only_give_no_substructure_term_and_the_fe_energy_as_the_norm() {
    let params = Params { random_young: true };
    let (sur, full, runs) = setup_with_runs(&params);
    let mut lay = layout();
    lay.subs[0].admissible = false;
    let fe_runs: Vec<RunData> = runs
        .iter()
        .map(|r| RunData {
            admissible: vec![Vec::new()],
            ..r.clone()
        })
        .collect();
    // Admissible samples given for a substructure the layout says has none: refused.
    let run_points = grid_points();
    let opts = EstimatorOptions::default();
    assert!(Estimator::new(lay.clone(), &runs, &run_points, &params, opts).is_err());
    let est = Estimator::new(lay, &fe_runs, &run_points, &params, opts).unwrap();
    let g = est.gram(0).unwrap();
    assert!(!g.has_admissible() && full.gram(0).unwrap().has_admissible());
    assert_eq!(g.hh, full.gram(0).unwrap().hh);
    let rule = gauss(8);
    let q = est.expectation(&rule, &sur, &params);
    let qf = full.expectation(&rule, &sur, &params);
    assert_eq!(
        (q.subs[0].e2, q.subs[0].geo2, q.subs[0].mean2),
        (0.0, 0.0, 0.0)
    );
    assert_eq!(q.interfaces, qf.interfaces);
    assert_eq!(q.e2, qf.interfaces[0].e2);
    // Direct sum of the FE energy of the interpolated displacement over the rule.
    let mut w = Vec::new();
    let mut direct = 0.0;
    for p in 0..rule.len() {
        let xi = rule.point(p);
        LinearSurrogate::weights(&sur, xi, &mut w);
        let a = params.alpha(xi);
        let mut y = vec![0.0; N];
        for &(k, wk) in &w {
            for (yi, h) in y.iter_mut().zip(&runs[k].fe[0]) {
                *yi += wk * h / runs[k].young[0];
            }
        }
        direct += rule.weight(p) * a * y.iter().map(|v| v * v).sum::<f64>();
    }
    assert!(
        (q.norm2 - direct).abs() < 1e-12 * direct,
        "{} vs {direct}",
        q.norm2
    );
    let mo = est
        .substructure_moments(&est.moments(&rule, &sur, &params))
        .unwrap()[0];
    assert_eq!((mo[0], mo[1]), (0.0, 0.0));
    assert!((mo[2] - direct).abs() < 1e-12 * direct);
    // The two normalisations agree to the size of the admissible-minus-FE difference.
    let rel = (q.norm2 - qf.norm2).abs() / qf.norm2;
    assert!(rel > 0.0 && rel < 0.2, "{rel}");
    let expect = (qf.interfaces[0].e2 / direct).sqrt();
    assert!((q.relative() - expect).abs() < 1e-12 * expect && expect > 0.0);
}

/// The interface terms point by point add up to the interface expectations on the same rule,
/// and every point's stochastic part `e - geo` is what the interface's `sto2` sums.
#[test]
fn interface_point_terms_add_up_to_the_interface_expectations() {
    let params = Params { random_young: true };
    let (sur, est) = setup(&params);
    let rule = gauss(6);
    let q = est.expectation(&rule, &sur, &params);
    let pts = est.interface_point_terms(&rule, &sur, &params);
    assert_eq!(pts.len(), 1);
    assert_eq!(pts[0].len(), NP);
    let e: f64 = pts[0].iter().map(|v| v[0]).sum();
    let g: f64 = pts[0].iter().map(|v| v[1]).sum();
    let it = &q.interfaces[0];
    assert!((e - it.e2).abs() < 1e-12 * it.e2.abs(), "{e} vs {}", it.e2);
    assert!((g - it.geo2).abs() < 1e-12 * it.geo2.abs().max(it.e2.abs()));
    assert!(it.sto2.abs() > 0.0);
    assert!(pts[0].iter().any(|v| v[0] != v[1]));
}
