//! The load case shared by the alea-fem benches: the model clamped on its `xmin` group and
//! loaded by a uniform traction (100, 10, 0) MPa on its `xmax` group.

use alea_fem::{Constraints, Loads, Model};

/// The constraints and loads of the benches' cantilever case on `model`.
pub fn cantilever(model: &Model) -> (Constraints, Loads) {
    let mut cons = Constraints::new();
    cons.clamp(&model.mesh, "xmin").unwrap();
    let mut loads = Loads::new(model);
    loads
        .traction(model, "xmax", |_, _| [100.0, 10.0, 0.0])
        .unwrap();
    (cons, loads)
}
