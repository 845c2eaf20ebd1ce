//! Nearest-neighbour search among a fixed set of points that are switched on and off: the
//! runner's greedy nearest-neighbour walk (points leave the set as they are visited) and its
//! warm-start lookup (finished runs join the set batch by batch).
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
//! below one of them), so the study's run order and warm starts do not change.
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

    /// Number of points (live or not).
    pub(crate) fn len(&self) -> usize {
        self.live.len()
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

    /// The live point nearest to `q` as `(squared distance, index)`, ties to the least index;
    /// `None` if no point is live.
    pub(crate) fn nearest(&self, q: &[f64]) -> Option<(f64, usize)> {
        if self.dim == 0 {
            // Points of no coordinate are all at distance 0: the least live index.
            return (0..self.live.len())
                .find(|&i| self.live[i])
                .map(|i| (0.0, i));
        }
        let mut best: Option<(f64, usize)> = None;
        self.search(q, 0, self.perm.len(), &mut best);
        best
    }

    fn search(&self, q: &[f64], lo: usize, hi: usize, best: &mut Option<(f64, usize)>) {
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
            let better = match *best {
                None => true,
                Some((bd, bi)) => d < bd || (d == bd && i < bi),
            };
            if better {
                *best = Some((d, i));
            }
        }
        let a = self.axis[m] as usize;
        let delta = q[a] - self.coords[i * self.dim + a];
        let (first, second) = if delta < 0.0 {
            ((lo, m), (m + 1, hi))
        } else {
            ((m + 1, hi), (lo, m))
        };
        self.search(q, first.0, first.1, best);
        if best.is_none_or(|(bd, _)| delta * delta <= bd) {
            self.search(q, second.0, second.1, best);
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

/// Greedy nearest-neighbour walk: start at the point nearest to `origin`, then repeatedly go to
/// the nearest point not yet visited (ties to the least index). `O(n log n)` on spread points.
pub(crate) fn nn_order(points: &[Vec<f64>], origin: &[f64]) -> Vec<usize> {
    let dim = origin.len();
    let refs: Vec<&[f64]> = points.iter().map(|p| p.as_slice()).collect();
    let mut tree = KdTree::new(dim, &refs);
    for i in 0..tree.len() {
        tree.set_live(i, true);
    }
    let mut order = Vec::with_capacity(points.len());
    let mut cur = origin.to_vec();
    while let Some((_, i)) = tree.nearest(&cur) {
        tree.set_live(i, false);
        cur.clone_from(&points[i]);
        order.push(i);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition: the brute-force walk (as the runner did it before the tree).
    fn brute_order(points: &[Vec<f64>], origin: &[f64]) -> Vec<usize> {
        let mut left: Vec<usize> = (0..points.len()).collect();
        let mut order = Vec::new();
        let mut cur = origin.to_vec();
        while !left.is_empty() {
            let (k, _) = left
                .iter()
                .enumerate()
                .map(|(k, &i)| (k, dist2(&points[i], &cur)))
                .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
            let i = left.remove(k);
            cur = points[i].clone();
            order.push(i);
        }
        order
    }

    fn lcg(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn walk_equals_brute_force_on_random_points() {
        let mut s = 7u64;
        for (n, d) in [(1, 1), (2, 2), (50, 1), (300, 2), (400, 3), (200, 6)] {
            let pts: Vec<Vec<f64>> = (0..n)
                .map(|_| (0..d).map(|_| lcg(&mut s)).collect())
                .collect();
            let origin = vec![0.5; d];
            assert_eq!(
                nn_order(&pts, &origin),
                brute_order(&pts, &origin),
                "{n} {d}"
            );
        }
    }

    #[test]
    fn walk_equals_brute_force_on_grids_with_ties_and_duplicates() {
        // Regular grids are full of equidistant neighbours: the tie rule decides the order.
        let mut pts = Vec::new();
        for i in 0..13 {
            for j in 0..11 {
                pts.push(vec![i as f64 / 12.0, j as f64 / 10.0]);
            }
        }
        pts.push(pts[40].clone()); // a duplicate point
        let origin = vec![0.5, 0.5];
        assert_eq!(nn_order(&pts, &origin), brute_order(&pts, &origin));
        let mut cube = Vec::new();
        for i in 0..5 {
            for j in 0..5 {
                for k in 0..5 {
                    cube.push(vec![i as f64, j as f64, k as f64]);
                }
            }
        }
        let o = vec![2.0, 2.0, 2.0];
        assert_eq!(nn_order(&cube, &o), brute_order(&cube, &o));
    }

    #[test]
    fn nearest_among_switched_points_equals_brute_force() {
        let mut s = 11u64;
        let pts: Vec<Vec<f64>> = (0..500)
            .map(|_| (0..3).map(|_| (lcg(&mut s) * 8.0).floor() / 8.0).collect())
            .collect();
        let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
        let mut tree = KdTree::new(3, &refs);
        assert_eq!(tree.nearest(&[0.0, 0.0, 0.0]), None);
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
            assert_eq!(tree.nearest(&q), brute, "step {step}");
        }
    }
}
