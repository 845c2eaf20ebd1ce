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

/// The simple blade root with its root pulled out of the slot (reversed pressure on its lower
/// face, contacts all open): no static equilibrium. `alea solve` must say so, naming the root
/// and its unbalanced force, write its output all the same, and exit with code 4.
#[test]
fn solve_without_static_equilibrium_exits_4() {
    let out = tmp("pulled-out");
    let case = out.join("pulled-out.toml");
    std::fs::write(
        &case,
        r#"
[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "blade_root_simple"
kind = "quad4"
params = { half_width = 35.0, bottom_half_width = 15.0, neck_half_width = 8.0, flank_height = 10.0, shank_height = 15.0, n_flank = 6, n_side = 8, n_root = 6, n_shank = 4 }

[analysis]
type = "plane_strain"
thickness = 1.0

[[substructure]]
name = "S1"
cells = "S1"
young = 210e3
poisson = 0.3
constraint = [ { group = "S1_left", x = 0.0 }, { group = "S1_bottom", y = 0.0 } ]

[[substructure]]
name = "S2"
cells = "S2"
young = 210e3
poisson = 0.3
load = [ { name = "pull", group = "S2_bottom", pressure = -1000.0 } ]

[[substructure]]
name = "S3"
cells = "S3"
young = 210e3
poisson = 0.3
constraint = [ { group = "S3_right", x = 0.0 }, { group = "S3_bottom", y = 0.0 } ]

[[interface]]
name = "G1"
side1 = ["S1", "G1_disk"]
side2 = ["S2", "G1_root"]
law = "coulomb"
mu = 0.5

[[interface]]
name = "G2"
side1 = ["S3", "G2_disk"]
side2 = ["S2", "G2_root"]
law = "coulomb"
mu = 0.5
"#,
    )
    .unwrap();
    let o = alea()
        .args(["solve", case.to_str().unwrap(), "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(4), "{text}");
    assert!(text.contains("NO STATIC EQUILIBRIUM"), "{text}");
    // The whole pull, 1000 MPa over the 30 mm lower face, is unbalanced.
    assert!(
        text.contains("substructure 'S2': unbalanced force ("),
        "{text}"
    );
    assert!(text.contains(", -3.0000e4), moment"), "{text}");
    assert!(out.join("pulled-out.vtm").exists());
}

#[test]
fn three_d_contact_example_prints_every_resultant_component() {
    let out = tmp("block3d");
    let o = alea()
        .args([
            "solve",
            root()
                .join("examples/block-on-plane-3d.toml")
                .to_str()
                .unwrap(),
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
    assert!(text.contains("converged in"), "{text}");
    // "resultant on side 2 (Fx = .., Fy = .., Fz = ..) N", every value at full precision.
    let line = text
        .lines()
        .find(|l| l.contains("interface") && l.contains("resultant on side 2"))
        .expect("interface line");
    let inner = line
        .split("resultant on side 2 (")
        .nth(1)
        .and_then(|s| s.split(')').next())
        .expect("resultant in parentheses");
    let parts: Vec<(&str, f64)> = inner
        .split(", ")
        .map(|p| {
            let (label, v) = p.split_once(" = ").expect("label = value");
            let digits = v.split('e').next().unwrap().replace(['-', '.'], "");
            assert!(digits.len() >= 12, "full precision expected: {v}");
            (label, v.parse().expect("a number"))
        })
        .collect();
    let labels: Vec<&str> = parts.iter().map(|p| p.0).collect();
    assert_eq!(labels, ["Fx", "Fy", "Fz"], "{line}");
    let f: Vec<f64> = parts.iter().map(|p| p.1).collect();
    // Gross slip along (2, 1): Fz = p A = 20, (Fx, Fy) = -mu Fz (2, 1) / sqrt(5) up to the
    // elastic part of the slip (see the example's header).
    let (mu, fz) = (0.3, 20.0);
    assert!((f[2] - fz).abs() < 1e-5 * fz, "Fz = {}", f[2]);
    let want = [-mu * fz * 2.0 / 5f64.sqrt(), -mu * fz / 5f64.sqrt()];
    let ft = (f[0] * f[0] + f[1] * f[1]).sqrt();
    assert!((ft - mu * fz).abs() < 1e-4 * mu * fz, "|F_t| = {ft}");
    for c in 0..2 {
        assert!(
            (f[c] - want[c]).abs() < 3e-3 * mu * fz,
            "component {c}: {} vs {}",
            f[c],
            want[c]
        );
    }
    assert!(out.join("block-on-plane-3d.vtm").exists());
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
            .and_then(|s| s.split([',', ' ', ')']).next())
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

/// Interface pairing errors (sides that do not match node to node, nothing to pair within the
/// mortar search distance) are input errors: exit code 2, naming the file, the line and the
/// field of the `[[interface]]` entry.
#[test]
fn interface_pairing_errors_name_file_line_and_field() {
    let base = std::fs::read_to_string(root().join("examples/dovetail-contact.toml")).unwrap();
    let side2 = "side2 = [\"root\", \"flank_right_root\"]";
    assert!(base.contains(side2));
    let far = "side2 = [\"root\", \"root_top\"]";
    let cases: &[(&str, &str, &str)] = &[
        // Node to node only: the root's top does not match the disk's flank.
        (
            "pairing = \"node\"\n",
            "interface[1].tolerance",
            "do not match node to node",
        ),
        // Mortar (auto falls back to it): nothing of the root's top faces the flank closely.
        ("", "interface[1].side2", "no part of side 2 faces side 1"),
        (
            "search_distance = 0.5\n",
            "interface[1].search_distance",
            "no part of side 2 faces side 1",
        ),
    ];
    let dir = tmp("pairing");
    for (i, (extra, field, needle)) in cases.iter().enumerate() {
        let text = base.replacen(side2, &format!("{extra}{far}"), 1);
        let path = dir.join(format!("pairing{i}.toml"));
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
        assert!(err.contains(field), "case {i}: field '{field}': {err}");
        assert!(err.contains(needle), "case {i}: '{needle}': {err}");
        assert!(err.contains("'flank_right'"), "case {i}: {err}");
        // The line of the field in the entry (of side2 when the field is not given).
        let start = text
            .lines()
            .position(|l| l.contains("name = \"flank_right\""))
            .unwrap();
        let entry: Vec<(usize, &str)> = text
            .lines()
            .enumerate()
            .skip(start)
            .take_while(|(k, l)| *k == start || !l.starts_with('['))
            .collect();
        let key = field.rsplit('.').next().unwrap();
        let find = |key: &str| {
            entry
                .iter()
                .find(|(_, l)| l.starts_with(&format!("{key} =")))
                .map(|(k, _)| k + 1)
        };
        let line = find(key).or_else(|| find("side2")).unwrap();
        assert!(
            err.contains(&format!("pairing{i}.toml:{line}:")),
            "case {i}: line {line} expected in: {err}"
        );
    }
}
