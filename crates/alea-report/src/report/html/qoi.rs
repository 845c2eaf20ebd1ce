//! A section per quantity of interest, and the comparison of methods.

use std::fmt::Write;

use super::super::format::{count, esc, num, prob};
use super::super::plots::{Figure, Kind};
use super::super::{Comparison, QoiReport, ReliabilityReport};
use super::figures::{put_figure, with_unit};

pub(super) fn qoi_section(o: &mut String, k: usize, q: &QoiReport, figures: &[Figure]) {
    let _ = writeln!(
        o,
        "<section id=\"qoi-{k}\"><h2>Quantity of interest: {}</h2>",
        with_unit(&q.name, &q.unit)
    );
    if !q.what.is_empty() {
        let _ = writeln!(o, "<p>{}</p>", esc(&q.what));
    }
    o.push_str("<div class=\"tables\">\n");
    // Statistics.
    o.push_str("<div><h3>Statistics</h3><table><tbody>\n");
    let unit = if q.unit.trim().is_empty() {
        String::new()
    } else {
        format!(" {}", esc(&q.unit))
    };
    let row = |o: &mut String, label: &str, value: String| {
        let _ = writeln!(o, "<tr><th>{label}</th><td class=\"n\">{value}</td></tr>");
    };
    row(o, "Mean", format!("{}{unit}", num(q.mean, 5)));
    row(o, "Standard deviation", format!("{}{unit}", num(q.std, 4)));
    if q.mean != 0.0 {
        row(
            o,
            "Coefficient of variation",
            format!("{} %", num(100.0 * q.std / q.mean.abs(), 3)),
        );
    }
    row(o, "Skewness", num(q.skewness, 3));
    row(o, "Monte Carlo samples", count(q.samples.len()));
    o.push_str("</tbody></table></div>\n");
    // Quantiles.
    o.push_str("<div><h3>Quantiles</h3>");
    if q.quantiles.is_empty() {
        o.push_str("<p class=\"ok-note\">None computed.</p>");
    } else {
        o.push_str(
            "<table><thead><tr><th class=\"n\">Probability</th><th class=\"n\">Value</th>\
             </tr></thead><tbody>\n",
        );
        for &(p, v) in &q.quantiles {
            let _ = writeln!(
                o,
                "<tr><td class=\"n\">{}</td><td class=\"n\">{}{unit}</td></tr>",
                prob(p),
                num(v, 4)
            );
        }
        o.push_str("</tbody></table>");
    }
    o.push_str("</div>\n");
    // Failure.
    o.push_str("<div><h3>Failure probability</h3>");
    if q.failure.is_empty() {
        o.push_str("<p class=\"ok-note\">No threshold given.</p>");
    } else {
        o.push_str(
            "<p class=\"hint\">P<sub>f</sub> = P(q &gt; threshold), with its confidence \
             interval</p><table><thead><tr><th class=\"n\">Threshold</th><th class=\"n\">P<sub>f</sub></th>\
             <th class=\"n\">Confidence interval</th></tr></thead><tbody>\n",
        );
        for f in &q.failure {
            let _ = writeln!(
                o,
                "<tr><td class=\"n\">{}{unit}</td><td class=\"n\">{}</td>\
                 <td class=\"n\">[{}, {}]</td></tr>",
                num(f.threshold, 5),
                prob(f.probability),
                prob(f.ci_low),
                prob(f.ci_high)
            );
        }
        o.push_str("</tbody></table>");
    }
    o.push_str("</div>\n</div>\n");
    budget_table(o, q, &unit);
    sobol_table(o, q);
    put_figure(
        o,
        figures,
        Kind::Pdf(k),
        &format!(
            "Probability density of {}: kernel density estimate over the normalised histogram \
             of the Monte Carlo samples on the surrogate; dashed: mean; red: failure thresholds, \
             shaded: the failure region q > threshold",
            q.name
        ),
    );
    put_figure(
        o,
        figures,
        Kind::Cdf(k),
        &format!(
            "Empirical cumulative distribution of {}, with the tabulated quantiles",
            q.name
        ),
    );
    if let Some(s) = &q.surface {
        put_figure(
            o,
            figures,
            Kind::Surface(k),
            &format!(
                "Response surface of {} over {} and {} (surrogate), with the {} collocation points",
                q.name,
                s.param_names[0],
                s.param_names[1],
                s.points.len()
            ),
        );
    }
    o.push_str("</section>\n");
}

/// Sobol' indices of every parameter (KL variables of random fields included).
fn sobol_table(o: &mut String, q: &QoiReport) {
    if q.sobol.is_empty() {
        return;
    }
    let _ = writeln!(
        o,
        "<div class=\"budget\"><h3>Sobol' indices</h3><p class=\"hint\">Share of the variance \
         of {} due to each parameter alone (first order) and with its interactions (total). {}</p>\
         <table><thead><tr><th>Parameter</th><th class=\"n\">First order</th>\
         <th class=\"n\">Total</th></tr></thead><tbody>",
        esc(&q.name),
        esc(&q.sobol_basis)
    );
    for (name, first, total) in &q.sobol {
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
            esc(name),
            num(*first, 3),
            num(*total, 3)
        );
    }
    o.push_str("</tbody></table></div>\n");
}

