//! The run schedule of a study: in which *generation* each design point is solved and which
//! finished runs its warm start is interpolated from. Both depend on the design alone (never on
//! the thread count, the MPI ranks, or what an interrupted invocation finished), so a study's
//! results are the same however it is run, and the parallel width grows with the design.
//!
//! **Generations: a tree grown from the centre.** Generation 0 is the point nearest the
//! nominal point (distances in the parameter box scaled to the unit cube; ties to the least
//! index). The other points are split recursively in two at the median of the axis of widest
//! spread (a kd-tree over the design); a node of depth `k >= 1` contributes one point to
//! generation `k`: its point nearest the centre of the node's bounding box (ties to the least
//! index), and the node's other points are split again. Generation `k` holds at most `2^k`
//! points and every point is in exactly one generation, so a design of `n` points has about
//! `log2(n) + 2` generations: the critical path of the study is that many runs long, and
//! generation `k` can use up to `2^k` solvers at once (a 1 000-run design: 256 and more). Each generation
//! refines the previous ones (coarse to fine, as the nodes halve), so its points lie between
//! finished runs. Building it costs `O(d n log n)`.
//!
//! **Parents and weights.** A run of generation `k` starts from the interface fields of its
//! `m = min(2d + 1, live)` nearest converged runs of generations `< k` (and of earlier calls:
//! an adaptive step's new points start from every finished run), combined with the weights of
//! a *moving least-squares* linear interpolation at its point `x`: with `phi_i = 1 / |p_i -
//! x|^2`, the weights
//! `w_i = phi_i (a + b . (p_i - x))` minimise `sum_i w_i^2 / phi_i` subject to
//! `sum_i w_i = 1` and `sum_i w_i (p_i - x) = 0`, i.e. they reproduce every affine function of
//! the parameters exactly (`[a, b]` solves the `(d + 1) x (d + 1)` moment system
//! `sum_i phi_i [1, p_i - x]^T [1, p_i - x] [a, b] = e_1`). With `d + 1` parents in general
//! position these are the barycentric weights of their simplex, the weights of the
//! piecewise-linear surrogate on a grid. When the moment system is singular (parents on a
//! line in 2D, ...) or the weights extrapolate far (`max |w_i| > 2`) the inverse-square-distance
//! weights `phi_i / sum phi` are used instead; a parent at the point itself gets weight 1.

use crate::spatial::{KdTree, dist2};

/// Parents a warm start is interpolated from, per parameter dimension (`2 d + 1` in all).
pub(crate) fn parent_count(dim: usize) -> usize {
    2 * dim + 1
}

/// Weights larger than this in magnitude mean the affine interpolation extrapolates too far:
/// the inverse-square-distance weights are used instead.
const MAX_WEIGHT: f64 = 2.0;

/// The generations of the design `points` (normalised coordinates) grown from `origin`: every
/// index once, generation 0 the point nearest `origin`.
pub(crate) fn generations(points: &[Vec<f64>], origin: &[f64]) -> Vec<Vec<usize>> {
    let n = points.len();
    if n == 0 {
        return Vec::new();
    }
    let first = (0..n)
        .min_by(|&a, &b| {
            dist2(&points[a], origin)
                .total_cmp(&dist2(&points[b], origin))
                .then(a.cmp(&b))
        })
        .unwrap_or(0);
    let mut out = vec![vec![first]];
    let rest: Vec<usize> = (0..n).filter(|&i| i != first).collect();
    // The nodes of the current depth: their points not yet in a generation.
    let mut nodes: Vec<Vec<usize>> = split(points, rest);
    while !nodes.is_empty() {
        let mut generation = Vec::with_capacity(nodes.len());
        let mut next = Vec::with_capacity(2 * nodes.len());
        for mut node in nodes {
            let centre = box_centre(points, &node);
            let k = (0..node.len())
                .min_by(|&a, &b| {
                    dist2(&points[node[a]], &centre)
                        .total_cmp(&dist2(&points[node[b]], &centre))
                        .then(node[a].cmp(&node[b]))
                })
                .unwrap_or(0);
            generation.push(node.remove(k));
            next.extend(split(points, node));
        }
        generation.sort_unstable();
        out.push(generation);
        nodes = next;
    }
    out
}

/// The centre of the bounding box of `node`'s points.
fn box_centre(points: &[Vec<f64>], node: &[usize]) -> Vec<f64> {
    let dim = points[node[0]].len();
    (0..dim)
        .map(|j| {
            let (lo, hi) = node
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &i| {
                    (l.min(points[i][j]), h.max(points[i][j]))
                });
            0.5 * (lo + hi)
        })
        .collect()
}

