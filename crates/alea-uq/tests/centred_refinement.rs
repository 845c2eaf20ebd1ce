//! Centred refinement of the stochastic mesh (the thesis's adaptive criteria, 4.2.2): one run
//! per refined cell (its centre) or at one chosen point, every other new node interpolated.
//! Checked: run counts, the surrogate unchanged outside the refined cells and continuous
//! everywhere, multilinear functions still reproduced exactly, in 2D and 3D.

use alea_uq::surrogate::{LinearSurrogate, StochasticMesh};

fn values(mesh: &StochasticMesh, f: impl Fn(&[f64]) -> f64) -> Vec<f64> {
    (0..mesh.num_runs()).map(|k| f(mesh.run_point(k))).collect()
}

/// A cheap deterministic pseudo-random sequence in [0, 1).
fn lcg(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

/// Continuity: at random points on the faces between leaves, the values just on either side
/// agree.
fn assert_continuous(mesh: &StochasticMesh, v: &[f64], lo: &[f64], hi: &[f64], seed: &mut u64) {
    let d = lo.len();
    for c in mesh.leaves() {
        let (a, b) = mesh.cell_bounds(c);
        for j in 0..d {
            for side in [a[j], b[j]] {
                if side <= lo[j] || side >= hi[j] {
                    continue;
                }
                for _ in 0..4 {
                    let mut x: Vec<f64> =
                        (0..d).map(|i| a[i] + (b[i] - a[i]) * lcg(seed)).collect();
                    let eps = 1e-9 * (hi[j] - lo[j]);
                    x[j] = side - eps;
                    let left = mesh.eval(&x, v);
                    x[j] = side + eps;
                    let right = mesh.eval(&x, v);
                    assert!(
                        (left - right).abs() < 1e-6,
                        "jump {left} / {right} across x_{j} = {side} of cell {c}"
                    );
                }
            }
        }
    }
}

#[test]
fn centred_refinement_adds_one_run_per_cell_and_keeps_the_surrogate_elsewhere() {
    for d in [2usize, 3] {
        let lo = vec![-1.0; d];
        let hi: Vec<f64> = (0..d).map(|j| 2.0 + j as f64).collect();
        let mut mesh = StochasticMesh::new(&lo, &hi, &vec![1; d]).unwrap();
        assert_eq!(mesh.num_runs(), 1 << d);
        // Corners + centre, the thesis's start.
        let new = mesh.refine_centred(&mesh.leaves()).unwrap();
        assert_eq!(new.len(), 1);
        assert_eq!(mesh.num_runs(), (1 << d) + 1);
        let centre: Vec<f64> = lo.iter().zip(&hi).map(|(a, b)| 0.5 * (a + b)).collect();
        assert_eq!(new[0].point, centre);
        // A multilinear function is still reproduced exactly (the interpolated nodes hold its
        // values).
        let f = |x: &[f64]| {
            let mut p = 1.0;
            for (j, v) in x.iter().enumerate() {
                p *= 1.0 + (j as f64 + 1.0) * v;
            }
            p
        };
        let mut seed = 42;
        for _ in 0..3 {
            let leaves = mesh.leaves();
            let pick: Vec<usize> = leaves
                .iter()
                .copied()
                .filter(|_| lcg(&mut seed) < 0.4)
                .collect();
            let before = mesh.clone();
            let old = values(&before, |x| x.iter().map(|v| v.sin()).sum());
            let added = mesh.refine_centred(&pick).unwrap();
            assert_eq!(added.len(), pick.len(), "one run per refined cell");
            // Old runs keep their index; new ones get the old function's value perturbed:
            // nothing changes outside the refined cells.
            let mut v = old.clone();
            for r in &added {
                assert_eq!(r.run, v.len());
                v.push(before.eval(&r.point, &old) + 1.0);
            }
            for _ in 0..200 {
                let x: Vec<f64> = (0..d)
                    .map(|j| lo[j] + (hi[j] - lo[j]) * lcg(&mut seed))
                    .collect();
                let cell = before.locate(&x).unwrap();
                if pick.contains(&cell) {
                    continue;
                }
                assert!((mesh.eval(&x, &v) - before.eval(&x, &old)).abs() < 1e-12);
            }
            assert_continuous(&mesh, &v, &lo, &hi, &mut seed);
            let fv = values(&mesh, f);
            for _ in 0..100 {
                let x: Vec<f64> = (0..d)
                    .map(|j| lo[j] + (hi[j] - lo[j]) * lcg(&mut seed))
                    .collect();
                assert!((mesh.eval(&x, &fv) - f(&x)).abs() < 1e-9 * f(&x).abs().max(1.0));
            }
        }
        // The weights at a run point pick that run.
        let mut w = Vec::new();
        for k in 0..mesh.num_runs() {
            let x = mesh.run_point(k).to_vec();
            mesh.weights(&x, &mut w);
            let wk: f64 = w.iter().filter(|e| e.0 == k).map(|e| e.1).sum();
            assert!((wk - 1.0).abs() < 1e-12, "run {k} weight {wk}");
        }
    }
}

#[test]
fn a_run_at_one_point_refines_towards_it_with_interpolated_nodes() {
    let lo = [0.0, 0.0];
    let hi = [1.0, 2.0];
    let mut mesh = StochasticMesh::new(&lo, &hi, &[1, 1]).unwrap();
    mesh.refine_centred(&[0]).unwrap();
    let mut seed = 7;
    for depth in [1u32, 2, 3] {
        let leaves = mesh.leaves();
        let cell = leaves[(lcg(&mut seed) * leaves.len() as f64) as usize];
        let cands = mesh.sub_cell_centres(cell, depth).unwrap();
        assert_eq!(cands.len(), 2 * (1 << (2 * depth)));
        let q = (lcg(&mut seed) * (cands.len() / 2) as f64) as usize;
        let p = cands[2 * q..2 * q + 2].to_vec();
        let before = mesh.clone();
        let old = values(&before, |x| (3.0 * x[0]).cos() + x[1] * x[1]);
        let run = mesh.refine_at_point(&p).unwrap();
        assert_eq!(run.point, p);
        assert_eq!(run.run, before.num_runs());
        assert_eq!(
            mesh.num_runs(),
            before.num_runs() + 1,
            "exactly one new run"
        );
        // Giving the new run the old surrogate's value changes nothing anywhere.
        let mut v = old.clone();
        v.push(before.eval(&p, &old));
        for _ in 0..300 {
            let x = [lcg(&mut seed), 2.0 * lcg(&mut seed)];
            assert!((mesh.eval(&x, &v) - before.eval(&x, &old)).abs() < 1e-12);
        }
        v[run.run] += 1.0;
        assert!((mesh.eval(&p, &v) - before.eval(&p, &old) - 1.0).abs() < 1e-12);
        assert_continuous(&mesh, &v, &lo, &hi, &mut seed);
    }
    // A node of the mesh or a point on a split plane is refused.
    assert!(mesh.refine_at_point(&[0.5, 1.0]).is_err());
    assert!(mesh.refine_at_point(&[0.3, 1.0]).is_err());
}

#[test]
fn an_interpolated_node_becomes_a_run_and_the_surrogate_stays_continuous() {
    // Corners + centre, then the four quarters refined at their centres: the edge midpoints and
    // the quarter corners are interpolated for good. Promoting one of them makes it a run: the
    // surrogate then takes the run's value there, stays continuous, still reproduces bilinear
    // functions, and changes only on the leaves around the node.
    let (lo, hi) = (vec![0.0, 0.0], vec![2.0, 1.0]);
    let mut mesh = StochasticMesh::new(&lo, &hi, &[1, 1]).unwrap();
    mesh.refine_centred(&mesh.leaves()).unwrap();
    mesh.refine_centred(&mesh.leaves()).unwrap();
    assert_eq!(mesh.num_runs(), 9);
    let nodes = mesh.interpolated_nodes();
    // The 5 x 5 grid of quarter-cell corners less the 9 runs, all corners of every leaf
    // around them.
    assert_eq!(nodes.len(), 16, "{nodes:?}");
    assert!(nodes.iter().all(|n| n.1.is_none()));
    let f = |x: &[f64]| (x[0] - 0.3).abs() + x[1] * x[1];
    let before = mesh.clone();
    let vb = values(&before, f);
    let node = [1.0, 0.0];
    assert!(nodes.iter().any(|p| p.0 == node));
    let new = mesh.promote(&node).unwrap();
    assert_eq!((new.run, new.point.as_slice()), (9, &node[..]));
    assert!(mesh.promote(&node).is_err(), "already a run");
    assert!(mesh.promote(&[0.7, 0.3]).is_err(), "not a node");
    let v = values(&mesh, f);
    assert_eq!(mesh.eval(&node, &v), f(&node));
    let mut seed = 7;
    assert_continuous(&mesh, &v, &lo, &hi, &mut seed);
    let bilinear = |x: &[f64]| 1.0 + 2.0 * x[0] - x[1] + 0.5 * x[0] * x[1];
    let vbil = values(&mesh, bilinear);
    for _ in 0..200 {
        let x = [2.0 * lcg(&mut seed), lcg(&mut seed)];
        assert!((mesh.eval(&x, &vbil) - bilinear(&x)).abs() < 1e-12);
        // The quarters below y = 0.5 interpolate their own nodes from their corners, (1, 0)
        // among them; above, nothing changed.
        if x[1] > 0.5 {
            assert!(
                (mesh.eval(&x, &v) - before.eval(&x, &vb)).abs() < 1e-12,
                "{x:?}"
            );
        }
    }
    // A node on the edge of a coarser leaf follows that leaf's interpolant: it names the leaf
    // and cannot become a run before that leaf is refined.
    let mut mesh = StochasticMesh::new(&lo, &hi, &[1, 1]).unwrap();
    mesh.refine_centred(&mesh.leaves()).unwrap();
    let first = mesh.leaves()[0];
    mesh.refine_centred(&[first]).unwrap();
    let (a, b) = mesh.cell_bounds(first);
    let on_edge = vec![b[0], 0.5 * (a[1] + b[1])];
    let nodes = mesh.interpolated_nodes();
    let master = nodes.iter().find(|n| n.0 == on_edge).expect("a node").1;
    let master = master.expect("on the edge of the unrefined neighbour");
    assert!(mesh.is_leaf(master) && master != first);
    assert!(mesh.promote(&on_edge).is_err());
    mesh.refine_centred(&[master]).unwrap();
    mesh.promote(&on_edge).unwrap();
    let v = values(&mesh, f);
    assert_continuous(&mesh, &v, &lo, &hi, &mut seed);
}
