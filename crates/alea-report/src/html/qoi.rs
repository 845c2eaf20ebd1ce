//! A section per quantity of interest, and the comparison of methods.

use std::fmt::Write;

use super::super::format::{count, esc, num, prob};
use super::super::plots::{Figure, Kind};
use super::super::{Comparison, QoiReport, ReliabilityReport, Statistic};
use super::figures::{put_figure, with_unit};
use super::interval::{Style, estimate, total, with_total};

/// The section of quantity `k`: what it is, its statistics, quantiles, failure probabilities,
/// error budget, Sobol' indices and figures.
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
    let unit = if q.unit.trim().is_empty() {
        String::new()
    } else {
        format!(" {}", esc(&q.unit))
    };
    statistics_table(o, q, &unit);
    quantiles_table(o, q, &unit);
    failure_table(o, q, &unit);
    o.push_str("</div>\n</div>\n");
    budget_table(o, q, &unit);
    sobol_table(o, q);
    qoi_figures(o, k, q, figures);
    o.push_str("</section>\n");
}

/// The statistics (mean, standard deviation with their total intervals, coefficient of
/// variation, skewness, samples) of a quantity (`unit`: its unit with a leading space).
fn statistics_table(o: &mut String, q: &QoiReport, unit: &str) {
    o.push_str("<div><h3>Statistics</h3><table><tbody>\n");
    let row = |o: &mut String, label: &str, value: String| {
        let _ = writeln!(o, "<tr><th>{label}</th><td class=\"n\">{value}</td></tr>");
    };
    // Each with its total interval (issue 40, item 3).
    let (mean, std) = (
        estimate(&q.budget, Statistic::Mean, q.mean),
        estimate(&q.budget, Statistic::Std, q.std),
    );
    let with_interval = |statistic: Statistic, value: f64, sig: usize| {
        let e = num(estimate(&q.budget, statistic, value), sig);
        match total(&q.budget, statistic, Style::Num(sig)) {
            Some(t) => format!("{e}{unit} <span class=\"ci\">total {t}</span>"),
            None => format!("{e}{unit}"),
        }
    };
    row(o, "Mean", with_interval(Statistic::Mean, q.mean, 5));
    row(
        o,
        "Standard deviation",
        with_interval(Statistic::Std, q.std, 4),
    );
    if mean != 0.0 {
        row(
            o,
            "Coefficient of variation",
            format!("{} %", num(100.0 * std / mean.abs(), 3)),
        );
    }
    row(o, "Skewness", num(q.skewness, 3));
    row(o, "Monte Carlo samples", count(q.samples.len()));
    o.push_str("</tbody></table></div>\n");
}

/// The quantiles of a quantity, with their total intervals when any is estimated.
fn quantiles_table(o: &mut String, q: &QoiReport, unit: &str) {
    o.push_str("<div><h3>Quantiles</h3>");
    if q.quantiles.is_empty() {
        o.push_str("<p class=\"ok-note\">None computed.</p>");
    } else {
        let intervals = q
            .quantiles
            .iter()
            .any(|&(p, _)| total(&q.budget, Statistic::Quantile(p), Style::Num(4)).is_some());
        let _ = writeln!(
            o,
            "<table><thead><tr><th class=\"n\">Probability</th><th class=\"n\">Value</th>{}\
             </tr></thead><tbody>",
            if intervals {
                "<th class=\"n\">Total interval</th>"
            } else {
                ""
            }
        );
        for &(p, v) in &q.quantiles {
            let statistic = Statistic::Quantile(p);
            let cell = if intervals {
                format!(
                    "<td class=\"n\">{}</td>",
                    total(&q.budget, statistic, Style::Num(4))
                        .unwrap_or_else(|| "not estimated".into())
                )
            } else {
                String::new()
            };
            let _ = writeln!(
                o,
                "<tr><td class=\"n\">{}</td><td class=\"n\">{}{unit}</td>{cell}</tr>",
                prob(p),
                num(estimate(&q.budget, statistic, v), 4)
            );
        }
        o.push_str("</tbody></table>");
    }
    o.push_str("</div>\n");
}

