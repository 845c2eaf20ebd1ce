//! The thesis's 3D turbine blade root / disk model (5.2.5, figure 5.17): the four-part 2D model
//! of [`turbine_2d`] (`Quad4` cells) extruded along the disk axis `z` over `depth` in `layers`
//! layers of `Hex8` cells ([`extrude`]).
//!
//! Every group of the 2D model is carried over: the cell groups `D1`, `D2`, `A1`, `A2`, the
//! contact faces `I1_disk`, `I1_root`, `I2_disk`, `I2_root`, the cut faces `D*_cut`, `A*_cut`,
//! and the boundary faces (`D*_side`, `D*_bottom`, `D*_fillet`, `A*_top`, ...), each as a
//! `Quad4` face group over all layers and as a node group. The end faces are the groups
//! `zmin` (z = 0, where the thesis blocks the out-of-plane displacement) and `zmax`. The contact
//! and cut faces keep coincident, distinct nodes layer by layer, ready for node-to-node
//! interfaces.
//!
//! Size: `N2 (layers + 1)` nodes for a 2D mesh of `N2` nodes (Quad4, so about one node per 2D
//! cell). Hexahedra are trilinear: the nodal von Mises stress on the curved fillet converges
//! like the cell size, as with `Quad4` in 2D (see the example's header for its mesh study).

use super::{TurbineParams, extrude, turbine_2d};
use crate::{CellType, Mesh, MeshError};

/// Meshes the four parts of [`turbine_2d`] (geometry and in-plane counts `p`) extruded over
/// `z in [0, depth]` in `layers` layers of `Hex8` cells.
///
/// # Errors
/// The errors of [`turbine_2d`] and [`extrude`] (zero layers, non-positive depth).
pub fn turbine_3d(p: &TurbineParams, depth: f64, layers: usize) -> Result<Mesh, MeshError> {
    let plane = turbine_2d(p, CellType::Quad4)?;
    extrude(&plane, layers, depth)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::test_checks::{assert_coincident, group_measure};

    #[test]
    fn extruded_turbine_has_coincident_interfaces_and_the_prism_volume() {
        let p = TurbineParams {
            n_flank: 4,
            n_runout: 2,
            n_fillet: 4,
            n_lobe: 3,
            n_slot: 2,
            n_below: 3,
            n_root: 3,
            n_shank: 3,
            ..TurbineParams::default()
        };
        let plane = turbine_2d(&p, CellType::Quad4).unwrap();
        let (depth, layers) = (12.0, 3);
        let m = turbine_3d(&p, depth, layers).unwrap();
        assert_eq!(m.dim, 3);
        assert_eq!(m.num_nodes(), plane.num_nodes() * (layers + 1));
        assert_eq!(m.num_cells(), plane.num_cells() * layers);
        for g in ["D1", "D2", "A1", "A2"] {
            let vol = group_measure(&m, g);
            let area = group_measure(&plane, g);
            assert!(
                (vol - depth * area).abs() < 1e-9 * vol,
                "{g}: {vol} vs {area}"
            );
        }
        for c in 0..m.num_cells() {
            assert!(m.cell_min_jacobian(c) > 0.0);
        }
        for (s1, s2) in [
            ("I1_disk", "I1_root"),
            ("I2_disk", "I2_root"),
            ("D1_cut", "D2_cut"),
            ("A1_cut", "A2_cut"),
        ] {
            assert_coincident(&m, s1, s2, 1e-9, false);
            assert_eq!(
                m.facet_group(s1).unwrap().len(),
                plane.facet_group(s1).unwrap().len() * layers
            );
        }
        for g in ["zmin", "zmax", "D2_fillet", "A2_top", "D1_bottom"] {
            assert!(!m.facet_group(g).unwrap().is_empty(), "{g}");
        }
        assert!(turbine_3d(&p, depth, 0).is_err());
        assert!(turbine_3d(&p, -1.0, 2).is_err());
    }
}
