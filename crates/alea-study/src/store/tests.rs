//! Tests of the store: which study a row or a run's data belongs to, damaged data, groups
//! committed all or none, migrations and directories with field files.

use super::*;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("alea-store-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn record(p: f64) -> RunRecord {
    RunRecord {
        params: vec![p, 2.0 * p],
        status: "converged".into(),
        iterations: 7,
        residual: 1e-7,
        seconds: 0.1,
        qois: vec![p * p],
        history: vec![1.0, 0.1],
        state: vec![0.5; 4],
        slide: None,
    }
}

#[test]
fn rows_and_field_data_of_another_study_are_never_used() {
    let d = dir("hash");
    let (a, b) = (study_hash("study A", &[]), study_hash("study B", &[]));
    let store = Store::open(&d, &a, false).unwrap();
    store
        .commit(&record(1.0), &[1.0, 2.0, 3.0], Some(&[4.0]))
        .unwrap();
    assert_eq!(store.fields(&[1.0, 2.0]).unwrap(), vec![1.0, 2.0, 3.0]);
    assert_eq!(store.cre(&[1.0, 2.0]).unwrap(), Some(vec![4.0]));
    assert!(
        !d.join("fields").exists() && !d.join("cre").exists(),
        "no file"
    );
    // A row of study B in the same table (what a second writer could leave).
    store
        .conn
        .execute(
            "INSERT INTO runs (key, params, status, iterations, residual, seconds, qois, history, state, study_hash)
             SELECT 'other', params, status, iterations, residual, seconds, qois, history, state, ?1 FROM runs",
            params![b],
        )
        .unwrap();
    let runs = store.runs().unwrap();
    assert_eq!(runs, vec![record(1.0)]);
    // Field data written by study B at the same point (what a second writer could leave).
    store
        .conn
        .execute("UPDATE run_data SET study_hash = ?1", params![b])
        .unwrap();
    for err in [
        store.fields(&[1.0, 2.0]).unwrap_err(),
        store.cre(&[1.0, 2.0]).unwrap_err(),
    ] {
        assert_eq!(err.exit_code(), 3, "{err}");
        assert!(
            err.to_string().contains("belongs to another study"),
            "{err}"
        );
    }
    let why = store.damaged_files(&[1.0, 2.0], 3, true).unwrap();
    assert!(why.contains("belongs to another study"), "{why}");
    // Truncated data: refused, not misread.
    store
        .conn
        .execute(
            "UPDATE run_data SET study_hash = ?1, fields = X'0102', cre = X'01'",
            params![a],
        )
        .unwrap();
    let err = store.fields(&[1.0, 2.0]).unwrap_err().to_string();
    assert!(
        err.contains("field data") && err.contains("damaged"),
        "{err}"
    );
    assert!(store.cre(&[1.0, 2.0]).is_err());
    drop(store);
    // The study file changed: refused without --restart, emptied with it.
    let e = Store::open(&d, &b, false).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    let s = Store::open(&d, &b, true).unwrap();
    assert!(s.runs().unwrap().is_empty());
    let rows: i64 = s
        .conn
        .query_row("SELECT COUNT(*) FROM run_data", [], |r| r.get(0))
        .unwrap();
    assert_eq!(rows, 0, "the data of the old study is gone with its rows");
}

