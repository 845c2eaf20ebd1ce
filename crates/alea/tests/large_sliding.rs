//! `alea solve` with `sliding = "large"` (issue 21): a block pressed by 10 MPa on a clamped base
//! and slid by 0.8 mm (8 base cells) by its top, friction 0.2, non-matching meshes written here
//! as a Gmsh 4.1 file. Large sliding pairs in the predicted slid configuration (one pairing
//! settles) and keeps the closed-form resultants
//! (N = 10 N/mm, T = mu N) with no small-sliding warning; small sliding warns and names the
//! setting, and so does a study; a bad `sliding` value, large sliding on a perfect interface and
//! large sliding in a study that estimates its error are refused at load (exit 2) at their
//! line. A study with large sliding (random `mu`) keeps the closed form at every run.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::text;

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn tmp(name: &str) -> PathBuf {
    common::fresh_dir("alea-large", name)
}

/// Two structured Quad4 rectangles with their own nodes: base `[0, 4] x [-1, 0]` (40 x 10) and
/// block `[1, 2] x [0, 0.5]` (12 x 6), curve groups `<body>_bottom` / `<body>_top`.
fn write_msh(path: &Path) {
    let bodies = [
        ("base", [0.0, -1.0], [4.0, 1.0], [40usize, 10usize]),
        ("block", [1.0, 0.0], [1.0, 0.5], [12, 6]),
    ];
    let mut nodes: Vec<Vec<(usize, f64, f64)>> = Vec::new();
    let mut quads: Vec<Vec<[usize; 4]>> = Vec::new();
    let mut lines: Vec<(String, Vec<[usize; 2]>)> = Vec::new();
    let mut next = 1;
    for (name, x0, l, n) in bodies {
        let first = next;
        let tag = |i: usize, j: usize| first + i + (n[0] + 1) * j;
        let mut ns = Vec::new();
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                ns.push((
                    tag(i, j),
                    x0[0] + l[0] * i as f64 / n[0] as f64,
                    x0[1] + l[1] * j as f64 / n[1] as f64,
                ));
            }
        }
        next += ns.len();
        nodes.push(ns);
        let mut qs = Vec::new();
        for j in 0..n[1] {
            for i in 0..n[0] {
                qs.push([tag(i, j), tag(i + 1, j), tag(i + 1, j + 1), tag(i, j + 1)]);
            }
        }
        quads.push(qs);
        for (face, j) in [("bottom", 0), ("top", n[1])] {
            let seg = (0..n[0]).map(|i| [tag(i, j), tag(i + 1, j)]).collect();
            lines.push((format!("{name}_{face}"), seg));
        }
    }
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n6\n");
    for (t, (name, _)) in lines.iter().enumerate() {
        writeln!(s, "1 {} \"{name}\"", t + 1).unwrap();
    }
    for (t, (name, ..)) in bodies.iter().enumerate() {
        writeln!(s, "2 {} \"{name}\"", t + 1).unwrap();
    }
    s.push_str("$EndPhysicalNames\n$Entities\n0 4 2 0\n");
    for t in 1..=4 {
        writeln!(s, "{t} 0 0 0 0 0 0 1 {t} 0").unwrap();
    }
    for t in 1..=2 {
        writeln!(s, "{t} 0 0 0 0 0 0 1 {t} 0").unwrap();
    }
    let total: usize = nodes.iter().map(Vec::len).sum();
    writeln!(s, "$EndEntities\n$Nodes\n2 {total} 1 {total}").unwrap();
    for (b, ns) in nodes.iter().enumerate() {
        writeln!(s, "2 {} 0 {}", b + 1, ns.len()).unwrap();
        for n in ns {
            writeln!(s, "{}", n.0).unwrap();
        }
        for n in ns {
            writeln!(s, "{:.17e} {:.17e} 0", n.1, n.2).unwrap();
        }
    }
    let nelem: usize =
        quads.iter().map(Vec::len).sum::<usize>() + lines.iter().map(|l| l.1.len()).sum::<usize>();
    writeln!(s, "$EndNodes\n$Elements\n6 {nelem} 1 {nelem}").unwrap();
    let mut e = 1;
    for (t, (_, seg)) in lines.iter().enumerate() {
        writeln!(s, "1 {} 1 {}", t + 1, seg.len()).unwrap();
        for l in seg {
            writeln!(s, "{e} {} {}", l[0], l[1]).unwrap();
            e += 1;
        }
    }
    for (t, qs) in quads.iter().enumerate() {
        writeln!(s, "2 {} 3 {}", t + 1, qs.len()).unwrap();
        for q in qs {
            writeln!(s, "{e} {} {} {} {}", q[0], q[1], q[2], q[3]).unwrap();
            e += 1;
        }
    }
    s.push_str("$EndElements\n");
    std::fs::write(path, s).unwrap();
}

