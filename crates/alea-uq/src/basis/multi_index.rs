//! Multi-index sets `A` of a polynomial chaos in `n` variables.
//!
//! * total degree `p`: `|alpha|_1 <= p`, with `card A = P + 1 = (n + p)! / (n! p!)` (thesis);
//! * hyperbolic (q-norm) `0 < q <= 1`: `(sum_i alpha_i^q)^(1/q) <= p` (Blatman & Sudret 2011).
//!
//! Indices are sorted by total degree, then in reverse lexicographic order, so index 0 is the
//! constant term.

use crate::error::{Result, invalid};

/// A set of multi-indices, stored flat (`len * dim` entries).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MultiIndexSet {
    dim: usize,
    data: Vec<u16>,
}

impl MultiIndexSet {
    /// Total-degree set of degree `p` in `dim` variables.
    ///
    /// # Errors
    /// If `dim == 0`.
    pub fn total_degree(dim: usize, p: usize) -> Result<Self> {
        Self::hyperbolic(dim, p, 1.0)
    }

    /// Hyperbolic set with q-norm `q` in `(0, 1]`.
    ///
    /// # Errors
    /// If `dim == 0` or `q` is not in `(0, 1]`.
    pub fn hyperbolic(dim: usize, p: usize, q: f64) -> Result<Self> {
        if dim == 0 {
            return Err(invalid("multi-index set", "dim", ">= 1", 0.0));
        }
        if !(q > 0.0 && q <= 1.0) {
            return Err(invalid("multi-index set", "q", "in (0, 1]", q));
        }
        let mut out: Vec<Vec<u16>> = Vec::new();
        let mut cur = vec![0u16; dim];
        let pf = p as f64 + 1e-9;
        fn rec(
            i: usize,
            left: usize,
            cur: &mut Vec<u16>,
            out: &mut Vec<Vec<u16>>,
            q: f64,
            pf: f64,
        ) {
            if i == cur.len() {
                let qn: f64 = cur.iter().map(|&a| (a as f64).powf(q)).sum::<f64>();
                if qn.powf(1.0 / q) <= pf {
                    out.push(cur.clone());
                }
                return;
            }
            for a in 0..=left {
                cur[i] = a as u16;
                rec(i + 1, left - a, cur, out, q, pf);
            }
            cur[i] = 0;
        }
        rec(0, p, &mut cur, &mut out, q, pf);
        out.sort_by(|a, b| {
            let sa: u32 = a.iter().map(|&v| v as u32).sum();
            let sb: u32 = b.iter().map(|&v| v as u32).sum();
            sa.cmp(&sb).then_with(|| b.cmp(a))
        });
        Ok(Self {
            dim,
            data: out.into_iter().flatten().collect(),
        })
    }

    /// Build from explicit indices (each of length `dim`).
    ///
    /// # Errors
    /// If an index has the wrong length or the set is empty.
    pub fn from_indices(dim: usize, indices: &[Vec<u16>]) -> Result<Self> {
        if indices.is_empty() {
            return Err(invalid("multi-index set", "indices", "non-empty", 0.0));
        }
        let mut data = Vec::with_capacity(dim * indices.len());
        for a in indices {
            crate::error::check_len("multi-index set", "index", dim, a.len())?;
            data.extend_from_slice(a);
        }
        Ok(Self { dim, data })
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Number of multi-indices.
    pub fn len(&self) -> usize {
        self.data.len() / self.dim
    }
    /// `true` if the set is empty.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }
    /// Multi-index number `i`.
    pub fn get(&self, i: usize) -> &[u16] {
        &self.data[i * self.dim..(i + 1) * self.dim]
    }
    /// Iterate over the multi-indices.
    pub fn iter(&self) -> impl Iterator<Item = &[u16]> {
        self.data.chunks_exact(self.dim)
    }
    /// Largest degree in variable `j`.
    pub fn max_degree(&self, j: usize) -> usize {
        self.iter().map(|a| a[j] as usize).max().unwrap_or(0)
    }
    /// Subset keeping the indices at positions `keep` (in that order).
    pub fn subset(&self, keep: &[usize]) -> Self {
        Self {
            dim: self.dim,
            data: keep.iter().flat_map(|&i| self.get(i).to_vec()).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_degree_cardinality() {
        // P + 1 = (n + p)! / (n! p!)
        assert_eq!(MultiIndexSet::total_degree(3, 4).unwrap().len(), 35);
        assert_eq!(MultiIndexSet::total_degree(2, 5).unwrap().len(), 21);
        assert_eq!(MultiIndexSet::total_degree(6, 3).unwrap().len(), 84);
        let s = MultiIndexSet::total_degree(3, 2).unwrap();
        assert_eq!(s.get(0), &[0, 0, 0]);
    }

    #[test]
    fn hyperbolic_is_smaller() {
        let full = MultiIndexSet::total_degree(4, 5).unwrap().len();
        let hyp = MultiIndexSet::hyperbolic(4, 5, 0.5).unwrap();
        assert!(hyp.len() < full);
        // q-norm 0.5 of (1,1) is 4 <= 5, of (1,1,1) is 9 > 5.
        assert!(hyp.iter().any(|a| a == [1, 1, 0, 0]));
        assert!(!hyp.iter().any(|a| a == [1, 1, 1, 0]));
    }
}
