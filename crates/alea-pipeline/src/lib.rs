//! # alea-pipeline: a study from its file to its outputs, shared by the `alea` command line and
//! the Python package
//!
//! One owner for a study's stages, in the order they run (each a function a front end calls):
//!
//! 1. **load and check** - [`alea_study::runner::Study::load`]: every setting validated, every
//!    size checked, before the first run;
//! 2. **run** - [`run_runs`]: every solve a study needs (design runs, adaptive steps,
//!    validation runs, the error budget's paired solves), by `alea_study`'s runner and executor
//!    (threads, or MPI ranks), each stored in the study directory as it finishes and resumed
//!    after a kill;
//! 3. **analyse** - [`analyse`] / [`analyse_all`] (`results.rs`): surrogates, Monte Carlo
//!    statistics with their error budgets, reliability, Sobol' indices; from the stored runs
//!    alone, no solve;
//! 4. **estimate** - `estimate.rs`: the stochastic error estimate of each method (thesis
//!    chapter 4), from the stored per-run estimates;
//! 5. **write** - [`write_outputs`] (`outputs.rs`): the typed [`StudyResult`] (`result.rs`;
//!    each quantity's statistics with their total intervals in `summary_intervals.rs`), and
//!    from it `summary.json` and `samples.csv` (`files.rs`), the report's input (`input.rs`,
//!    `estimate_report.rs`) drawn by `alea_report`, and the console's tables (`table.rs`,
//!    `estimate_text.rs`).
//!
//! [`run`] (`alea run`, Python's `alea.run` with outputs) is stages 1 - 5; [`rebuild`]
//! (`alea report DIR`, Python's `alea.report`) reopens a study directory and runs stages 3 - 5,
//! computing no run; [`stored_runs`] (Python's `alea.open_store`) reads the runs. `alea serve`
//! uses `alea_study::model_session` (stages 1 - 2 for points a client sends).
//!
//! What a study prints goes through a [`Console`] (the CLI prints to stdout / stderr, Python
//! stays silent); errors are typed ([`Error`]), the front ends map them to exit codes or
//! exceptions.

mod console;
mod error;
mod estimate;
mod estimate_report;
mod estimate_text;
mod files;
mod input;
mod outputs;
mod result;
mod results;
mod summary_intervals;
mod table;

use std::path::{Path, PathBuf};
use std::time::Instant;

use alea_study::analysis::{AnalysisSettings, analysis_settings};
use alea_study::runner::{Progress, Study, StudyRuns, run_study};

pub use outputs::{Outputs, write_outputs};
pub use result::{
    AdaptiveLoop, AdaptiveStep, EntityError, ErrorEstimate, MethodOutcome, Parameter, Run, Slide,
    StepQuantity, StudyResult, SurrogateError, Units,
};
pub use results::{
    Analysis, StoredRuns, analyse, analyse_all, converged_runs, sample_points, stored_runs,
};
pub use summary_intervals::{Budget, BudgetInterval, FailureProbability, QuantityStatistics};

pub use console::{Console, Silent};
pub use error::Error;

/// A study file whose runs are done (computed or resumed), not yet analysed.
pub struct Ran {
    /// The loaded study.
    pub study: Study,
    /// Its analysis settings (Monte Carlo draws, confidence, KDE).
    pub settings: AnalysisSettings,
    /// Its runs, the solver and the adaptive loops' outcomes.
    pub runs: StudyRuns,
}

/// Default study directory: `out/<file stem>`.
pub fn default_dir(study: &Path) -> PathBuf {
    let stem = study
        .file_stem()
        .map_or("study".into(), |s| s.to_string_lossy().into_owned());
    PathBuf::from("out").join(stem)
}

