//! One run per point: design points that differ only by round-off are the same point.
//!
//! Two methods may compute the same design point by different arithmetic (a grid's
//! `lo + i h` and a quadrature rule's mapped node): `[239999.99999999953, 0.4999999999999988]`
//! and `[240000.0, 0.5]`. Keyed by the exact bits of their coordinates
//! ([`crate::store::point_key`]) they would be two runs. A [`PointIndex`] maps every point to
//! its **canonical** point: the first point it was given (stored runs first, then design
//! points in method order) whose every coordinate is within [`POINT_TOLERANCE`] of the
//! parameter's range. The canonical point keeps its exact bits, so runs stored by older
//! versions (keyed by exact bits) are still found, and a stored run within round-off of a new
//! design point is that point's run.
//!
//! Look-up is a hash of the coordinates quantised on a grid much coarser than the tolerance
//! (cells of `1e-9` of the range, shifted off the round values designs produce), so a point
//! within the tolerance of another lies in its cell or, near a cell's side, in the neighbour
//! across it; both are searched. `O(1)` per point.

use std::collections::HashMap;

/// Largest difference of two coordinates of the same point, relative to the parameter's range.
pub const POINT_TOLERANCE: f64 = 1e-12;

/// Side of the look-up grid's cells, relative to the parameter's range.
const CELL: f64 = 1e-9;

/// Shift of the look-up grid, in cells (away from the round values of designs).
const SHIFT: f64 = std::f64::consts::FRAC_1_PI;

/// Beyond this many cells to search (points near the sides of many cells), a linear search.
const MAX_CELLS: usize = 64;

/// The canonical points seen so far (module doc).
#[derive(Clone, Debug)]
pub struct PointIndex {
    lo: Vec<f64>,
    range: Vec<f64>,
    points: Vec<Vec<f64>>,
    exact: HashMap<String, usize>,
    cells: HashMap<Vec<i64>, Vec<usize>>,
}

impl PointIndex {
    /// An empty index for the parameter box `[lo, hi]` (a parameter with an empty or infinite
    /// range is compared on a range of 1).
    pub fn new(lo: &[f64], hi: &[f64]) -> Self {
        let range = lo
            .iter()
            .zip(hi)
            .map(|(a, b)| {
                let r = b - a;
                if r.is_finite() && r > 0.0 { r } else { 1.0 }
            })
            .collect();
        PointIndex {
            lo: lo
                .iter()
                .map(|a| if a.is_finite() { *a } else { 0.0 })
                .collect(),
            range,
            points: Vec::new(),
            exact: HashMap::new(),
            cells: HashMap::new(),
        }
    }

    /// The canonical point of `p`: `p` itself if it was given before (exactly), else the first
    /// point given within the tolerance, else `p`, which becomes canonical.
    pub fn canonical(&mut self, p: &[f64]) -> Vec<f64> {
        if let Some(q) = self.find(p) {
            return q.to_vec();
        }
        self.insert(p);
        p.to_vec()
    }

    /// Adds `p` as a point of its own (a stored run: exact look-ups find it even when an
    /// earlier point lies within the tolerance).
    pub fn insert(&mut self, p: &[f64]) {
        let key = crate::store::point_key(p);
        if self.exact.contains_key(&key) {
            return;
        }
        let i = self.points.len();
        self.points.push(p.to_vec());
        self.exact.insert(key, i);
        let cell = self.cell(p);
        self.cells.entry(cell).or_default().push(i);
    }

    /// The point given before that `p` is (exactly, else within the tolerance), if any.
    pub fn find(&self, p: &[f64]) -> Option<&[f64]> {
        if let Some(&i) = self.exact.get(&crate::store::point_key(p)) {
            return Some(&self.points[i]);
        }
        let best = match self.candidate_cells(p) {
            Some(cells) => cells
                .iter()
                .filter_map(|c| self.cells.get(c))
                .flatten()
                .copied()
                .filter(|&i| self.same(p, &self.points[i]))
                .min(),
            None => (0..self.points.len()).find(|&i| self.same(p, &self.points[i])),
        };
        best.map(|i| self.points[i].as_slice())
    }

