//! The solver's side of one run spread over ranks (module [`crate::ranks`] for the design and
//! the collective operations): which rank owns which substructure, and the exchanges of the
//! owners' data - at set-up the factors' sizes, the coarse responses' interface values and the
//! condensed operators' sizes; in each iteration the linear stage's interface fields `W`, `F`;
//! at the equilibrium checks each substructure's check; at the end of a run its displacement.
//! Every exchange carries, per substructure, exactly the values its owner computed, so every
//! rank holds the same replicated data as the one process would, bit for bit.
//!
//! A substructure not owned by this rank keeps its model, dof map, links and rigid modes but no
//! operator, factor, prescribed or load right-hand sides (`SubOperator::chol` is `None`), no
//! condensed operator and no volume vectors in a run (its `SubState::rhs` is empty), and of its
//! coarse responses only their interface values (`MacroColumn::u` is empty).

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use super::{FactorInfo, LatinSolver, SubState, V3};
use crate::coarse::{MacroColumn, SubMacro};
use crate::ranks::{RankExchange, assign_substructures};
use crate::{Assembly, LatinError, LatinOptions, SubEquilibrium};

/// The ranks of a solver spread over ranks: the exchange, each substructure's owner and the
/// set-up facts every rank reports of every substructure.
pub(super) struct Ranks {
    exchange: Arc<dyn RankExchange>,
    owner: Vec<usize>,
    /// Per substructure: order, factor entries and supernodal storage of its factor.
    pub(super) factors: Vec<FactorInfo>,
    /// Per substructure: bytes of its condensed stage (`None`: volume solves).
    pub(super) condensed: Vec<Option<f64>>,
    /// One batch of runs at a time on this rank (their exchanges must not interleave).
    turn: Mutex<()>,
}

impl Ranks {
    /// The exchange between the ranks.
    pub(super) fn exchange(&self) -> Arc<dyn RankExchange> {
        self.exchange.clone()
    }

    /// The ranks of `exchange` owning the substructures of `assembly`, each weighed by the
    /// cost of its factorisation, `n^1.5` with `n` its nodal unknowns.
    pub(super) fn for_assembly(exchange: Arc<dyn RankExchange>, assembly: &Assembly) -> Self {
        let costs: Vec<f64> = assembly
            .subs
            .iter()
            .map(|s| ((s.model.mesh.num_nodes() * s.model.mesh.dim) as f64).powf(1.5))
            .collect();
        Ranks::new(exchange, &costs)
    }

    /// Substructures of costs `costs` assigned to the ranks of `exchange`
    /// ([`assign_substructures`]).
    pub(super) fn new(exchange: Arc<dyn RankExchange>, costs: &[f64]) -> Self {
        Ranks {
            owner: assign_substructures(costs, exchange.size()),
            exchange,
            factors: Vec::new(),
            condensed: Vec::new(),
            turn: Mutex::new(()),
        }
    }

    /// Whether this rank owns substructure `s`.
    pub(super) fn owns(&self, s: usize) -> bool {
        self.owner[s] == self.exchange.rank()
    }

    /// For every substructure `s` with `want[s]`, its owner's `encode(s)` (called on the
    /// owned ones only), on every rank; `None` where not wanted.
    pub(super) fn share(
        &self,
        want: &[bool],
        encode: impl Fn(usize) -> Vec<f64>,
    ) -> Vec<Option<Vec<f64>>> {
        let rank = self.exchange.rank();
        let mut mine = Vec::new();
        for s in (0..self.owner.len()).filter(|&s| want[s] && self.owner[s] == rank) {
            let v = encode(s);
            mine.push(v.len() as f64);
            mine.extend_from_slice(&v);
        }
        let all = self.exchange.all_gather(&mine);
        let mut out = vec![None; self.owner.len()];
        for (r, buf) in all.iter().enumerate() {
            let mut at = 0;
            for s in (0..self.owner.len()).filter(|&s| want[s] && self.owner[s] == r) {
                let n = buf.get(at).map_or(0, |&n| n as usize);
                let end = (at + 1 + n).min(buf.len());
                out[s] = Some(buf[(at + 1).min(end)..end].to_vec());
                at = end;
            }
        }
        out
    }

    /// `local` if every rank's is `Ok`; otherwise, on every rank, this rank's error or the
    /// first failing rank's ([`LatinError::OtherRank`]).
    pub(super) fn agree<T>(&self, local: Result<T, LatinError>) -> Result<T, LatinError> {
        let mine: Vec<f64> = match &local {
            Ok(_) => Vec::new(),
            Err(e) => e.to_string().bytes().map(f64::from).collect(),
        };
        let failed = self
            .exchange
            .all_gather(&[vec![f64::from(u8::from(local.is_err()))], mine].concat());
        let first = failed
            .iter()
            .position(|b| b.first().is_some_and(|&f| f != 0.0));
        match (local, first) {
            (Err(e), _) => Err(e),
            (Ok(_), Some(rank)) => Err(LatinError::OtherRank {
                rank,
                message: failed[rank][1..].iter().map(|&c| c as u8 as char).collect(),
            }),
            (Ok(v), None) => Ok(v),
        }
    }

