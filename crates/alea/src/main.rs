//! The `alea` command line. Thin: parsing arguments, calling `alea-pipeline` (studies, their
//! outputs and reports) and `alea-study`, printing.

mod exit;
mod out;
mod run_report;
mod serve;
mod solve;
mod solve_steps;
mod study_cmd;
mod umbridge;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use out::errln;

/// alea: design quantities of elastic assemblies with uncertain frictional contact.
#[derive(Parser, Debug)]
#[command(
    version,
    about,
    long_about = None,
    after_help = exit::help()
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Solve one deterministic case file (a single body by direct FE, an assembly by LATIN)
    /// and write ParaView output.
    Solve {
        /// The case file (TOML).
        case: PathBuf,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Run a stochastic study: the runs (resumable), surrogates, Monte Carlo statistics,
    /// summary.json, samples.csv and an HTML report, in a study directory.
    Run {
        /// The study file (TOML).
        study: PathBuf,
        /// Study directory (default: out/<study file name>).
        #[arg(long)]
        dir: Option<PathBuf>,
        /// Discard the runs of a previous version of the study file.
        #[arg(long)]
        restart: bool,
        /// Worker threads (default: all cores; results do not depend on it).
        #[arg(long)]
        threads: Option<usize>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Rebuild every output of a study directory (statistics, summary.json, samples.csv, mean /
    /// std fields, the HTML report) from its store, computing no run.
    Report {
        /// The study directory.
        dir: PathBuf,
        /// No progress spinner.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Serve a study's model over the UM-Bridge protocol (HTTP + JSON; the `umbridge` clients
    /// of Python, C++, MATLAB, R, Julia): inputs the study's parameters, outputs its
    /// quantities, each evaluation a run of the study stored in its directory.
    Serve {
        /// The study file (TOML).
        study: PathBuf,
        /// Study directory (default: out/<study file name>); a repeated point is answered
        /// from its store.
        #[arg(long)]
        dir: Option<PathBuf>,
        /// Discard the runs of a previous version of the study file.
        #[arg(long)]
        restart: bool,
        /// Address to listen on (default: this machine only).
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
        /// Port (0: any free port; the address is printed).
        #[arg(long, default_value_t = 4242)]
        port: u16,
        /// Worker threads of the solver (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Run a built-in demonstration case and write ParaView output.
    Demo {
        /// Which demo: `dovetail` (blade root in its disk, frictional contact) or `kirsch`
        /// (plate with a hole).
        #[arg(default_value = "dovetail")]
        name: String,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
}

/// `alea run` in one process.
fn run_single(
    study: &std::path::Path,
    dir: &std::path::Path,
    restart: bool,
    quiet: bool,
    threads: Option<usize>,
) -> anyhow::Result<()> {
    set_threads(threads)?;
    study_cmd::run(study, dir, restart, quiet)
}

/// The global rayon pool's size (`None`: all cores).
fn set_threads(threads: Option<usize>) -> anyhow::Result<()> {
    if let Some(n) = threads {
        let n = alea_study::limits::check_threads(n)?;
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
            .map_err(|e| anyhow::anyhow!("cannot start {n} worker threads: {e}"))?;
    }
    Ok(())
}

/// `alea run` under an MPI launcher (feature `mpi`): rank 0 runs the study with the MPI
/// executor, the other ranks solve the runs it sends. `None` when not started by a launcher or
/// with one rank (then the study runs in one process).
#[cfg(feature = "mpi")]
fn run_distributed(
    study: &std::path::Path,
    dir: &std::path::Path,
    restart: bool,
    quiet: bool,
    threads: Option<usize>,
) -> Option<anyhow::Result<()>> {
    use alea_study::distributed::{Role, start};
    use out::outln;
    let per_run = alea_study::distributed::ranks_per_run(study);
    match start(threads, per_run) {
        Err(e) => Some(Err(e.into())),
        Ok(Role::Single) => None,
        Ok(Role::Worker(w)) => {
            let rank = w.rank();
            Some(
                w.serve(study, dir)
                    .map_err(|e| anyhow::anyhow!("rank {rank}: {e}")),
            )
        }
        Ok(Role::Leader(leader)) => {
            alea_study::runner::install_executor(leader.executor());
            let result = study_cmd::run(study, dir, restart, quiet);
            if let (true, Err(e)) = (per_run > 1, &result) {
                // The other ranks of rank 0's group may wait for it in an exchange that will
                // not come: the job ends here (mpirun stops the other ranks).
                errln!("error: {}", exit::message(e));
                let _ = out::finish();
                std::process::exit(i32::from(exit::code(e)));
            }
            match leader.finish() {
                Ok(stats) if stats.batches > 0 => outln!("{}", stats.summary()),
                Ok(_) => {}
                Err(e) => errln!("warning: {e}"),
            }
            Some(result)
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    alea_latin::dense::use_sequential_dense_kernels();
    let result = match cli.command {
        Command::Solve { case, out } => solve::solve_file(&case, &out),
        Command::Demo { name, out } => solve::demo(&name, &out),
        Command::Report { dir, quiet } => study_cmd::rebuild_report(&dir, quiet),
        Command::Serve {
            study,
            dir,
            restart,
            host,
            port,
            threads,
        } => set_threads(threads).and_then(|()| {
            let dir = dir.unwrap_or_else(|| alea_pipeline::default_dir(&study));
            serve::serve(&serve::ServeOptions {
                study: &study,
                dir: &dir,
                restart,
                host: &host,
                port,
            })
        }),
        Command::Run {
            study,
            dir,
            restart,
            threads,
            quiet,
        } => {
            let dir = dir.unwrap_or_else(|| alea_pipeline::default_dir(&study));
            #[cfg(feature = "mpi")]
            {
                match run_distributed(&study, &dir, restart, quiet, threads) {
                    Some(r) => r,
                    None => run_single(&study, &dir, restart, quiet, threads),
                }
            }
            #[cfg(not(feature = "mpi"))]
            run_single(&study, &dir, restart, quiet, threads)
        }
    };
    // A closed stdout is no error; another error writing it fails a command that succeeded.
    let printed = out::finish();
    let result = result
        .and_then(|()| printed.map_err(|e| anyhow::Error::from(e).context("writing to stdout")));
    match result {
        Ok(()) => ExitCode::from(exit::SUCCESS),
        Err(e) => {
            errln!("error: {}", exit::message(&e));
            ExitCode::from(exit::code(&e))
        }
    }
}
