//! Reopening a study directory without computing: `alea report DIR` rebuilds every output
//! from the store alone (after a kill during the output phase, or for a study that ran with
//! `report = false`).
//!
//! The store keeps the study file's text and path; the study is rebuilt from that text (the
//! mesh file, if any, must still be where it was and unchanged: its bytes are part of the
//! study hash). Runs come from the store only; runs missing from it (a study stopped before it
//! finished) are counted, never computed.

use std::path::Path;

use crate::lock::StudyLock;
use crate::store::Store;
use crate::study::Study;
use crate::study_runs::StudyRuns;
use crate::{Source, StudyError};

/// A reopened study directory.
pub struct Reopened {
    /// The study, rebuilt from the text kept in the store.
    pub study: Study,
    /// Its finished runs (in [`Study::all_points`] order, missing ones left out), the solver
    /// (for field outputs) and the directory's lock.
    pub runs: StudyRuns,
    /// Design points without a finished run (runs whose stored files are damaged included).
    pub missing: usize,
    /// What was found on the way: each run left out because a stored file of it is damaged,
    /// named.
    pub notes: Vec<String>,
}

/// Collects the notes of a replay.
#[derive(Default)]
struct Notes(std::sync::Mutex<Vec<String>>);

impl crate::runner::Progress for Notes {
    fn note(&self, message: &str) {
        if let Ok(mut v) = self.0.lock() {
            v.push(message.to_string());
        }
    }
}

/// Reopens study directory `dir` for `command` (taking its lock).
///
/// # Errors
/// [`StudyError::Usage`] if `dir` holds no study or its mesh file changed;
/// [`StudyError::Busy`] if another process works in it; any error of rebuilding the study.
pub fn reopen(dir: &Path, command: &str) -> Result<Reopened, StudyError> {
    let lock = StudyLock::acquire_existing(dir, command)?;
    let Some((hash, path, text)) = Store::saved_study(dir)? else {
        return Err(StudyError::Usage(format!(
            "{} is not a study directory written by `alea run` (no study.db with the study file in it)",
            dir.display()
        )));
    };
    let study = Study::from_source(Source { path, text })?;
    if study.hash != hash {
        return Err(StudyError::Usage(format!(
            "the runs in {} were computed with another version of the mesh file of {} (hash {hash}, now {}); \
             restore it, or run the study again",
            dir.display(),
            study.source.path.display(),
            study.hash
        )));
    }
    let notes = Notes::default();
    let (runs, missing) = crate::runner::execute(&study, dir, false, &notes, lock, false)?;
    Ok(Reopened {
        runs,
        study,
        missing,
        notes: notes.0.into_inner().unwrap_or_default(),
    })
}
