//! Where points and nodes are: locating a point or an integer node in the leaves, corners and
//! the leaf a hanging node follows (its master), sub-cell centres and neighbours.

use super::*;

impl StochasticMesh {
    /// Leaf containing `xi` and the local coordinates of `xi` in it (`None` outside the box).
    pub fn locate_local(&self, xi: &[f64], t: &mut [f64]) -> Option<CellId> {
        let d = self.d;
        let mut root = 0usize;
        let mut stride = 1usize;
        for j in 0..d {
            let x = xi[j];
            if !(x >= self.lo[j] && x <= self.hi[j]) {
                return None;
            }
            let s = (x - self.lo[j]) / (self.hi[j] - self.lo[j]) * self.roots[j] as f64;
            let r = (s.floor() as usize).min(self.roots[j] - 1);
            t[j] = (s - r as f64).clamp(0.0, 1.0);
            root += r * stride;
            stride *= self.roots[j];
        }
        let mut c = root;
        loop {
            let first = self.child[c];
            if first == u32::MAX {
                break;
            }
            let first = first as usize;
            let mask = self.split_mask[c];
            let mut child = 0usize;
            let mut b = 0;
            for (j, tj) in t.iter_mut().enumerate().take(d) {
                if (mask >> j) & 1 == 1 {
                    if *tj >= 0.5 {
                        child |= 1 << b;
                        *tj = 2.0 * *tj - 1.0;
                    } else {
                        *tj *= 2.0;
                    }
                    b += 1;
                }
            }
            c = first + child;
        }
        Some(c)
    }

    /// Leaf cell containing `xi` (`None` outside the box).
    pub fn locate(&self, xi: &[f64]) -> Option<CellId> {
        let mut t = [0.0; MAX_DIM];
        self.locate_local(xi, &mut t[..self.d])
    }

    /// Leaf containing the neighbourhood of integer point `p` in the orthant `signs` (bit j set:
    /// positive direction), or `None` outside the box.
    pub(super) fn locate_key(&self, p: &Key, signs: usize) -> Option<usize> {
        let s = 1u64 << MAX_LEVEL;
        let mut root = 0usize;
        let mut stride = 1usize;
        for j in 0..self.d {
            let r = if (signs >> j) & 1 == 1 {
                p[j] / s
            } else {
                if p[j] == 0 {
                    return None;
                }
                (p[j] - 1) / s
            };
            if r >= self.roots[j] as u64 {
                return None;
            }
            root += r as usize * stride;
            stride *= self.roots[j];
        }
        let mut c = root;
        while let Some(first) = self.cells[c].first_child {
            let mask = self.split_mask[c];
            let o = self.cells[c].origin;
            let mut child = 0usize;
            let mut b = 0;
            for j in 0..self.d {
                if (mask >> j) & 1 == 0 {
                    continue;
                }
                let half = self.size(c, j) / 2;
                let off = p[j] - o[j];
                let up = if (signs >> j) & 1 == 1 {
                    off >= half
                } else {
                    off > half
                };
                if up {
                    child |= 1 << b;
                }
                b += 1;
            }
            c = first + child;
        }
        Some(c)
    }

    pub(super) fn is_corner(&self, c: usize, p: &Key) -> bool {
        let o = self.cells[c].origin;
        (0..self.d).all(|j| p[j] == o[j] || p[j] == o[j] + self.size(c, j))
    }

    /// Extent of the face of cell `c` through `p` (in its closure): the cell's size in the
    /// directions where `p` is strictly inside it, 0 in the others.
    pub(super) fn extent(&self, c: usize, p: &Key) -> Key {
        let o = self.cells[c].origin;
        let mut e = [0u64; MAX_DIM];
        for j in 0..self.d {
            let s = self.size(c, j);
            if p[j] != o[j] && p[j] != o[j] + s {
                e[j] = s;
            }
        }
        e
    }

