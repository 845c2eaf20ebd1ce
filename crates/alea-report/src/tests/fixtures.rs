//! The synthetic study and the checks of PNG and SVG files.

use std::path::{Path, PathBuf};

use super::super::*;

/// SplitMix64: deterministic uniform numbers without a dependency.
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Box-Muller.
    pub(super) fn normal(&mut self, mean: f64, std: f64) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        mean + std * (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

pub(super) fn normal_pdf(x: f64, m: f64, s: f64) -> f64 {
    (-0.5 * ((x - m) / s).powi(2)).exp() / (s * (2.0 * std::f64::consts::PI).sqrt())
}

pub(super) fn kde_of(m: f64, s: f64, n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let x = m - 4.5 * s + 9.0 * s * i as f64 / (n - 1) as f64;
            (x, normal_pdf(x, m, s))
        })
        .collect()
}

/// A budget row with only a surrogate part (or none) and a sampling part.
pub(super) fn row(statistic: &str, value: f64, surrogate: Option<f64>, sampling: f64) -> BudgetRow {
    BudgetRow {
        statistic: statistic.parse().expect("a statistic"),
        value,
        mesh: None,
        surrogate,
        sampling,
        sliding: None,
        total: sampling + surrogate.unwrap_or(0.0),
        validation: None,
    }
}

/// The QoI of the synthetic study: work of friction as a function of (E, mu).
pub(super) fn work(e: f64, mu: f64) -> f64 {
    10.0 + 40.0 * (mu - 0.5) * (mu - 0.2) + 3.0e-5 * (e - 240e3) * (1.0 + mu)
}

