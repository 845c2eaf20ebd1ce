//! Joint laws: Gaussian copula sample correlation within its confidence interval, Nataf round
//! trip, user density on a box (moments against exact values), validation errors.

use alea_uq::design::monte_carlo;
use alea_uq::joint::{BoxDensity, GaussianCopula, Independent, JointLaw};
use alea_uq::law::{Gamma, Marginal, Normal, TruncatedNormal, Uniform};
use alea_uq::special::norm_quantile;
use std::sync::Arc;

fn copula(rho: f64) -> GaussianCopula {
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Uniform::new(0.0, 2.0).unwrap()),
        Arc::new(Gamma::new(2.0, 1.0, 0.0).unwrap()),
        Arc::new(TruncatedNormal::new(0.0, 1.0, -1.0, 2.0).unwrap()),
    ];
    let c = vec![1.0, rho, 0.2, rho, 1.0, -0.3, 0.2, -0.3, 1.0];
    GaussianCopula::new(m, c).unwrap()
}

#[test]
fn copula_sample_correlation_within_ci() {
    let law = copula(0.6);
    let n = 50_000;
    let d = monte_carlo(&law, n, 5);
    // Normal scores z_i = Phi^-1(F_i(x_i)) must have correlation R.
    let z: Vec<[f64; 3]> = d
        .iter()
        .map(|x| {
            let mut z = [0.0; 3];
            for i in 0..3 {
                z[i] = norm_quantile(law.marginals()[i].cdf(x[i]));
            }
            z
        })
        .collect();
    for &(i, j, rho) in &[(0, 1, 0.6), (0, 2, 0.2), (1, 2, -0.3)] {
        let mi = z.iter().map(|v| v[i]).sum::<f64>() / n as f64;
        let mj = z.iter().map(|v| v[j]).sum::<f64>() / n as f64;
        let cov: f64 = z.iter().map(|v| (v[i] - mi) * (v[j] - mj)).sum::<f64>();
        let vi: f64 = z.iter().map(|v| (v[i] - mi).powi(2)).sum::<f64>();
        let vj: f64 = z.iter().map(|v| (v[j] - mj).powi(2)).sum::<f64>();
        let r = cov / (vi * vj).sqrt();
        // Fisher transform: atanh(r) ~ N(atanh(rho), 1/(n - 3)); 4.5 sigma.
        let dev = (r.atanh() - f64::atanh(rho)).abs() * ((n - 3) as f64).sqrt();
        assert!(dev < 4.5, "r_{i}{j} = {r} vs {rho}");
    }
}

#[test]
fn nataf_round_trip() {
    let law = copula(0.8);
    for u in [[0.1, 0.5, 0.9], [0.01, 0.99, 0.3], [0.5, 0.5, 0.5]] {
        let mut x = [0.0; 3];
        let mut back = [0.0; 3];
        law.unit_to_x(&u, &mut x);
        law.x_to_unit(&x, &mut back);
        for k in 0..3 {
            assert!((u[k] - back[k]).abs() < 1e-9, "{u:?} -> {back:?}");
        }
        let mut y = [0.0; 3];
        let mut x2 = [0.0; 3];
        law.x_to_standard_normal(&x, &mut y);
        law.standard_normal_to_x(&y, &mut x2);
        for k in 0..3 {
            assert!((x[k] - x2[k]).abs() < 1e-9 * (1.0 + x[k].abs()));
        }
    }
}

#[test]
fn copula_density_integrates_to_one_and_reduces_to_bivariate_normal() {
    // Normal marginals + Gaussian copula = bivariate normal density.
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
    ];
    let rho: f64 = 0.5;
    let law = GaussianCopula::new(m, vec![1.0, rho, rho, 1.0]).unwrap();
    let (x, y) = (0.3, -0.7);
    let exact = (-(x * x - 2.0 * rho * x * y + y * y) / (2.0 * (1.0 - rho * rho))).exp()
        / (2.0 * std::f64::consts::PI * (1.0 - rho * rho).sqrt());
    assert!((law.pdf(&[x, y]) - exact).abs() < 1e-13);
    // Probability of [-8, 8]^2 summed over unit cells (6-point Gauss-Legendre per cell).
    let mut total = 0.0;
    for i in 0..16 {
        for j in 0..16 {
            let lo = [-8.0 + i as f64, -8.0 + j as f64];
            total += law.box_probability(&lo, &[lo[0] + 1.0, lo[1] + 1.0]);
        }
    }
    assert!((total - 1.0).abs() < 1e-6, "{total}");
}

#[test]
fn invalid_copula_is_reported() {
    let m: Vec<Arc<dyn Marginal>> = vec![
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
    ];
    let e = GaussianCopula::new(m.clone(), vec![1.0, 1.5, 1.5, 1.0]).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("gaussian copula: correlation entry"),
        "{e}"
    );
    let m3: Vec<Arc<dyn Marginal>> = vec![m[0].clone(), m[0].clone(), m[0].clone()];
    // Symmetric, unit diagonal, entries in [-1, 1], but not positive definite.
    let c = vec![1.0, 0.9, -0.9, 0.9, 1.0, 0.9, -0.9, 0.9, 1.0];
    let e = GaussianCopula::new(m3, c).unwrap_err();
    assert!(
        e.to_string().contains("not symmetric positive definite"),
        "{e}"
    );
}