/// The failure probabilities of a quantity with their total and sampling-only intervals.
fn failure_table(o: &mut String, q: &QoiReport, unit: &str) {
    o.push_str("<div><h3>Failure probability</h3>");
    if q.failure.is_empty() {
        o.push_str("<p class=\"ok-note\">No threshold given.</p>");
    } else {
        o.push_str(
            "<p class=\"hint\">P<sub>f</sub> = P(q &gt; threshold) with its total interval \
             (every estimated part of its error budget), and the interval from the Monte Carlo \
             draws alone (sampling only, Wilson)</p><table><thead><tr>\
             <th class=\"n\">Threshold</th><th class=\"n\">P<sub>f</sub></th>\
             <th class=\"n\">Total interval</th><th class=\"n\">Sampling-only interval</th>\
             </tr></thead><tbody>\n",
        );
        for f in &q.failure {
            let statistic = Statistic::Exceedance(f.threshold);
            let _ = writeln!(
                o,
                "<tr><td class=\"n\">{}{unit}</td><td class=\"n\">{}</td>\
                 <td class=\"n\">{}</td><td class=\"n\">[{}, {}]</td></tr>",
                num(f.threshold, 5),
                prob(estimate(&q.budget, statistic, f.probability)),
                total(&q.budget, statistic, Style::Prob).unwrap_or_else(|| "not estimated".into()),
                prob(f.ci_low),
                prob(f.ci_high)
            );
        }
        o.push_str("</tbody></table>");
    }
}

