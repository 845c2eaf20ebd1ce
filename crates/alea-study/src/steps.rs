//! `[[step]]` load histories in a model file: the schema, its checks at load (file, line and
//! field of every bad entry) and the plan the solve follows (the mechanics are in
//! `alea_latin::steps`: each step is a LATIN solve from the end state of the previous one, with
//! the Coulomb law applied incrementally).
//!
//! ```toml
//! [[step]]
//! name = "press"
//! load = { shear = 0.0 }            # factor of each named load in this step
//! [[step]]
//! name = "slide"
//! load = { shear = 1.0 }
//! constraint = [ { substructure = "block", group = "block_top", x = 0.01 } ]
//! ```
//!
//! **Loads.** `load = { NAME = f }` multiplies every load named `NAME` (`[[substructure.load]]`
//! `name`) by `f` on top of its own `factor`. A load keeps its step factor until a later step
//! changes it; before any step names it, its step factor is 1.
//!
//! **Imposed displacements.** `constraint = [{ substructure, group, x / y / z / normal }]`
//! gives new values to components that a `[[substructure]]` constraint on that group already
//! imposes (the constrained degrees of freedom are those of the model for the whole history;
//! only their values change). A value holds until a later step changes it. Each distinct set
//! of imposed values is one factorised solver.

use std::sync::Arc;
use toml::Spanned;

pub use crate::step_spec::{StepConstraintSpec, StepSpec};

use crate::spec::ModelFile;
use crate::{Source, StudyError};

/// One step of the plan.
#[derive(Clone, Debug)]
pub struct StepPlan {
    /// Step name.
    pub name: String,
    /// Step factor of each load case of each substructure (multiplies the load's own factor).
    pub load_scale: Vec<Vec<f64>>,
    /// Index of this step's model file in [`Plan::files`] (its imposed values).
    pub file: usize,
}

/// The steps of a model file and the model files of their distinct imposed values.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The steps, in order.
    pub steps: Vec<StepPlan>,
    /// `files[0]` is the file as written; the others differ only by constraint values.
    pub files: Vec<ModelFile>,
    /// The `[cycle]`: its steps are the last ones of `steps` (module `cycle`).
    pub cycle: Option<crate::cycle::CyclePlan>,
}

type Values = Vec<Vec<[Option<f64>; 4]>>;

fn values_of(file: &ModelFile) -> Values {
    file.substructure
        .iter()
        .map(|s| {
            s.constraint
                .iter()
                .map(|c| [&c.x, &c.y, &c.z, &c.normal].map(|v| v.as_ref().map(|v| *v.get_ref())))
                .collect()
        })
        .collect()
}

fn with_values(file: &ModelFile, values: &Values) -> ModelFile {
    let mut f = file.clone();
    for (s, sub) in f.substructure.iter_mut().enumerate() {
        for (j, c) in sub.constraint.iter_mut().enumerate() {
            for (k, slot) in [&mut c.x, &mut c.y, &mut c.z, &mut c.normal]
                .into_iter()
                .enumerate()
            {
                if let (Some(old), Some(v)) = (slot.as_ref(), values[s][j][k]) {
                    *slot = Some(Spanned::new(old.span(), v));
                }
            }
        }
    }
    f
}

/// The name of step `k` (`step-K` by default), usable in file names and not in `names`.
fn step_name(
    src: &Source,
    st: &StepSpec,
    k: usize,
    names: &[String],
) -> Result<String, StudyError> {
    let Some(n) = &st.name else {
        return Ok(format!("step-{}", k + 1));
    };
    let field = format!("step[{k}].name");
    let v = n.get_ref().trim().to_string();
    if v.is_empty()
        || !v
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Err(src.error(
            n.span(),
            field,
            format!("'{v}' is not a usable step name (letters, digits, '_' and '-')"),
        ));
    }
    if names.contains(&v) {
        return Err(src.error(n.span(), field, format!("duplicate step '{v}'")));
    }
    Ok(v)
}

