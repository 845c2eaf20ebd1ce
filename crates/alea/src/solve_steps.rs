//! `alea solve` of a file with `[[step]]`s: the load history (module `alea_study::steps` for the
//! plan, `alea_latin::steps` for the mechanics), each step reported and written like a single
//! solve, to `<stem>-<K>-<name>.vtm` with its `.vtu` and interface `.csv` files beside it.

use std::path::Path;
use std::time::Instant;

use alea_latin::{LatinSolver, RunInput, RunStatus};
use alea_study::steps::Plan;
use alea_study::{BuiltModel, ParamSpace, Source, build_model, spec::ModelFile};
use anyhow::Result;

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
    let mut solvers: Vec<LatinSolver> = Vec::with_capacity(models.len());
    for m in &models {
        solvers.push(m.solver()?);
    }
    let setup: f64 = solvers.iter().map(|s| s.setup_seconds).sum();
    println!(
        "{} load step(s); LATIN set-up (assembly + factorisations) of {} solver(s) (one per set of imposed displacements): {setup:.3} s",
        plan.steps.len(),
        solvers.len()
    );
    let mut previous: Option<alea_latin::RunResult> = None;
    for (k, step) in plan.steps.iter().enumerate() {
        let (model, solver) = (&models[step.file], &solvers[step.file]);
        let mut input: RunInput = model.parametric.run_input(&params.nominal, vec![]);
        for (f, sc) in input.load_factors.iter_mut().zip(&step.load_scale) {
            for (a, b) in f.iter_mut().zip(sc) {
                *a *= b;
            }
        }
        if let Some(prev) = &previous {
            input.previous_step = Some(std::sync::Arc::new(prev.end_state()));
        }
        println!("step {} '{}':", k + 1, step.name);
        let res = solver.run_shared(&input)?;
        let path = out.join(format!("{stem}-{}-{}.vtm", k + 1, step.name));
        report_run(file, model, solver, &res, &input, &path)?;
        for (i, it) in res.interfaces.iter().enumerate() {
            if it.law != "perfect" {
                let prev = previous.as_ref().map(|p| &p.interfaces[i]);
                println!(
                    "  interface {:>12}: friction dissipation in this step {:e} (the slip increment of the step against the friction force)",
                    it.name,
                    alea_latin::steps::step_friction_dissipation(prev, it)
                );
            }
        }
        if res.status != RunStatus::Converged {
            println!(
                "step {} '{}' did not converge: the later steps are not run ({:.2} s in all)",
                k + 1,
                step.name,
                t0.elapsed().as_secs_f64()
            );
            return Err(not_converged(solver, &res).into());
        }
        previous = Some(res);
    }
    println!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    Ok(())
}