pub(super) fn synthetic() -> ReportInput {
    let mut rng = Rng(42);
    let (m, s) = (10.0, 2.0);
    // The size a study draws by default.
    let samples: Vec<f64> = (0..250_000).map(|_| rng.normal(m, s)).collect();
    let z = [
        (0.01, -2.326),
        (0.05, -1.645),
        (0.5, 0.0),
        (0.95, 1.645),
        (0.99, 2.326),
    ];
    let quantiles = z.iter().map(|&(p, z)| (p, m + s * z)).collect();
    let es = [210e3, 240e3, 270e3];
    let mus = [0.1, 0.5, 0.9];
    let mut points = Vec::new();
    let mut runs = Vec::new();
    for &e in &es {
        for &mu in &mus {
            points.push([e, mu, work(e, mu)]);
            runs.push(RunInfo {
                params: vec![e, mu],
                status: "converged".into(),
                iterations: 20 + (mu * 30.0) as usize,
                seconds: 0.4 + mu,
                qois: vec![work(e, mu), 412.0],
            });
        }
    }
    runs.push(RunInfo {
        params: vec![225e3, 0.85],
        status: "not converged".into(),
        iterations: 500,
        seconds: 12.5,
        qois: vec![],
    });
    let x: Vec<f64> = (0..31).map(|i| 210e3 + 2e3 * i as f64).collect();
    let y: Vec<f64> = (0..41).map(|j| 0.1 + 0.02 * j as f64).collect();
    let values = y
        .iter()
        .flat_map(|&mu| x.iter().map(move |&e| work(e, mu)))
        .collect();
    let history = |rate: f64, n: usize| (0..n).map(|i| rate.powi(i as i32)).collect::<Vec<_>>();
    ReportInput {
        title: "Blade root <simple> & disk".into(),
        study_file: "examples/blade-root-simple.toml".into(),
        units: vec![
            ("length".into(), "mm".into()),
            ("force".into(), "N".into()),
            ("stress".into(), "MPa".into()),
        ],
        method: "polynomial chaos, degree 2, regression on 9 runs".into(),
        parameters: vec![
            ParamInfo {
                name: "E2".into(),
                law: "truncated normal (240e3, 10e3) on [210e3, 270e3]".into(),
                lo: 210e3,
                hi: 270e3,
            },
            ParamInfo {
                name: "mu".into(),
                law: "truncated normal (0.5, 0.2) on [0.1, 0.9]".into(),
                lo: 0.1,
                hi: 0.9,
            },
        ],
        runs,
        residual_histories: vec![
            ("run 1 (E2 = 210000, mu = 0.1)".into(), history(0.8, 40)),
            ("run 5 (E2 = 240000, mu = 0.5)".into(), history(0.85, 60)),
            ("run 9 (E2 = 270000, mu = 0.9)".into(), history(0.9, 90)),
        ],
        qois: vec![
            QoiReport {
                name: "friction work".into(),
                unit: "N·mm".into(),
                what: String::new(),
                samples,
                mean: m,
                std: s,
                skewness: 0.0,
                quantiles,
                kde: kde_of(m, s, 200),
                atoms: vec![],
                failure: vec![
                    FailureInfo {
                        threshold: 14.0,
                        probability: 0.02275,
                        ci_low: 0.0207,
                        ci_high: 0.0248,
                    },
                    FailureInfo {
                        threshold: 40.0,
                        probability: 0.0,
                        ci_low: 0.0,
                        ci_high: 1.5e-4,
                    },
                ],
                surface: Some(Surface {
                    param_names: ["E2 [MPa]".into(), "mu".into()],
                    x,
                    y,
                    values,
                    points,
                }),
                budget: vec![
                    row("mean", m, Some(0.04), 0.008),
                    row("std", s, Some(0.03), 0.006),
                    row("q0.05", m - 1.645 * s, Some(0.05), 0.01),
                    row("q0.5", m, Some(0.02), 0.01),
                    row("q0.95", m + 1.645 * s, None, 0.01),
                    // Total interval [0.01875, 0.02675] about 0.02275.
                    row("P(> 14)", 0.02275, Some(0.00375), 0.00025),
                ],
                budget_basis: vec![
                    "surrogate: largest difference with the nested 3^2 grid, on the same draws"
                        .into(),
                    "mesh: not estimated".into(),
                ],
                sobol: vec![
                    ("MU_G1_1".into(), 0.41, 0.52),
                    ("E2 <x>".into(), 0.30, 0.36),
                ],
                sobol_basis: "From the chaos expansion <exact>.".into(),
            },
            // Degenerate: every sample equal, zero std, no KDE, no threshold.
            QoiReport {
                name: "max <σ>".into(),
                unit: "MPa".into(),
                what: String::new(),
                samples: vec![412.0; 50],
                mean: 412.0,
                std: 0.0,
                skewness: 0.0,
                quantiles: vec![(0.5, 412.0)],
                kde: vec![],
                atoms: vec![],
                failure: vec![],
                surface: None,
                budget: vec![],
                budget_basis: vec![],
                sobol: vec![],
                sobol_basis: String::new(),
            },
        ],
        comparison: Some(Comparison {
            qoi: "friction work".into(),
            rows: vec![
                ComparisonRow {
                    method: "standard polynomial, order 2".into(),
                    runs: 9,
                    mean: 10.3,
                    std: 2.6,
                    kde: kde_of(10.3, 2.6, 150),
                    atoms: vec![],
                    budget: vec![
                        row("mean", 10.3, Some(0.25), 0.01),
                        row("std", 2.6, Some(0.5), 0.01),
                    ],
                },
                ComparisonRow {
                    method: "polynomial chaos, order 2".into(),
                    runs: 9,
                    mean: 10.05,
                    std: 2.1,
                    kde: kde_of(10.05, 2.1, 150),
                    atoms: vec![],
                    budget: vec![
                        row("mean", 10.05, Some(0.125), 0.0),
                        row("std", 2.1, Some(0.0625), 0.0),
                    ],
                },
                ComparisonRow {
                    method: "piecewise linear, regular grid".into(),
                    runs: 9,
                    mean: 9.9,
                    std: 1.8,
                    kde: kde_of(9.9, 1.8, 150),
                    atoms: vec![],
                    budget: vec![],
                },
                ComparisonRow {
                    method: "reference (11 x 11 grid)".into(),
                    runs: 121,
                    mean: 10.0,
                    std: 2.0,
                    kde: kde_of(10.0, 2.0, 150),
                    atoms: vec![],
                    budget: vec![
                        row("mean", 10.0, None, 0.03125),
                        row("std", 2.0, None, 0.015625),
                    ],
                },
            ],
        }),
        timings: vec![
            ("solves".into(), 8.2),
            ("surrogate".into(), 0.012),
            ("monte carlo".into(), 0.35),
            ("report".into(), 0.4),
        ],
        notes: vec![
            "1 run did not converge and was left out: run 10 (E2 = 225000, mu = 0.85)".into(),
            "<script>alert('x')</script> is text, not code".into(),
        ],
        error: Some(error_section()),
        reliability: vec![ReliabilityReport {
            quantity: "friction work".into(),
            threshold: 0.004,
            method: "piecewise linear 3^2".into(),
            rows: vec![
                ReliabilityRow {
                    algorithm: "FORM".into(),
                    pf: 1.1e-4,
                    interval: None,
                    evaluations: 31,
                },
                ReliabilityRow {
                    algorithm: "subset simulation".into(),
                    pf: 1.25e-4,
                    interval: Some((0.9e-4, 1.6e-4)),
                    evaluations: 7200,
                },
            ],
            notes: vec!["2 design points within beta 3.7 + 1".into()],
        }],
    }
}

