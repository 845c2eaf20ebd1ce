//! `alea solve` of a `[[step]]` load history (examples/press-then-slide.toml): the friction
//! resultant of every step against Coulomb's law on the resultants, the output files of every
//! step, and every bad `[[step]]` entry refused at load (exit 2) at its file, line and field.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("alea-steps-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn text(o: &Output) -> String {
    format!(
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn solve(case: &Path, out: &Path) -> Output {
    alea()
        .args([
            "solve",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap()
}

/// The `Fx` and `Fy` of every "resultant on side 2" line, in order.
fn resultants(t: &str) -> Vec<(f64, f64)> {
    t.lines()
        .filter_map(|l| l.split("resultant on side 2 (").nth(1))
        .map(|r| {
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
        })
        .collect()
}

#[test]
fn press_nudge_slide_and_back_follow_coulomb_on_the_resultants() {
    let dir = tmp("example");
    let case = root().join("examples/press-then-slide.toml");
    let o = solve(&case, &dir);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(0), "{t}");
    let r = resultants(&t);
    assert_eq!(r.len(), 4, "{t}");
    // The interface force on the block (side 2) opposes its motion: Fx = -Q.
    let (mu, n) = (0.3, 400.0);
    for (k, (fx, fy)) in r.iter().enumerate() {
        assert!((fy - n).abs() < 1e-6 * n, "step {}: N = {fy}", k + 1);
        let q = -fx;
        match k {
            0 => assert!(q.abs() < 1e-9 * n, "press: Q = {q}"),
            1 => assert!(q > 0.0 && q < 0.05 * mu * n, "nudge: Q = {q}"),
            2 => assert!((q - mu * n).abs() < 1e-6 * mu * n, "slide: Q = {q}"),
            _ => assert!((q + mu * n).abs() < 1e-6 * mu * n, "back: Q = {q}"),
        }
    }
    for (k, name) in ["press", "nudge", "slide", "back"].iter().enumerate() {
        let stem = format!("press-then-slide-{}-{name}", k + 1);
        assert!(dir.join(format!("{stem}.vtm")).is_file(), "{stem}.vtm");
        for f in ["base.vtu", "block.vtu", "interface_contact.csv"] {
            assert!(dir.join(&stem).join(f).is_file(), "{stem}/{f}");
        }
    }
    // The back step's interface CSV: every closed point slips.
    let csv =
        std::fs::read_to_string(dir.join("press-then-slide-4-back/interface_contact.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "status")
        .expect("status column");
    let codes: Vec<String> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(col).unwrap().trim().to_string())
        .collect();
    assert!(!codes.is_empty());
    assert!(
        codes.iter().all(|c| c != "stick" && c != "2"),
        "no stick point when sliding back: {codes:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Writes the example with `edit` applied (`from` replaced by `to`) and `tail` appended.
fn variant(dir: &Path, name: &str, edits: &[(&str, &str)], tail: &str) -> (PathBuf, String) {
    let mut s = std::fs::read_to_string(root().join("examples/press-then-slide.toml")).unwrap();
    for (from, to) in edits {
        assert!(s.contains(from), "{from}");
        s = s.replacen(from, to, 1);
    }
    s.push_str(tail);
    let p = dir.join(format!("{name}.toml"));
    std::fs::write(&p, &s).unwrap();
    (p, s)
}

fn line_of(text: &str, needle: &str) -> usize {
    text.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("'{needle}' not in the file"))
        + 1
}

fn expect_input_error(o: &Output, file: &Path, line: usize, field: &str, what: &str) {
    let t = text(o);
    assert_eq!(o.status.code(), Some(2), "{what}: {t}");
    assert!(!t.contains("panicked"), "{what}: {t}");
    let name = file.file_name().unwrap().to_string_lossy();
    assert!(
        t.contains(&format!("{name}:{line}: {field}")),
        "{what}: '{name}:{line}: {field}' expected in: {t}"
    );
    assert!(
        !t.contains("step 1 '"),
        "{what}: refused before any step ran: {t}"
    );
}

#[test]
fn bad_steps_are_refused_at_their_field() {
    let dir = tmp("bad");
    let cases: [(&str, &str, &str, &str); 7] = [
        (
            "unknown_load",
            "\n[[step]]\nname = \"more\"\nload = { pres = 2.0 }\n",
            "pres = 2.0",
            "step[4].load.pres",
        ),
        (
            "unknown_sub",
            "\n[[step]]\nname = \"more\"\nconstraint = [ { substructure = \"blok\", group = \"upper_top\", x = 1e-3 } ]\n",
            "blok",
            "step[4].constraint[0].substructure",
        ),
        (
            "no_constraint_on_group",
            "\n[[step]]\nname = \"more\"\nconstraint = [ { substructure = \"block\", group = \"upper_bottom\", x = 1e-3 } ]\n",
            "upper_bottom\", x = 1e-3",
            "step[4].constraint[0].group",
        ),
        (
            "component_not_imposed",
            "\n[[step]]\nname = \"more\"\nconstraint = [ { substructure = \"block\", group = \"upper_top\", y = -1e-3 } ]\n",
            "y = -1e-3",
            "step[4].constraint[0].y",
        ),
        (
            "nothing_changed",
            "\n[[step]]\nname = \"more\"\nconstraint = [ { substructure = \"block\", group = \"upper_top\" } ]\n",
            "group = \"upper_top\" }",
            "step[4].constraint[0].group",
        ),
        (
            "not_finite",
            "\n[[step]]\nname = \"more\"\nload = { press = inf }\n",
            "press = inf",
            "step[4].load.press",
        ),
        (
            "duplicate_name",
            "\n[[step]]\nname = \"slide\"\n",
            "ERROR_AT_LAST",
            "step[4].name",
        ),
    ];
    for (name, tail, needle, field) in cases {
        let (p, s) = variant(&dir, name, &[], tail);
        let line = if needle == "ERROR_AT_LAST" {
            s.lines().count()
        } else {
            line_of(&s, needle)
        };
        let o = solve(&p, &dir.join("out"));
        expect_input_error(&o, &p, line, field, name);
    }
    // An unknown key in a step.
    let (p, s) = variant(
        &dir,
        "unknown_key",
        &[],
        "\n[[step]]\nname = \"more\"\nloads = { press = 2.0 }\n",
    );
    let o = solve(&p, &dir.join("out"));
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains(&format!("unknown_key.toml:{}:", line_of(&s, "loads ="))),
        "{t}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
