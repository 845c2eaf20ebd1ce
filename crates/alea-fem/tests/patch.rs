//! Patch tests: an affine displacement field imposed on the boundary is reproduced exactly in
//! the interior, with the exact constant stress, for every element type, on regular and on
//! distorted meshes (interior nodes moved randomly; mid-edge nodes of quadratic cells kept at
//! edge midpoints so the geometry stays affine per edge).

use alea_fem::{
    Analysis, Constraints, Loads, Material, Model, Ordering, post::nodal_stresses, solve_elastic,
};
use alea_mesh::{CellType, Mesh, generate};

/// Affine field u = A x + c.
fn u_exact(x: [f64; 3], dim: usize) -> [f64; 3] {
    let a = [
        [1.0e-3, 2.0e-3, -1.5e-3],
        [-0.5e-3, 3.0e-3, 0.7e-3],
        [0.4e-3, -0.8e-3, 1.2e-3],
    ];
    let c = [0.1, -0.2, 0.05];
    let mut u = [0.0; 3];
    for i in 0..dim {
        u[i] = c[i] + (0..dim).map(|j| a[i][j] * x[j]).sum::<f64>();
    }
    u
}

/// Moves interior corner nodes by up to `amp` of the cell size (deterministic pseudo-random),
/// then re-centres mid-edge nodes of quadratic cells.
fn distort(mesh: &mut Mesh, amp: f64) {
    let boundary: std::collections::HashSet<usize> = mesh
        .boundary_facets()
        .iter()
        .flat_map(|b| b.facet.nodes.clone())
        .collect();
    let mut corner = vec![false; mesh.num_nodes()];
    for (_, kind, nodes) in mesh.cells() {
        for &n in &nodes[..kind.num_corners()] {
            corner[n] = true;
        }
    }
    let mut seed: u64 = 12345;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
    };
    for n in 0..mesh.num_nodes() {
        if corner[n] && !boundary.contains(&n) {
            for d in 0..mesh.dim {
                mesh.coords[n][d] += amp * rnd();
            }
        }
    }
    // Mid-edge nodes back to the middle of their (moved) edge.
    let edges: &[(usize, usize, usize)] = &[];
    let _ = edges;
    let cells: Vec<(CellType, Vec<usize>)> =
        mesh.cells().map(|(_, k, n)| (k, n.to_vec())).collect();
    for (kind, nodes) in cells {
        let pairs: &[(usize, usize)] = match kind {
            CellType::Tri6 => &[(0, 1), (1, 2), (2, 0)],
            CellType::Quad8 => &[(0, 1), (1, 2), (2, 3), (3, 0)],
            CellType::Tet10 => &[(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
            _ => &[],
        };
        for (m, &(a, b)) in pairs.iter().enumerate() {
            let (xa, xb) = (mesh.coords[nodes[a]], mesh.coords[nodes[b]]);
            let mid = nodes[kind.num_corners() + m];
            for d in 0..3 {
                mesh.coords[mid][d] = 0.5 * (xa[d] + xb[d]);
            }
        }
    }
}

fn run_patch(mesh: Mesh, analysis: Analysis) {
    let dim = mesh.dim;
    let kind = mesh.cell_type(0);
    let mut model = Model::new(mesh, analysis).unwrap();
    let mat = Material::new(200e3, 0.3, 0.0).unwrap();
    model.set_material_all(mat);
    let mut cons = Constraints::new();
    let sides: &[&str] = if dim == 2 {
        &["xmin", "xmax", "ymin", "ymax"]
    } else {
        &["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"]
    };
    for s in sides {
        for c in 0..dim {
            cons.fix_component_with(&model.mesh, s, c, |x| u_exact(x, dim)[c])
                .unwrap();
        }
    }
    let loads = Loads::new(&model);
    let sol = solve_elastic(&model, &cons, &loads, Ordering::Metis).unwrap();
    let mut err: f64 = 0.0;
    for (n, x) in model.mesh.coords.iter().enumerate() {
        let ue = u_exact(*x, dim);
        for c in 0..dim {
            err = err.max((sol.u[n * dim + c] - ue[c]).abs());
        }
    }
    assert!(
        err < 1e-12,
        "{kind} {analysis:?}: displacement error {err:e}"
    );
    // Constant stress = D eps.
    let eps: Vec<f64> = {
        let e = |i: usize, j: usize| {
            let h = 1e-3;
            let mut xp = [0.3; 3];
            xp[j] += h;
            (u_exact(xp, dim)[i] - u_exact([0.3; 3], dim)[i]) / h
        };
        if dim == 2 {
            vec![e(0, 0), e(1, 1), e(0, 1) + e(1, 0)]
        } else {
            vec![
                e(0, 0),
                e(1, 1),
                e(2, 2),
                e(1, 2) + e(2, 1),
                e(0, 2) + e(2, 0),
                e(0, 1) + e(1, 0),
            ]
        }
    };
    let s_ex = mat.stress(analysis, &eps);
    let s = nodal_stresses(&model, &sol.u).unwrap();
    for sn in &s {
        for k in 0..6 {
            assert!(
                (sn[k] - s_ex[k]).abs() < 1e-8 * 200e3 * 1e-3,
                "{kind}: stress {k} = {} vs {}",
                sn[k],
                s_ex[k]
            );
        }
    }
    // Reactions balance (no external load): resultant zero.
    for c in 0..dim {
        let r: f64 = sol.reactions.iter().skip(c).step_by(dim).sum();
        assert!(r.abs() < 1e-8, "{kind}: reaction resultant {r}");
    }
}

#[test]
fn patch_test_2d_all_elements_regular_and_distorted() {
    for kind in [
        CellType::Tri3,
        CellType::Tri6,
        CellType::Quad4,
        CellType::Quad8,
    ] {
        for analysis in [
            Analysis::PlaneStrain { thickness: 1.0 },
            Analysis::PlaneStress { thickness: 2.5 },
        ] {
            let mesh = generate::rectangle(2.0, 1.0, 4, 3, kind).unwrap();
            run_patch(mesh.clone(), analysis);
            let mut d = mesh;
            distort(&mut d, 0.2);
            run_patch(d, analysis);
        }
    }
}

#[test]
fn patch_test_3d_all_elements_regular_and_distorted() {
    for kind in [CellType::Tet4, CellType::Tet10, CellType::Hex8] {
        let mesh = generate::box_mesh([1.0, 1.5, 1.2], [3, 3, 3], kind).unwrap();
        run_patch(mesh.clone(), Analysis::Solid);
        let mut d = mesh;
        distort(&mut d, 0.15);
        run_patch(d, Analysis::Solid);
    }
}
