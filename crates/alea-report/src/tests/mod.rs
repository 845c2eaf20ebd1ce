//! Report tests on a synthetic study: a normal QoI with a known law, a degenerate QoI, a
//! response surface, a comparison, runs with a failure, and hostile text.
//!
//! Set `ALEA_REPORT_TEST_OUT=<dir>` to keep the full report of `full_report_is_written` there
//! (for a look in a browser or `scripts/check-report.sh`).

mod fixtures;
mod inputs;
mod intervals;
mod labels;

use super::plots::{SIZE, SURFACE_SIZE};
use super::*;
use fixtures::*;

// Here, not in a file of its own: scripts/check-report.sh runs it by its exact path.
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
    // Sobol' indices per parameter, names and basis escaped.
    assert!(html.contains("<h3>Sobol' indices</h3>"));
    assert!(html.contains("<td>MU_G1_1</td><td class=\"n\">0.41</td><td class=\"n\">0.52</td>"));
    assert!(html.contains("E2 &lt;x&gt;") && html.contains("expansion &lt;exact&gt;."));
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
