//! The `ishigami_pc` example runs and gives the variance of Ishigami to 1 %.

#[path = "../examples/ishigami_pc.rs"]
mod ishigami_pc;

#[test]
fn ishigami_example_runs() {
    let (e, loo) = ishigami_pc::run(10, 1000, 1).unwrap();
    let exact = alea_uq::samples::Ishigami::default().variance();
    assert!(
        (e.variance() - exact).abs() < 0.01 * exact,
        "{}",
        e.variance()
    );
    assert!(loo < 1e-2, "{loo}");
}
