//! Karhunen-Loeve random fields against closed forms and exact statistics.
//!
//! Truth: the KL of the exponential kernel `k(x, y) = exp(-|x - y| / L)` on `[-a, a]`
//! (Ghanem & Spanos 1991, section 2.3.3), with `c = 1 / L`:
//! * even modes `cos(w x) / sqrt(a + sin(2 w a) / (2 w))`, `c - w tan(w a) = 0`;
//! * odd modes `sin(w x) / sqrt(a - sin(2 w a) / (2 w))`, `w + c tan(w a) = 0`;
//! * eigenvalues `lambda = 2 c / (w^2 + c^2) = 2 L / (1 + L^2 w^2)`.

use alea_uq::field::*;
use alea_uq::rng::{chunk_rng, open01};
use alea_uq::special::norm_quantile;

/// One closed-form eigenpair: frequency, eigenvalue, parity.
#[derive(Clone, Copy, Debug)]
struct Exact {
    w: f64,
    lambda: f64,
    even: bool,
}

fn bisect(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    let flo = f(lo);
    assert!(flo * f(hi) < 0.0, "no sign change in [{lo}, {hi}]");
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if (f(mid) > 0.0) == (flo > 0.0) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The `count` largest closed-form eigenpairs of the exponential kernel on `[-a, a]`.
fn exact_exponential_kl(a: f64, len: f64, count: usize) -> Vec<Exact> {
    let c = 1.0 / len;
    let pi = std::f64::consts::PI;
    let eps = 1e-12;
    let mut out = Vec::new();
    for i in 0..count {
        // Even: w a in (i pi, i pi + pi/2), f = c cos - w sin.
        let f = |w: f64| c * (w * a).cos() - w * (w * a).sin();
        let w = bisect(
            f,
            (i as f64 * pi + eps) / a,
            ((i as f64 + 0.5) * pi - eps) / a,
        );
        out.push(Exact {
            w,
            lambda: 2.0 * c / (w * w + c * c),
            even: true,
        });
        // Odd: w a in ((i + 1/2) pi, (i + 1) pi), f = w cos + c sin.
        let f = |w: f64| w * (w * a).cos() + c * (w * a).sin();
        let w = bisect(
            f,
            ((i as f64 + 0.5) * pi + eps) / a,
            ((i as f64 + 1.0) * pi - eps) / a,
        );
        out.push(Exact {
            w,
            lambda: 2.0 * c / (w * w + c * c),
            even: false,
        });
    }
    out.sort_by(|p, q| q.lambda.total_cmp(&p.lambda));
    out.truncate(count);
    out
}

fn exact_mode(e: &Exact, a: f64, x: f64) -> f64 {
    let s = (2.0 * e.w * a).sin() / (2.0 * e.w);
    if e.even {
        (e.w * x).cos() / (a + s).sqrt()
    } else {
        (e.w * x).sin() / (a - s).sqrt()
    }
}

fn kl_on(a: f64, len: f64, cells: usize, modes: usize) -> KlExpansion {
    let mesh = FieldMesh::interval(-a, a, cells).unwrap();
    let cov = Covariance::new(KernelShape::Exponential, 1.0, len).unwrap();
    KlExpansion::galerkin(&mesh, &cov, Truncation::Modes(modes)).unwrap()
}

fn max_rel_error(kl: &KlExpansion, exact: &[Exact]) -> f64 {
    kl.eigenvalues()
        .iter()
        .zip(exact)
        .map(|(l, e)| ((l - e.lambda) / e.lambda).abs())
        .fold(0.0, f64::max)
}

#[test]
fn exponential_eigenvalues_match_closed_form_at_20_modes_with_fourth_order_convergence() {
    let (a, len) = (1.0, 1.0);
    let exact = exact_exponential_kl(a, len, 20);
    let mut errors = Vec::new();
    // Galerkin eigenvalues of a compact self-adjoint operator converge as the square of the
    // eigenfunction error: h^(2 (p + 1)) = h^4 with P1.
    for cells in [50, 100, 200, 400] {
        let kl = kl_on(a, len, cells, 20);
        let err = max_rel_error(&kl, &exact);
        // Galerkin eigenvalues bound the exact ones from below (min-max principle).
        for (l, e) in kl.eigenvalues().iter().zip(&exact) {
            assert!(
                *l <= e.lambda * (1.0 + 1e-9),
                "{cells} cells: {l} above {}",
                e.lambda
            );
        }
        println!("cells {cells}: max relative eigenvalue error over 20 modes {err:.3e}");
        errors.push(err);
    }
    for w in errors.windows(2) {
        let rate = (w[0] / w[1]).log2();
        println!("rate {rate:.3}");
        assert!((3.7..4.5).contains(&rate), "convergence rate {rate}");
    }
    assert!(errors[1] < 1e-3, "error at 100 cells {}", errors[1]);
    assert!(errors[3] < 1e-6, "error at 400 cells {}", errors[3]);
}

#[test]
fn exponential_modes_match_closed_form_up_to_sign_and_are_mass_orthonormal() {
    let (a, len) = (1.0, 0.5);
    let cells = 400;
    let kl = kl_on(a, len, cells, 10);
    let exact = exact_exponential_kl(a, len, 10);
    let mesh = kl.mesh();
    for (k, e) in exact.iter().enumerate() {
        let truth: Vec<f64> = mesh
            .nodes()
            .iter()
            .map(|x| exact_mode(e, a, x[0]))
            .collect();
        let phi = kl.mode(k);
        let sign = mesh.l2_product(phi, &truth).signum();
        let diff: Vec<f64> = phi.iter().zip(&truth).map(|(p, t)| sign * p - t).collect();
        let l2 = mesh.l2_product(&diff, &diff).sqrt();
        println!("mode {k}: L2 error {l2:.3e}");
        assert!(l2 < 2e-3 * (1.0 + e.w), "mode {k}: L2 error {l2}");
        for l in 0..=k {
            let g = mesh.l2_product(phi, kl.mode(l));
            let delta = if l == k { 1.0 } else { 0.0 };
            assert!((g - delta).abs() < 1e-10, "<phi_{k}, phi_{l}> = {g}");
        }
    }
}

#[test]
fn exponential_modes_converge_at_second_order_in_l2() {
    let (a, len) = (1.0, 0.5);
    let exact = exact_exponential_kl(a, len, 10);
    let err = |cells: usize| -> f64 {
        let kl = kl_on(a, len, cells, 10);
        let mesh = kl.mesh();
        let e = &exact[9];
        let truth: Vec<f64> = mesh
            .nodes()
            .iter()
            .map(|x| exact_mode(e, a, x[0]))
            .collect();
        let sign = mesh.l2_product(kl.mode(9), &truth).signum();
        let diff: Vec<f64> = kl
            .mode(9)
            .iter()
            .zip(&truth)
            .map(|(p, t)| sign * p - t)
            .collect();
        mesh.l2_product(&diff, &diff).sqrt()
    };
    let (e1, e2) = (err(100), err(200));
    let rate = (e1 / e2).log2();
    println!("mode 10 L2 error: {e1:.3e} (100 cells), {e2:.3e} (200 cells), rate {rate:.3}");
    assert!((1.8..2.3).contains(&rate), "rate {rate}");
}

#[test]
fn variance_fraction_truncation_keeps_the_fewest_modes_reaching_the_fraction() {
    let (a, len) = (1.0, 0.5);
    let mesh = FieldMesh::interval(-a, a, 400).unwrap();
    let cov = Covariance::new(KernelShape::Exponential, 2.5, len).unwrap();
    let exact = exact_exponential_kl(a, len, 60);
    let total = 2.5 * 2.0 * a;
    for f in [0.5, 0.8, 0.9, 0.95] {
        let kl = KlExpansion::galerkin(&mesh, &cov, Truncation::VarianceFraction(f)).unwrap();
        let m = kl.num_modes();
        assert!((kl.total_variance() - total).abs() < 1e-12 * total);
        assert!(kl.captured_fraction() >= f);
        let without_last: f64 = kl.eigenvalues()[..m - 1].iter().sum();
        assert!(
            without_last < f * total,
            "fraction {f}: {m} modes, one too many"
        );
        // Same count as the closed form (eigenvalues scale with the variance).
        let mut acc = 0.0;
        let m_exact = exact.iter().position(|e| {
            acc += 2.5 * e.lambda;
            acc >= f * total
        });
        println!(
            "fraction {f}: {m} modes (closed form {:?}), captured {:.4}",
            m_exact.map(|p| p + 1),
            kl.captured_fraction()
        );
        assert_eq!(Some(m), m_exact.map(|p| p + 1), "fraction {f}");
    }
    // Unreachable fractions and bad settings are errors, not panics.
    assert!(
        KlExpansion::galerkin(
            &FieldMesh::interval(-a, a, 4).unwrap(),
            &cov,
            Truncation::VarianceFraction(0.999)
        )
        .is_err()
    );
    assert!(KlExpansion::galerkin(&mesh, &cov, Truncation::VarianceFraction(1.5)).is_err());
    assert!(KlExpansion::galerkin(&mesh, &cov, Truncation::Modes(0)).is_err());
    assert!(KlExpansion::galerkin(&mesh, &cov, Truncation::Modes(402)).is_err());
}

/// Standard normal sample from a seeded stream.
fn normals(seed: u64, n: usize) -> Vec<f64> {
    let mut rng = chunk_rng(seed, 0);
    (0..n).map(|_| norm_quantile(open01(&mut rng))).collect()
}

#[test]
fn empirical_covariance_of_realisations_matches_the_truncated_kernel() {
    let mesh = FieldMesh::interval(0.0, 4.0, 80).unwrap();
    let sigma = 0.3;
    let cov = Covariance::new(KernelShape::Matern52, sigma * sigma, 1.0).unwrap();
    let kl = KlExpansion::galerkin(&mesh, &cov, Truncation::VarianceFraction(0.99)).unwrap();
    let m = kl.num_modes();
    let n = mesh.num_nodes();
    let samples = 20_000;
    let xi = normals(11, samples * m);
    let mean = 1.5;
    let pairs = [(0, 0), (40, 40), (0, 10), (20, 30), (40, 60), (5, 75)];
    let mut sum = vec![0.0; n];
    let mut prod = vec![0.0; pairs.len()];
    let mut g = vec![0.0; n];
    let mut all = Vec::with_capacity(samples);
    for s in 0..samples {
        kl.realise(mean, &xi[s * m..(s + 1) * m], &mut g).unwrap();
        for (a, v) in sum.iter_mut().zip(&g) {
            *a += v;
        }
        all.push(g.clone());
    }
    let avg: Vec<f64> = sum.iter().map(|s| s / samples as f64).collect();
    for g in &all {
        for (p, &(i, j)) in pairs.iter().enumerate() {
            prod[p] += (g[i] - avg[i]) * (g[j] - avg[j]);
        }
    }
    for (p, &(i, j)) in pairs.iter().enumerate() {
        let emp = prod[p] / (samples - 1) as f64;
        let truncated = kl.truncated_covariance(i, j);
        let var_i = kl.truncated_covariance(i, i);
        let var_j = kl.truncated_covariance(j, j);
        // Standard error of a sample covariance of Gaussians: sqrt((s_ij^2 + s_ii s_jj) / N).
        let se = ((truncated * truncated + var_i * var_j) / samples as f64).sqrt();
        let kernel = cov.eval(&mesh.nodes()[i], &mesh.nodes()[j]);
        println!(
            "({i}, {j}): empirical {emp:.5}, truncated {truncated:.5} +- {se:.1e}, kernel {kernel:.5}"
        );
        assert!(
            (emp - truncated).abs() < 4.0 * se,
            "({i},{j}): {emp} vs {truncated}"
        );
        // 99 % of the variance kept: the truncated kernel is close to the kernel.
        assert!(
            (truncated - kernel).abs() < 0.05 * sigma * sigma,
            "({i},{j}): {truncated} vs {kernel}"
        );
    }
    for (i, a) in avg.iter().enumerate() {
        let se = (kl.truncated_covariance(i, i) / samples as f64).sqrt();
        assert!((a - mean).abs() < 4.5 * se, "mean at node {i}: {a}");
    }
}

#[test]
fn transforms_map_the_gaussian_field_pointwise() {
    let mesh = FieldMesh::interval(0.0, 1.0, 20).unwrap();
    let (m, var) = lognormal_gaussian_parameters(0.3, 0.05).unwrap();
    // Exact lognormal moments of exp(N(m, var)).
    assert!(((m + 0.5 * var).exp() - 0.3).abs() < 1e-14);
    assert!((((var.exp() - 1.0) * (2.0 * m + var).exp()).sqrt() - 0.05).abs() < 1e-14);
    let cov = Covariance::new(KernelShape::SquaredExponential, var, 0.3).unwrap();
    let kl = KlExpansion::galerkin(&mesh, &cov, Truncation::Modes(4)).unwrap();
    let xi = [0.7, -1.2, 0.4, 2.0];
    let mut g = vec![0.0; 21];
    kl.realise(m, &xi, &mut g).unwrap();
    let logn = RandomField::new(m, var.sqrt(), FieldTransform::Lognormal, kl.clone()).unwrap();
    for (u, v) in logn.at_nodes(&xi).unwrap().iter().zip(&g) {
        assert!((u - v.exp()).abs() < 1e-14);
    }
    let bounded = FieldTransform::Bounded {
        lower: 0.1,
        upper: 0.4,
    };
    let b = RandomField::new(m, var.sqrt(), bounded, kl.clone()).unwrap();
    for (u, v) in b.at_nodes(&xi).unwrap().iter().zip(&g) {
        assert!(*u > 0.1 && *u < 0.4);
        let z = (v - m) / var.sqrt();
        assert!((u - (0.1 + 0.3 * alea_uq::special::norm_cdf(z))).abs() < 1e-14);
    }
    // At xi = 0 the bounded field sits at the middle of its interval.
    assert!(
        b.at_nodes(&[0.0; 4])
            .unwrap()
            .iter()
            .all(|u| (u - 0.25).abs() < 1e-14)
    );
    assert!(
        RandomField::new(
            m,
            1.0,
            FieldTransform::Bounded {
                lower: 1.0,
                upper: 1.0
            },
            kl.clone()
        )
        .is_err()
    );
    assert!(logn.at_nodes(&[0.0; 3]).is_err());
    assert!(logn.at_nodes(&[f64::NAN, 0.0, 0.0, 0.0]).is_err());
}

#[test]
fn covariance_models_and_mesh_checks() {
    let x = [0.0, 0.0, 0.0];
    let y = [0.6, 0.8, 0.0];
    let r: f64 = 1.0 / 2.0; // |x - y| = 1, length 2
    let cases = [
        (KernelShape::SquaredExponential, (-0.5 * r * r).exp()),
        (KernelShape::Exponential, (-r).exp()),
        (
            KernelShape::Matern32,
            (1.0 + 3f64.sqrt() * r) * (-(3f64.sqrt()) * r).exp(),
        ),
        (
            KernelShape::Matern52,
            (1.0 + 5f64.sqrt() * r + 5.0 * r * r / 3.0) * (-(5f64.sqrt()) * r).exp(),
        ),
    ];
    for (shape, rho) in cases {
        let c = Covariance::new(shape, 4.0, 2.0).unwrap();
        assert!((c.eval(&x, &y) - 4.0 * rho).abs() < 1e-14);
        assert!((c.eval(&x, &x) - 4.0).abs() < 1e-15);
    }
    assert_eq!(KernelShape::matern(1.5).unwrap(), KernelShape::Matern32);
    assert!(KernelShape::matern(1.0).is_err());
    // Anisotropic: lengths (0.6, 0.8) make the scaled distance sqrt(2).
    let c = Covariance::anisotropic(KernelShape::Exponential, 1.0, &[0.6, 0.8]).unwrap();
    assert!((c.scaled_distance(&x, &y) - 2f64.sqrt()).abs() < 1e-14);
    assert!(Covariance::new(KernelShape::Exponential, -1.0, 1.0).is_err());
    assert!(Covariance::new(KernelShape::Exponential, 1.0, 0.0).is_err());
    assert!(Covariance::anisotropic(KernelShape::Exponential, 1.0, &[]).is_err());
    // Mesh checks.
    let nodes = vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
    assert!(FieldMesh::new(nodes.clone(), FieldCells::Segments(vec![[0, 1]])).is_err()); // node 2 unused
    assert!(FieldMesh::new(nodes.clone(), FieldCells::Segments(vec![[0, 1], [1, 3]])).is_err());
    assert!(
        FieldMesh::new(
            nodes.clone(),
            FieldCells::Segments(vec![[0, 1], [1, 1], [1, 2]])
        )
        .is_err()
    );
    assert!(FieldMesh::new(nodes.clone(), FieldCells::Triangles(vec![[0, 1, 2]])).is_err()); // flat
    let m = FieldMesh::new(nodes, FieldCells::Segments(vec![[0, 1], [1, 2]])).unwrap();
    let mass = m.mass_matrix();
    let ones = vec![1.0; 3];
    // int 1 = |D|, and the dense and cell-wise products agree.
    assert!((mass.iter().sum::<f64>() - 2.0).abs() < 1e-15);
    assert!((m.l2_product(&ones, &ones) - 2.0).abs() < 1e-15);
}

/// On a triangulated square the trace of the discrete operator approaches sigma^2 |D|, the modes
/// are mass-orthonormal, and the leading eigenvalues of the separable squared-exponential kernel
/// are products of the 1D ones.
#[test]
fn triangles_capture_the_trace_and_modes_are_orthonormal() {
    let k = 12;
    let mut nodes = Vec::new();
    for j in 0..=k {
        for i in 0..=k {
            nodes.push([i as f64 / k as f64, j as f64 / k as f64, 0.0]);
        }
    }
    let id = |i: usize, j: usize| j * (k + 1) + i;
    let mut tris = Vec::new();
    for j in 0..k {
        for i in 0..k {
            tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let mesh = FieldMesh::new(nodes, FieldCells::Triangles(tris)).unwrap();
    assert!((mesh.measure() - 1.0).abs() < 1e-14);
    let cov = Covariance::new(KernelShape::SquaredExponential, 1.0, 0.5).unwrap();
    let kl = KlExpansion::galerkin(&mesh, &cov, Truncation::VarianceFraction(0.95)).unwrap();
    // Smooth kernel: the discrete trace is within the P1 interpolation error of sigma^2 |D|.
    let trace = kl.discrete_variance() / kl.total_variance();
    println!(
        "triangles: {} modes for 95 %, discrete trace {trace:.5}",
        kl.num_modes()
    );
    assert!(
        trace > 0.99 && trace <= 1.0 + 1e-9,
        "trace fraction {trace}"
    );
    for a in 0..kl.num_modes() {
        for b in 0..=a {
            let g = mesh.l2_product(kl.mode(a), kl.mode(b));
            assert!((g - if a == b { 1.0 } else { 0.0 }).abs() < 1e-10);
        }
    }
    // Separable kernel on the unit square: eigenvalues are products of 1D eigenvalues; the
    // largest is the square of the largest 1D one.
    let line = KlExpansion::galerkin(
        &FieldMesh::interval(0.0, 1.0, 200).unwrap(),
        &cov,
        Truncation::Modes(3),
    )
    .unwrap();
    let l1 = line.eigenvalues();
    let expect = [l1[0] * l1[0], l1[0] * l1[1], l1[0] * l1[1]];
    for (got, want) in kl.eigenvalues().iter().zip(expect) {
        println!("2D eigenvalue {got:.6} vs product of 1D {want:.6}");
        assert!((got - want).abs() < 5e-3 * want, "{got} vs {want}");
    }
}

/// The nodal-interpolation formulation (`C = M K M`, OpenTURNS's `KarhunenLoeveP1Algorithm`)
/// converges at second order only, and stays below the quadrature one's accuracy.
#[test]
fn nodal_interpolation_converges_at_second_order() {
    let (a, len) = (1.0, 1.0);
    let exact = exact_exponential_kl(a, len, 20);
    let cov = Covariance::new(KernelShape::Exponential, 1.0, len).unwrap();
    let err = |cells: usize, integration: KernelIntegration| {
        let mesh = FieldMesh::interval(-a, a, cells).unwrap();
        let kl =
            KlExpansion::galerkin_with(&mesh, &cov, Truncation::Modes(20), integration).unwrap();
        max_rel_error(&kl, &exact)
    };
    let (e1, e2) = (
        err(100, KernelIntegration::NodalInterpolation),
        err(200, KernelIntegration::NodalInterpolation),
    );
    let rate = (e1 / e2).log2();
    println!("nodal interpolation: {e1:.3e} (100 cells), {e2:.3e} (200 cells), rate {rate:.3}");
    assert!((1.8..2.3).contains(&rate), "rate {rate}");
    assert!(err(100, KernelIntegration::Quadrature) < 0.05 * e1);
}

/// Same mesh and kernel: bit-identical eigenpairs whatever the number of threads.
#[test]
fn expansion_does_not_depend_on_the_thread_count() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| kl_on(1.0, 0.7, 300, 15))
    };
    let (one, two) = (run(1), run(2));
    assert_eq!(one.eigenvalues(), two.eigenvalues());
    for k in 0..15 {
        assert_eq!(one.mode(k), two.mode(k));
    }
}

