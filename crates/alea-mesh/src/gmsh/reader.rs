//! The tokenizer of the `.msh` reader: whitespace-separated ASCII tokens and, in binary files,
//! `size_t` / `int` / `double` items in the file's endianness, with errors naming the line (or
//! byte offset) and the section.

use std::path::PathBuf;

use crate::MeshError;

pub(super) struct Reader<'a> {
    pub(super) path: PathBuf,
    pub(super) data: &'a [u8],
    pub(super) pos: usize,
    pub(super) line: usize,
    pub(super) section: String,
    pub(super) binary: bool,
    pub(super) big_endian: bool,
    pub(super) size_t: usize,
}

impl<'a> Reader<'a> {
    pub(super) fn err(&self, message: String) -> MeshError {
        if self.binary && self.section != "$MeshFormat" && self.section != "$PhysicalNames" {
            MeshError::Parse {
                path: self.path.clone(),
                line: 0,
                section: self.section.clone(),
                message: format!("at byte offset {}: {message}", self.pos),
            }
        } else {
            MeshError::Parse {
                path: self.path.clone(),
                line: self.line,
                section: self.section.clone(),
                message,
            }
        }
    }

    pub(super) fn skip_ws(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            match b {
                b'\n' => self.line += 1,
                b' ' | b'\t' | b'\r' => {}
                _ => break,
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its line.
    pub(super) fn token(&mut self, what: &str) -> Result<(&'a str, usize), MeshError> {
        self.skip_ws();
        let start = self.pos;
        let data: &'a [u8] = self.data;
        while let Some(&b) = data.get(self.pos) {
            if b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err(format!("unexpected end of file, expected {what}")));
        }
        match std::str::from_utf8(&data[start..self.pos]) {
            Ok(s) => Ok((s, self.line)),
            Err(_) => {
                self.pos = start;
                Err(self.err(format!("found non-text bytes, expected {what}")))
            }
        }
    }

    pub(super) fn parse_tok<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, MeshError> {
        let (t, _) = self.token(what)?;
        t.parse::<T>()
            .map_err(|_| self.err(format!("expected {what}, found '{t}'")))
    }

    pub(super) fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], MeshError> {
        let data: &'a [u8] = self.data;
        if self.pos + n > data.len() {
            return Err(self.err(format!(
                "unexpected end of file in binary data, expected {what}"
            )));
        }
        let b = &data[self.pos..self.pos + n];
        self.pos += n;
        Ok(b)
    }

    pub(super) fn uint_bytes(&self, b: &[u8]) -> u64 {
        let mut v = 0u64;
        if self.big_endian {
            for &x in b {
                v = (v << 8) | x as u64;
            }
        } else {
            for &x in b.iter().rev() {
                v = (v << 8) | x as u64;
            }
        }
        v
    }

    /// A `size_t` count or tag.
    pub(super) fn size(&mut self, what: &str) -> Result<u64, MeshError> {
        if self.binary {
            let b = self.bytes(self.size_t, what)?;
            Ok(self.uint_bytes(b))
        } else {
            self.parse_tok(what)
        }
    }

    /// An `int`.
    pub(super) fn int(&mut self, what: &str) -> Result<i32, MeshError> {
        if self.binary {
            let b = self.bytes(4, what)?;
            Ok(self.uint_bytes(b) as u32 as i32)
        } else {
            self.parse_tok(what)
        }
    }

    /// A finite `double`.
    pub(super) fn double(&mut self, what: &str) -> Result<f64, MeshError> {
        let v = if self.binary {
            let b = self.bytes(8, what)?;
            f64::from_bits(self.uint_bytes(b))
        } else {
            self.parse_tok::<f64>(what)?
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(format!("expected {what} (a finite number), found {v}")))
        }
    }

    /// A count, checked against the bytes left (each item takes at least `min_bytes`).
    pub(super) fn count(&mut self, what: &str, min_bytes: usize) -> Result<usize, MeshError> {
        let n = self.size(what)?;
        let left = (self.data.len() - self.pos.min(self.data.len())) as u64;
        if n.saturating_mul(min_bytes as u64) > left {
            return Err(self.err(format!(
                "{what} is {n}, more than the rest of the file can hold (truncated file or wrong count?)"
            )));
        }
        Ok(n as usize)
    }

    pub(super) fn skip_ws_inline(&mut self) {
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
            self.pos += 1;
        }
    }
}
