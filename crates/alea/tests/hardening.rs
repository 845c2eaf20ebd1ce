//! The command line under misuse, round two (issue 23): bounded inputs, temporary files,
//! damaged stored files, messages and exit codes, `summary.json` of `alea report`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::text;

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn tmp(name: &str) -> PathBuf {
    common::fresh_dir("alea-hard", name)
}

/// The shipped plate study, smaller (a few tenths of a second).
fn small_study(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(root().join("examples/plate-random-E.toml"))
        .unwrap()
        .replace("runs = 400", "runs = 30")
        + "\n[statistics]\nsamples = 4000\n";
    let path = dir.join("plate.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn run_in(cwd: &Path, study: &str, dir: &str) -> Output {
    alea()
        .current_dir(cwd)
        .args(["run", study, "--dir", dir, "-q"])
        .output()
        .unwrap()
}

/// Every file under `dir` whose name holds `.tmp-`.
fn temporaries(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            if e.file_type().unwrap().is_dir() {
                stack.push(e.path());
            } else if e.file_name().to_string_lossy().contains(".tmp-") {
                out.push(e.path());
            }
        }
    }
    out
}

#[test]
fn devices_and_non_text_study_files_fail_fast_as_input_errors() {
    let base = tmp("inputs");
    let t = std::time::Instant::now();
    let o = alea()
        .args(["run", "/dev/zero", "--dir"])
        .arg(base.join("o"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("/dev/zero:0: (file): not a regular file (a device"),
        "{}",
        text(&o)
    );
    assert!(t.elapsed().as_secs_f64() < 5.0);
    let o = alea()
        .args(["solve", "/dev/urandom", "--out"])
        .arg(base.join("s"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    // A mesh file that is a device (in a case file: the same loader as a study's).
    let study = std::fs::read_to_string(root().join("examples/block-on-plane-3d.toml"))
        .unwrap()
        .replace("block-on-plane-3d.msh", "/dev/zero");
    assert!(study.contains("/dev/zero"));
    std::fs::write(base.join("dev.toml"), study).unwrap();
    let t = std::time::Instant::now();
    let o = alea()
        .current_dir(&base)
        .args(["solve", "dev.toml", "--out", "out"])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("mesh.file") && text(&o).contains("a device"),
        "{}",
        text(&o)
    );
    assert!(t.elapsed().as_secs_f64() < 5.0);
    // Invalid UTF-8: exit 2 at its line.
    std::fs::write(base.join("bad.toml"), b"[study]\n\xff\n").unwrap();
    let o = run_in(&base, "bad.toml", "out");
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("bad.toml:2: (text)"), "{}", text(&o));
    // A missing study file: the OS cause once, exit 3.
    let o = run_in(&base, "missing.toml", "out");
    assert_eq!(o.status.code(), Some(3), "{}", text(&o));
    assert_eq!(
        text(&o).matches("No such file or directory").count(),
        1,
        "{}",
        text(&o)
    );
    // --dir naming a file.
    let study = small_study(&base);
    std::fs::write(base.join("afile"), "x").unwrap();
    let o = alea()
        .arg("run")
        .arg(&study)
        .arg("--dir")
        .arg(base.join("afile"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("is a file, not a study directory"),
        "{}",
        text(&o)
    );
    assert!(!text(&o).contains("File exists"), "{}", text(&o));
}

#[test]
fn a_corrupt_store_is_a_store_error() {
    let base = tmp("corrupt");
    let study = small_study(&base);
    let dir = base.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("study.db"), vec![0x5a; 8192]).unwrap();
    for o in [
        alea()
            .arg("run")
            .arg(&study)
            .arg("--dir")
            .arg(&dir)
            .arg("-q")
            .output()
            .unwrap(),
        alea().arg("report").arg(&dir).output().unwrap(),
    ] {
        assert_eq!(o.status.code(), Some(3), "{}", text(&o));
        assert!(
            text(&o).contains("study.db") || text(&o).contains("database"),
            "{}",
            text(&o)
        );
    }
}

#[test]
fn help_prints_the_exit_code_table() {
    let o = alea().arg("--help").output().unwrap();
    let t = text(&o);
    assert!(
        t.contains("Exit codes:\n  0  success, also when stdout closes")
            && t.contains("complete\n  1  internal error"),
        "{t}"
    );
    assert!(
        t.contains("  3  file-system or store error")
            && t.contains("  5  the study directory is in use"),
        "{t}"
    );
}

#[test]
fn temporaries_go_damaged_runs_are_recomputed_and_report_matches_run() {
    let base = tmp("resume");
    small_study(&base);
    // A relative study path, as a user types it.
    let o = run_in(&base, "plate.toml", "out");
    assert!(o.status.success(), "{}", text(&o));
    let dir = base.join("out");
    let summary = std::fs::read(dir.join("summary.json")).unwrap();
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    // `alea report` rebuilds summary.json byte for byte (no absolute study path in it).
    let o = alea().arg("report").arg(&dir).output().unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
    // What kills leave: temporaries of a dead process (pid above Linux's pid_max), also in
    // `fields/`, where a directory written when the runs' data were files had them.
    std::fs::create_dir_all(dir.join("fields")).unwrap();
    let stale = [
        dir.join(".samples.csv.tmp-4000000"),
        dir.join("report/.report-input.json.tmp-4000000"),
        dir.join("fields/.run_0000000000000000.bin.tmp-4000000"),
    ];
    for s in &stale {
        std::fs::write(s, vec![0u8; 4096]).unwrap();
    }
    // One run's field data lost, one's truncated (in the database, which the runs' data are in).
    let stored = |dir: &Path| -> Vec<(String, Vec<u8>)> {
        let db = rusqlite::Connection::open(dir.join("study.db")).unwrap();
        let mut st = db
            .prepare("SELECT key, fields FROM run_data ORDER BY key LIMIT 2")
            .unwrap();
        st.query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    };
    let before = stored(&dir);
    assert_eq!(before.len(), 2);
    {
        let db = rusqlite::Connection::open(dir.join("study.db")).unwrap();
        db.execute("DELETE FROM run_data WHERE key = ?1", [&before[0].0])
            .unwrap();
        db.execute(
            "UPDATE run_data SET fields = substr(fields, 1, ?2) WHERE key = ?1",
            rusqlite::params![before[1].0, before[1].1.len() as i64 / 2],
        )
        .unwrap();
    }
    // `alea report`: the two runs named and counted missing, not "did not converge".
    let o = alea().arg("report").arg(&dir).output().unwrap();
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("78 of 80 runs finished"), "{t}");
    assert_eq!(t.matches("cannot be used").count(), 2, "{t}");
    assert!(t.contains("is missing") && t.contains("truncated"), "{t}");
    assert!(t.contains("2 of 80 runs are missing"), "{t}");
    assert!(!t.contains("did not converge"), "{t}");
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    for s in &stale {
        std::fs::write(s, vec![0u8; 4096]).unwrap();
    }
    // `alea run` (resume): the two runs computed again, everything as before.
    let o = run_in(&base, "plate.toml", "out");
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("runs: 2 computed, 78 resumed"), "{t}");
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    // Both stored again, as they were.
    assert_eq!(stored(&dir), before);
}

