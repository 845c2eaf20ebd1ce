//! The study directory's crash-safe store: an SQLite database (bundled, WAL journal) with one
//! row per finished run and, in the same database, the run's displacement fields (and its
//! error-estimate data when the study estimates its error) as BLOBs.
//!
//! **Tables.** `meta` (the study hash, the run hash, the study hashes it held before with the
//! same runs, the study file's path and text), `runs` (one row per finished run: point,
//! status, iterations, quantities of interest, error history, local-stage state, study hash,
//! run hash, quantities' keys) and `run_data` (per run: `key` as in `runs`, `study_hash`, `fields` - the
//! displacements of every substructure, f64 little-endian - and `cre`, the error-estimate
//! values or NULL). `run_data` is a table of its own so that reading every run's row
//! ([`Store::runs`]) never reads the fields. `paired_models` and `paired_runs` hold the paired
//! solves of the error budget's mesh and sliding parts, apart from the runs (module `paired`).
//!
//! A run is committed atomically: its `runs` row and its `run_data` row are inserted in one
//! transaction, and the runs solved together are committed together ([`Store::commit_group`]:
//! one synced database commit per group, no file at all). A committed row therefore always has
//! its data, and a study killed at any point resumes with every committed run intact.
//!
//! **Which study.** The study's hash (of the study file's text and of the mesh file it reads)
//! is kept in the database, and every run row and every `run_data` row carries it: rows of
//! another hash are never returned, and field data of another study is refused on reading.
//! Every run row also carries the study's run hash and its quantities' keys
//! (`crate::run_hash`; columns `run_hash`, `quantities`, NULL in rows written before them):
//! a directory holding another study hash is accepted by [`Store::open_study`] when its run
//! hash is the study's (an edit that keeps the runs - the runs are re-tagged with the new
//! study hash, their quantity values put in the study's order, a run lacking a quantity left
//! out to be computed again), and refused otherwise unless the caller asks to start over. The
//! study file's text is kept too, so that `alea report DIR` can rebuild every output from the
//! directory alone.
//!
//! **Durability.** `synchronous = FULL` with the WAL journal: a commit returns only once the
//! WAL is synced, so a finished run survives a kill, an OS crash and a power loss (given a disk
//! that honours flushes). `NORMAL` would survive a kill but could lose the last commits on power
//! loss; FULL costs one more fsync per commit, measured in `BENCHMARKS.md` ("store commits").
//!
//! **Directories written before the data moved into the database** (up to 2026-11) kept each
//! run's fields in a file `fields/run_<h>.bin` (and `cre/run_<h>.bin`): 8 bytes `ALEAFLD1`, 16
//! ASCII hex digits of the study hash, then the values as f64 little-endian (or, older still,
//! the values alone). A run with no `run_data` row is read from its file ([`Store::field_path`],
//! [`Store::cre_path`]), so such directories are still read and resumed; the runs solved after
//! the resumption are stored in the database.
//!
//! The runs are committed with their data, and that data read back, in `store/run_data.rs`.

use std::path::{Path, PathBuf};

use rusqlite::{Connection, OptionalExtension, params};

use crate::StudyError;

mod paired;
mod run_data;
pub use paired::{PairedModel, PairedRow};

/// What defines a study's runs, as the store keeps it: the run hash and the quantities' keys
/// in study order (`crate::run_hash::RunIdentity` computes them; the store does not depend on
/// how).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunKeys<'a> {
    /// The run hash.
    pub run_hash: &'a str,
    /// The quantities' keys, in study order.
    pub quantities: &'a [String],
}

/// [`RunKeys`], owned by an open store.
#[derive(Clone, Debug)]
struct OwnedRunKeys {
    run_hash: String,
    quantities: Vec<String>,
}

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
    /// The run's largest slide over the local mesh size, on any contact interface and step
    /// (`alea_latin::sliding`; columns `slide_interface`, `slide_slip`, `slide_ratio`); `None`
    /// for a study without a contact interface, and for the runs stored before the slide was
    /// kept with the run (their slide is unknown).
    pub slide: Option<RunSlide>,
}

/// The largest slide of a run: where the tangential slip over the local mesh size is largest
/// among its contact interfaces and steps (module `alea_latin::sliding`).
#[derive(Clone, Debug, PartialEq)]
pub struct RunSlide {
    /// The interface's name (as in the study file).
    pub interface: String,
    /// The tangential slip there (length).
    pub slip: f64,
    /// The slip over the local mesh size (beyond small sliding above
    /// `alea_latin::sliding::SMALL_SLIDING_LIMIT`).
    pub ratio: f64,
}

