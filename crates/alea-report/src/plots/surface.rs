//! A response surface (or the error-density map) over two parameters, with the collocation
//! points and a colour bar.

use plotters::coord::Shift;
use plotters::element::ComposedElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::super::Surface;
use super::common::{axis_label, err, extend, font, pad, ticks};
use super::raster::{LEVELS, RASTER_MARKER, Raster, level_color, raster_rgb};

/// A collocation point: a white disc ringed in black.
type Marker<C, DB> = ComposedElement<C, DB, Circle<(i32, i32), i32>, Circle<(i32, i32), i32>>;

/// The marker of a collocation point, on the plot and in its key.
fn marker<C, DB: DrawingBackend>(at: C) -> Marker<C, DB> {
    EmptyElement::at(at)
        + Circle::new((0, 0), 6, WHITE.filled())
        + Circle::new((0, 0), 6, BLACK.stroke_width(2))
}

pub(super) fn draw_surface<DB: DrawingBackend>(
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
    if !s.points.is_empty() {
        chart
            .draw_series(s.points.iter().map(|p| marker((p[0], p[1]))))
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
