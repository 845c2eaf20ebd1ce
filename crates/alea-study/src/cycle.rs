//! `[cycle]`: the last `[[step]]`s of a load history repeated as a load cycle, a stated number
//! of times or until the contact state is shakedown-periodic; the quantities are measured over
//! the last cycle.
//!
//! ```toml
//! [[step]]
//! name = "press"
//! load = { pull = 0.0 }
//! [[step]]
//! name = "up"
//! load = { pull = 1.0 }
//! [[step]]
//! name = "down"
//! load = { pull = -1.0 }
//! [cycle]
//! steps = ["up", "down"]   # the last steps of the history, in their order
//! until = 1e-3             # shakedown tolerance on the slip amplitude (optional)
//! repeat = 10              # cycles run (with until: at most; default 20)
//! ```
//!
//! The steps before the cycle run once; then the cycle's steps run in order, each from the end
//! state of the previous step (module `steps`), `repeat` times, or with `until` until the
//! **slip amplitude** of every frictional interface changes by less than `until` from one cycle
//! to the next, relative to the largest amplitude of the cycles run so far:
//! `max_p |delta_n(p) - delta_{n-1}(p)| <= until max_{m <= n, p} delta_m(p)` (at least two
//! cycles; changes below `1e-6` of the largest tangential jump count as none, the solver's
//! round-off; a run that does not get there within `repeat` cycles is reported not converged).
//! The reference is the largest amplitude seen, not the current one, because a contact that
//! shakes down to sticking (a wedged blade root) has an amplitude decaying geometrically to 0:
//! its relative change from cycle to cycle stays constant while the amplitude vanishes.
//! A quantity with `step = NAME` measures that step of the **last** cycle (a step before the
//! cycle: its only run); the fretting quantities (`qoi::fretting`) are taken over the last
//! cycle, from the state at the end of the step before it.
//!
//! **Large sliding** (`sliding = "large"`, `alea_latin::large_sliding`): every step of the
//! cycle is a large-sliding step, re-paired from the previous step's pairing and end state
//! (`steps::run_large_sliding`, the same [`run_cycles`] over `SlidingStep`s); there is no warm
//! start from the previous cycle (`steps::cycle_start` starts a LATIN iterate on the same
//! interface points, and a re-paired step starts from its predicted configuration on the
//! pairing found there). A point of a re-paired interface is a material point of the side
//! carrying the points (`alea_latin::fretting::slip_cycle_repaired`: the multiplier node of
//! side `P`, whose partner changes with the slide); shakedown compares the amplitudes of the
//! same nodes from cycle to cycle (a point present in one cycle only changes by its amplitude),
//! and the fretting quantities take each step on its own pairing, the work from the step's
//! slip origin `j0_k = [Pi_k u_{k-1}]_t`:
//!
//! ```text
//!   delta_i = 1/2 max_{k,l closed} |j_k - j_l|,   j_k = [Pi_k u_k]_t
//!   W = sum_k sum_i w_i^k (-(j_k - j0_k) . q_k)   (= the sum of the steps' friction dissipations)
//! ```
//!
//! Checked at load (file, line, field): a cycle with no step, an unknown or repeated step, steps
//! that are not the last ones of the history in their order, `repeat < 1`, `until` not in
//! `(0, 1)`, a cycle without `[[step]]`s, (module `steps`) a fretting quantity without a
//! cycle or with a `step`, and ([`check_large_sliding_fretting`]) `ruiz_f2` or a fretting
//! quantity at a `point` on a re-paired interface (or on any contact interface with the
//! sliding part of `[budget]`).

use std::collections::BTreeMap;

use alea_latin::fretting::{CycleStep, slip_cycle, slip_cycle_repaired};
use alea_latin::large_sliding::SlidingStep;
use alea_latin::{InterfaceResult, RunResult, RunStatus};

use crate::spec::ModelFile;
use crate::{Source, StudyError};

/// Cycles run with `until` and no `repeat`.
pub const DEFAULT_MAX_CYCLES: usize = 20;

/// The cycle of a load history.
#[derive(Clone, Debug, PartialEq)]
pub struct CyclePlan {
    /// Index of the cycle's first step in the plan's steps.
    pub first: usize,
    /// Number of steps in the cycle (the plan's last ones).
    pub len: usize,
    /// Number of cycles (with `until`: at most).
    pub repeat: usize,
    /// Shakedown tolerance.
    pub until: Option<f64>,
}