/// A stochastic error estimate: two methods, three entities, an adaptive method's steps and a
/// density map peaked in one corner.
pub(super) fn error_section() -> ErrorReport {
    let x: Vec<f64> = (0..20).map(|i| 210e3 + 3e3 * i as f64).collect();
    let y: Vec<f64> = (0..20).map(|j| 0.1 + 0.04 * j as f64).collect();
    let values = y
        .iter()
        .flat_map(|&mu| {
            x.iter()
                .map(move |&e| ((e - 210e3) / 6e4 * mu).powi(2) * 1e-3)
        })
        .collect();
    ErrorReport {
        warn: 0.1,
        methods: vec![
            ErrorRow {
                method: "adaptive (improved)".into(),
                runs: 13,
                relative: 0.12,
                i_geo: 0.11,
                i_sto: 0.05,
                dominant: "interface 'G2': 60 %".into(),
                violation: 0.0,
            },
            ErrorRow {
                method: "chaos p=2".into(),
                runs: 9,
                relative: 0.2,
                i_geo: 0.11,
                i_sto: 0.17,
                dominant: "substructure <S2>: 40 %".into(),
                violation: 0.25,
            },
        ],
        main: "adaptive (improved)".into(),
        entities: vec![
            EntityRow {
                entity: "S2".into(),
                kind: "substructure".into(),
                relative: 0.08,
                i_geo: 0.08,
                i_sto: 0.0,
                mean_share: Some(0.9),
            },
            EntityRow {
                entity: "G2".into(),
                kind: "interface".into(),
                relative: 0.09,
                i_geo: 0.07,
                i_sto: 0.05,
                mean_share: None,
            },
        ],
        adaptive: vec![AdaptiveReport {
            method: "adaptive (improved)".into(),
            stop: "i_sto <= i_geo".into(),
            qoi: "friction work".into(),
            steps: [(5, 0.3, 0.2), (7, 0.2, 0.14), (13, 0.05, 0.11)]
                .iter()
                .map(|&(runs, sto, geo)| StepRow {
                    runs,
                    new_runs: 2,
                    i_sto: sto,
                    i_geo: geo,
                    relative: (sto * sto + geo * geo).sqrt(),
                    mean: 4.2e3,
                    std: 900.0,
                    failure: Some(0.02),
                    cost: runs as f64 + 1.5,
                })
                .collect(),
        }],
        map: Some(Surface {
            param_names: ["E2".into(), "mu".into()],
            x,
            y,
            values,
            points: vec![[210e3, 0.1, 0.0], [267e3, 0.86, 0.0], [240e3, 0.5, 0.0]],
        }),
        vtu: Some("out/study/paraview/error.vtm".into()),
    }
}

pub(super) fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("alea-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Signature and IHDR by hand, then a full decode.
pub(super) fn check_png(path: &Path, (w, h): (u32, u32)) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{path:?}: PNG signature");
    assert_eq!(&bytes[8..12], &13u32.to_be_bytes(), "{path:?}: IHDR length");
    assert_eq!(&bytes[12..16], b"IHDR", "{path:?}: first chunk");
    let width = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let height = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!((width, height), (w, h), "{path:?}: size");
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (w, h));
    // Not a blank image: some dark pixels (axes, text) and some white.
    let px = &buf[..info.buffer_size()];
    assert!(
        px.chunks(3).any(|c| c.iter().all(|&v| v < 80)),
        "{path:?}: no dark pixel"
    );
    assert!(
        px.chunks(3).any(|c| c.iter().all(|&v| v == 255)),
        "{path:?}: no white pixel"
    );
}

/// Well-formed XML with an `svg` root and the element names given.
pub(super) fn check_svg(path: &Path, size: (u32, u32), elements: &[&str]) {
    let text = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(
        root.attribute("viewBox"),
        Some(format!("0 0 {} {}", size.0, size.1).as_str())
    );
    for name in elements {
        assert!(
            doc.descendants().any(|n| n.tag_name().name() == *name),
            "{path:?}: no <{name}>"
        );
    }
    assert!(!text.contains("NaN"), "{path:?} contains NaN");
}
