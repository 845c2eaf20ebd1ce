//! Contact quantities against identities they must satisfy, on a coarse copy of the simple
//! blade root (`examples/blade-root-simple.toml`, every cell count divided by 3):
//! - on a straight flank the normal is constant, so the integrated contact pressure equals
//!   the normal component of the resultant force on side 2 (`interface_force`);
//! - the open, stick and slip zones partition the flank: their lengths add up to its length
//!   (10 sqrt 2 mm times the thickness), and `closed` = stick + slip;
//! - the root is held by its flanks only: the vertical resultants on it balance the pressure
//!   p = 1000 on its 36 mm bottom face (the shank pressures cancel);
//! - at a point, the status indicator is 0 or 1 and the pointwise pressure and slip of the
//!   interface point nearest to it are consistent with that status (no pressure where open,
//!   no slip where it sticks);
//! - the friction work is mu times the integral of pressure x slip (Coulomb: |F_t| = mu p
//!   where it slips, no slip where it sticks), checked against the sum of the pointwise
//!   values over all interface points.

use alea_latin::LatinSolver;
use alea_study::Source;
use alea_study::runner::Study;

const EXTRA: &str = r#"
[[quantity]]
name = "p_int"
kind = "contact_pressure"
interface = "G2"

[[quantity]]
name = "Rx"
kind = "interface_force"
interface = "G2"
component = 0

[[quantity]]
name = "Ry"
kind = "interface_force"
interface = "G2"
component = 1

[[quantity]]
name = "Ry1"
kind = "interface_force"
interface = "G1"
component = 1

[[quantity]]
name = "open"
kind = "contact_status"
interface = "G2"
status = "open"

[[quantity]]
name = "stick"
kind = "contact_status"
interface = "G2"
status = "stick"

[[quantity]]
name = "slip"
kind = "contact_status"
interface = "G2"
status = "slip"

[[quantity]]
name = "closed"
kind = "contact_status"
interface = "G2"
"#;

fn study() -> Study {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/blade-root-simple.toml");
    let text = std::fs::read_to_string(path).unwrap().replace(
        "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27",
        "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9",
    );
    assert!(text.contains("n_flank = 12"));
    Study::from_source(Source::from_text("blade.toml", &format!("{text}\n{EXTRA}"))).unwrap()
}

/// Quantities at point `(x, y)` of G2: pressure, slip, and the status indicators.
fn at_point(x: f64, y: f64) -> String {
    let mut s = String::new();
    for (name, kind, status) in [
        ("pt_p", "contact_pressure", ""),
        ("pt_s", "contact_slip", ""),
        ("pt_open", "contact_status", "open"),
        ("pt_stick", "contact_status", "stick"),
        ("pt_slip", "contact_status", "slip"),
    ] {
        s.push_str(&format!(
            "\n[[quantity]]\nname = \"{name}\"\nkind = \"{kind}\"\ninterface = \"G2\"\npoint = [{x}, {y}]\n"
        ));
        if !status.is_empty() {
            s.push_str(&format!("status = \"{status}\"\n"));
        }
    }
    s
}

#[test]
fn contact_quantities_satisfy_equilibrium_and_partition_identities() {
    let base = study();
    let q = |n: &str| base.qois.iter().position(|q| q.name == n).unwrap();
    let solver = LatinSolver::new(base.model.assembly.clone(), base.model.options.clone()).unwrap();
    let flank = 10.0 * 2f64.sqrt();
    // G2's side-1 normal (outward from S3, toward the root): (-1, -1)/sqrt 2.
    let n = [
        -std::f64::consts::FRAC_1_SQRT_2,
        -std::f64::consts::FRAC_1_SQRT_2,
    ];
    for mu in [0.1, 0.5, 0.9] {
        let res = solver
            .run_shared(&base.model.parametric.run_input(&[240e3, mu]))
            .unwrap();
        let v = |name: &str| base.qois[q(name)].eval(&solver, &res).unwrap();
        let rn = v("Rx") * n[0] + v("Ry") * n[1];
        assert!(
            (v("p_int") - rn).abs() < 1e-9 * rn.abs(),
            "mu {mu}: {} vs {rn}",
            v("p_int")
        );
        assert!(v("p_int") > 0.0);
        let total = v("open") + v("stick") + v("slip");
        assert!((total - flank).abs() < 1e-9 * flank, "mu {mu}: {total}");
        assert!((v("closed") - v("stick") - v("slip")).abs() < 1e-12);
        // Vertical equilibrium of the root: both flanks carry p x 36.
        let ry = v("Ry") + v("Ry1");
        assert!((ry + 36_000.0).abs() < 1e-3 * 36_000.0, "mu {mu}: {ry}");
        // Friction work = mu sum_i w_i p_i s_i over the interface points.
        let g2 = res.interfaces.iter().find(|i| i.name == "G2").unwrap();
        let mut ps = 0.0;
        for i in 0..g2.points.len() {
            let nn = g2.points[i].normal;
            let f = g2.fhat[1][i];
            let p = f[0] * nn[0] + f[1] * nn[1];
            let j = g2.jump(i);
            let jn = j[0] * nn[0] + j[1] * nn[1];
            let s = ((j[0] - jn * nn[0]).powi(2) + (j[1] - jn * nn[1]).powi(2)).sqrt();
            if g2.status[i] != alea_latin::PointStatus::Open {
                ps += g2.weights[i] * p * s;
            }
        }
        let t = v("T");
        assert!(
            (t - mu * ps).abs() < 1e-6 * t,
            "mu {mu}: T {t} vs {}",
            mu * ps
        );
    }
    // Pointwise values along the flank at mu = 0.9 (open near the neck, stick in the middle,
    // slip toward the bottom): each point's status is one of the three, and consistent.
    let mut seen = [false; 3];
    for k in 1..12 {
        let y = 10.0 * k as f64 / 12.0;
        let st = Study::from_source(Source::from_text(
            "blade.toml",
            &format!("{}\n{}", base.source.text, at_point(18.0 - y, y)),
        ))
        .unwrap();
        let solver = LatinSolver::new(st.model.assembly.clone(), st.model.options.clone()).unwrap();
        let res = solver
            .run_shared(&st.model.parametric.run_input(&[240e3, 0.9]))
            .unwrap();
        let v = |name: &str| {
            let i = st.qois.iter().position(|q| q.name == name).unwrap();
            st.qois[i].eval(&solver, &res).unwrap()
        };
        let (open, stick, slip) = (v("pt_open"), v("pt_stick"), v("pt_slip"));
        assert_eq!(open + stick + slip, 1.0, "y = {y}");
        if open == 1.0 {
            assert_eq!(v("pt_p"), 0.0);
            seen[0] = true;
        } else {
            assert!(v("pt_p") > 0.0);
        }
        if stick == 1.0 {
            assert!(v("pt_s") < 1e-12, "y = {y}: slip {}", v("pt_s"));
            seen[1] = true;
        }
        if slip == 1.0 {
            assert!(v("pt_s") > 0.0);
            seen[2] = true;
        }
    }
    assert_eq!(
        seen,
        [true, true, true],
        "open, stick and slip all met along the flank"
    );
}
