//! The report's plots, drawn once per backend (SVG string, RGB buffer encoded as PNG) by the same
//! generic code, with the bundled DejaVu Sans (plotters' `ab_glyph` font path: no system font
//! library).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::format::{count, num, slug};
use super::{AdaptiveReport, Comparison, QoiReport, ReportError, ReportInput, Surface};

/// DejaVu Sans (Bitstream Vera licence, see assets/fonts/DejaVu-LICENSE.txt).
const FONT_TTF: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";

/// Size of the PDF, CDF, convergence and comparison plots (pixels; the SVG's view box).
pub const SIZE: (u32, u32) = (900, 560);
/// Size of the response-surface plot (room for the colour bar).
pub const SURFACE_SIZE: (u32, u32) = (900, 640);

/// Histogram bars, KDE curve, mean, thresholds, quantile markers.
const HIST_FILL: RGBColor = RGBColor(198, 219, 239);
const HIST_EDGE: RGBColor = RGBColor(140, 180, 215);
const KDE: RGBColor = RGBColor(8, 69, 148);
const MEAN: RGBColor = RGBColor(40, 40, 40);
const THRESHOLD: RGBColor = RGBColor(203, 24, 29);
const QUANTILE: RGBColor = RGBColor(230, 120, 20);
const GRID_BOLD: RGBColor = RGBColor(222, 222, 222);
const GRID_LIGHT: RGBColor = RGBColor(242, 242, 242);
const LEGEND_EDGE: RGBColor = RGBColor(190, 190, 190);
/// Qualitative palette for several lines (Tableau 10).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
/// Points drawn at most for the empirical CDF.
const CDF_POINTS: usize = 2000;
/// Colour levels of the response surface.
const LEVELS: usize = 14;
/// Legend entries at most in the convergence plot.
const MAX_LEGEND: usize = 12;

/// What a figure shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Pdf(usize),
    Cdf(usize),
    Surface(usize),
    Convergence,
    Comparison,
    /// The stochastic error density over two parameters.
    ErrorMap,
    /// `i_sto` and `i_geo` against the runs of the adaptive methods.
    Indicators,
}

/// One plot, written as PNG and SVG; `svg` is the SVG text for inlining.
#[derive(Debug, Clone)]
pub struct Figure {
    pub kind: Kind,
    pub png: PathBuf,
    pub svg_path: PathBuf,
    pub svg: String,
}

type DrawResult = Result<(), String>;

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn font(size: f64) -> FontDesc<'static> {
    (FAMILY, size).into_font()
}

fn register_font() -> Result<(), ReportError> {
    static OK: OnceLock<bool> = OnceLock::new();
    let ok = *OK.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, FONT_TTF).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(ReportError::Plot {
            plot: "(all)".into(),
            message: "the bundled font DejaVuSans.ttf cannot be read".into(),
        })
    }
}

/// Unique file stems per QoI (`slug` of the name, `_2`, `_3` ... on collisions).
pub fn qoi_stems(input: &ReportInput) -> Vec<String> {
    let mut stems: Vec<String> = Vec::new();
    for q in &input.qois {
        let base = slug(&q.name);
        let mut stem = base.clone();
        let mut k = 2;
        while stems.contains(&stem) {
            stem = format!("{base}_{k}");
            k += 1;
        }
        stems.push(stem);
    }
    stems
}

/// Draws every plot the input calls for into `dir`.
pub fn draw_all(dir: &Path, input: &ReportInput) -> Result<Vec<Figure>, ReportError> {
    register_font()?;
    let stems = qoi_stems(input);
    let mut figures = Vec::new();
    for (k, q) in input.qois.iter().enumerate() {
        let mut sorted = q.samples.clone();
        sorted.sort_by(f64::total_cmp);
        let stem = &stems[k];
        let pdf = Spec::Pdf(q, &sorted);
        figures.push(render(
            dir,
            &format!("pdf_{stem}"),
            SIZE,
            Kind::Pdf(k),
            &pdf,
        )?);
        let cdf = Spec::Cdf(q, &sorted);
        figures.push(render(
            dir,
            &format!("cdf_{stem}"),
            SIZE,
            Kind::Cdf(k),
            &cdf,
        )?);
        if let Some(s) = &q.surface {
            let title = format!("Response surface of {}", q.name);
            let spec = Spec::Surface(&title, (&q.name, &q.unit), s);
            let stem = format!("surface_{stem}");
            figures.push(render(dir, &stem, SURFACE_SIZE, Kind::Surface(k), &spec)?);
        }
    }
    let histories: Vec<(&str, Vec<(f64, f64)>)> = input
        .residual_histories
        .iter()
        .map(|(label, h)| {
            let pts: Vec<(f64, f64)> = h
                .iter()
                .enumerate()
                .filter(|(_, v)| **v > 0.0)
                .map(|(i, v)| ((i + 1) as f64, *v))
                .collect();
            (label.as_str(), pts)
        })
        .filter(|(_, pts)| !pts.is_empty())
        .collect();
    if !histories.is_empty() {
        let spec = Spec::Convergence(&histories);
        figures.push(render(dir, "convergence", SIZE, Kind::Convergence, &spec)?);
    }
    if let Some(c) = &input.comparison
        && c.rows.iter().any(|r| r.kde.len() >= 2)
    {
        let unit = input
            .qois
            .iter()
            .find(|q| q.name == c.qoi)
            .map_or("", |q| q.unit.as_str());
        let spec = Spec::Comparison(c, unit);
        figures.push(render(dir, "comparison", SIZE, Kind::Comparison, &spec)?);
    }
    if let Some(e) = &input.error {
        if let Some(m) = &e.map {
            let title = format!("Stochastic error density ({})", e.main);
            let spec = Spec::Surface(&title, ("density of I_sto^2", ""), m);
            figures.push(render(
                dir,
                "error_map",
                SURFACE_SIZE,
                Kind::ErrorMap,
                &spec,
            )?);
        }
        if e.adaptive.iter().any(|a| !a.steps.is_empty()) {
            let spec = Spec::Indicators(&e.adaptive);
            figures.push(render(dir, "indicators", SIZE, Kind::Indicators, &spec)?);
        }
    }
    Ok(figures)
}

