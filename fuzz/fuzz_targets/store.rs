//! The study directory's store reader: a `study.db` and a field file of arbitrary bytes are
//! read (`Store::saved_study`, `Store::open`, `Store::runs`, `Store::fields`,
//! `store::read_values`): an error or values, never a panic.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use alea_study::store::{Store, read_values};
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;

#[derive(Arbitrary, Debug)]
struct Input<'a> {
    /// Bytes of `study.db` (empty: no database).
    db: &'a [u8],
    /// Bytes of a run's field file.
    field: &'a [u8],
    /// The run whose field file is read.
    point: [f64; 2],
}

/// One scratch directory per fuzzing process.
fn scratch() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("alea-fuzz-store-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(d.join("fields")).expect("scratch directory");
        d
    })
}

const HASH: &str = "0123456789abcdef";

fuzz_target!(|input: Input| {
    let dir = scratch();
    for name in ["study.db", "study.db-wal", "study.db-shm"] {
        let _ = std::fs::remove_file(dir.join(name));
    }
    if !input.db.is_empty() {
        std::fs::write(dir.join("study.db"), input.db).expect("write study.db");
    }
    let _ = Store::saved_study(dir);
    if let Ok(store) = Store::open(dir, HASH, false) {
        let _ = store.runs();
        let path = store.field_path(&input.point);
        std::fs::write(&path, input.field).expect("write field file");
        let _ = store.fields(&input.point);
        let _ = store.cre(&input.point);
        let _ = read_values(&path);
    }
});
