//! The `[output]` settings that need checking, resolved at load: how many draws `samples.csv`
//! holds (`samples_rows`: a number of draws, or `"all"`; default
//! [`DEFAULT_SAMPLES_ROWS`]). A bad value is refused with the file, line and field.

use crate::StudyError;
use crate::source::Source;
use crate::spec::{OutputSpec, SamplesRows};

/// Draws written to `samples.csv` unless `[output] samples_rows` says otherwise: enough to
/// plot or re-bin the quantities' laws outside alea (about 0.1 MB per column), not the
/// hundreds of thousands of draws behind the statistics (every one of them is in memory for
/// Python's `res.samples`, and `"all"` writes them).
pub const DEFAULT_SAMPLES_ROWS: usize = 10_000;

/// The rows of `samples.csv`: the first this many draws of the main method, `None` for every
/// draw.
///
/// # Errors
/// [`StudyError::Input`] at `output.samples_rows` for a count below 1, a word other than
/// `"all"`, or the key given with `samples_csv = false` (it would be ignored).
pub fn samples_rows(source: &Source, output: &OutputSpec) -> Result<Option<usize>, StudyError> {
    let Some(v) = &output.samples_rows else {
        return Ok(Some(DEFAULT_SAMPLES_ROWS));
    };
    let refuse = |why: String| source.error(v.span(), "output.samples_rows", why);
    if output.samples_csv == Some(false) {
        return Err(refuse(
            "is ignored with samples_csv = false (no samples.csv is written): remove one of them"
                .into(),
        ));
    }
    match v.get_ref() {
        SamplesRows::Count(n) if *n >= 1 => Ok(Some(usize::try_from(*n).unwrap_or(usize::MAX))),
        SamplesRows::Count(n) => Err(refuse(format!(
            "must be at least 1 (a number of draws) or \"all\", got {n}"
        ))),
        SamplesRows::Word(w) if w == "all" => Ok(None),
        SamplesRows::Word(w) => Err(refuse(format!(
            "unknown value '{w}'; expected a number of draws (default {DEFAULT_SAMPLES_ROWS}) or \"all\""
        ))),
    }
}
