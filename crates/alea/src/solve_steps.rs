//! `alea solve` of a file with `[[step]]`s: the load history (module `alea_study::steps` for the
//! plan, `alea_latin::steps` for the mechanics), each step reported and written like a single
//! solve, to `<stem>-<K>-<name>.vtm` with its `.vtu` and interface `.csv` files beside it.

use std::path::Path;
use std::time::Instant;

use alea_latin::large_sliding::{self, SlidingStep};
use alea_latin::{LatinSolver, RunInput, RunStatus};
use alea_study::steps::Plan;
use alea_study::{BuiltModel, ParamSpace, Source, build_model, spec::ModelFile};
use anyhow::Result;

use crate::out::outln;
use crate::run_report::{not_converged, report_run};

/// Solves the steps of `plan` in order, each from the end of the previous one.
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
    if alea_latin::large_sliding::uses_large_sliding(&models[0].assembly) {
        return large_sliding_history(file, params, &models, &plan, out, stem, t0);
    }
    let mut solvers: Vec<LatinSolver> = Vec::with_capacity(models.len());
    for m in &models {
        solvers.push(m.solver()?);
    }
    let setup: f64 = solvers.iter().map(|s| s.setup_seconds).sum();
    outln!(
        "{} load step(s); LATIN set-up (assembly + factorisations) of {} solver(s) (one per set of imposed displacements): {setup:.3} s",
        plan.steps.len(),
        solvers.len()
    );
    let mut previous: Option<alea_latin::RunResult> = None;
    for (k, step) in plan.steps.iter().enumerate() {
        let (model, solver) = (&models[step.file], &solvers[step.file]);
        let mut input = step_input(model, params, step);
        if let Some(prev) = &previous {
            input.previous_step = Some(std::sync::Arc::new(prev.end_state()));
        }
        outln!("step {} '{}':", k + 1, step.name);
        let res = solver.run_shared(&input)?;
        let path = out.join(format!("{stem}-{}-{}.vtm", k + 1, step.name));
        let origins = alea_latin::steps::step_origins(previous.as_ref(), &res);
        report_run(file, model, solver, &res, &input, &path, Some(&origins))?;
        print_dissipation(&res, &origins);
        if res.status != RunStatus::Converged {
            outln!(
                "step {} '{}' did not converge: the later steps are not run ({:.2} s in all)",
                k + 1,
                step.name,
                t0.elapsed().as_secs_f64()
            );
            return Err(not_converged(solver, &res).into());
        }
        previous = Some(res);
    }
    outln!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    Ok(())
}

/// The run input of step `step` of a history on `model`: the nominal parameters, the loads
/// scaled by the step's factors.
fn step_input(
    model: &BuiltModel,
    params: &ParamSpace,
    step: &alea_study::steps::StepPlan,
) -> RunInput {
    let mut input: RunInput = model.parametric.run_input(&params.nominal, vec![]);
    for (f, sc) in input.load_factors.iter_mut().zip(&step.load_scale) {
        for (a, b) in f.iter_mut().zip(sc) {
            *a *= b;
        }
    }
    input
}

/// Prints the friction dissipation of each contact interface within the step of `res`, whose
/// slip starts from `origins` (per interface and point, `alea_latin::steps::step_origins`).
fn print_dissipation(res: &alea_latin::RunResult, origins: &[Vec<[f64; 3]>]) {
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

/// One step of `model` with large sliding (module `alea_latin::large_sliding`) from the end of
/// `start`, with its pairings printed.
pub(crate) fn large_sliding_step(
    model: &BuiltModel,
    start: Option<&SlidingStep>,
    input: &RunInput,
) -> Result<SlidingStep> {
    let settings = &model.repairing;
    let step = large_sliding::run_step(&model.assembly, &model.options, settings, start, input)?;
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
    Ok(step)
}

/// [`solve_history`] with large sliding: each step solved by `alea_latin::large_sliding` from
/// the end of the previous one, reported with the solver of its last pairing.
fn large_sliding_history(
    file: &ModelFile,
    params: &ParamSpace,
    models: &[BuiltModel],
    plan: &Plan,
    out: &Path,
    stem: &str,
    t0: Instant,
) -> Result<()> {
    outln!("{} load step(s), large sliding", plan.steps.len());
    let mut previous: Option<SlidingStep> = None;
    for (k, step) in plan.steps.iter().enumerate() {
        let model = &models[step.file];
        let input = step_input(model, params, step);
        outln!("step {} '{}':", k + 1, step.name);
        let done = large_sliding_step(model, previous.as_ref(), &input)?;
        let path = out.join(format!("{stem}-{}-{}.vtm", k + 1, step.name));
        let origins = large_sliding::step_origins(&done, previous.as_ref());
        report_run(
            file,
            model,
            &done.solver,
            &done.result,
            &input,
            &path,
            Some(&origins),
        )?;
        print_dissipation(&done.result, &origins);
        if done.result.status != RunStatus::Converged {
            outln!(
                "step {} '{}' did not converge: the later steps are not run ({:.2} s in all)",
                k + 1,
                step.name,
                t0.elapsed().as_secs_f64()
            );
            return Err(not_converged(&done.solver, &done.result).into());
        }
        previous = Some(done);
    }
    outln!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    Ok(())
}