/// The unit cube split into `n^3` boxes of 6 tetrahedra each (Kuhn's split along each box's
/// main diagonal).
fn cube_tetrahedra(n: usize) -> FieldMesh {
    let id = |i: usize, j: usize, k: usize| (k * (n + 1) + j) * (n + 1) + i;
    let mut nodes = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                nodes.push([
                    i as f64 / n as f64,
                    j as f64 / n as f64,
                    k as f64 / n as f64,
                ]);
            }
        }
    }
    let mut tets = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let c = |di: usize, dj: usize, dk: usize| id(i + di, j + dj, k + dk);
                // Paths from (0,0,0) to (1,1,1) one axis at a time: the 6 Kuhn tetrahedra.
                for order in [
                    [0, 1, 2],
                    [0, 2, 1],
                    [1, 0, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [2, 1, 0],
                ] {
                    let mut d = [0usize; 3];
                    let mut t = [c(0, 0, 0); 4];
                    for (s, &axis) in order.iter().enumerate() {
                        d[axis] = 1;
                        t[s + 1] = c(d[0], d[1], d[2]);
                    }
                    tets.push(t);
                }
            }
        }
    }
    FieldMesh::new(nodes, FieldCells::Tetrahedra(tets)).unwrap()
}

/// Tetrahedra: the squared-exponential kernel is separable, `k(x, y) = prod_d k1(x_d, y_d)`, so
/// its KL on the unit cube has the eigenvalues `lambda_i lambda_j lambda_k` of the 1D kernel on
/// `[0, 1]` (here from a 400-cell 1D Galerkin KL, itself `O(h^4)`-accurate). The tetrahedral
/// Galerkin KL converges to them (error falling at least 8x per halving of h: measured 9.7e-3
/// and 3.9e-4 over the 8 largest at 3 and 6 boxes per side), the mesh has
/// volume 1, the modes are mass-orthonormal and the trace of `C` is `sigma^2 |D|`.
#[test]
fn tetrahedra_match_the_separable_product_of_1d_eigenvalues() {
    let len = 0.5;
    let cov = Covariance::new(KernelShape::SquaredExponential, 1.0, len).unwrap();
    let line = FieldMesh::interval(0.0, 1.0, 400).unwrap();
    let l1 = KlExpansion::galerkin(&line, &cov, Truncation::Modes(4)).unwrap();
    let e1 = l1.eigenvalues();
    let mut exact: Vec<f64> = Vec::new();
    for a in 0..4 {
        for b in 0..4 {
            for c in 0..4 {
                exact.push(e1[a] * e1[b] * e1[c]);
            }
        }
    }
    exact.sort_by(|x, y| y.total_cmp(x));
    let compare = 8;
    let mut errors = Vec::new();
    for n in [3, 6] {
        let mesh = cube_tetrahedra(n);
        assert!((mesh.measure() - 1.0).abs() < 1e-12);
        let kl = KlExpansion::galerkin(&mesh, &cov, Truncation::Modes(compare)).unwrap();
        let err = kl
            .eigenvalues()
            .iter()
            .zip(&exact)
            .map(|(l, e)| ((l - e) / e).abs())
            .fold(0.0f64, f64::max);
        eprintln!(
            "tetrahedra n = {n}: {} nodes, max relative eigenvalue error over {compare} modes {err:e}",
            mesh.num_nodes()
        );
        // Mass-orthonormal modes.
        for i in 0..3 {
            for j in 0..3 {
                let g = mesh.l2_product(kl.mode(i), kl.mode(j));
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((g - want).abs() < 1e-9, "({i}, {j}): {g}");
            }
        }
        assert!((kl.total_variance() - 1.0).abs() < 1e-12);
        errors.push(err);
    }
    assert!(errors[1] < 1e-3, "{errors:?}");
    assert!(errors[1] < errors[0] / 8.0, "{errors:?}");
}
