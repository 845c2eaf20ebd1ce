//! Constraint frames of the nodes and the reaction projectors of boundary sides (thesis
//! 3.1.1.4 b with skew constraints): the node systems (3.22) are written per direction of each
//! node's frame (free directions, then constrained ones); on a boundary side the traction in a
//! direction `q` constrained at all its nodes is a reaction (an unknown of the node systems),
//! so prescribed data there are projected by `P = I - sum q q^T`.

use alea_fem::DofMap;

use super::topology::SideTopology;
use super::vector::{Frame, dot, identity};

/// Per node: orthonormal frame and number of free directions.
pub(crate) fn node_frames<T: SideTopology<D>, const D: usize>(
    dofs: &DofMap,
    nn: usize,
) -> Vec<Frame<D>> {
    let mut scratch = vec![0.0; dofs.num_free()];
    (0..nn)
        .map(|n| {
            if dofs.is_free_node(n) {
                return (identity(), D);
            }
            let r = dofs.node_dofs(n);
            let nf = r.len();
            let mut free = [[0.0; D]; D];
            for c in 0..D {
                let mut v = [0.0; 3];
                v[c] = 1.0;
                dofs.add_node_force(n, &v, &mut scratch);
                for (i, g) in r.clone().enumerate() {
                    free[i][c] = scratch[g];
                    scratch[g] = 0.0;
                }
            }
            T::complete_frame(free, nf)
        })
        .collect()
}

/// True if direction `d` is constrained at a node with frame `f`.
pub(crate) fn constrained<const D: usize>(f: &Frame<D>, d: [f64; D]) -> bool {
    let free_part: f64 = (0..f.1).map(|k| dot(f.0[k], d).powi(2)).sum();
    free_part < 1e-12
}

/// True if direction `d` is constrained at every node of side `s`.
pub(crate) fn constrained_on_side<T: SideTopology<D>, const D: usize>(
    topo: &T,
    frames: &[Frame<D>],
    s: usize,
    d: [f64; D],
) -> bool {
    topo.side_nodes(s).all(|nd| constrained(&frames[nd], d))
}

/// Projector `P = I - sum q q^T` of boundary side `s` over the directions `q` constrained at
/// all its nodes (the traction there is a reaction, not data).
pub(crate) fn side_projector<T: SideTopology<D>, const D: usize>(
    topo: &T,
    frames: &[Frame<D>],
    s: usize,
) -> [[f64; D]; D] {
    let first = topo.side_nodes(s).next().unwrap_or(0);
    let fa = &frames[first];
    let mut p = identity();
    for k in fa.1..D {
        let q = fa.0[k];
        if constrained_on_side(topo, frames, s, q) {
            for i in 0..D {
                for j in 0..D {
                    p[i][j] -= q[i] * q[j];
                }
            }
        }
    }
    p
}