/// Loads the study file `path` and runs (or resumes) its runs in `dir`, reporting each run to
/// `progress` and the study's account (sizes, run counts, timings) to `console`. Writes no
/// output but the store.
pub fn run_runs(
    path: &Path,
    dir: &Path,
    restart: bool,
    progress: &dyn Progress,
    console: &dyn Console,
) -> Result<Ran, Error> {
    let study = Study::load(path)?;
    let settings = analysis_settings(&study)?;
    // The validation runs of the designs known before the runs (an adaptive loop's own are
    // counted once it ends).
    let validation = alea_study::validation_runs::count(&study, &study.methods);
    let design = study.all_points().len();
    // The paired solves of the budget's mesh and sliding parts (`alea_study::paired_runs`).
    let paired = alea_study::paired_runs::count(&study);
    console.line(&format!(
        "study '{}': {} parameter(s), {} quantit{} of interest, {} method(s), {} distinct runs{}{} -> {}",
        study.title(),
        study.params.names.len(),
        study.qois.len(),
        if study.qois.len() == 1 { "y" } else { "ies" },
        study.methods.len(),
        design + validation,
        if validation > 0 {
            format!(" ({validation} of them validation runs)")
        } else {
            String::new()
        },
        if paired > 0 {
            format!(", plus {paired} paired solves for the error budget")
        } else {
            String::new()
        },
        dir.display()
    ));
    let runs = run_study(&study, dir, restart, progress)?;
    let per_run_estimates = if runs.estimate_seconds > 0.0 {
        format!(
            "; per-run error estimates {:.2} s summed over the runs",
            runs.estimate_seconds
        )
    } else {
        String::new()
    };
    console.line(&format!(
        "runs: {} computed, {} resumed; solver set-up {:.2} s, solves {:.2} s ({:.1} runs/s{per_run_estimates})",
        runs.computed,
        runs.resumed,
        runs.setup_seconds,
        runs.solve_seconds,
        runs.computed as f64 / runs.solve_seconds.max(1e-9)
    ));
    if paired > 0 {
        console.line(&format!(
            "paired solves of the error budget: {} computed, {} resumed ({:.2} s)",
            runs.paired.computed, runs.paired.resumed, runs.paired.seconds
        ));
    }
    console.line(&runs.linear_stage_line());
    let iterations: Vec<usize> = runs
        .records
        .iter()
        .filter(|r| r.converged())
        .map(|r| r.iterations)
        .collect();
    if let (Some(lo), Some(hi)) = (iterations.iter().min(), iterations.iter().max()) {
        console.line(&format!(
            "LATIN iterations per converged run: min {lo}, mean {:.1}, max {hi}",
            iterations.iter().sum::<usize>() as f64 / iterations.len() as f64
        ));
    }
    Ok(Ran {
        study,
        settings,
        runs,
    })
}

/// `alea run`: runs the study file `path` into `dir` (resumable; `restart` discards the runs
/// of a previous version of the file), then writes every output ([`write_outputs`]; the report
/// unless the file says `report = false`).
///
/// # Errors
/// Any error of loading or running the study or of writing an output; after writing what it
/// can, [`alea_study::StudyError::Failed`] if no run converged or no method produced
/// statistics.
pub fn run(
    path: &Path,
    dir: &Path,
    restart: bool,
    progress: &dyn Progress,
    console: &dyn Console,
) -> Result<Outputs, Error> {
    let t_all = Instant::now();
    let ran = run_runs(path, dir, restart, progress, console)?;
    let report = ran.study.output.report.unwrap_or(true);
    let out = write_outputs(
        &ran.study,
        &ran.runs,
        dir,
        &ran.settings,
        Vec::new(),
        report,
        console,
    )?;
    console.line(&format!("done in {:.2} s", t_all.elapsed().as_secs_f64()));
    Ok(out)
}

/// `alea report DIR`: rebuilds every output of a study directory (statistics, `summary.json`,
/// `samples.csv`, mean / std fields, the report) from its store alone, computing no run - after
/// a kill during the outputs, or for a study that ran with `report = false`. `command` names
/// the caller in the messages of a busy directory.
///
/// # Errors
/// As [`run`]; [`alea_study::StudyError::Usage`] if `dir` is not a study directory,
/// [`alea_study::StudyError::Busy`] if another process works in it.
pub fn rebuild(dir: &Path, command: &str, console: &dyn Console) -> Result<Outputs, Error> {
    let t_all = Instant::now();
    let re = alea_study::reopen::reopen(dir, command)?;
    let settings = analysis_settings(&re.study)?;
    let mut notes = Vec::new();
    let total = re.runs.records.len() + re.missing;
    console.line(&format!(
        "study '{}' in {}: {} of {total} runs finished",
        re.study.title(),
        dir.display(),
        re.runs.records.len()
    ));
    for n in &re.notes {
        console.warning(n);
        notes.push(n.clone());
    }
    if re.missing > 0 {
        let msg = format!(
            "{} of {total} runs are missing from the study directory (the study was stopped before it finished, \
             or a stored file of the run is damaged): these results use the finished runs only; \
             compute them with `alea run {} --dir {}`",
            re.missing,
            re.study.source.path.display(),
            dir.display()
        );
        console.warning(&msg);
        notes.push(msg);
    }
    // The budget's paired solves are the run's (`alea_study::paired_runs`): without them in
    // the store their part is not estimated, and nothing is solved here.
    let paired = &re.runs.paired;
    for (part, check) in [("mesh", &paired.mesh), ("sliding", &paired.sliding)] {
        if let Some(Err(why)) = check
            && why == alea_study::paired_runs::NOT_SOLVED
        {
            let msg = format!(
                "the error budget's {part} part is not estimated: its paired solves are not in the study directory \
                 (a study run by an older alea, or stopped before they were solved); solve them with `alea run {} --dir {}`",
                re.study.source.path.display(),
                dir.display()
            );
            console.warning(&msg);
            notes.push(msg);
        }
    }
    let out = write_outputs(&re.study, &re.runs, dir, &settings, notes, true, console)?;
    console.line(&format!("done in {:.2} s", t_all.elapsed().as_secs_f64()));
    Ok(out)
}
