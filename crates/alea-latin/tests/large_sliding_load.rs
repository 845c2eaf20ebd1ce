//! Large sliding driven by a load (module `alea_latin::large_sliding`, issue 21): slides of
//! about 9 base cells driven by a traction instead of an imposed displacement. No prescribed
//! displacement predicts such a slide: the step's first solve is on the start configuration's
//! pairing, and its solution is the configuration the second pass is paired in.
//! - A block 210 times softer than the base, held at one end and stretched over the base by a
//!   pull on the other: 2 pairings (62 + 147 iterations), against the closed form.
//! - Ignored, **failing today** (LATIN, not the pairing): the same block 2 100 times softer than
//!   the base (3 469 iterations on the start pairing, then no convergence in 20 000), and a
//!   floating block in gross slip held by a bonded elastic layer, which does not converge even
//!   with small sliding and a slide of 5e-5 (20 000 iterations, "not converged", with or
//!   without the coarse problem or acceleration). So no predictor from a floating body's free
//!   rigid modes is built: there is no converged first solve to take its rigid translation from.
//!   Run them with `cargo test --release -p alea-latin --test large_sliding_load -- --ignored
//!   --nocapture`.
//!
//! Closed forms asserted (resultants, exact for any elastic stress field): the normal force on
//! the base is `N = P w` (`w = 1` the block's width), the friction force at most `mu N`, and
//! equal to it in gross slip.

mod common;

use alea_fem::{Constraints, Loads};
use alea_latin::large_sliding::{Repairing, SlidingStep, run_step};
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, RunInput, RunStatus, Sliding};
use alea_mesh::CellType;
use common::*;

const P: f64 = 10.0;
const MU: f64 = 0.2;
const H: f64 = 0.5;
/// Base cell size.
const CELL: f64 = 0.1;

fn options() -> LatinOptions {
    LatinOptions {
        tolerance: 1e-8,
        max_iterations: 20000,
        ..Default::default()
    }
}

/// Base `[0, 4] x [-1, 0]` clamped below, block `[1, 2] x [0, H]` pulled by `pull` (traction
/// along x on its right side), layer `[1, 2] x [H, 2 H]` of Young's modulus `soft`, top held in
/// x and pressed by `P`.
fn assembly(pull: f64, soft: f64) -> Assembly {
    let base = clamped_base();
    let block = {
        let m = model(rect(1.0, 0.0, 1.0, H, 12, 6, CellType::Quad4), 210e3, 0.3);
        with_load(sub("block", m, Constraints::new()), |m, ld: &mut Loads| {
            ld.traction(m, "xmax", |_, _| [pull, 0.0, 0.0]).unwrap();
        })
    };
    let layer = {
        let m = model(rect(1.0, H, 1.0, H, 12, 4, CellType::Quad4), soft, 0.3);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "ymax", 0, 0.0).unwrap();
        with_load(sub("layer", m, c), |m, ld: &mut Loads| {
            ld.traction(m, "ymax", |_, _| [0.0, -P, 0.0]).unwrap();
        })
    };
    let mut contact = InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", MU);
    contact.sliding = Sliding::Large;
    Assembly {
        subs: vec![base, block, layer],
        interfaces: vec![
            contact,
            InterfaceSpec::perfect("bond", 1, "ymax", 2, "ymin"),
        ],
    }
}

/// The block's slide: the mean x displacement of its bottom nodes.
fn slide(step: &SlidingStep) -> f64 {
    let m = &step.solver.model(1).mesh;
    let nodes = m.group_nodes("ymin").unwrap();
    let u = &step.result.displacements[1];
    nodes.iter().map(|&n| u[2 * n]).sum::<f64>() / nodes.len() as f64
}

/// Reports and checks one large-sliding step of a load-driven case.
fn check(name: &str, asm: &Assembly, gross_slip: bool) -> SlidingStep {
    let t0 = std::time::Instant::now();
    let step = run_step(
        asm,
        &options(),
        &Repairing::default(),
        None,
        &RunInput::default(),
    )
    .unwrap();
    let f = step.result.interfaces[0].resultant();
    eprintln!(
        "{name}: {} pairing(s), {} iterations, mismatch {:.2e}, {:.2} s; N = {}, T = {}, status {:?}",
        step.pairings,
        step.iterations,
        step.mismatch,
        t0.elapsed().as_secs_f64(),
        f[1],
        f[0],
        step.result.status
    );
    assert_eq!(step.result.status, RunStatus::Converged);
    assert!((f[1] - P).abs() < 5e-4 * P, "N = {}", f[1]);
    assert!(f[0].abs() <= MU * P * (1.0 + 5e-4), "T = {}", f[0]);
    if gross_slip {
        assert!((f[0].abs() - MU * P).abs() < 5e-4 * P, "T = {}", f[0]);
    }
    step
}

