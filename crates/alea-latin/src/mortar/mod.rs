//! Mortar pairing of non-matching interface sides: dual mortar with segment-to-segment
//! integration, 2D and 3D, small sliding.
//!
//! # Variant
//! The interface fields `(W_s, F_s, W_hat_s, F_hat_s)` live on the **multiplier nodes** of one
//! side, the *point side*: the nodes of its facets (for `Tri6` facets only the corners). Below,
//! "side 1" is the point side and "side 2" the other one; [`pair_mortar`] pairs both ways and
//! keeps the way with fewer points - the **coarser side carries the points** - and returns the
//! result in the user's conventions (normals outward of the user's side 1). The reason is the
//! LATIN iteration, not the accuracy (both choices are optimal mortar discretisations): the
//! other side sees the point values only through `Pi_2`, and where it is coarser than the point
//! side the components of `W_hat_2` outside the range of `Pi_2` are invisible to its linear
//! stage; at open contact points nothing else acts on them, and they flip sign at every
//! iteration (`W_hat' = 2 W - W_hat`), so the error indicator stalls (measured: plain LATIN on a
//! 40-cell cylinder on a 50-cell block stalled at 5.6e-4; with the points on the cylinder it
//! converges). On a side-1 facet `e` the
//! multiplier functions are the **dual basis** (Wohlmuth 2000; Popp, Gee and Wall 2009)
//! `psi_i = sum_j A_ij phi_j` of the facet's Lagrange functions `phi` (its own shape functions;
//! the linear corner functions for `Tri6`), with `A = D_e M_e^-1`,
//! `M_e,ij = int_e phi_i phi_j dS`, `D_e = diag(int_e phi_i dS)`: biorthogonal,
//! `int_e psi_i phi_j dS = delta_ij D_e,i`, and a partition of unity, `sum_i psi_i = 1`.
//! An interface point `p` (multiplier node `i`) gets the weight and the rows of both sides'
//! projections (module [`crate::interface`], [`SideProjection`](crate::interface::SideProjection))
//!
//! ```text
//! m_p = int_Gamma psi_i dS,     Pi_s(p, a) = (1 / m_p) int_Gamma psi_i N_a^s dS,
//! ```
//! so `W_s(p) = sum_a Pi_s(p, a) u_a` and the nodal forces are `f_a = sum_p m_p Pi_s(p, a) F(p)`.
//! On side 1, biorthogonality makes `Pi_1` the identity wherever `phi = N^1` (a node-to-node
//! side). At convergence the perfect law `W_1(p) = W_2(p)` is the dual-mortar constraint
//! `int psi_i (u_1 - u_2) dS = 0`, and the contact law acts on the weighted gaps
//! `g_p = (Pi_2 (x_2 + u_2) - Pi_1 (x_1 + u_1))(p) . n_p` (Hueber and Wohlmuth 2005): the
//! nominal part `(Pi_2 x_2 - Pi_1 x_1)(p) . n_p` is the point's **geometric gap**, added to the
//! gap field of contact interfaces. The force on side 2 is `lambda = sum_p F(p) psi_p` integrated
//! against side 2's shape functions: a uniform traction gives exactly the consistent nodal
//! forces on both sides (`sum_i psi_i = 1`), and every row sums to 1, so rigid motions and the
//! total force are transmitted exactly - the patch test holds to round-off on flat interfaces.
//!
//! # Integration (segment to segment)
//! Each side-1 facet `e` has an auxiliary plane (line in 2D) through its centre, normal to its
//! centre normal `n_0`. The facet's corners and those of every side-2 facet facing it
//! (`n_2 . n_0 < -1/2`) are projected on it along `n_0`; the side-2 polygons are clipped by the
//! side-1 polygon (Sutherland-Hodgman; intervals in 2D), the pieces triangulated, and each piece
//! integrated with a Gauss rule (6 points per segment in 2D, degree 6 per triangle in 3D) whose
//! points are mapped back to both facets by projection along `n_0` (Newton on
//! `x_s(xi) + t n_0 = p`), with the surface factor `1 / |n_1(xi) . n_0|` (and the thickness in
//! 2D). This is exact for flat interfaces with affine facets. A piece whose sides are farther
//! apart than the **search distance** (along `n_0`, at its centre) is not paired: side-1 points
//! beyond it are free boundary.
//!
//! # Nodes held by constraints
//! A side-1 multiplier node held in every direction by side 1's constraints (a clamped edge of
//! the interface) carries no point: its `W_1` cannot move, so a point there would only add the
//! constraint `W_2 = W_1` on side 2, which over-constrains side 2 near the edge and slows the
//! LATIN iteration by orders of magnitude (measured: 5133 instead of 88 iterations on a
//! clamped 8 | 12-cell Q4 interface). As in the standard mortar treatment of Dirichlet ends
//! (Wohlmuth 2000), its function is shared equally among the other multiplier nodes of each
//! facet (`psi_q <- psi_q + psi_p / (kept nodes)`, which keeps `sum psi = 1`); side 1's row of
//! those points then involves the held node (`Pi_1` is no longer the identity there), and the
//! point's position is `Pi_1 x_1`.
//!
//! # Partial coverage
//! A side-1 facet covered by side 2 over less than all of its area (edges of a contact zone,
//! sides of different extent) uses the linear corner functions themselves (non-negative, a
//! partition of unity) instead of the dual basis on the covered part: the weights stay positive
//! and rows still sum to 1, at the price of first-order consistency on those facets only. A
//! multiplier node with no covered facet is not an interface point. A side-1 facet covered more
//! than once (two layers of side 2 within the search distance) is an error.
//!
//! # Files
//! Vector algebra, facets, their positions and projections (`geometry.rs`); the
//! segment-to-segment integration points: auxiliary plane, Sutherland-Hodgman clipping, Gauss
//! rules (`clipping.rs`); the multiplier functions - dual basis, held nodes, partial coverage -
//! and a facet's contributions to the weights and rows (`dual.rs`); the pairing of two sides,
//! both ways, coarser side carrying the points (`pairing.rs`).

