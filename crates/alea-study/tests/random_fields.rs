//! Random fields along the contact (`[[field]]`, module `random_field`) on the simple blade
//! root of `examples/blade-root-simple-field.toml`, its mesh coarsened 3 times (about 1 300
//! dof):
//!
//! - one perfectly correlated mode (correlation length 1e6 mm on 14 mm flanks) is the constant
//!   friction coefficient `mean + std xi` at every interface point, and its run is the run of
//!   the constant-mu study (`examples/blade-root-simple.toml`) at that mu;
//! - at the mean field (every KL variable 0) the run is the deterministic run at the mean mu and
//!   the mean gap, value for value;
//! - the KL variables carry `sum_k lambda_k` of the variance, at least the stated fraction of
//!   `sigma^2 |D|` and with one mode fewer below it, measured through the study's own profiles;
//! - every bad `[[field]]` setting is refused at load with the file, the line and the field.

use alea_latin::LatinSolver;
use alea_study::Source;
use alea_study::runner::Study;

const FINE: &str = "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27";
const COARSE: &str = "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9";

/// The example's text on the coarse mesh, with `edits` (`from`, `to`) applied in order (each
/// to the first occurrence).
fn text(file: &str, edits: &[(&str, &str)]) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(file);
    let mut t = std::fs::read_to_string(path).unwrap().replace(FINE, COARSE);
    for (from, to) in edits {
        assert!(t.contains(from), "{from}");
        t = t.replacen(from, to, 1);
    }
    t
}

fn load(file: &str, edits: &[(&str, &str)]) -> Study {
    Study::from_source(Source::from_text(file, &text(file, edits))).unwrap()
}

/// Every quantity of one run at `theta`, and the friction coefficients and gaps the run was
/// given at the points of each interface.
fn run(study: &Study, theta: &[f64]) -> (Vec<f64>, Vec<Vec<(f64, f64)>>) {
    let solver =
        LatinSolver::new(study.model.assembly.clone(), study.model.options.clone()).unwrap();
    let input = study.model.parametric.run_input(theta);
    let inputs = (0..solver.num_interfaces())
        .map(|i| {
            solver
                .interface_points(i)
                .iter()
                .map(|p| {
                    (
                        input.mu[i].as_ref().unwrap()(p.x),
                        input.gap[i].as_ref().unwrap()(p.x),
                    )
                })
                .collect()
        })
        .collect();
    let res = solver.run_shared(&input).unwrap();
    assert_eq!(res.status, alea_latin::RunStatus::Converged);
    let q = study
        .qois
        .iter()
        .map(|q| q.eval(&solver, &res).unwrap())
        .collect();
    (q, inputs)
}

/// The example's adaptive method left out (its stochastic mesh and the error estimate take at
/// most 6 parameters).
const NO_ADAPTIVE: (&str, &str) = (
    "[[method]]\ntype = \"adaptive\"\nmax_runs = 40\nlabel = \"adaptive\"\n",
    "",
);

const PERFECT: &str = r#"covariance = "squared_exponential"
correlation_length = 1e6
transform = "gaussian"
mean = 0.5
std = 0.1
modes = 1"#;

const EXAMPLE_FIELD: &str = r#"covariance = "squared_exponential"
correlation_length = 10.0
transform = "bounded"
lower = 0.3
upper = 0.7
variance_fraction = 0.9"#;