impl RunRecord {
    /// A converged run at `params` with the quantities `qois`, one iteration, no history and no
    /// warm-start state: the record of a response known without a solve (tests, benchmarks).
    pub fn known(params: Vec<f64>, qois: Vec<f64>) -> Self {
        RunRecord {
            params,
            status: "converged".into(),
            iterations: 1,
            residual: 0.0,
            seconds: 0.0,
            qois,
            history: Vec::new(),
            state: Vec::new(),
            slide: None,
        }
    }

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

/// A vector as a BLOB (`alea_uq::bytes`, alea's one binary encoding).
fn to_blob(v: &[f64]) -> Vec<u8> {
    alea_uq::bytes::f64s_to_le(v)
}

/// A BLOB as a vector.
fn from_blob(b: &[u8]) -> Vec<f64> {
    alea_uq::bytes::f64s_from_le(b)
}

/// Magic bytes at the start of a field file (directories written before the data moved into
/// the database).
const FIELD_MAGIC: &[u8; 8] = b"ALEAFLD1";

/// A finished run to commit ([`Store::commit_group`]): its row, its displacement fields and
/// its error-estimate data (when the study estimates its error).
pub type RunToCommit<'a> = (&'a RunRecord, &'a [f64], Option<&'a [f64]>);

/// Removes the field and error-estimate files of a directory written before the run data
/// moved into the database (best effort: their rows are gone, nothing reads them).
fn remove_legacy_files(dir: &Path) {
    let _ = std::fs::remove_dir_all(dir.join("fields"));
    let _ = std::fs::remove_dir_all(dir.join("cre"));
}

/// Sets `key` in the `meta` table.
fn set_meta(tx: &Connection, dir: &Path, key: &str, value: &str) -> Result<(), StudyError> {
    tx.execute(
        "INSERT OR REPLACE INTO meta (key, value) VALUES (?1, ?2)",
        params![key, value],
    )
    .map(|_| ())
    .map_err(db_err(dir))
}

/// The refusal of a directory that holds another study (`runs_known`: it records a run hash,
/// which differs from this study's).
fn different_study(dir: &Path, old: &str, new: &str, runs_known: bool) -> StudyError {
    let why = if runs_known {
        "what defines its runs differs (the model - mesh and its files, substructures, \
         materials, loads, constraints, interfaces, fields, steps -, the parameters' laws or \
         the solver settings)"
    } else {
        "it was written before study directories recorded what defines their runs, so only \
         an unchanged study file reuses them"
    };
    StudyError::Usage(format!(
        "{} holds the results of a different study or version of the study file \
         (hash {old}, now {new}; the mesh file counts too): {why}; refusing to mix them. \
         Run again with --restart to discard them, or use another --dir",
        dir.display()
    ))
}

/// Makes the runs of `run_hash` stored under the study hash `old` (or any earlier one) runs
/// of the study hash `new` (an edit that keeps them, `Store::open_study`): each run whose
/// stored quantities include every quantity of `id` gets its values in `id`'s order and the
/// new study hash (its data too); the others keep their old hash, out of [`Store::runs`],
/// until they are computed again. `old` is remembered for the field files of old directories.
fn adopt(
    tx: &Connection,
    dir: &Path,
    old: &str,
    new: &str,
    id: &RunKeys<'_>,
) -> Result<(), StudyError> {
    let rows: Vec<(String, String, Vec<u8>, Option<String>)> = tx
        .prepare("SELECT key, study_hash, qois, quantities FROM runs WHERE run_hash = ?1")
        .and_then(|mut st| {
            st.query_map(params![id.run_hash], |r| {
                Ok((r.get(0)?, r.get(1)?, r.get(2)?, r.get(3)?))
            })?
            .collect::<Result<Vec<_>, _>>()
        })
        .map_err(db_err(dir))?;
    let quantities = id.quantities.join(",");
    for (key, row_hash, qois, stored) in rows {
        let stored: Vec<&str> = stored
            .as_deref()
            .map_or(Vec::new(), |s| s.split(',').collect());
        let Some(values) = remap_quantities(&from_blob(&qois), &stored, id.quantities) else {
            continue;
        };
        tx.execute(
            "UPDATE runs SET qois = ?1, quantities = ?2, study_hash = ?3 WHERE key = ?4",
            params![to_blob(&values), quantities, new, key],
        )
        .map_err(db_err(dir))?;
        tx.execute(
            "UPDATE run_data SET study_hash = ?1 WHERE key = ?2 AND study_hash = ?3",
            params![new, key, row_hash],
        )
        .map_err(db_err(dir))?;
    }
    let former: Option<String> = tx
        .query_row(
            "SELECT value FROM meta WHERE key = 'former_hashes'",
            [],
            |r| r.get(0),
        )
        .optional()
        .map_err(db_err(dir))?;
    let mut list: Vec<String> = former
        .map(|f| f.split(',').map(str::to_string).collect())
        .unwrap_or_default();
    if !list.iter().any(|h| h == old) {
        list.push(old.to_string());
    }
    set_meta(tx, dir, "former_hashes", &list.join(","))
}