#[test]
fn box_density_moments_and_round_trip() {
    // f(a, b) proportional to 1 + a b on [0, 1]^2: E[a] = (1/2 + 1/6) / (5/4) = 8/15,
    // E[a b] = (1/4 + 1/9) / (5/4) = 13/45.
    let law =
        BoxDensity::from_fn(vec![0.0, 0.0], vec![1.0, 1.0], 64, |x| 1.0 + x[0] * x[1]).unwrap();
    assert!((law.pdf(&[0.5, 0.5]) - 1.25 / 1.25).abs() < 1e-10);
    assert!((law.pdf(&[1.0, 1.0]) - 2.0 / 1.25).abs() < 1e-10);
    let n = 100_000;
    let d = monte_carlo(&law, n, 9);
    let ea = d.iter().map(|x| x[0]).sum::<f64>() / n as f64;
    let eab = d.iter().map(|x| x[0] * x[1]).sum::<f64>() / n as f64;
    // std of a <= 0.3: 4.5 sigma = 0.0043
    assert!((ea - 8.0 / 15.0).abs() < 0.0043, "{ea}");
    assert!((eab - 13.0 / 45.0).abs() < 0.0043, "{eab}");
    for u in [[0.2, 0.7], [0.9, 0.05]] {
        let mut x = [0.0; 2];
        let mut back = [0.0; 2];
        law.unit_to_x(&u, &mut x);
        law.x_to_unit(&x, &mut back);
        assert!((u[0] - back[0]).abs() < 1e-12 && (u[1] - back[1]).abs() < 1e-12);
    }
    // Tabulated variant on a 3 x 3 grid of the same (multilinear) density.
    let vals: Vec<f64> = (0..9)
        .map(|k| 1.0 + (k / 3) as f64 * 0.5 * (k % 3) as f64 * 0.5)
        .collect();
    let tab = BoxDensity::from_grid(vec![0.0, 0.0], vec![1.0, 1.0], 3, vals).unwrap();
    assert!((tab.pdf(&[0.3, 0.8]) - law.pdf(&[0.3, 0.8])).abs() < 1e-10);
}

#[test]
fn independent_box_probability_is_exact() {
    let law = Independent::new(vec![
        Arc::new(Uniform::new(0.0, 4.0).unwrap()),
        Arc::new(Normal::new(0.0, 1.0).unwrap()),
    ])
    .unwrap();
    let p = law.box_probability(&[1.0, 0.0], &[2.0, f64::INFINITY]);
    assert!((p - 0.125).abs() < 1e-15);
}

/// The map from the standard normal space stays finite and non-decreasing in the far tails:
/// exact for normal (`m + s z`) and lognormal (`exp(mu + sigma z)`) marginals; a law unbounded
/// above (gamma) saturates at its quantile of `Phi(8.2)` where `Phi(z)` rounds to 1
/// (`z > 8.29`); the same through a Gaussian copula and the default map of the other copulas.
#[test]
fn the_standard_normal_map_is_finite_in_the_far_tails() {
    use alea_uq::copula::ClaytonCopula;
    use alea_uq::law::{Gamma, LogNormal, Normal};
    let normal: Arc<dyn Marginal> = Arc::new(Normal::new(2.0, 0.5).unwrap());
    let lognormal: Arc<dyn Marginal> = Arc::new(LogNormal::new(0.1, 0.2).unwrap());
    let gamma: Arc<dyn Marginal> = Arc::new(Gamma::new(2.0, 1.5, 0.0).unwrap());
    let marginals = vec![normal, lognormal, gamma];
    let independent = Independent::new(marginals.clone()).unwrap();
    let copula = GaussianCopula::new(
        marginals.clone(),
        vec![1.0, 0.3, 0.2, 0.3, 1.0, 0.1, 0.2, 0.1, 1.0],
    )
    .unwrap();
    let clayton = ClaytonCopula::new(marginals, 1.5).unwrap();
    let laws: [(&str, &dyn JointLaw); 3] = [
        ("independent", &independent),
        ("gaussian copula", &copula),
        ("clayton", &clayton),
    ];
    for (name, law) in laws {
        let mut last = [f64::NEG_INFINITY; 3];
        for z in [-12.0, -9.0, -5.0, 0.0, 5.0, 8.0, 8.3, 9.0, 12.0, 40.0] {
            let mut x = [0.0; 3];
            law.standard_normal_to_x(&[z, z, z], &mut x);
            for k in 0..3 {
                assert!(x[k].is_finite(), "{name}: z = {z}, x[{k}] = {}", x[k]);
                assert!(x[k] >= last[k], "{name}: z = {z}, x[{k}] decreased");
                last[k] = x[k];
            }
        }
    }
    let mut x = [0.0; 3];
    independent.standard_normal_to_x(&[12.0, 12.0, 12.0], &mut x);
    assert_eq!(x[0], 2.0 + 0.5 * 12.0);
    assert!((x[1] - (0.1f64 + 0.2 * 12.0).exp()).abs() < 1e-12 * x[1]);
}
