//! The checks of a study at load that span several of its tables: before its model is built
//! (methods, quantities, the error estimate's settings) and once it is (the error estimate
//! with `[[step]]`s or large sliding).

use super::{Study, estimates_error};
use crate::StudyError;
use crate::limits::check_study_file;
use crate::params::ParamSpace;
use crate::source::Source;
use crate::spec::ModelFile;

/// The checks of a study file's tables before its model is built: methods only with random
/// parameters, at least one quantity and (with parameters) one method, the file's own checks,
/// settings that would be ignored, and the error estimate's settings when it runs.
pub(super) fn check_study_tables(
    source: &Source,
    file: &ModelFile,
    params: &ParamSpace,
) -> Result<(), StudyError> {
    if params.names.is_empty()
        && let Some(m) = file.method.first()
    {
        return Err(source.error(m.kind.span(), "method[0].type", "methods need random parameters: without [[parameter]], leave out [[method]] (the study is then one deterministic run)"));
    }
    if file.quantity.is_empty() {
        return Err(source.error(0..0, "quantity", "a study needs at least one [[quantity]]"));
    }
    if file.method.is_empty() && !params.names.is_empty() {
        return Err(source.error(0..0, "method", "a study needs at least one [[method]]"));
    }
    check_study_file(source, file, params.names.len())?;
    crate::settings_check::check(source, file)?;
    // The error estimate's settings, when it runs: an [error] table not disabled, or an
    // adaptive method (a study without either may have more parameters than its rules take).
    let estimates = file
        .error
        .as_ref()
        .is_some_and(|e| e.enabled.unwrap_or(true))
        || file.method.iter().any(|m| m.kind.get_ref() == "adaptive");
    if !params.names.is_empty() && estimates {
        crate::error_settings::read(source, file.error.as_ref(), params.names.len())?;
    }
    Ok(())
}

/// The error estimate (an `[error]` table or an adaptive method) is refused with `[[step]]`s
/// and with large sliding (each run's own interface points).
pub(super) fn check_error_estimate_fits(study: &Study) -> Result<(), StudyError> {
    if study.steps.is_some() && estimates_error(study) {
        return Err(study.source.error(
            study.file.step[0].span(),
            "step",
            "the error estimate (an [error] table or an adaptive method) is for single-step runs: leave out [error] and adaptive methods, or the [[step]]s",
        ));
    }
    if estimates_error(study)
        && let Some(i) = study
            .model
            .assembly
            .interfaces
            .iter()
            .position(alea_latin::large_sliding::is_repaired)
        && let Some(site) = study.model.interface_sites.get(i)
    {
        return Err(StudyError::Input {
            file: site.file.clone(),
            line: site.sliding,
            field: format!("interface[{i}].sliding"),
            message: "large sliding (the pairing re-found in the deformed configuration of \
                      each run) gives every run its own interface points, while the error \
                      estimate ([error], adaptive methods) needs the same interface layout \
                      in every run: leave out [error] and adaptive methods, or use \
                      sliding = \"small\""
                .into(),
        });
    }
    Ok(())
}
