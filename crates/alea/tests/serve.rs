//! `alea serve` (issue 39): the study's model over the UM-Bridge protocol, checked over real
//! HTTP against `alea run` on the shipped simple blade root - evaluations from two client
//! threads equal the study's runs at the same points (to the solver's tolerance), bad requests
//! get errors naming their cause while the server goes on answering, and a server killed and
//! started again answers every finished point from its store, solving nothing.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use serde_json::{Value, json};

fn alea() -> Command {
    Command::new(env!("CARGO_BIN_EXE_alea"))
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("alea-serve-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn study() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/blade-root-simple.toml")
}

/// A running server: the child and the address it printed, with the runs its store held.
struct Server {
    child: Child,
    addr: String,
    stored_at_start: usize,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start(dir: &Path) -> Server {
    start_study(&study(), dir)
}

fn start_study(study: &Path, dir: &Path) -> Server {
    let mut child = alea()
        .args([
            "serve",
            study.to_str().unwrap(),
            "--port",
            "0",
            "--threads",
            "2",
        ])
        .arg("--dir")
        .arg(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    // "serving '...' (...) as UM-Bridge model 'forward' at http://127.0.0.1:PORT (N runs in DIR)"
    let addr = line
        .split("http://")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .unwrap_or_else(|| panic!("no address in {line:?}"))
        .to_string();
    let stored_at_start = line
        .split(" (")
        .last()
        .and_then(|s| s.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no run count in {line:?}"));
    Server {
        child,
        addr,
        stored_at_start,
    }
}

/// One HTTP/1.1 request: the status and the JSON body.
fn request(addr: &str, method: &str, path: &str, body: &str) -> (u16, Value) {
    let mut s = TcpStream::connect(addr).unwrap();
    write!(
        s,
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut text = String::new();
    s.read_to_string(&mut text).unwrap();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap();
    let json = text.split("\r\n\r\n").nth(1).unwrap_or("");
    (status, serde_json::from_str(json).unwrap_or(Value::Null))
}

fn evaluate(addr: &str, p: &[f64]) -> (u16, Value) {
    let body = json!({ "name": "forward", "input": [p], "config": {} }).to_string();
    request(addr, "POST", "/Evaluate", &body)
}

fn floats(blob: &[u8]) -> Vec<f64> {
    blob.chunks_exact(8)
        .map(|b| f64::from_le_bytes(b.try_into().unwrap()))
        .collect()
}

/// The converged runs of a study directory: (parameters, quantities).
fn runs(dir: &Path) -> Vec<(Vec<f64>, Vec<f64>)> {
    let db = rusqlite::Connection::open(dir.join("study.db")).unwrap();
    let mut stmt = db
        .prepare("SELECT params, qois FROM runs WHERE status = 'converged' ORDER BY rowid")
        .unwrap();
    stmt.query_map([], |r| {
        Ok((
            floats(&r.get::<_, Vec<u8>>(0)?),
            floats(&r.get::<_, Vec<u8>>(1)?),
        ))
    })
    .unwrap()
    .map(Result::unwrap)
    .collect()
}

#[test]
fn serves_the_study_model_over_um_bridge() {
    // The reference: the study's own runs.
    let reference_dir = tmp("reference");
    let o = alea()
        .args(["run", study().to_str().unwrap(), "-q", "--threads", "2"])
        .arg("--dir")
        .arg(&reference_dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let reference = runs(&reference_dir);
    assert!(reference.len() >= 12, "{} runs", reference.len());
    let points: Vec<Vec<f64>> = reference.iter().take(12).map(|r| r.0.clone()).collect();
    // The scale of each quantity over the study, for the solver's tolerance.
    let scale: Vec<f64> = (0..reference[0].1.len())
        .map(|q| reference.iter().fold(0.0_f64, |m, r| m.max(r.1[q].abs())))
        .collect();

    let dir = tmp("served");
    let server = start(&dir);
    let addr = server.addr.clone();
    assert_eq!(server.stored_at_start, 0);
    assert_eq!(
        request(&addr, "GET", "/Info", "").1,
        json!({ "protocolVersion": 1.0, "models": ["forward"] })
    );
    assert_eq!(
        request(&addr, "POST", "/InputSizes", r#"{"name": "forward"}"#).1,
        json!({ "inputSizes": [2] })
    );
    assert_eq!(
        request(
            &addr,
            "POST",
            "/OutputSizes",
            r#"{"name": "forward", "config": {}}"#
        )
        .1,
        json!({ "outputSizes": [3] })
    );
    // Two client threads, six points each, concurrently.
    let answers: Vec<(usize, Vec<f64>)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..2)
            .map(|t| {
                let (addr, points) = (&addr, &points);
                s.spawn(move || {
                    (0..points.len())
                        .filter(|k| k % 2 == t)
                        .map(|k| {
                            let (status, v) = evaluate(addr, &points[k]);
                            assert_eq!(status, 200, "{v}");
                            let out: Vec<f64> = v["output"][0]
                                .as_array()
                                .unwrap()
                                .iter()
                                .map(|x| x.as_f64().unwrap())
                                .collect();
                            (k, out)
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    assert_eq!(answers.len(), points.len());
    let worst = answers
        .iter()
        .flat_map(|(k, out)| {
            out.iter()
                .zip(&reference[*k].1)
                .zip(&scale)
                .map(|((a, b), s)| (a - b).abs() / s)
        })
        .fold(0.0_f64, f64::max);
    println!("largest difference with alea run, relative to the quantity's scale: {worst:.2e}");
    for (k, out) in &answers {
        for (q, (a, b)) in out.iter().zip(&reference[*k].1).enumerate() {
            assert!(
                (a - b).abs() <= 1e-4 * scale[q],
                "point {:?} quantity {q}: served {a}, alea run {b}",
                points[*k]
            );
        }
    }

    // Bad requests: an error naming the cause, and the server goes on.
    let bad = [
        (
            "/Evaluate",
            r#"{"name": "forward", "input": [[1.0]]}"#,
            "InvalidInput",
            "has 1 values",
        ),
        (
            "/Evaluate",
            r#"{"name": "forward", "input": [[-1.0, 0.5]]}"#,
            "InvalidInput",
            "must be > 0",
        ),
        (
            "/Evaluate",
            r#"{"name": "forward", "input": [[2.4e5, 0.5]], "config": {"tol": 1}}"#,
            "InvalidInput",
            "unknown config key 'tol'",
        ),
        (
            "/Evaluate",
            r#"{"name": "other", "input": [[2.4e5, 0.5]]}"#,
            "ModelNotFound",
            "'other'",
        ),
        ("/Evaluate", "{not json", "InvalidInput", "not JSON"),
        (
            "/Gradient",
            r#"{"name": "forward"}"#,
            "UnsupportedFeature",
            "Gradient",
        ),
    ];
    for (path, body, kind, phrase) in bad {
        let (status, v) = request(&addr, "POST", path, body);
        assert!(status >= 400, "{path} {body}: {status}");
        assert_eq!(v["error"]["type"], kind, "{path} {body}: {v}");
        let message = v["error"]["message"].as_str().unwrap();
        assert!(message.contains(phrase), "{path} {body}: {message}");
    }
    // A client that connects and drops the connection mid-request.
    drop(TcpStream::connect(&addr).unwrap());
    let (status, _) = evaluate(&addr, &points[0]);
    assert_eq!(status, 200);

    // Killed (no clean stop) and started again: every finished point from the store.
    drop(server);
    let stored = runs(&dir).len();
    assert_eq!(stored, points.len());
    let again = start(&dir);
    assert_eq!(again.stored_at_start, stored);
    for (k, out) in &answers {
        let (status, v) = evaluate(&again.addr, &points[*k]);
        assert_eq!(status, 200);
        assert_eq!(v["output"][0], json!(out), "point {:?}", points[*k]);
    }
    drop(again);
    assert_eq!(runs(&dir).len(), stored, "a stored point was solved again");
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&reference_dir);
}

/// The root pulled out of its slot (the pressure on its lower face reversed, as in
/// alea-study's `no_equilibrium.rs`): no equilibrium exists at low friction, and the answer is
/// an error naming the run's status, its certificate and its last residual - the same when
/// asked again (the failed run is stored) - while the server goes on answering.
#[test]
fn a_run_without_equilibrium_is_an_error_naming_its_cause() {
    let work = tmp("pulled");
    std::fs::create_dir_all(&work).unwrap();
    let text = std::fs::read_to_string(study()).unwrap();
    let pulled = text.replace(
        r#"{ name = "p", group = "S2_bottom", pressure = 1000.0 }"#,
        r#"{ name = "p", group = "S2_bottom", pressure = -1000.0 }"#,
    );
    assert_ne!(pulled, text, "the example's load changed");
    let file = work.join("pulled.toml");
    std::fs::write(&file, pulled).unwrap();
    let server = start_study(&file, &work.join("served"));
    let mut messages = Vec::new();
    for _ in 0..2 {
        let (status, v) = evaluate(&server.addr, &[2.4e5, 0.3]);
        assert_eq!(status, 500, "{v}");
        assert_eq!(v["error"]["type"], "ModelFailed", "{v}");
        let m = v["error"]["message"].as_str().unwrap().to_string();
        assert!(
            m.contains("no equilibrium")
                && m.contains("substructure 'S2'")
                && m.contains("residual"),
            "{m}"
        );
        messages.push(m);
    }
    assert_eq!(messages[0], messages[1]);
    assert_eq!(
        request(
            &server.addr,
            "POST",
            "/InputSizes",
            r#"{"name": "forward"}"#
        )
        .0,
        200
    );
    drop(server);
    let _ = std::fs::remove_dir_all(&work);
}

/// SIGTERM (what a batch system sends) ends the server cleanly: exit status 0 (its first line
/// read, its stdout closed: the account it prints on stopping is no error either) and the run
/// it finished in the store.
#[test]
fn sigterm_stops_the_server_cleanly() {
    let dir = tmp("sigterm");
    let mut server = start(&dir);
    let (status, _) = evaluate(&server.addr, &[2.4e5, 0.5]);
    assert_eq!(status, 200);
    let pid = server.child.id().to_string();
    assert!(
        Command::new("kill")
            .args(["-TERM", &pid])
            .status()
            .unwrap()
            .success()
    );
    let exit = server.child.wait().unwrap();
    assert!(exit.success(), "{exit:?}");
    assert_eq!(runs(&dir).len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}
