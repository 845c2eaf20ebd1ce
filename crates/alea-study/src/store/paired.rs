//! The paired solves of the error budget's mesh and sliding parts in the store
//! (`crate::paired_runs`): tables of their own, `paired_models` (per model solved, keyed by its
//! run hash: its node count, or why its solver could not be built) and `paired_runs` (per
//! model and point: the point, the status, the iterations, the seconds, the quantity values
//! with their quantities' keys). Not rows of `runs`: they are solved on other models (the
//! refined mesh, large sliding) and cold, so a row of `runs` at the same point would hold
//! another answer; keyed by the run hash of the model solved, they stay valid through every
//! edit that keeps that model's runs and are never mixed with the design runs.

use std::collections::HashMap;

use rusqlite::{OptionalExtension, params};

use super::{RunRecord, Store, db_err, from_blob, point_key, to_blob};
use crate::StudyError;

/// The schema of the paired solves' tables (created with the store's).
pub(super) const SCHEMA: &str = "CREATE TABLE IF NOT EXISTS paired_models (
     model TEXT PRIMARY KEY,
     nodes INTEGER,
     error TEXT);
 CREATE TABLE IF NOT EXISTS paired_runs (
     model TEXT NOT NULL,
     key TEXT NOT NULL,
     params BLOB NOT NULL,
     status TEXT NOT NULL,
     iterations INTEGER NOT NULL,
     seconds REAL NOT NULL,
     qois BLOB NOT NULL,
     quantities TEXT NOT NULL,
     finished_at TEXT NOT NULL DEFAULT CURRENT_TIMESTAMP,
     PRIMARY KEY (model, key));";

/// What the store holds of a model of the paired solves ([`Store::paired_model`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PairedModel {
    /// Its solver was built: its node count.
    Nodes(usize),
    /// Its solver could not be built: why.
    Failed(String),
}

/// A stored paired solve ([`Store::paired_runs`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PairedRow {
    /// `converged`, another status of a run, or `failed: <why>`.
    pub status: String,
    /// The quantity values (empty for a failed solve).
    pub qois: Vec<f64>,
    /// The quantities' keys of `qois`.
    pub quantities: Vec<String>,
}

impl Store {
    /// What the store holds of the paired solves' model `model` (its run hash), `None` if
    /// nothing.
    ///
    /// # Errors
    /// On database errors.
    pub fn paired_model(&self, model: &str) -> Result<Option<PairedModel>, StudyError> {
        let row: Option<(Option<i64>, Option<String>)> = self
            .conn
            .query_row(
                "SELECT nodes, error FROM paired_models WHERE model = ?1",
                params![model],
                |r| Ok((r.get(0)?, r.get(1)?)),
            )
            .optional()
            .map_err(db_err(&self.dir))?;
        Ok(row.and_then(|(nodes, error)| match (nodes, error) {
            (_, Some(e)) => Some(PairedModel::Failed(e)),
            (Some(n), None) => Some(PairedModel::Nodes(n.max(0) as usize)),
            (None, None) => None,
        }))
    }

    /// The stored paired solves of model `model` (its run hash), by point key.
    ///
    /// # Errors
    /// On database errors.
    pub fn paired_runs(&self, model: &str) -> Result<HashMap<String, PairedRow>, StudyError> {
        let mut st = self
            .conn
            .prepare("SELECT key, status, qois, quantities FROM paired_runs WHERE model = ?1")
            .map_err(db_err(&self.dir))?;
        let rows = st
            .query_map(params![model], |r| {
                let quantities: String = r.get(3)?;
                Ok((
                    r.get::<_, String>(0)?,
                    PairedRow {
                        status: r.get(1)?,
                        qois: from_blob(&r.get::<_, Vec<u8>>(2)?),
                        quantities: if quantities.is_empty() {
                            Vec::new()
                        } else {
                            quantities.split(',').map(str::to_string).collect()
                        },
                    },
                ))
            })
            .map_err(db_err(&self.dir))?;
        rows.collect::<Result<HashMap<_, _>, _>>()
            .map_err(db_err(&self.dir))
    }

