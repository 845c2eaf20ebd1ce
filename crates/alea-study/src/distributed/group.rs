//! Groups of ranks that solve one run together (`[solver] ranks_per_run = R`, issue 38): the
//! world is split into groups of `R` consecutive ranks, and each group's communicator carries
//! the collective operations of its runs ([`MpiExchange`], `alea_latin::RankExchange`: each
//! rank owns some substructures, module `alea_latin::ranks`). The group's first rank is the one
//! rank 0 sees (it gets the group's jobs and sends their results back); it forwards each job to
//! the other ranks of its group, which solve it with it and send nothing back. A group solves
//! one group of runs at a time, on one solver thread per rank, so that its ranks call the
//! exchanges in the same order; the exchanges are called from that thread while the main thread
//! polls the world communicator, hence MPI's `Threading::Multiple` for such jobs.

use mpi::datatype::PartitionMut;
use mpi::topology::{Color, SimpleCommunicator};
use mpi::traits::*;

use crate::StudyError;

/// The collective operations of one run over the communicator of a group of ranks.
pub struct MpiExchange {
    comm: SimpleCommunicator,
}

// SAFETY: MPI is initialised with `Threading::Multiple` whenever an `MpiExchange` exists
// (`super::start`), and a group communicator is used by one thread at a time: the solver's
// exchanges of a rank are sequential (one batch at a time, `alea_latin::ranks`), and the main
// thread never uses it after the set-up.
unsafe impl Send for MpiExchange {}
unsafe impl Sync for MpiExchange {}

impl alea_latin::RankExchange for MpiExchange {
    fn rank(&self) -> usize {
        self.comm.rank() as usize
    }

    fn size(&self) -> usize {
        self.comm.size() as usize
    }

    fn all_gather(&self, mine: &[f64]) -> Vec<Vec<f64>> {
        let size = self.size();
        let n = mine.len() as mpi::Count;
        let mut counts: Vec<mpi::Count> = vec![0; size];
        self.comm.all_gather_into(&n, &mut counts[..]);
        let displs: Vec<mpi::Count> = counts
            .iter()
            .scan(0, |at, &c| {
                let d = *at;
                *at += c;
                Some(d)
            })
            .collect();
        let total: usize = counts.iter().map(|&c| c as usize).sum();
        let mut buf = vec![0.0f64; total];
        {
            let mut part = PartitionMut::new(&mut buf[..], &counts[..], &displs[..]);
            self.comm.all_gather_varcount_into(mine, &mut part);
        }
        counts
            .iter()
            .zip(&displs)
            .map(|(&c, &d)| buf[d as usize..(d + c) as usize].to_vec())
            .collect()
    }
}

/// This rank's place in a job of `size` ranks in groups of `per_run`.
#[derive(Clone, Copy, Debug)]
pub struct Place {
    /// Ranks per group.
    pub per_run: usize,
    /// The first rank of this rank's group.
    pub head: usize,
}

impl Place {
    /// The place of `rank`.
    pub fn of(rank: usize, per_run: usize) -> Self {
        Place {
            per_run,
            head: rank - rank % per_run,
        }
    }

    /// The other ranks of a group whose first rank is `head`.
    pub fn members(&self) -> std::ops::Range<usize> {
        self.head + 1..self.head + self.per_run
    }
}

/// Splits `world` into groups of `per_run` consecutive ranks (collective on `world`).
///
/// # Errors
/// When the job's ranks are not a multiple of `per_run`.
pub fn split(world: &SimpleCommunicator, per_run: usize) -> Result<MpiExchange, StudyError> {
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    if size % per_run != 0 {
        return Err(StudyError::Mpi(format!(
            "[solver] ranks_per_run = {per_run} needs a number of ranks that is a multiple of it, got {size}"
        )));
    }
    let color = Color::with_value((rank / per_run) as i32);
    let comm = world
        .split_by_color(color)
        .ok_or_else(|| StudyError::Mpi("the world communicator could not be split".into()))?;
    Ok(MpiExchange { comm })
}

/// `[solver] ranks_per_run` of the study file at `path` (1 when absent, or when the file cannot
/// be read or parsed here: loading the study reports its errors with their lines).
pub fn ranks_per_run(path: &std::path::Path) -> usize {
    let Ok(text) = std::fs::read_to_string(path) else {
        return 1;
    };
    let Ok(table) = text.parse::<toml::Table>() else {
        return 1;
    };
    table
        .get("solver")
        .and_then(|s| s.get("ranks_per_run"))
        .and_then(toml::Value::as_integer)
        .filter(|r| (1..=crate::settings_check::MAX_RANKS_PER_RUN).contains(r))
        .map_or(1, |r| r as usize)
}