/// Checks the `[[step]]` entries of `file` and returns their plan (`None` without steps).
pub fn plan_steps(src: &Source, file: &ModelFile) -> Result<Option<Plan>, StudyError> {
    if file.step.is_empty() {
        crate::cycle::plan_cycle(src, file, &[])?;
        return Ok(None);
    }
    let mut names: Vec<String> = Vec::new();
    let mut scale: Vec<Vec<f64>> = file
        .substructure
        .iter()
        .map(|s| vec![1.0; s.load.len()])
        .collect();
    let load_names: Vec<String> = file
        .substructure
        .iter()
        .flat_map(|s| s.load.iter().filter_map(|l| l.name.as_ref()))
        .map(|n| n.get_ref().clone())
        .collect();
    let mut values = values_of(file);
    let mut sets: Vec<Values> = vec![values.clone()];
    let mut steps = Vec::new();
    for (k, st) in file.step.iter().enumerate() {
        let st = st.get_ref();
        let f = |key: &str| format!("step[{k}].{key}");
        let name = step_name(src, st, k, &names)?;
        names.push(name.clone());
        for (lname, v) in &st.load {
            let field = f(&format!("load.{lname}"));
            if !load_names.contains(lname) {
                return Err(src.error(
                    v.span(),
                    field,
                    format!(
                        "no load is named '{lname}' (named loads: {})",
                        if load_names.is_empty() {
                            "none; give a [[substructure.load]] a name".to_string()
                        } else {
                            load_names.join(", ")
                        }
                    ),
                ));
            }
            if !v.get_ref().is_finite() {
                return Err(src.error(v.span(), field, "the factor must be finite"));
            }
            for (s, sub) in file.substructure.iter().enumerate() {
                for (j, l) in sub.load.iter().enumerate() {
                    if l.name.as_ref().is_some_and(|n| n.get_ref() == lname) {
                        scale[s][j] = *v.get_ref();
                    }
                }
            }
        }
        for (j, c) in st.constraint.iter().enumerate() {
            let cf = |key: &str| f(&format!("constraint[{j}].{key}"));
            let sname = c.substructure.get_ref();
            let s = file
                .substructure
                .iter()
                .position(|s| s.name.get_ref() == sname)
                .ok_or_else(|| {
                    src.error(
                        c.substructure.span(),
                        cf("substructure"),
                        format!("no substructure is named '{sname}'"),
                    )
                })?;
            let g = c.group.get_ref();
            let e = file.substructure[s]
                .constraint
                .iter()
                .position(|sc| sc.group.get_ref() == g)
                .ok_or_else(|| {
                    src.error(
                        c.group.span(),
                        cf("group"),
                        format!(
                            "substructure '{sname}' has no constraint on group '{g}': a step \
                             changes the values of existing constraints (the constrained \
                             components are those of the model for the whole history)"
                        ),
                    )
                })?;
            let mut any = false;
            for (comp, (key, v)) in [("x", &c.x), ("y", &c.y), ("z", &c.z), ("normal", &c.normal)]
                .into_iter()
                .enumerate()
            {
                let Some(v) = v else { continue };
                if values[s][e][comp].is_none() {
                    return Err(src.error(
                        v.span(),
                        cf(key),
                        format!(
                            "the constraint of '{sname}' on '{g}' does not impose {key}; add \
                             {key} to it in [[substructure]] (its value before the steps) to \
                             change it in a step"
                        ),
                    ));
                }
                if !v.get_ref().is_finite() {
                    return Err(src.error(v.span(), cf(key), "the value must be finite"));
                }
                values[s][e][comp] = Some(*v.get_ref());
                any = true;
            }
            if !any {
                return Err(src.error(
                    c.group.span(),
                    cf("group"),
                    "the step changes nothing here; give x, y, z and/or normal",
                ));
            }
        }
        let file_index = match sets.iter().position(|v| *v == values) {
            Some(i) => i,
            None => {
                sets.push(values.clone());
                sets.len() - 1
            }
        };
        steps.push(StepPlan {
            name,
            load_scale: scale.clone(),
            file: file_index,
        });
    }
    let files = sets.iter().map(|v| with_values(file, v)).collect();
    let cycle = crate::cycle::plan_cycle(src, file, &names)?;
    Ok(Some(Plan {
        steps,
        files,
        cycle,
    }))
}