/// A figure and its data; drawn by the same code on both backends.
enum Spec<'a> {
    Pdf(&'a QoiReport, &'a [f64]),
    Cdf(&'a QoiReport, &'a [f64]),
    /// Title, colour-bar label (name, unit), surface.
    Surface(&'a str, (&'a str, &'a str), &'a Surface),
    Indicators(&'a [AdaptiveReport]),
    Convergence(&'a [(&'a str, Vec<(f64, f64)>)]),
    Comparison(&'a Comparison, &'a str),
}

impl Spec<'_> {
    /// Draws the figure; `vector` says the backend is SVG, where a response surface leaves a
    /// placeholder for its embedded raster (returned).
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        vector: bool,
    ) -> Result<Option<Raster>, String> {
        root.fill(&WHITE).map_err(err)?;
        match *self {
            Spec::Pdf(q, sorted) => draw_pdf(root, q, sorted),
            Spec::Cdf(q, sorted) => draw_cdf(root, q, sorted),
            Spec::Surface(title, label, s) => return draw_surface(root, title, label, s, vector),
            Spec::Indicators(a) => draw_indicators(root, a),
            Spec::Convergence(h) => draw_convergence(root, h),
            Spec::Comparison(c, unit) => draw_comparison(root, c, unit),
        }?;
        Ok(None)
    }
}

/// Where a response surface's raster goes (pixels) and what it shows (data range, levels).
#[derive(Debug, Clone, Copy)]
struct Raster {
    px: (i32, i32, i32, i32),
    x: (f64, f64),
    y: (f64, f64),
    v: (f64, f64),
}

/// Placeholder text the SVG backend writes where the raster image goes.
const RASTER_MARKER: &str = "@@alea-surface-raster@@";

/// Band colour of `v` among `LEVELS` equal bands of `[vmin, vmax]`.
fn band_color(v: f64, (vmin, vmax): (f64, f64)) -> RGBColor {
    let l = (((v - vmin) / (vmax - vmin) * LEVELS as f64)
        .floor()
        .max(0.0) as usize)
        .min(LEVELS - 1);
    viridis((l as f64 + 0.5) / LEVELS as f64)
}

/// The raster's pixels (RGB, `scale` pixels per plot pixel), row 0 at the top.
fn raster_rgb(s: &Surface, r: &Raster, scale: u32) -> (u32, u32, Vec<u8>) {
    let (px0, py0, px1, py1) = r.px;
    let w = (px1 - px0).max(1) as u32 * scale;
    let h = (py1 - py0).max(1) as u32 * scale;
    let mut rgb = Vec::with_capacity(w as usize * h as usize * 3);
    for j in 0..h {
        let y = r.y.1 - (j as f64 + 0.5) / h as f64 * (r.y.1 - r.y.0);
        for i in 0..w {
            let x = r.x.0 + (i as f64 + 0.5) / w as f64 * (r.x.1 - r.x.0);
            let c = band_color(bilinear(s, x, y), r.v);
            rgb.extend_from_slice(&[c.0, c.1, c.2]);
        }
    }
    (w, h, rgb)
}

