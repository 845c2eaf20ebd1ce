//! One LATIN run spread over ranks (issue 38, item 2): the collective operations a run needs
//! ([`RankExchange`]), the deterministic assignment of substructures to ranks
//! ([`assign_substructures`]) and an implementation over threads of one process
//! ([`ThreadExchange`], for tests and for callers without MPI; `alea_study::distributed`
//! implements the trait over an MPI communicator).
//!
//! # Why this split of the work
//! The memory of a substructured model is in its factorisations (and, condensed, its dense
//! interface operators); everything the iteration does outside the linear stage reads interface
//! values only. So each substructure is **owned** by one rank, which alone assembles and
//! factorises it, computes its coarse responses and does its linear stage; the interface fields
//! of the owned substructures (`W`, `F` per link, `6 x points` values per side) are all-gathered
//! after every linear stage, and every rank then does the coarse correction, relaxation, local
//! stage, Anderson acceleration and convergence check for the whole assembly, redundantly and
//! identically (the interface data are small beside the volume; the local stage is a few flops
//! per point). Each owner computes exactly what the one process computes for its substructure,
//! with the same code, and every `f64` travels bit for bit, so a run is **bitwise** the run of
//! one process whatever the number of ranks (`tests/ranks.rs`). The solver side is in
//! `solver/ranks.rs` ([`crate::LatinSolver::with_ranks`]).
//!
//! The memory per rank is then that of its own factors and operators, plus the set-up data
//! every rank keeps of every substructure (model, dof map, links, rigid modes, the interface
//! values of its coarse responses) and the run's results (gathered on every rank).

use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::time::Duration;

/// The collective operations of one run spread over ranks. Every rank of the group calls each
/// operation at the same point of the same run, in the same order (the solver guarantees it:
/// the sequence of calls depends on the run's data only, replicated on every rank).
pub trait RankExchange: Send + Sync {
    /// This rank's number, `0 .. size()`.
    fn rank(&self) -> usize;
    /// Number of ranks of the group.
    fn size(&self) -> usize;
    /// Every rank's `mine`, in rank order (the lengths may differ from rank to rank); the
    /// values arrive bit for bit.
    fn all_gather(&self, mine: &[f64]) -> Vec<Vec<f64>>;
}

/// The rank owning each substructure: greedy by decreasing `cost` (ties by index), each to the
/// least loaded rank so far (ties by the lowest rank). The same on every rank for the same
/// costs. The solver's cost of a substructure is `n^1.5` with `n` its free unknowns, the
/// growth of a sparse factor of a 3D mesh (known before any factorisation).
pub fn assign_substructures(costs: &[f64], ranks: usize) -> Vec<usize> {
    let ranks = ranks.max(1);
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    let mut load = vec![0.0_f64; ranks];
    let mut owner = vec![0; costs.len()];
    for s in order {
        let r = (0..ranks)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .unwrap_or(0);
        owner[s] = r;
        load[r] += costs[s];
    }
    owner
}

/// Ranks simulated by threads of one process: [`ThreadExchange::group`] gives one handle per
/// rank, each to be used by one thread; `all_gather` waits for the other threads.
pub struct ThreadExchange {
    rank: usize,
    shared: Arc<Shared>,
}

struct Shared {
    size: usize,
    /// How long a rank waits for the others before it panics (`None`: for ever).
    timeout: Option<Duration>,
    state: Mutex<Round>,
    done: Condvar,
}

/// The exchange in progress and the last one completed.
struct Round {
    slots: Vec<Vec<f64>>,
    arrived: usize,
    /// Exchanges completed.
    generation: u64,
    gathered: Arc<Vec<Vec<f64>>>,
}

impl ThreadExchange {
    /// The handles of a group of `size` ranks (at least one), rank `r` at index `r`.
    pub fn group(size: usize) -> Vec<Arc<ThreadExchange>> {
        Self::group_with_timeout(size, None)
    }

