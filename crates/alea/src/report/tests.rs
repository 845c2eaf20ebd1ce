//! Report tests on a synthetic study: a normal QoI with a known law, a degenerate QoI, a
//! response surface, a comparison, runs with a failure, and hostile text.
//!
//! Set `ALEA_REPORT_TEST_OUT=<dir>` to keep the full report of `full_report_is_written` there
//! (for a look in a browser or `scripts/check-report.sh`).

use std::path::{Path, PathBuf};

use super::plots::{SIZE, SURFACE_SIZE};
use super::*;

/// SplitMix64: deterministic uniform numbers without a dependency.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Box-Muller.
    fn normal(&mut self, mean: f64, std: f64) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        mean + std * (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}

fn normal_pdf(x: f64, m: f64, s: f64) -> f64 {
    (-0.5 * ((x - m) / s).powi(2)).exp() / (s * (2.0 * std::f64::consts::PI).sqrt())
}

fn kde_of(m: f64, s: f64, n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let x = m - 4.5 * s + 9.0 * s * i as f64 / (n - 1) as f64;
            (x, normal_pdf(x, m, s))
        })
        .collect()
}

/// The QoI of the synthetic study: work of friction as a function of (E, mu).
fn work(e: f64, mu: f64) -> f64 {
    10.0 + 40.0 * (mu - 0.5) * (mu - 0.2) + 3.0e-5 * (e - 240e3) * (1.0 + mu)
}

fn synthetic() -> ReportInput {
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
                failure: vec![],
                surface: None,
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
                },
                ComparisonRow {
                    method: "polynomial chaos, order 2".into(),
                    runs: 9,
                    mean: 10.05,
                    std: 2.1,
                    kde: kde_of(10.05, 2.1, 150),
                },
                ComparisonRow {
                    method: "piecewise linear, regular grid".into(),
                    runs: 9,
                    mean: 9.9,
                    std: 1.8,
                    kde: kde_of(9.9, 1.8, 150),
                },
                ComparisonRow {
                    method: "reference (11 x 11 grid)".into(),
                    runs: 121,
                    mean: 10.0,
                    std: 2.0,
                    kde: kde_of(10.0, 2.0, 150),
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
    }
}