    /// True on every rank if `flag` is true on every rank.
    pub(super) fn all(&self, flag: bool) -> bool {
        self.exchange
            .all_gather(&[f64::from(u8::from(flag))])
            .iter()
            .all(|b| b.first() == Some(&1.0))
    }

    /// This rank's turn to run a batch (held for the batch).
    pub(super) fn turn(&self) -> MutexGuard<'_, ()> {
        self.turn.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl LatinSolver {
    /// Sets up the assembly for one rank of `exchange` (module [`crate::ranks`]): the
    /// substructures are assigned to the ranks by the growth of their factors
    /// ([`crate::ranks::assign_substructures`], `n^1.5` with `n` the nodal unknowns), and this
    /// rank assembles and factorises only its own. Every rank of the group calls this with the
    /// same assembly and options, then runs the same runs in the same order; each run's
    /// [`crate::RunResult`] is complete on every rank and bitwise the run of
    /// [`LatinSolver::new`]. A solver with ranks runs one batch at a time.
    ///
    /// # Errors
    /// As [`LatinSolver::new`], on every rank: a rank whose own substructures fail returns its
    /// error, the others [`LatinError::OtherRank`].
    pub fn with_ranks(
        assembly: Assembly,
        options: LatinOptions,
        exchange: Arc<dyn RankExchange>,
    ) -> Result<Self, LatinError> {
        let ranks = Ranks::for_assembly(exchange, &assembly);
        Self::set_up(assembly, options, Vec::new(), None, Some(ranks))
    }

    /// The rank owning each substructure (all 0 for a solver of one process).
    pub fn substructure_owners(&self) -> Vec<usize> {
        match &self.ranks {
            Some(r) => r.owner.clone(),
            None => vec![0; self.subs.len()],
        }
    }

    /// Ranks this solver's runs are spread over (1 for a solver of one process).
    pub fn rank_count(&self) -> usize {
        self.ranks.as_ref().map_or(1, |r| r.exchange.size())
    }

    /// Whether this rank holds the factorisation of substructure `s` (always, for a solver
    /// of one process).
    pub fn holds_factor(&self, s: usize) -> bool {
        self.subs[s].chol.is_some()
    }

    /// Whether this rank computes substructure `s` (always without ranks).
    pub(super) fn owns(&self, s: usize) -> bool {
        self.ranks.as_ref().is_none_or(|r| r.owns(s))
    }

    /// `local` agreed over the ranks ([`Ranks::agree`]; itself without ranks).
    pub(super) fn agree<T>(
        ranks: Option<&Ranks>,
        local: Result<T, LatinError>,
    ) -> Result<T, LatinError> {
        match ranks {
            Some(r) => r.agree(local),
            None => local,
        }
    }

    /// `flag` on every rank (itself without ranks).
    pub(super) fn everywhere(&self, flag: bool) -> bool {
        self.ranks.as_ref().map_or(flag, |r| r.all(flag))
    }

    /// The linear stage's fields `W`, `F` (before the coarse correction) of every
    /// substructure in every run of `runs`, from their owners.
    pub(super) fn share_fields(&self, mut runs: Vec<&mut Vec<SubState>>) {
        let Some(ranks) = &self.ranks else {
            return;
        };
        let all = vec![true; self.subs.len()];
        let got = ranks.share(&all, |s| {
            let mut v = Vec::new();
            for st in runs.iter() {
                for (w, f) in st[s].w_new.iter().zip(&st[s].f_new) {
                    v.extend(w.iter().chain(f).flatten());
                }
            }
            v
        });
        for (s, vals) in got.into_iter().enumerate() {
            let Some(vals) = vals.filter(|_| !ranks.owns(s)) else {
                continue;
            };
            let mut it = vals.into_iter();
            for st in runs.iter_mut() {
                let SubState { w_new, f_new, .. } = &mut st[s];
                for (w, f) in w_new.iter_mut().zip(f_new.iter_mut()) {
                    for p in w.iter_mut().chain(f.iter_mut()) {
                        *p = take3(&mut it);
                    }
                }
            }
        }
    }

    /// The equilibrium check of every substructure with `want[s]`, from its owner.
    pub(super) fn share_equilibrium(&self, eq: &mut [SubEquilibrium], want: &[bool]) {
        let Some(ranks) = &self.ranks else {
            return;
        };
        let got = ranks.share(want, |s| {
            let e = &eq[s];
            [
                &[e.free_modes as f64][..],
                &e.force,
                &e.moment,
                &[e.relative_imbalance, e.relative_rigid_motion],
            ]
            .concat()
        });
        for (s, v) in got.into_iter().enumerate() {
            if let Some(v) = v.filter(|v| v.len() == 9 && !ranks.owns(s)) {
                eq[s] = SubEquilibrium {
                    free_modes: v[0] as usize,
                    force: [v[1], v[2], v[3]],
                    moment: [v[4], v[5], v[6]],
                    relative_imbalance: v[7],
                    relative_rigid_motion: v[8],
                };
            }
        }
    }

    /// The node-major displacement of every substructure, from its owner.
    pub(super) fn share_displacements(&self, u: &mut [Vec<f64>]) {
        let Some(ranks) = &self.ranks else {
            return;
        };
        let all = vec![true; u.len()];
        let got = ranks.share(&all, |s| u[s].clone());
        for (s, v) in got.into_iter().enumerate() {
            if let Some(v) = v.filter(|_| !ranks.owns(s)) {
                u[s] = v;
            }
        }
    }
}

/// The factor of every substructure (order, entries, supernodal) from its owner; `local`: this
/// rank's, `None` where it holds none.
pub(super) fn share_factors(ranks: &Ranks, local: &[Option<FactorInfo>]) -> Vec<FactorInfo> {
    let all = vec![true; local.len()];
    let flag = |b: bool| f64::from(u8::from(b));
    ranks
        .share(&all, |s| {
            local[s].map_or_else(Vec::new, |f| {
                vec![
                    f.n as f64,
                    f.entries as f64,
                    flag(f.supernodal),
                    flag(f.single),
                    f.bytes as f64,
                ]
            })
        })
        .into_iter()
        .map(|v| match v.as_deref() {
            Some([n, entries, supernodal, single, bytes]) => FactorInfo {
                n: *n as usize,
                entries: *entries as usize,
                supernodal: *supernodal != 0.0,
                single: *single != 0.0,
                bytes: *bytes as usize,
            },
            _ => FactorInfo::default(),
        })
        .collect()
}

/// The bytes of every substructure's condensed stage from its owner (`local`: this rank's,
/// `None` for volume solves or a substructure of another rank; `want`: condensed somewhere).
pub(super) fn share_condensed(
    ranks: &Ranks,
    want: &[bool],
    local: &[Option<f64>],
) -> Vec<Option<f64>> {
    ranks
        .share(want, |s| local[s].into_iter().collect())
        .into_iter()
        .map(|v| v.and_then(|v| v.first().copied()))
        .collect()
}

/// The coarse responses of the substructures with `want[s]` not owned here, from their owners:
/// their interface values and block of the macro operator (not their volume displacements,
/// which only the owner reads).
pub(super) fn share_macros(ranks: &Ranks, subs: &mut [SubMacro], want: &[bool]) {
    let got = ranks.share(want, |s| encode_macro(&subs[s]));
    for (s, v) in got.into_iter().enumerate() {
        if let Some(v) = v.filter(|_| !ranks.owns(s)) {
            subs[s] = decode_macro(&v);
        }
    }
}

/// `[columns, l0 entries, per column: index, links, per link: points, W (3 per point),
/// W_full (3 per point); per entry of l0: row, column, value]`.
fn encode_macro(m: &SubMacro) -> Vec<f64> {
    let mut v = vec![m.columns.len() as f64, m.l0.len() as f64];
    for c in &m.columns {
        v.push(c.index as f64);
        v.push(c.w.len() as f64);
        for (w, wf) in c.w.iter().zip(&c.w_full) {
            v.push(w.len() as f64);
            v.extend(w.iter().chain(wf).flatten());
        }
    }
    for &(r, c, x) in &m.l0 {
        v.extend([r as f64, c as f64, x]);
    }
    v
}

/// Inverse of [`encode_macro`], with empty displacements.
fn decode_macro(v: &[f64]) -> SubMacro {
    let mut it = v.iter().copied();
    let mut next = || it.next().unwrap_or(0.0);
    let (ncol, nl0) = (next() as usize, next() as usize);
    let mut columns = Vec::with_capacity(ncol);
    for _ in 0..ncol {
        let index = next() as usize;
        let links = next() as usize;
        let (mut w, mut w_full) = (Vec::with_capacity(links), Vec::with_capacity(links));
        for _ in 0..links {
            let n = next() as usize;
            let mut read = || -> Vec<V3> { (0..n).map(|_| [next(), next(), next()]).collect() };
            w.push(read());
            w_full.push(read());
        }
        columns.push(MacroColumn {
            index,
            u: Vec::new(),
            w,
            w_full,
        });
    }
    let l0 = (0..nl0)
        .map(|_| (next() as usize, next() as usize, next()))
        .collect();
    SubMacro { columns, l0 }
}

/// The next three values of `it` (zeros past its end).
fn take3(it: &mut impl Iterator<Item = f64>) -> V3 {
    let mut p = [0.0; 3];
    for c in &mut p {
        *c = it.next().unwrap_or(0.0);
    }
    p
}