const CASE: &str = r#"[units]
length = "mm"
force = "N"
stress = "MPa"

[mesh]
generator = "gmsh"
file = "slide.msh"

[analysis]
type = "plane_strain"
thickness = 1.0

[[substructure]]
name = "base"
cells = "base"
young = 210e3
poisson = 0.3
constraint = [ { group = "base_bottom", x = 0.0, y = 0.0 } ]

[[substructure]]
name = "block"
cells = "block"
young = 210e3
poisson = 0.3
constraint = [ { group = "block_top", x = 0.8 } ]
load = [ { name = "press", group = "block_top", traction = [0.0, -10.0] } ]

[[interface]]
name = "contact"
side1 = ["base", "base_top"]
side2 = ["block", "block_bottom"]
law = "coulomb"
mu = 0.2
sliding = "large"
"#;

/// Writes the case with `edits` applied into `dir` (with the mesh); returns its path and text.
fn case(dir: &Path, name: &str, edits: &[(&str, &str)], tail: &str) -> (PathBuf, String) {
    write_msh(&dir.join("slide.msh"));
    common::write_case(dir, name, CASE, edits, tail)
}

fn solve(case: &Path, out: &Path) -> Output {
    alea()
        .args(["solve", case.to_str().unwrap(), "--out"])
        .arg(out)
        .output()
        .unwrap()
}

/// `(Fx, Fy)` of the "resultant on side 2" line.
fn resultant(t: &str) -> (f64, f64) {
    let r = t
        .lines()
        .find_map(|l| l.split("resultant on side 2 (").nth(1))
        .expect("a resultant line");
    let num = |key: &str| -> f64 {
        let rest = r.split(key).nth(1).unwrap();
        rest.split([',', ')'])
            .next()
            .unwrap()
            .trim()
            .parse()
            .unwrap()
    };
    (num("Fx = "), num("Fy = "))
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("'{needle}' not in the file"))
        + 1
}

