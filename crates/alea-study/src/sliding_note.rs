//! The study's warnings about small sliding, from its stored runs: how many runs slid beyond
//! small sliding, on which interface (named, with its two substructures) and the worst run;
//! and how many runs were stored before alea kept each run's slide (their slide is unknown).
//!
//! Each run's largest slide is stored with the run (`crate::store::RunSlide`, computed in
//! `crate::solve`), so these warnings are the same after the run that computed the runs, after
//! a resumption that computes none and after `alea report DIR`: the outputs (`summary.json`'s
//! notes, the report's warnings, Python's `StudyOutputs.notes`) always carry them.

use alea_latin::LatinSolver;
use alea_latin::sliding::SMALL_SLIDING_LIMIT;

use crate::store::{RunRecord, RunSlide};

/// The warnings about small sliding of a study whose runs are `records`, solved by `solver`,
/// with parameters `names`: none if every converged run slid within small sliding.
pub fn sliding_warnings(
    records: &[RunRecord],
    solver: &LatinSolver,
    names: &[String],
) -> Vec<String> {
    let converged: Vec<&RunRecord> = records.iter().filter(|r| r.converged()).collect();
    let contact = (0..solver.num_interfaces()).any(|i| solver.interface_law(i) != "perfect");
    let label = |name: &str| interface_label(solver, name);
    beyond_warning(&converged, names, &label)
        .into_iter()
        .chain(unknown_warning(&converged, contact))
        .collect()
}

/// The slide of a run beyond small sliding, if it is.
fn beyond(r: &RunRecord) -> Option<&RunSlide> {
    r.slide.as_ref().filter(|s| s.ratio > SMALL_SLIDING_LIMIT)
}

/// `'G2' (between 'S1' and 'S2')`: an interface named with its substructures.
fn interface_label(solver: &LatinSolver, name: &str) -> String {
    match (0..solver.num_interfaces()).find(|&i| solver.interface_name(i) == name) {
        Some(i) => {
            let [a, b] = solver.interface_nodes(i).0;
            format!(
                "'{name}' (between '{}' and '{}')",
                solver.sub_name(a),
                solver.sub_name(b)
            )
        }
        None => format!("'{name}'"),
    }
}

/// `E2 = 240000, mu = 0.5`: a run's point with its parameters' names.
fn point_label(params: &[f64], names: &[String]) -> String {
    params
        .iter()
        .enumerate()
        .map(|(i, v)| match names.get(i) {
            Some(n) => format!("{n} = {v}"),
            None => format!("{v}"),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The converged runs beyond small sliding: their count per interface and the worst one.
fn beyond_warning(
    converged: &[&RunRecord],
    names: &[String],
    label: &dyn Fn(&str) -> String,
) -> Option<String> {
    let slid: Vec<(&RunRecord, &RunSlide)> = converged
        .iter()
        .filter_map(|r| beyond(r).map(|s| (*r, s)))
        .collect();
    let (worst_run, worst) = slid
        .iter()
        .copied()
        .max_by(|a, b| a.1.ratio.total_cmp(&b.1.ratio))?;
    let mut per_interface: Vec<(&str, usize)> = Vec::new();
    for (_, s) in &slid {
        match per_interface.iter_mut().find(|(n, _)| *n == s.interface) {
            Some(e) => e.1 += 1,
            None => per_interface.push((&s.interface, 1)),
        }
    }
    let counts = per_interface
        .iter()
        .map(|(n, k)| format!("{k} on interface {}", label(n)))
        .collect::<Vec<_>>()
        .join(", ");
    Some(format!(
        "{} of {} converged runs slid beyond small sliding (more than {} x the local mesh size; \
         {counts}): the pairing no longer pairs the points that face each other and the contact \
         zone, gap and pressure of these runs may be wrong (sliding = \"large\" on the interface \
         re-pairs it in the deformed configuration during the solve); the worst, the run at \
         {}, slid by {:.4e} on interface {}, {:.2} x the local mesh size",
        slid.len(),
        converged.len(),
        SMALL_SLIDING_LIMIT,
        point_label(&worst_run.params, names),
        worst.slip,
        label(&worst.interface),
        worst.ratio,
    ))
}

/// The converged runs whose slide is unknown (stored before alea kept it), in a study with a
/// contact interface (`contact`).
fn unknown_warning(converged: &[&RunRecord], contact: bool) -> Option<String> {
    let unknown = converged.iter().filter(|r| r.slide.is_none()).count();
    (contact && unknown > 0).then(|| {
        format!(
            "{unknown} of {} converged runs were stored before alea kept each run's slide: \
             whether they slid beyond small sliding is not known (`alea run --restart` computes \
             them again with the check)",
            converged.len()
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(p: f64, slide: Option<(&str, f64)>) -> RunRecord {
        let mut r = RunRecord::known(vec![p, 0.5], vec![1.0]);
        r.slide = slide.map(|(interface, ratio)| RunSlide {
            interface: interface.into(),
            slip: 0.4 * ratio,
            ratio,
        });
        r
    }

    #[test]
    fn points_are_named_by_their_parameters() {
        let names = ["E2".to_string(), "mu".to_string()];
        assert_eq!(
            point_label(&[240000.0, 0.5], &names),
            "E2 = 240000, mu = 0.5"
        );
    }

    #[test]
    fn converged_runs_beyond_the_limit_are_counted_per_interface_with_the_worst() {
        let mut failed = run(4.0, Some(("G2", 3.0)));
        failed.status = "not converged".into();
        let runs = [
            run(1.0, Some(("G2", 0.72))),
            run(2.0, Some(("G2", 0.2))),
            run(3.0, Some(("G3", 0.9))),
            run(5.0, Some(("G2", 0.6))),
            failed,
        ];
        let converged: Vec<&RunRecord> = runs.iter().filter(|r| r.converged()).collect();
        let names = ["E2".to_string(), "mu".to_string()];
        let label = |n: &str| format!("'{n}' (between 'S1' and 'S2')");
        let w = beyond_warning(&converged, &names, &label).unwrap();
        assert!(
            w.starts_with("3 of 4 converged runs slid beyond small sliding"),
            "{w}"
        );
        assert!(
            w.contains("2 on interface 'G2' (between 'S1' and 'S2'), 1 on interface 'G3'"),
            "{w}"
        );
        assert!(
            w.contains(
                "the worst, the run at E2 = 3, mu = 0.5, slid by 3.6000e-1 on interface 'G3'"
            ),
            "{w}"
        );
        assert!(w.ends_with("0.90 x the local mesh size"), "{w}");
        // Within small sliding everywhere: no warning.
        assert_eq!(beyond_warning(&converged[1..2], &names, &label), None);
    }

    #[test]
    fn runs_of_unknown_slide_are_counted_only_with_a_contact_interface() {
        let runs = [run(1.0, None), run(2.0, Some(("G2", 0.1))), run(3.0, None)];
        let converged: Vec<&RunRecord> = runs.iter().collect();
        let w = unknown_warning(&converged, true).unwrap();
        assert!(
            w.starts_with("2 of 3 converged runs were stored before"),
            "{w}"
        );
        assert_eq!(unknown_warning(&converged, false), None);
        assert_eq!(unknown_warning(&converged[1..2], true), None);
    }
}
