//! Exit codes of `alea` (the table in `docs/study-file.md`, section "Exit codes"):
//!
//! | code | meaning |
//! |---|---|
//! | 0 | success |
//! | 1 | internal error (a bug: please report it with the input) |
//! | 2 | input error: the study or case file, a file it names (Gmsh mesh), a size beyond the limits, or the command line; the message names file:line:field |
//! | 3 | file-system error: a file or directory cannot be read or written (missing study file, permissions, disk full) |
//! | 4 | computation failed: a solve that did not converge, a study where no run converged or no method produced statistics, a numerical failure |
//! | 5 | the study directory is in use by another process (the message names it) |

use alea_study::StudyError;

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
    use alea_report::report::ReportError;
    if let Some(o) = cause.downcast_ref::<alea_report::Error>() {
        return Some(match o {
            alea_report::Error::Study(s) => study_code(s),
            alea_report::Error::Report(r) => report_code(r),
            alea_report::Error::Write { .. } => FILES,
            alea_report::Error::NoStore { .. } | alea_report::Error::Store { .. } => INPUT,
            alea_report::Error::NonFinite | alea_report::Error::Json(_) => INTERNAL,
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

fn report_code(r: &alea_report::report::ReportError) -> u8 {
    use alea_report::report::ReportError;
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
    fn errors_of_the_study_outputs_keep_their_inner_codes() {
        let busy = alea_report::Error::Study(StudyError::Busy {
            dir: "d".into(),
            holder: "h".into(),
        });
        assert_eq!(code(&busy.into()), BUSY);
        let failed = alea_report::Error::Study(StudyError::Failed("f".into()));
        assert_eq!(code(&failed.into()), COMPUTATION);
        let write = alea_report::Error::Write {
            path: "summary.json".into(),
            source: std::io::Error::other("disk full"),
        };
        let e = anyhow::Error::from(write);
        assert_eq!(format!("{e:#}"), "writing summary.json: disk full");
        assert_eq!(code(&e), FILES);
        let report = alea_report::Error::Report(alea_report::report::ReportError::Plot {
            plot: "pdf".into(),
            message: "m".into(),
        });
        assert_eq!(code(&report.into()), INTERNAL);
        assert_eq!(code(&alea_report::Error::NonFinite.into()), INTERNAL);
    }
}
