//! FE-side helpers: nodal values and strains of the FE solution, the Jacobian check of the
//! local rules, element Hooke matrices, facet points.

use alea_fem::kinematics::{PointGeometry, point_geometry};
use alea_fem::reference::node_coords;
use alea_fem::{Analysis, Material};
use alea_mesh::CellType;

use crate::CreError;

/// The values of the `D`-component node-major field `u` at the nodes `nodes` of a cell
/// (node-major, `D` per node).
pub fn cell_values<const D: usize>(u: &[f64], nodes: &[usize]) -> Vec<f64> {
    nodes
        .iter()
        .flat_map(|&n| (0..D).map(move |k| u[D * n + k]))
        .collect()
}

/// `Ok` if the point geometry `g` of cell `c` (of type `kind`) has a positive Jacobian,
/// [`alea_fem::FemError::BadJacobian`] otherwise.
#[inline]
pub fn check_jacobian(g: &PointGeometry, c: usize, kind: CellType) -> Result<(), CreError> {
    if g.det <= 0.0 {
        return Err(alea_fem::FemError::BadJacobian {
            cell: c,
            kind: kind.to_string(),
            det: g.det,
        }
        .into());
    }
    Ok(())
}

/// Voigt strain `[e_xx, e_yy, g_xy]` of the FE displacement `ue` (node-major, 2 per node) at
/// reference point `xi`, with the point geometry.
pub fn strain_h(
    kind: CellType,
    coords: &[[f64; 3]],
    ue: &[f64],
    xi: [f64; 3],
) -> ([f64; 3], PointGeometry) {
    let g = point_geometry(kind, coords, xi);
    let mut e = [0.0; 3];
    for a in 0..g.nn {
        let [gx, gy, _] = g.grad[a];
        let (ux, uy) = (ue[2 * a], ue[2 * a + 1]);
        e[0] += gx * ux;
        e[1] += gy * uy;
        e[2] += gy * ux + gx * uy;
    }
    (e, g)
}

/// 3x3 Hooke matrix of a 2D analysis.
pub fn hooke(mat: &Material, analysis: Analysis) -> [[f64; 3]; 3] {
    let d = mat.hooke(analysis);
    [[d[0], d[1], d[2]], [d[3], d[4], d[5]], [d[6], d[7], d[8]]]
}

/// `D e`.
pub fn mul3(d: &[[f64; 3]; 3], e: &[f64; 3]) -> [f64; 3] {
    [
        d[0][0] * e[0] + d[0][1] * e[1] + d[0][2] * e[2],
        d[1][0] * e[0] + d[1][1] * e[1] + d[1][2] * e[2],
        d[2][0] * e[0] + d[2][1] * e[1] + d[2][2] * e[2],
    ]
}

/// Reference point of local facet `local` of a cell at edge parameter `s in [0, 1]` (from the
/// facet's first node to its second).
pub fn facet_point(kind: CellType, local: usize, s: f64) -> [f64; 3] {
    let refs = node_coords(kind);
    let loc = kind.facets()[local].1;
    let (a, b) = (refs[loc[0]], refs[loc[1]]);
    [
        (1.0 - s) * a[0] + s * b[0],
        (1.0 - s) * a[1] + s * b[1],
        0.0,
    ]
}

/// Gauss-Legendre rule with `n` points on `[0, 1]`.
pub fn gauss01(n: usize) -> Vec<(f64, f64)> {
    let (x, w) = alea_fem::quadrature::gauss_legendre(n);
    x.iter()
        .zip(&w)
        .map(|(x, w)| (0.5 * (x + 1.0), 0.5 * w))
        .collect()
}

/// Traction `sigma n` of a Voigt stress `[s_xx, s_yy, s_xy]`.
pub fn traction_of(s: &[f64; 3], n: [f64; 2]) -> [f64; 2] {
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}
