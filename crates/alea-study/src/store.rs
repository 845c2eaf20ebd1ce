//! The study directory's crash-safe store: an SQLite database (bundled, WAL journal) with one
//! row per finished run, and a compact binary file per run with its displacement fields.
//!
//! A run is committed atomically: its field file is written to a temporary name, synced and
//! renamed, then its row is inserted in one transaction. A study killed at any point therefore
//! resumes with every committed run intact (a field file without a row is simply rewritten).
//! The study file's hash is kept in the database: a changed study file is refused unless the
//! caller asks to start over.

use std::io::Write;
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

/// The study directory.
pub struct Store {
    conn: Connection,
    dir: PathBuf,
}

impl std::fmt::Debug for Store {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Store").field("dir", &self.dir).finish()
    }
}

fn db_err(dir: &Path) -> impl Fn(rusqlite::Error) -> StudyError + '_ {
    move |e| StudyError::Other(format!("study database in {}: {e}", dir.display()))
}

impl Store {
    /// Opens (or creates) the store in `dir` for a study whose file hashes to `hash`.
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
        conn.pragma_update(None, "synchronous", "NORMAL")
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
        match old {
            Some(h) if h != hash => {
                if !restart {
                    return Err(StudyError::Other(format!(
                        "{} holds the results of a different version of this study file (hash {h}, now {hash}); \
                         refusing to mix them. Run again with --restart to discard them, or use another --dir",
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
        })
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Every finished run, in insertion order.
    pub fn runs(&self) -> Result<Vec<RunRecord>, StudyError> {
        let mut st = self
            .conn
            .prepare("SELECT params, status, iterations, residual, seconds, qois, history, state FROM runs ORDER BY rowid")
            .map_err(db_err(&self.dir))?;
        let rows = st
            .query_map([], |r| {
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

    /// Writes `values` (f64 little-endian) to `path` through a synced temporary file renamed
    /// into place.
    fn write_atomic(path: &Path, values: &[f64]) -> Result<(), StudyError> {
        let tmp = path.with_extension("tmp");
        let io = |p: &Path| {
            let p = p.to_path_buf();
            move |source| StudyError::Io { path: p, source }
        };
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(io(parent))?;
        }
        {
            let mut f = std::fs::File::create(&tmp).map_err(io(&tmp))?;
            f.write_all(&to_blob(values)).map_err(io(&tmp))?;
            f.sync_all().map_err(io(&tmp))?;
        }
        std::fs::rename(&tmp, path).map_err(io(path))
    }

    /// Commits a finished run: its fields and, if given, its error estimate (each f64
    /// little-endian, atomically renamed into place), then its row. A committed row therefore
    /// always has its files.
    pub fn commit(
        &self,
        rec: &RunRecord,
        fields: &[f64],
        cre: Option<&[f64]>,
    ) -> Result<(), StudyError> {
        Self::write_atomic(&self.field_path(&rec.params), fields)?;
        if let Some(c) = cre {
            Self::write_atomic(&self.cre_path(&rec.params), c)?;
        }
        self.conn
            .execute(
                "INSERT OR REPLACE INTO runs (key, params, status, iterations, residual, seconds, qois, history, state)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
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
                ],
            )
            .map_err(db_err(&self.dir))?;
        Ok(())
    }

    /// Reads a run's error-estimate file (`None` if the run has none).
    pub fn cre(&self, params: &[f64]) -> Result<Option<Vec<f64>>, StudyError> {
        let path = self.cre_path(params);
        match std::fs::read(&path) {
            Ok(b) => Ok(Some(from_blob(&b))),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(source) => Err(StudyError::Io { path, source }),
        }
    }

    /// Reads a run's field file.
    pub fn fields(&self, params: &[f64]) -> Result<Vec<f64>, StudyError> {
        read_values(&self.field_path(params))
    }
}

/// Reads a file of `f64` little-endian values (a field or error-estimate file).
pub fn read_values(path: &Path) -> Result<Vec<f64>, StudyError> {
    let b = std::fs::read(path).map_err(|source| StudyError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(from_blob(&b))
}

/// The file stem of a run's files: `run_<FNV-1a of its point key>` (short and stable).
pub fn run_file_stem(params: &[f64]) -> String {
    let mut h: u64 = 0xcbf29ce484222325;
    for b in point_key(params).bytes() {
        h = (h ^ b as u64).wrapping_mul(0x100000001b3);
    }
    format!("run_{h:016x}")
}

/// A stable 64-bit hash (FNV-1a) of a study file's text, as 16 hex digits.
pub fn text_hash(text: &str) -> String {
    let mut h: u64 = 0xcbf29ce484222325;
    for b in text.bytes() {
        h = (h ^ b as u64).wrapping_mul(0x100000001b3);
    }
    format!("{h:016x}")
}