#[test]
fn one_perfectly_correlated_mode_is_the_constant_mu_study() {
    let field = load(
        "blade-root-simple-field.toml",
        &[(EXAMPLE_FIELD, PERFECT), (EXAMPLE_FIELD, PERFECT)],
    );
    assert_eq!(field.params.names, ["MU_G1_1", "MU_G2_1"]);
    let constant = load("blade-root-simple.toml", &[]);
    let xi = 1.5;
    let (q_field, inputs) = run(&field, &[xi, xi]);
    // The single mode is constant: sqrt(lambda) phi = +-sigma (its sign is the eigensolver's).
    let mut mus = Vec::new();
    for (i, pts) in inputs.iter().enumerate() {
        let mu = pts[0].0;
        assert!(
            (mu - 0.65).abs() < 1e-9 || (mu - 0.35).abs() < 1e-9,
            "interface {i}: mu = {mu}"
        );
        assert!(pts.iter().all(|p| (p.0 - mu).abs() < 1e-9), "{pts:?}");
        mus.push(mu);
    }
    // Both flanks have mirror meshes and the same kernel, so the same mode and sign.
    assert!((mus[0] - mus[1]).abs() < 1e-12, "{mus:?}");
    let (q_const, _) = run(&constant, &[240e3, mus[0]]);
    for (k, (a, b)) in q_field.iter().zip(&q_const).enumerate() {
        let name = &field.qois[k].name;
        assert!(
            (a - b).abs() <= 1e-6 * b.abs().max(1e-3),
            "{name}: field {a}, constant {b}"
        );
    }
}

#[test]
fn the_mean_field_gives_the_deterministic_run() {
    // mu a bounded field on each flank, and a Gaussian field of mean 0 added to G2's gap.
    let gap_field = r#"
[[field]]
name = "DG"
interface = "G2"
covariance = "exponential"
correlation_length = 3.0
mean = 0.0
std = 0.002
modes = 3
"#;
    let field = load(
        "blade-root-simple-field.toml",
        &[
            (
                "[[substructure]]",
                &format!("{gap_field}\n[[substructure]]"),
            ),
            NO_ADAPTIVE,
            (
                "mu = \"MU_G2\"\ngap = \"max(0, 2.414 - s)^2 / 2\"",
                "mu = \"MU_G2\"\ngap = \"max(0, 2.414 - s)^2 / 2 + DG\"",
            ),
        ],
    );
    let d = field.params.names.len();
    assert_eq!(field.params.fields.len(), 3);
    assert_eq!(&field.params.names[d - 3..], ["DG_1", "DG_2", "DG_3"]);
    assert!(field.params.nominal.iter().all(|&v| v == 0.0));
    let constant = load("blade-root-simple.toml", &[]);
    let (q_field, in_field) = run(&field, &vec![0.0; d]);
    let (q_const, in_const) = run(&constant, &[240e3, 0.5]);
    assert_eq!(in_field, in_const);
    assert!(in_field.iter().flatten().all(|p| p.0 == 0.5));
    for (a, b) in q_field.iter().zip(&q_const) {
        assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
    }
    // Away from the mean the gap moves, by at most a few standard deviations of the field.
    let mut theta = vec![0.0; d];
    theta[d - 3..].copy_from_slice(&[1.0, -1.0, 0.5]);
    let input = field.model.parametric.run_input(&theta);
    let solver =
        LatinSolver::new(field.model.assembly.clone(), field.model.options.clone()).unwrap();
    let mut moved = 0.0f64;
    for (p, nominal) in solver.interface_points(1).iter().zip(&in_field[1]) {
        let dg = input.gap[1].as_ref().unwrap()(p.x) - nominal.1;
        moved = moved.max(dg.abs());
    }
    assert!(moved > 1e-4 && moved < 5.0 * 0.002 * 3f64.sqrt(), "{moved}");
}

