//! Little-endian bytes of `u64` and `f64` values: the one binary encoding of alea, for what it
//! keeps or sends bit for bit - the study store's BLOBs (parameters, quantities, states,
//! fields), the estimator's per-run data (`alea_estimate::RunData`) and the messages between
//! MPI ranks (`alea_study`'s `distributed/wire.rs`).
//!
//! A record is a sequence of `u64` (8 bytes, little-endian) and `f64` (its IEEE bits as a
//! `u64`); a vector is either raw (its length known from elsewhere: [`ByteWriter::f64s`]) or
//! preceded by its length ([`ByteWriter::f64s_counted`]); a string or a nested record is its
//! byte length then its bytes. [`ByteReader`] reads them back in the same order; a length is
//! checked against the bytes left before anything is allocated, and a truncated or foreign
//! byte string is an error, never a panic.
//!
//! Written by hand (a page) rather than with a serialisation crate: every `f64` must come back
//! bit for bit (NaN payloads, `-0.0`), which text formats do not promise, and the layout must
//! stay the one that stores written by earlier versions hold, which a crate's own format
//! (bincode, postcard) would not let us fix.

/// A byte string that does not decode: where, and what was expected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct BytesError(pub String);

/// Appends values to a byte buffer.
#[derive(Debug, Default, Clone)]
pub struct ByteWriter {
    buf: Vec<u8>,
}

impl ByteWriter {
    /// An empty buffer.
    pub fn new() -> Self {
        Self::default()
    }

    /// Bytes written so far.
    pub fn len(&self) -> usize {
        self.buf.len()
    }

    /// True when nothing was written.
    pub fn is_empty(&self) -> bool {
        self.buf.is_empty()
    }

    /// The bytes.
    pub fn into_bytes(self) -> Vec<u8> {
        self.buf
    }

    /// Bytes as they are (a magic, a nested record whose length is known).
    pub fn raw(&mut self, b: &[u8]) -> &mut Self {
        self.buf.extend_from_slice(b);
        self
    }

    /// A `u64`.
    pub fn u64(&mut self, v: u64) -> &mut Self {
        self.buf.extend_from_slice(&v.to_le_bytes());
        self
    }

    /// An `f64`, bit for bit.
    pub fn f64(&mut self, v: f64) -> &mut Self {
        self.u64(v.to_bits())
    }

    /// The values of `v`, without their number.
    pub fn f64s(&mut self, v: &[f64]) -> &mut Self {
        self.buf.reserve(8 * v.len());
        for x in v {
            self.buf.extend_from_slice(&x.to_le_bytes());
        }
        self
    }

    /// The number of values of `v`, then the values.
    pub fn f64s_counted(&mut self, v: &[f64]) -> &mut Self {
        self.u64(v.len() as u64).f64s(v)
    }

    /// The byte length of `b`, then `b`.
    pub fn bytes_counted(&mut self, b: &[u8]) -> &mut Self {
        self.u64(b.len() as u64).raw(b)
    }

    /// The byte length of `s`, then its UTF-8 bytes.
    pub fn str(&mut self, s: &str) -> &mut Self {
        self.bytes_counted(s.as_bytes())
    }
}

/// Reads values back in the order a [`ByteWriter`] wrote them.
#[derive(Debug, Clone)]
pub struct ByteReader<'a> {
    buf: &'a [u8],
    at: usize,
}

impl<'a> ByteReader<'a> {
    /// Reads `buf` from its start.
    pub fn new(buf: &'a [u8]) -> Self {
        ByteReader { buf, at: 0 }
    }

    /// Bytes not read yet.
    pub fn remaining(&self) -> usize {
        self.buf.len() - self.at
    }

    /// The next `n` bytes.
    ///
    /// # Errors
    /// If fewer than `n` are left.
    pub fn take(&mut self, n: usize) -> Result<&'a [u8], BytesError> {
        if self.remaining() < n {
            return Err(BytesError(format!(
                "{} bytes end at byte {} while {n} more were expected",
                self.buf.len(),
                self.at
            )));
        }
        let s = &self.buf[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }

    /// A `u64`.
    ///
    /// # Errors
    /// If fewer than 8 bytes are left.
    pub fn u64(&mut self) -> Result<u64, BytesError> {
        let b = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(u64::from_le_bytes(a))
    }

    /// An `f64`, bit for bit.
    ///
    /// # Errors
    /// If fewer than 8 bytes are left.
    pub fn f64(&mut self) -> Result<f64, BytesError> {
        Ok(f64::from_bits(self.u64()?))
    }

