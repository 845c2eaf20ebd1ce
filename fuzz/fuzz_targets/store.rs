//! The study directory's store reader. A valid store (a `study.db` with three committed runs,
//! two with their field and error-estimate data in the database, one written as before the
//! data moved into it - its row only - and that run's field file) is made once; each case
//! changes bytes of both at offsets chosen by the fuzzer, may cut them short, or replaces the
//! database by arbitrary bytes, then reads them as `alea run` and `alea report` do
//! (`Store::saved_study`, `Store::open`, `Store::runs`, `Store::damaged_files`,
//! `Store::fields`, `Store::cre`): an error or values, never a panic.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use alea_study::store::{RunRecord, Store, point_key};
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;

const HASH: &str = "0123456789abcdef";

fn record(p: f64) -> RunRecord {
    RunRecord {
        params: vec![p, 2.0 * p],
        status: if p > 2.0 {
            "not converged"
        } else {
            "converged"
        }
        .into(),
        iterations: 7,
        residual: 1e-7,
        seconds: 0.1,
        qois: vec![p * p, -p],
        history: vec![1.0, 0.1, 0.01],
        state: vec![0.5; 6],
        slide: None,
    }
}

struct Template {
    dir: PathBuf,
    db: Vec<u8>,
    field: Vec<u8>,
}

/// The valid store, and one scratch directory per fuzzing process.
fn template() -> &'static Template {
    static T: OnceLock<Template> = OnceLock::new();
    T.get_or_init(|| {
        let root = std::env::temp_dir().join(format!("alea-fuzz-store-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let made = root.join("template");
        {
            let store = Store::open(&made, HASH, false).expect("template store");
            store
                .save_study(&made.join("s.toml"), "[study]\ntitle = \"t\"\n")
                .expect("study text");
            for p in [1.0, 2.0, 3.0] {
                store
                    .commit(&record(p), &[p; 6], Some(&[p; 3]))
                    .expect("commit");
            }
        }
        // The run at 1.0 as a directory written before the data moved into the database has
        // it: a row, no `run_data`, a field file (study-hash header, then the values).
        rusqlite::Connection::open(made.join("study.db"))
            .and_then(|c| {
                c.execute(
                    "DELETE FROM run_data WHERE key = ?1",
                    [point_key(&[1.0, 2.0])],
                )
            })
            .expect("template legacy run");
        let db = std::fs::read(made.join("study.db")).expect("template database");
        let mut field = b"ALEAFLD1".to_vec();
        field.extend_from_slice(HASH.as_bytes());
        field.extend(std::iter::repeat_n(1.0f64.to_le_bytes(), 6).flatten());
        let dir = root.join("scratch");
        std::fs::create_dir_all(dir.join("fields")).expect("scratch directory");
        Template { dir, db, field }
    })
}

#[derive(Arbitrary, Debug)]
struct Input<'a> {
    /// Byte changes of the database: (offset modulo its length, new byte).
    db_edits: Vec<(u32, u8)>,
    /// Cut the database to this many bytes (modulo its length + 1).
    db_cut: Option<u32>,
    /// Arbitrary bytes instead of the database.
    db_raw: Option<&'a [u8]>,
    /// Byte changes of the field file.
    field_edits: Vec<(u16, u8)>,
    /// Cut the field file.
    field_cut: Option<u16>,
    /// Values expected in a field file (the model's size).
    field_values: u8,
}

/// The first `n` byte edits of `list`, as (offset, value).
fn edits<T: Copy + Into<u64>>(
    list: &[(T, u8)],
    n: usize,
) -> impl Iterator<Item = (usize, u8)> + '_ {
    list.iter().take(n).map(|&(o, v)| (o.into() as usize, v))
}

fn mutate(bytes: &[u8], edits: impl Iterator<Item = (usize, u8)>, cut: Option<usize>) -> Vec<u8> {
    let mut b = bytes.to_vec();
    if !b.is_empty() {
        for (at, v) in edits {
            let n = b.len();
            b[at % n] = v;
        }
    }
    if let Some(c) = cut {
        b.truncate(c % (bytes.len() + 1));
    }
    b
}

fuzz_target!(|input: Input| {
    let t = template();
    let dir = &t.dir;
    for name in ["study.db", "study.db-wal", "study.db-shm"] {
        let _ = std::fs::remove_file(dir.join(name));
    }
    let db = match input.db_raw {
        Some(raw) => raw.to_vec(),
        None => mutate(
            &t.db,
            edits(&input.db_edits, 64),
            input.db_cut.map(|c| c as usize),
        ),
    };
    std::fs::write(dir.join("study.db"), db).expect("write study.db");
    let _ = Store::saved_study(dir);
    let Ok(store) = Store::open(dir, HASH, false) else {
        return;
    };
    let runs = store.runs().unwrap_or_default();
    let field = mutate(
        &t.field,
        edits(&input.field_edits, 16),
        input.field_cut.map(|c| c as usize),
    );
    for r in runs.iter().take(4) {
        let path = store.field_path(&r.params);
        std::fs::write(&path, &field).expect("write field file");
        let _ = store.damaged_files(&r.params, input.field_values as usize, true);
        let _ = store.fields(&r.params);
        let _ = store.cre(&r.params);
        let _ = std::fs::remove_file(&path);
    }
});
