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

use std::path::{Path, PathBuf};

use rusqlite::{Connection, OptionalExtension, params};

use crate::StudyError;

mod paired;
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

fn to_blob(v: &[f64]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn from_blob(b: &[u8]) -> Vec<f64> {
    b.chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect()
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
        let mut st = self
            .conn
            .prepare("SELECT params, status, iterations, residual, seconds, qois, history, state, slide_interface, slide_slip, slide_ratio FROM runs WHERE study_hash = ?1 ORDER BY rowid")
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

    /// Commits a finished run: its row, its fields and, if given, its error estimate, in one
    /// transaction.
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

    /// Commits finished runs together (a group of runs solved together): every run's row and
    /// its data (fields, error estimate) in one transaction - one synced database commit for
    /// the group, no file. A committed row therefore always has its data, and the group's rows
    /// are committed all or none.
    ///
    /// # Errors
    /// [`StudyError::Busy`] if the database now holds another study (another process started
    /// one in the directory): the rows are refused, never mixed with the other study's; on I/O
    /// or database errors.
    pub fn commit_group(&self, runs: &[RunToCommit<'_>]) -> Result<(), StudyError> {
        if runs.is_empty() {
            return Ok(());
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
        {
            let mut row = tx
                .prepare_cached(
                    "INSERT OR REPLACE INTO runs (key, params, status, iterations, residual, seconds, qois, history, state, study_hash, run_hash, quantities, slide_interface, slide_slip, slide_ratio)
                     VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15)",
                )
                .map_err(db_err(&self.dir))?;
            let mut data = tx
                .prepare_cached(
                    "INSERT OR REPLACE INTO run_data (key, study_hash, fields, cre)
                     VALUES (?1, ?2, ?3, ?4)",
                )
                .map_err(db_err(&self.dir))?;
            let run_hash = self.identity.as_ref().map(|id| id.run_hash.as_str());
            let quantities = self.identity.as_ref().map(|id| id.quantities.join(","));
            for &(rec, fields, cre) in runs {
                let key = point_key(&rec.params);
                row.execute(params![
                    key,
                    to_blob(&rec.params),
                    rec.status,
                    rec.iterations as i64,
                    rec.residual,
                    rec.seconds,
                    to_blob(&rec.qois),
                    to_blob(&rec.history),
                    to_blob(&rec.state),
                    self.hash,
                    run_hash,
                    quantities,
                    rec.slide.as_ref().map(|s| s.interface.as_str()),
                    rec.slide.as_ref().map(|s| s.slip),
                    rec.slide.as_ref().map(|s| s.ratio),
                ])
                .map_err(db_err(&self.dir))?;
                data.execute(params![key, self.hash, to_blob(fields), cre.map(to_blob)])
                    .map_err(db_err(&self.dir))?;
            }
        }
        tx.commit().map_err(db_err(&self.dir))
    }

    /// The `run_data` row of the run at `params`: its study hash and `column` (`None` if the
    /// run has no row: a directory written before the data moved into the database).
    fn data_row<T: rusqlite::types::FromSql>(
        &self,
        params: &[f64],
        column: &str,
    ) -> Result<Option<(String, T)>, StudyError> {
        let sql = match column {
            "fields" => "SELECT study_hash, fields FROM run_data WHERE key = ?1",
            "cre" => "SELECT study_hash, cre FROM run_data WHERE key = ?1",
            _ => return Err(StudyError::Internal(format!("no run_data column {column}"))),
        };
        self.conn
            .prepare_cached(sql)
            .and_then(|mut st| {
                st.query_row(params![point_key(params)], |r| Ok((r.get(0)?, r.get(1)?)))
                    .optional()
            })
            .map_err(db_err(&self.dir))
    }

    /// A [`StudyError::RunData`] for the run at `params`.
    fn data_error(&self, params: &[f64], what: &'static str, why: String) -> StudyError {
        StudyError::RunData {
            dir: self.dir.clone(),
            params: params.to_vec(),
            what,
            why,
        }
    }

    /// The values of a `run_data` BLOB of this study (`hash`), whole f64 values.
    fn untag_blob(
        &self,
        params: &[f64],
        what: &'static str,
        hash: &str,
        b: &[u8],
    ) -> Result<Vec<f64>, StudyError> {
        if hash != self.hash {
            return Err(self.data_error(
                params,
                what,
                format!(
                    "belongs to another study (hash {hash}, this study {}); run again with --restart",
                    self.hash
                ),
            ));
        }
        if !b.len().is_multiple_of(8) {
            return Err(self.data_error(
                params,
                what,
                format!("has {} bytes, not whole values (damaged)", b.len()),
            ));
        }
        Ok(from_blob(b))
    }

    /// Why the stored data of the run at `params` cannot be used, `None` if it can: its field
    /// data must be of this study with `field_values` values, and with `estimate` its
    /// error-estimate data must be present and whole. Reads the sizes only. A run with no
    /// `run_data` row (a directory written before the data moved into the database) is checked
    /// in its files: its field file must exist with `field_values` values (after the
    /// study-hash header of this study, or none for a directory written before headers), and
    /// with `estimate` its error-estimate file must exist with this study's header and whole
    /// values.
    pub fn damaged_files(
        &self,
        params: &[f64],
        field_values: usize,
        estimate: bool,
    ) -> Option<String> {
        // length() of a BLOB reads its size, not its bytes.
        let row = self
            .conn
            .prepare_cached(
                "SELECT study_hash, length(fields), length(cre) FROM run_data WHERE key = ?1",
            )
            .and_then(|mut st| {
                st.query_row(params![point_key(params)], |r| {
                    Ok((
                        r.get::<_, String>(0)?,
                        r.get::<_, Option<i64>>(1)?,
                        r.get::<_, Option<i64>>(2)?,
                    ))
                })
                .optional()
            });
        let (hash, fields, cre) = match row {
            Ok(Some(row)) => row,
            Ok(None) => return self.damaged_legacy_files(params, field_values, estimate),
            Err(e) => return Some(format!("its data cannot be read: {e}")),
        };
        if hash != self.hash {
            return Some(format!(
                "its data belongs to another study (hash {hash}, this study {})",
                self.hash
            ));
        }
        let expected = 8 * field_values as i64;
        let Some(fields) = fields else {
            return Some("its field data is missing".into());
        };
        if fields % 8 != 0 {
            return Some(format!(
                "its field data has {fields} bytes, expected {expected} (truncated or damaged)"
            ));
        }
        if fields != expected {
            return Some(format!(
                "its field data has {} values, expected {field_values} (truncated or damaged)",
                fields / 8
            ));
        }
        if estimate {
            let Some(cre) = cre else {
                return Some("its error-estimate data is missing".into());
            };
            if cre % 8 != 0 {
                return Some(format!(
                    "its error-estimate data has {cre} bytes, not whole values (truncated)"
                ));
            }
        }
        None
    }

    /// [`Store::damaged_files`] for a run stored in files.
    fn damaged_legacy_files(
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
            Err(_) => {
                return Some(format!(
                    "its field data is missing (not in the database, and no file {})",
                    name(&fields)
                ));
            }
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
                Err(_) => {
                    return Some(format!(
                        "its error-estimate data is missing (not in the database, and no file {})",
                        name(&cre)
                    ));
                }
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

    /// True if `hash` (a field file's header) is this study's, or one it held before with the
    /// same runs.
    fn is_this_study(&self, hash: &[u8]) -> bool {
        hash == self.hash.as_bytes() || self.former.iter().any(|h| h.as_bytes() == hash)
    }

    /// True if `path` starts with the header of this study.
    fn header_ok(&self, path: &Path) -> bool {
        use std::io::Read;
        let mut head = [0u8; 24];
        std::fs::File::open(path)
            .and_then(|mut f| f.read_exact(&mut head))
            .is_ok()
            && &head[..8] == FIELD_MAGIC
            && self.is_this_study(&head[8..])
    }

    /// A run's error-estimate data (`None` if the run has none).
    ///
    /// # Errors
    /// If it cannot be read, is damaged, or belongs to another study.
    pub fn cre(&self, params: &[f64]) -> Result<Option<Vec<f64>>, StudyError> {
        const WHAT: &str = "error-estimate data";
        if let Some((hash, blob)) = self.data_row::<Option<Vec<u8>>>(params, "cre")? {
            return match blob {
                Some(b) => self.untag_blob(params, WHAT, &hash, &b).map(Some),
                None => Ok(None),
            };
        }
        let path = self.cre_path(params);
        match std::fs::read(&path) {
            Ok(b) => self.untag(&path, &b).map(Some),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(source) => Err(StudyError::Io { path, source }),
        }
    }

    /// A run's displacement fields (every substructure's, in order).
    ///
    /// # Errors
    /// If they are missing, cannot be read, are damaged, or belong to another study.
    pub fn fields(&self, params: &[f64]) -> Result<Vec<f64>, StudyError> {
        const WHAT: &str = "field data";
        if let Some((hash, b)) = self.data_row::<Vec<u8>>(params, "fields")? {
            return self.untag_blob(params, WHAT, &hash, &b);
        }
        let path = self.field_path(params);
        let b = std::fs::read(&path).map_err(|source| {
            if source.kind() == std::io::ErrorKind::NotFound {
                self.data_error(
                    params,
                    WHAT,
                    format!(
                        "is missing (not in the database, and no file {})",
                        path.display()
                    ),
                )
            } else {
                StudyError::Io {
                    path: path.clone(),
                    source,
                }
            }
        })?;
        match b.strip_prefix(FIELD_MAGIC) {
            Some(_) => self.untag(&path, &b),
            // Written before field files had a header (their rows were migrated above).
            None => Ok(from_blob(&b)),
        }
    }

    /// The values of a file written by the store before the data moved into the database,
    /// checked against this study's hash.
    fn untag(&self, path: &Path, b: &[u8]) -> Result<Vec<f64>, StudyError> {
        match b.strip_prefix(FIELD_MAGIC) {
            Some(rest) if rest.len() >= 16 && (rest.len() - 16) % 8 == 0 => {
                if !self.is_this_study(&rest[..16]) {
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
}
