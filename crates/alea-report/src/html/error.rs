//! The stochastic error estimate.

use std::fmt::Write;

use super::super::ErrorReport;
use super::super::format::{esc, num};
use super::super::plots::{Figure, Kind};
use super::figures::put_figure;

fn pct(v: f64) -> String {
    format!("{:.2} %", 100.0 * v)
}

/// The stochastic error estimate: indicators per method and per entity, adaptive steps, the
/// error-density map and the indicators against the runs.
pub(super) fn error_section(o: &mut String, e: &ErrorReport, figures: &[Figure]) {
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
