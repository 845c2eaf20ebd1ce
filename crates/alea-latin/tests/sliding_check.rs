//! The small-sliding check (module `alea_latin::sliding`): a block pressed on a base and moved
//! by an imposed displacement of its top, slightly (1 % of a cell: below the limit) and over
//! three cells (beyond: flagged at the point that slid most, with the slip of the block's
//! rigid slide).

mod common;

use alea_fem::{Constraints, Loads};
use alea_latin::sliding::{SMALL_SLIDING_LIMIT, slide_checks};
use alea_latin::{Assembly, InterfaceSpec, LatinOptions, LatinSolver, RunInput, RunStatus};
use alea_mesh::CellType;
use common::*;

fn solver(d: f64, thickness_2: bool) -> LatinSolver {
    let mk = |m: alea_mesh::Mesh| {
        let mut md = model(m, 210e3, 0.3);
        if thickness_2 {
            md.analysis = alea_fem::Analysis::PlaneStrain { thickness: 2.0 };
        }
        md
    };
    let base = {
        let m = mk(rect(0.0, -10.0, 20.0, 10.0, 20, 10, CellType::Quad4));
        let mut c = Constraints::new();
        c.clamp(&m.mesh, "ymin").unwrap();
        sub("base", m, c)
    };
    let block = {
        let m = mk(rect(0.0, 0.0, 20.0, 10.0, 20, 10, CellType::Quad4));
        let mut c = Constraints::new();
        c.fix_component(&m.mesh, "ymax", 0, d).unwrap();
        with_load(sub("block", m, c), |m, ld: &mut Loads| {
            ld.traction(m, "ymax", |_, _| [0.0, -10.0, 0.0]).unwrap();
        })
    };
    LatinSolver::new(
        Assembly {
            subs: vec![base, block],
            interfaces: vec![InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", 0.3)],
        },
        LatinOptions {
            tolerance: 1e-8,
            max_iterations: 20000,
            ..Default::default()
        },
    )
    .unwrap()
}

#[test]
fn a_slide_over_several_cells_is_flagged_and_a_small_one_is_not() {
    for thick in [false, true] {
        for (d, beyond) in [(0.01, false), (3.0, true)] {
            let s = solver(d, thick);
            let r = s.run_shared(&RunInput::default()).unwrap();
            assert_eq!(r.status, RunStatus::Converged);
            let checks = slide_checks(&s, &r);
            assert_eq!(checks.len(), 1);
            let c = checks[0];
            eprintln!("d = {d}, thickness 2: {thick}: {c:?}");
            assert_eq!(c.beyond_small_sliding(), beyond, "{c:?}");
            // Cells of size 1: h = 1 inside, 1/2 at the two end points (their share).
            assert!(
                (c.h - 1.0).abs() < 1e-12 || (c.h - 0.5).abs() < 1e-12,
                "h = {}",
                c.h
            );
            // The block slides rigidly by d less its elastic shear.
            assert!(c.slip < d && c.slip > 0.5 * d, "slip {} vs {d}", c.slip);
            assert!((c.ratio - c.slip / c.h).abs() < 1e-12);
            if beyond {
                assert!(c.ratio > 4.0 * SMALL_SLIDING_LIMIT);
            }
        }
    }
}
