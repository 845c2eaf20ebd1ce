//! Cyclic symmetry, zero harmonic: a perfect interface whose side 2 is the image of side 1 by
//! the rotation `x -> c + R (x - c)` of the sector angle about an axis through a centre
//! (a disk sector's two faces `A` = side 1 and `B` = side 2).
//!
//! # Equations
//! The zero-harmonic solution of a cyclically symmetric structure under a load repeated in
//! every sector is the same in every sector up to the rotation: on the sector's faces
//!
//! ```text
//! u(B) = R u(A),      F_B = -R F_A      (R x_A = x_B - c + R c),
//! ```
//! (`F_s` the traction on the sector through face `s`). This is the perfect interface law in
//! the frame of side 1: with the side-2 quantities rotated back, `W'_2 = R^T W_2`,
//! `F'_2 = R^T F_2`, the law reads `W'_2 = W_1`, `F_1 + F'_2 = 0` (module [`crate::law`]).
//!
//! # Implementation
//! - **Pairing** (module [`crate::interface`], [`crate::mortar`]): side 2's mesh is mapped back
//!   by the inverse rotation, `x -> c + R^T (x - c)`, onto side 1, and the two sides are paired
//!   as any perfect interface (node to node when they match, dual mortar otherwise; the
//!   projections `Pi_s` are scalar, so they do not depend on the frame). The pairing records
//!   `R` ([`crate::InterfacePairing::rotation`]). At set-up the mapped faces must cover each
//!   other: every side-1 node within the matching tolerance of a side-2 node (node to node),
//!   or, for a mortar pairing, each side's area covered by the other to `1e-3` relative and the
//!   normal distance between them at most [`mortar_gap_tolerance`] (otherwise
//!   [`crate::LatinError::Cyclic`]).
//! - **Fields**: every side's `(W_s, F_s, W_hat_s, F_hat_s)` is stored in its own
//!   substructure's frame, the one its linear stage works in: the linear stage, the condensed
//!   operators, the equilibrium checks and the nodal forces of a side are unchanged.
//! - **Local stage** (module `solver::local_stage`): side 2's `W_2, F_2` are rotated into
//!   side 1's frame (`R^T`), the perfect law's closed form applied, and side 2's `W_hat_2`,
//!   `F_hat_2` rotated back (`R`). A cyclic interface is perfect, so its search direction is
//!   isotropic, `k I`, which commutes with `R`: the search directions and the error indicator's
//!   norms are the same in either frame.
//! - **Coarse problem** (module [`crate::coarse`]): the macro basis of side 2 is side 1's
//!   rotated, `e_j^(2)(p) = R e_j(p)` (a rigid mode rotated is the image's rigid mode), so the
//!   macro constraint is `E^T (M_1 F_1 + M_2 R^T F_2) = 0`, the rotated resultant and moment.
//! - **Outputs**: the jump `[W] = R^T W_2 - W_1` and the force `R^T F_hat_2` of an interface
//!   point are given in side 1's frame ([`crate::InterfaceResult::jump`]); the nodal forces of
//!   each side in its own frame.
//!
//! Both sides may belong to the same substructure (a single sector: its two faces joined by
//! the interface): each side is one link of the substructure and nothing in the iteration
//! assumes two different substructures. The faces must then be disjoint (no node on both, as
//! in a ring sector; a sector that reaches its axis is refused): a node on both faces would
//! need `u = R u`, which the iteration can only approach.

use alea_mesh::Mesh;

use crate::interface::{InterfacePairing, side_geometry};
use crate::{InterfaceSpec, LatinError, Sliding, Substructure};

pub use crate::rotation::{Cyclic, Mat3, apply, apply_transpose, check_angle};

/// The largest normal distance between the mapped faces of a mortar-paired cyclic interface:
/// `1e-3` of the interface size, or the interface's matching tolerance when given.
pub fn mortar_gap_tolerance(size: f64, tolerance: Option<f64>) -> f64 {
    tolerance.unwrap_or(1e-3 * size)
}

/// The checks of a cyclic interface before its pairing: a perfect law in small sliding, in 2D
/// an axis along `z`, and, when both faces belong to one substructure, faces with no common
/// node.
pub(crate) fn check_spec(spec: &InterfaceSpec, subs: &[Substructure]) -> Result<(), LatinError> {
    let Some(c) = &spec.cyclic else {
        return Ok(());
    };
    let fail = |message: String| LatinError::Cyclic {
        interface: spec.name.clone(),
        message,
    };
    if spec.law.name() != "perfect" {
        return Err(fail(format!(
            "applies to perfect interfaces only, not to law '{}'",
            spec.law.name()
        )));
    }
    if spec.sliding != Sliding::Small {
        return Err(fail("applies to small sliding only".into()));
    }
    let mesh = &subs[spec.sub1].model.mesh;
    if mesh.dim == 2 && (c.axis[0] != 0.0 || c.axis[1] != 0.0) {
        return Err(fail(format!(
            "a 2D model rotates about the z axis ([0, 0, 1] or [0, 0, -1]), got {:?}",
            c.axis
        )));
    }
    if spec.sub1 == spec.sub2 {
        let nodes = |g: &str| -> Result<Vec<usize>, LatinError> {
            let sg = side_geometry(mesh, g, 1.0).map_err(|e| fail(e.to_string()))?;
            Ok(sg.nodes)
        };
        let (a, b) = (nodes(&spec.group1)?, nodes(&spec.group2)?);
        if let Some(n) = a.iter().find(|n| b.binary_search(n).is_ok()) {
            return Err(fail(format!(
                "both faces are on substructure '{}' and share node {n} at {:?} (a sector \
                 reaching its axis): the faces of a single-substructure sector must be disjoint",
                subs[spec.sub1].name, mesh.coords[*n]
            )));
        }
    }
    Ok(())
}

