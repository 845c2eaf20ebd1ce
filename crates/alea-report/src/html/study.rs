//! Warnings, the study overview and the random parameters.

use std::fmt::Write;

use super::super::format::{esc, num, prob};
use super::super::{BudgetRow, ReportInput, Statistic, budget_row};
use super::runs::is_converged;

pub(super) fn notes(o: &mut String, input: &ReportInput) {
    if input.notes.is_empty() {
        return;
    }
    let _ = writeln!(
        o,
        "<section class=\"warn\" id=\"warnings\"><h2>&#9888; Warnings ({})</h2><ul>",
        input.notes.len()
    );
    for n in &input.notes {
        let _ = writeln!(o, "<li>{}</li>", esc(n));
    }
    o.push_str("</ul></section>\n");
}

pub(super) fn overview(o: &mut String, input: &ReportInput) {
    o.push_str("<section id=\"study\"><h2>Study</h2><dl class=\"meta\">\n");
    let _ = writeln!(
        o,
        "<dt>Study file</dt><dd><code>{}</code></dd>",
        esc(&input.study_file)
    );
    let _ = writeln!(o, "<dt>Method</dt><dd>{}</dd>", esc(&input.method));
    let converged = input.runs.iter().filter(|r| is_converged(r)).count();
    let _ = writeln!(
        o,
        "<dt>Runs</dt><dd>{} ({} converged)</dd>",
        input.runs.len(),
        converged
    );
    o.push_str("<dt>Units</dt><dd>");
    if input.units.is_empty() {
        o.push_str("&mdash;");
    }
    for (kind, unit) in &input.units {
        let _ = write!(
            o,
            "<span class=\"chip\">{}: {}</span>",
            esc(kind),
            esc(unit)
        );
    }
    o.push_str("</dd>\n</dl>\n");
    // At a glance: one card per QoI.
    if !input.qois.is_empty() {
        o.push_str("<div class=\"glance\">\n");
        for (k, q) in input.qois.iter().enumerate() {
            let unit = esc(&q.unit);
            // The mean with the total of its error budget (issue 40, item 3: "mean +- std"
            // read as an error bar), corrected by the validation runs where there are some;
            // the standard deviation on its own line.
            let mean = budget_row(&q.budget, Statistic::Mean);
            let bar = mean.map_or_else(String::new, |r| {
                format!("<span class=\"pm\">± {}</span> ", num(r.total, 2))
            });
            let _ = write!(
                o,
                "<a class=\"card\" href=\"#qoi-{k}\"><div class=\"name\">{}</div>\
                 <div class=\"big\">{} {bar}<span class=\"unit\">{unit}</span></div>\
                 <div class=\"pf\">mean{}; standard deviation {} {unit}</div>",
                esc(&q.name),
                num(mean.map_or(q.mean, BudgetRow::estimate), 4),
                if bar.is_empty() {
                    ""
                } else {
                    " ± the total of its error budget"
                },
                num(
                    budget_row(&q.budget, Statistic::Std).map_or(q.std, BudgetRow::estimate),
                    3
                )
            );
            if let Some(f) = q.failure.first() {
                let row = budget_row(&q.budget, Statistic::Exceedance(f.threshold));
                let interval = match row {
                    Some(r) => {
                        let (lo, hi) = r.interval();
                        format!("total [{}, {}]", prob(lo), prob(hi))
                    }
                    None => format!("sampling only [{}, {}]", prob(f.ci_low), prob(f.ci_high)),
                };
                let _ = write!(
                    o,
                    "<div class=\"pf\">P(q &gt; {}) = {} <span class=\"ci\">{interval}</span></div>",
                    num(f.threshold, 4),
                    prob(row.map_or(f.probability, BudgetRow::estimate))
                );
            }
            o.push_str("</a>\n");
        }
        o.push_str("</div>\n");
    }
    o.push_str("</section>\n");
}

fn bound(v: f64) -> String {
    num(v, 6)
}

pub(super) fn parameters(o: &mut String, input: &ReportInput) {
    o.push_str("<section id=\"parameters\"><h2>Random parameters</h2>\n");
    if input.parameters.is_empty() {
        o.push_str("<p class=\"ok-note\">No random parameter.</p></section>\n");
        return;
    }
    o.push_str(
        "<table><thead><tr><th>Parameter</th><th>Law</th><th class=\"n\">Lower bound</th>\
         <th class=\"n\">Upper bound</th></tr></thead><tbody>\n",
    );
    for p in &input.parameters {
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>",
            esc(&p.name),
            esc(&p.law),
            bound(p.lo),
            bound(p.hi)
        );
    }
    o.push_str("</tbody></table></section>\n");
}
