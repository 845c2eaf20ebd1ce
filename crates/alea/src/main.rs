//! The `alea` command line. Thin: parsing arguments, calling `alea-study`, printing.

mod report;
mod solve;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// alea: design quantities of elastic assemblies with uncertain frictional contact.
#[derive(Parser, Debug)]
#[command(version, about, long_about = None)]
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Solve { case, out } => solve::solve_file(&case, &out),
        Command::Demo { name, out } => solve::demo(&name, &out),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            let code = e
                .downcast_ref::<alea_study::StudyError>()
                .map_or(1, |s| s.exit_code());
            ExitCode::from(code as u8)
        }
    }
}
