//! An input file kept in memory, to turn byte spans into line numbers in error messages.

use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::StudyError;

/// A parsed input file's path and text.
#[derive(Clone, Debug)]
pub struct Source {
    /// The file.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
}

impl Source {
    /// Reads a study or case file: a regular file of at most
    /// [`alea_mesh::input::max_input_bytes`] bytes, in UTF-8.
    ///
    /// # Errors
    /// [`StudyError::Io`] if it cannot be read (missing, permissions); [`StudyError::Input`]
    /// (line 0) if it is not a regular file (`/dev/zero`, a directory, a pipe) or is too large,
    /// and at the line and column of the first invalid byte if it is not UTF-8.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, StudyError> {
        let path = path.as_ref().to_path_buf();
        let bytes = alea_mesh::input::read_input(&path).map_err(|source| {
            if alea_mesh::input::is_refusal(&source) {
                StudyError::Input {
                    file: path.clone(),
                    line: 0,
                    field: "(file)".into(),
                    message: source.to_string(),
                }
            } else {
                StudyError::Io {
                    path: path.clone(),
                    source,
                }
            }
        })?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
            let line = good.iter().filter(|&&b| b == b'\n').count() + 1;
            let column =
                good.len() - good.iter().rposition(|&b| b == b'\n').map_or(0, |p| p + 1) + 1;
            StudyError::Input {
                file: path.clone(),
                line,
                field: "(text)".into(),
                message: format!(
                    "byte {} (column {column}) is not UTF-8: save the file as UTF-8 text",
                    good.len() + 1
                ),
            }
        })?;
        Ok(Source { path, text })
    }

    /// Wraps text that did not come from a file (built-in examples, tests).
    pub fn from_text(name: &str, text: &str) -> Self {
        Source {
            path: PathBuf::from(name),
            text: text.to_string(),
        }
    }

    /// 1-based line of a byte offset.
    pub fn line_of(&self, offset: usize) -> usize {
        self.text[..offset.min(self.text.len())]
            .bytes()
            .filter(|&b| b == b'\n')
            .count()
            + 1
    }

    /// An input error at `span` about `field`.
    pub fn error(
        &self,
        span: Range<usize>,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> StudyError {
        StudyError::Input {
            file: self.path.clone(),
            line: self.line_of(span.start),
            field: crate::expr::abbreviate(&field.into()),
            message: abbreviate_quotes(&message.into()),
        }
    }

    /// Deserialises the whole file, turning TOML/serde errors into [`StudyError::Input`] with
    /// the line and the offending key.
    pub fn parse<T: serde::de::DeserializeOwned>(&self) -> Result<T, StudyError> {
        toml::from_str(&self.text).map_err(|e| {
            let line = e.span().map(|s| self.line_of(s.start)).unwrap_or(0);
            let key = e
                .span()
                .map(|s| {
                    let line_start = self.text[..s.start].rfind('\n').map_or(0, |p| p + 1);
                    let line_end = self.text[s.start..]
                        .find('\n')
                        .map_or(self.text.len(), |p| s.start + p);
                    self.text[line_start..line_end]
                        .split('=')
                        .next()
                        .unwrap_or("")
                        .trim()
                        .to_string()
                })
                .unwrap_or_default();
            StudyError::Input {
                file: self.path.clone(),
                line,
                field: if key.is_empty() {
                    "(document)".into()
                } else {
                    crate::expr::abbreviate(&key)
                },
                message: abbreviate_quotes(e.message()),
            }
        })
    }
}

/// `message` with every text between single quotes longer than
/// [`crate::expr::MAX_QUOTED`] characters abbreviated (a quoted value of the file, an
/// expression, a name), so that an error line stays readable whatever the input.
pub fn abbreviate_quotes(message: &str) -> String {
    let parts: Vec<&str> = message.split('\'').collect();
    if parts.len() < 3 {
        return crate::expr::abbreviate_long(message);
    }
    parts
        .iter()
        .enumerate()
        .map(|(k, p)| {
            // (Room for the length said by an abbreviation made before.)
            if k % 2 == 1
                && k + 1 < parts.len()
                && p.chars().nth(crate::expr::MAX_QUOTED + 40).is_some()
            {
                crate::expr::abbreviate(p)
            } else {
                p.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("'")
}
