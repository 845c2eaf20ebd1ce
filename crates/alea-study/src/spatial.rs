//! Nearest-neighbour search among a fixed set of points that are switched on and off: the
//! runner's warm-start look-up (finished runs join the set generation by generation, and a
//! run's parents are its `k` nearest live points).
//!
//! A balanced kd-tree over the points, built once (`O(n log n)`), stored implicitly in a
//! permutation (the node of the range `[lo, hi)` sits at its middle position), with the number
//! of live points in every subtree so empty subtrees are skipped. Switching a point on or off is
//! `O(log n)`; a query is `O(log n)` on well-spread points.
//!
//! The answer is **exactly** the brute-force one: the live point of least squared distance
//! `sum_j (x_j - q_j)^2` (summed in coordinate order, as the brute force does), ties to the
//! least index. Pruning a subtree whose splitting plane is at `delta` uses `delta^2 <= best`,
//! exact in floating point (rounding is monotone, and a sum of non-negative terms is never
//! below one of them), so a study's warm starts do not depend on the tree's shape.
//!
//! Written here rather than taken from a crate: `kiddo` and `rstar` fix the dimension at
//! compile time (a study's is read from its file), and the order of the runs - and so the
//! bit-exact results of a study - depends on the tie rule, which no crate specifies.

/// Squared distance, summed in coordinate order.
pub(crate) fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>()
}

/// A kd-tree over fixed points with live/dead flags.
#[derive(Debug, Clone)]
pub(crate) struct KdTree {
    dim: usize,
    /// Coordinates, point-major (`dim` per point), by point index.
    coords: Vec<f64>,
    /// Point index at each tree position.
    perm: Vec<usize>,
    /// Tree position of each point.
    pos: Vec<usize>,
    /// Splitting axis at each position.
    axis: Vec<u8>,
    /// Live points in the subtree rooted at each position.
    alive: Vec<u32>,
    /// Whether each point (by index) is live.
    live: Vec<bool>,
}

impl KdTree {
    /// Builds the tree over `points` (all of dimension `dim`), every point dead.
    pub(crate) fn new(dim: usize, points: &[&[f64]]) -> Self {
        let n = points.len();
        let mut coords = Vec::with_capacity(n * dim);
        for p in points {
            debug_assert_eq!(p.len(), dim);
            coords.extend_from_slice(p);
        }
        let mut perm: Vec<usize> = (0..n).collect();
        let mut axis = vec![0u8; n];
        build(&coords, dim, &mut perm, &mut axis, 0);
        let mut pos = vec![0; n];
        for (k, &i) in perm.iter().enumerate() {
            pos[i] = k;
        }
        KdTree {
            dim,
            coords,
            perm,
            pos,
            axis,
            alive: vec![0; n],
            live: vec![false; n],
        }
    }

    fn point(&self, i: usize) -> &[f64] {
        &self.coords[i * self.dim..(i + 1) * self.dim]
    }

    /// Switches point `i` on (`true`) or off; nothing if it already is.
    pub(crate) fn set_live(&mut self, i: usize, on: bool) {
        if self.live[i] == on {
            return;
        }
        self.live[i] = on;
        // Walk from the root to the position of `i`, adjusting the counts on the way.
        let target = self.pos[i];
        let (mut lo, mut hi) = (0, self.perm.len());
        loop {
            let m = (lo + hi) / 2;
            if on {
                self.alive[m] += 1;
            } else {
                self.alive[m] -= 1;
            }
            match target.cmp(&m) {
                std::cmp::Ordering::Equal => return,
                std::cmp::Ordering::Less => hi = m,
                std::cmp::Ordering::Greater => lo = m + 1,
            }
        }
    }

    /// The `k` live points nearest to `q` as `(squared distance, index)`, nearest first (ties
    /// to the least index); fewer if fewer are live. Exactly the first `k` of the brute-force
    /// sort.
    pub(crate) fn nearest_k(&self, q: &[f64], k: usize) -> Vec<(f64, usize)> {
        let mut best: Vec<(f64, usize)> = Vec::with_capacity(k + 1);
        if k == 0 {
            return best;
        }
        if self.dim == 0 {
            return (0..self.live.len())
                .filter(|&i| self.live[i])
                .take(k)
                .map(|i| (0.0, i))
                .collect();
        }
        self.search_k(q, 0, self.perm.len(), k, &mut best);
        best
    }