#[test]
fn kl_variables_carry_the_truncated_fraction_of_the_variance() {
    // A Gaussian field (linear in the KL variables): mu(e_k) - mu(0) = sqrt(lambda_k) phi_k.
    let gaussian = r#"covariance = "exponential"
correlation_length = 5.0
transform = "gaussian"
mean = 0.5
std = 0.05
variance_fraction = 0.8"#;
    let study = load(
        "blade-root-simple-field.toml",
        &[
            (EXAMPLE_FIELD, gaussian),
            (EXAMPLE_FIELD, gaussian),
            NO_ADAPTIVE,
        ],
    );
    let f = &study.params.fields[0];
    let kl = f.field.kl();
    let mesh = kl.mesh();
    let m = f.num_variables();
    assert!(m >= 2, "{m} modes");
    let d = study.params.names.len();
    let solver =
        LatinSolver::new(study.model.assembly.clone(), study.model.options.clone()).unwrap();
    let x: Vec<[f64; 3]> = mesh.nodes().to_vec();
    let par = &study.model.parametric;
    let at = |theta: &[f64]| -> Vec<f64> {
        let mu = par.run_input(theta).mu[f.interface().unwrap()]
            .clone()
            .unwrap();
        x.iter().map(|&p| mu(p)).collect()
    };
    let base = at(&vec![0.0; d]);
    let mut variance = 0.0;
    for k in 0..m {
        let mut theta = vec![0.0; d];
        theta[f.first_variable + k] = 1.0;
        let dk: Vec<f64> = at(&theta).iter().zip(&base).map(|(a, b)| a - b).collect();
        variance += mesh.l2_product(&dk, &dk);
    }
    let lambda: f64 = kl.eigenvalues().iter().sum();
    assert!(
        (variance / lambda - 1.0).abs() < 1e-10,
        "{variance} vs {lambda}"
    );
    let total = 0.05f64.powi(2) * mesh.measure();
    assert!((kl.total_variance() / total - 1.0).abs() < 1e-12);
    assert!(variance >= 0.8 * total, "{variance} < 0.8 x {total}");
    let last = kl.eigenvalues()[m - 1];
    assert!(
        variance - last < 0.8 * total,
        "one mode fewer reaches the fraction"
    );
    // The flank is 14.1 mm long; its points are where the solver reads mu.
    assert!((mesh.measure() - 10.0 * 2f64.sqrt()).abs() < 1e-9);
    assert!(solver.interface_points(f.interface().unwrap()).len() >= mesh.num_nodes());
}

/// `edits` applied to the example refused at load: the message names the line of the last
/// `needle` (after the edits) and `field`, and contains `words`.
fn refused(edits: &[(&str, &str)], needle: &str, field: &str, words: &str) {
    let t = text("blade-root-simple-field.toml", edits);
    let e = Study::from_source(Source::from_text("f.toml", &t)).expect_err("refused");
    let lines: Vec<&str> = t.lines().collect();
    let line = lines
        .iter()
        .rposition(|l| l.contains(needle))
        .expect(needle)
        + 1;
    let msg = e.to_string();
    assert!(
        msg.starts_with(&format!("f.toml:{line}: {field}: ")),
        "{msg} (expected line {line}, field {field})"
    );
    assert!(msg.contains(words), "{msg}");
}