/// The error budget of each statistic: value, mesh, surrogate, sampling, sliding (when asked
/// for) and total parts.
fn budget_table(o: &mut String, q: &QoiReport, unit: &str) {
    if q.budget.is_empty() {
        return;
    }
    let sliding = q.budget.iter().any(|b| b.sliding.is_some());
    let _ = writeln!(
        o,
        "<div class=\"budget\"><h3>Error budget</h3><p class=\"hint\">How far each statistic \
         can be trusted: estimated error by source (±), and their sum</p>\
         <table><thead><tr><th>Statistic</th><th class=\"n\">Value</th><th class=\"n\">Mesh</th>\
         <th class=\"n\">Surrogate</th><th class=\"n\">Sampling</th>{}<th class=\"n\">Total</th>\
         </tr></thead><tbody>",
        if sliding {
            "<th class=\"n\">Sliding</th>"
        } else {
            ""
        }
    );
    let part = |v: Option<f64>| v.map_or_else(|| "not estimated".to_string(), |v| num(v, 2));
    for b in &q.budget {
        let u = if b.statistic.starts_with('P') {
            ""
        } else {
            unit
        };
        let sliding_cell = if sliding {
            format!("<td class=\"n\">{}</td>", part(b.sliding))
        } else {
            String::new()
        };
        let _ = writeln!(
            o,
            "<tr><th>{}</th><td class=\"n\">{}{u}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>\
             <td class=\"n\">{}</td>{sliding_cell}<td class=\"n\">{}</td></tr>",
            esc(&b.statistic),
            num(b.value, 5),
            part(b.mesh),
            part(b.surrogate),
            num(b.sampling, 2),
            num(b.total, 2)
        );
    }
    o.push_str("</tbody></table>");
    for line in &q.budget_basis {
        let _ = writeln!(o, "<p class=\"hint\">{}</p>", esc(line));
    }
    o.push_str("</div>\n");
}

/// The `[[reliability]]` analyses: the failure probability by each algorithm.
pub(super) fn reliability(o: &mut String, list: &[ReliabilityReport]) {
    if list.is_empty() {
        return;
    }
    o.push_str("<section id=\"reliability\"><h2>Rare events</h2>\n");
    for r in list {
        let _ = writeln!(
            o,
            "<h3>P({} &gt; {}) on the surrogate of {}</h3>",
            esc(&r.quantity),
            num(r.threshold, 5),
            esc(&r.method)
        );
        o.push_str(
            "<table><thead><tr><th>Algorithm</th><th class=\"n\">P<sub>f</sub></th>\
             <th class=\"n\">Confidence interval</th><th class=\"n\">Evaluations</th></tr>\
             </thead><tbody>\n",
        );
        for row in &r.rows {
            let ci = row.interval.map_or_else(
                || "asymptotic (no interval)".to_string(),
                |(a, b)| format!("[{}, {}]", prob(a), prob(b)),
            );
            let _ = writeln!(
                o,
                "<tr><th>{}</th><td class=\"n\">{}</td><td class=\"n\">{ci}</td><td class=\"n\">{}</td></tr>",
                esc(&row.algorithm),
                prob(row.pf),
                count(row.evaluations)
            );
        }
        o.push_str("</tbody></table>\n");
        for n in &r.notes {
            let _ = writeln!(o, "<p class=\"warn\">{}</p>", esc(n));
        }
    }
    o.push_str("</section>\n");
}

pub(super) fn comparison(o: &mut String, c: &Comparison, figures: &[Figure]) {
    let _ = writeln!(
        o,
        "<section id=\"comparison\"><h2>Methods compared on {}</h2>",
        esc(&c.qoi)
    );
    let reference = c
        .rows
        .iter()
        .find(|r| r.method.to_lowercase().contains("reference"));
    o.push_str(
        "<table><thead><tr><th>Method</th><th class=\"n\">Runs</th><th class=\"n\">Mean</th>\
         <th class=\"n\">Std</th>",
    );
    if reference.is_some() {
        o.push_str("<th class=\"n\">Mean vs reference</th><th class=\"n\">Std vs reference</th>");
    }
    o.push_str("</tr></thead><tbody>\n");
    let rel = |v: f64, r: f64| -> String {
        if r != 0.0 {
            let d = 100.0 * (v - r) / r.abs();
            format!("{}{} %", if d > 0.0 { "+" } else { "" }, num(d, 3))
        } else {
            "&mdash;".into()
        }
    };
    for row in &c.rows {
        let is_ref = reference.is_some_and(|r| std::ptr::eq(r, row));
        let _ = write!(
            o,
            "<tr{}><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>",
            if is_ref { " class=\"ref\"" } else { "" },
            esc(&row.method),
            row.runs,
            num(row.mean, 5),
            num(row.std, 4)
        );
        if let Some(r) = reference {
            if is_ref {
                o.push_str("<td class=\"n\">reference</td><td class=\"n\">reference</td>");
            } else {
                let _ = write!(
                    o,
                    "<td class=\"n\">{}</td><td class=\"n\">{}</td>",
                    rel(row.mean, r.mean),
                    rel(row.std, r.std)
                );
            }
        }
        o.push_str("</tr>\n");
    }
    o.push_str("</tbody></table>\n");
    put_figure(
        o,
        figures,
        Kind::Comparison,
        &format!("Probability density of {} by each method", c.qoi),
    );
    o.push_str("</section>\n");
}
