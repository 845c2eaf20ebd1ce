//! What an MPI job did, as rank 0 saw it: ranks, threads, runs per rank, bytes each way.

/// Traffic and work of an MPI job, as seen by rank 0.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Ranks.
    pub ranks: usize,
    /// Solver threads of each rank.
    pub threads: Vec<usize>,
    /// Runs solved by each rank.
    pub runs: Vec<usize>,
    /// Bytes of the jobs sent to other ranks.
    pub job_bytes: u64,
    /// Of which warm-start states.
    pub state_bytes: u64,
    /// Bytes of the results received from other ranks.
    pub result_bytes: u64,
    /// Batches that went through the executor.
    pub batches: usize,
}

impl Stats {
    /// Runs solved on ranks other than 0.
    pub fn remote_runs(&self) -> usize {
        self.runs.iter().skip(1).sum()
    }

    /// One line for the log: ranks, runs per rank, bytes per remote run each way.
    pub fn summary(&self) -> String {
        let per = |b: u64| b as f64 / self.remote_runs().max(1) as f64;
        format!(
            "MPI: {} ranks x {:?} solver threads, runs per rank {:?}, {} batches; per remote run: \
             {:.0} bytes sent (warm-start state {:.0}), {:.0} bytes back (a state kept on every \
             rank instead would cost {:.0} bytes per run)",
            self.ranks,
            self.threads,
            self.runs,
            self.batches,
            per(self.job_bytes),
            per(self.state_bytes),
            per(self.result_bytes),
            per(self.state_bytes) * (self.ranks.saturating_sub(1)) as f64,
        )
    }
}