#[test]
fn bad_field_settings_are_refused_at_load_with_file_line_and_field() {
    let cl = "correlation_length = 10.0";
    refused(
        &[(cl, "correlation_length = 0.0")],
        "correlation_length = 0.0",
        "field[0].correlation_length",
        "> 0",
    );
    refused(
        &[(cl, "correlation_length = -2.0")],
        "correlation_length = -2.0",
        "field[0].correlation_length",
        "> 0",
    );
    refused(
        &[(cl, "correlation_length = nan")],
        "correlation_length = nan",
        "field[0].correlation_length",
        "finite",
    );
    let vf = "variance_fraction = 0.9";
    refused(
        &[(vf, "variance_fraction = 0.0")],
        "variance_fraction = 0.0",
        "field[0].variance_fraction",
        "(0, 1]",
    );
    refused(
        &[(vf, "variance_fraction = 1.5")],
        "variance_fraction = 1.5",
        "field[0].variance_fraction",
        "(0, 1]",
    );
    refused(
        &[(vf, "variance_fraction = 0.9\nmodes = 2")],
        "modes = 2",
        "field[0].modes",
        "not both",
    );
    refused(
        &[(vf, "")],
        "name = \"MU_G1\"",
        "field[0].variance_fraction",
        "needs",
    );
    refused(&[(vf, "modes = 0")], "modes = 0", "field[0].modes", ">= 1");
    refused(
        &[(vf, "modes = 100")],
        "modes = 100",
        "field[0].modes",
        "nodes",
    );
    refused(
        &[("interface = \"G2\"", "interface = \"G3\"")],
        "interface = \"G3\"",
        "field[1].interface",
        "unknown interface 'G3'",
    );
    refused(
        &[("\"squared_exponential\"", "\"gaussian\"")],
        "covariance = \"gaussian\"",
        "field[0].covariance",
        "unknown covariance",
    );
    refused(
        &[("\"bounded\"", "\"uniform\"")],
        "transform = \"uniform\"",
        "field[0].transform",
        "unknown transform",
    );
    refused(
        &[("lower = 0.3", "lower = 0.3\nmean = 0.5")],
        "mean = 0.5",
        "field[0].mean",
        "takes no 'mean'",
    );
    refused(
        &[("upper = 0.7", "upper = 0.2")],
        "upper = 0.2",
        "field[0].upper",
        "> lower",
    );
    refused(
        &[(
            "transform = \"bounded\"\nlower = 0.3\nupper = 0.7",
            "transform = \"lognormal\"\nmean = 0.5",
        )],
        "transform = \"lognormal\"",
        "field[0].std",
        "needs 'std'",
    );
    refused(
        &[(
            "transform = \"bounded\"\nlower = 0.3\nupper = 0.7",
            "transform = \"lognormal\"\nmean = -0.5\nstd = 0.1",
        )],
        "mean = -0.5",
        "field[0].mean",
        "mean",
    );
    refused(
        &[("name = \"MU_G2\"", "name = \"MU_G1\"")],
        "name = \"MU_G1\"",
        "field[1].name",
        "not a usable name",
    );
    refused(
        &[("name = \"MU_G1\"", "name = \"s\"")],
        "name = \"s\"",
        "field[0].name",
        "not a usable name",
    );
    // A field used on another interface, and a name no field has.
    refused(
        &[("mu = \"MU_G2\"", "mu = \"MU_G1\"")],
        "mu = \"MU_G1\"",
        "interface[1].mu",
        "lives on interface 'G1'",
    );
    refused(
        &[("mu = \"MU_G2\"", "mu = \"MU_G3\"")],
        "mu = \"MU_G3\"",
        "interface[1].mu",
        "MU_G3",
    );
    // A dependent joint spans the [[parameter]]s; with none, there is nothing for it to join.
    refused(
        &[(
            "[[field]]",
            "[joint]\ntype = \"gaussian_copula\"\n\n[[field]]",
        )],
        "type = \"gaussian_copula\"",
        "joint.type",
        "needs [[parameter]]s",
    );
    refused(
        &[(vf, "variance_fraction = 0.9\nlength = 2.0")],
        "length = 2.0",
        "length",
        "unknown field",
    );
}