/// Replaces the placeholder text element of the SVG by the raster as an embedded PNG.
fn embed_raster(svg: &mut String, s: &Surface, r: &Raster) -> Result<(), String> {
    use base64::Engine;
    let at = svg
        .find(RASTER_MARKER)
        .ok_or("raster placeholder missing")?;
    let start = svg[..at]
        .rfind("<text")
        .ok_or("raster placeholder malformed")?;
    let end = at
        + svg[at..]
            .find("</text>")
            .ok_or("raster placeholder malformed")?
        + 7;
    let (w, h, rgb) = raster_rgb(s, r, 2);
    let mut png_bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut png_bytes, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(err)?;
        writer.write_image_data(&rgb).map_err(err)?;
        writer.finish().map_err(err)?;
    }
    let (px0, py0, px1, py1) = r.px;
    let image = format!(
        "<image x=\"{px0}\" y=\"{py0}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\" \
         href=\"data:image/png;base64,{}\"/>",
        px1 - px0,
        py1 - py0,
        base64::engine::general_purpose::STANDARD.encode(&png_bytes)
    );
    svg.replace_range(start..end, &image);
    Ok(())
}

fn render(
    dir: &Path,
    stem: &str,
    size: (u32, u32),
    kind: Kind,
    spec: &Spec,
) -> Result<Figure, ReportError> {
    let plot_err = |message: String| ReportError::Plot {
        plot: stem.to_string(),
        message,
    };
    let mut svg = String::new();
    let raster = {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        let raster = spec.draw(&root, true).map_err(plot_err)?;
        root.present().map_err(|e| plot_err(e.to_string()))?;
        raster
    };
    if let (Some(r), Spec::Surface(_, _, s)) = (raster, spec) {
        embed_raster(&mut svg, s, &r).map_err(plot_err)?;
    }
    let (w, h) = size;
    let mut rgb = vec![255u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        spec.draw(&root, false).map_err(plot_err)?;
        root.present().map_err(|e| plot_err(e.to_string()))?;
    }
    let svg_path = dir.join(format!("{stem}.svg"));
    alea_mesh::atomic::write_bytes_atomic(&svg_path, svg.as_bytes()).map_err(|source| {
        ReportError::Io {
            path: svg_path.clone(),
            source,
        }
    })?;
    let png_path = dir.join(format!("{stem}.png"));
    write_png(&png_path, size, &rgb)?;
    Ok(Figure {
        kind,
        png: png_path,
        svg_path,
        svg,
    })
}

fn write_png(path: &Path, (w, h): (u32, u32), rgb: &[u8]) -> Result<(), ReportError> {
    let io = |source| ReportError::Io {
        path: path.to_path_buf(),
        source,
    };
    let enc_err = |e: png::EncodingError| match e {
        png::EncodingError::IoError(source) => io(source),
        other => ReportError::Plot {
            plot: path.display().to_string(),
            message: format!("PNG encoding: {other}"),
        },
    };
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(enc_err)?;
        writer.write_image_data(rgb).map_err(enc_err)?;
        writer.finish().map_err(enc_err)?;
    }
    alea_mesh::atomic::write_bytes_atomic(path, &bytes).map_err(io)
}

// ---------------------------------------------------------------------------------------------
// Helpers

fn axis_label(name: &str, unit: &str) -> String {
    if unit.trim().is_empty() {
        name.to_string()
    } else {
        format!("{name} [{unit}]")
    }
}

/// `[lo, hi]` widened by a margin; a zero-width range gets a width of its own.
fn pad((lo, hi): (f64, f64), frac: f64) -> (f64, f64) {
    let w = hi - lo;
    if w > 1e-12 * lo.abs().max(hi.abs()) && w > 0.0 {
        (lo - frac * w, hi + frac * w)
    } else {
        let d = if lo.abs() > 0.0 { 0.05 * lo.abs() } else { 1.0 };
        (lo - d, hi + d)
    }
}

fn extend(range: &mut Option<(f64, f64)>, v: f64) {
    *range = Some(match *range {
        None => (v, v),
        Some((a, b)) => (a.min(v), b.max(v)),
    });
}

/// The x range of a QoI's plots: samples, KDE grid, mean, and the thresholds that are not far
/// off (returned with a flag: on scale or not).
fn qoi_x_range(q: &QoiReport, sorted: &[f64]) -> ((f64, f64), Vec<bool>) {
    let mut r = None;
    if let (Some(a), Some(b)) = (sorted.first(), sorted.last()) {
        extend(&mut r, *a);
        extend(&mut r, *b);
    }
    for (x, _) in &q.kde {
        extend(&mut r, *x);
    }
    extend(&mut r, q.mean);
    let (lo, hi) = r.unwrap_or((q.mean, q.mean));
    let w = if hi > lo {
        hi - lo
    } else {
        pad((lo, hi), 0.0).1 - lo
    };
    let on_scale: Vec<bool> = q
        .failure
        .iter()
        .map(|f| f.threshold >= lo - 0.5 * w && f.threshold <= hi + 0.5 * w)
        .collect();
    let mut r = Some((lo, hi));
    for (f, on) in q.failure.iter().zip(&on_scale) {
        if *on {
            extend(&mut r, f.threshold);
        }
    }
    (pad(r.unwrap_or((lo, hi)), 0.03), on_scale)
}

