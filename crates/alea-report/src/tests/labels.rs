//! File stems and tick labels.

use super::super::plots;
use super::fixtures::*;

#[test]
fn file_stems_are_unique_and_safe() {
    let mut input = synthetic();
    let mut twin = input.qois[1].clone();
    twin.name = "max (σ)".into();
    input.qois.push(twin);
    input.qois[0].name = "../../etc/passwd".into();
    assert_eq!(plots::qoi_stems(&input), ["etc_passwd", "max", "max_2"]);
}

#[test]
fn tick_labels_share_one_style_per_axis() {
    let t = plots::ticks(0.0, 0.0032, 7);
    assert_eq!([t(&0.0), t(&0.0005), t(&0.001)], ["0", "0.0005", "0.0010"]);
    let t = plots::ticks(-0.02, 1.04, 10);
    assert_eq!([t(&0.0), t(&0.3), t(&1.0)], ["0", "0.3", "1.0"]);
    let t = plots::ticks(206e3, 274e3, 8);
    assert_eq!(t(&220e3), "220000");
    let t = plots::ticks(0.0, 3e-5, 7);
    assert_eq!(t(&1e-5), "1e-5");
    let t = plots::ticks(5.0, 5.0, 7);
    assert_eq!(t(&5.0), "5");
}
