//! Where the account of a study goes: lines for the user and warnings.

/// Receives what a study reports while it runs: the `alea` CLI prints lines to stdout and
/// warnings to stderr (`warning: ...`); Python keeps quiet and gets the warnings back as notes.
pub trait Console {
    /// One line of the account (may start with `\n` or be empty).
    fn line(&self, text: &str);
    /// A warning (also kept in the notes of `summary.json` and the report).
    fn warning(&self, text: &str);
}

/// A console that shows nothing.
pub struct Silent;

impl Console for Silent {
    fn line(&self, _text: &str) {}
    fn warning(&self, _text: &str) {}
}