/// Tick labels for an axis over `[lo, hi]` with about `n` ticks, all in one style: fixed with
/// the decimals of the tick step (0.0005, 0.0010 ...), or scientific for very large or very
/// small magnitudes.
pub fn ticks(lo: f64, hi: f64, n: usize) -> impl Fn(&f64) -> String {
    let m = lo.abs().max(hi.abs());
    let raw = (hi - lo).abs() / n.max(1) as f64;
    let scientific = !(m > 0.0) || !(1e-3..1e6).contains(&m) || !(raw > 0.0);
    let decimals = if scientific {
        0
    } else {
        let p = 10f64.powf(raw.log10().floor());
        let nice = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|k| k * p)
            .find(|s| *s >= raw * 0.999)
            .unwrap_or(10.0 * p);
        (-nice.log10().floor()).clamp(0.0, 9.0) as usize
    };
    move |v: &f64| {
        if scientific {
            num(*v, 3)
        } else if v.abs() < 0.5 * 10f64.powi(-(decimals as i32)) {
            "0".to_string()
        } else {
            format!("{v:.decimals$}")
        }
    }
}

/// The region under a curve (increasing x) right of `t`, as a closed polygon; `None` when the
/// curve ends before `t`.
fn tail_polygon(curve: &[(f64, f64)], t: f64) -> Option<Vec<(f64, f64)>> {
    let last = *curve.last()?;
    if last.0 <= t {
        return None;
    }
    let k = curve.partition_point(|p| p.0 <= t);
    let start = if k == 0 {
        curve[0]
    } else {
        let (a, b) = (curve[k - 1], curve[k]);
        let w = (t - a.0) / (b.0 - a.0);
        (t, a.1 + w * (b.1 - a.1))
    };
    let mut poly = vec![(start.0, 0.0), start];
    poly.extend_from_slice(&curve[k..]);
    poly.push((last.0, 0.0));
    Some(poly)
}

/// A curve's points in increasing x (a KDE grid handed over in any order still draws right).
fn by_x(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut v = points.to_vec();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

/// Freedman-Diaconis bins (10 to 80) of sorted samples, as (left, right, density).
fn histogram(sorted: &[f64]) -> Vec<(f64, f64, f64)> {
    let n = sorted.len();
    if n < 2 {
        return Vec::new();
    }
    let (lo, hi) = (sorted[0], sorted[n - 1]);
    if !(hi > lo) {
        return Vec::new();
    }
    let iqr = sorted[(3 * (n - 1)) / 4] - sorted[(n - 1) / 4];
    let bins = if iqr > 0.0 {
        let h = 2.0 * iqr / (n as f64).cbrt();
        ((hi - lo) / h).ceil() as usize
    } else {
        (n as f64).sqrt().ceil() as usize
    }
    .clamp(10, 80);
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0usize; bins];
    for &v in sorted {
        let b = (((v - lo) / width) as usize).min(bins - 1);
        counts[b] += 1;
    }
    counts
        .iter()
        .enumerate()
        .map(|(b, &c)| {
            let a = lo + b as f64 * width;
            (a, a + width, c as f64 / (n as f64 * width))
        })
        .collect()
}

fn line_legend(color: RGBColor, width: u32) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(width))
}

fn configure_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> DrawResult {
    chart
        .configure_series_labels()
        .position(position)
        .margin(12)
        .legend_area_size(30)
        .label_font(font(15.0))
        .background_style(WHITE.mix(0.92))
        .border_style(LEGEND_EDGE)
        .draw()
        .map_err(err)
}

// ---------------------------------------------------------------------------------------------
// Figures