/// FNV-1a of `text` as 16 hex digits: the stem of a run's file (`alea_study::store::run_file_stem`
/// of its point, whose key is what `run_data.key` holds).
fn fnv_stem(text: &str) -> String {
    let mut h: u64 = 0xcbf29ce484222325;
    for b in text.bytes() {
        h = (h ^ b as u64).wrapping_mul(0x100000001b3);
    }
    format!("run_{h:016x}")
}

/// A study directory written when each run's displacements were a file of its own
/// (`fields/run_<h>.bin`: `ALEAFLD1`, the study hash, the values; no `run_data` table) is
/// still read - `alea report` rebuilds the same outputs from it - and resumed: nothing is
/// computed again, a damaged file's run is, and it then goes into the database.
#[test]
fn a_directory_with_one_field_file_per_run_is_read_and_resumed() {
    let base = tmp("legacy");
    small_study(&base);
    let o = run_in(&base, "plate.toml", "out");
    assert!(o.status.success(), "{}", text(&o));
    let dir = base.join("out");
    let summary = std::fs::read(dir.join("summary.json")).unwrap();
    // The mean / std fields (read from every run's fields): every file under `paraview/`.
    let mut mean_fields: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut stack = vec![dir.join("paraview")];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            if e.file_type().unwrap().is_dir() {
                stack.push(e.path());
            } else {
                mean_fields.push((e.path(), std::fs::read(e.path()).unwrap()));
            }
        }
    }
    assert!(
        !mean_fields.is_empty(),
        "the study writes mean / std fields"
    );
    // The directory as the store wrote it before the data moved into the database.
    let files = {
        let db = rusqlite::Connection::open(dir.join("study.db")).unwrap();
        let hash: String = db
            .query_row("SELECT value FROM meta WHERE key = 'study_hash'", [], |r| {
                r.get(0)
            })
            .unwrap();
        let rows: Vec<(String, Vec<u8>)> = db
            .prepare("SELECT key, fields FROM run_data")
            .unwrap()
            .query_map([], |r| Ok((r.get(0)?, r.get(1)?)))
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap();
        std::fs::create_dir_all(dir.join("fields")).unwrap();
        let mut files = Vec::new();
        for (key, values) in &rows {
            let mut bytes = b"ALEAFLD1".to_vec();
            bytes.extend_from_slice(hash.as_bytes());
            bytes.extend_from_slice(values);
            let path = dir.join("fields").join(format!("{}.bin", fnv_stem(key)));
            std::fs::write(&path, bytes).unwrap();
            files.push(path);
        }
        db.execute_batch("DROP TABLE run_data").unwrap();
        files
    };
    assert!(files.len() >= 30, "{}", files.len());
    std::fs::remove_file(dir.join("summary.json")).unwrap();
    let _ = std::fs::remove_dir_all(dir.join("paraview"));
    // Read: the same outputs, no run left out.
    let o = alea().arg("report").arg(&dir).output().unwrap();
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(!t.contains("cannot be used"), "{t}");
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
    for (path, bytes) in &mean_fields {
        assert_eq!(&std::fs::read(path).unwrap(), bytes, "{}", path.display());
    }
    // Resumed: nothing computed again.
    let o = run_in(&base, "plate.toml", "out");
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(t.contains("runs: 0 computed"), "{t}");
    // A truncated file: its run computed again, into the database; the outputs as before.
    let bytes = std::fs::read(&files[0]).unwrap();
    std::fs::write(&files[0], &bytes[..bytes.len() / 2]).unwrap();
    let o = run_in(&base, "plate.toml", "out");
    let t = text(&o);
    assert!(o.status.success(), "{t}");
    assert!(
        t.contains("cannot be used") && t.contains("truncated"),
        "{t}"
    );
    assert!(t.contains("runs: 1 computed"), "{t}");
    assert_eq!(common::stored_runs(&dir, "fields"), 1);
    assert_eq!(std::fs::read(dir.join("summary.json")).unwrap(), summary);
}

