//! The run table and the timings.

use std::fmt::Write;

use super::super::format::{esc, num, seconds};
use super::super::{ReportInput, RunInfo};
use super::figures::with_unit;

/// Runs shown with the run table open; more and the table starts collapsed.
const OPEN_RUNS: usize = 20;

pub(super) fn is_converged(r: &RunInfo) -> bool {
    r.status.trim().eq_ignore_ascii_case("converged")
}

pub(super) fn runs(o: &mut String, input: &ReportInput) {
    let n = input.runs.len();
    let converged = input.runs.iter().filter(|r| is_converged(r)).count();
    let _ = write!(
        o,
        "<section id=\"runs\"><h2>Runs</h2>\n<details{}><summary>{} runs: {} converged, {} not</summary>\n",
        if n <= OPEN_RUNS { " open=\"open\"" } else { "" },
        n,
        converged,
        n - converged
    );
    if n == 0 {
        o.push_str("<p class=\"ok-note\">No run recorded.</p></details></section>\n");
        return;
    }
    o.push_str("<div class=\"scroll\"><table><thead><tr><th class=\"n\">#</th>");
    for p in &input.parameters {
        let _ = write!(o, "<th class=\"n\">{}</th>", esc(&p.name));
    }
    o.push_str("<th>Status</th><th class=\"n\">Iterations</th><th class=\"n\">Time</th>");
    for q in &input.qois {
        let _ = write!(o, "<th class=\"n\">{}</th>", with_unit(&q.name, &q.unit));
    }
    o.push_str("</tr></thead><tbody>\n");
    for (i, r) in input.runs.iter().enumerate() {
        let _ = write!(
            o,
            "<tr{}><td class=\"n\">{}</td>",
            if is_converged(r) {
                ""
            } else {
                " class=\"failed\""
            },
            i + 1
        );
        for v in &r.params {
            let _ = write!(o, "<td class=\"n\">{}</td>", num(*v, 5));
        }
        let class = if is_converged(r) { "ok" } else { "bad" };
        let _ = write!(
            o,
            "<td><span class=\"badge {class}\">{}</span></td><td class=\"n\">{}</td><td class=\"n\">{}</td>",
            esc(&r.status),
            r.iterations,
            seconds(r.seconds)
        );
        for k in 0..input.qois.len() {
            match r.qois.get(k) {
                Some(v) => {
                    let _ = write!(o, "<td class=\"n\">{}</td>", num(*v, 5));
                }
                None => o.push_str("<td class=\"n\">&mdash;</td>"),
            }
        }
        o.push_str("</tr>\n");
    }
    o.push_str("</tbody></table></div></details></section>\n");
}

pub(super) fn timings(o: &mut String, input: &ReportInput) {
    if input.timings.is_empty() {
        return;
    }
    // A step labelled "total" is the total; otherwise the steps are summed.
    let given_total = input
        .timings
        .iter()
        .find(|(label, _)| label.trim().eq_ignore_ascii_case("total"))
        .map(|t| t.1);
    let total: f64 =
        given_total.unwrap_or_else(|| input.timings.iter().map(|t| t.1.max(0.0)).sum());
    o.push_str(
        "<section id=\"timings\"><h2>Timings</h2><table><thead><tr><th>Step</th>\
         <th class=\"n\">Wall time</th><th class=\"n\">Share</th><th></th></tr></thead><tbody>\n",
    );
    for (label, t) in &input.timings {
        let share = if total > 0.0 { t.max(0.0) / total } else { 0.0 };
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{} %</td>\
             <td style=\"width:40%\"><span class=\"bar\" style=\"width:{:.1}%\"></span></td></tr>",
            esc(label),
            seconds(*t),
            num(100.0 * share, 3),
            100.0 * share
        );
    }
    if given_total.is_some() {
        o.push_str("</tbody></table></section>\n");
        return;
    }
    let _ = writeln!(
        o,
        "<tr><th>Total</th><th class=\"n\">{}</th><th class=\"n\"></th><th></th></tr>",
        seconds(total)
    );
    o.push_str("</tbody></table></section>\n");
}