fn draw_pdf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    q: &QoiReport,
    sorted: &[f64],
) -> DrawResult {
    let ((lo, hi), on_scale) = qoi_x_range(q, sorted);
    let bars = histogram(sorted);
    let point_mass = !sorted.is_empty() && bars.is_empty();
    let ymax = bars
        .iter()
        .map(|b| b.2)
        .chain(q.kde.iter().map(|p| p.1))
        .fold(0.0, f64::max);
    let ymax = if ymax > 0.0 { ymax * 1.15 } else { 1.0 };
    let mut chart = ChartBuilder::on(root)
        .caption(format!("Probability density of {}", q.name), font(24.0))
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(lo..hi, 0.0..ymax)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(axis_label(&q.name, &q.unit))
        .y_desc("probability density")
        .x_labels(8)
        .y_labels(7)
        .x_label_formatter(&ticks(lo, hi, 8))
        .y_label_formatter(&ticks(0.0, ymax, 7))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
        .draw()
        .map_err(err)?;
    if !bars.is_empty() {
        chart
            .draw_series(
                bars.iter()
                    .map(|&(a, b, d)| Rectangle::new([(a, 0.0), (b, d)], HIST_FILL.filled())),
            )
            .map_err(err)?
            .label(format!("histogram of {} samples", count(sorted.len())))
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 22, y + 6)], HIST_FILL.filled()));
        chart
            .draw_series(
                bars.iter().map(|&(a, b, d)| {
                    Rectangle::new([(a, 0.0), (b, d)], HIST_EDGE.stroke_width(1))
                }),
            )
            .map_err(err)?;
    }
    if point_mass {
        let v = sorted[0];
        chart
            .draw_series(LineSeries::new(
                [(v, 0.0), (v, ymax / 1.15)],
                KDE.stroke_width(4),
            ))
            .map_err(err)?
            .label(format!("all {} samples = {}", sorted.len(), num(v, 5)))
            .legend(line_legend(KDE, 4));
    }
    if q.kde.len() >= 2 {
        // The failure region P(q > t) shaded under the KDE, for each threshold on scale.
        let kde = by_x(&q.kde);
        for (f, on) in q.failure.iter().zip(&on_scale) {
            if let (true, Some(tail)) = (*on, tail_polygon(&kde, f.threshold)) {
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        tail,
                        THRESHOLD.mix(0.14).filled(),
                    )))
                    .map_err(err)?;
            }
        }
        chart
            .draw_series(LineSeries::new(by_x(&q.kde), KDE.stroke_width(3)))
            .map_err(err)?
            .label("kernel density estimate")
            .legend(line_legend(KDE, 3));
    }
    let top = ymax / 1.15;
    chart
        .draw_series(DashedLineSeries::new(
            [(q.mean, 0.0), (q.mean, top)],
            9,
            6,
            MEAN.stroke_width(2),
        ))
        .map_err(err)?
        .label(format!("mean = {}", num(q.mean, 4)))
        .legend(line_legend(MEAN, 2));
    draw_thresholds(&mut chart, q, &on_scale, top)?;
    let position = if q.mean > 0.5 * (lo + hi) {
        SeriesLabelPosition::UpperLeft
    } else {
        SeriesLabelPosition::UpperRight
    };
    configure_legend(&mut chart, position)
}

fn draw_thresholds<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    q: &QoiReport,
    on_scale: &[bool],
    top: f64,
) -> DrawResult {
    for (f, on) in q.failure.iter().zip(on_scale) {
        let label = format!(
            "P(q > {}) = {}{}",
            num(f.threshold, 4),
            num(f.probability, 3),
            if *on { "" } else { " (threshold off scale)" }
        );
        // Off scale: no line, only the legend entry.
        let pts: Vec<(f64, f64)> = if *on {
            vec![(f.threshold, 0.0), (f.threshold, top)]
        } else {
            Vec::new()
        };
        chart
            .draw_series(LineSeries::new(pts, THRESHOLD.stroke_width(2)))
            .map_err(err)?
            .label(label)
            .legend(line_legend(THRESHOLD, 2));
    }
    Ok(())
}

fn draw_cdf<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    q: &QoiReport,
    sorted: &[f64],
) -> DrawResult {
    let ((lo, hi), on_scale) = qoi_x_range(q, sorted);
    let mut chart = ChartBuilder::on(root)
        .caption(format!("Cumulative distribution of {}", q.name), font(24.0))
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(lo..hi, -0.02..1.04)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(axis_label(&q.name, &q.unit))
        .y_desc("probability")
        .x_labels(8)
        .y_labels(11)
        .x_label_formatter(&ticks(lo, hi, 8))
        .y_label_formatter(&ticks(0.0, 1.0, 10))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
        .draw()
        .map_err(err)?;
    let n = sorted.len();
    if n > 0 {
        let nf = n as f64;
        let mut pts = vec![(lo, 0.0), (sorted[0], 0.0)];
        if n <= CDF_POINTS {
            for (k, &x) in sorted.iter().enumerate() {
                pts.push((x, k as f64 / nf));
                pts.push((x, (k + 1) as f64 / nf));
            }
        } else {
            for i in 0..CDF_POINTS {
                let k = i * (n - 1) / (CDF_POINTS - 1);
                pts.push((sorted[k], (k + 1) as f64 / nf));
            }
        }
        pts.push((hi, 1.0));
        chart
            .draw_series(LineSeries::new(pts, KDE.stroke_width(2)))
            .map_err(err)?
            .label(format!("empirical CDF ({} samples)", count(n)))
            .legend(line_legend(KDE, 2));
    }
    chart
        .draw_series(DashedLineSeries::new(
            [(q.mean, 0.0), (q.mean, 1.0)],
            9,
            6,
            MEAN.stroke_width(2),
        ))
        .map_err(err)?
        .label(format!("mean = {}", num(q.mean, 4)))
        .legend(line_legend(MEAN, 2));
    if !q.quantiles.is_empty() {
        chart
            .draw_series(
                q.quantiles
                    .iter()
                    .filter(|(_, v)| *v >= lo && *v <= hi)
                    .map(|&(p, v)| Circle::new((v, p), 5, QUANTILE.filled())),
            )
            .map_err(err)?
            .label("quantiles")
            .legend(|(x, y)| Circle::new((x + 11, y), 5, QUANTILE.filled()));
    }
    draw_thresholds(&mut chart, q, &on_scale, 1.0)?;
    configure_legend(&mut chart, SeriesLabelPosition::LowerRight)
}

