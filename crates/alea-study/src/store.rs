//! The study directory's crash-safe store: an SQLite database (bundled, WAL journal) with one
//! row per finished run, and a compact binary file per run with its displacement fields.
//!
//! A run is committed atomically: its field file is written to a temporary name, synced and
//! renamed (and the directory synced), then its row is inserted in one transaction. A study
//! killed at any point therefore resumes with every committed run intact (a field file without
//! a row is simply rewritten).
//!
//! **Which study.** The study's hash (of the study file's text and of the mesh file it reads)
//! is kept in the database, and every run row and every field file carries it: a changed
//! study is refused unless the caller asks to start over, rows of another hash are never
//! returned, and a field file of another study is refused on reading. The study file's text is
//! kept too, so that `alea report DIR` can rebuild every output from the directory alone.
//!
//! **Durability.** `synchronous = FULL` with the WAL journal: a commit returns only once the
//! WAL is synced, so a finished run survives a kill, an OS crash and a power loss (given a disk
//! that honours flushes). `NORMAL` would survive a kill but could lose the last commits on power
//! loss; FULL costs one more fsync per run, measured in `BENCHMARKS.md` ("store commits").
//! Field file format: 8 bytes `ALEAFLD1`, 16 ASCII hex digits of the study hash, then the
//! values as f64 little-endian.

use std::path::{Path, PathBuf};

use rusqlite::{Connection, OptionalExtension, params};

use crate::StudyError;

/// One finished run (converged or not).
#[derive(Clone, Debug, PartialEq)]
pub struct RunRecord {
    /// Parameter point (physical values).
    pub params: Vec<f64>,
    /// `converged`, `not converged`, `diverged`, or `no equilibrium: <which substructure, its
    /// unbalanced force and moment, its rigid motion>`.
    pub status: String,
    /// LATIN iterations.
    pub iterations: usize,
    /// Final error indicator.
    pub residual: f64,
    /// Wall-clock seconds of the solve.
    pub seconds: f64,
    /// Quantities of interest, in study order.
    pub qois: Vec<f64>,
    /// Error indicator history.
    pub history: Vec<f64>,
    /// Local-stage state (`alea_latin::LocalState::to_vec`), for warm starts.
    pub state: Vec<f64>,
}

impl RunRecord {
    /// True if the run converged.
    pub fn converged(&self) -> bool {
        self.status == "converged"
    }
}

/// Key of a parameter point: the exact bits of its coordinates.
pub fn point_key(params: &[f64]) -> String {
    params
        .iter()
        .map(|v| format!("{:016x}", v.to_bits()))
        .collect::<Vec<_>>()
        .join(":")
}

fn to_blob(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn from_blob(b: &[u8]) -> Vec<f64> {
    b.chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect()
}

/// Magic bytes at the start of a field file.
const FIELD_MAGIC: &[u8; 8] = b"ALEAFLD1";

/// A finished run to commit ([`Store::commit_group`]): its row, its displacement fields and
/// its error-estimate data (when the study estimates its error).
pub type RunToCommit<'a> = (&'a RunRecord, &'a [f64], Option<&'a [f64]>);

/// The SQLite `synchronous` level of the store (see the module doc).
pub const SYNCHRONOUS: &str = "FULL";

/// The study directory.
pub struct Store {
    conn: Connection,
    dir: PathBuf,
    hash: String,
}

impl std::fmt::Debug for Store {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Store").field("dir", &self.dir).finish()
    }
}

/// A database error: a full disk or an I/O failure is a file-system error (exit code 3),
/// anything else a store failure.
fn db_err(dir: &Path) -> impl Fn(rusqlite::Error) -> StudyError + '_ {
    move |e| {
        use rusqlite::ErrorCode as C;
        let io = matches!(
            e.sqlite_error_code(),
            Some(
                C::DiskFull
                    | C::SystemIoFailure
                    | C::CannotOpen
                    | C::ReadOnly
                    | C::PermissionDenied
                    | C::DatabaseBusy
                    | C::DatabaseLocked
            )
        );
        if io {
            StudyError::Io {
                path: dir.join("study.db"),
                source: std::io::Error::other(e.to_string()),
            }
        } else {
            StudyError::Database {
                dir: dir.to_path_buf(),
                error: e,
            }
        }
    }
}

