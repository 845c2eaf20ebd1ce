//! Element stiffness kernel against its definition.
//!
//! Reference: the definition `K_e = int_e B^T D B t dV` (Zienkiewicz, Taylor & Zhu, *The Finite
//! Element Method: Its Basis and Fundamentals*, 7th ed., 6.2), evaluated here densely from
//! `kinematics::strain_operator` and `Material::hooke` with the same quadrature rule.
//! `assembly::element_stiffness` computes it node block by node block, exploiting the sparsity of
//! `B`; the two must agree to round-off for every cell type and analysis, on distorted cells, and
//! `K_e` must be symmetric, positive semi-definite with exactly the rigid-body modes as kernel
//! (`K_e r = 0` for translations and infinitesimal rotations).
//!
//! ```text
//!   one cell of each type, corners moved by up to 15 % of its size, mid-edge nodes re-centred
//! ```

use alea_fem::assembly::element_stiffness;
use alea_fem::kinematics::{point_geometry, strain_operator};
use alea_fem::{Analysis, Material, Model, Quadrature};
use alea_mesh::{CellType, Mesh, generate};

fn distorted(kind: CellType) -> Mesh {
    let mut mesh = if kind.dim() == 2 {
        generate::rectangle(2.0, 1.5, 1, 1, kind).unwrap()
    } else {
        generate::box_mesh([2.0, 1.5, 1.2], [1, 1, 1], kind).unwrap()
    };
    let mut seed: u64 = 7;
    for x in &mut mesh.coords {
        for v in x.iter_mut().take(kind.dim()) {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *v += 0.3 * (((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5);
        }
    }
    mesh
}

/// Dense `sum_q w det t B^T D B` for cell `c`.
fn reference(model: &Model, c: usize) -> Vec<f64> {
    let kind = model.mesh.cell_type(c);
    let dim = model.mesh.dim;
    let m = kind.num_nodes() * dim;
    let nv = model.analysis.n_voigt();
    let d = model.material(c).unwrap().hooke(model.analysis);
    let coords = model.cell_coords(c);
    let q = Quadrature::stiffness(kind);
    let mut k = vec![0.0; m * m];
    let mut b = vec![0.0; nv * m];
    for (xi, w) in q.points.iter().zip(&q.weights) {
        let g = point_geometry(kind, &coords, *xi);
        strain_operator(&g, dim, &mut b);
        let f = w * g.det * model.analysis.thickness();
        for i in 0..m {
            for j in 0..m {
                let mut s = 0.0;
                for r in 0..nv {
                    for l in 0..nv {
                        s += b[r * m + i] * d[r * nv + l] * b[l * m + j];
                    }
                }
                k[i * m + j] += f * s;
            }
        }
    }
    k
}

#[test]
fn element_stiffness_matches_dense_btdb() {
    let cases = [
        (CellType::Tri3, Analysis::PlaneStrain { thickness: 1.0 }),
        (CellType::Tri6, Analysis::PlaneStress { thickness: 0.7 }),
        (CellType::Quad4, Analysis::PlaneStress { thickness: 2.0 }),
        (CellType::Quad8, Analysis::PlaneStrain { thickness: 1.0 }),
        (CellType::Tet4, Analysis::Solid),
        (CellType::Tet10, Analysis::Solid),
        (CellType::Hex8, Analysis::Solid),
    ];
    for (kind, analysis) in cases {
        let mut model = Model::new(distorted(kind), analysis).unwrap();
        model.set_material_all(Material::new(210e3, 0.3, 0.0).unwrap());
        let dim = model.mesh.dim;
        let mut ke = Vec::new();
        for c in 0..model.mesh.num_cells() {
            element_stiffness(&model, c, &mut ke).unwrap();
            let kr = reference(&model, c);
            let m = kind.num_nodes() * dim;
            let scale = kr.iter().map(|v| v.abs()).fold(0.0, f64::max);
            for i in 0..m {
                for j in 0..m {
                    assert!(
                        (ke[i * m + j] - kr[i * m + j]).abs() < 1e-12 * scale,
                        "{kind} cell {c} entry ({i}, {j}): {} vs {}",
                        ke[i * m + j],
                        kr[i * m + j]
                    );
                    assert_eq!(ke[i * m + j], ke[j * m + i], "{kind}: not symmetric");
                }
            }
            // Rigid-body modes: translations and rotations about each axis.
            let coords = model.cell_coords(c);
            let mut modes: Vec<Vec<f64>> = Vec::new();
            for t in 0..dim {
                modes.push(
                    (0..m)
                        .map(|i| if i % dim == t { 1.0 } else { 0.0 })
                        .collect(),
                );
            }
            let rot_axes: &[usize] = if dim == 2 { &[2] } else { &[0, 1, 2] };
            for &ax in rot_axes {
                let mut r = vec![0.0; m];
                for (a, x) in coords.iter().enumerate() {
                    // u = e_ax x x
                    let u = match ax {
                        0 => [0.0, -x[2], x[1]],
                        1 => [x[2], 0.0, -x[0]],
                        _ => [-x[1], x[0], 0.0],
                    };
                    r[a * dim..a * dim + dim].copy_from_slice(&u[..dim]);
                }
                modes.push(r);
            }
            for r in &modes {
                let norm: f64 = r.iter().map(|v| v * v).sum::<f64>().sqrt();
                for i in 0..m {
                    let s: f64 = (0..m).map(|j| ke[i * m + j] * r[j]).sum();
                    assert!(
                        s.abs() < 1e-11 * scale * norm,
                        "{kind}: K r = {s} for a rigid mode"
                    );
                }
            }
        }
    }
}
