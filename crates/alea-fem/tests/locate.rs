//! Point location (`alea_fem::locate`) against what it must find:
//! - on distorted meshes of every 2D cell type (corner jitter; curved edges for Tri6 / Quad8),
//!   random reference points of random cells are mapped to physical points and located again:
//!   the same physical point comes back (`x(xi) = x` to 1e-10 of the cell size), in the cell it
//!   came from or in a neighbour whose closure also holds it (shared edges), with `xi` inside
//!   the reference cell;
//! - on a structured mesh, a grid of points is located in the cell a brute-force search over
//!   every cell finds, and points outside return `None`;
//! - points just outside a boundary are placed by `locate_nearest` on the boundary at the right
//!   distance, and refused beyond the given distance.

use alea_fem::PointLocator;
use alea_fem::reference::{MAX_NODES, shape};
use alea_mesh::generate::rectangle;
use alea_mesh::{CellType, Mesh};

fn lcg(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

/// The rectangle `[0, 4] x [0, 3]` with interior corner nodes jittered by up to 15 % of a
/// cell; the mid-side nodes of quadratic cells sit at their edge's midpoint moved by up to 4 %
/// of a cell across it (curved edges), a smooth function of the position so that both cells of
/// an edge agree.
fn distorted(kind: CellType, seed: &mut u64) -> Mesh {
    let (nx, ny) = (8, 6);
    let mut mesh = rectangle(4.0, 3.0, nx, ny, kind).unwrap();
    let h = 0.5;
    let corners = match kind {
        CellType::Tri6 => 3,
        CellType::Quad8 => 4,
        _ => kind.num_nodes(),
    };
    let interior =
        |x: [f64; 3]| x[0] > 1e-9 && x[0] < 4.0 - 1e-9 && x[1] > 1e-9 && x[1] < 3.0 - 1e-9;
    let mut is_corner = vec![false; mesh.num_nodes()];
    for c in 0..mesh.num_cells() {
        for &n in &mesh.cell_nodes(c)[..corners] {
            is_corner[n] = true;
        }
    }
    for (n, x) in mesh.coords.iter_mut().enumerate() {
        if is_corner[n] && interior(*x) {
            x[0] += 0.15 * h * (2.0 * lcg(seed) - 1.0);
            x[1] += 0.15 * h * (2.0 * lcg(seed) - 1.0);
        }
    }
    for c in 0..mesh.num_cells() {
        let nodes = mesh.cell_nodes(c).to_vec();
        for (e, &mid) in nodes[corners..].iter().enumerate() {
            let (a, b) = (mesh.coords[nodes[e]], mesh.coords[nodes[(e + 1) % corners]]);
            let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
            let bulge = if interior(mesh.coords[mid]) {
                0.04 * h
            } else {
                0.0
            };
            let (tx, ty) = (b[0] - a[0], b[1] - a[1]);
            let len = (tx * tx + ty * ty).sqrt();
            let amp = bulge * (3.0 * m[0] + 2.0 * m[1]).sin();
            mesh.coords[mid] = [m[0] - amp * ty / len, m[1] + amp * tx / len, 0.0];
        }
    }
    mesh
}

fn map(mesh: &Mesh, c: usize, xi: [f64; 2]) -> [f64; 2] {
    let mut n = [0.0; MAX_NODES];
    let mut dn = [[0.0; 3]; MAX_NODES];
    shape(mesh.cell_type(c), [xi[0], xi[1], 0.0], &mut n, &mut dn);
    let mut p = [0.0; 2];
    for (i, &node) in mesh.cell_nodes(c).iter().enumerate() {
        p[0] += n[i] * mesh.coords[node][0];
        p[1] += n[i] * mesh.coords[node][1];
    }
    p
}

fn random_reference(kind: CellType, seed: &mut u64) -> [f64; 2] {
    if matches!(kind, CellType::Quad4 | CellType::Quad8) {
        [2.0 * lcg(seed) - 1.0, 2.0 * lcg(seed) - 1.0]
    } else {
        let (r, s) = (lcg(seed), lcg(seed));
        if r + s > 1.0 {
            [1.0 - r, 1.0 - s]
        } else {
            [r, s]
        }
    }
}

fn inside(kind: CellType, xi: [f64; 3]) -> bool {
    let tol = 1e-9;
    if matches!(kind, CellType::Quad4 | CellType::Quad8) {
        xi[0].abs() <= 1.0 + tol && xi[1].abs() <= 1.0 + tol
    } else {
        xi[0] >= -tol && xi[1] >= -tol && xi[0] + xi[1] <= 1.0 + tol
    }
}

#[test]
fn random_points_of_distorted_cells_are_found_again() {
    let mut seed = 42;
    for kind in [
        CellType::Tri3,
        CellType::Tri6,
        CellType::Quad4,
        CellType::Quad8,
    ] {
        let mesh = distorted(kind, &mut seed);
        let loc = PointLocator::new(&mesh).unwrap();
        let mut same_cell = 0;
        let trials = 2000;
        for _ in 0..trials {
            let c = (lcg(&mut seed) * mesh.num_cells() as f64) as usize;
            let xi = random_reference(kind, &mut seed);
            let x = map(&mesh, c, xi);
            let l = loc
                .locate([x[0], x[1], 0.0])
                .unwrap_or_else(|| panic!("{kind}: {x:?} of cell {c} not found"));
            assert!(inside(kind, l.xi), "{kind}: {:?}", l.xi);
            let back = map(&mesh, l.cell, [l.xi[0], l.xi[1]]);
            let err = ((back[0] - x[0]).powi(2) + (back[1] - x[1]).powi(2)).sqrt();
            assert!(err < 1e-10 * 0.5, "{kind}: x(xi) misses x by {err}");
            assert!(l.distance < 1e-10);
            if l.cell == c {
                same_cell += 1;
                let d = (l.xi[0] - xi[0]).abs().max((l.xi[1] - xi[1]).abs());
                assert!(d < 1e-9, "{kind}: xi {:?} instead of {xi:?}", l.xi);
            }
        }
        // Only points on (or within round-off of) a shared edge may go to the neighbour.
        assert!(
            same_cell > trials * 99 / 100,
            "{kind}: {same_cell} of {trials}"
        );
    }
}

#[test]
fn grid_points_match_a_brute_force_search_and_outside_points_are_refused() {
    for kind in [CellType::Quad4, CellType::Tri3] {
        let mesh = rectangle(2.0, 1.0, 7, 5, kind).unwrap();
        let loc = PointLocator::new(&mesh).unwrap();
        for i in 0..=40 {
            for j in 0..=20 {
                // Off the cell edges (0.01 shifts), so that the cell is unique.
                let x = [
                    0.013 + 1.97 * i as f64 / 40.0,
                    0.007 + 0.98 * j as f64 / 20.0,
                    0.0,
                ];
                let brute: Vec<usize> = (0..mesh.num_cells())
                    .filter(|&c| {
                        let (xi, ok) = loc.inverse_map(c, x);
                        ok && inside(kind, [xi[0], xi[1], 0.0])
                    })
                    .collect();
                assert_eq!(brute.len(), 1, "{kind}: {x:?} in {brute:?}");
                assert_eq!(
                    loc.locate(x).map(|l| l.cell),
                    Some(brute[0]),
                    "{kind}: {x:?}"
                );
            }
        }
        for x in [
            [-0.01, 0.5, 0.0],
            [2.01, 0.5, 0.0],
            [1.0, -1e-3, 0.0],
            [5.0, 5.0, 0.0],
        ] {
            assert!(loc.locate(x).is_none(), "{kind}: {x:?} is outside");
        }
    }
}

#[test]
fn points_just_outside_are_placed_on_the_boundary() {
    let mesh = rectangle(2.0, 1.0, 6, 4, CellType::Quad8).unwrap();
    let loc = PointLocator::new(&mesh).unwrap();
    for (x, foot) in [
        ([-0.002, 0.4, 0.0], [0.0, 0.4]),
        ([1.3, 1.0015, 0.0], [1.3, 1.0]),
        ([2.001, 0.05, 0.0], [2.0, 0.05]),
    ] {
        let l = loc.locate_nearest(x, 0.01).expect("within reach");
        let p = map(&mesh, l.cell, [l.xi[0], l.xi[1]]);
        assert!(
            (p[0] - foot[0]).abs() < 1e-12 && (p[1] - foot[1]).abs() < 1e-12,
            "{p:?}"
        );
        let d = ((x[0] - foot[0]).powi(2) + (x[1] - foot[1]).powi(2)).sqrt();
        assert!((l.distance - d).abs() < 1e-12);
        assert!(loc.locate_nearest(x, 0.5 * d).is_none());
    }
    // Inside points come back unchanged.
    let l = loc.locate_nearest([0.7, 0.3, 0.0], 0.01).unwrap();
    assert_eq!(l.distance, loc.locate([0.7, 0.3, 0.0]).unwrap().distance);
}

#[test]
fn three_dimensional_meshes_are_refused() {
    let mesh = alea_mesh::generate::box_mesh([1.0; 3], [2; 3], CellType::Hex8).unwrap();
    assert!(PointLocator::new(&mesh).is_err());
}
