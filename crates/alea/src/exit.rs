//! Exit codes of `alea`: [`TABLE`], printed by `alea --help` and copied in `docs/study-file.md`
//! (section "Exit codes") and `README.md` (a test checks that the three agree), and the message
//! of an error ([`message`]: its chain of causes, each said once).

use alea_study::StudyError;

/// Every exit code and its meaning: the one table of `--help`, the docs and the README.
pub const TABLE: &[(u8, &str)] = &[
    (
        SUCCESS,
        "success, also when stdout closes before all is printed (piped into `head`): the rest of the printout is dropped and the command goes on; the outputs are written before the results are printed, so they are complete",
    ),
    (
        INTERNAL,
        "internal error (a bug: please report it with the input), including a report plot that cannot be drawn",
    ),
    (
        INPUT,
        "input error: the study or case file (not a regular file, too large, not UTF-8, a bad value), a file it names (every Gmsh error is reported at `mesh.file`, with the mesh file's own line), interface pairing, a size beyond the limits, a study directory holding another study, or the command line (a `--dir` that is a file); the message names `file:line: field`",
    ),
    (
        FILES,
        "file-system or store error: a file or directory that cannot be read or written (missing study file, permissions, disk full), stdout that cannot be written (other than closed: a redirection to a full disk; the files are written), a corrupt `study.db`, a stored run's data of another study",
    ),
    (
        COMPUTATION,
        "computation failed: `alea solve` did not converge (the files hold the last iterate), or a study in which no run converged or no method produced statistics (its outputs are written first)",
    ),
    (
        BUSY,
        "the study directory is in use by another process (the message names it)",
    ),
];

/// The exit-code table as printed by `alea --help`.
pub fn help() -> String {
    let mut s = String::from("Exit codes:\n");
    for (code, meaning) in TABLE {
        s.push_str(&format!("  {code}  {meaning}\n"));
    }
    s
}

/// The exit-code table as a Markdown table (as in `docs/study-file.md` and `README.md`).
#[cfg(test)]
pub fn markdown() -> String {
    let mut s = String::from("| code | meaning |\n|---|---|\n");
    for (code, meaning) in TABLE {
        s.push_str(&format!("| {code} | {meaning} |\n"));
    }
    s
}

/// The message of an error: its causes joined by `: `, a cause whose text is already in the
/// message (an OS error that a layer above quotes) said once.
pub fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if out.contains(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    out
}

/// Success.
pub const SUCCESS: u8 = 0;
/// Internal error.
pub const INTERNAL: u8 = 1;
/// Input error.
pub const INPUT: u8 = 2;
/// File-system error.
pub const FILES: u8 = 3;
/// Computation failed.
pub const COMPUTATION: u8 = 4;
/// Study directory busy.
pub const BUSY: u8 = 5;

/// The exit code of an error: the first cause in its chain that has a known kind decides.
pub fn code(e: &anyhow::Error) -> u8 {
    e.chain().find_map(kind).unwrap_or(INTERNAL)
}

