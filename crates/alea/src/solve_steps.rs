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
    let name = |k: usize| format!("{stem}-{}-{}.vtm", k + 1, plan.steps[k].name);
    if large_sliding::uses_large_sliding(&models[0].assembly) {
        outln!("{} load step(s), large sliding", plan.steps.len());
        let assemblies: Vec<&alea_latin::Assembly> = models.iter().map(|m| &m.assembly).collect();
        let (options, repairing) = (&models[0].options, &models[0].repairing);
        let steps = run_large_sliding(Some(&plan), &assemblies, options, repairing, &input)?;
        for (k, done) in steps.iter().enumerate() {
            outln!("step {} '{}':", k + 1, plan.steps[k].name);
            print_pairings(done, repairing);
            let origins = large_sliding::step_origins(done, k.checked_sub(1).map(|j| &steps[j]));
            let model = &models[plan.steps[k].file];
            let step = Step {
                k,
                solver: &done.solver,
                res: &done.result,
                input: &inputs[k],
                origins,
            };
            report_step(file, &plan, model, &step, &out.join(name(k)), t0)?;
        }
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
            outln!("step {} '{}':", k + 1, plan.steps[k].name);
            let origins =
                alea_latin::steps::step_origins(k.checked_sub(1).map(|j| &results[j]), res);
            let file_k = plan.steps[k].file;
            let step = Step {
                k,
                solver: &solvers[file_k],
                res,
                input: &inputs[k],
                origins,
            };
            report_step(file, &plan, &models[file_k], &step, &out.join(name(k)), t0)?;
        }
    }
    outln!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    Ok(())
}

/// Step `k` of a history, solved: its solver, result and input, and the slip origin of every
/// point of every interface (the tangential jump at the step's start).
struct Step<'a> {
    k: usize,
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
    let (k, solver, res) = (step.k, step.solver, step.res);
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
    outln!(
        "step {} '{}' did not converge: the later steps are not run ({:.2} s in all)",
        k + 1,
        plan.steps[k].name,
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
