//! `alea run` and `alea report`: the study pipeline of `alea-pipeline` with a progress bar
//! and the account printed to stdout, warnings to stderr.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use alea_pipeline::Console;
use alea_study::runner::Progress;
use alea_study::store::RunRecord;
use anyhow::Result;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::out::{errln, outln};

/// The account of a study on the terminal: lines to stdout, warnings to stderr.
struct Terminal;

impl Console for Terminal {
    fn line(&self, text: &str) {
        outln!("{text}");
    }
    fn warning(&self, text: &str) {
        errln!("warning: {text}");
    }
}

/// Progress bar: runs done, ETA, mean LATIN iterations, failures. Shown from the start of the
/// runs on (`begin`), unless quiet.
struct Bar {
    bar: ProgressBar,
    quiet: bool,
    iterations: AtomicUsize,
    runs: AtomicUsize,
    failures: AtomicUsize,
}

impl Bar {
    fn new(quiet: bool) -> Self {
        let bar = ProgressBar::hidden();
        bar.set_style(
            ProgressStyle::with_template(
                "{spinner} runs {pos}/{len} [{bar:30}] {elapsed_precise} ETA {eta} {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        Self {
            bar,
            quiet,
            iterations: AtomicUsize::new(0),
            runs: AtomicUsize::new(0),
            failures: AtomicUsize::new(0),
        }
    }
}

impl Progress for Bar {
    fn begin(&self, total: usize, done: usize) {
        if !self.quiet {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        self.bar.set_length(total as u64);
        self.bar.set_position(done as u64);
        if done > 0 {
            self.bar.println(format!(
                "resuming: {done} of {total} runs already in the study directory"
            ));
        }
    }
    fn finished(&self, rec: &RunRecord) {
        let n = self.runs.fetch_add(1, Ordering::Relaxed) + 1;
        let it = self.iterations.fetch_add(rec.iterations, Ordering::Relaxed) + rec.iterations;
        let f = self.failures.load(Ordering::Relaxed) + usize::from(!rec.converged());
        if !rec.converged() {
            self.failures.fetch_add(1, Ordering::Relaxed);
        }
        self.bar.set_message(format!(
            "mean LATIN iterations {:.0}, not converged {f}",
            it as f64 / n as f64
        ));
        self.bar.inc(1);
    }
    fn end(&self) {
        self.bar.finish();
    }
    fn note(&self, message: &str) {
        // A hidden bar (--quiet, no terminal) prints nothing: notes go to stderr then.
        if self.bar.is_hidden() {
            errln!("note: {message}");
        } else {
            self.bar.println(format!("note: {message}"));
        }
    }
}

/// The account of `alea report` under a spinner on stderr (the analysis takes seconds on a
/// large study and prints nothing meanwhile): each line printed with the spinner cleared.
struct Spinning {
    spinner: ProgressBar,
}

impl Console for Spinning {
    fn line(&self, text: &str) {
        self.spinner.suspend(|| outln!("{text}"));
    }
    fn warning(&self, text: &str) {
        self.spinner.suspend(|| errln!("warning: {text}"));
    }
}

/// `alea report`: rebuilds every output of a study directory from its store alone, under a
/// spinner unless quiet (or stderr is not a terminal).
pub fn rebuild_report(dir: &Path, quiet: bool) -> Result<()> {
    let spinner = if quiet {
        ProgressBar::hidden()
    } else {
        ProgressBar::new_spinner()
    };
    spinner.set_message("analysing the study's runs (surrogates, draws, error budgets)");
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let console = Spinning { spinner };
    let result = alea_pipeline::rebuild(dir, "alea report", &console);
    console.spinner.finish_and_clear();
    result?;
    Ok(())
}

/// `alea run`: runs the study in `path` into `dir` and writes its outputs.
pub fn run(path: &Path, dir: &Path, restart: bool, quiet: bool) -> Result<()> {
    alea_pipeline::run(path, dir, restart, &Bar::new(quiet), &Terminal)?;
    Ok(())
}