/// The exit code of one error, `None` if its kind is not known here.
fn kind(cause: &(dyn std::error::Error + 'static)) -> Option<u8> {
    use alea_mesh::MeshError;
    use alea_report::ReportError;
    if let Some(o) = cause.downcast_ref::<alea_pipeline::Error>() {
        return Some(match o {
            alea_pipeline::Error::Study(s) => study_code(s),
            alea_pipeline::Error::Report(r) => report_code(r),
            alea_pipeline::Error::Write { .. } => FILES,
            alea_pipeline::Error::NoStore { .. } | alea_pipeline::Error::Store { .. } => INPUT,
            alea_pipeline::Error::NonFinite | alea_pipeline::Error::Json(_) => INTERNAL,
        });
    }
    if let Some(s) = cause.downcast_ref::<StudyError>() {
        return Some(study_code(s));
    }
    if let Some(l) = cause.downcast_ref::<alea_latin::LatinError>() {
        return Some(match l {
            alea_latin::LatinError::Io { .. }
            | alea_latin::LatinError::Mesh {
                source: MeshError::Io { .. },
                ..
            } => FILES,
            _ => COMPUTATION,
        });
    }
    if let Some(r) = cause.downcast_ref::<ReportError>() {
        return Some(report_code(r));
    }
    if let Some(m) = cause.downcast_ref::<MeshError>() {
        return Some(match m {
            MeshError::Io { .. } => FILES,
            _ => INTERNAL,
        });
    }
    if cause.downcast_ref::<std::io::Error>().is_some() {
        return Some(FILES);
    }
    if cause.downcast_ref::<alea_fem::FemError>().is_some() {
        return Some(COMPUTATION);
    }
    None
}

fn study_code(s: &StudyError) -> u8 {
    match s.exit_code() {
        2 => INPUT,
        3 => FILES,
        5 => BUSY,
        _ => COMPUTATION,
    }
}

fn report_code(r: &alea_report::ReportError) -> u8 {
    use alea_report::ReportError;
    match r {
        ReportError::Io { .. } | ReportError::Json { .. } => FILES,
        _ => INTERNAL,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_of_error_has_its_documented_code() {
        let input = StudyError::Input {
            file: "s.toml".into(),
            line: 3,
            field: "mesh.file".into(),
            message: "m".into(),
        };
        assert_eq!(code(&anyhow::Error::from(input)), INPUT);
        assert_eq!(code(&StudyError::Usage("u".into()).into()), INPUT);
        assert_eq!(code(&StudyError::TooLarge("t".into()).into()), INPUT);
        let io = StudyError::Io {
            path: "x".into(),
            source: std::io::Error::other("disk full"),
        };
        assert_eq!(code(&io.into()), FILES);
        assert_eq!(code(&StudyError::Failed("f".into()).into()), COMPUTATION);
        let busy = StudyError::Busy {
            dir: "d".into(),
            holder: "pid 1".into(),
        };
        assert_eq!(code(&busy.into()), BUSY);
        // Context layers do not hide the kind.
        let wrapped = anyhow::Error::from(std::io::Error::other("no space left on device"))
            .context("writing summary.json");
        assert_eq!(code(&wrapped), FILES);
        assert_eq!(code(&anyhow::anyhow!("something unexpected")), INTERNAL);
        // StudyError's own code agrees with the binary's table.
        for e in [
            StudyError::Usage("u".into()),
            StudyError::Failed("f".into()),
            StudyError::Busy {
                dir: "d".into(),
                holder: "h".into(),
            },
        ] {
            let own = e.exit_code() as u8;
            assert_eq!(code(&e.into()), own);
        }
        assert_eq!(SUCCESS, 0);
    }

    #[test]
    fn the_exit_code_table_is_the_same_in_the_help_the_docs_and_the_readme() {
        let table = markdown();
        for (name, text) in [
            (
                "docs/study-file.md",
                include_str!("../../../docs/study-file.md"),
            ),
            ("README.md", include_str!("../../../README.md")),
        ] {
            assert!(text.contains(&table), "{name} has not the table:\n{table}");
        }
        let codes: Vec<u8> = TABLE.iter().map(|(c, _)| *c).collect();
        assert_eq!(codes, [0, 1, 2, 3, 4, 5]);
        assert!(help().starts_with("Exit codes:\n  0  success, also when stdout closes"));
    }

    #[test]
    fn an_os_cause_is_said_once() {
        let io = StudyError::Io {
            path: "study.toml".into(),
            source: std::io::Error::from_raw_os_error(2),
        };
        let text = message(&anyhow::Error::from(io));
        assert_eq!(text.matches("os error 2").count(), 1, "{text}");
        assert!(text.starts_with("study.toml: "), "{text}");
        let wrapped = anyhow::Error::from(std::io::Error::other("disk full")).context("writing x");
        assert_eq!(message(&wrapped), "writing x: disk full");
    }

    #[test]
    fn errors_of_the_study_outputs_keep_their_inner_codes() {
        let busy = alea_pipeline::Error::Study(StudyError::Busy {
            dir: "d".into(),
            holder: "h".into(),
        });
        assert_eq!(code(&busy.into()), BUSY);
        let failed = alea_pipeline::Error::Study(StudyError::Failed("f".into()));
        assert_eq!(code(&failed.into()), COMPUTATION);
        let write = alea_pipeline::Error::Write {
            path: "summary.json".into(),
            source: std::io::Error::other("disk full"),
        };
        let e = anyhow::Error::from(write);
        assert_eq!(format!("{e:#}"), "writing summary.json: disk full");
        assert_eq!(code(&e), FILES);
        let report = alea_pipeline::Error::Report(alea_report::ReportError::Plot {
            plot: "pdf".into(),
            message: "m".into(),
        });
        assert_eq!(code(&report.into()), INTERNAL);
        assert_eq!(code(&alea_pipeline::Error::NonFinite.into()), INTERNAL);
    }
}