/// Checks the `[cycle]` of `file` against the step names `names` (in order).
pub fn plan_cycle(
    src: &Source,
    file: &ModelFile,
    names: &[String],
) -> Result<Option<CyclePlan>, StudyError> {
    let Some(spec) = &file.cycle else {
        return Ok(None);
    };
    let c = spec.get_ref();
    let steps = c.steps.get_ref();
    if names.is_empty() {
        return Err(src.error(
            spec.span(),
            "cycle",
            "a cycle repeats [[step]]s: the file has none",
        ));
    }
    if steps.is_empty() {
        return Err(src.error(
            c.steps.span(),
            "cycle.steps",
            "a cycle needs at least one step",
        ));
    }
    for (j, s) in steps.iter().enumerate() {
        if !names.contains(s.get_ref()) {
            return Err(src.error(
                s.span(),
                format!("cycle.steps[{j}]"),
                format!(
                    "no step is named '{}' (steps: {})",
                    s.get_ref(),
                    names.join(", ")
                ),
            ));
        }
    }
    let first = names.len().saturating_sub(steps.len());
    let tail = &names[first..];
    if steps.len() > names.len() || steps.iter().zip(tail).any(|(s, n)| s.get_ref() != n) {
        return Err(src.error(
            c.steps.span(),
            "cycle.steps",
            format!(
                "a cycle is the last steps of the history, in their order: here [{}]",
                tail.iter()
                    .map(|n| format!("\"{n}\""))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ));
    }
    let until = match &c.until {
        Some(u) => {
            let v = *u.get_ref();
            if !(v.is_finite() && v > 0.0 && v < 1.0) {
                return Err(src.error(
                    u.span(),
                    "cycle.until",
                    format!("the shakedown tolerance is a relative change in (0, 1), got {v}"),
                ));
            }
            Some(v)
        }
        None => None,
    };
    let repeat = match &c.repeat {
        Some(r) => {
            let v = *r.get_ref();
            if v < 1 {
                return Err(src.error(
                    r.span(),
                    "cycle.repeat",
                    format!("at least one cycle, got {v}"),
                ));
            }
            usize::try_from(v).unwrap_or(usize::MAX)
        }
        None if until.is_some() => DEFAULT_MAX_CYCLES,
        None => {
            return Err(src.error(
                spec.span(),
                "cycle.repeat",
                "missing; give repeat (the number of cycles) and/or until (a shakedown tolerance)",
            ));
        }
    };
    if until.is_some() && repeat < 2 {
        return Err(src.error(
            c.repeat.as_ref().map_or(spec.span(), |r| r.span()),
            "cycle.repeat",
            "shakedown (until) compares two cycles: repeat must be at least 2",
        ));
    }
    Ok(Some(CyclePlan {
        first,
        len: steps.len(),
        repeat,
        until,
    }))
}

/// The fretting quantities a `[cycle]` with a re-paired interface (`sliding = "large"`) cannot
/// give: Ruiz's F2 (its `sigma_T`, at a material point of the stress substructure, and its
/// `tau delta`, at a material point of the side carrying the interface points, are the same
/// point only while the sides do not slide apart) and any quantity at a `point` (the nearest
/// side-1 point: the points of a re-paired interface are on the side the first pairing chose,
/// the coarser one, and side 1's node facing a side-2 point changes with the slide). Refused
/// with the file, line and field of the quantity. `budget`: the check is that of the sliding
/// part of `[budget]`, whose solves put every contact interface in large sliding (the
/// message says so); otherwise of the interfaces with `sliding = "large"`.
pub fn check_large_sliding_fretting(
    src: &Source,
    file: &ModelFile,
    qois: &[crate::qoi::Qoi],
    assembly: &alea_latin::Assembly,
    budget: bool,
) -> Result<(), StudyError> {
    for (i, (q, spec)) in qois.iter().zip(&file.quantity).enumerate() {
        let crate::qoi::QoiKind::Fretting(f) = &q.kind else {
            continue;
        };
        let Some(it) = assembly.interfaces.get(f.iface).filter(|it| {
            alea_latin::large_sliding::is_repaired(it) || (budget && it.law.uses_gap())
        }) else {
            continue;
        };
        let at_point = f.node.is_some();
        if !crate::qoi::fretting::refused_with_large_sliding(f.field, at_point) {
            continue;
        }
        let (span, field, why) = match (&spec.point, at_point) {
            (Some(p), true) => (
                p.span(),
                format!("quantity[{i}].point"),
                "a fretting quantity at a point is not available on an interface with \
                 sliding = \"large\": its points are material points of the side its first \
                 pairing chose and the point facing a side-1 node changes with the slide; \
                 leave out point (the largest over the interface)",
            ),
            _ => (
                spec.kind.span(),
                format!("quantity[{i}].kind"),
                "ruiz_f2 is not available on an interface with sliding = \"large\": its \
                 surface stress and its slip and traction belong to material points of the \
                 two sides that slide apart (docs/study-file.md, [cycle]); use ruiz_f1 and swt",
            ),
        };
        let context = if budget {
            " (the sliding part of [budget], large_sliding = true, solves the study with \
             sliding = \"large\" on every contact interface)"
        } else {
            ""
        };
        return Err(src.error(
            span,
            field,
            format!(
                "'{}' on interface '{}'{context}: {why}",
                spec.name.get_ref(),
                it.name
            ),
        ));
    }
    Ok(())
}

/// Which results of a run's history the plan's steps are.
#[derive(Clone, Debug, PartialEq)]
pub struct HistoryView {
    /// Per plan step, its result (of the last cycle for the cycle's steps); `None` if the
    /// history stopped before it.
    pub index: Vec<Option<usize>>,
    /// The results of the last complete cycle (empty without a cycle or before one ended).
    pub cycle: std::ops::Range<usize>,
}

impl HistoryView {
    /// The view of `n` results of a history of `steps` plan steps with cycle `cycle`.
    pub fn new(steps: usize, cycle: Option<&CyclePlan>, n: usize) -> Self {
        let Some(c) = cycle else {
            return HistoryView {
                index: (0..steps).map(|k| (k < n).then_some(k)).collect(),
                cycle: 0..0,
            };
        };
        let done = n.saturating_sub(c.first) / c.len.max(1);
        let start = c.first + done.saturating_sub(1) * c.len;
        let index = (0..steps)
            .map(|k| {
                if k < c.first {
                    (k < n).then_some(k)
                } else if done >= 1 {
                    Some(start + k - c.first)
                } else {
                    (k < n).then_some(k)
                }
            })
            .collect();
        HistoryView {
            index,
            cycle: if done >= 1 {
                start..start + c.len
            } else {
                0..0
            },
        }
    }
}

/// A solved step of a load history, as the cycle sees it: its result and, per interface, the
/// side carrying the points of a re-paired interface (large sliding,
/// `alea_latin::fretting::slip_cycle_repaired`; `None`: the same points in every step).
pub(crate) trait HistoryStep {
    /// The step's result.
    fn result(&self) -> &RunResult;
    /// The step's result, to mark it not converged.
    fn result_mut(&mut self) -> &mut RunResult;
    /// The side carrying the points of interface `i` if it is re-paired.
    fn point_side(&self, i: usize) -> Option<usize>;
}

impl HistoryStep for RunResult {
    fn result(&self) -> &RunResult {
        self
    }
    fn result_mut(&mut self) -> &mut RunResult {
        self
    }
    fn point_side(&self, _: usize) -> Option<usize> {
        None
    }
}

impl HistoryStep for SlidingStep {
    fn result(&self) -> &RunResult {
        &self.result
    }
    fn result_mut(&mut self) -> &mut RunResult {
        &mut self.result
    }
    fn point_side(&self, i: usize) -> Option<usize> {
        self.point_sides.get(i).copied().flatten()
    }
}

/// The slip amplitude of interface `i` over the cycle `steps[from..to]`, per point, keyed by
/// the point's index (the same points in every step) or, on a re-paired interface, by its node
/// on the side carrying the points (module doc of `alea_latin::fretting::slip_cycle_repaired`:
/// the points of two cycles are the same material points when they have the same node).
fn amplitudes<T: HistoryStep>(
    steps: &[T],
    i: usize,
    from: usize,
    to: usize,
) -> Option<BTreeMap<usize, f64>> {
    let its: Vec<&InterfaceResult> = steps[from..to]
        .iter()
        .map(|s| s.result().interfaces.get(i))
        .collect::<Option<_>>()?;
    let sc = match steps.get(from).and_then(|s| s.point_side(i)) {
        Some(side) => {
            // The amplitude does not depend on the origins (only the work does).
            let zeros: Vec<Vec<[f64; 3]>> = its
                .iter()
                .map(|it| vec![[0.0; 3]; it.points.len()])
                .collect();
            let cycle: Vec<CycleStep<'_>> = its
                .iter()
                .zip(&zeros)
                .map(|(it, z)| CycleStep {
                    result: it,
                    origin: z,
                })
                .collect();
            let sc = slip_cycle_repaired(&cycle, side).ok()?;
            return Some(sc.nodes.iter().copied().zip(sc.slip_amplitude).collect());
        }
        None => {
            let origin = from
                .checked_sub(1)
                .and_then(|o| steps[o].result().interfaces.get(i));
            slip_cycle(origin, &its).ok()?
        }
    };
    Some(sc.slip_amplitude.into_iter().enumerate().collect())
}

/// Per frictional interface, the largest change of the slip amplitude between the cycles
/// `steps[a..b]` and `steps[b..c]` (per point: [`amplitudes`]; a point of one cycle only
/// changes by its amplitude), and the largest amplitude of either; the changes below `1e-6`
/// of the largest tangential jump of the cycles count as none (solver round-off: a cycle that
/// sticks everywhere has amplitudes of that size).
pub(crate) fn slip_change<T: HistoryStep>(
    steps: &[T],
    a: usize,
    b: usize,
    c: usize,
) -> Vec<(f64, f64)> {
    let n_ifaces = steps.get(a).map_or(0, |r| r.result().interfaces.len());
    let mut out = Vec::with_capacity(n_ifaces);
    for i in 0..n_ifaces {
        let (Some(old), Some(new)) = (amplitudes(steps, i, a, b), amplitudes(steps, i, b, c))
        else {
            out.push((0.0, 0.0));
            continue;
        };
        let jump = steps[a..c]
            .iter()
            .map(|r| {
                let it = &r.result().interfaces[i];
                (0..it.points.len())
                    .map(|p| {
                        let j = it.step_slip(p, &[]);
                        (j[0] * j[0] + j[1] * j[1] + j[2] * j[2]).sqrt()
                    })
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let scale = new
            .values()
            .chain(old.values())
            .copied()
            .fold(0.0, f64::max);
        let change = old
            .keys()
            .chain(new.keys())
            .map(|k| {
                let v = |m: &BTreeMap<usize, f64>| m.get(k).copied().unwrap_or(0.0);
                (v(&old) - v(&new)).abs()
            })
            .fold(0.0, f64::max);
        out.push((if change <= 1e-6 * jump { 0.0 } else { change }, scale));
    }
    out
}

/// Runs the cycles of `c` after the steps already in `steps`: `run(k, n, done)` solves the
/// cycle's step `k` of cycle `n` (from 0) after the steps `done` (the history so far: its
/// last is the end state the step starts from). Stops at the first step that does not
/// converge, after `repeat` cycles, or at shakedown; a run that does not reach shakedown within
/// `repeat` cycles has its last result marked not converged.
pub(crate) fn run_cycles<T: HistoryStep>(
    c: &CyclePlan,
    steps: &mut Vec<T>,
    mut run: impl FnMut(usize, usize, &[T]) -> Result<T, StudyError>,
) -> Result<(), StudyError> {
    let stopped = |steps: &[T]| {
        steps
            .last()
            .is_some_and(|r| r.result().status != RunStatus::Converged)
    };
    // Per interface, the largest slip amplitude of the cycles so far.
    let mut reference: Vec<f64> = Vec::new();
    for n in 0..c.repeat {
        for k in 0..c.len {
            if stopped(steps) {
                return Ok(());
            }
            let r = run(k, n, steps)?;
            steps.push(r);
        }
        if stopped(steps) {
            return Ok(());
        }
        if let Some(tol) = c.until
            && n >= 1
        {
            let end = steps.len();
            let changes = slip_change(steps, end - 2 * c.len, end - c.len, end);
            reference.resize(changes.len(), 0.0);
            let mut done = true;
            for ((change, scale), r) in changes.iter().zip(reference.iter_mut()) {
                *r = r.max(*scale);
                done &= *change <= tol * *r;
            }
            if done {
                return Ok(());
            }
        }
    }
    if c.until.is_some()
        && let Some(last) = steps.last_mut()
    {
        last.result_mut().status = RunStatus::NotConverged;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_view_points_at_the_last_complete_cycle() {
        let c = CyclePlan {
            first: 2,
            len: 2,
            repeat: 3,
            until: None,
        };
        // press, up, then three cycles (down, back): 8 results.
        let v = HistoryView::new(4, Some(&c), 8);
        assert_eq!(v.index, vec![Some(0), Some(1), Some(6), Some(7)]);
        assert_eq!(v.cycle, 6..8);
        // Stopped in the second cycle's second step: the first cycle is the last complete one.
        let v = HistoryView::new(4, Some(&c), 5);
        assert_eq!(v.index, vec![Some(0), Some(1), Some(2), Some(3)]);
        assert_eq!(v.cycle, 2..4);
        // Stopped before the cycle: no cycle, the steps not run have no result.
        let v = HistoryView::new(4, Some(&c), 1);
        assert_eq!(v.index, vec![Some(0), None, None, None]);
        assert!(v.cycle.is_empty());
        // A cycle that is the whole history: its origin is the unloaded state.
        let whole = CyclePlan { first: 0, ..c };
        let v = HistoryView::new(2, Some(&whole), 6);
        assert_eq!(v.index, vec![Some(4), Some(5)]);
        assert_eq!(v.cycle, 4..6);
        // Without a cycle, the identity.
        let v = HistoryView::new(3, None, 3);
        assert_eq!(v.index, vec![Some(0), Some(1), Some(2)]);
    }
}