    /// [`ThreadExchange::group`] whose ranks panic when the others have not reached an exchange
    /// within `timeout` (tests: a rank that leaves the common sequence of exchanges fails
    /// instead of waiting for ever).
    pub fn group_with_timeout(size: usize, timeout: Option<Duration>) -> Vec<Arc<ThreadExchange>> {
        let size = size.max(1);
        let shared = Arc::new(Shared {
            size,
            timeout,
            state: Mutex::new(Round {
                slots: vec![Vec::new(); size],
                arrived: 0,
                generation: 0,
                gathered: Arc::new(Vec::new()),
            }),
            done: Condvar::new(),
        });
        (0..size)
            .map(|rank| {
                Arc::new(ThreadExchange {
                    rank,
                    shared: shared.clone(),
                })
            })
            .collect()
    }
}

impl RankExchange for ThreadExchange {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.shared.size
    }

    fn all_gather(&self, mine: &[f64]) -> Vec<Vec<f64>> {
        let sh = &self.shared;
        let mut round = sh.state.lock().unwrap_or_else(PoisonError::into_inner);
        round.slots[self.rank] = mine.to_vec();
        round.arrived += 1;
        let generation = round.generation;
        if round.arrived == sh.size {
            // The last to arrive completes the exchange; nobody writes the next one's values
            // before every rank has arrived again, so the others read these.
            let slots = std::mem::replace(&mut round.slots, vec![Vec::new(); sh.size]);
            round.gathered = Arc::new(slots);
            round.arrived = 0;
            round.generation += 1;
            sh.done.notify_all();
            return round.gathered.to_vec();
        }
        let pending = |r: &mut Round| r.generation == generation;
        let round = match sh.timeout {
            None => sh
                .done
                .wait_while(round, pending)
                .unwrap_or_else(PoisonError::into_inner),
            Some(t) => {
                let (round, waited) = sh
                    .done
                    .wait_timeout_while(round, t, pending)
                    .unwrap_or_else(PoisonError::into_inner);
                assert!(
                    !waited.timed_out(),
                    "rank {} waited {t:?} for the other ranks at exchange {generation}",
                    self.rank
                );
                round
            }
        };
        round.gathered.to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest first, each to the least loaded rank; the same for any order of equal costs.
    #[test]
    fn assignment_balances_by_cost() {
        assert_eq!(
            assign_substructures(&[1.0, 5.0, 3.0, 3.0], 2),
            vec![0, 0, 1, 1]
        );
        assert_eq!(assign_substructures(&[2.0, 2.0, 2.0], 4), vec![0, 1, 2]);
        assert_eq!(assign_substructures(&[2.0, 2.0], 1), vec![0, 0]);
    }

    /// Each thread gets every thread's values in rank order.
    #[test]
    fn threads_gather_in_rank_order() {
        let group = ThreadExchange::group(3);
        let lonely = ThreadExchange::group_with_timeout(2, Some(Duration::from_millis(50)));
        let waited = std::thread::spawn(move || lonely[0].all_gather(&[1.0])).join();
        assert!(waited.is_err(), "a rank alone at an exchange times out");
        let out: Vec<Vec<Vec<f64>>> = std::thread::scope(|sc| {
            let hs: Vec<_> = group
                .iter()
                .map(|ex| {
                    sc.spawn(move || {
                        let r = ex.rank() as f64;
                        let first = ex.all_gather(&vec![r; ex.rank() + 1]);
                        let second = ex.all_gather(&[10.0 + r]);
                        [first, second].concat()
                    })
                })
                .collect();
            hs.into_iter().map(|h| h.join().unwrap()).collect()
        });
        for o in &out {
            assert_eq!(
                o,
                &vec![
                    vec![0.0],
                    vec![1.0, 1.0],
                    vec![2.0, 2.0, 2.0],
                    vec![10.0],
                    vec![11.0],
                    vec![12.0]
                ]
            );
        }
    }
}
