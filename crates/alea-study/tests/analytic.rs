//! End to end against exact statistics: a plate in uniaxial tension (plane stress, nu = 0) with
//! the traction scaled by a random load factor `P ~ N(1, 0.1^2)` and a random Young's modulus
//! `E ~ U(150e3, 250e3)` MPa. The tip displacement is exactly `u = P s L / E` (a linear field,
//! reproduced exactly by the elements), so
//! `E[u] = s L E[P] ln(b/a)/(b - a)`, `E[u^2] = s^2 L^2 E[P^2] / (a b)`, and
//! `P(u > t) = int_a^b (1 - Phi((t E/(s L) - 1)/0.1)) dE / (b - a)`.
//! The study runs a degree-4 PC regression, Monte Carlo on it, a KDE and a failure probability;
//! each must match within its Monte Carlo confidence interval (plus a small surrogate error).

use alea_study::Source;
use alea_study::analysis::{AnalysisSettings, analyse_method};
use alea_study::runner::{NoProgress, Study, run_study};
use alea_uq::kde::Bandwidth;

const STUDY: &str = r#"
[study]
title = "plate with random E and load"
seed = 7

[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [100.0, 20.0]
cells = [10, 2]

[analysis]
type = "plane_stress"
thickness = 1.0

[[parameter]]
name = "E"
law = "uniform"
lo = 150e3
hi = 250e3

[[parameter]]
name = "P"
law = "normal"
mean = 1.0
std = 0.1

[[substructure]]
name = "plate"
young = "E"
poisson = 0.0
constraint = [ { group = "xmin", x = 0.0 }, { group = "ymin", y = 0.0 } ]
load = [ { group = "xmax", traction = [200.0, 0.0], factor = "P" } ]

[[quantity]]
name = "tip"
kind = "displacement"
substructure = "plate"
point = [100.0, 20.0]
component = 0
unit = "mm"
thresholds = [0.13]

[[method]]
type = "pc_regression"
degree = 4
design = "lhs"
runs = 40

[[method]]
type = "monte_carlo"
runs = 400
"#;

fn norm_cdf(x: f64) -> f64 {
    // Abramowitz-Stegun 7.1.26 is too coarse; use erfc via a continued fraction-free series.
    0.5 * erfc(-x / std::f64::consts::SQRT_2)
}

fn erfc(x: f64) -> f64 {
    // Numerical Recipes erfcc (fractional error < 1.2e-7).
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let r = t
        * (-z * z - 1.26551223
            + t * (1.00002368
                + t * (0.37409196
                    + t * (0.09678418
                        + t * (-0.18628806
                            + t * (0.27886807
                                + t * (-1.13520398
                                    + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))))
            .exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

#[test]
fn pc_and_monte_carlo_match_the_exact_law() {
    let study = Study::from_source(Source::from_text("analytic.toml", STUDY)).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-analytic-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    // 40 + 400 design runs and 10 validation runs (a quarter of the chaos design).
    assert_eq!(runs.records.len(), 450);
    assert!(runs.records.iter().all(|r| r.converged()));
    let (a, b, s, l): (f64, f64, f64, f64) = (150e3, 250e3, 200.0, 100.0);
    // Each run is exact: u = P s L / E.
    for r in &runs.records {
        let exact = r.params[1] * s * l / r.params[0];
        assert!(
            (r.qois[0] - exact).abs() < 1e-9 * exact,
            "run at {:?}: {} vs {exact}",
            r.params,
            r.qois[0]
        );
    }
    let mean = s * l * (b / a).ln() / (b - a);
    let m2 = s * s * l * l * (1.0 + 0.01) / (a * b);
    let std = (m2 - mean * mean).sqrt();
    // Exact failure probability by quadrature over E.
    let t = 0.13;
    let n = 20000;
    let pf: f64 = (0..n)
        .map(|i| {
            let e = a + (b - a) * (i as f64 + 0.5) / n as f64;
            1.0 - norm_cdf((t * e / (s * l) - 1.0) / 0.1)
        })
        .sum::<f64>()
        / n as f64;
    let settings = AnalysisSettings {
        samples: 200_000,
        bandwidth: Bandwidth::Isj,
        kde_points: 256,
        confidence: 0.95,
    };
    for (m, method) in study.methods.iter().enumerate() {
        let res = analyse_method(&study, method, &runs.records, &settings);
        assert!(res.account.error.is_none(), "{:?}", res.account.error);
        let q = &res.qois[0];
        let n = res.draws as f64;
        let se_mean = std / n.sqrt();
        let se_std = std / (2.0 * n).sqrt() * 1.2;
        let se_pf = (pf * (1.0 - pf) / n).sqrt();
        let slack = if m == 0 { 1e-4 * mean } else { 0.0 }; // surrogate error of the PC
        eprintln!(
            "{}: mean {} (exact {mean}), std {} (exact {std}), pf {} (exact {pf})",
            res.account.label, q.distribution.mean, q.distribution.std, q.failure[0].probability
        );
        assert!(
            (q.distribution.mean - mean).abs() < 4.0 * se_mean + slack,
            "{}: mean {} vs {mean}",
            res.account.label,
            q.distribution.mean
        );
        assert!(
            (q.distribution.std - std).abs() < 4.0 * se_std + slack,
            "{}: std {} vs {std}",
            res.account.label,
            q.distribution.std
        );
        let f = &q.failure[0];
        assert!(
            (f.probability - pf).abs() < 4.0 * se_pf + 2e-3 * (m == 0) as u8 as f64,
            "{}: pf {} vs {pf}",
            res.account.label,
            f.probability
        );
        assert!(f.ci_low <= f.probability && f.probability <= f.ci_high);
        if m == 0 {
            // The KDE integrates to 1 and follows the exact density of u = P s L / E:
            // f(u) = int f_E(e) f_P(u e/(s L)) e/(s L) de.
            let h = q.distribution.kde[1].0 - q.distribution.kde[0].0;
            let total: f64 = q.distribution.kde.iter().map(|p| p.1).sum::<f64>() * h;
            assert!((total - 1.0).abs() < 1e-3, "KDE integral {total}");
            let exact_pdf = |u: f64| {
                let k = 4000;
                (0..k)
                    .map(|i| {
                        let e = a + (b - a) * (i as f64 + 0.5) / k as f64;
                        let p = u * e / (s * l);
                        let fp = (-(p - 1.0).powi(2) / (2.0 * 0.01)).exp()
                            / (0.1 * (2.0 * std::f64::consts::PI).sqrt());
                        fp * e / (s * l) / (b - a)
                    })
                    .sum::<f64>()
                    * (b - a)
                    / k as f64
            };
            let l1: f64 = q
                .distribution
                .kde
                .iter()
                .map(|&(u, p)| (p - exact_pdf(u)).abs())
                .sum::<f64>()
                * h;
            assert!(l1 < 0.03, "KDE L1 distance to the exact density {l1}");
        }
    }
    // Resuming an identical study recomputes nothing (once the first invocation has released
    // the study directory's lock: a second holder is refused, even in the same process).
    match run_study(&study, &dir, false, &NoProgress) {
        Err(busy) => assert_eq!(busy.exit_code(), 5, "{busy}"),
        Ok(_) => panic!("a second holder of the study directory must be refused"),
    }
    drop(runs.lock);
    let again = run_study(&study, &dir, false, &NoProgress).unwrap();
    assert_eq!(again.computed, 0);
    assert_eq!(again.resumed, 450);
    assert_eq!(again.records, runs.records);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn per_run_paraview_files_on_request() {
    let text = STUDY.replace("runs = 400", "runs = 3").replace(
        "degree = 4\ndesign = \"lhs\"\nruns = 40",
        "degree = 1\ndesign = \"lhs\"\nruns = 4",
    ) + "\n[output]\nvtu = true\n";
    let study = Study::from_source(Source::from_text("vtu.toml", &text)).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-vtu-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    // 4 + 3 design runs and 5 validation runs, each with its ParaView file.
    assert_eq!(runs.records.len(), 12);
    let vtm: Vec<_> = std::fs::read_dir(dir.join("vtu"))
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().extension().is_some_and(|x| x == "vtm"))
        .collect();
    assert_eq!(vtm.len(), 12);
    for e in vtm {
        let part = e.path().with_extension("").join("plate.vtu");
        let xml = std::fs::read_to_string(&part).unwrap();
        assert!(xml.contains("Name=\"displacement\"") && xml.contains("Name=\"von_mises\""));
        assert!(!xml.contains("NaN"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn mean_and_std_fields_agree_with_the_scalar_statistics() {
    // The tip displacement is both a quantity of interest and a node of the field: the field
    // statistics (weight moments on the same draws) must equal the scalar ones.
    let text = STUDY.replace("runs = 400", "runs = 3");
    let study = Study::from_source(Source::from_text("fields.toml", &text)).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-fields-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let settings = AnalysisSettings {
        samples: 50_000,
        bandwidth: Bandwidth::Silverman,
        kde_points: 64,
        confidence: 0.95,
    };
    let res = analyse_method(&study, &study.methods[0], &runs.records, &settings);
    let q = &res.qois[0];
    let fields = alea_study::fields::mean_std_fields(&study, &runs, &dir, 0, &res.points).unwrap();
    let model = runs.solver.model(0);
    let tip = (0..model.mesh.num_nodes())
        .find(|&n| {
            (model.mesh.coords[n][0] - 100.0).abs() < 1e-9
                && (model.mesh.coords[n][1] - 20.0).abs() < 1e-9
        })
        .unwrap();
    let (m, s) = (
        fields[0].displacement_mean[2 * tip],
        fields[0].displacement_std[2 * tip],
    );
    assert!(
        (m - q.distribution.mean).abs() < 1e-9 * q.distribution.mean.abs(),
        "mean {m} vs {}",
        q.distribution.mean
    );
    // Population vs sample variance: a factor sqrt(n / (n - 1)).
    assert!(
        (s - q.distribution.std).abs() < 1e-4 * q.distribution.std,
        "std {s} vs {}",
        q.distribution.std
    );
    // Uniaxial stress s = P * 200 MPa everywhere: von Mises mean = 200 E[P] = 200, std = 20.
    let vm_mean = &fields[0].von_mises_mean;
    let vm_std = &fields[0].von_mises_std;
    for n in 0..model.mesh.num_nodes() {
        assert!((vm_mean[n] - 200.0).abs() < 1.0, "node {n}: {}", vm_mean[n]);
        assert!((vm_std[n] - 20.0).abs() < 0.5, "node {n}: {}", vm_std[n]);
    }
    let path =
        alea_study::fields::write_mean_std_fields(&study, &runs, &dir, 0, &res.points).unwrap();
    assert!(path.exists() && dir.join("paraview/mean_std/plate.vtu").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
