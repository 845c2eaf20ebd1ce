//! What the figures share: the bundled font, colours, axis helpers, legend style, and the output
//! of a figure as SVG and PNG.

use std::path::Path;
use std::sync::OnceLock;

use plotters::chart::MeshStyle;
use plotters::coord::Shift;
use plotters::coord::ranged1d::AsRangedCoord;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::super::ReportError;
use super::super::format::num;
use super::raster::embed_raster;
pub(super) use super::util::{encode_png, err};
use super::{Figure, Kind, Spec};

/// DejaVu Sans (Bitstream Vera licence, see assets/fonts/DejaVu-LICENSE.txt).
const FONT_TTF: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";

/// Histogram bars, KDE curve, mean, thresholds, quantile markers.
pub(super) const HIST_FILL: RGBColor = RGBColor(198, 219, 239);
pub(super) const HIST_EDGE: RGBColor = RGBColor(140, 180, 215);
pub(super) const KDE: RGBColor = RGBColor(8, 69, 148);
pub(super) const MEAN: RGBColor = RGBColor(40, 40, 40);
pub(super) const THRESHOLD: RGBColor = RGBColor(203, 24, 29);
pub(super) const QUANTILE: RGBColor = RGBColor(230, 120, 20);
const GRID_BOLD: RGBColor = RGBColor(222, 222, 222);
const GRID_LIGHT: RGBColor = RGBColor(242, 242, 242);
const LEGEND_EDGE: RGBColor = RGBColor(190, 190, 190);
/// Qualitative palette for several lines (Tableau 10).
pub(super) const PALETTE: [RGBColor; 10] = [
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

pub(super) type DrawResult = Result<(), String>;

pub(super) fn font(size: f64) -> FontDesc<'static> {
    (FAMILY, size).into_font()
}

pub(super) fn register_font() -> Result<(), ReportError> {
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

pub(super) fn render(
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
    let bytes = encode_png((w, h), rgb).map_err(enc_err)?;
    alea_mesh::atomic::write_bytes_atomic(path, &bytes).map_err(io)
}

// ---------------------------------------------------------------------------------------------
// Helpers

pub(super) fn axis_label(name: &str, unit: &str) -> String {
    if unit.trim().is_empty() {
        name.to_string()
    } else {
        format!("{name} [{unit}]")
    }
}

/// `[lo, hi]` widened by a margin; a zero-width range gets a width of its own.
pub(super) fn pad((lo, hi): (f64, f64), frac: f64) -> (f64, f64) {
    let w = hi - lo;
    if w > 1e-12 * lo.abs().max(hi.abs()) && w > 0.0 {
        (lo - frac * w, hi + frac * w)
    } else {
        let d = if lo.abs() > 0.0 { 0.05 * lo.abs() } else { 1.0 };
        (lo - d, hi + d)
    }
}

pub(super) fn extend(range: &mut Option<(f64, f64)>, v: f64) {
    *range = Some(match *range {
        None => (v, v),
        Some((a, b)) => (a.min(v), b.max(v)),
    });
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

/// A curve's points in increasing x (a KDE grid handed over in any order still draws right).
pub(super) fn by_x(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut v = points.to_vec();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v
}

/// A chart with Cartesian coordinates.
type Chart2d<'a, DB, X, Y> = ChartContext<'a, DB, Cartesian2d<X, Y>>;

/// A chart in the frame every plot but the response surface has: title, margins, room for the
/// axis labels.
pub(super) fn chart<'a, DB: DrawingBackend, X: AsRangedCoord, Y: AsRangedCoord>(
    root: &'a DrawingArea<DB, Shift>,
    title: impl AsRef<str>,
    x: X,
    y: Y,
) -> Result<Chart2d<'a, DB, X::CoordDescType, Y::CoordDescType>, String> {
    ChartBuilder::on(root)
        .caption(title, font(24.0))
        .margin(18)
        .x_label_area_size(54)
        .y_label_area_size(72)
        .build_cartesian_2d(x, y)
        .map_err(err)
}

/// The axis and grid style of the same plots.
pub(super) fn grid<'m, 'a, 'b, X: Ranged, Y: Ranged, DB: DrawingBackend>(
    mesh: &'m mut MeshStyle<'a, 'b, X, Y, DB>,
) -> &'m mut MeshStyle<'a, 'b, X, Y, DB> {
    mesh.axis_desc_style(font(17.0))
        .label_style(font(15.0))
        .bold_line_style(GRID_BOLD)
        .light_line_style(GRID_LIGHT)
}

/// A chart of a positive quantity on a log scale against a count (iterations, runs), with 10
/// labels on each axis: the y range `(lo, hi)` is widened by the factor `margin` (by 10 when it
/// is a single value).
pub(super) fn count_log_chart<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    title: &str,
    x: std::ops::Range<f64>,
    (y0, y1): (f64, f64),
    margin: f64,
    (x_desc, y_desc): (&str, &str),
) -> Result<Chart2d<'a, DB, RangedCoordf64, LogCoord<f64>>, String> {
    let (y0, y1) = if y1 > y0 {
        (y0 / margin, y1 * margin)
    } else {
        (y0 / 10.0, y1 * 10.0)
    };
    let mut chart = chart(root, title, x, (y0..y1).log_scale())?;
    grid(&mut chart.configure_mesh())
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&integer_label)
        .y_label_formatter(&|v| num(*v, 2))
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// Tick label of a count axis (runs, iterations): whole numbers only.
pub(super) fn integer_label(v: &f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        format!("{}", v.round() as i64)
    } else {
        String::new()
    }
}

pub(super) fn line_legend(
    color: RGBColor,
    width: u32,
) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(width))
}

pub(super) fn configure_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
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
