//! The filled levels of a response surface: drawn pixel by pixel on the bitmap, embedded as a
//! PNG image in the SVG.

use plotters::prelude::*;

use super::super::Surface;
use super::util::{encode_png, err};

/// Colour levels of the response surface.
pub(super) const LEVELS: usize = 14;

/// Where a response surface's raster goes (pixels) and what it shows (data range, levels).
#[derive(Debug, Clone, Copy)]
pub(super) struct Raster {
    pub(super) px: (i32, i32, i32, i32),
    pub(super) x: (f64, f64),
    pub(super) y: (f64, f64),
    pub(super) v: (f64, f64),
}

/// Placeholder text the SVG backend writes where the raster image goes.
pub(super) const RASTER_MARKER: &str = "@@alea-surface-raster@@";

/// Band colour of `v` among `LEVELS` equal bands of `[vmin, vmax]`.
fn band_color(v: f64, (vmin, vmax): (f64, f64)) -> RGBColor {
    let l = (((v - vmin) / (vmax - vmin) * LEVELS as f64)
        .floor()
        .max(0.0) as usize)
        .min(LEVELS - 1);
    level_color(l)
}

/// Colour of level `l` of `LEVELS` (the middle of its band on the viridis scale).
pub(super) fn level_color(l: usize) -> RGBColor {
    viridis((l as f64 + 0.5) / LEVELS as f64)
}

/// The raster's pixels (RGB, `scale` pixels per plot pixel), row 0 at the top.
pub(super) fn raster_rgb(s: &Surface, r: &Raster, scale: u32) -> (u32, u32, Vec<u8>) {
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
pub(super) fn embed_raster(svg: &mut String, s: &Surface, r: &Raster) -> Result<(), String> {
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
    let png_bytes = encode_png((w, h), &rgb).map_err(err)?;
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