/// The load history of a study: [`plan_steps`], plus what a study needs on top: each quantity
/// gets the index of its step (`[[quantity]] step`, default the last) and its description
/// names that step. Steps may change loads and imposed displacements, as in `alea solve`; each
/// distinct set of imposed values is one solver, shared by every run
/// (`Study::step_solvers`).
pub fn study_steps(
    src: &Source,
    file: &ModelFile,
    qois: &mut [crate::qoi::Qoi],
) -> Result<Option<Plan>, StudyError> {
    let plan = plan_steps(src, file)?;
    check_fretting(src, file, qois, plan.as_ref())?;
    let Some(plan) = plan else {
        if let Some((i, s)) = file
            .quantity
            .iter()
            .enumerate()
            .find_map(|(i, q)| q.step.as_ref().map(|s| (i, s)))
        {
            return Err(src.error(
                s.span(),
                format!("quantity[{i}].step"),
                "the file has no [[step]]: leave out step",
            ));
        }
        return Ok(None);
    };
    let names: Vec<&str> = plan.steps.iter().map(|s| s.name.as_str()).collect();
    for (i, (q, spec)) in qois.iter_mut().zip(&file.quantity).enumerate() {
        if matches!(q.kind, crate::qoi::QoiKind::Fretting(_)) {
            q.what = format!("{}, over the last load cycle", q.what);
            continue;
        }
        let k = match &spec.step {
            Some(s) => names.iter().position(|n| n == s.get_ref()).ok_or_else(|| {
                src.error(
                    s.span(),
                    format!("quantity[{i}].step"),
                    format!(
                        "no step is named '{}' (steps: {})",
                        s.get_ref(),
                        names.join(", ")
                    ),
                )
            })?,
            None => names.len() - 1,
        };
        q.step = Some(k);
        let cycle = match &plan.cycle {
            Some(c) if k >= c.first => " of the last cycle",
            _ => "",
        };
        q.what = format!("{}, at the end of step '{}'{cycle}", q.what, names[k]);
    }
    Ok(Some(plan))
}

/// A fretting quantity is measured over the `[cycle]`: the file must have one, and the
/// quantity no `step`.
fn check_fretting(
    src: &Source,
    file: &ModelFile,
    qois: &[crate::qoi::Qoi],
    plan: Option<&Plan>,
) -> Result<(), StudyError> {
    let has_cycle = plan.is_some_and(|p| p.cycle.is_some());
    for (i, (q, spec)) in qois.iter().zip(&file.quantity).enumerate() {
        if !matches!(q.kind, crate::qoi::QoiKind::Fretting(_)) {
            continue;
        }
        if let Some(s) = &spec.step {
            return Err(src.error(
                s.span(),
                format!("quantity[{i}].step"),
                "a fretting quantity is measured over the last load cycle: leave out step",
            ));
        }
        if !has_cycle {
            return Err(src.error(
                spec.kind.span(),
                format!("quantity[{i}].kind"),
                format!(
                    "'{}' is measured over a load cycle: give the file [[step]]s and a [cycle] (docs/study-file.md)",
                    spec.kind.get_ref()
                ),
            ));
        }
    }
    Ok(())
}

/// The run input of every step of `plan` for a run whose input is `input` (its `initial`
/// state is that of the first step only): the loads scaled by the step's factors.
pub fn step_inputs(plan: &Plan, input: &alea_latin::RunInput) -> Vec<alea_latin::RunInput> {
    plan.steps
        .iter()
        .enumerate()
        .map(|(k, step)| {
            let mut i = input.clone();
            if k > 0 {
                i.initial = None;
            }
            for (f, sc) in i.load_factors.iter_mut().zip(&step.load_scale) {
                for (a, b) in f.iter_mut().zip(sc) {
                    *a *= b;
                }
            }
            i
        })
        .collect()
}

/// Runs the load history `plan` of one study run from `input` (the run's parameters; its
/// `initial` state is that of the first step): each step on the solver of its imposed
/// displacements (`solver` for those of the file as written, `others[j - 1]` for
/// `plan.files[j]`: the study's step solvers), with its loads scaled. Returns the results of
/// the steps run: the history stops after a step that does not converge.
pub fn run_study_history(
    plan: &Plan,
    solver: &alea_latin::LatinSolver,
    others: &[std::sync::Arc<alea_latin::LatinSolver>],
    input: &alea_latin::RunInput,
) -> Result<Vec<alea_latin::RunResult>, StudyError> {
    if others.len() + 1 < plan.files.len() {
        return Err(StudyError::Failed(format!(
            "the steps need {} solvers, {} were built",
            plan.files.len(),
            others.len() + 1
        )));
    }
    let steps: Vec<(&alea_latin::LatinSolver, alea_latin::RunInput)> = plan
        .steps
        .iter()
        .zip(step_inputs(plan, input))
        .map(|(step, i)| {
            let s: &alea_latin::LatinSolver = match step.file {
                0 => solver,
                j => &others[j - 1],
            };
            (s, i)
        })
        .collect();
    let Some(cycle) = &plan.cycle else {
        return Ok(alea_latin::steps::run_history(&steps)?);
    };
    // The steps before the cycle once, then the cycle's (module `cycle`).
    let mut results = alea_latin::steps::run_history(&steps[..cycle.first])?;
    if results.len() < cycle.first {
        return Ok(results);
    }
    crate::cycle::run_cycles(cycle, &mut results, |k, n, done| {
        let (s, input) = &steps[cycle.first + k];
        let mut input = input.clone();
        if let Some(prev) = done.last() {
            input.initial = cycle_start(plan, cycle, k, n, done).map(|r| Arc::new(r.end_state()));
            input.previous_step = Some(Arc::new(prev.end_state()));
        }
        Ok(s.run_shared(&input)?)
    })?;
    Ok(results)
}