impl Store {
    /// Opens (or creates) the store in `dir` for a study whose hash is `hash` (see
    /// [`study_hash`]). With `restart`, every stored run is discarded.
    ///
    /// # Errors
    /// If the directory holds a different study (hash mismatch) and `restart` is false; on
    /// I/O or database errors.
    pub fn open(dir: &Path, hash: &str, restart: bool) -> Result<Self, StudyError> {
        let io = |p: &Path| {
            let p = p.to_path_buf();
            move |source| StudyError::Io { path: p, source }
        };
        std::fs::create_dir_all(dir.join("fields")).map_err(io(dir))?;
        let db = dir.join("study.db");
        let mut conn = Connection::open(&db).map_err(db_err(dir))?;
        conn.pragma_update(None, "journal_mode", "WAL")
            .map_err(db_err(dir))?;
        conn.pragma_update(None, "synchronous", SYNCHRONOUS)
            .map_err(db_err(dir))?;
        conn.execute_batch(
            "CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
             CREATE TABLE IF NOT EXISTS runs (
                 key TEXT PRIMARY KEY,
                 params BLOB NOT NULL,
                 status TEXT NOT NULL,
                 iterations INTEGER NOT NULL,
                 residual REAL NOT NULL,
                 seconds REAL NOT NULL,
                 qois BLOB NOT NULL,
                 history BLOB NOT NULL,
                 state BLOB NOT NULL,
                 finished_at TEXT NOT NULL DEFAULT CURRENT_TIMESTAMP);",
        )
        .map_err(db_err(dir))?;
        let old: Option<String> = conn
            .query_row("SELECT value FROM meta WHERE key = 'study_hash'", [], |r| {
                r.get(0)
            })
            .optional()
            .map_err(db_err(dir))?;
        // Directories written before runs carried their study's hash: their rows belong to
        // the hash in `meta`.
        let has_column = conn.prepare("SELECT study_hash FROM runs LIMIT 0").is_ok();
        if !has_column {
            conn.execute("ALTER TABLE runs ADD COLUMN study_hash TEXT", [])
                .map_err(db_err(dir))?;
            if let Some(h) = &old {
                conn.execute("UPDATE runs SET study_hash = ?1", params![h])
                    .map_err(db_err(dir))?;
            }
        }
        match old {
            Some(h) if h != hash => {
                if !restart {
                    return Err(StudyError::Usage(format!(
                        "{} holds the results of a different study or version of the study file \
                         (hash {h}, now {hash}; the mesh file counts too); refusing to mix them. \
                         Run again with --restart to discard them, or use another --dir",
                        dir.display()
                    )));
                }
                let tx = conn.transaction().map_err(db_err(dir))?;
                tx.execute("DELETE FROM runs", []).map_err(db_err(dir))?;
                tx.execute(
                    "UPDATE meta SET value = ?1 WHERE key = 'study_hash'",
                    params![hash],
                )
                .map_err(db_err(dir))?;
                tx.commit().map_err(db_err(dir))?;
                let _ = std::fs::remove_dir_all(dir.join("fields"));
                let _ = std::fs::remove_dir_all(dir.join("cre"));
                std::fs::create_dir_all(dir.join("fields")).map_err(io(dir))?;
            }
            Some(_) => {
                if restart {
                    conn.execute("DELETE FROM runs", []).map_err(db_err(dir))?;
                }
            }
            None => {
                conn.execute(
                    "INSERT INTO meta (key, value) VALUES ('study_hash', ?1)",
                    params![hash],
                )
                .map_err(db_err(dir))?;
            }
        }
        Ok(Store {
            conn,
            dir: dir.to_path_buf(),
            hash: hash.to_string(),
        })
    }

    /// The study hash of a study directory and the study file it holds (path as given to
    /// `alea run`, text), without opening it for writing; `None` if `dir` holds no study.
    ///
    /// # Errors
    /// On database errors.
    pub fn saved_study(dir: &Path) -> Result<Option<(String, PathBuf, String)>, StudyError> {
        let db = dir.join("study.db");
        if !db.is_file() {
            return Ok(None);
        }
        let conn = Connection::open_with_flags(&db, rusqlite::OpenFlags::SQLITE_OPEN_READ_ONLY)
            .map_err(db_err(dir))?;
        let get = |k: &str| -> Result<Option<String>, StudyError> {
            conn.query_row("SELECT value FROM meta WHERE key = ?1", params![k], |r| {
                r.get(0)
            })
            .optional()
            .map_err(db_err(dir))
        };
        match (get("study_hash")?, get("study_path")?, get("study_text")?) {
            (Some(h), Some(p), Some(t)) => Ok(Some((h, PathBuf::from(p), t))),
            _ => Ok(None),
        }
    }