/// `alea` with stdout a pipe whose reader has already gone (every write fails with EPIPE).
fn with_closed_stdout(args: &[&std::ffi::OsStr]) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    alea()
        .args(args)
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .unwrap()
}

/// A command whose stdout closed ended quietly: exit code 0 (docs/study-file.md, "Exit
/// codes"), no panic, no error.
fn ended_quietly(o: &Output, what: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    assert!(!err.contains("error: "), "{what}: {err}");
}

/// Issue 42, item 1: `alea run study.toml | head -1` used to panic ("failed printing to stdout:
/// Broken pipe", exit 101) and leave only `study.db`, the outputs being written after the
/// tables were printed. Now the outputs are written first and a closed stdout ends the command
/// quietly (exit 0) with every output complete: `alea report` rebuilds the same
/// `summary.json`. `alea report` and `alea solve` also end quietly with their files written;
/// a stdout that fails otherwise (a full disk) is a file-system error (3), files written.
#[test]
fn a_closed_stdout_ends_quietly_with_the_outputs_complete() {
    use std::io::BufRead;
    let base = tmp("epipe");
    let study = small_study(&base);
    let dir = base.join("study");
    let mut child = alea()
        .arg("run")
        .arg(&study)
        .arg("--dir")
        .arg(&dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    std::io::BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    // The reader is dropped: the pipe is closed while the study runs.
    assert!(
        first.starts_with("study 'plate with random E and load'"),
        "{first}"
    );
    let o = child.wait_with_output().unwrap();
    ended_quietly(&o, "alea run | head -1");
    let summary = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&summary).unwrap();
    assert!(json.is_object(), "{summary}");
    let samples = std::fs::read_to_string(dir.join("samples.csv")).unwrap();
    assert!(
        samples.lines().count() > 1000,
        "{} lines",
        samples.lines().count()
    );
    let html = std::fs::read_to_string(dir.join("report/report.html")).unwrap();
    assert!(
        html.trim_end().ends_with("</html>"),
        "{}",
        &html[html.len() - 100..]
    );
    // The report's input is not an output (issue 42: 21 MB for a 50-run study).
    assert!(!dir.join("report/report-input.json").exists());
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
    // `alea report` into a closed stdout: quiet, and the same summary.json, byte for byte.
    let o = with_closed_stdout(&["report".as_ref(), dir.as_os_str()]);
    ended_quietly(&o, "alea report | (closed)");
    assert_eq!(
        std::fs::read_to_string(dir.join("summary.json")).unwrap(),
        summary
    );
    // `alea solve`, a direct solve and a LATIN solve: quiet, their files written.
    for (case, file) in [
        ("examples/kirsch.toml", "kirsch.vtu"),
        ("examples/full-slip.toml", "full-slip.vtm"),
    ] {
        let out = base.join("solve");
        let o = with_closed_stdout(&[
            "solve".as_ref(),
            root().join(case).as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        ended_quietly(&o, case);
        assert!(out.join(file).exists(), "{case}: no {file}");
    }
    // A stdout that cannot be written (a full disk): exit 3 with the reason, files written.
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let out = base.join("full");
        let o = alea()
            .args([
                "solve",
                root().join("examples/kirsch.toml").to_str().unwrap(),
                "--out",
            ])
            .arg(&out)
            .stdout(full)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(3), "{err}");
        assert!(err.contains("error: writing to stdout: "), "{err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(out.join("kirsch.vtu").exists());
    }
}