/// A run's quantity values `values` (stored under the keys `stored`) in the order of the keys
/// `wanted`; `None` if a wanted key is not stored (or the values do not match their keys).
pub fn remap_quantities(values: &[f64], stored: &[&str], wanted: &[String]) -> Option<Vec<f64>> {
    if values.len() != stored.len() {
        return None;
    }
    wanted
        .iter()
        .map(|w| stored.iter().position(|s| s == w).map(|i| values[i]))
        .collect()
}

/// The SQLite `synchronous` level of the store (see the module doc).
pub const SYNCHRONOUS: &str = "FULL";

/// The study directory.
pub struct Store {
    conn: Connection,
    dir: PathBuf,
    hash: String,
    /// What defines the study's runs (`None`: opened by its study hash alone; its commits
    /// carry no run hash).
    identity: Option<OwnedRunKeys>,
    /// Study hashes this directory held before with the same runs (edits that kept them):
    /// the headers of field files written then are this study's too.
    former: Vec<String>,
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
    /// [`study_hash`]), known by that hash alone: a directory holding another study hash is
    /// refused (or, with `restart`, emptied). With `restart`, every stored run is discarded.
    ///
    /// # Errors
    /// If the directory holds a different study (hash mismatch) and `restart` is false; on
    /// I/O or database errors.
    pub fn open(dir: &Path, hash: &str, restart: bool) -> Result<Self, StudyError> {
        Self::open_with(dir, hash, None, restart)
    }

    /// Opens (or creates) the store in `dir` for a study whose hash is `hash` and whose runs
    /// are defined by `identity` (`crate::run_hash`). A directory holding another study hash
    /// is accepted when it holds the same run hash (the study file was edited in a way that
    /// keeps its runs): the new study hash is recorded, and each stored run that has a value of
    /// every quantity of the study is kept (its values put in the study's order); a run that
    /// lacks one stays out of [`Store::runs`] and is computed again. Rows written before runs
    /// carried a run hash are this study's only if the study hash is unchanged (they are then
    /// given the run hash). With `restart`, every stored run is discarded.
    ///
    /// # Errors
    /// If the directory holds a study with other runs (another run hash, or another study
    /// hash and no run hash) and `restart` is false; on I/O or database errors.
    pub fn open_study(
        dir: &Path,
        hash: &str,
        identity: RunKeys<'_>,
        restart: bool,
    ) -> Result<Self, StudyError> {
        Self::open_with(dir, hash, Some(identity), restart)
    }