    /// A count of items of `width` bytes each, checked against the bytes left (so that a
    /// foreign byte string cannot make the caller allocate without bound).
    ///
    /// # Errors
    /// If fewer than 8 bytes are left, or the items would not fit in what is left.
    pub fn count(&mut self, width: usize) -> Result<usize, BytesError> {
        let n = usize::try_from(self.u64()?)
            .map_err(|_| BytesError("a count does not fit in memory".into()))?;
        if n.checked_mul(width).is_none_or(|b| b > self.remaining()) {
            return Err(BytesError(format!(
                "a count of {n} exceeds the {} bytes left",
                self.remaining()
            )));
        }
        Ok(n)
    }

    /// `n` values written by [`ByteWriter::f64s`].
    ///
    /// # Errors
    /// If fewer than `8 n` bytes are left.
    pub fn f64s(&mut self, n: usize) -> Result<Vec<f64>, BytesError> {
        let len = n
            .checked_mul(8)
            .ok_or_else(|| BytesError(format!("{n} values do not fit in memory")))?;
        Ok(f64s_from_le(self.take(len)?))
    }

    /// Values written by [`ByteWriter::f64s_counted`].
    ///
    /// # Errors
    /// If the count or the values are not there.
    pub fn f64s_counted(&mut self) -> Result<Vec<f64>, BytesError> {
        let n = self.count(8)?;
        self.f64s(n)
    }

    /// Bytes written by [`ByteWriter::bytes_counted`].
    ///
    /// # Errors
    /// If the length or the bytes are not there.
    pub fn bytes_counted(&mut self) -> Result<&'a [u8], BytesError> {
        let n = self.count(1)?;
        self.take(n)
    }

    /// A string written by [`ByteWriter::str`].
    ///
    /// # Errors
    /// If the length or the bytes are not there, or they are not UTF-8.
    pub fn str(&mut self) -> Result<String, BytesError> {
        let b = self.bytes_counted()?;
        String::from_utf8(b.to_vec()).map_err(|e| BytesError(e.to_string()))
    }

    /// Checks that every byte was read.
    ///
    /// # Errors
    /// If bytes are left.
    pub fn end(&self) -> Result<(), BytesError> {
        match self.remaining() {
            0 => Ok(()),
            n => Err(BytesError(format!("{n} trailing bytes"))),
        }
    }
}

/// The values of `v` as bytes ([`ByteWriter::f64s`]).
pub fn f64s_to_le(v: &[f64]) -> Vec<u8> {
    let mut w = ByteWriter::new();
    w.f64s(v);
    w.into_bytes()
}

/// The values of `b`, 8 bytes each (a trailing partial value is left out: the store checks
/// its sizes elsewhere).
pub fn f64s_from_le(b: &[u8]) -> Vec<f64> {
    b.chunks_exact(8)
        .map(|c| {
            let mut a = [0u8; 8];
            a.copy_from_slice(c);
            f64::from_le_bytes(a)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of value comes back bit for bit, and every cut of the bytes is an error.
    #[test]
    fn values_round_trip_bit_for_bit_and_cuts_are_errors() {
        let odd = [f64::NAN, -0.0, f64::MIN_POSITIVE / 3.0, f64::MAX, 1.5];
        let mut w = ByteWriter::new();
        w.raw(b"MAGIC123")
            .u64(7)
            .f64(-0.0)
            .f64s_counted(&odd)
            .str("\u{e9}t\u{e9}")
            .bytes_counted(&[1, 2, 3])
            .f64s(&odd[1..3]);
        let b = w.into_bytes();
        let read = |b: &[u8]| -> Result<(), BytesError> {
            let mut r = ByteReader::new(b);
            assert_eq!(r.take(8)?, b"MAGIC123");
            assert_eq!(r.u64()?, 7);
            assert_eq!(r.f64()?.to_bits(), (-0.0f64).to_bits());
            let v = r.f64s_counted()?;
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&v), bits(&odd));
            assert_eq!(r.str()?, "\u{e9}t\u{e9}");
            assert_eq!(r.bytes_counted()?, &[1, 2, 3]);
            assert_eq!(bits(&r.f64s(2)?), bits(&odd[1..3]));
            r.end()
        };
        read(&b).unwrap();
        for cut in 0..b.len() {
            assert!(read(&b[..cut]).is_err(), "cut at {cut}");
        }
        let mut longer = b.clone();
        longer.push(0);
        assert!(read(&longer).is_err());
        assert_eq!(f64s_from_le(&f64s_to_le(&odd[1..])), odd[1..].to_vec());
    }

    /// A count larger than the bytes left is refused before anything is allocated.
    #[test]
    fn a_huge_count_is_refused() {
        let mut w = ByteWriter::new();
        w.u64(u64::MAX).f64(1.0);
        let b = w.into_bytes();
        assert!(ByteReader::new(&b).f64s_counted().is_err());
        assert!(ByteReader::new(&b).bytes_counted().is_err());
    }
}