/// `node` split in two at the median of its axis of widest spread (ties by index); the empty
/// halves are left out.
fn split(points: &[Vec<f64>], mut node: Vec<usize>) -> Vec<Vec<usize>> {
    match node.len() {
        0 => return Vec::new(),
        1 => return vec![node],
        _ => {}
    }
    let dim = points[node[0]].len();
    let mut axis = 0;
    let mut widest = -1.0;
    for j in 0..dim {
        let (lo, hi) = node
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &i| {
                (l.min(points[i][j]), h.max(points[i][j]))
            });
        if hi - lo > widest {
            widest = hi - lo;
            axis = j;
        }
    }
    let m = node.len() / 2;
    if dim > 0 {
        node.select_nth_unstable_by(m, |&x, &y| {
            points[x][axis].total_cmp(&points[y][axis]).then(x.cmp(&y))
        });
    } else {
        node.sort_unstable();
    }
    let right = node.split_off(m);
    vec![node, right]
}

/// The warm-start parents of the point `x` among the live points of `sources` (indices into
/// `coords`) and their interpolation weights (module doc), nearest first; empty if no source is
/// live.
pub(crate) fn parents(sources: &KdTree, coords: &[&[f64]], x: &[f64]) -> Vec<(usize, f64)> {
    let near = sources.nearest_k(x, parent_count(x.len()));
    if near.is_empty() {
        return Vec::new();
    }
    if near[0].0 == 0.0 {
        return vec![(near[0].1, 1.0)];
    }
    let pts: Vec<&[f64]> = near.iter().map(|&(_, k)| coords[k]).collect();
    let d2: Vec<f64> = near.iter().map(|&(d, _)| d).collect();
    let w = mls_weights(x, &pts, &d2).unwrap_or_else(|| {
        let phi: Vec<f64> = d2.iter().map(|d| 1.0 / d).collect();
        let s: f64 = phi.iter().sum();
        phi.iter().map(|p| p / s).collect()
    });
    near.iter().map(|&(_, k)| k).zip(w).collect()
}

/// The moving least-squares weights (module doc) of `pts` at `x`, `d2` their squared
/// distances (all > 0); `None` if the moment system is singular or a weight exceeds
/// [`MAX_WEIGHT`].
fn mls_weights(x: &[f64], pts: &[&[f64]], d2: &[f64]) -> Option<Vec<f64>> {
    let dim = x.len();
    let m = dim + 1;
    let basis = |p: &[f64]| -> Vec<f64> {
        std::iter::once(1.0)
            .chain(p.iter().zip(x).map(|(a, b)| a - b))
            .collect()
    };
    let mut mat = vec![0.0; m * m];
    for (p, d) in pts.iter().zip(d2) {
        let b = basis(p);
        for r in 0..m {
            for c in 0..m {
                mat[r * m + c] += b[r] * b[c] / d;
            }
        }
    }
    let scale = mat.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut rhs = vec![0.0; m];
    rhs[0] = 1.0;
    // A pivot below 1e-10 of the largest entry means the parents do not determine an affine
    // function.
    let coef = alea_latin::dense::solve_pivoted(&mut mat, &mut rhs, m, 1e-10 * scale)?;
    let w: Vec<f64> = pts
        .iter()
        .zip(d2)
        .map(|(p, d)| {
            let b = basis(p);
            b.iter().zip(&coef).map(|(u, v)| u * v).sum::<f64>() / d
        })
        .collect();
    if w.iter().all(|v| v.is_finite() && v.abs() <= MAX_WEIGHT) {
        Some(w)
    } else {
        None
    }
}

