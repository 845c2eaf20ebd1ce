//! Copulas in study files (issue 24, item 3): `[joint] type = "clayton" | "gumbel" | "frank"`
//! with `theta` (Clayton's negative dependence included, for two parameters) and `"student"`
//! with `nu` and a correlation matrix; their draws against Kendall's tau in closed form, and
//! their bad settings refused at load with the field.

mod common;

use alea_study::Source;
use alea_study::runner::Study;
use alea_uq::rng::chunk_rng;

fn load(params: usize, joint: &str) -> Result<Study, alea_study::StudyError> {
    let mut laws = String::new();
    for k in 0..params {
        laws.push_str(&format!(
            "\n[[parameter]]\nname = \"p{k}\"\nlaw = \"uniform\"\nlo = 1.0\nhi = 2.0\n"
        ));
    }
    laws.push_str(&format!("\n[joint]\n{joint}\n"));
    let text = common::plate_study("copulas", &laws, "200e3 * p0");
    Study::from_source(Source::from_text("copulas.toml", &text))
}

/// Kendall's tau of 2 000 draws of the study's joint law.
fn kendall(s: &Study) -> f64 {
    let law = s.params.joint.as_ref();
    let mut rng = chunk_rng(9, 0);
    let mut x = vec![0.0; law.dim()];
    let pts: Vec<(f64, f64)> = (0..2000)
        .map(|_| {
            law.sample(&mut rng, &mut x);
            (x[0], x[1])
        })
        .collect();
    let n = pts.len();
    let mut s = 0.0;
    for i in 0..n {
        for j in i + 1..n {
            s += ((pts[i].0 - pts[j].0) * (pts[i].1 - pts[j].1)).signum();
        }
    }
    s / (n * (n - 1) / 2) as f64
}

/// Kendall's tau within 0.04 (about 4 standard errors at 2 000 draws) of the closed forms:
/// Clayton `theta / (theta + 2)` for theta = -0.5 and 2, Gumbel `1 - 1/theta`, Student
/// `(2/pi) asin(rho)`.
#[test]
fn copulas_from_study_files_have_their_kendall_tau() {
    let cases = [
        ("type = \"clayton\"\ntheta = -0.5", -0.5 / 1.5),
        ("type = \"clayton\"\ntheta = 2.0", 0.5),
        ("type = \"gumbel\"\ntheta = 2.5", 0.6),
        (
            "type = \"student\"\nnu = 4.0\ncorrelation = [[1.0, 0.6], [0.6, 1.0]]",
            2.0 / std::f64::consts::PI * 0.6f64.asin(),
        ),
    ];
    for (joint, tau) in cases {
        let s = load(2, joint).unwrap();
        let got = kendall(&s);
        assert!((got - tau).abs() < 0.04, "{joint}: tau {got} vs {tau}");
    }
}

/// Bad copula settings: a missing or misplaced theta, nu or correlation, and Clayton's
/// negative theta with three parameters - refused at load naming the field.
#[test]
fn bad_copula_settings_are_refused_at_load() {
    let cases = [
        (2, "type = \"clayton\"", "joint.theta"),
        (
            2,
            "type = \"gaussian_copula\"\ncorrelation = [[1.0, 0.5], [0.5, 1.0]]\ntheta = 1.0",
            "joint.theta",
        ),
        (2, "type = \"frank\"\ntheta = 2.0\nnu = 3.0", "joint.nu"),
        (2, "type = \"student\"\nnu = 4.0", "joint.correlation"),
        (3, "type = \"clayton\"\ntheta = -0.5", "joint.theta"),
    ];
    for (d, joint, field) in cases {
        let e = load(d, joint).unwrap_err().to_string();
        assert!(
            e.contains("copulas.toml:") && e.contains(field),
            "{joint}: {e}"
        );
    }
}