mod clipping;
mod dual;
mod geometry;
mod pairing;

pub use pairing::{pair_mortar, pair_mortar_sided};

#[cfg(test)]
use alea_fem::Quadrature;
#[cfg(test)]
use alea_fem::kinematics::facet_geometry;
#[cfg(test)]
use alea_fem::reference::{MAX_NODES, shape};
#[cfg(test)]
use alea_mesh::CellType;
#[cfg(test)]
use clipping::{area, clip_polygon};
#[cfg(test)]
use dual::{dual_coefficients, multiplier_kind};
#[cfg(test)]
use geometry::SideFacet;

type V3 = [f64; 3];

/// Default search distance as a fraction of the interface size (the diagonal of the bounding
/// box of both sides).
pub const DEFAULT_SEARCH_FRACTION: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_of_overlapping_squares() {
        let a = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let b = [[1.0, 1.0], [3.0, 1.0], [3.0, 3.0], [1.0, 3.0]];
        let c = clip_polygon(&b, &a);
        assert!((area(&c) - 1.0).abs() < 1e-14);
        let tri = [[0.5, -1.0], [1.5, -1.0], [1.0, 5.0]];
        let c = clip_polygon(&tri, &a);
        // The triangle's part inside the square: a trapezoid between y = 0 and y = 2.
        let width = |y: f64| 1.0 - (y + 1.0) / 6.0;
        assert!((area(&c) - 0.5 * (width(0.0) + width(2.0)) * 2.0).abs() < 1e-14);
    }

    #[test]
    fn dual_basis_is_biorthogonal() {
        for (kind, x) in [
            (CellType::Line2, vec![[0.0, 0.0, 0.0], [2.0, 0.5, 0.0]]),
            (
                CellType::Line3,
                vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.1, 0.0]],
            ),
            (
                CellType::Quad4,
                vec![
                    [0.0, 0.0, 0.0],
                    [2.0, 0.0, 0.0],
                    [2.0, 1.0, 0.0],
                    [0.0, 1.5, 0.0],
                ],
            ),
            // The reference Tri6 (straight sides, mid-side nodes at the middles).
            (
                CellType::Tri6,
                alea_mesh::reference::node_coords(CellType::Tri6),
            ),
        ] {
            let f = SideFacet {
                kind,
                nodes: (0..x.len()).collect(),
                x,
            };
            let mk = multiplier_kind(kind, true);
            let nm = mk.num_nodes();
            let a = dual_coefficients(&f, mk).unwrap();
            let q = Quadrature::for_cell(kind, 8);
            let mut phi = [0.0; MAX_NODES];
            let mut dphi = [[0.0; 3]; MAX_NODES];
            let mut gram = vec![0.0; nm * nm];
            let mut d = vec![0.0; nm];
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = facet_geometry(kind, &f.x, *xi);
                shape(mk, *xi, &mut phi, &mut dphi);
                let psi: Vec<f64> = (0..nm)
                    .map(|i| (0..nm).map(|j| a[i * nm + j] * phi[j]).sum())
                    .collect();
                let s: f64 = psi.iter().sum();
                assert!((s - 1.0).abs() < 1e-12, "{kind:?}: partition of unity {s}");
                for i in 0..nm {
                    d[i] += w * g.jac * phi[i];
                    for j in 0..nm {
                        gram[i * nm + j] += w * g.jac * psi[i] * phi[j];
                    }
                }
            }
            for i in 0..nm {
                for j in 0..nm {
                    let want = if i == j { d[i] } else { 0.0 };
                    assert!(
                        (gram[i * nm + j] - want).abs() < 1e-12,
                        "{kind:?} ({i}, {j}): {} vs {want}",
                        gram[i * nm + j]
                    );
                }
            }
        }
    }
}
