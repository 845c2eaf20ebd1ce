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
    /// Reads a file.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, StudyError> {
        let path = path.as_ref().to_path_buf();
        let text = std::fs::read_to_string(&path).map_err(|source| StudyError::Io {
            path: path.clone(),
            source,
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
            field: field.into(),
            message: message.into(),
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
                    key
                },
                message: e.message().to_string(),
            }
        })
    }
}
