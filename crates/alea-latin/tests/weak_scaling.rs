//! Weak scaling of the two-scale LATIN (issue 38): a block of `a x b x c` unit cubes, each a
//! substructure of the same size (`4 x 4 x 4` Hex8 cells), joined by perfect interfaces to
//! their neighbours, clamped on `z = 0` and loaded on top by a traction with a shear part, from
//! 4 to 64 substructures.
//!
//! ```text
//!        traction (0.3, 0.2, -1) on z = c
//!      +----+----+----+
//!     /    /    /    /|      a x b x c cubes; every cube is one substructure; every
//!    +----+----+----+ |      shared face a perfect interface (node to node)
//!    |    |    |    | +
//!    |    |    |    |/
//!    +----+----+----+        clamped on z = 0
//! ```
//! The coarse problem balances every substructure's interface resultants and moments at each
//! iteration, which is what should keep the iteration count flat as substructures are added
//! (Ladeveze & Dureisseix 2000); the issue's target is at most 1.5x from 4 to 64 substructures.
//!
//! Checked: every block converges (tolerance 1e-6, the studies' order), its answer equals one
//! FE mesh of the whole block (relative energy of the difference below 1e-8 at tolerance
//! 1e-10 on the 8-cube block), and the iteration counts are printed with their ratio (asserted
//! below the measured value with a margin: BENCHMARKS.md "Weak scaling").

mod common;

use alea_fem::{Constraints, Loads, Ordering, solve_elastic};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunResult, RunStatus,
    Substructure,
};
use alea_mesh::CellType;
use common::*;

const E: f64 = 1000.0;
const CELLS: usize = 4;
const TRACTION: [f64; 3] = [0.3, 0.2, -1.0];

fn block(dims: [usize; 3]) -> Assembly {
    let [a, b, c] = dims;
    let index = |i: usize, j: usize, k: usize| (k * b + j) * a + i;
    let mut subs: Vec<Substructure> = Vec::with_capacity(a * b * c);
    for k in 0..c {
        for j in 0..b {
            for i in 0..a {
                let m = solid(
                    cuboid(
                        [i as f64, j as f64, k as f64],
                        [1.0; 3],
                        [CELLS; 3],
                        CellType::Hex8,
                    ),
                    E,
                    0.3,
                );
                let mut con = Constraints::new();
                if k == 0 {
                    con.clamp(&m.mesh, "zmin").unwrap();
                }
                let s = sub(&format!("s{i}_{j}_{k}"), m, con);
                subs.push(if k == c - 1 {
                    with_load(s, |m, l| {
                        l.traction(m, "zmax", |_, _| TRACTION).unwrap();
                    })
                } else {
                    s
                });
            }
        }
    }
    let mut interfaces = Vec::new();
    for k in 0..c {
        for j in 0..b {
            for i in 0..a {
                let s = index(i, j, k);
                let mut tie = |t: usize, g1: &str, g2: &str| {
                    interfaces.push(InterfaceSpec::perfect(&format!("{s}-{t}"), s, g1, t, g2))
                };
                if i + 1 < a {
                    tie(index(i + 1, j, k), "xmax", "xmin");
                }
                if j + 1 < b {
                    tie(index(i, j + 1, k), "ymax", "ymin");
                }
                if k + 1 < c {
                    tie(index(i, j, k + 1), "zmax", "zmin");
                }
            }
        }
    }
    Assembly { subs, interfaces }
}

fn solve(asm: &Assembly, tolerance: f64) -> RunResult {
    let mut s = LatinSolver::new(
        asm.clone(),
        LatinOptions {
            tolerance,
            max_iterations: 2000,
            coarse: true,
            ..Default::default()
        },
    )
    .unwrap();
    s.run(&RunInput::default()).unwrap()
}

/// The relative energy of the difference between the substructures' displacements and one FE
/// mesh of the whole block.
fn energy_error(dims: [usize; 3], asm: &Assembly, r: &RunResult) -> f64 {
    let l = dims.map(|d| d as f64);
    let whole = solid(
        cuboid([0.0; 3], l, dims.map(|d| d * CELLS), CellType::Hex8),
        E,
        0.3,
    );
    let mut c = Constraints::new();
    c.clamp(&whole.mesh, "zmin").unwrap();
    let mut loads = Loads::new(&whole);
    loads.traction(&whole, "zmax", |_, _| TRACTION).unwrap();
    let sol = solve_elastic(&whole, &c, &loads, Ordering::Metis).unwrap();
    relative_energy_error(&whole.mesh, &sol.u, &asm.subs, &r.displacements)
}

#[test]
fn the_block_of_cubes_equals_one_mesh_of_it() {
    let dims = [2, 2, 2];
    let asm = block(dims);
    let r = solve(&asm, 1e-10);
    assert_eq!(r.status, RunStatus::Converged);
    let e = energy_error(dims, &asm, &r);
    assert!(e < 1e-8, "relative energy of the difference {e}");
}

#[test]
fn iterations_grow_little_from_4_to_64_substructures() {
    let mut counts = Vec::new();
    for dims in [
        [2, 2, 1],
        [2, 2, 2],
        [4, 2, 2],
        [3, 3, 3],
        [4, 4, 2],
        [4, 4, 4],
    ] {
        let asm = block(dims);
        let t = std::time::Instant::now();
        let r = solve(&asm, 1e-6);
        assert_eq!(r.status, RunStatus::Converged, "{dims:?}");
        eprintln!(
            "{:?}: {} substructures, {} interfaces, {} iterations, {:.2} s",
            dims,
            asm.subs.len(),
            asm.interfaces.len(),
            r.iterations,
            t.elapsed().as_secs_f64()
        );
        counts.push(r.iterations);
    }
    let ratio = *counts.last().unwrap() as f64 / counts[0] as f64;
    eprintln!("iterations {counts:?}; 64 / 4 substructures: {ratio:.2}");
    assert!(ratio <= 1.5, "{counts:?}");
}
