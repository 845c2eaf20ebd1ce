//! The report's plots, drawn once per backend (SVG string, RGB buffer encoded as PNG) by the same
//! generic code, with the bundled DejaVu Sans (plotters' `ab_glyph` font path: no system font
//! library).
//!
//! One file per chart kind; `common` holds the shared drawing set-up (font, colours, axes,
//! legend) and the output of a figure as SVG and PNG.

mod cdf;
mod common;
mod comparison;
mod convergence;
mod indicators;
mod marks;
mod pdf;
mod qoi;
mod raster;
mod surface;
mod util;

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use super::format::slug;
use super::{AdaptiveReport, Comparison, QoiReport, ReportError, ReportInput, Surface};
use cdf::draw_cdf;
use common::{err, register_font, render};
use comparison::draw_comparison;
use convergence::draw_convergence;
use indicators::draw_indicators;
use pdf::draw_pdf;
use raster::Raster;
use surface::draw_surface;

#[cfg(test)]
pub use common::ticks;

/// Size of the PDF, CDF, convergence and comparison plots (pixels; the SVG's view box).
pub const SIZE: (u32, u32) = (900, 560);
/// Size of the response-surface plot (room for the colour bar).
pub const SURFACE_SIZE: (u32, u32) = (900, 640);

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
        && c.rows
            .iter()
            .any(|r| r.kde.len() >= 2 || !r.atoms.is_empty())
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