/// Viridis, from 9 control points.
fn viridis(t: f64) -> RGBColor {
    const C: [(f64, f64, f64); 9] = [
        (68.0, 1.0, 84.0),
        (71.0, 44.0, 122.0),
        (59.0, 81.0, 139.0),
        (44.0, 113.0, 142.0),
        (33.0, 144.0, 141.0),
        (39.0, 173.0, 129.0),
        (92.0, 200.0, 99.0),
        (170.0, 220.0, 50.0),
        (253.0, 231.0, 37.0),
    ];
    let s = t.clamp(0.0, 1.0) * 8.0;
    let i = (s.floor() as usize).min(7);
    let f = s - i as f64;
    let (a, b) = (C[i], C[i + 1]);
    let mix = |u: f64, v: f64| (u + f * (v - u)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Interval of a strictly increasing grid holding `v` (clamped), with the local coordinate.
fn locate(g: &[f64], v: f64) -> (usize, f64) {
    let i = g
        .partition_point(|&a| a <= v)
        .saturating_sub(1)
        .min(g.len() - 2);
    let t = ((v - g[i]) / (g[i + 1] - g[i])).clamp(0.0, 1.0);
    (i, t)
}

fn bilinear(s: &Surface, x: f64, y: f64) -> f64 {
    let nx = s.x.len();
    let (i, tx) = locate(&s.x, x);
    let (j, ty) = locate(&s.y, y);
    let v = |i: usize, j: usize| s.values[j * nx + i];
    (1.0 - ty) * ((1.0 - tx) * v(i, j) + tx * v(i + 1, j))
        + ty * ((1.0 - tx) * v(i, j + 1) + tx * v(i + 1, j + 1))
}

fn draw_surface<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    (name, unit): (&str, &str),
    s: &Surface,
    vector: bool,
) -> Result<Option<Raster>, String> {
    let (x0, x1) = (s.x[0], s.x[s.x.len() - 1]);
    let (y0, y1) = (s.y[0], s.y[s.y.len() - 1]);
    let mut xr = Some((x0, x1));
    let mut yr = Some((y0, y1));
    let mut vr = None;
    for &v in &s.values {
        extend(&mut vr, v);
    }
    for p in &s.points {
        extend(&mut xr, p[0]);
        extend(&mut yr, p[1]);
        extend(&mut vr, p[2]);
    }
    let (xlo, xhi) = pad(xr.unwrap_or((x0, x1)), 0.035);
    let (ylo, yhi) = pad(yr.unwrap_or((y0, y1)), 0.035);
    let (vmin, vmax) = vr.unwrap_or((0.0, 1.0));
    let (vmin, vmax) = if vmax > vmin {
        (vmin, vmax)
    } else {
        pad((vmin, vmax), 0.0)
    };
    let level_color = |l: usize| viridis((l as f64 + 0.5) / LEVELS as f64);

    let (w, _) = root.dim_in_pixel();
    let left_w = w as i32 - 140;
    let (left, right) = root.split_horizontally(left_w);
    let mut chart = ChartBuilder::on(&left)
        .caption(title, font(24.0))
        .margin(18)
        .margin_right(8)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(xlo..xhi, ylo..yhi)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(s.param_names[0].as_str())
        .y_desc(s.param_names[1].as_str())
        .x_labels(8)
        .y_labels(8)
        .x_label_formatter(&ticks(xlo, xhi, 8))
        .y_label_formatter(&ticks(ylo, yhi, 8))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .draw()
        .map_err(err)?;
    // Filled levels over the grid: pixels here, an embedded PNG in the SVG (a vector raster of
    // thousands of cells would be heavy and show seams).
    let (px0, py0) = chart.backend_coord(&(x0, y1));
    let (px1, py1) = chart.backend_coord(&(x1, y0));
    let raster = Raster {
        px: (px0, py0, px1, py1),
        x: (x0, x1),
        y: (y0, y1),
        v: (vmin, vmax),
    };
    if vector {
        chart
            .draw_series(std::iter::once(Text::new(
                RASTER_MARKER,
                (x0, y1),
                font(1.0),
            )))
            .map_err(err)?;
    } else {
        let (rw, rh, rgb) = raster_rgb(s, &raster, 1);
        for j in 0..rh as i32 {
            for i in 0..rw as i32 {
                let k = 3 * (j as usize * rw as usize + i as usize);
                let c = RGBColor(rgb[k], rgb[k + 1], rgb[k + 2]);
                left.draw_pixel((px0 + i, py0 + j), &c).map_err(err)?;
            }
        }
    }
    // Grid outline.
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(x0, y0), (x1, y1)],
            BLACK.mix(0.5).stroke_width(1),
        )))
        .map_err(err)?;
    let marker = |at: (i32, i32)| {
        EmptyElement::at(at)
            + Circle::new((0, 0), 6, WHITE.filled())
            + Circle::new((0, 0), 6, BLACK.stroke_width(2))
    };
    if !s.points.is_empty() {
        chart
            .draw_series(s.points.iter().map(|p| {
                EmptyElement::at((p[0], p[1]))
                    + Circle::new((0, 0), 6, WHITE.filled())
                    + Circle::new((0, 0), 6, BLACK.stroke_width(2))
            }))
            .map_err(err)?;
        // Key, bottom right, below the plot.
        let label = format!("collocation points ({})", s.points.len());
        let x = left_w - 24 - 8 * label.chars().count() as i32;
        let y = root.dim_in_pixel().1 as i32 - 20;
        left.draw(&marker((x, y))).map_err(err)?;
        left.draw(&Text::new(
            label,
            (x + 12, y - 7),
            TextStyle::from(font(14.0)).pos(Pos::new(HPos::Left, VPos::Top)),
        ))
        .map_err(err)?;
    }
    // Colour bar, aligned with the plotting area on the left.
    let mut bar = ChartBuilder::on(&right)
        .margin_top(py0 as u32)
        .margin_bottom((root.dim_in_pixel().1 as i32 - py1).max(0) as u32)
        .margin_left(6)
        .margin_right(8)
        .set_label_area_size(LabelAreaPosition::Right, 70)
        .build_cartesian_2d(0.0..1.0, vmin..vmax)
        .map_err(err)?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .set_tick_mark_size(LabelAreaPosition::Right, 5)
        .y_labels(8)
        .y_label_formatter(&ticks(vmin, vmax, 8))
        .y_desc(axis_label(name, unit))
        .axis_desc_style(font(15.0))
        .label_style(font(13.0))
        .draw()
        .map_err(err)?;
    let step = (vmax - vmin) / LEVELS as f64;
    bar.draw_series((0..LEVELS).map(|l| {
        let a = vmin + l as f64 * step;
        Rectangle::new([(0.0, a), (1.0, a + step)], level_color(l).filled())
    }))
    .map_err(err)?;
    bar.draw_series(std::iter::once(Rectangle::new(
        [(0.0, vmin), (1.0, vmax)],
        BLACK.mix(0.5).stroke_width(1),
    )))
    .map_err(err)?;
    Ok(vector.then_some(raster))
}

