//! The command line end to end: the shipped examples run (examples double as tests), and bad
//! case files give a message naming the file, line and field, with the input-error exit code
//! (2), never a panic.

use std::path::PathBuf;
use std::process::Command;

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("alea-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn kirsch_example_gives_the_stress_concentration() {
    let out = tmp("kirsch");
    let o = alea()
        .args([
            "solve",
            root().join("examples/kirsch.toml").to_str().unwrap(),
            "--out",
        ])
        .arg(&out)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // "max von Mises 307.9 MPa at (0.000, 10.000, ...)": the hole top, about 3 x 100 MPa
    // (finite width W/a = 10 raises it by a few percent).
    let vm: f64 = text
        .split("max von Mises ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
        .expect("max von Mises printed");
    assert!((300.0..320.0).contains(&vm), "peak {vm}");
    assert!(text.contains("at (0.000, 10.000"), "{text}");
    assert!(out.join("kirsch.vtu").exists());
}

#[test]
fn dovetail_demo_converges_and_writes_paraview_output() {
    let out = tmp("dovetail");
    let o = alea()
        .args(["demo", "dovetail", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}");
    assert!(text.contains("converged in"), "{text}");
    assert!(out.join("dovetail-contact.vtm").exists());
    assert!(out.join("dovetail-contact/disk.vtu").exists());
    assert!(out.join("dovetail-contact/root.vtu").exists());
}

#[test]
fn bad_case_files_name_file_line_and_field() {
    let base = std::fs::read_to_string(root().join("examples/kirsch.toml")).unwrap();
    let cases: &[(&str, &str, &str)] = &[
        ("young = 210e3", "young = -1.0", "substructure[0].young"),
        ("poisson = 0.3", "poisson = 0.5", "substructure[0].poisson"),
        ("kind = \"quad8\"", "kind = \"quad9\"", "mesh.kind"),
        (
            "group = \"right\"",
            "group = \"rigth\"",
            "substructure[0].load[0].group",
        ),
        (
            "type = \"plane_stress\"",
            "type = \"plane_stres\"",
            "analysis.type",
        ),
        ("thickness = 1.0", "thickness = 1.0\ncolour = 3", "colour"),
        ("young = 210e3", "young = \"steel\"", "young"),
        ("young = 210e3", "young = nan", "substructure[0].young"),
    ];
    let dir = tmp("bad");
    for (i, (from, to, field)) in cases.iter().enumerate() {
        assert!(base.contains(from), "fixture must contain {from}");
        let text = base.replacen(from, to, 1);
        let path = dir.join(format!("bad{i}.toml"));
        std::fs::write(&path, &text).unwrap();
        let o = alea()
            .arg("solve")
            .arg(&path)
            .arg("--out")
            .arg(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "case {i}: {err}");
        assert!(!err.contains("panicked"), "case {i}: {err}");
        assert!(
            err.contains(&format!("bad{i}.toml:")),
            "case {i}: file named: {err}"
        );
        assert!(
            err.contains(field),
            "case {i}: field '{field}' named: {err}"
        );
        // The line number is the line of the changed text.
        let line = text
            .lines()
            .position(|l| l.contains(to.lines().last().unwrap()))
            .unwrap()
            + 1;
        assert!(
            err.contains(&format!(".toml:{line}:")),
            "case {i}: line {line} expected in: {err}"
        );
    }
    let o = alea()
        .args(["solve", "/nonexistent/case.toml"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(3));
}

#[test]
fn three_d_resultants_and_reactions_print_every_component_at_full_precision() {
    // The full-slip example extruded to 3D: hex8 blocks, 4 layers.
    let text = std::fs::read_to_string(root().join("examples/full-slip.toml"))
        .unwrap()
        .replace("kind = \"quad4\"", "kind = \"hex8\"")
        .replace("n_upper = 8 }", "n_upper = 4, depth = 10.0, n_z = 3 }")
        .replace("n_lower = 8", "n_lower = 4")
        .replace("n_x = 16", "n_x = 8")
        .replace(
            "type = \"plane_stress\"\nthickness = 1.0",
            "type = \"solid\"",
        )
        .replace(
            "{ group = \"lower_bottom\", x = 0.0, y = 0.0 }",
            "{ group = \"lower_bottom\", x = 0.0, y = 0.0, z = 0.0 }",
        )
        .replace(
            "{ group = \"upper_top\", x = 0.05 }",
            "{ group = \"upper_top\", x = 0.05, z = 0.0 }",
        )
        .replace("traction = [0.0, -10.0]", "traction = [0.0, -10.0, 0.0]");
    let dir = tmp("3d");
    let case = dir.join("slip3d.toml");
    std::fs::write(&case, &text).unwrap();
    let o = alea()
        .arg("solve")
        .arg(&case)
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{out}\n{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let line = out
        .lines()
        .find(|l| l.contains("resultant on side 2"))
        .expect("resultant printed");
    let comp = |name: &str| -> f64 {
        line.split(&format!("{name} = "))
            .nth(1)
            .and_then(|s| s.split([',', ' ']).next())
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("{name} in {line}"))
    };
    let (fx, fy, fz) = (comp("Fx"), comp("Fy"), comp("Fz"));
    // N = 10 MPa x 40 x 10 mm^2; full slip: |F_t| = 0.3 N pointwise, along x up to the small
    // transverse tractions (which cancel in Fz); no force across z.
    assert!((fy - 4000.0).abs() < 1e-6 * 4000.0, "{line}");
    assert!(fx < 0.0 && (fx + 0.3 * fy).abs() < 1e-4 * fy, "{line}");
    assert!(fz.abs() < 1e-6 * fy, "{line}");
    // Full precision: more than the 5 significant digits printed before.
    assert!(
        line.split("Fy = ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .len()
            > 10,
        "{line}"
    );
    let reaction = out
        .lines()
        .find(|l| l.contains("reaction on") && l.contains("lower_bottom"))
        .expect("reaction printed");
    assert!(
        reaction.contains("Rx = ") && reaction.contains("Ry = ") && reaction.contains("Rz = "),
        "{reaction}"
    );
    assert!(dir.join("slip3d/interface_contact.csv").exists());
}