/// `sum_i w_i state_i` of flat local-stage states of one length (parents in order).
pub(crate) fn combine(states: &[(&[f64], f64)]) -> Vec<f64> {
    let len = states.first().map_or(0, |s| s.0.len());
    let mut out = vec![0.0; len];
    for (s, w) in states {
        for (o, v) in out.iter_mut().zip(s.iter()) {
            *o += w * v;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(k: usize) -> Vec<Vec<f64>> {
        let mut pts = Vec::new();
        for i in 0..k {
            for j in 0..k {
                pts.push(vec![i as f64 / (k - 1) as f64, j as f64 / (k - 1) as f64]);
            }
        }
        pts
    }

    use crate::test_rng::lcg;

    #[test]
    fn generations_partition_the_design_and_double() {
        let mut s = 3u64;
        let random: Vec<Vec<f64>> = (0..1000)
            .map(|_| (0..3).map(|_| lcg(&mut s)).collect())
            .collect();
        for pts in [grid(15), grid(2), random, vec![vec![0.5, 0.5]]] {
            let g = generations(&pts, &vec![0.5; pts[0].len()]);
            let mut all: Vec<usize> = g.iter().flatten().copied().collect();
            all.sort_unstable();
            assert_eq!(all, (0..pts.len()).collect::<Vec<_>>());
            assert_eq!(g[0].len(), 1);
            for (k, generation) in g.iter().enumerate().skip(1) {
                assert!(
                    generation.len() <= 1 << k,
                    "generation {k}: {}",
                    generation.len()
                );
            }
            let depth = (pts.len() as f64).log2().ceil() as usize + 2;
            assert!(
                g.len() <= depth,
                "{} generations for {}",
                g.len(),
                pts.len()
            );
        }
    }

    #[test]
    fn a_1000_run_design_has_32_runs_in_parallel_from_its_sixth_generation() {
        let mut s = 5u64;
        let pts: Vec<Vec<f64>> = (0..1000)
            .map(|_| (0..2).map(|_| lcg(&mut s)).collect())
            .collect();
        let g = generations(&pts, &[0.5, 0.5]);
        let widths: Vec<usize> = g.iter().map(Vec::len).collect();
        assert_eq!(widths[..6], [1, 2, 4, 8, 16, 32], "{widths:?}");
        assert!(widths.iter().max().is_some_and(|&w| w >= 256), "{widths:?}");
        assert!(g.len() <= 12, "critical path {} runs: {widths:?}", g.len());
    }

    #[test]
    fn the_first_generation_is_the_point_nearest_the_origin() {
        let pts = grid(15);
        let g = generations(&pts, &[0.5, 0.5]);
        assert_eq!(g[0], vec![7 * 15 + 7]);
        // Every later point of a grid has a finished neighbour closer than the first
        // generations' spacing: the last generation's points are one grid step from one.
        let done: Vec<usize> = g[..g.len() - 1].iter().flatten().copied().collect();
        let step2 = (1.0f64 / 14.0).powi(2) * 2.0 + 1e-12;
        for &i in g.last().unwrap() {
            let near = done
                .iter()
                .map(|&j| dist2(&pts[i], &pts[j]))
                .fold(f64::INFINITY, f64::min);
            assert!(near <= step2, "point {i} is {near} from the finished ones");
        }
    }

    #[test]
    fn weights_reproduce_affine_functions() {
        let mut s = 9u64;
        for dim in 1..5 {
            let pts: Vec<Vec<f64>> = (0..60)
                .map(|_| (0..dim).map(|_| lcg(&mut s)).collect())
                .collect();
            let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
            let mut tree = KdTree::new(dim, &refs);
            for i in 0..pts.len() {
                tree.set_live(i, true);
            }
            let f = |p: &[f64]| {
                0.3 + p
                    .iter()
                    .enumerate()
                    .map(|(j, v)| (j as f64 + 1.5) * v)
                    .sum::<f64>()
            };
            let mut checked = 0;
            for _ in 0..40 {
                let x: Vec<f64> = (0..dim).map(|_| 0.2 + 0.6 * lcg(&mut s)).collect();
                let w = parents(&tree, &refs, &x);
                assert_eq!(w.len(), parent_count(dim));
                let sum: f64 = w.iter().map(|p| p.1).sum();
                assert!((sum - 1.0).abs() < 1e-12, "{sum}");
                // Either the affine weights (which reproduce `f`) or the fallback.
                let idw = {
                    let phi: Vec<f64> = w.iter().map(|&(k, _)| 1.0 / dist2(refs[k], &x)).collect();
                    let t: f64 = phi.iter().sum();
                    phi.iter().map(|p| p / t).collect::<Vec<_>>()
                };
                let is_idw = w.iter().zip(&idw).all(|(a, b)| (a.1 - b).abs() < 1e-14);
                if !is_idw {
                    assert!(w.iter().all(|p| p.1.abs() <= MAX_WEIGHT), "{w:?}");
                    let fi: f64 = w.iter().map(|&(k, wk)| wk * f(refs[k])).sum();
                    assert!((fi - f(&x)).abs() < 1e-10, "dim {dim}: {fi} vs {}", f(&x));
                    checked += 1;
                }
            }
            assert!(
                checked >= 30,
                "dim {dim}: only {checked} affine interpolations"
            );
        }
    }

    #[test]
    fn grid_midpoints_get_the_bilinear_weights() {
        // Midway between two finished runs on a line: half of each.
        let pts = [
            vec![0.0, 0.0],
            vec![1.0, 0.0],
            vec![0.0, 1.0],
            vec![1.0, 1.0],
        ];
        let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
        let mut tree = KdTree::new(2, &refs);
        for i in 0..4 {
            tree.set_live(i, true);
        }
        let w = parents(&tree, &refs, &[0.5, 0.5]);
        for (_, wk) in &w {
            assert!((wk - 0.25).abs() < 1e-14, "{w:?}");
        }
        let w = parents(&tree, &refs, &[1.0, 1.0]);
        assert_eq!(w, vec![(3, 1.0)]);
    }
}
