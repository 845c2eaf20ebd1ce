//! `report.html`: one self-contained page (inline CSS, inline SVG plots, no JavaScript).

use std::fmt::Write;

use super::format::{count, esc, num, prob, seconds};
use super::plots::{Figure, Kind};
use super::{Comparison, QoiReport, ReportInput, RunInfo};

/// Runs shown with the run table open; more and the table starts collapsed.
const OPEN_RUNS: usize = 20;

const CSS: &str = r#"
:root { --ink:#1d2733; --muted:#5b6775; --line:#dde3ea; --band:#f4f6f9; --accent:#0b4f8a;
  --ok:#1e7b34; --bad:#b3261e; --warn-bg:#fff6e0; --warn-line:#e0a100; }
* { box-sizing: border-box; }
body { margin:0; background:#eef1f5; color:var(--ink);
  font: 15px/1.5 "DejaVu Sans", "Segoe UI", Helvetica, Arial, sans-serif; }
main { max-width: 1040px; margin: 0 auto; padding: 0 24px 40px; }
header.top { background: linear-gradient(120deg, #0b3d6b, #0b4f8a 60%, #136fae); color:#fff;
  padding: 28px 0 24px; margin-bottom: 24px; }
header.top .inner { max-width:1040px; margin:0 auto; padding:0 24px; }
header.top h1 { margin:0 0 4px; font-size: 28px; font-weight: 600; letter-spacing: .2px; }
header.top .sub { opacity:.85; font-size:14px; }
.bad { color:#b3261e; }
section { background:#fff; border:1px solid var(--line); border-radius:8px; padding:20px 24px;
  margin: 0 0 20px; box-shadow: 0 1px 2px rgba(20,30,40,.05); }
h2 { font-size: 20px; margin: 0 0 14px; color: var(--accent); font-weight: 600; }
h3 { font-size: 15px; margin: 18px 0 8px; color: var(--muted); text-transform: uppercase;
  letter-spacing: .6px; font-weight: 600; }
dl.meta { display:grid; grid-template-columns: 140px 1fr; gap: 6px 16px; margin:0; }
dl.meta dt { color: var(--muted); }
dl.meta dd { margin:0; }
code { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 13px;
  background: var(--band); padding: 1px 5px; border-radius: 4px; word-break: break-all; }
.chip { display:inline-block; border:1px solid var(--line); background:var(--band);
  border-radius: 12px; padding: 0 10px; margin: 0 6px 4px 0; font-size: 13px; }
.warn { background: var(--warn-bg); border: 1px solid var(--warn-line);
  border-left: 6px solid var(--warn-line); }
.warn h2 { color: #7a5200; }
.warn ul { margin: 0; padding-left: 20px; }
.ok-note { color: var(--muted); font-size: 14px; }
table { border-collapse: collapse; width: 100%; font-size: 14px; }
th, td { padding: 6px 10px; border-bottom: 1px solid var(--line); text-align: left;
  vertical-align: top; }
th { background: var(--band); font-weight: 600; color: #344252; white-space: nowrap; }
td.n, th.n { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.ref td { font-weight: 600; }
tbody tr:hover td { background: #fafbfd; }
.tables { display:flex; flex-wrap: wrap; gap: 0 28px; }
.tables > div { flex: 1 1 auto; min-width: 230px; }
figure { margin: 16px auto 8px; max-width: 900px; }
figure svg.plot { width: 100%; height: auto; display:block; border:1px solid var(--line);
  border-radius: 6px; background:#fff; }
figcaption { font-size: 13px; color: var(--muted); margin-top: 6px; }
figcaption a { color: var(--accent); }
.badge { display:inline-block; padding: 0 8px; border-radius: 10px; font-size: 12px;
  font-weight: 600; white-space: nowrap; }
.badge.ok { background:#e3f4e7; color: var(--ok); }
.badge.bad { background:#fde8e6; color: var(--bad); }
details > summary { cursor: pointer; font-weight: 600; color: var(--accent); margin-bottom: 8px; }
.scroll { overflow-x: auto; }
.bar { display:inline-block; height: 10px; background: #6a9fd0; border-radius: 2px;
  vertical-align: middle; }
.hint { color: var(--muted); font-size: 13px; margin: -4px 0 6px; }
tr.failed td { background: #fff7f6; }
@media print {
  body { background: #fff; }
  header.top { background: none; color: var(--ink); border-bottom: 2px solid var(--accent); }
  section { box-shadow: none; break-inside: avoid-page; }
  figure { break-inside: avoid; }
}
.glance { display:grid; grid-template-columns: repeat(auto-fit, minmax(230px, 1fr)); gap: 12px;
  margin-top: 18px; }
.card { display:block; text-decoration:none; color:inherit; border:1px solid var(--line);
  border-top: 4px solid var(--accent); border-radius: 6px; padding: 10px 14px; background:#fbfcfe; }
.card .name { color: var(--muted); font-size: 13px; }
.card .big { font-size: 22px; font-weight: 600; font-variant-numeric: tabular-nums; }
.card .pm { font-weight: 400; color: #344252; }
.card .unit { font-size: 14px; font-weight: 400; color: var(--muted); }
.card .pf { font-size: 13px; color: #344252; }
.card .ci { color: var(--muted); }
nav.toc { margin-top: 10px; font-size: 13px; }
nav.toc a { color: #fff; opacity: .85; text-decoration: none; margin-right: 14px; }
nav.toc a:hover { opacity: 1; text-decoration: underline; }
footer { color: var(--muted); font-size: 12px; text-align: center; margin-top: 12px; }
"#;

fn figure(figures: &[Figure], kind: Kind) -> Option<&Figure> {
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

fn put_figure(out: &mut String, figures: &[Figure], kind: Kind, caption: &str) {
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

fn with_unit(name: &str, unit: &str) -> String {
    if unit.trim().is_empty() {
        esc(name)
    } else {
        format!("{} [{}]", esc(name), esc(unit))
    }
}

/// The whole page.
pub fn render(input: &ReportInput, figures: &[Figure]) -> String {
    let mut o =
        String::with_capacity(64 * 1024 + figures.iter().map(|f| f.svg.len()).sum::<usize>());
    let title = if input.title.trim().is_empty() {
        "alea study report"
    } else {
        input.title.as_str()
    };
    let _ = write!(
        o,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <meta name=\"generator\" content=\"alea {version}\">\n<title>{t}</title>\n\
         <style>{CSS}</style>\n</head>\n<body>\n\
         <header class=\"top\"><div class=\"inner\"><h1>{t}</h1>\
         <div class=\"sub\">Stochastic study report &middot; alea {version}</div>{nav}</div></header>\n<main>\n",
        t = esc(title),
        version = env!("CARGO_PKG_VERSION"),
        nav = toc(input, figures),
    );
    notes(&mut o, input);
    overview(&mut o, input);
    parameters(&mut o, input);
    for (k, q) in input.qois.iter().enumerate() {
        qoi_section(&mut o, k, q, figures);
    }
    if let Some(c) = &input.comparison {
        comparison(&mut o, c, figures);
    }
    if let Some(e) = &input.error {
        error_section(&mut o, e, figures);
    }
    if figure(figures, Kind::Convergence).is_some() {
        o.push_str("<section id=\"convergence\"><h2>Solver convergence</h2>\n");
        put_figure(
            &mut o,
            figures,
            Kind::Convergence,
            "LATIN error indicator per iteration (log scale), one line per run",
        );
        o.push_str("</section>\n");
    }
    runs(&mut o, input);
    timings(&mut o, input);
    let _ = write!(
        o,
        "<footer>Generated by alea {} &middot; plots also saved as PNG and SVG beside this page</footer>\n\
         </main>\n</body>\n</html>\n",
        env!("CARGO_PKG_VERSION")
    );
    o
}

/// Links to the sections.
fn toc(input: &ReportInput, figures: &[Figure]) -> String {
    let mut links = vec![("study".to_string(), "Study".to_string())];
    if !input.notes.is_empty() {
        links.insert(0, ("warnings".into(), "Warnings".into()));
    }
    links.push(("parameters".into(), "Parameters".into()));
    for (k, q) in input.qois.iter().enumerate() {
        links.push((format!("qoi-{k}"), esc(&q.name)));
    }
    if input.comparison.is_some() {
        links.push(("comparison".into(), "Comparison".into()));
    }
    if input.error.is_some() {
        links.push(("error".into(), "Error estimate".into()));
    }
    if figure(figures, Kind::Convergence).is_some() {
        links.push(("convergence".into(), "Convergence".into()));
    }
    links.push(("runs".into(), "Runs".into()));
    if !input.timings.is_empty() {
        links.push(("timings".into(), "Timings".into()));
    }
    let mut out = String::from("<nav class=\"toc\">");
    for (id, label) in links {
        let _ = write!(out, "<a href=\"#{id}\">{label}</a>");
    }
    out.push_str("</nav>");
    out
}

fn notes(o: &mut String, input: &ReportInput) {
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

fn overview(o: &mut String, input: &ReportInput) {
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
            let _ = write!(
                o,
                "<a class=\"card\" href=\"#qoi-{k}\"><div class=\"name\">{}</div>\
                 <div class=\"big\">{} <span class=\"pm\">± {}</span> \
                 <span class=\"unit\">{unit}</span></div>",
                esc(&q.name),
                num(q.mean, 4),
                num(q.std, 3)
            );
            match q.failure.first() {
                Some(f) => {
                    let _ = write!(
                        o,
                        "<div class=\"pf\">P(q &gt; {}) = {} <span class=\"ci\">[{}, {}]</span></div>",
                        num(f.threshold, 4),
                        prob(f.probability),
                        prob(f.ci_low),
                        prob(f.ci_high)
                    );
                }
                None => o.push_str("<div class=\"pf\">mean ± standard deviation</div>"),
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

fn parameters(o: &mut String, input: &ReportInput) {
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

fn qoi_section(o: &mut String, k: usize, q: &QoiReport, figures: &[Figure]) {
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

fn comparison(o: &mut String, c: &Comparison, figures: &[Figure]) {
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

fn is_converged(r: &RunInfo) -> bool {
    r.status.trim().eq_ignore_ascii_case("converged")
}

fn runs(o: &mut String, input: &ReportInput) {
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

fn timings(o: &mut String, input: &ReportInput) {
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

fn pct(v: f64) -> String {
    format!("{:.2} %", 100.0 * v)
}

/// The stochastic error estimate: indicators per method and per entity, adaptive steps, the
/// error-density map and the indicators against the runs.
fn error_section(o: &mut String, e: &super::ErrorReport, figures: &[Figure]) {
    o.push_str("<section id=\"error\"><h2>Error estimate</h2>\n");
    let _ = writeln!(
        o,
        "<p>Constitutive-relation error of the stochastic solution (thesis 3.2), split into a \
         space part <i>i</i><sub>geo</sub> (the finite-element mesh) and a stochastic part \
         <i>i</i><sub>sto</sub> (the runs and the surrogate), <i>e</i>&#771;<sup>2</sup> = \
         <i>I</i><sub>geo</sub><sup>2</sup> + <i>I</i><sub>sto</sub><sup>2</sup> (4.1-4.9), relative \
         to the energy of the admissible stresses. Values above {} are flagged.</p>",
        esc(&pct(e.warn))
    );
    let flag = |v: f64| {
        if v > e.warn {
            format!("<b class=\"bad\">{}</b>", esc(&pct(v)))
        } else {
            esc(&pct(v))
        }
    };
    o.push_str(
        "<table><thead><tr><th>Method</th><th>Runs</th><th>e&#771;</th><th>i<sub>geo</sub></th>\
         <th>i<sub>sto</sub></th><th>Largest part of e&#771;<sup>2</sup></th>\
         <th>P(not admissible)</th></tr></thead><tbody>\n",
    );
    for r in &e.methods {
        let _ = writeln!(
            o,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(&r.method),
            r.runs,
            esc(&pct(r.relative)),
            flag(r.i_geo),
            flag(r.i_sto),
            esc(&r.dominant),
            num(r.violation, 3)
        );
    }
    o.push_str("</tbody></table>\n");
    if !e.entities.is_empty() {
        let _ = writeln!(
            o,
            "<h3>Per entity ({})</h3><table><thead><tr><th>Entity</th><th>Kind</th><th>e&#771;</th>\
             <th>i<sub>geo</sub></th><th>i<sub>sto</sub></th><th>Mean part of e<sup>2</sup> (3.32)</th></tr></thead><tbody>",
            esc(&e.main)
        );
        for r in &e.entities {
            let _ = writeln!(
                o,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                esc(&r.entity),
                esc(&r.kind),
                esc(&pct(r.relative)),
                esc(&pct(r.i_geo)),
                esc(&pct(r.i_sto)),
                r.mean_share.map_or("-".to_string(), |m| esc(&pct(m)))
            );
        }
        o.push_str("</tbody></table>\n");
    }
    for a in &e.adaptive {
        let _ = writeln!(
            o,
            "<h3>Adaptive steps: {}</h3><p>Stopped: {}. Cost in the thesis's units (tables 4.3-4.4): a run 1, an estimate 1.5.</p>\
             <table><thead><tr><th>Step</th><th>Runs</th><th>New</th><th>i<sub>sto</sub></th><th>i<sub>geo</sub></th>\
             <th>e&#771;</th><th>Mean {q}</th><th>Std {q}</th><th>P<sub>f</sub></th><th>Cost</th></tr></thead><tbody>",
            esc(&a.method),
            esc(&a.stop),
            q = esc(&a.qoi)
        );
        for (k, s) in a.steps.iter().enumerate() {
            let _ = writeln!(
                o,
                "<tr><td>{k}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                s.runs,
                s.new_runs,
                esc(&pct(s.i_sto)),
                esc(&pct(s.i_geo)),
                esc(&pct(s.relative)),
                num(s.mean, 5),
                num(s.std, 4),
                s.failure.map_or("-".to_string(), |p| num(p, 3)),
                num(s.cost, 3)
            );
        }
        o.push_str("</tbody></table>\n");
    }
    put_figure(
        o,
        figures,
        Kind::ErrorMap,
        "Density of the stochastic error over the parameters (contribution to I_sto^2 per unit parameter area; other parameters integrated), with the runs",
    );
    put_figure(
        o,
        figures,
        Kind::Indicators,
        "i_sto (solid) and i_geo (dashed) after each adaptive step",
    );
    if let Some(v) = &e.vtu {
        let _ = writeln!(
            o,
            "<p>Mean error densities for ParaView: <code>{}</code> (cells of substructures with admissible stresses: <code>space_error_density</code>, <code>error_density</code>; interface nodes: <code>interface_error_density</code>, <code>interface_space_error_density</code>, <code>interface_stochastic_error_density</code>; cells along the interfaces: <code>interface_cell_error</code>, <code>interface_cell_space_error</code>, <code>interface_cell_stochastic_error</code>, <code>interface_cell_error_density</code>).</p>",
            esc(v)
        );
    }
    o.push_str("</section>\n");
}
