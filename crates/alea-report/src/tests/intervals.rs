//! Issue 40, item 3: every interval the report shows is the total one (the budget rows'
//! `interval()` about their `estimate()`), the sampling-only one labelled as such, and a
//! probability atom drawn as an atom.

use alea_study::atoms::split_atoms;
use alea_study::budget::validation::Corrected;
use alea_uq::kde::Bandwidth;

use super::super::*;
use super::fixtures::*;

/// The failure table gives P with the total interval of its budget row and the Wilson
/// interval in its own column, labelled sampling-only.
#[test]
fn failure_table_gives_the_total_interval_and_labels_the_sampling_one() {
    let input = synthetic();
    let dir = out_dir("failure-table");
    let files = write_report(&dir, &input).unwrap();
    let html = std::fs::read_to_string(&files.html).unwrap();
    // The P(> 14) row: 0.02275 +- (0.00375 + 0.00025) = [0.01875, 0.02675].
    let row = "<td class=\"n\">0.02275</td><td class=\"n\">[0.01875, 0.02675]</td>\
               <td class=\"n\">[0.0207, 0.0248]</td>";
    assert!(html.contains(row), "no failure row with both intervals");
    assert!(html.contains("<th class=\"n\">Sampling-only interval</th>"));
    // P(> 40) has no budget row: its total interval is not estimated, not the sampling one.
    assert!(html.contains("<td class=\"n\">0</td><td class=\"n\">not estimated</td>"));
    // The card: the total interval of the first threshold.
    assert!(html.contains("total [0.01875, 0.02675]"), "card");
    // The statistics table: the mean with its total interval.
    assert!(html.contains("10 N·mm <span class=\"ci\">total [9.952, 10.048]</span>"));
    // The quantiles' total intervals; q0.01 has no row.
    assert!(html.contains("<th class=\"n\">Total interval</th>"));
    assert!(html.contains(
        "<td class=\"n\">0.01</td><td class=\"n\">5.348 N·mm</td><td class=\"n\">not estimated</td>"
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every compared method shows its own statistics with its own total interval; a method
/// without a budget says so.
#[test]
fn methods_compared_each_with_its_own_interval() {
    let input = synthetic();
    let dir = out_dir("compared");
    let files = write_report(&dir, &input).unwrap();
    let html = std::fs::read_to_string(&files.html).unwrap();
    let section = &html[html.find("id=\"comparison\"").unwrap()..];
    for cell in [
        // standard polynomial: mean 10.3 +- 0.26, std 2.6 +- 0.51.
        "10.3 <span class=\"ci\">[10.04, 10.56]</span>",
        "2.6 <span class=\"ci\">[2.09, 3.11]</span>",
        // chaos: 10.05 +- 0.125.
        "10.05 <span class=\"ci\">[9.925, 10.175]</span>",
        // the grid has no budget.
        "9.9 <span class=\"ci\">not estimated</span>",
        // the reference: sampling only, 10 +- 0.03125.
        "10 <span class=\"ci\">[9.9688, 10.031]</span>",
    ] {
        assert!(section.contains(cell), "no {cell}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A row corrected by validation runs: its corrected value is what the page reads, its total
/// interval about it.
#[test]
fn corrected_estimates_are_what_the_page_reads() {
    let mut input = synthetic();
    let rows = &mut input.qois[0].budget;
    rows[0].validation = Some(Corrected {
        value: 10.5,
        half_width: 0.04,
        runs: 40,
        detected: true,
        bound: 0.6,
        difference: 0.5,
        atom: false,
    });
    let dir = out_dir("corrected");
    let files = write_report(&dir, &input).unwrap();
    let html = std::fs::read_to_string(&files.html).unwrap();
    // The card and the statistics table: 10.5 +- 0.048.
    assert!(html.contains("<div class=\"big\">10.5 <span class=\"pm\">± 0.048</span>"));
    assert!(html.contains("10.5 N·mm <span class=\"ci\">total [10.452, 10.548]</span>"));
    // The budget table: the surrogate's value and the corrected one side by side.
    assert!(html.contains("<th class=\"n\">Corrected</th>"));
    assert!(html.contains("<td class=\"n\">10.5 <span class=\"ci\">(40 runs)</span></td>"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Half the samples exactly 0 (a contact that opens): the density plots draw an atom of
/// probability 0.5 with its sampling interval, and the kernel density of the rest (mass 0.5),
/// not a spike; in the comparison too.
#[test]
fn an_atom_is_drawn_as_an_atom() {
    let mut input = synthetic();
    let mut rng = Rng(7);
    let samples: Vec<f64> = (0..20_000)
        .map(|i| if i % 2 == 0 { 0.0 } else { 1.0 + rng.uniform() })
        .collect();
    let law = split_atoms(&samples, Bandwidth::Isj, 256, 0.95).unwrap();
    assert_eq!(law.atoms.len(), 1);
    assert_eq!(law.atoms[0].probability, 0.5);
    let mass: f64 = law
        .kde
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
        .sum();
    assert!((mass - 0.5).abs() < 5e-3, "continuous mass {mass}");
    let q = &mut input.qois[0];
    q.samples = samples;
    q.kde = law.kde.clone();
    q.atoms = law.atoms.clone();
    q.mean = 0.75;
    q.budget = vec![
        row("mean", 0.75, Some(0.05), 0.01),
        row("q0.5", 0.5, Some(0.2), 0.01),
        row("q0.95", 1.9, Some(0.04), 0.01),
    ];
    q.failure.truncate(0);
    q.surface = None;
    let c = input.comparison.as_mut().unwrap();
    c.rows[1].kde = law.kde.clone();
    c.rows[1].atoms = law.atoms.clone();
    let dir = std::env::var_os("ALEA_REPORT_TEST_OUT")
        .map_or_else(|| out_dir("atom"), std::path::PathBuf::from);
    let files = write_report(&dir, &input).unwrap();
    let pdf = std::fs::read_to_string(dir.join("pdf_friction_work.svg")).unwrap();
    assert!(
        pdf.contains("atom P(q = 0) = 0.5 [0.4931, 0.5069] (sampling only)"),
        "no atom in the legend"
    );
    assert!(pdf.contains("kernel density estimate off the atoms"));
    assert!(
        pdf.contains("mean&apos;s total interval [0.69, 0.81]")
            || pdf.contains("mean's total interval [0.69, 0.81]")
    );
    let cmp = std::fs::read_to_string(dir.join("comparison.svg")).unwrap();
    assert!(cmp.contains("P(q = 0) = 0.5"), "no atom in the comparison");
    let cdf = std::fs::read_to_string(dir.join("cdf_friction_work.svg")).unwrap();
    assert!(cdf.contains("total intervals of the quantiles"));
    assert!(files.html.exists());
    if std::env::var_os("ALEA_REPORT_TEST_OUT").is_none() {
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