/// The state the LATIN iterate of the cycle's step `k` in cycle `n` starts from (`None`: the
/// previous step's end, as every step). From the second cycle on, the same step's end in the
/// previous cycle: once the cycle settles, nearly this step's answer. In the first cycle, the
/// latest earlier step of the history with the same loads and imposed values (a cycle back to
/// the first loading's level starts from that loading's end). Only the start of the iteration:
/// the friction law's origin is the previous step's end in every case, and the answer is the
/// same to the solver tolerance; measured in BENCHMARKS "Fretting" (5 - 10x fewer iterations
/// in the steps that repeat). Small sliding only: with large sliding the state of another
/// step lives on another pairing ([`run_large_sliding`]).
fn cycle_start<'a>(
    plan: &Plan,
    cycle: &crate::cycle::CyclePlan,
    k: usize,
    n: usize,
    done: &'a [alea_latin::RunResult],
) -> Option<&'a alea_latin::RunResult> {
    if n >= 1 {
        return done.len().checked_sub(cycle.len).map(|i| &done[i]);
    }
    let step = &plan.steps[cycle.first + k];
    let step_of = |j: usize| {
        if j < cycle.first || cycle.len == 0 {
            j
        } else {
            cycle.first + (j - cycle.first) % cycle.len
        }
    };
    let j = (0..done.len()).rev().find(|&j| {
        plan.steps
            .get(step_of(j))
            .is_some_and(|other| other.file == step.file && other.load_scale == step.load_scale)
    })?;
    // The previous step is the default start.
    (j + 1 < done.len()).then(|| &done[j])
}

/// The status of a history whose last result (`results`' last, solved by `solver`) did not
/// converge: the step (and cycle) it stopped at, or, for a `[cycle]` with `until` whose steps
/// all converged, that it did not shake down within its cycles.
pub(crate) fn history_status(
    plan: &Plan,
    results: &[alea_latin::RunResult],
    solver: &alea_latin::LatinSolver,
    status: String,
) -> String {
    let i = results.len().saturating_sub(1);
    let Some(c) = plan.cycle.as_ref().filter(|c| i >= c.first && c.len > 0) else {
        let name = plan.steps.get(i).map_or("?", |s| s.name.as_str());
        return format!("step {} '{name}': {status}", i + 1);
    };
    let (n, k) = ((i - c.first) / c.len, (i - c.first) % c.len);
    let solved = results
        .last()
        .and_then(|r| r.residuals.last())
        .is_some_and(|&r| r <= solver.options().tolerance);
    if let Some(tol) = c.until
        && solved
        && n + 1 == c.repeat
        && k + 1 == c.len
    {
        return format!(
            "no shakedown: the slip amplitude still changes by more than {tol} after {} cycles",
            c.repeat
        );
    }
    let name = plan.steps.get(c.first + k).map_or("?", |s| s.name.as_str());
    format!("cycle {}, step '{name}': {status}", n + 1)
}

/// Runs one study run with large sliding (`alea_latin::large_sliding`): the steps of `plan`
/// (`None`: one step, `input` itself) on the assembly of their imposed displacements
/// (`assemblies[j]` for `plan.files[j]`), each re-paired in its deformed configuration from
/// the end of the step before it; with a `[cycle]`, its steps repeated as in
/// [`run_study_history`] (module `cycle`), one result per step run. Returns the steps run: the
/// history stops after a step that does not converge.
pub fn run_large_sliding(
    plan: Option<&Plan>,
    assemblies: &[&alea_latin::Assembly],
    options: &alea_latin::LatinOptions,
    repairing: &alea_latin::large_sliding::Repairing,
    input: &alea_latin::RunInput,
) -> Result<Vec<alea_latin::large_sliding::SlidingStep>, StudyError> {
    let steps: Vec<(&alea_latin::Assembly, alea_latin::RunInput)> = match plan {
        None => vec![(assemblies[0], input.clone())],
        Some(plan) => plan
            .steps
            .iter()
            .zip(step_inputs(plan, input))
            .map(|(step, i)| {
                assemblies
                    .get(step.file)
                    .map(|a| (*a, i))
                    .ok_or_else(|| StudyError::Failed("a step's model was not built".into()))
            })
            .collect::<Result<_, _>>()?,
    };
    let Some(cycle) = plan.and_then(|p| p.cycle.as_ref()) else {
        return Ok(alea_latin::large_sliding::run_history(
            &steps, options, repairing,
        )?);
    };
    // The steps before the cycle once, then the cycle's (module `cycle`), each re-paired from
    // the end of the step before it. No warm start from the previous cycle (`cycle_start`):
    // a large-sliding step starts from its predicted configuration on the pairing found there
    // (`alea_latin::large_sliding`), and the previous cycle's state is on other pairings.
    let mut done = alea_latin::large_sliding::run_history(
        &steps[..cycle.first.min(steps.len())],
        options,
        repairing,
    )?;
    if done.len() < cycle.first {
        return Ok(done);
    }
    crate::cycle::run_cycles(cycle, &mut done, |k, _, done| {
        let (assembly, input) = steps
            .get(cycle.first + k)
            .ok_or_else(|| StudyError::Internal("a cycle step out of the plan".into()))?;
        Ok(alea_latin::large_sliding::run_step(
            assembly,
            options,
            repairing,
            done.last(),
            input,
        )?)
    })?;
    Ok(done)
}

