//! Laws from measured data in study files (issue 24, item 3): `law = "fit" | "empirical" |
//! "kde"` with `data = "file.csv"`, against the law that generated the data, and their bad
//! inputs refused at load with the study file's field and the data file's line.

mod common;

use alea_study::Source;
use alea_study::runner::Study;
use alea_uq::special::norm_quantile;
use std::path::PathBuf;

/// `n` values of the lognormal law with log-mean `mu` and log-std `s`, at the probabilities
/// `(k + 1/2) / n` (a stratified sample: its statistics are those of the law to O(1/n)).
fn lognormal_values(n: usize, mu: f64, s: f64) -> Vec<f64> {
    (0..n)
        .map(|k| (mu + s * norm_quantile((k as f64 + 0.5) / n as f64)).exp())
        .collect()
}

struct Dir(PathBuf);
impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn setup(name: &str, csv: &str) -> Dir {
    let dir = std::env::temp_dir().join(format!("alea-data-law-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("mu.csv"), csv).unwrap();
    Dir(dir)
}

fn load(dir: &Dir, parameter: &str) -> Result<Study, alea_study::StudyError> {
    let text = common::plate_study(
        "laws from data",
        &format!("[[parameter]]\nname = \"E\"\n{parameter}"),
        "E",
    );
    let path = dir.0.join("study.toml");
    std::fs::write(&path, &text).unwrap();
    Study::from_source(Source::read(&path).unwrap())
}

fn csv(header: &str, values: &[f64]) -> String {
    let mut s = format!("{header}\n");
    for v in values {
        s.push_str(&format!("{v}\n"));
    }
    s
}

/// 400 values of LN(log 200e3, 0.1): the fit picks the lognormal family (smallest BIC among
/// normal, lognormal, gamma, uniform) and its median and quantiles are those of the law within
/// a few standard errors; the description gives the fit and its goodness of fit.
#[test]
fn a_fit_to_lognormal_data_picks_the_lognormal_law() {
    let (mu, s) = (200e3f64.ln(), 0.1);
    let dir = setup("fit", &csv("E", &lognormal_values(400, mu, s)));
    let study = load(&dir, "law = \"fit\"\ndata = \"mu.csv\"").unwrap();
    let d = &study.params.descriptions[0];
    assert!(
        d.starts_with("lognormal fitted by maximum likelihood"),
        "{d}"
    );
    assert!(d.contains("Kolmogorov-Smirnov"), "{d}");
    let law = &study.params.marginals[0];
    for p in [0.05, 0.5, 0.95] {
        let exact = (mu + s * norm_quantile(p)).exp();
        let got = law.quantile(p);
        // Standard error of a quantile estimate from 400 values: well below 1 %.
        assert!((got / exact - 1.0).abs() < 0.01, "q{p}: {got} vs {exact}");
    }
}

/// The empirical law runs through the data's order statistics (its median is the sample
/// median), and the kernel density law is centred on the data.
#[test]
fn empirical_and_kde_laws_follow_the_data() {
    let values = lognormal_values(101, 200e3f64.ln(), 0.1);
    let two_columns: String = std::iter::once("E,other\n".to_string())
        .chain(values.iter().map(|v| format!("{v},1\n")))
        .collect();
    let dir = setup("emp", &two_columns);
    let study = load(
        &dir,
        "law = \"empirical\"\ndata = \"mu.csv\"\ncolumn = \"E\"",
    )
    .unwrap();
    let median = values[50];
    let got = study.params.marginals[0].quantile(0.5);
    assert!((got / median - 1.0).abs() < 1e-3, "{got} vs {median}");
    assert!(study.params.descriptions[0].contains("101 values of mu.csv (column E)"));
    let study = load(&dir, "law = \"kde\"\ndata = \"mu.csv\"\ncolumn = \"E\"").unwrap();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let got = study.params.marginals[0].mean();
    assert!((got / mean - 1.0).abs() < 1e-9, "{got} vs {mean}");
}

/// Bad data: a value that is not a number (named by the data file's line), an unknown column,
/// data on a parametric law, too few values - each refused at load with the field.
#[test]
fn bad_data_is_refused_at_load_with_the_line() {
    let dir = setup("bad", "E\n1.0\n2.0\n3.0\nabc\n5.0\n");
    let e = load(&dir, "law = \"empirical\"\ndata = \"mu.csv\"")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("parameter[0].data") && e.contains("mu.csv:5") && e.contains("'abc'"),
        "{e}"
    );
    let e = load(&dir, "law = \"fit\"\ndata = \"mu.csv\"\ncolumn = \"F\"")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("parameter[0].column") && e.contains("no column 'F'"),
        "{e}"
    );
    let e = load(
        &dir,
        "law = \"uniform\"\nlo = 1.0\nhi = 2.0\ndata = \"mu.csv\"",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("parameter[0].data") && e.contains("takes no data"),
        "{e}"
    );
    std::fs::write(dir.0.join("mu.csv"), "E\n1.0\n2.0\n").unwrap();
    let e = load(&dir, "law = \"empirical\"\ndata = \"mu.csv\"")
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least 3"), "{e}");
    let e = load(
        &dir,
        "law = \"empirical\"\ndata = \"mu.csv\"\nbandwidth = 2.0",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("parameter[0].bandwidth") && e.contains("used by law = \"kde\" only"),
        "{e}"
    );
    let e = load(
        &dir,
        "law = \"kde\"\ndata = \"mu.csv\"\nfamilies = [\"normal\"]",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("parameter[0].families"), "{e}");
    let e = load(&dir, "law = \"kde\"\ndata = \"missing.csv\"")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("parameter[0].data") && e.contains("missing.csv"),
        "{e}"
    );
}

/// The data file is an input of the study: changing it changes the study hash (a store of the
/// old data is not reused), the same bytes give the same hash.
#[test]
fn the_data_file_enters_the_study_hash() {
    let dir = setup("hash", "E\n1.0\n2.0\n3.0\n4.0\n");
    let a = load(&dir, "law = \"empirical\"\ndata = \"mu.csv\"")
        .unwrap()
        .hash;
    let b = load(&dir, "law = \"empirical\"\ndata = \"mu.csv\"")
        .unwrap()
        .hash;
    std::fs::write(dir.0.join("mu.csv"), "E\n1.0\n2.0\n3.0\n4.5\n").unwrap();
    let c = load(&dir, "law = \"empirical\"\ndata = \"mu.csv\"")
        .unwrap()
        .hash;
    assert_eq!(a, b);
    assert_ne!(a, c);
}