#[test]
#[ignore = "fails today: LATIN does not converge on a floating block in gross slip held by a bonded layer (issue 21)"]
fn a_floating_block_held_by_a_bonded_layer_in_gross_slip() {
    // Steel layer: slide (pull w H / 2 - mu N) / (G w / H) = 5e-5, small sliding suffices.
    let mut asm = assembly(20.0, 210e3);
    asm.interfaces[0].sliding = Sliding::Small;
    check("bonded layer, small sliding", &asm, true);
    // A soft layer (E = 100): the block slides about 8 cells.
    let step = check(
        "bonded soft layer, large sliding",
        &assembly(120.0, 100.0),
        true,
    );
    assert!(slide(&step) > 5.0 * CELL, "slide {}", slide(&step));
}

/// Block `[1, 2] x [0, H]` of modulus `e`, held in x on its left side, pressed by `P` on its
/// top and pulled by `pull` on its right side: it stretches over the base.
fn stretched(pull: f64, e: f64) -> Assembly {
    let base = clamped_base();
    let block = {
        let m = model(rect(1.0, 0.0, 1.0, H, 12, 6, CellType::Quad4), e, 0.3);
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "xmin", 0, 0.0).unwrap();
        with_load(sub("block", m, c), |m, ld: &mut Loads| {
            ld.traction(m, "xmax", |_, _| [pull, 0.0, 0.0]).unwrap();
            ld.traction(m, "ymax", |_, _| [0.0, -P, 0.0]).unwrap();
        })
    };
    let mut contact = InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", MU);
    contact.sliding = Sliding::Large;
    Assembly {
        subs: vec![base, block],
        interfaces: vec![contact],
    }
}

/// The base nodes loaded by more than 1e-9 N: their x range (initial coordinates).
fn loaded_range(step: &SlidingStep) -> [f64; 2] {
    let it = &step.result.interfaces[0];
    let nodes = it.pairing.sides[0].side_nodes();
    let forces = it.local_nodal_forces(0);
    let coords = &step.solver.model(0).mesh.coords;
    let mut range = [f64::INFINITY, f64::NEG_INFINITY];
    for (&a, f) in nodes.iter().zip(&forces) {
        if f[1].abs() > 1e-9 {
            range[0] = range[0].min(coords[a][0]);
            range[1] = range[1].max(coords[a][0]);
        }
    }
    range
}

/// A block 210 times softer than the base, held in x on its left side and stretched by a pull
/// on its right side: its right end slides 0.93 (9 base cells). The first solve (on the start
/// configuration's pairing) predicts the configuration of the second; 2 pairings settle.
/// Closed forms: `N = P w`, `|T| <= mu N`, and the base loaded under the stretched block,
/// `[1, 2 + u_R]` (`u_R` the mean x displacement of the block's right side) within one base
/// cell. The pairing of the initial configuration loads the base under `[1, 2]` only (checked,
/// so the test can fail).
#[test]
fn a_soft_block_stretched_over_nine_cells_by_a_load() {
    let step = check("stretched block", &stretched(1000.0, 1000.0), false);
    assert!(step.pairing_settled);
    assert_eq!(step.pairings, 2);
    // 62 + 147 iterations: the re-paired pass starts without the forces carried at the same
    // material points (module doc); with them it took 332 (394 in all).
    assert!(step.iterations <= 300, "{} iterations", step.iterations);
    let m = &step.solver.model(1).mesh;
    let right = m.group_nodes("xmax").unwrap();
    let u = &step.result.displacements[1];
    let ur = right.iter().map(|&n| u[2 * n]).sum::<f64>() / right.len() as f64;
    let range = loaded_range(&step);
    eprintln!("right end slid {ur}, loaded base x in {range:?}");
    assert!(ur > 8.0 * CELL, "right end {ur}");
    assert!((range[0] - 1.0).abs() <= CELL + 1e-9, "{range:?}");
    assert!(
        (range[1] - (2.0 + ur)).abs() <= CELL + 1e-9,
        "{range:?} vs {}",
        2.0 + ur
    );
    // Small sliding: the base is loaded under the block's initial footprint.
    let mut small = stretched(1000.0, 1000.0);
    small.interfaces[0].sliding = Sliding::Small;
    let solver = alea_latin::LatinSolver::new(small, options()).unwrap();
    let res = solver.run_shared(&RunInput::default()).unwrap();
    assert_eq!(res.status, RunStatus::Converged);
    let it = &res.interfaces[0];
    let nodes = it.pairing.sides[0].side_nodes();
    let forces = it.local_nodal_forces(0);
    let coords = &solver.model(0).mesh.coords;
    let far = nodes
        .iter()
        .zip(&forces)
        .filter(|(a, f)| f[1].abs() > 1e-9 && coords[**a][0] > 2.0 + CELL + 1e-9)
        .count();
    assert_eq!(
        far, 0,
        "small sliding loads the base beyond the initial footprint"
    );
}

#[test]
#[ignore = "fails today: with a block 2 100 times softer than the base, LATIN takes 3 469 iterations on the start pairing and the re-paired solve does not converge in 20 000 (issue 21)"]
fn a_very_soft_block_stretched_over_nine_cells() {
    let step = check("very soft stretched block", &stretched(100.0, 100.0), false);
    assert!(step.pairing_settled);
}