#[test]
fn the_size_of_the_kl_problem_is_checked_before_it_is_solved() {
    let text = r#"
[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "rectangle"
kind = "quad4"
size = [10.0, 1.0]
cells = [2001, 1]

[analysis]
type = "plane_stress"

[[field]]
name = "F"
interface = "top"
covariance = "exponential"
correlation_length = 1.0
mean = 0.3
std = 0.05
modes = 2

[[substructure]]
name = "plate"
young = 200e3
poisson = 0.3
constraint = [ { group = "ymin", y = 0.0 }, { group = "xmin", x = 0.0 } ]

[[interface]]
name = "top"
side1 = ["plate", "ymax"]
side2 = ["plate", "ymin"]
law = "coulomb"
mu = "F"

[[quantity]]
name = "u"
kind = "displacement"
substructure = "plate"
point = [10.0, 1.0]
component = 0

[[method]]
type = "pc_regression"
"#;
    let start = std::time::Instant::now();
    let e = Study::from_source(Source::from_text("big.toml", text)).expect_err("refused");
    let line = text
        .lines()
        .position(|l| l.contains("interface = \"top\""))
        .unwrap()
        + 1;
    let msg = e.to_string();
    assert!(
        msg.starts_with(&format!("big.toml:{line}: field[0].interface: ")),
        "{msg}"
    );
    assert!(msg.contains("2002 nodes") && msg.contains("2000"), "{msg}");
    assert!(start.elapsed().as_secs_f64() < 5.0);
}

/// The Sobol' indices per KL mode written for a chaos method (exact from its expansion) agree
/// with the pick-freeze estimates on the same surrogate, within 4 standard errors; the
/// per-field indices are consistent with the per-mode ones.
#[test]
fn sobol_indices_per_kl_mode_agree_with_pick_freeze_on_the_same_surrogate() {
    use alea_study::analysis::{AnalysisSettings, analyse_method};
    use alea_study::runner::{NoProgress, run_study};
    let study = load(
        "blade-root-simple-field.toml",
        &[
            NO_ADAPTIVE,
            ("seed = 2008", "seed = 2008\n\n[statistics]\nsamples = 2000"),
        ],
    );
    let dir = std::env::temp_dir().join(format!("alea-field-sobol-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let method = &runs.methods[0];
    let settings = AnalysisSettings {
        samples: 2000,
        bandwidth: alea_uq::kde::Bandwidth::Silverman,
        kde_points: 64,
        confidence: 0.95,
    };
    let res = analyse_method(&study, method, &runs.records, &settings);
    let used: Vec<&alea_study::store::RunRecord> = method
        .points
        .iter()
        .map(|p| runs.records.iter().find(|r| &r.params == p).unwrap())
        .collect();
    assert!(used.iter().all(|r| r.converged()));
    let points: Vec<Vec<f64>> = used.iter().map(|r| r.params.clone()).collect();
    let sur = method.surrogate(&study.params, &points).unwrap();
    for (q, stats) in res.qois.iter().enumerate() {
        let exact = stats.sobol.as_ref().expect("indices of a field study");
        assert_eq!(exact.estimator, "pc_expansion");
        let values: Vec<f64> = used.iter().map(|r| r.qois[q]).collect();
        let mc = alea_study::sensitivity::pick_freeze(&study, &sur, &values).unwrap();
        for i in 0..study.params.names.len() {
            let (e, m, se) = (exact.first[i], mc.first[i], mc.first_se[i]);
            assert!(
                (e - m).abs() <= 4.0 * se + 1e-3,
                "{} S_{i}: {e} vs {m} +- {se}",
                stats.name
            );
            let (e, m, se) = (exact.total[i], mc.total[i], mc.total_se[i]);
            assert!(
                (e - m).abs() <= 4.0 * se + 1e-3,
                "{} T_{i}: {e} vs {m} +- {se}",
                stats.name
            );
            assert!(exact.first[i] <= exact.total[i] + 1e-12);
        }
        // Two fields of two modes each: field 1's closed index is the sum of its modes' first
        // orders and their interaction, and the other field's total is its complement.
        let f = &exact.fields;
        assert_eq!(f.len(), 2);
        assert!(f[0].closed >= exact.first[0] + exact.first[1] - 1e-12);
        assert!((f[0].closed + f[1].total - 1.0).abs() < 1e-12);
        assert!((f[1].closed + f[0].total - 1.0).abs() < 1e-12);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Sparse chaos (`pc_sparse`) on the field study: LARS keeps a strict subset of the 35
/// candidate terms (the constant included), the same one when the study is reopened from its
/// store, and its mean and std of the friction work agree with Monte Carlo on the model
/// (400 runs) within the Monte Carlo error and 15 % in std.
#[test]
fn sparse_chaos_selects_a_reproducible_basis_and_matches_monte_carlo() {
    use alea_study::analysis::{AnalysisSettings, analyse_method};
    use alea_study::runner::{NoProgress, run_study};
    let methods = "[[method]]\ntype = \"pc_sparse\"\ndegree = 3\ndesign = \"lhs\"\nruns = 80\n\n[[method]]\ntype = \"monte_carlo\"\nruns = 400\n\n";
    let study = load(
        "blade-root-simple-field.toml",
        &[
            NO_ADAPTIVE,
            (
                "[[method]]\ntype = \"pc_sparse\"",
                &format!("{methods}[[method]]\ntype = \"pc_sparse\""),
            ),
        ],
    );
    let dir = std::env::temp_dir().join(format!("alea-field-sparse-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    let basis = runs.methods[0]
        .sparse_basis
        .clone()
        .expect("a sparse basis");
    assert!(basis.len() > 1 && basis.len() < 35, "{} terms", basis.len());
    assert!(basis.iter().any(|a| a.iter().all(|&v| v == 0)));
    drop(runs);
    let runs = run_study(&study, &dir, false, &NoProgress).unwrap();
    assert_eq!(runs.computed, 0);
    assert_eq!(runs.methods[0].sparse_basis.as_ref(), Some(&basis));
    let settings = AnalysisSettings {
        samples: 20_000,
        bandwidth: alea_uq::kde::Bandwidth::Silverman,
        kde_points: 64,
        confidence: 0.95,
    };
    let t = study.qois.iter().position(|q| q.name == "T").unwrap();
    let sparse = analyse_method(&study, &runs.methods[0], &runs.records, &settings);
    let mc = analyse_method(&study, &runs.methods[1], &runs.records, &settings);
    let (s, m) = (&sparse.qois[t], &mc.qois[t]);
    assert_eq!(s.sobol.as_ref().unwrap().estimator, "pc_expansion");
    let se = m.distribution.std / 400f64.sqrt();
    assert!(
        (s.distribution.mean - m.distribution.mean).abs() < 3.0 * se,
        "mean {} vs {} +- {se}",
        s.distribution.mean,
        m.distribution.mean
    );
    assert!(
        (s.distribution.std / m.distribution.std - 1.0).abs() < 0.15,
        "std {} vs {}",
        s.distribution.std,
        m.distribution.std
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A lognormal field has the stated mean and std pointwise: at the mean field (KL variables
/// 0) it is its median `mean / sqrt(1 + cv^2)` everywhere, and it stays positive at the
/// corners of the KL variables' box.
#[test]
fn a_lognormal_field_is_its_median_at_zero_and_positive_everywhere() {
    let lognormal = r#"covariance = "matern52"
correlation_length = 4.0
transform = "lognormal"
mean = 0.5
std = 0.1
modes = 3"#;
    let study = load(
        "blade-root-simple-field.toml",
        &[
            (EXAMPLE_FIELD, lognormal),
            (EXAMPLE_FIELD, lognormal),
            NO_ADAPTIVE,
        ],
    );
    let d = study.params.names.len();
    assert_eq!(d, 6);
    let solver =
        LatinSolver::new(study.model.assembly.clone(), study.model.options.clone()).unwrap();
    let median = 0.5 / (1.0f64 + 0.04).sqrt();
    for theta in [
        vec![0.0; d],
        study.params.lo.clone(),
        study.params.hi.clone(),
    ] {
        let input = study.model.parametric.run_input(&theta);
        for i in 0..2 {
            for p in solver.interface_points(i) {
                let mu = input.mu[i].as_ref().unwrap()(p.x);
                assert!(mu > 0.0 && mu.is_finite(), "{mu}");
                if theta[0] == 0.0 {
                    assert!((mu - median).abs() < 1e-14, "{mu} vs {median}");
                }
            }
        }
    }
}

/// With `[budget] refined_mesh`, a field truncated by variance fraction must keep the same
/// number of modes on the finer mesh: a fraction between the one-mode fractions of the two
/// meshes (Galerkin eigenvalues grow with refinement) is refused at `budget.refined_mesh`.
#[test]
fn a_refined_mesh_that_changes_the_number_of_kl_modes_is_refused() {
    let one_mode_fraction = |edits: &[(&str, &str)]| {
        let s = load("blade-root-simple-field.toml", edits);
        let kl = s.params.fields[0].field.kl();
        kl.eigenvalues()[0] / kl.total_variance()
    };
    let coarse = one_mode_fraction(&[NO_ADAPTIVE]);
    let fine = one_mode_fraction(&[NO_ADAPTIVE, ("n_flank = 12", "n_flank = 24")]);
    assert!(fine > coarse, "{coarse} {fine}");
    let f = format!("variance_fraction = {}", 0.5 * (coarse + fine));
    let budget = "[budget]\nrefined_mesh = { params = { n_flank = 24 } }\n\n[[substructure]]";
    refused(
        &[
            NO_ADAPTIVE,
            ("variance_fraction = 0.9", &f),
            ("variance_fraction = 0.9", &f),
            ("[[substructure]]", budget),
        ],
        "refined_mesh = ",
        "budget.refined_mesh",
        "KL modes",
    );
    // With a mode count the refined study has the same parameters.
    let t = text(
        "blade-root-simple-field.toml",
        &[
            NO_ADAPTIVE,
            ("variance_fraction = 0.9", "modes = 2"),
            ("variance_fraction = 0.9", "modes = 2"),
            ("[[substructure]]", budget),
        ],
    );
    let s = Study::from_source(Source::from_text("f.toml", &t)).unwrap();
    assert_eq!(s.refined.unwrap().params.names, s.params.names);
}

/// A Gaussian copula of the `[[parameter]]`s beside the fields' KL variables
/// (`alea_uq::joint::ProductJoint`): the copula's correlation holds between the parameters (in
/// normal scores), nothing links them to the KL variables, which stay independent standard
/// normal; a run at a point uses every coordinate.
#[test]
fn a_copula_of_the_parameters_sits_beside_the_kl_variables() {
    use alea_uq::special::norm_quantile;
    let params = r#"[[parameter]]
name = "E_root"
law = "normal"
mean = 240e3
std = 20e3

[[parameter]]
name = "P"
law = "uniform"
lo = 0.8
hi = 1.2

[joint]
type = "gaussian_copula"
correlation = [[1.0, 0.7], [0.7, 1.0]]

[[field]]"#;
    let study = load(
        "blade-root-simple-field.toml",
        &[
            ("[[field]]", params),
            ("young = 240e3", "young = \"E_root\""),
            ("pressure = 1000.0 }", "pressure = 1000.0, factor = \"P\" }"),
            NO_ADAPTIVE,
        ],
    );
    let joint = study.params.joint.as_ref();
    let d = study.params.names.len();
    assert_eq!(&study.params.names[..2], ["E_root", "P"]);
    assert!(d > 2 && joint.dim() == d);
    assert!(!joint.is_independent());
    // Normal scores of 20 000 draws: z_i = Phi^-1(F_i(x_i)).
    let draws = alea_uq::design::monte_carlo(joint, 20_000, 7);
    let n = draws.len();
    let scores: Vec<Vec<f64>> = draws
        .iter()
        .map(|x| {
            x.iter()
                .zip(&study.params.marginals)
                .map(|(&v, m)| norm_quantile(m.cdf(v)))
                .collect()
        })
        .collect();
    let mean = |i: usize| scores.iter().map(|z| z[i]).sum::<f64>() / n as f64;
    let cov = |i: usize, j: usize| {
        let (mi, mj) = (mean(i), mean(j));
        scores
            .iter()
            .map(|z| (z[i] - mi) * (z[j] - mj))
            .sum::<f64>()
            / n as f64
    };
    let corr = |i: usize, j: usize| cov(i, j) / (cov(i, i) * cov(j, j)).sqrt();
    // Sampling standard errors: about 1 / sqrt(n) = 0.007 for a correlation near 0.
    assert!(
        (corr(0, 1) - 0.7).abs() < 0.02,
        "corr(E, P) = {}",
        corr(0, 1)
    );
    for j in 2..d {
        assert!(
            mean(j).abs() < 0.03 && (cov(j, j) - 1.0).abs() < 0.04,
            "KL variable {j}"
        );
        for i in 0..2 {
            assert!(corr(i, j).abs() < 0.03, "corr({i}, {j}) = {}", corr(i, j));
        }
    }
    // The parameters reach the model: P scales the pressure, E_root the root's modulus.
    let mut theta = study.params.nominal.clone();
    theta[1] = 1.1;
    let input = study.model.parametric.run_input(&theta);
    assert!((input.load_factors[1][0] - 1.1).abs() < 1e-15);
    let (q, _) = run(&study, &theta);
    assert!(q.iter().all(|v| v.is_finite()));
}