/// The value of `q` for a run whose steps gave `results` (one result without steps), each
/// step `k` solved by `solvers[k]` and its slip measured from `origins[k]` (per interface and
/// point, the tangential jump at the step's start: `alea_latin::steps::step_origins`, or
/// `alea_latin::large_sliding::step_origins`): at its step's end state; NaN if the history
/// stopped before that step. The interface work and the friction dissipation of a step after
/// the first are the step's own, on the jump from the step's start; the other quantities are
/// states at the end of the step (`contact_slip` is the total tangential jump: the slip left
/// by the history).
///
/// With a `[cycle]`, `view` says which results are the plan's steps (those of the last cycle
/// for the cycle's steps), and a fretting quantity is evaluated over the last complete cycle
/// (NaN if none completed); on an interface `i` with `point_sides[i] = Some(side)` (re-paired,
/// large sliding: the side carrying its points) by `FrettingQoi::eval_repaired`, with the
/// steps' `origins`.
pub(crate) fn eval_qoi(
    q: &crate::qoi::Qoi,
    solvers: &[&alea_latin::LatinSolver],
    results: &[alea_latin::RunResult],
    origins: &[Vec<Vec<[f64; 3]>>],
    view: Option<&crate::cycle::HistoryView>,
    point_sides: &[Option<usize>],
) -> Result<f64, StudyError> {
    use crate::qoi::QoiKind;
    if let QoiKind::Fretting(f) = &q.kind {
        let Some(range) = view.map(|v| v.cycle.clone()).filter(|r| !r.is_empty()) else {
            return Ok(f64::NAN);
        };
        let Some(solver) = solvers.get(range.end - 1) else {
            return Ok(f64::NAN);
        };
        if let Some(side) = point_sides.get(f.iface).copied().flatten() {
            // A re-paired interface: per step its own pairing and slip origin.
            let cycle: Vec<&alea_latin::RunResult> = results[range.clone()].iter().collect();
            let starts = origins
                .get(range)
                .and_then(|o| {
                    o.iter()
                        .map(|o| o.get(f.iface).map(Vec::as_slice))
                        .collect::<Option<Vec<_>>>()
                })
                .ok_or_else(|| StudyError::Internal("no slip origin for a cycle step".into()))?;
            return f.eval_repaired(solver, &cycle, &starts, side);
        }
        let origin = range.start.checked_sub(1).and_then(|o| results.get(o));
        let cycle: Vec<&alea_latin::RunResult> = results[range].iter().collect();
        return f.eval(solver, origin, &cycle);
    }
    let k = match (view, q.step) {
        (Some(v), Some(step)) => match v.index.get(step).copied().flatten() {
            Some(k) => k,
            None => return Ok(f64::NAN),
        },
        (_, step) => step.unwrap_or(results.len().saturating_sub(1)),
    };
    let (Some(res), Some(solver)) = (results.get(k), solvers.get(k)) else {
        return Ok(f64::NAN);
    };
    let origin = |i: usize| {
        origins
            .get(k)
            .and_then(|o| o.get(i))
            .map(Vec::as_slice)
            .ok_or_else(|| StudyError::Internal(format!("no slip origin for step {}", k + 1)))
    };
    match (&q.kind, k > 0) {
        (QoiKind::FrictionDissipation(i), true) => {
            Ok(res.interfaces[*i].step_friction_dissipation(origin(*i)?))
        }
        (QoiKind::InterfaceWork(i), true) => Ok(res.interfaces[*i].step_work(origin(*i)?)),
        _ => q.eval(solver, res),
    }
}