fn draw_convergence<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    histories: &[(&str, Vec<(f64, f64)>)],
) -> DrawResult {
    let mut xr = None;
    let mut yr = None;
    for (_, h) in histories {
        for &(i, v) in h {
            extend(&mut xr, i);
            extend(&mut yr, v);
        }
    }
    let (x0, x1) = xr.unwrap_or((1.0, 1.0));
    let (x0, x1) = if x1 > x0 {
        (x0 - 0.02 * (x1 - x0), x1 + 0.02 * (x1 - x0))
    } else {
        (x0 - 0.5, x1 + 0.5)
    };
    let (y0, y1) = yr.unwrap_or((0.1, 1.0));
    let (y0, y1) = if y1 > y0 {
        (y0 / 1.6, y1 * 1.6)
    } else {
        (y0 / 10.0, y1 * 10.0)
    };
    let mut chart = ChartBuilder::on(root)
        .caption("Convergence of the LATIN iterations", font(24.0))
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("iteration")
        .y_desc("LATIN error indicator")
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&|v| {
            if (v - v.round()).abs() < 1e-9 {
                format!("{}", v.round() as i64)
            } else {
                String::new()
            }
        })
        .y_label_formatter(&|v| num(*v, 2))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
        .draw()
        .map_err(err)?;
    for (k, (label, h)) in histories.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let series = chart
            .draw_series(LineSeries::new(h.iter().copied(), color.stroke_width(2)))
            .map_err(err)?;
        if k < MAX_LEGEND {
            series.label(*label).legend(line_legend(color, 2));
        } else if k == MAX_LEGEND {
            series
                .label(format!("... {} more", histories.len() - MAX_LEGEND))
                .legend(line_legend(color, 2));
        }
        if h.len() <= 25 {
            chart
                .draw_series(h.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(err)?;
        }
    }
    configure_legend(&mut chart, SeriesLabelPosition::UpperRight)
}