    /// Keeps the study file (its path and text) in the store, for `alea report`.
    pub fn save_study(&self, path: &Path, text: &str) -> Result<(), StudyError> {
        let tx = self
            .conn
            .unchecked_transaction()
            .map_err(db_err(&self.dir))?;
        for (k, v) in [
            (
                "study_path",
                std::fs::canonicalize(path)
                    .unwrap_or_else(|_| path.to_path_buf())
                    .display()
                    .to_string(),
            ),
            ("study_text", text.to_string()),
        ] {
            tx.execute(
                "INSERT OR REPLACE INTO meta (key, value) VALUES (?1, ?2)",
                params![k, v],
            )
            .map_err(db_err(&self.dir))?;
        }
        tx.commit().map_err(db_err(&self.dir))
    }

    /// Sets SQLite's `synchronous` level (`OFF`, `NORMAL`, `FULL`) for this connection: only
    /// for measuring what [`SYNCHRONOUS`] costs (`benches/store.rs`).
    pub fn set_synchronous(&self, level: &str) -> Result<(), StudyError> {
        self.conn
            .pragma_update(None, "synchronous", level)
            .map_err(db_err(&self.dir))
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Every finished run of this study (rows of another study hash are never returned), in
    /// insertion order.
    pub fn runs(&self) -> Result<Vec<RunRecord>, StudyError> {
        let mut st = self
            .conn
            .prepare("SELECT params, status, iterations, residual, seconds, qois, history, state FROM runs WHERE study_hash = ?1 ORDER BY rowid")
            .map_err(db_err(&self.dir))?;
        let rows = st
            .query_map(params![self.hash], |r| {
                Ok(RunRecord {
                    params: from_blob(&r.get::<_, Vec<u8>>(0)?),
                    status: r.get(1)?,
                    iterations: r.get::<_, i64>(2)? as usize,
                    residual: r.get(3)?,
                    seconds: r.get(4)?,
                    qois: from_blob(&r.get::<_, Vec<u8>>(5)?),
                    history: from_blob(&r.get::<_, Vec<u8>>(6)?),
                    state: from_blob(&r.get::<_, Vec<u8>>(7)?),
                })
            })
            .map_err(db_err(&self.dir))?;
        rows.collect::<Result<Vec<_>, _>>()
            .map_err(db_err(&self.dir))
    }

    /// Path of the field file of a run (`fields/<run_file_stem>.bin`).
    pub fn field_path(&self, params: &[f64]) -> PathBuf {
        self.dir
            .join("fields")
            .join(format!("{}.bin", run_file_stem(params)))
    }

    /// Path of the error-estimate file of a run (`cre/run_<hash>.bin`, next to its fields).
    pub fn cre_path(&self, params: &[f64]) -> PathBuf {
        let f = self.field_path(params);
        let name = f.file_name().map(|n| n.to_os_string()).unwrap_or_default();
        self.dir.join("cre").join(name)
    }

    /// Writes `values` with the study-hash header (then f64 little-endian), synced and
    /// atomically renamed into place.
    fn write_tagged(&self, path: &Path, values: &[f64]) -> Result<(), StudyError> {
        let mut bytes = Vec::with_capacity(24 + 8 * values.len());
        bytes.extend_from_slice(FIELD_MAGIC);
        bytes.extend_from_slice(self.hash.as_bytes());
        bytes.extend_from_slice(&to_blob(values));
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|source| StudyError::Io {
                path: parent.to_path_buf(),
                source,
            })?;
        }
        alea_mesh::atomic::write_bytes_atomic_unsynced_dir(path, &bytes).map_err(|source| {
            StudyError::Io {
                path: path.to_path_buf(),
                source,
            }
        })
    }

    /// Commits a finished run: its fields and, if given, its error estimate (each with the
    /// study-hash header, then f64 little-endian; synced and atomically renamed into place),
    /// then its row. A committed row therefore always has its files.
    ///
    /// # Errors
    /// As [`Store::commit_group`].
    pub fn commit(
        &self,
        rec: &RunRecord,
        fields: &[f64],
        cre: Option<&[f64]>,
    ) -> Result<(), StudyError> {
        self.commit_group(&[(rec, fields, cre)])
    }

    /// Commits finished runs together (a group of runs solved together): every run's files
    /// (each synced and atomically renamed into place), then their directories synced once,
    /// then all their rows in one transaction - one synced database commit and one directory
    /// sync for the group instead of one per run. A committed row therefore always has its
    /// files, and the group's rows are committed all or none.
    ///
    /// # Errors
    /// [`StudyError::Busy`] if the database now holds another study (another process started
    /// one in the directory): the rows are refused, never mixed with the other study's; on I/O
    /// or database errors.
    pub fn commit_group(&self, runs: &[RunToCommit<'_>]) -> Result<(), StudyError> {
        if runs.is_empty() {
            return Ok(());
        }
        let mut dirs: Vec<PathBuf> = Vec::new();
        for &(rec, fields, cre) in runs {
            let mut write = |path: PathBuf, values: &[f64]| -> Result<(), StudyError> {
                self.write_tagged(&path, values)?;
                if let Some(d) = path.parent()
                    && !dirs.iter().any(|x| x == d)
                {
                    dirs.push(d.to_path_buf());
                }
                Ok(())
            };
            write(self.field_path(&rec.params), fields)?;
            if let Some(c) = cre {
                write(self.cre_path(&rec.params), c)?;
            }
        }
        for d in &dirs {
            alea_mesh::atomic::sync_parent(&d.join("x"));
        }
        // One write transaction, taken at once: the study the directory holds is checked and
        // the rows inserted with no other writer in between.
        let tx = rusqlite::Transaction::new_unchecked(
            &self.conn,
            rusqlite::TransactionBehavior::Immediate,
        )
        .map_err(db_err(&self.dir))?;
        let now: Option<String> = tx
            .query_row("SELECT value FROM meta WHERE key = 'study_hash'", [], |r| {
                r.get(0)
            })
            .optional()
            .map_err(db_err(&self.dir))?;
        if now.as_deref() != Some(self.hash.as_str()) {
            return Err(StudyError::Busy {
                dir: self.dir.clone(),
                holder: format!(
                    "another study (hash {}, this study {}), started in it by another process; \
                     {} not stored",
                    now.as_deref().unwrap_or("none"),
                    self.hash,
                    if runs.len() == 1 {
                        "this run is".to_string()
                    } else {
                        format!("these {} runs are", runs.len())
                    }
                ),
            });
        }
        for &(rec, _, _) in runs {
            tx.execute(
                "INSERT OR REPLACE INTO runs (key, params, status, iterations, residual, seconds, qois, history, state, study_hash)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)",
                params![
                    point_key(&rec.params),
                    to_blob(&rec.params),
                    rec.status,
                    rec.iterations as i64,
                    rec.residual,
                    rec.seconds,
                    to_blob(&rec.qois),
                    to_blob(&rec.history),
                    to_blob(&rec.state),
                    self.hash,
                ],
            )
            .map_err(db_err(&self.dir))?;
        }
        tx.commit().map_err(db_err(&self.dir))
    }

    /// Why the stored files of the run at `params` cannot be used, `None` if they can: its
    /// field file must exist with `field_values` values (after the study-hash header of this
    /// study, or none for a directory written before headers), and with `estimate` its
    /// error-estimate file must exist with this study's header and whole values. Reads the
    /// headers only.
    pub fn damaged_files(
        &self,
        params: &[f64],
        field_values: usize,
        estimate: bool,
    ) -> Option<String> {
        let header = 8 + 16;
        let name = |p: &Path| p.strip_prefix(&self.dir).unwrap_or(p).display().to_string();
        let fields = self.field_path(params);
        let expected = [header + 8 * field_values as u64, 8 * field_values as u64];
        match std::fs::metadata(&fields) {
            Err(_) => return Some(format!("{} is missing", name(&fields))),
            Ok(m) if !expected.contains(&m.len()) => {
                return Some(format!(
                    "{} has {} bytes, expected {} (truncated or damaged)",
                    name(&fields),
                    m.len(),
                    expected[0]
                ));
            }
            Ok(m) if m.len() == expected[0] && !self.header_ok(&fields) => {
                return Some(format!("{} has a damaged header", name(&fields)));
            }
            Ok(_) => {}
        }
        if estimate {
            let cre = self.cre_path(params);
            match std::fs::metadata(&cre) {
                Err(_) => return Some(format!("{} is missing", name(&cre))),
                Ok(m) if m.len() < header || (m.len() - header) % 8 != 0 => {
                    return Some(format!("{} is truncated", name(&cre)));
                }
                Ok(_) if !self.header_ok(&cre) => {
                    return Some(format!("{} has a damaged header", name(&cre)));
                }
                Ok(_) => {}
            }
        }
        None
    }

    /// True if `path` starts with the header of this study.
    fn header_ok(&self, path: &Path) -> bool {
        use std::io::Read;
        let mut head = [0u8; 24];
        std::fs::File::open(path)
            .and_then(|mut f| f.read_exact(&mut head))
            .is_ok()
            && &head[..8] == FIELD_MAGIC
            && &head[8..] == self.hash.as_bytes()
    }

    /// Reads a run's error-estimate file (`None` if the run has none).
    pub fn cre(&self, params: &[f64]) -> Result<Option<Vec<f64>>, StudyError> {
        let path = self.cre_path(params);
        match std::fs::read(&path) {
            Ok(b) => self.untag(&path, &b).map(Some),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(source) => Err(StudyError::Io { path, source }),
        }
    }

    /// Reads a run's field file.
    ///
    /// # Errors
    /// If it cannot be read, or belongs to another study.
    pub fn fields(&self, params: &[f64]) -> Result<Vec<f64>, StudyError> {
        let path = self.field_path(params);
        let b = std::fs::read(&path).map_err(|source| StudyError::Io {
            path: path.clone(),
            source,
        })?;
        match b.strip_prefix(FIELD_MAGIC) {
            Some(_) => self.untag(&path, &b),
            // Written before field files had a header (their rows were migrated above).
            None => Ok(from_blob(&b)),
        }
    }

    /// The values of a file written by `write_tagged`, checked against this study's hash.
    fn untag(&self, path: &Path, b: &[u8]) -> Result<Vec<f64>, StudyError> {
        match b.strip_prefix(FIELD_MAGIC) {
            Some(rest) if rest.len() >= 16 && (rest.len() - 16) % 8 == 0 => {
                if &rest[..16] != self.hash.as_bytes() {
                    return Err(StudyError::ForeignFile {
                        path: path.to_path_buf(),
                        hash: String::from_utf8_lossy(&rest[..16]).into_owned(),
                        study: self.hash.clone(),
                    });
                }
                Ok(from_blob(&rest[16..]))
            }
            _ => Err(StudyError::Corrupt {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Reads a file of `f64` little-endian values written by the store (a field or error-estimate
/// file): the study-hash header, if any, is skipped (the store's own readers check it).
pub fn read_values(path: &Path) -> Result<Vec<f64>, StudyError> {
    let b = std::fs::read(path).map_err(|source| StudyError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    match b.strip_prefix(FIELD_MAGIC) {
        Some(rest) if rest.len() >= 16 && (rest.len() - 16) % 8 == 0 => Ok(from_blob(&rest[16..])),
        Some(_) => Err(StudyError::Corrupt {
            path: path.to_path_buf(),
        }),
        None => Ok(from_blob(&b)),
    }
}

/// The file stem of a run's files: `run_<FNV-1a of its point key>` (short and stable).
pub fn run_file_stem(params: &[f64]) -> String {
    let mut h: u64 = 0xcbf29ce484222325;
    for b in point_key(params).bytes() {
        h = (h ^ b as u64).wrapping_mul(0x100000001b3);
    }
    format!("run_{h:016x}")
}

/// The hash of a study: its file's text and the bytes of every other input file it reads
/// (`extra`, e.g. a Gmsh mesh), as 16 hex digits.
pub fn study_hash(text: &str, extra: &[&[u8]]) -> String {
    let mut h: u64 = 0xcbf29ce484222325;
    let mut feed = |bytes: &[u8]| {
        for &b in bytes {
            h = (h ^ b as u64).wrapping_mul(0x100000001b3);
        }
    };
    feed(text.as_bytes());
    for e in extra {
        feed(&(e.len() as u64).to_le_bytes());
        feed(e);
    }
    format!("{h:016x}")
}

#[cfg(test)]
mod tests {
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
        }
    }

    #[test]
    fn rows_and_field_files_of_another_study_are_never_used() {
        let d = dir("hash");
        let (a, b) = (study_hash("study A", &[]), study_hash("study B", &[]));
        let store = Store::open(&d, &a, false).unwrap();
        store.commit(&record(1.0), &[1.0, 2.0, 3.0], None).unwrap();
        assert_eq!(store.fields(&[1.0, 2.0]).unwrap(), vec![1.0, 2.0, 3.0]);
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
        // A field file written by study B at the same point.
        let mut bytes = FIELD_MAGIC.to_vec();
        bytes.extend_from_slice(b.as_bytes());
        bytes.extend_from_slice(&to_blob(&[9.0, 9.0, 9.0]));
        std::fs::write(store.field_path(&[1.0, 2.0]), bytes).unwrap();
        let err = store.fields(&[1.0, 2.0]).unwrap_err().to_string();
        assert!(err.contains("belongs to another study"), "{err}");
        // Truncated file: refused, not misread.
        let path = store.field_path(&[1.0, 2.0]);
        std::fs::write(&path, &b"ALEAFLD1abc"[..]).unwrap();
        assert!(store.fields(&[1.0, 2.0]).is_err());
        drop(store);
        // The study file changed: refused without --restart, emptied with it.
        let e = Store::open(&d, &b, false).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{e}");
        let s = Store::open(&d, &b, true).unwrap();
        assert!(s.runs().unwrap().is_empty());
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
    }
}