    fn search_k(&self, q: &[f64], lo: usize, hi: usize, k: usize, best: &mut Vec<(f64, usize)>) {
        if lo >= hi {
            return;
        }
        let m = (lo + hi) / 2;
        if self.alive[m] == 0 {
            return;
        }
        let i = self.perm[m];
        if self.live[i] {
            let d = dist2(self.point(i), q);
            let before = |a: &(f64, usize)| a.0 < d || (a.0 == d && a.1 < i);
            let at = best.iter().position(|a| !before(a)).unwrap_or(best.len());
            if at < k {
                best.insert(at, (d, i));
                best.truncate(k);
            }
        }
        let a = self.axis[m] as usize;
        let delta = q[a] - self.coords[i * self.dim + a];
        let (first, second) = if delta < 0.0 {
            ((lo, m), (m + 1, hi))
        } else {
            ((m + 1, hi), (lo, m))
        };
        self.search_k(q, first.0, first.1, k, best);
        if best.len() < k || best.last().is_some_and(|&(bd, _)| delta * delta <= bd) {
            self.search_k(q, second.0, second.1, k, best);
        }
    }
}

/// Builds the implicit tree on `perm` (a range of point indices): the median along the axis of
/// widest spread goes to the middle position, smaller to the left, larger to the right.
fn build(coords: &[f64], dim: usize, perm: &mut [usize], axis: &mut [u8], depth: usize) {
    let n = perm.len();
    if n == 0 || dim == 0 {
        return;
    }
    let mut a = depth % dim;
    if dim > 1 && n > 2 {
        let mut widest = -1.0;
        for j in 0..dim {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for &i in perm.iter() {
                let v = coords[i * dim + j];
                lo = lo.min(v);
                hi = hi.max(v);
            }
            if hi - lo > widest {
                widest = hi - lo;
                a = j;
            }
        }
    }
    let m = n / 2;
    perm.select_nth_unstable_by(m, |&x, &y| {
        coords[x * dim + a]
            .total_cmp(&coords[y * dim + a])
            .then(x.cmp(&y))
    });
    axis[m] = a as u8;
    let (left, rest) = perm.split_at_mut(m);
    let (left_axis, rest_axis) = axis.split_at_mut(m);
    build(coords, dim, left, left_axis, depth + 1);
    build(coords, dim, &mut rest[1..], &mut rest_axis[1..], depth + 1);
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::test_rng::lcg;

    #[test]
    fn k_nearest_equals_the_brute_force_sort() {
        let mut s = 13u64;
        let pts: Vec<Vec<f64>> = (0..400)
            .map(|_| (0..2).map(|_| (lcg(&mut s) * 6.0).floor() / 6.0).collect())
            .collect();
        let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
        let mut tree = KdTree::new(2, &refs);
        let mut live = vec![false; pts.len()];
        for step in 0..600 {
            let i = (lcg(&mut s) * pts.len() as f64) as usize;
            tree.set_live(i, step % 4 != 0);
            live[i] = step % 4 != 0;
            let q: Vec<f64> = (0..2).map(|_| lcg(&mut s)).collect();
            let mut brute: Vec<(f64, usize)> = (0..pts.len())
                .filter(|&k| live[k])
                .map(|k| (dist2(&pts[k], &q), k))
                .collect();
            brute.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            brute.truncate(5);
            assert_eq!(tree.nearest_k(&q, 5), brute, "step {step}");
        }
    }

    #[test]
    fn nearest_among_switched_points_equals_brute_force() {
        let mut s = 11u64;
        let pts: Vec<Vec<f64>> = (0..500)
            .map(|_| (0..3).map(|_| (lcg(&mut s) * 8.0).floor() / 8.0).collect())
            .collect();
        let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
        let mut tree = KdTree::new(3, &refs);
        assert_eq!(tree.nearest_k(&[0.0, 0.0, 0.0], 1), vec![]);
        let mut live = vec![false; pts.len()];
        for step in 0..2000 {
            let i = (lcg(&mut s) * pts.len() as f64) as usize;
            let on = step % 3 != 0;
            tree.set_live(i, on);
            live[i] = on;
            let q: Vec<f64> = (0..3).map(|_| lcg(&mut s)).collect();
            let brute = (0..pts.len())
                .filter(|&k| live[k])
                .map(|k| (dist2(&pts[k], &q), k))
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            assert_eq!(tree.nearest_k(&q, 1).first().copied(), brute, "step {step}");
        }
    }
}