    /// `true` if leaf `c` is a better master than `b` for `p`: its face through `p` contains
    /// `b`'s (componentwise larger extent; for isotropic cells: coarser), or, when neither
    /// contains the other, it has the larger total extent.
    pub(super) fn better_master(&self, c: usize, b: usize, p: &Key) -> bool {
        let (ec, eb) = (self.extent(c, p), self.extent(b, p));
        let ge = (0..self.d).all(|j| ec[j] >= eb[j]);
        let le = (0..self.d).all(|j| ec[j] <= eb[j]);
        if ge || le {
            ge && !le
        } else {
            ec.iter().sum::<u64>() > eb.iter().sum::<u64>()
        }
    }

    /// Classify node `p`: `None` if it is a corner of every leaf around it, else the coarsest
    /// leaf that contains it without having it as a corner (the one whose face through `p`
    /// contains the others').
    pub(super) fn master_of(&self, p: &Key) -> Option<usize> {
        let mut best: Option<usize> = None;
        for signs in 0..(1usize << self.d) {
            if let Some(c) = self.locate_key(p, signs)
                && !self.is_corner(c, p)
                && best.is_none_or(|b| self.better_master(c, b, p))
            {
                best = Some(c);
            }
        }
        best
    }

    /// Centres of the `2^(d depth)` sub-cells of `cell` at relative depth `depth` (the candidate
    /// points of the maximum-error criterion), row-major `n x d`.
    ///
    /// # Errors
    /// If the sub-cells would be deeper than [`MAX_LEVEL`] or more than 2^20.
    pub fn sub_cell_centres(&self, cell: CellId, depth: u32) -> Result<Vec<f64>> {
        let d = self.d;
        if self.cells[cell].level + depth + 1 > MAX_LEVEL || (d as u32) * depth > 20 {
            return Err(invalid(
                "stochastic mesh",
                "sub-cell depth",
                "within the maximum level and 2^20 points",
                depth as f64,
            ));
        }
        let o = self.cells[cell].origin;
        let step: Vec<u64> = (0..d).map(|j| self.size(cell, j) >> depth).collect();
        let n = 1usize << depth;
        let mut out = Vec::with_capacity(n.pow(d as u32) * d);
        let mut idx = [0usize; MAX_DIM];
        for _ in 0..n.pow(d as u32) {
            let mut key = o;
            for j in 0..d {
                key[j] += step[j] / 2 + idx[j] as u64 * step[j];
            }
            out.extend(self.key_point(&key));
            for v in idx.iter_mut().take(d) {
                *v += 1;
                if *v < n {
                    break;
                }
                *v = 0;
            }
        }
        Ok(out)
    }

    /// Leaf cells adjacent to `cell` (sharing a face, an edge or a corner).
    pub fn neighbours(&self, cell: CellId) -> Vec<CellId> {
        let d = self.d;
        let o = self.cells[cell].origin;
        let mut out = Vec::new();
        let mut delta = [-1i32; MAX_DIM];
        for _ in 0..3usize.pow(d as u32) {
            // delta in {-1, 0, 1}^d, enumerated as base-3 digits.
            if delta[..d].iter().any(|&v| v != 0) {
                // A probe point strictly inside the neighbouring region, in units where a
                // cell of this size spans 4 sub-units (sizes are powers of two >= 1).
                let mut ok = true;
                let mut key = [0u64; MAX_DIM];
                for j in 0..d {
                    let span = (self.roots[j] as u64) << MAX_LEVEL;
                    let v = match delta[j] {
                        -1 => o[j].checked_sub(1),
                        0 => Some(o[j] + self.size(cell, j) / 2),
                        _ => Some(o[j] + self.size(cell, j)),
                    };
                    match v {
                        Some(v) if v < span => key[j] = v,
                        _ => ok = false,
                    }
                }
                if ok
                    && let Some(c) = self.locate_key(&key, (1usize << d) - 1)
                    && !out.contains(&c)
                {
                    out.push(c);
                }
            }
            for v in delta.iter_mut().take(d) {
                *v += 1;
                if *v <= 1 {
                    break;
                }
                *v = -1;
            }
        }
        out
    }
}