    fn open_with(
        dir: &Path,
        hash: &str,
        identity: Option<RunKeys<'_>>,
        restart: bool,
    ) -> Result<Self, StudyError> {
        let mut conn = Self::connect(dir)?;
        let meta = |conn: &Connection, k: &str| -> Result<Option<String>, StudyError> {
            conn.query_row("SELECT value FROM meta WHERE key = ?1", params![k], |r| {
                r.get(0)
            })
            .optional()
            .map_err(db_err(dir))
        };
        let old = meta(&conn, "study_hash")?;
        let old_runs = meta(&conn, "run_hash")?;
        let tx = conn.transaction().map_err(db_err(dir))?;
        let clear = |tx: &rusqlite::Transaction<'_>| {
            tx.execute_batch("DELETE FROM runs; DELETE FROM run_data; DELETE FROM paired_runs; DELETE FROM paired_models; DELETE FROM meta WHERE key = 'former_hashes';")
                .map_err(db_err(dir))
        };
        let mut cleared = false;
        match old {
            Some(h) if h != hash => {
                let same_runs = identity.is_some_and(|id| old_runs.as_deref() == Some(id.run_hash));
                if restart {
                    clear(&tx)?;
                    cleared = true;
                } else if let (true, Some(id)) = (same_runs, &identity) {
                    adopt(&tx, dir, &h, hash, id)?;
                } else {
                    return Err(different_study(dir, &h, hash, old_runs.is_some()));
                }
                set_meta(&tx, dir, "study_hash", hash)?;
            }
            Some(_) => {
                if restart {
                    clear(&tx)?;
                    cleared = true;
                }
            }
            None => set_meta(&tx, dir, "study_hash", hash)?,
        }
        if let Some(id) = &identity {
            // Rows of this very study written before runs carried a run hash.
            tx.execute(
                "UPDATE runs SET run_hash = ?1, quantities = ?2 WHERE study_hash = ?3 AND run_hash IS NULL",
                params![id.run_hash, id.quantities.join(","), hash],
            )
            .map_err(db_err(dir))?;
            set_meta(&tx, dir, "run_hash", id.run_hash)?;
        }
        tx.commit().map_err(db_err(dir))?;
        if cleared {
            remove_legacy_files(dir);
        }
        let former = meta(&conn, "former_hashes")?
            .map(|f| f.split(',').map(str::to_string).collect())
            .unwrap_or_default();
        Ok(Store {
            conn,
            dir: dir.to_path_buf(),
            hash: hash.to_string(),
            identity: identity.map(|id| OwnedRunKeys {
                run_hash: id.run_hash.to_string(),
                quantities: id.quantities.to_vec(),
            }),
            former,
        })
    }

    /// Opens the database of `dir` (created if needed, tables and columns migrated).
    fn connect(dir: &Path) -> Result<Connection, StudyError> {
        std::fs::create_dir_all(dir).map_err(|source| StudyError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let conn = Connection::open(dir.join("study.db")).map_err(db_err(dir))?;
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
                 finished_at TEXT NOT NULL DEFAULT CURRENT_TIMESTAMP);
             CREATE TABLE IF NOT EXISTS run_data (
                 key TEXT PRIMARY KEY,
                 study_hash TEXT NOT NULL,
                 fields BLOB NOT NULL,
                 cre BLOB);",
        )
        .map_err(db_err(dir))?;
        conn.execute_batch(paired::SCHEMA).map_err(db_err(dir))?;
        let has = |column: &str| {
            conn.prepare(&format!("SELECT {column} FROM runs LIMIT 0"))
                .is_ok()
        };
        // Directories written before runs carried their study's hash: their rows belong to
        // the hash in `meta`.
        if !has("study_hash") {
            conn.execute("ALTER TABLE runs ADD COLUMN study_hash TEXT", [])
                .map_err(db_err(dir))?;
            conn.execute(
                "UPDATE runs SET study_hash = (SELECT value FROM meta WHERE key = 'study_hash')",
                [],
            )
            .map_err(db_err(dir))?;
        }
        // Directories written before runs carried their run hash and their quantities' keys
        // (NULL: known only through the study hash).
        // Directories written before each run kept its largest slide (NULL: not known; also
        // the runs of a study without a contact interface).
        for (column, kind) in [
            ("run_hash", "TEXT"),
            ("quantities", "TEXT"),
            ("slide_interface", "TEXT"),
            ("slide_slip", "REAL"),
            ("slide_ratio", "REAL"),
        ] {
            if !has(column) {
                conn.execute(&format!("ALTER TABLE runs ADD COLUMN {column} {kind}"), [])
                    .map_err(db_err(dir))?;
            }
        }
        Ok(conn)
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
        self.read_runs(true)
    }

    /// [`Store::runs`] without their warm-start states (`RunRecord::state` empty): what reading
    /// a study's results needs. A state holds 12 values per interface point, cuts of automatic
    /// subdomains included (2.2 MB a run on the 3D turbine at 602 100 dof), which a study of
    /// thousands of runs would otherwise load in full only to report on them.
    pub fn runs_without_states(&self) -> Result<Vec<RunRecord>, StudyError> {
        self.read_runs(false)
    }

    fn read_runs(&self, states: bool) -> Result<Vec<RunRecord>, StudyError> {
        let state = if states { "state" } else { "x''" };
        let mut st = self
            .conn
            .prepare(&format!("SELECT params, status, iterations, residual, seconds, qois, history, {state}, slide_interface, slide_slip, slide_ratio FROM runs WHERE study_hash = ?1 ORDER BY rowid"))
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
                    slide: match (r.get(8)?, r.get(9)?, r.get(10)?) {
                        (Some(interface), Some(slip), Some(ratio)) => Some(RunSlide {
                            interface,
                            slip,
                            ratio,
                        }),
                        _ => None,
                    },
                })
            })
            .map_err(db_err(&self.dir))?;
        rows.collect::<Result<Vec<_>, _>>()
            .map_err(db_err(&self.dir))
    }

    /// Path of the field file of a run in a directory written before the run data moved into
    /// the database (`fields/<run_file_stem>.bin`): read when the run has no `run_data` row.
    pub fn field_path(&self, params: &[f64]) -> PathBuf {
        self.dir
            .join("fields")
            .join(format!("{}.bin", run_file_stem(params)))
    }

    /// Path of the error-estimate file of a run in a directory written before the run data
    /// moved into the database (`cre/run_<hash>.bin`, next to its fields).
    pub fn cre_path(&self, params: &[f64]) -> PathBuf {
        let f = self.field_path(params);
        let name = f.file_name().map(|n| n.to_os_string()).unwrap_or_default();
        self.dir.join("cre").join(name)
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
mod tests;
