//! Rank 0's side of handing out work (module doc of `distributed`): a group of runs sent to
//! the rank that solves it, and the dispatch log that records where each run went.

use std::io::Write;
use std::path::Path;
use std::sync::mpsc;

use mpi::topology::SimpleCommunicator;

use super::transport::{Incoming, send};
use super::wire;
use super::{Group, LeaderInner, LeaderState, TAG_JOB, TAG_RESULT};
use crate::StudyError;
use crate::solve::RunJob;

/// Sends the group `out` to rank `r`: to rank 0's own solver threads (`job_tx`) and to the other
/// members of its group of ranks per run (module `group`), or as a message to rank `r`;
/// returns the messages that arrived while sending.
pub(super) fn send_group(
    world: &SimpleCommunicator,
    inner: &LeaderInner,
    st: &mut LeaderState,
    r: usize,
    out: Group,
    job_tx: &mpsc::Sender<Group>,
) -> Result<Vec<Incoming>, StudyError> {
    let refs: Vec<(u64, &RunJob)> = out.iter().map(|(id, j)| (*id, j)).collect();
    let (bytes, state) = wire::encode_group(&refs);
    let mut arrived = Vec::new();
    if r == 0 {
        // Rank 0's group solves it with rank 0 (module `group`).
        for m in inner.place.members() {
            arrived.extend(send(world, m, TAG_JOB, &bytes, Some(TAG_RESULT)));
        }
        job_tx
            .send(out)
            .map_err(|_| StudyError::Mpi("rank 0's solver threads stopped".into()))?;
    } else {
        st.stats.job_bytes += bytes.len() as u64;
        st.stats.state_bytes += state as u64;
        arrived.extend(send(world, r, TAG_JOB, &bytes, Some(TAG_RESULT)));
    }
    Ok(arrived)
}

/// The dispatch log of the study directory `dir` (`mpi-dispatch.log`, appended to), its
/// header line written for a job of `size` ranks.
pub(super) fn open_dispatch_log(
    dir: &Path,
    size: usize,
) -> Result<std::io::BufWriter<std::fs::File>, StudyError> {
    let path = dir.join("mpi-dispatch.log");
    let file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&path)
        .map_err(|source| StudyError::Io { path, source })?;
    let mut w = std::io::BufWriter::new(file);
    let _ = writeln!(w, "# job of {size} ranks: batch, rank <- run");
    Ok(w)
}