    /// True if `a` and `b` are the same point (every coordinate within the tolerance).
    pub fn same(&self, a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len()
            && a.iter()
                .zip(b)
                .zip(&self.range)
                .all(|((x, y), r)| (x - y).abs() <= POINT_TOLERANCE * r)
    }

    /// Position of `p` on the look-up grid, in cells.
    fn scaled(&self, p: &[f64]) -> Vec<f64> {
        p.iter()
            .zip(&self.lo)
            .zip(&self.range)
            .map(|((x, lo), r)| (x - lo) / (r * CELL) + SHIFT)
            .collect()
    }

    /// The cell of `p`.
    fn cell(&self, p: &[f64]) -> Vec<i64> {
        self.scaled(p).iter().map(|s| s.floor() as i64).collect()
    }

    /// The cells that may hold a point within the tolerance of `p`; `None` if too many.
    fn candidate_cells(&self, p: &[f64]) -> Option<Vec<Vec<i64>>> {
        // The tolerance in cells, with room for the rounding of the scaling.
        let reach = 2.0 * POINT_TOLERANCE / CELL;
        let mut cells: Vec<Vec<i64>> = vec![Vec::with_capacity(p.len())];
        for s in self.scaled(p) {
            let c = s.floor();
            let mut options = vec![c as i64];
            if s - c < reach {
                options.push(c as i64 - 1);
            }
            if c + 1.0 - s < reach {
                options.push(c as i64 + 1);
            }
            if cells.len() * options.len() > MAX_CELLS {
                return None;
            }
            cells = cells
                .into_iter()
                .flat_map(|prefix| {
                    options.iter().map(move |&o| {
                        let mut next = prefix.clone();
                        next.push(o);
                        next
                    })
                })
                .collect();
        }
        Some(cells)
    }
}

/// The points of every list of `lists` replaced by their canonical points (`index`, which
/// learns the new ones), in order.
pub fn canonicalise<'a>(
    index: &mut PointIndex,
    lists: impl IntoIterator<Item = &'a mut Vec<Vec<f64>>>,
) {
    for list in lists {
        for p in list.iter_mut() {
            *p = index.canonical(p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_off_makes_the_same_point_and_a_real_difference_another() {
        let mut idx = PointIndex::new(&[150e3, 0.2], &[250e3, 0.8]);
        let a = idx.canonical(&[240000.0, 0.5]);
        assert_eq!(a, vec![240000.0, 0.5]);
        assert_eq!(
            idx.canonical(&[239999.99999999953, 0.4999999999999988]),
            vec![240000.0, 0.5]
        );
        // 1e-9 of the range apart: another point.
        let b = [240000.0 + 1e-4, 0.5];
        assert_eq!(idx.canonical(&b), b.to_vec());
        assert_eq!(idx.points.len(), 2);
    }

    #[test]
    fn a_point_on_a_cell_side_finds_its_twin_across_it() {
        let mut idx = PointIndex::new(&[0.0], &[1.0]);
        // The side of a cell at (k - SHIFT) * CELL.
        let side = (1000.0 - SHIFT) * CELL;
        idx.insert(&[side - 2e-13]);
        assert_eq!(idx.find(&[side + 2e-13]), Some(&[side - 2e-13][..]));
        assert_eq!(idx.find(&[side + 3e-12]), None);
    }

    #[test]
    fn an_exact_point_finds_itself_before_an_earlier_twin() {
        let mut idx = PointIndex::new(&[0.0, 0.0], &[1.0, 1.0]);
        idx.insert(&[0.5, 0.5]);
        idx.insert(&[0.5 + 1e-15, 0.5]);
        assert_eq!(idx.find(&[0.5 + 1e-15, 0.5]), Some(&[0.5 + 1e-15, 0.5][..]));
        assert_eq!(idx.find(&[0.5 - 1e-15, 0.5]), Some(&[0.5, 0.5][..]));
    }
}
