//! Figures inlined as SVG with links to their PNG and SVG files; names with units.

use std::fmt::Write;

use super::super::format::esc;
use super::super::plots::{Figure, Kind};

pub(super) fn figure(figures: &[Figure], kind: Kind) -> Option<&Figure> {
    figures.iter().find(|f| f.kind == kind)
}

/// The SVG with its fixed size removed (the view box stays), so it scales with the page.
fn inline_svg(fig: &Figure, label: &str) -> String {
    let body = match fig.svg.find("<svg") {
        Some(start) => &fig.svg[start..],
        None => fig.svg.as_str(),
    };
    let (open, rest) = match body.find('>') {
        Some(end) => (&body[..end], &body[end + 1..]),
        None => (body, ""),
    };
    let view_box = open
        .split("viewBox=\"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .unwrap_or("0 0 900 560");
    format!(
        "<svg class=\"plot\" viewBox=\"{}\" xmlns=\"http://www.w3.org/2000/svg\" role=\"img\" \
         aria-label=\"{}\">{}",
        esc(view_box),
        esc(label),
        rest
    )
}

fn file_name(path: &std::path::Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

pub(super) fn put_figure(out: &mut String, figures: &[Figure], kind: Kind, caption: &str) {
    if let Some(f) = figure(figures, kind) {
        let png = file_name(&f.png);
        let svg = file_name(&f.svg_path);
        let _ = writeln!(
            out,
            "<figure>{}<figcaption>{} &middot; <a href=\"{}\">PNG</a> &middot; \
             <a href=\"{}\">SVG</a></figcaption></figure>",
            inline_svg(f, caption),
            esc(caption),
            esc(&png),
            esc(&svg)
        );
    }
}

pub(super) fn with_unit(name: &str, unit: &str) -> String {
    if unit.trim().is_empty() {
        esc(name)
    } else {
        format!("{} [{}]", esc(name), esc(unit))
    }
}
