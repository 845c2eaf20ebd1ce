//! `alea solve` of a file with `[[step]]`s, or with a large-sliding interface: the load
//! history solved by the same functions as a study's runs (`alea_study::steps`:
//! `run_study_history`, `run_large_sliding`; the mechanics in `alea_latin::steps` and
//! `alea_latin::large_sliding`), then each step reported and written like a single solve, to
//! `<stem>-<K>-<name>.vtm` with its `.vtu` and interface `.csv` files beside it.

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use alea_latin::large_sliding::{self, Repairing, SlidingStep};
use alea_latin::{LatinSolver, RunInput, RunResult, RunStatus};
use alea_study::steps::{Plan, run_large_sliding, run_study_history, step_inputs};
use alea_study::{BuiltModel, ParamSpace, Source, build_model, spec::ModelFile};
use anyhow::Result;

use crate::out::outln;
use crate::run_report::{not_converged, report_run};

/// Solves the steps of `plan` in order, each from the end of the previous one, then reports
/// and writes each step.
#[allow(clippy::too_many_arguments)]
pub fn solve_history(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
    built: BuiltModel,
    plan: Plan,
    out: &Path,
    stem: &str,
    t0: Instant,
) -> Result<()> {
    // One model and factorised solver per distinct set of imposed values (files[0]: as built).
    let mut models: Vec<BuiltModel> = vec![built];
    for f in &plan.files[1..] {
        models.push(build_model(src, f, params)?);
    }
    let input = models[0].parametric.run_input(&params.nominal);
    let inputs = step_inputs(&plan, &input);
    // Result `k` of the history is step `step_of(k)` of the plan: with a `[cycle]`, the cycle's
    // steps come back once per cycle run (module `alea_study::cycle`).
    let step_of = |k: usize| match &plan.cycle {
        Some(c) if k >= c.first && c.len > 0 => c.first + (k - c.first) % c.len,
        _ => k,
    };
    let label = |k: usize| {
        let j = step_of(k);
        match &plan.cycle {
            Some(c) if k >= c.first && c.len > 0 => format!(
                "step {} '{}' (cycle {})",
                k + 1,
                plan.steps[j].name,
                (k - c.first) / c.len + 1
            ),
            _ => format!("step {} '{}'", k + 1, plan.steps[j].name),
        }
    };
    let name = |k: usize| format!("{stem}-{}-{}.vtm", k + 1, plan.steps[step_of(k)].name);
    if large_sliding::uses_large_sliding(&models[0].assembly) {
        outln!("{} load step(s), large sliding", plan.steps.len());
        let assemblies: Vec<&alea_latin::Assembly> = models.iter().map(|m| &m.assembly).collect();
        let (options, repairing) = (&models[0].options, &models[0].repairing);
        let steps = run_large_sliding(Some(&plan), &assemblies, options, repairing, &input)?;
        for (k, done) in steps.iter().enumerate() {
            outln!("{}:", label(k));
            print_pairings(done, repairing);
            let origins = large_sliding::step_origins(done, k.checked_sub(1).map(|j| &steps[j]));
            let j = step_of(k);
            let model = &models[plan.steps[j].file];
            let step = Step {
                label: label(k),
                solver: &done.solver,
                res: &done.result,
                input: &inputs[j],
                origins,
            };
            report_step(file, &plan, model, &step, &out.join(name(k)), t0)?;
        }
        print_cycles(&plan, steps.len());
    } else {
        let solvers: Vec<Arc<LatinSolver>> = models
            .iter()
            .map(|m| m.solver().map(Arc::new))
            .collect::<Result<_, _>>()?;
        let setup: f64 = solvers.iter().map(|s| s.setup_seconds).sum();
        outln!(
            "{} load step(s); LATIN set-up (assembly + factorisations) of {} solver(s) (one per set of imposed displacements): {setup:.3} s",
            plan.steps.len(),
            solvers.len()
        );
        let results = run_study_history(&plan, &solvers[0], &solvers[1..], &input)?;
        for (k, res) in results.iter().enumerate() {
            outln!("{}:", label(k));
            let origins =
                alea_latin::steps::step_origins(k.checked_sub(1).map(|j| &results[j]), res);
            let j = step_of(k);
            let file_k = plan.steps[j].file;
            let step = Step {
                label: label(k),
                solver: &solvers[file_k],
                res,
                input: &inputs[j],
                origins,
            };
            report_step(file, &plan, &models[file_k], &step, &out.join(name(k)), t0)?;
        }
        print_cycles(&plan, results.len());
    }
    outln!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    Ok(())
}