fn draw_comparison<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    c: &Comparison,
    unit: &str,
) -> DrawResult {
    let mut xr = None;
    let mut ymax: f64 = 0.0;
    for row in &c.rows {
        if row.kde.len() >= 2 {
            for &(x, p) in &row.kde {
                extend(&mut xr, x);
                ymax = ymax.max(p);
            }
        }
    }
    let (x0, x1) = pad(xr.unwrap_or((0.0, 1.0)), 0.02);
    let ymax = if ymax > 0.0 { ymax * 1.15 } else { 1.0 };
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("Probability density of {}: methods compared", c.qoi),
            font(24.0),
        )
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(x0..x1, 0.0..ymax)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(axis_label(&c.qoi, unit))
        .y_desc("probability density")
        .x_labels(8)
        .y_labels(7)
        .x_label_formatter(&ticks(x0, x1, 8))
        .y_label_formatter(&ticks(0.0, ymax, 7))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
        .draw()
        .map_err(err)?;
    let mut k = 0;
    for row in &c.rows {
        if row.kde.len() < 2 {
            continue;
        }
        let reference = row.method.to_lowercase().contains("reference");
        let (color, width) = if reference {
            (RGBColor(0, 0, 0), 3)
        } else {
            k += 1;
            (PALETTE[(k - 1) % PALETTE.len()], 2)
        };
        // Labels often say their run count already ("chaos p=2 (9 runs)").
        let label = if row.method.contains("run") {
            row.method.clone()
        } else {
            format!("{} ({} runs)", row.method, row.runs)
        };
        if reference {
            chart
                .draw_series(DashedLineSeries::new(
                    by_x(&row.kde),
                    10,
                    5,
                    color.stroke_width(width),
                ))
                .map_err(err)?
                .label(label)
                .legend(line_legend(color, width));
        } else {
            chart
                .draw_series(LineSeries::new(by_x(&row.kde), color.stroke_width(width)))
                .map_err(err)?
                .label(label)
                .legend(line_legend(color, width));
        }
    }
    configure_legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// `i_sto` (solid) and `i_geo` (dashed) of each adaptive method against its number of runs
/// (log scale), with the thesis's stopping rule `i_sto <= i_geo` where the lines cross.
fn draw_indicators<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    adaptive: &[AdaptiveReport],
) -> DrawResult {
    let mut xr = None;
    let mut yr = None;
    for a in adaptive {
        for s in &a.steps {
            extend(&mut xr, s.runs as f64);
            for v in [s.i_sto, s.i_geo] {
                if v > 0.0 {
                    extend(&mut yr, 100.0 * v);
                }
            }
        }
    }
    let (x0, x1) = pad(xr.unwrap_or((0.0, 1.0)), 0.05);
    let (y0, y1) = yr.unwrap_or((0.1, 100.0));
    let (y0, y1) = if y1 > y0 {
        (y0 / 1.5, y1 * 1.5)
    } else {
        (y0 / 10.0, y1 * 10.0)
    };
    let mut chart = ChartBuilder::on(root)
        .caption("Error indicators of the adaptive steps", font(24.0))
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("runs")
        .y_desc("indicator (% of the admissible energy)")
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&|v| {
            if (v - v.round()).abs() < 1e-9 {
                format!("{}", v.round() as i64)
            } else {
                String::new()
            }
        })
        .y_label_formatter(&|v| num(*v, 2))
        .axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
        .draw()
        .map_err(err)?;
    for (k, a) in adaptive.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let pts = |f: fn(&super::StepRow) -> f64| -> Vec<(f64, f64)> {
            a.steps
                .iter()
                .filter(|s| f(s) > 0.0)
                .map(|s| (s.runs as f64, 100.0 * f(s)))
                .collect()
        };
        let sto = pts(|s| s.i_sto);
        let geo = pts(|s| s.i_geo);
        chart
            .draw_series(LineSeries::new(sto.iter().copied(), color.stroke_width(2)))
            .map_err(err)?
            .label(format!("i_sto, {}", a.method))
            .legend(line_legend(color, 2));
        chart
            .draw_series(sto.iter().map(|&p| Circle::new(p, 4, color.filled())))
            .map_err(err)?;
        chart
            .draw_series(DashedLineSeries::new(
                geo.iter().copied(),
                8,
                5,
                color.stroke_width(2),
            ))
            .map_err(err)?
            .label(format!("i_geo, {}", a.method))
            .legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (8, 0)], color.stroke_width(2))
                    + PathElement::new(vec![(12, 0), (20, 0)], color.stroke_width(2))
            });
        chart
            .draw_series(geo.iter().map(|&p| Cross::new(p, 4, color.stroke_width(2))))
            .map_err(err)?;
    }
    configure_legend(&mut chart, SeriesLabelPosition::UpperRight)
}