/// `damaged_files` names what is wrong with a run's stored data: nothing when it is whole,
/// a missing, truncated or wrong-sized field datum, a missing or truncated error estimate.
#[test]
fn damaged_run_data_is_named() {
    let d = dir("damaged");
    let h = study_hash("study", &[]);
    let s = Store::open(&d, &h, false).unwrap();
    let (p, q) = (record(1.0), record(2.0));
    s.commit_group(&[
        (&p, &[1.0, 2.0, 3.0][..], Some(&[5.0][..])),
        (&q, &[1.0, 2.0, 3.0][..], None),
    ])
    .unwrap();
    assert_eq!(s.damaged_files(&p.params, 3, true), None);
    assert_eq!(s.damaged_files(&q.params, 3, false), None);
    let why = |params: &[f64], n, estimate| s.damaged_files(params, n, estimate).unwrap();
    assert_eq!(
        why(&p.params, 4, false),
        "its field data has 3 values, expected 4 (truncated or damaged)"
    );
    assert_eq!(
        why(&q.params, 3, true),
        "its error-estimate data is missing"
    );
    assert_eq!(s.cre(&q.params).unwrap(), None);
    let key = point_key(&p.params);
    let set = |sql: &str| s.conn.execute(sql, params![key]).unwrap();
    set("UPDATE run_data SET cre = X'0102' WHERE key = ?1");
    assert!(why(&p.params, 3, true).contains("error-estimate data has 2 bytes"));
    set("UPDATE run_data SET fields = substr(fields, 1, 12) WHERE key = ?1");
    assert_eq!(
        why(&p.params, 3, false),
        "its field data has 12 bytes, expected 24 (truncated or damaged)"
    );
    // Its data row lost: no legacy file either.
    set("DELETE FROM run_data WHERE key = ?1");
    let w = why(&p.params, 3, false);
    assert!(w.starts_with("its field data is missing"), "{w}");
    let err = s.fields(&p.params).unwrap_err().to_string();
    assert!(
        err.contains("field data") && err.contains("is missing"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_run_of_a_study_replaced_in_the_store_is_refused() {
    let d = dir("replaced");
    let (a, b) = (study_hash("study A", &[]), study_hash("study B", &[]));
    let first = Store::open(&d, &a, false).unwrap();
    first.commit(&record(1.0), &[1.0], None).unwrap();
    // A second process (its lock defeated) restarts the directory with study B.
    let second = Store::open(&d, &b, true).unwrap();
    second.commit(&record(2.0), &[2.0], None).unwrap();
    let err = first.commit(&record(3.0), &[3.0], None).unwrap_err();
    assert_eq!(err.exit_code(), 5, "{err}");
    assert!(err.to_string().contains("another study"), "{err}");
    assert_eq!(second.runs().unwrap(), vec![record(2.0)]);
    let rows: i64 = second
        .conn
        .query_row("SELECT COUNT(*) FROM runs", [], |r| r.get(0))
        .unwrap();
    assert_eq!(rows, 1, "no row of study A in study B's store");
}

/// A group of runs is committed together: every row with its files, and a group refused
/// (the directory now holds another study) stores none of its rows.
#[test]
fn a_group_of_runs_is_committed_all_or_none() {
    let d = dir("group");
    let (a, b) = (study_hash("study A", &[]), study_hash("study B", &[]));
    let first = Store::open(&d, &a, false).unwrap();
    let recs = [record(1.0), record(2.0), record(3.0)];
    let fields = [[1.0, 1.5], [2.0, 2.5], [3.0, 3.5]];
    let group: Vec<RunToCommit<'_>> = recs
        .iter()
        .zip(&fields)
        .map(|(r, f)| (r, &f[..], None))
        .collect();
    first.commit_group(&group).unwrap();
    assert_eq!(first.runs().unwrap().len(), 3);
    for (r, f) in recs.iter().zip(&fields) {
        assert_eq!(first.fields(&r.params).unwrap(), f.to_vec());
    }
    let second = Store::open(&d, &b, true).unwrap();
    let later = [record(4.0), record(5.0)];
    let group: Vec<RunToCommit<'_>> = later.iter().map(|r| (r, &fields[0][..], None)).collect();
    let err = first.commit_group(&group).unwrap_err();
    assert!(
        err.to_string().contains("these 2 runs are not stored"),
        "{err}"
    );
    assert!(second.runs().unwrap().is_empty());
    let data: i64 = second
        .conn
        .query_row("SELECT COUNT(*) FROM run_data", [], |r| r.get(0))
        .unwrap();
    assert_eq!(data, 0, "no field data of the refused group");
    assert!(!d.join("fields").exists(), "no file");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_directory_from_before_run_hashes_is_migrated() {
    let d = dir("legacy");
    std::fs::create_dir_all(d.join("fields")).unwrap();
    let h = study_hash("legacy", &[]);
    {
        let c = Connection::open(d.join("study.db")).unwrap();
        c.execute_batch(
            "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
             CREATE TABLE runs (key TEXT PRIMARY KEY, params BLOB NOT NULL, status TEXT NOT NULL,
               iterations INTEGER NOT NULL, residual REAL NOT NULL, seconds REAL NOT NULL,
               qois BLOB NOT NULL, history BLOB NOT NULL, state BLOB NOT NULL,
               finished_at TEXT NOT NULL DEFAULT CURRENT_TIMESTAMP);",
        )
        .unwrap();
        c.execute("INSERT INTO meta VALUES ('study_hash', ?1)", params![h])
            .unwrap();
        let r = record(3.0);
        c.execute(
            "INSERT INTO runs (key, params, status, iterations, residual, seconds, qois, history, state)
             VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
            params![point_key(&r.params), to_blob(&r.params), r.status, 7i64, r.residual,
                    r.seconds, to_blob(&r.qois), to_blob(&r.history), to_blob(&r.state)],
        )
        .unwrap();
    }
    let s = Store::open(&d, &h, false).unwrap();
    assert_eq!(s.runs().unwrap(), vec![record(3.0)]);
    // Legacy field file without a header.
    std::fs::write(s.field_path(&[3.0, 6.0]), to_blob(&[4.0, 5.0])).unwrap();
    assert_eq!(s.fields(&[3.0, 6.0]).unwrap(), vec![4.0, 5.0]);
    assert_eq!(s.damaged_files(&[3.0, 6.0], 2, false), None);
    let why = s.damaged_files(&[3.0, 6.0], 3, false).unwrap();
    assert!(
        why.contains("fields/run_") && why.contains("expected"),
        "{why}"
    );
    // The slide columns were added: the old run's slide is unknown (None above), a run
    // committed now keeps its own.
    let mut slid = record(4.0);
    slid.slide = Some(RunSlide {
        interface: "G2".into(),
        slip: 0.28,
        ratio: 0.72,
    });
    s.commit(&slid, &[1.0, 2.0], None).unwrap();
    assert_eq!(s.runs().unwrap(), vec![record(3.0), slid]);
}

fn identity(run_hash: &'static str, quantities: &[&str]) -> RunKeys<'static> {
    let quantities: Vec<String> = quantities.iter().map(|q| q.to_string()).collect();
    RunKeys {
        run_hash,
        quantities: Vec::leak(quantities),
    }
}

/// An edit that keeps what defines the runs (same run hash, another study hash) keeps the
/// runs and their data, their quantities put in the study's order; a run lacking a
/// quantity is left out (computed again); another run hash is refused.
#[test]
fn an_edit_that_keeps_the_runs_keeps_them() {
    let d = dir("edit");
    let (a, b, c) = (
        study_hash("A", &[]),
        study_hash("A # comment", &[]),
        study_hash("A, E doubled", &[]),
    );
    let mut r = record(1.0);
    r.qois = vec![10.0, 20.0];
    let s = Store::open_study(&d, &a, identity("runs1", &["q1", "q2"]), false).unwrap();
    s.commit(&r, &[1.0, 2.0], Some(&[3.0])).unwrap();
    drop(s);
    // Same runs, quantities reordered (and q1 renamed: same key).
    let s = Store::open_study(&d, &b, identity("runs1", &["q2", "q1"]), false).unwrap();
    let mut expected = r.clone();
    expected.qois = vec![20.0, 10.0];
    assert_eq!(s.runs().unwrap(), vec![expected]);
    assert_eq!(s.fields(&r.params).unwrap(), vec![1.0, 2.0]);
    assert_eq!(s.cre(&r.params).unwrap(), Some(vec![3.0]));
    assert_eq!(s.damaged_files(&r.params, 2, true), None);
    drop(s);
    // Study hash recorded: the store opened by hash alone (outputs) finds the runs.
    assert_eq!(Store::open(&d, &b, false).unwrap().runs().unwrap().len(), 1);
    // Another model: refused, with what a run is in the message.
    let e = Store::open_study(&d, &c, identity("runs2", &["q2", "q1"]), false).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{e}");
    assert!(
        e.to_string().contains("what defines its runs differs"),
        "{e}"
    );
    // A quantity added: the run lacks it and is left out, not mixed.
    let s = Store::open_study(&d, &a, identity("runs1", &["q1", "q2", "q3"]), false).unwrap();
    assert!(s.runs().unwrap().is_empty());
    // Computed again: it replaces the old row.
    let mut again = r.clone();
    again.qois = vec![10.0, 20.0, 30.0];
    s.commit(&again, &[1.0, 2.0], None).unwrap();
    assert_eq!(s.runs().unwrap(), vec![again]);
    let _ = std::fs::remove_dir_all(&d);
}

/// Rows written before runs carried a run hash: kept when the study hash is unchanged
/// (and given the run hash), refused when it changed, as before.
#[test]
fn rows_without_a_run_hash_need_the_same_study_hash() {
    let d = dir("no-run-hash");
    let (a, b) = (study_hash("A", &[]), study_hash("A # comment", &[]));
    let s = Store::open(&d, &a, false).unwrap();
    s.commit(&record(1.0), &[1.0], None).unwrap();
    drop(s);
    let e = Store::open_study(&d, &b, identity("runs1", &["q1"]), false).unwrap_err();
    assert!(
        e.to_string()
            .contains("written before study directories recorded"),
        "{e}"
    );
    let s = Store::open_study(&d, &a, identity("runs1", &["q1"]), false).unwrap();
    assert_eq!(s.runs().unwrap(), vec![record(1.0)]);
    drop(s);
    // Now tagged: a later edit keeps it.
    let s = Store::open_study(&d, &b, identity("runs1", &["q1"]), false).unwrap();
    assert_eq!(s.runs().unwrap(), vec![record(1.0)]);
    assert_eq!(s.fields(&[1.0, 2.0]).unwrap(), vec![1.0]);
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn quantities_are_remapped_by_key() {
    let w = |k: &[&str]| k.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    assert_eq!(
        remap_quantities(&[1.0, 2.0, 3.0], &["a", "b", "c"], &w(&["c", "a"])),
        Some(vec![3.0, 1.0])
    );
    assert_eq!(remap_quantities(&[1.0], &["a"], &w(&["a", "b"])), None);
    assert_eq!(remap_quantities(&[1.0, 2.0], &["a"], &w(&["a"])), None);
}

fn tagged(hash: &str, values: &[f64]) -> Vec<u8> {
    let mut bytes = FIELD_MAGIC.to_vec();
    bytes.extend_from_slice(hash.as_bytes());
    bytes.extend_from_slice(&to_blob(values));
    bytes
}

/// A directory written when each run's data was a file (`fields/`, `cre/`, with the study
/// hash header): its runs are read from their files and checked as before (another study's
/// file refused, a truncated one refused, a missing one named), it resumes, and the runs
/// committed after the resumption are stored in the database.
#[test]
fn a_directory_with_field_files_is_read_and_resumed() {
    let d = dir("files");
    let (h, other) = (study_hash("files", &[]), study_hash("other", &[]));
    let s = Store::open(&d, &h, false).unwrap();
    // What the store wrote then: the row, and the files.
    let old = record(1.0);
    s.conn
        .execute(
            "INSERT INTO runs (key, params, status, iterations, residual, seconds, qois, history, state, study_hash)
             VALUES (?1, ?2, ?3, 7, ?4, ?5, ?6, ?7, ?8, ?9)",
            params![point_key(&old.params), to_blob(&old.params), old.status, old.residual,
                    old.seconds, to_blob(&old.qois), to_blob(&old.history), to_blob(&old.state), h],
        )
        .unwrap();
    std::fs::create_dir_all(d.join("fields")).unwrap();
    std::fs::create_dir_all(d.join("cre")).unwrap();
    std::fs::write(s.field_path(&old.params), tagged(&h, &[1.0, 2.0])).unwrap();
    std::fs::write(s.cre_path(&old.params), tagged(&h, &[7.0])).unwrap();
    drop(s);
    let s = Store::open(&d, &h, false).unwrap();
    assert_eq!(s.runs().unwrap(), vec![old.clone()]);
    assert_eq!(s.fields(&old.params).unwrap(), vec![1.0, 2.0]);
    assert_eq!(s.cre(&old.params).unwrap(), Some(vec![7.0]));
    assert_eq!(s.damaged_files(&old.params, 2, true), None);
    // Resumed: a new run goes into the database, the old one is still read from its files.
    let new = record(2.0);
    s.commit(&new, &[3.0, 4.0], Some(&[8.0])).unwrap();
    assert!(!s.field_path(&new.params).exists());
    assert_eq!(s.fields(&new.params).unwrap(), vec![3.0, 4.0]);
    assert_eq!(s.fields(&old.params).unwrap(), vec![1.0, 2.0]);
    assert_eq!(s.runs().unwrap(), vec![old.clone(), new.clone()]);
    // A file of another study: refused on reading and named.
    std::fs::write(s.field_path(&old.params), tagged(&other, &[1.0, 2.0])).unwrap();
    let err = s.fields(&old.params).unwrap_err().to_string();
    assert!(err.contains("belongs to another study"), "{err}");
    let why = s.damaged_files(&old.params, 2, true).unwrap();
    assert!(why.contains("damaged header"), "{why}");
    // Truncated: refused, not misread.
    std::fs::write(s.field_path(&old.params), &b"ALEAFLD1abc"[..]).unwrap();
    assert!(s.fields(&old.params).is_err());
    assert!(
        s.damaged_files(&old.params, 2, true)
            .unwrap()
            .contains("truncated")
    );
    // Missing error estimate; then missing fields.
    std::fs::write(s.field_path(&old.params), tagged(&h, &[1.0, 2.0])).unwrap();
    std::fs::remove_file(s.cre_path(&old.params)).unwrap();
    assert_eq!(s.cre(&old.params).unwrap(), None);
    let why = s.damaged_files(&old.params, 2, true).unwrap();
    assert!(why.contains("error-estimate data is missing"), "{why}");
    std::fs::remove_file(s.field_path(&old.params)).unwrap();
    let why = s.damaged_files(&old.params, 2, false).unwrap();
    assert!(why.contains("field data is missing"), "{why}");
    // Re-solved: stored in the database, read from it.
    s.commit(&old, &[1.5, 2.5], None).unwrap();
    assert_eq!(s.fields(&old.params).unwrap(), vec![1.5, 2.5]);
    drop(s);
    // Started over: the old files go with the rows.
    let s = Store::open(&d, &h, true).unwrap();
    assert!(s.runs().unwrap().is_empty());
    assert!(!d.join("fields").exists() && !d.join("cre").exists());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn runs_read_without_states_are_the_runs_with_empty_states() {
    let d = dir("nostates");
    let h = study_hash("study", &[]);
    let store = Store::open(&d, &h, false).unwrap();
    store.commit(&record(1.0), &[1.0], None).unwrap();
    store.commit(&record(2.0), &[2.0], None).unwrap();
    let full = store.runs().unwrap();
    assert_eq!(full, vec![record(1.0), record(2.0)]);
    let light = store.runs_without_states().unwrap();
    let expected: Vec<RunRecord> = full
        .into_iter()
        .map(|r| RunRecord {
            state: Vec::new(),
            ..r
        })
        .collect();
    assert_eq!(light, expected);
    let _ = std::fs::remove_dir_all(&d);
}