/// A copy of `mesh` with every node mapped back by the inverse rotation, `c + R^T (x - c)`.
pub(crate) fn mapped_back(c: &Cyclic, mesh: &Mesh) -> Mesh {
    let mut m = mesh.clone();
    for x in m.coords.iter_mut() {
        *x = c.unmap_point(x);
    }
    m
}

/// An error of the pairing of a cyclic interface's faces, as a [`LatinError::Cyclic`].
pub(crate) fn pairing_error(spec: &InterfaceSpec, e: LatinError) -> LatinError {
    if spec.cyclic.is_none() {
        return e;
    }
    let message = match e {
        LatinError::Unmatched {
            side1,
            side2,
            worst,
            at,
            tol,
            ..
        } => format!(
            "side 1 mapped by the rotation does not fall on side 2 node to node ({side1} and \
             {side2} nodes; a side-1 node is {worst:e} from the nearest mapped side-2 node at \
             {at:?}, tolerance {tol:e})"
        ),
        LatinError::Pairing { message, .. } => {
            format!("side 1 mapped by the rotation does not face side 2 ({message})")
        }
        other => return other,
    };
    LatinError::Cyclic {
        interface: spec.name.clone(),
        message,
    }
}

/// Checks that the mortar-paired faces of a cyclic interface cover each other (each side's
/// area within `1e-3` of the covered area, normal distances within [`mortar_gap_tolerance`]),
/// then records the rotation and clears the geometric gap (a perfect law's gap is 0).
/// `sides`: the two faces' `(mesh, group, thickness)`, side 2's mapped back.
pub(crate) fn finish(
    spec: &InterfaceSpec,
    mut pairing: InterfacePairing,
    sides: [(&Mesh, &str, f64); 2],
) -> Result<InterfacePairing, LatinError> {
    let Some(c) = &spec.cyclic else {
        return Ok(pairing);
    };
    let fail = |message: String| LatinError::Cyclic {
        interface: spec.name.clone(),
        message,
    };
    if pairing.kind == crate::PairingKind::Mortar {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut area = [0.0; 2];
        for (s, (mesh, group, th)) in sides.iter().enumerate() {
            let g = side_geometry(mesh, group, *th).map_err(|e| fail(e.to_string()))?;
            area[s] = g.weights.iter().sum();
            for &n in &g.nodes {
                for k in 0..3 {
                    lo[k] = lo[k].min(mesh.coords[n][k]);
                    hi[k] = hi[k].max(mesh.coords[n][k]);
                }
            }
        }
        let size = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        let covered: f64 = pairing.weights.iter().sum();
        for (s, a) in area.iter().enumerate() {
            if !((covered - a).abs() <= 1e-3 * a) {
                return Err(fail(format!(
                    "the faces mapped by the rotation overlap on {covered:e} of side {}'s \
                     area {a:e}: they do not map onto each other",
                    s + 1
                )));
            }
        }
        let tol = mortar_gap_tolerance(size, spec.match_tolerance);
        let worst = pairing
            .geometric_gap
            .iter()
            .fold(0.0f64, |m, g| m.max(g.abs()));
        if !(worst <= tol) {
            return Err(fail(format!(
                "side 1 mapped by the rotation is {worst:e} from side 2's surface, more than \
                 the tolerance {tol:e}"
            )));
        }
    }
    pairing.geometric_gap.fill(0.0);
    pairing.rotation = Some(c.matrix());
    Ok(pairing)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_maps_and_unmaps() {
        let c = Cyclic::new(30.0, [1.0, 2.0, 0.0], [0.0, 0.0, 2.0]).unwrap();
        let x = [3.0, 2.0, 0.5];
        let y = c.map_point(&x);
        let want = [
            1.0 + 2.0 * 0.5f64.sqrt() * 0.0 + 2.0 * (30f64.to_radians()).cos(),
            2.0 + 2.0 * (30f64.to_radians()).sin(),
            0.5,
        ];
        for k in 0..3 {
            assert!((y[k] - want[k]).abs() < 1e-14, "{y:?} vs {want:?}");
        }
        let back = c.unmap_point(&y);
        for k in 0..3 {
            assert!((back[k] - x[k]).abs() < 1e-14);
        }
        let r = c.matrix();
        let v = [0.3, -1.0, 2.0];
        let w = apply_transpose(&r, &apply(&r, &v));
        for k in 0..3 {
            assert!((w[k] - v[k]).abs() < 1e-14);
        }
        for bad in [0.0, -10.0, 181.0, f64::NAN, f64::INFINITY] {
            assert!(
                Cyclic::new(bad, [0.0; 3], [0.0, 0.0, 1.0]).is_err(),
                "{bad}"
            );
        }
        assert!(Cyclic::new(180.0, [0.0; 3], [0.0, 0.0, 1.0]).is_ok());
        assert!(Cyclic::new(10.0, [0.0; 3], [0.0; 3]).is_err());
    }
}