/// The figures of quantity `k`: its density, distribution and response surface.
fn qoi_figures(o: &mut String, k: usize, q: &QoiReport, figures: &[Figure]) {
    put_figure(
        o,
        figures,
        Kind::Pdf(k),
        &format!(
            "Probability density of {}: kernel density estimate over the normalised histogram \
             of the Monte Carlo samples on the surrogate; dashed: mean, grey band: its total \
             interval; red: failure thresholds, shaded: the failure region q > threshold; a value \
             taken with positive probability (an atom: e.g. many exact zeros where a contact \
             opens) is a stem ending in a dot, its height its probability (the top of the frame: \
             1), and the histogram and the curve are then those of the other values, scaled by \
             their share",
            q.name
        ),
    );
    put_figure(
        o,
        figures,
        Kind::Cdf(k),
        &format!(
            "Empirical cumulative distribution of {}, with the tabulated quantiles and their \
             total intervals (horizontal bars)",
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

/// The error budget of each statistic: value, the corrected value (when validation runs
/// corrected some), mesh, surrogate, sampling, sliding (when asked for) and total parts, and
/// the total interval.
fn budget_table(o: &mut String, q: &QoiReport, unit: &str) {
    if q.budget.is_empty() {
        return;
    }
    let sliding = q.budget.iter().any(|b| b.sliding.is_some());
    let corrected = q.budget.iter().any(|b| b.validation.is_some());
    let _ = writeln!(
        o,
        "<div class=\"budget\"><h3>Error budget</h3><p class=\"hint\">How far each statistic \
         can be trusted: estimated error by source (±), their sum, and the total interval about \
         the statistic{}</p>\
         <table><thead><tr><th>Statistic</th><th class=\"n\">Value</th>{}<th class=\"n\">Mesh</th>\
         <th class=\"n\">Surrogate</th><th class=\"n\">Sampling</th>{}<th class=\"n\">Total</th>\
         <th class=\"n\">Total interval</th></tr></thead><tbody>",
        if corrected {
            " (corrected by the validation runs where they detect the surrogate's error; \"agree\": \
             their difference with the surrogate is within their own noise)"
        } else {
            ""
        },
        if corrected {
            "<th class=\"n\">Corrected</th>"
        } else {
            ""
        },
        if sliding {
            "<th class=\"n\">Sliding</th>"
        } else {
            ""
        }
    );
    let part = |v: Option<f64>| v.map_or_else(|| "not estimated".to_string(), |v| num(v, 2));
    for b in &q.budget {
        let is_p = b.statistic.is_probability();
        let u = if is_p { "" } else { unit };
        let style = if is_p { Style::Prob } else { Style::Num(5) };
        let corrected_cell = match (&b.validation, corrected) {
            (Some(v), _) if v.detected => format!(
                "<td class=\"n\">{} <span class=\"ci\">({} runs)</span></td>",
                style.text(v.value),
                v.runs
            ),
            (Some(v), _) => format!(
                "<td class=\"n\">agree <span class=\"ci\">({} runs)</span></td>",
                v.runs
            ),
            (None, true) => "<td class=\"n\">&mdash;</td>".to_string(),
            (None, false) => String::new(),
        };
        let sliding_cell = if sliding {
            format!("<td class=\"n\">{}</td>", part(b.sliding))
        } else {
            String::new()
        };
        let (lo, hi) = b.interval();
        let _ = writeln!(
            o,
            "<tr><th>{}</th><td class=\"n\">{}{u}</td>{corrected_cell}<td class=\"n\">{}</td>\
             <td class=\"n\">{}</td><td class=\"n\">{}</td>{sliding_cell}<td class=\"n\">{}</td>\
             <td class=\"n\">[{}, {}]</td></tr>",
            esc(&b.statistic.to_string()),
            style.text(b.value),
            part(b.mesh),
            part(b.surrogate),
            num(b.sampling, 2),
            num(b.total, 2),
            style.text(lo),
            style.text(hi)
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

/// The methods side by side: each method's mean, standard deviation and failure
/// probabilities with its own total interval (issue 40, item 3: before, only the first
/// method's budget was shown), and the differences with a reference method if there is one.
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
    // The failure probabilities any method has a budget row of, in their first order.
    let mut thresholds: Vec<Statistic> = Vec::new();
    for b in c.rows.iter().flat_map(|r| &r.budget) {
        if b.statistic.is_probability() && !thresholds.contains(&b.statistic) {
            thresholds.push(b.statistic);
        }
    }
    let _ = write!(
        o,
        "<p class=\"hint\">Each statistic with its method's total interval (every estimated \
         part of its error budget; \"not estimated\" where the method has no budget)</p>\
         <table><thead><tr><th>Method</th><th class=\"n\">Runs</th><th class=\"n\">Mean</th>\
         <th class=\"n\">Std</th>{}",
        thresholds
            .iter()
            .map(|t| format!("<th class=\"n\">{}</th>", esc(&t.to_string())))
            .collect::<String>()
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
    let cell = |rows: &[_], statistic: Statistic, value: Option<f64>, style: Style| match value {
        Some(v) if total(rows, statistic, style).is_some() => with_total(rows, statistic, v, style),
        Some(v) => format!("{} <span class=\"ci\">not estimated</span>", style.text(v)),
        None => "&mdash;".to_string(),
    };
    for row in &c.rows {
        let is_ref = reference.is_some_and(|r| std::ptr::eq(r, row));
        let _ = write!(
            o,
            "<tr{}><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>",
            if is_ref { " class=\"ref\"" } else { "" },
            esc(&row.method),
            row.runs,
            cell(&row.budget, Statistic::Mean, Some(row.mean), Style::Num(5)),
            cell(&row.budget, Statistic::Std, Some(row.std), Style::Num(4))
        );
        for &t in &thresholds {
            let value = row
                .budget
                .iter()
                .find(|b| b.statistic == t)
                .map(|b| b.value);
            let _ = write!(
                o,
                "<td class=\"n\">{}</td>",
                cell(&row.budget, t, value, Style::Prob)
            );
        }
        if let Some(r) = reference {
            if is_ref {
                o.push_str("<td class=\"n\">reference</td><td class=\"n\">reference</td>");
            } else {
                let _ = write!(
                    o,
                    "<td class=\"n\">{}</td><td class=\"n\">{}</td>",
                    rel(
                        estimate(&row.budget, Statistic::Mean, row.mean),
                        estimate(&r.budget, Statistic::Mean, r.mean)
                    ),
                    rel(
                        estimate(&row.budget, Statistic::Std, row.std),
                        estimate(&r.budget, Statistic::Std, r.std)
                    )
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
        &format!(
            "Probability density of {} by each method; a value taken with positive probability \
             (an atom: e.g. many exact zeros where a contact opens) is a stem ending in a dot, its \
             height its probability (the top of the frame: 1; the legend gives it), the curve the \
             density of the other values; bars near the axis: each method's mean with its total \
             interval",
            c.qoi
        ),
    );
    o.push_str("</section>\n");
}