/// A stochastic error estimate: two methods, three entities, an adaptive method's steps and a
/// density map peaked in one corner.
fn error_section() -> ErrorReport {
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

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("alea-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Signature and IHDR by hand, then a full decode.
fn check_png(path: &Path, (w, h): (u32, u32)) {
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
fn check_svg(path: &Path, size: (u32, u32), elements: &[&str]) {
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

#[test]
fn full_report_is_written() {
    let input = synthetic();
    let dir = match std::env::var_os("ALEA_REPORT_TEST_OUT") {
        Some(d) => PathBuf::from(d),
        None => out_dir("full"),
    };
    let files = write_report(&dir, &input).unwrap();
    assert_eq!(files.html, dir.join("report.html"));
    let stems = [
        ("pdf_friction_work", SIZE),
        ("cdf_friction_work", SIZE),
        ("surface_friction_work", SURFACE_SIZE),
        ("pdf_max", SIZE),
        ("cdf_max", SIZE),
        ("convergence", SIZE),
        ("comparison", SIZE),
        ("error_map", SURFACE_SIZE),
        ("indicators", SIZE),
    ];
    assert_eq!(files.plots.len(), 2 * stems.len(), "{:?}", files.plots);
    let html = std::fs::read_to_string(&files.html).unwrap();
    assert!(html.contains("id=\"error\"") && html.contains("Adaptive steps"));
    assert!(
        html.contains("substructure &lt;S2&gt;"),
        "escaped entity names"
    );
    for (stem, size) in stems {
        let png = dir.join(format!("{stem}.png"));
        let svg = dir.join(format!("{stem}.svg"));
        assert!(
            files.plots.contains(&png) && files.plots.contains(&svg),
            "{stem}"
        );
        check_png(&png, size);
        let elements: &[&str] = match stem {
            s if s.starts_with("pdf_friction") => &["rect", "polyline", "text", "line"],
            s if s.starts_with("surface") || s == "error_map" => {
                &["rect", "circle", "text", "image"]
            }
            _ => &["polyline", "text"],
        };
        check_svg(&svg, size, elements);
    }
    // The surface's filled levels: an embedded PNG (2 pixels per plot pixel), no placeholder.
    let svg = std::fs::read_to_string(dir.join("surface_friction_work.svg")).unwrap();
    assert!(!svg.contains("@@"), "raster placeholder left in the SVG");
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let image = doc
        .descendants()
        .find(|n| n.tag_name().name() == "image")
        .unwrap();
    let width: u32 = image.attribute("width").unwrap().parse().unwrap();
    let height: u32 = image.attribute("height").unwrap().parse().unwrap();
    let data = image
        .attribute("href")
        .unwrap()
        .strip_prefix("data:image/png;base64,")
        .unwrap();
    use base64::Engine;
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(data)
        .unwrap();
    let reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    assert_eq!(
        (reader.info().width, reader.info().height),
        (2 * width, 2 * height)
    );
    assert!(width > 400 && height > 400, "{width} x {height}");

    let html = std::fs::read_to_string(&files.html).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert_eq!(html.matches("<svg class=\"plot\"").count(), stems.len());
    assert!(!html.contains("<script"), "unescaped text");
    assert!(html.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"));
    assert!(html.contains("Blade root &lt;simple&gt; &amp; disk"));
    assert!(html.contains("max &lt;σ&gt; [MPa]"));
    for section in [
        "id=\"warnings\"",
        "id=\"parameters\"",
        "id=\"qoi-0\"",
        "id=\"qoi-1\"",
        "id=\"comparison\"",
        "id=\"convergence\"",
        "id=\"runs\"",
        "id=\"timings\"",
    ] {
        assert!(html.contains(section), "no {section}");
    }
    assert!(html.contains("truncated normal (0.5, 0.2) on [0.1, 0.9]"));
    assert!(
        html.contains("<details open=\"open\">"),
        "10 runs: run table open"
    );
    assert!(html.contains("not converged"));
    assert!(html.contains("0.02275") && html.contains("[0.0207, 0.0248]"));
    assert!(html.contains("reference (11 x 11 grid)"));
    assert!(!html.contains("NaN"));
    // 250 000 samples, yet a light page (plots are subsampled or binned).
    assert!(
        html.len() < 1_000_000,
        "report.html is {} bytes",
        html.len()
    );
    // The whole page is well-formed XML too (inline SVGs included) once the doctype is gone.
    let body = html.trim_start_matches("<!DOCTYPE html>\n");
    let xml = body.replace("<meta charset=\"utf-8\">", "<meta charset=\"utf-8\"/>");
    let xml = xml
        .replace(
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">",
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>",
        )
        .replace(
            &format!(
                "<meta name=\"generator\" content=\"alea {}\">",
                env!("CARGO_PKG_VERSION")
            ),
            "",
        )
        .replace("&middot;", "·")
        .replace("&mdash;", "—");
    roxmltree::Document::parse(&xml).unwrap_or_else(|e| panic!("report.html: {e}"));
    if std::env::var_os("ALEA_REPORT_TEST_OUT").is_none() {
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn nan_is_an_error_naming_the_field() {
    let mut input = synthetic();
    input.qois[0].samples[3] = f64::NAN;
    let dir = out_dir("nan");
    let e = write_report(&dir, &input).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.contains("qois[0] \"friction work\".samples[3]"),
        "message: {msg}"
    );
    assert!(!dir.join("report.html").exists());

    let mut input = synthetic();
    input.comparison.as_mut().unwrap().rows[1].std = f64::INFINITY;
    let msg = validate(&input).unwrap_err().to_string();
    assert!(
        msg.contains("comparison.rows[1]") && msg.contains(".std"),
        "{msg}"
    );

    let mut input = synthetic();
    input.qois[0].failure[0].probability = 1.5;
    let msg = validate(&input).unwrap_err().to_string();
    assert!(msg.contains("failure[0].probability"), "{msg}");

    let mut input = synthetic();
    input.qois[0].surface.as_mut().unwrap().values.pop();
    let msg = validate(&input).unwrap_err().to_string();
    assert!(msg.contains("surface.values"), "{msg}");

    let mut input = synthetic();
    input.runs[2].params.push(1.0);
    let msg = validate(&input).unwrap_err().to_string();
    assert!(msg.contains("runs[2].params"), "{msg}");
}

#[test]
fn degenerate_inputs_give_a_report() {
    // One run, one sample, no KDE, no history, no comparison, no timings, no notes.
    let input = ReportInput {
        title: String::new(),
        study_file: "one.toml".into(),
        units: vec![],
        method: "Monte Carlo on the model, 1 run".into(),
        parameters: vec![ParamInfo {
            name: "E".into(),
            law: "normal (200e3, 10e3)".into(),
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
        }],
        runs: vec![RunInfo {
            params: vec![200e3],
            status: "converged".into(),
            iterations: 1,
            seconds: 0.0,
            qois: vec![0.0],
        }],
        residual_histories: vec![("run 1".into(), vec![0.0])],
        qois: vec![QoiReport {
            name: "compliance".into(),
            unit: String::new(),
            what: String::new(),
            samples: vec![0.0],
            mean: 0.0,
            std: 0.0,
            skewness: 0.0,
            quantiles: vec![],
            kde: vec![],
            failure: vec![FailureInfo {
                threshold: 0.0,
                probability: 1.0,
                ci_low: 1.0,
                ci_high: 1.0,
            }],
            surface: None,
        }],
        comparison: Some(Comparison {
            qoi: "compliance".into(),
            rows: vec![],
        }),
        timings: vec![],
        notes: vec![],
        error: None,
    };
    let dir = out_dir("degenerate");
    let files = write_report(&dir, &input).unwrap();
    // PDF and CDF only: the history has no positive value, the comparison no curve.
    assert_eq!(files.plots.len(), 4);
    for stem in ["pdf_compliance", "cdf_compliance"] {
        check_png(&dir.join(format!("{stem}.png")), SIZE);
        check_svg(
            &dir.join(format!("{stem}.svg")),
            SIZE,
            &["polyline", "text"],
        );
    }
    let html = std::fs::read_to_string(&files.html).unwrap();
    assert!(html.contains("alea study report"));
    assert!(html.contains("−∞") && html.contains("∞"));
    assert!(!html.contains("NaN") && !html.contains("id=\"warnings\""));
    std::fs::remove_dir_all(&dir).unwrap();

    // No run, no QoI at all.
    let empty = ReportInput {
        runs: vec![],
        qois: vec![],
        parameters: vec![],
        residual_histories: vec![],
        comparison: None,
        ..input
    };
    let dir = out_dir("empty");
    let files = write_report(&dir, &empty).unwrap();
    assert!(files.plots.is_empty());
    assert!(
        std::fs::read_to_string(&files.html)
            .unwrap()
            .contains("No run recorded")
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn json_round_trip_keeps_infinite_bounds() {
    let mut input = synthetic();
    input.parameters[0].hi = f64::INFINITY;
    input.parameters[1].lo = f64::NEG_INFINITY;
    input.qois[0].samples.truncate(100);
    let dir = out_dir("json");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("report-input.json");
    input.save_json(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("\"hi\": \"inf\"") && text.contains("\"lo\": \"-inf\""));
    let back = ReportInput::load_json(&path).unwrap();
    assert_eq!(back.parameters[0].hi, f64::INFINITY);
    assert_eq!(back.parameters[1].lo, f64::NEG_INFINITY);
    assert_eq!(back.parameters[0].lo, 210e3);
    assert_eq!(back.runs.len(), input.runs.len());
    assert_eq!(back.title, input.title);
    for (a, b) in back.qois[0].samples.iter().zip(&input.qois[0].samples) {
        assert!((a - b).abs() <= 1e-14 * b.abs());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn file_stems_are_unique_and_safe() {
    let mut input = synthetic();
    let mut twin = input.qois[1].clone();
    twin.name = "max (σ)".into();
    input.qois.push(twin);
    input.qois[0].name = "../../etc/passwd".into();
    assert_eq!(
        super::plots::qoi_stems(&input),
        ["etc_passwd", "max", "max_2"]
    );
}

#[test]
fn tick_labels_share_one_style_per_axis() {
    let t = super::plots::ticks(0.0, 0.0032, 7);
    assert_eq!([t(&0.0), t(&0.0005), t(&0.001)], ["0", "0.0005", "0.0010"]);
    let t = super::plots::ticks(-0.02, 1.04, 10);
    assert_eq!([t(&0.0), t(&0.3), t(&1.0)], ["0", "0.3", "1.0"]);
    let t = super::plots::ticks(206e3, 274e3, 8);
    assert_eq!(t(&220e3), "220000");
    let t = super::plots::ticks(0.0, 3e-5, 7);
    assert_eq!(t(&1e-5), "1e-5");
    let t = super::plots::ticks(5.0, 5.0, 7);
    assert_eq!(t(&5.0), "5");
}