/// The number of cycles of a history of `n` steps run (all converged), with its shakedown.
fn print_cycles(plan: &Plan, n: usize) {
    if let Some(c) = plan.cycle.as_ref().filter(|c| c.len > 0) {
        let cycles = n.saturating_sub(c.first) / c.len;
        outln!(
            "load cycle: {cycles} cycle(s) of {} step(s) run{}",
            c.len,
            match c.until {
                Some(tol) => format!(
                    "; shaken down: the slip amplitude changed by at most {tol} of the largest in the last cycle"
                ),
                None => String::new(),
            }
        );
    }
}

/// Step `k` of a history, solved: its solver, result and input, and the slip origin of every
/// point of every interface (the tangential jump at the step's start).
struct Step<'a> {
    /// `step K 'name'`, with the cycle when the step belongs to one.
    label: String,
    solver: &'a LatinSolver,
    res: &'a RunResult,
    input: &'a RunInput,
    origins: Vec<Vec<[f64; 3]>>,
}

/// Reports and writes `step` of `plan` (on `model`) to `path`, with its friction dissipation;
/// the error of a step that did not converge (the history stopped there).
fn report_step(
    file: &ModelFile,
    plan: &Plan,
    model: &BuiltModel,
    step: &Step<'_>,
    path: &Path,
    t0: Instant,
) -> Result<()> {
    let (solver, res) = (step.solver, step.res);
    report_run(
        file,
        model,
        solver,
        res,
        step.input,
        path,
        Some(&step.origins),
    )?;
    print_dissipation(res, &step.origins);
    if res.status == RunStatus::Converged {
        return Ok(());
    }
    // A `[cycle]` with `until` whose last step converged but whose slip amplitude still
    // changed: the history is marked not converged (module `alea_study::cycle`).
    let solved = res
        .residuals
        .last()
        .is_some_and(|&r| r <= solver.options().tolerance);
    if let Some(c) = plan.cycle.as_ref().filter(|c| solved && c.until.is_some()) {
        outln!(
            "{}: the load cycle did not shake down within {} cycles ([cycle] until = {}; {:.2} s in all)",
            step.label,
            c.repeat,
            c.until.unwrap_or(0.0),
            t0.elapsed().as_secs_f64()
        );
        return Err(alea_study::StudyError::Failed(format!(
            "no shakedown: the slip amplitude still changes by more than {} after {} cycles",
            c.until.unwrap_or(0.0),
            c.repeat
        ))
        .into());
    }
    outln!(
        "{} did not converge: the later steps are not run ({:.2} s in all)",
        step.label,
        t0.elapsed().as_secs_f64()
    );
    Err(not_converged(solver, res).into())
}

/// Prints the friction dissipation of each contact interface within the step of `res`, whose
/// slip starts from `origins` (per interface and point, `alea_latin::steps::step_origins`).
fn print_dissipation(res: &RunResult, origins: &[Vec<[f64; 3]>]) {
    for (it, origin) in res.interfaces.iter().zip(origins) {
        if it.law != "perfect" {
            outln!(
                "  interface {:>12}: friction dissipation in this step {:e} (the slip increment of the step against the friction force)",
                it.name,
                it.step_friction_dissipation(origin)
            );
        }
    }
}

/// One solve of `model` with large sliding and no `[[step]]` (a history of one step, as a
/// study's run), with its pairings printed.
pub(crate) fn large_sliding_solve(model: &BuiltModel, input: &RunInput) -> Result<SlidingStep> {
    let (options, repairing) = (&model.options, &model.repairing);
    let mut steps = run_large_sliding(None, &[&model.assembly], options, repairing, input)?;
    let step = steps.pop().ok_or_else(|| {
        anyhow::anyhow!("internal error: the large-sliding solve returned no step")
    })?;
    print_pairings(&step, repairing);
    Ok(step)
}

/// The pairings of a large-sliding step, its iterations and whether its pairing settled.
fn print_pairings(step: &SlidingStep, settings: &Repairing) {
    outln!(
        "large sliding: {} pairing(s) in the deformed configuration, {} LATIN iterations in all, set-up {:.3} s; slide since the last pairing {:.2e} x the mesh size (tolerance {:.0e}){}",
        step.pairings,
        step.iterations,
        step.setup_seconds,
        step.mismatch,
        settings.tolerance,
        if step.pairing_settled {
            String::new()
        } else {
            format!(
                ": the pairing did not settle within {} pairing(s) ([solver] max_pairings), the step is not converged",
                settings.max_pairings
            )
        }
    );
}