fn expect_input_error(o: &Output, file: &Path, line: usize, field: &str) {
    let t = text(o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(!t.contains("panicked"), "{t}");
    let name = file.file_name().unwrap().to_string_lossy();
    assert!(
        t.contains(&format!("{name}:{line}: {field}")),
        "'{name}:{line}: {field}' expected in: {t}"
    );
}

#[test]
fn large_sliding_re_pairs_and_small_sliding_warns() {
    let dir = tmp("solve");
    let (p, _) = case(&dir, "large", &[], "");
    let o = solve(&p, &dir.join("out-large"));
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("large sliding: 1 pairing(s)"), "{t}");
    assert!(!t.contains("warning: interface"), "{t}");
    let (fx, fy) = resultant(&t);
    // N = 10 MPa x 1 mm; the block slides in +x: friction -mu N on it.
    assert!((fy - 10.0).abs() < 1e-3, "{t}");
    assert!((fx + 2.0).abs() < 1e-3, "{t}");
    assert!(dir.join("out-large/large/interface_contact.csv").is_file());

    // Small sliding from a cold start needs ~10 000 iterations on this slide (the default
    // 2 000 end as "not converged"); large sliding starts from the predicted slide. That count
    // depends on round-off (Anderson acceleration while the block drifts: BENCHMARKS.md, issue
    // 41), so the linear stage is fixed to the volume path, whose rounding gives 10 210.
    let (p, _) = case(
        &dir,
        "small",
        &[("sliding = \"large\"", "")],
        "\n[solver]\nmax_iterations = 20000\nlinear_stage = \"volume\"\n",
    );
    let o = solve(&p, &dir.join("out-small"));
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(!t.contains("large sliding:"), "{t}");
    assert!(
        t.contains("beyond small sliding") && t.contains("sliding = \"large\""),
        "{t}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_sliding_settings_are_refused_at_their_line() {
    let dir = tmp("misuse");
    let (p, s) = case(
        &dir,
        "huge",
        &[("sliding = \"large\"", "sliding = \"huge\"")],
        "",
    );
    expect_input_error(
        &solve(&p, &dir.join("o")),
        &p,
        line_of(&s, "sliding ="),
        "interface[0].sliding",
    );
    let (p, s) = case(
        &dir,
        "perfect",
        &[("law = \"coulomb\"", "law = \"perfect\"")],
        "",
    );
    expect_input_error(
        &solve(&p, &dir.join("o")),
        &p,
        line_of(&s, "sliding ="),
        "interface[0].sliding",
    );
    let study_tail = "\n[study]\ntitle = \"slide\"\n\n[[quantity]]\nname = \"fy\"\nkind = \"interface_force\"\ninterface = \"contact\"\ncomponent = 1\n";
    // A study with small sliding: the run slides beyond it, and the study says so.
    let (p, _) = case(
        &dir,
        "study-small",
        &[("sliding = \"large\"", "")],
        &format!("{study_tail}\n[solver]\nmax_iterations = 20000\n"),
    );
    let o = alea()
        .args(["run", p.to_str().unwrap(), "--quiet", "--dir"])
        .arg(dir.join("study-small"))
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("beyond small sliding"), "{t}");
    // Large sliding in a study that estimates its error (which needs one interface layout for
    // every run): refused at the interface's line.
    let (p, s) = case(&dir, "study", &[], &format!("{study_tail}\n[error]\n"));
    let o = alea()
        .args(["run", p.to_str().unwrap(), "--quiet", "--dir"])
        .arg(dir.join("study"))
        .output()
        .unwrap();
    expect_input_error(&o, &p, line_of(&s, "sliding ="), "interface[0].sliding");
    assert!(text(&o).contains("error estimate"), "{}", text(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 42: the small-sliding warning of a study is kept with its runs, not only printed by
/// the invocation that computed them: after the run, after a resumption that computes nothing
/// and after `alea report DIR`, `summary.json`'s notes count the runs beyond small sliding and
/// name the worst one's interface by its name and substructures (not by an index), and every
/// invocation prints it.
#[test]
fn a_study_beyond_small_sliding_keeps_its_warning_in_every_output() {
    let dir = tmp("notes");
    let (p, _) = case(
        &dir,
        "study-small",
        &[("sliding = \"large\"", "")],
        "\n[study]\ntitle = \"slide\"\n\n[[quantity]]\nname = \"fy\"\nkind = \"interface_force\"\ninterface = \"contact\"\ncomponent = 1\n\n[solver]\nmax_iterations = 20000\n",
    );
    let out = dir.join("study-small");
    let summary = out.join("summary.json");
    let check = |o: &Output, what: &str| {
        let t = text(o);
        assert_eq!(o.status.code(), Some(0), "{what}: {t}");
        assert!(
            t.contains("1 of 1 converged runs slid beyond small sliding"),
            "{what}: {t}"
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
        let notes: Vec<&str> = json["notes"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|n| n.as_str())
            .filter(|n| n.contains("beyond small sliding"))
            .collect();
        assert_eq!(notes.len(), 1, "{what}: {json}");
        let n = notes[0];
        assert!(
            n.starts_with("1 of 1 converged runs slid beyond small sliding")
                && n.contains("1 on interface 'contact' (between 'base' and 'block')")
                && n.contains("slid by")
                && !n.contains("interface 0"),
            "{what}: {n}"
        );
        // The block slides by 0.8 mm over base cells of 0.1 mm.
        let ratio: f64 = n
            .rsplit(", ")
            .next()
            .and_then(|s| s.split(' ').next())
            .and_then(|s| s.parse().ok())
            .unwrap_or_else(|| panic!("{what}: {n}"));
        assert!(ratio > 2.0, "{what}: {n}");
        // No warning about runs of unknown slide: this run's is stored.
        assert!(!t.contains("is not known"), "{what}: {t}");
    };
    let run = || {
        alea()
            .args(["run", p.to_str().unwrap(), "--quiet", "--dir"])
            .arg(&out)
            .output()
            .unwrap()
    };
    check(&run(), "run");
    std::fs::remove_file(&summary).unwrap();
    let o = run();
    assert!(
        !text(&o).contains("warning: the run at"),
        "the resumption computed a run: {}",
        text(&o)
    );
    check(&o, "resume");
    std::fs::remove_file(&summary).unwrap();
    let o = alea().arg("report").arg(&out).output().unwrap();
    check(&o, "report");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `[solver] repair_tolerance` and `max_pairings` drive the re-pairing: with a tolerance of
/// 1e-5 of the mesh size the slide since the first pairing (5.8e-4 of it, measured) is too
/// large and the step re-pairs once (2 pairings, as `alea-latin/tests/large_sliding.rs`
/// measures), keeping the closed-form resultants; allowed a single pairing, the same step
/// cannot settle and is not converged (exit 4). Out-of-range values, and either key without a
/// large-sliding interface, are refused at their line (exit 2).
#[test]
fn re_pairing_settings_are_used_and_checked_at_load() {
    let dir = tmp("settings");
    let (p, _) = case(&dir, "tight", &[], "\n[solver]\nrepair_tolerance = 1e-5\n");
    let o = solve(&p, &dir.join("out-tight"));
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("large sliding: 2 pairing(s)"), "{t}");
    assert!(t.contains("(tolerance 1e-5)"), "{t}");
    let (fx, fy) = resultant(&t);
    assert!((fy - 10.0).abs() < 1e-3 && (fx + 2.0).abs() < 1e-3, "{t}");
    let (p, _) = case(
        &dir,
        "one",
        &[],
        "\n[solver]\nrepair_tolerance = 1e-5\nmax_pairings = 1\n",
    );
    let o = solve(&p, &dir.join("out-one"));
    let t = text(&o);
    assert_eq!(o.status.code(), Some(4), "{t}");
    assert!(
        t.contains("large sliding: 1 pairing(s)")
            && t.contains("did not settle within 1 pairing(s) ([solver] max_pairings)"),
        "{t}"
    );
    for (name, setting, field) in [
        ("zero", "repair_tolerance = 0.0", "solver.repair_tolerance"),
        ("half", "repair_tolerance = 0.6", "solver.repair_tolerance"),
        ("none", "max_pairings = 0", "solver.max_pairings"),
        ("many", "max_pairings = 101", "solver.max_pairings"),
    ] {
        let (p, s) = case(&dir, name, &[], &format!("\n[solver]\n{setting}\n"));
        expect_input_error(&solve(&p, &dir.join("o")), &p, line_of(&s, setting), field);
    }
    let (p, s) = case(
        &dir,
        "unused",
        &[("sliding = \"large\"", "")],
        "\n[solver]\nmax_pairings = 3\n",
    );
    let o = solve(&p, &dir.join("o"));
    expect_input_error(&o, &p, line_of(&s, "max_pairings"), "solver.max_pairings");
    assert!(text(&o).contains("no interface has sliding = \"large\""));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A study with large sliding: the 8-cell slide with a random friction coefficient
/// `mu ~ U(0.1, 0.3)`, each run re-paired in its deformed configuration. Closed form at every
/// run: `N = 10 N/mm`, friction `-mu N` on the block, and no slide beyond what its pairing
/// represents (no small-sliding warning). On the old code the study was refused at load.
#[test]
fn a_study_with_large_sliding_keeps_the_closed_form_at_every_run() {
    let dir = tmp("study-large");
    let tail = "\n[study]\ntitle = \"slide, random mu\"\nseed = 2\n\n\
                [[parameter]]\nname = \"mu\"\nlaw = \"uniform\"\nlo = 0.1\nhi = 0.3\n\n\
                [[quantity]]\nname = \"fx\"\nkind = \"interface_force\"\ninterface = \"contact\"\ncomponent = 0\n\n\
                [[quantity]]\nname = \"fy\"\nkind = \"interface_force\"\ninterface = \"contact\"\ncomponent = 1\n\n\
                [[method]]\ntype = \"monte_carlo\"\nruns = 4\n";
    let (p, _) = case(&dir, "study", &[("mu = 0.2", "mu = \"mu\"")], tail);
    let out = dir.join("run");
    let o = alea()
        .args(["run", p.to_str().unwrap(), "--quiet", "--dir"])
        .arg(&out)
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    assert!(!t.contains("beyond small sliding"), "{t}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let runs = summary["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 4);
    for r in runs {
        assert_eq!(r["status"], "converged", "{r}");
        let mu = r["params"][0].as_f64().unwrap();
        let (fx, fy) = (
            r["qois"][0].as_f64().unwrap(),
            r["qois"][1].as_f64().unwrap(),
        );
        assert!((fy - 10.0).abs() < 1e-3, "mu {mu}: N = {fy}");
        assert!(
            (fx + mu * 10.0).abs() < 1e-3,
            "mu {mu}: T = {fx} vs {}",
            -mu * 10.0
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A study whose runs are load histories with large sliding and imposed displacements per step:
/// press, then slide the block's top by 0.8 mm (8 base cells), random `mu ~ U(0.1, 0.3)`.
/// Closed forms at every run: friction `-mu N` on the block at the end of the slide
/// (`N = 10 N/mm`), and the slide step's own dissipation `mu N` times its slip, the imposed
/// 0.8 mm less the block's elastic shear (about 4e-5 mm): within [0.799, 0.8] mu N; its
/// interface work is minus that.
#[test]
fn a_study_of_press_then_slide_histories_with_large_sliding() {
    let dir = tmp("study-steps");
    let tail = "\n[study]\ntitle = \"press then slide, random mu\"\nseed = 4\n\n\
                [[parameter]]\nname = \"mu\"\nlaw = \"uniform\"\nlo = 0.1\nhi = 0.3\n\n\
                [[step]]\nname = \"press\"\n\n\
                [[step]]\nname = \"slide\"\n\
                constraint = [ { substructure = \"block\", group = \"block_top\", x = 0.8 } ]\n\n\
                [[quantity]]\nname = \"fx\"\nkind = \"interface_force\"\ninterface = \"contact\"\ncomponent = 0\n\n\
                [[quantity]]\nname = \"dissipated\"\nkind = \"friction_dissipation\"\ninterface = \"contact\"\n\n\
                [[quantity]]\nname = \"work\"\nkind = \"interface_work\"\ninterface = \"contact\"\n\n\
                [[method]]\ntype = \"monte_carlo\"\nruns = 3\n";
    let (p, _) = case(
        &dir,
        "study",
        &[
            ("mu = 0.2", "mu = \"mu\""),
            (
                "group = \"block_top\", x = 0.8",
                "group = \"block_top\", x = 0.0",
            ),
        ],
        tail,
    );
    let out = dir.join("run");
    let o = alea()
        .args(["run", p.to_str().unwrap(), "--quiet", "--dir"])
        .arg(&out)
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let runs = summary["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 3);
    for r in runs {
        assert_eq!(r["status"], "converged", "{r}");
        let mu = r["params"][0].as_f64().unwrap();
        let q: Vec<f64> = (0..3).map(|i| r["qois"][i].as_f64().unwrap()).collect();
        let mu_n = mu * 10.0;
        assert!(
            (q[0] + mu_n).abs() < 1e-3,
            "mu {mu}: T = {} vs {}",
            q[0],
            -mu_n
        );
        assert!(
            q[1] > 0.799 * mu_n && q[1] < 0.8 * mu_n * (1.0 + 1e-3),
            "mu {mu}: dissipation {} vs mu N x 0.8 = {}",
            q[1],
            0.8 * mu_n
        );
        assert!(
            (q[1] + q[2]).abs() < 1e-6 * q[1],
            "work {} vs {}",
            q[2],
            q[1]
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