    /// Records the paired solves' model `model` (its run hash): built with `nodes` nodes, or
    /// not built, and why.
    ///
    /// # Errors
    /// As [`Store::commit_paired`].
    pub fn set_paired_model(&self, model: &str, what: &PairedModel) -> Result<(), StudyError> {
        let (nodes, error) = match what {
            PairedModel::Nodes(n) => (Some(*n as i64), None),
            PairedModel::Failed(e) => (None, Some(e.as_str())),
        };
        self.write_paired(|tx| {
            tx.execute(
                "INSERT OR REPLACE INTO paired_models (model, nodes, error) VALUES (?1, ?2, ?3)",
                params![model, nodes, error],
            )
            .map(|_| ())
        })
    }

    /// Commits one paired solve of model `model` (its run hash): `rec` with the quantities'
    /// keys `quantities` of its values, in one synced transaction.
    ///
    /// # Errors
    /// [`StudyError::Busy`] if the database now holds another study; on I/O or database
    /// errors.
    pub fn commit_paired(
        &self,
        model: &str,
        rec: &RunRecord,
        quantities: &[String],
    ) -> Result<(), StudyError> {
        self.write_paired(|tx| {
            tx.execute(
                "INSERT OR REPLACE INTO paired_runs (model, key, params, status, iterations, seconds, qois, quantities)
                 VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)",
                params![
                    model,
                    point_key(&rec.params),
                    to_blob(&rec.params),
                    rec.status,
                    rec.iterations as i64,
                    rec.seconds,
                    to_blob(&rec.qois),
                    quantities.join(","),
                ],
            )
            .map(|_| ())
        })
    }

    /// Runs `write` in one immediate transaction once the database is checked to hold this
    /// study still (as [`Store::commit_group`]).
    fn write_paired(
        &self,
        write: impl FnOnce(&rusqlite::Transaction<'_>) -> rusqlite::Result<()>,
    ) -> Result<(), StudyError> {
        let tx = self.checked_transaction("this paired solve is")?;
        write(&tx).map_err(db_err(&self.dir))?;
        tx.commit().map_err(db_err(&self.dir))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paired_rows_are_kept_per_model_and_cleared_on_restart() {
        let dir = std::env::temp_dir().join(format!("alea-store-{}-paired", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let store = Store::open(&dir, "h1", false).unwrap();
        let rec = RunRecord::known(vec![1.0, 2.0], vec![3.0, f64::NAN]);
        let keys = vec!["a".to_string(), "b".to_string()];
        store.commit_paired("m1", &rec, &keys).unwrap();
        store
            .set_paired_model("m1", &PairedModel::Nodes(42))
            .unwrap();
        store
            .set_paired_model("m2", &PairedModel::Failed("singular".into()))
            .unwrap();
        let rows = store.paired_runs("m1").unwrap();
        let row = &rows[&point_key(&[1.0, 2.0])];
        assert_eq!(row.status, "converged");
        assert_eq!(row.qois[0], 3.0);
        assert!(row.qois[1].is_nan());
        assert_eq!(row.quantities, keys);
        assert!(store.paired_runs("m2").unwrap().is_empty());
        assert_eq!(
            store.paired_model("m1").unwrap(),
            Some(PairedModel::Nodes(42))
        );
        assert_eq!(
            store.paired_model("m2").unwrap(),
            Some(PairedModel::Failed("singular".into()))
        );
        assert_eq!(store.paired_model("m3").unwrap(), None);
        // The design runs do not see them.
        assert!(store.runs().unwrap().is_empty());
        drop(store);
        let store = Store::open(&dir, "h1", true).unwrap();
        assert!(store.paired_runs("m1").unwrap().is_empty());
        assert_eq!(store.paired_model("m1").unwrap(), None);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
