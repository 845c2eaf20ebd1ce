//! Contact patch test on non-matching interface meshes (mortar pairing), 2D and 3D.
//!
//! Reference: A. El-Abbasi and K.-J. Bathe, *Stability and patch test performance of contact
//! discretizations and a new solution algorithm*, Computers & Structures 79 (2001) 1473-1486,
//! section 4 (contact patch test): two blocks meshed independently, so that the contact
//! surfaces' nodes do not coincide, under a uniform pressure on top, `nu = 0`. A contact
//! discretisation passes if it transmits the uniform pressure exactly and reproduces the
//! uniform stress state (node-to-segment contact does not; mortar methods do).
//!
//! ```text
//!        uniform pressure p  (or imposed u_y = -delta)
//!        +--+--+--+--+--+  y = 2 h     upper block (E2), m cells across
//!        |  |  |  |  |  |
//!  u_x=0 +==+==+==+==+==+  y = h       contact (Coulomb, mu = 0.3): non-matching nodes
//!        |   |   |   |  |
//!        +---+---+---+--+  y = 0       lower block (E1), n cells across, u_y = 0
//!       x=0            x=w
//! ```
//! With `nu = 0` the exact solution is uniform stress `sigma_yy = -p` in both blocks and
//! `u_y = -p y / E1` (lower), `u_y = -p h / E1 - p (y - h) / E2` (upper), `u_x = 0`: every
//! linear field is in the FE spaces, so a consistent method reproduces it to round-off. The
//! 3D test is the same with boxes (`u_x = 0` on `x = 0`, `u_y = 0` on `y = 0`, hexahedra against
//! hexahedra or tetrahedra).
//!
//! Checked to 1e-8 relative: the local-stage pressure at every interface point (and zero
//! tangential force), the linear-stage one, every nodal displacement of both blocks against the
//! exact field (a uniform displacement of the interface), the total force; both with the
//! pressure load (upper block floating in y) and with an imposed displacement on top
//! (uniform displacement transmitted). Cases: coarse on fine and fine on coarse, linear and
//! quadratic cells, triangles against quadrilaterals, and the mortar forced on matching meshes
//! (same answer as node to node).

mod common;

use alea_fem::{Analysis, Constraints, Material, Model};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LatinSolver, Pairing, PairingKind, RunInput, RunStatus,
    Substructure,
};
use alea_mesh::{CellType, Mesh, generate};
use common::*;

const P: f64 = 7.0;
const E1: f64 = 1000.0;
const E2: f64 = 400.0;
const H: f64 = 1.0;

#[derive(Clone, Copy)]
enum Top {
    Pressure,
    Displacement(f64),
}

/// Materials: Young's moduli of the lower and upper blocks and the common Poisson's ratio
/// (`nu != 0` only with equal moduli: the lateral expansions must agree).
#[derive(Clone, Copy)]
struct Materials {
    e1: f64,
    e2: f64,
    nu: f64,
}

const NU0: Materials = Materials {
    e1: E1,
    e2: E2,
    nu: 0.0,
};

impl Materials {
    /// Lateral and vertical strains per unit pressure in a block of modulus `e` under
    /// `sigma_vertical = -p`, free lateral stresses (plane strain in 2D).
    fn strains(&self, e: f64, dim: usize) -> (f64, f64) {
        let nu = self.nu;
        if dim == 2 {
            (nu * (1.0 + nu) / e, -(1.0 - nu * nu) / e)
        } else {
            (nu / e, -1.0 / e)
        }
    }

    /// Exact displacement component `c` at `x` under pressure `p`.
    fn exact(&self, x: &[f64; 3], c: usize, p: f64, dim: usize) -> f64 {
        let (l1, v1) = self.strains(self.e1, dim);
        let (l2, v2) = self.strains(self.e2, dim);
        let y = x[dim - 1];
        if c < dim - 1 {
            p * if y <= H { l1 } else { l2 } * x[c]
        } else if y <= H {
            p * v1 * y
        } else {
            p * (v1 * H + v2 * (y - H))
        }
    }
}

fn shifted(mut m: Mesh, dz: f64) -> Mesh {
    let c = m.dim - 1;
    for x in m.coords.iter_mut() {
        x[c] += dz;
    }
    m
}

fn solid(mesh: Mesh, young: f64, nu: f64) -> Model {
    let mut m = Model::new(mesh, Analysis::Solid).unwrap();
    m.set_material_all(Material::new(young, nu, 0.0).unwrap());
    m
}

/// Builds and solves the patch test; `lower`/`upper` are the two meshes (upper already
/// shifted to start at `y = H`), `side1_lower`: the lower block is side 1.
fn patch(
    lower: Mesh,
    upper: Mesh,
    top: Top,
    side1_lower: bool,
    pairing: Pairing,
    mat: Materials,
    perfect: bool,
) -> f64 {
    let dim = lower.dim;
    let (lo, hi) = if dim == 2 {
        ("ymin", "ymax")
    } else {
        ("zmin", "zmax")
    };
    let make = |mesh: Mesh, young: f64| {
        if dim == 2 {
            model(mesh, young, mat.nu)
        } else {
            solid(mesh, young, mat.nu)
        }
    };
    let roller = |m: &Model, c: &mut Constraints| {
        c.fix_component(&m.mesh, "xmin", 0, 0.0).unwrap();
        if dim == 3 {
            c.fix_component(&m.mesh, "ymin", 1, 0.0).unwrap();
        }
    };
    let lower_sub = {
        let m = make(lower, mat.e1);
        let mut c = Constraints::new();
        roller(&m, &mut c);
        c.fix_component(&m.mesh, lo, dim - 1, 0.0).unwrap();
        sub("lower", m, c)
    };
    let upper_sub = {
        let m = make(upper, mat.e2);
        let mut c = Constraints::new();
        roller(&m, &mut c);
        let s = match top {
            Top::Displacement(d) => {
                c.fix_component(&m.mesh, hi, dim - 1, -d).unwrap();
                sub("upper", m, c)
            }
            Top::Pressure => sub("upper", m, c),
        };
        match top {
            Top::Pressure => with_load(s, |m, l| {
                l.pressure(m, hi, P).unwrap();
            }),
            Top::Displacement(_) => s,
        }
    };
    let subs: Vec<Substructure> = vec![lower_sub, upper_sub];
    let (s1, g1, s2, g2) = if side1_lower {
        (0, hi, 1, lo)
    } else {
        (1, lo, 0, hi)
    };
    let mut iface = if perfect {
        InterfaceSpec::perfect("contact", s1, g1, s2, g2)
    } else {
        InterfaceSpec::coulomb("contact", s1, g1, s2, g2, 0.3)
    };
    iface.pairing = pairing;
    let mut solver = LatinSolver::new(
        Assembly {
            subs,
            interfaces: vec![iface],
        },
        LatinOptions {
            tolerance: 1e-13,
            max_iterations: 5000,
            ..Default::default()
        },
    )
    .unwrap();
    let r = solver.run(&RunInput::default()).unwrap();
    assert_eq!(r.status, RunStatus::Converged, "{:?}", r.residuals.last());
    let it = &r.interfaces[0];
    // The pressure this run transmits (the imposed displacement gives p = delta / compliance).
    let p = match top {
        Top::Pressure => P,
        Top::Displacement(d) => {
            -d / (H * (mat.strains(mat.e1, dim).1 + mat.strains(mat.e2, dim).1))
        }
    };
    // Force on side 2 along the side-1 normal: +p if side 2 is the upper block.
    let sign = if side1_lower { 1.0 } else { -1.0 };
    let mut worst: f64 = 0.0;
    for i in 0..it.points.len() {
        let (fn_, ft) = it.normal_tangential(i);
        worst = worst.max((fn_ - p).abs() / p).max(ft / p);
        let n = it.points[i].normal;
        let fl = it.f[1][i];
        let fl_n = fl[0] * n[0] + fl[1] * n[1] + fl[2] * n[2];
        worst = worst.max((fl_n - p).abs() / p);
        assert!((n[dim - 1] - sign).abs() < 1e-12, "normal {n:?}");
    }
    // Every nodal displacement of both blocks.
    let umax = -p * H * (mat.strains(mat.e1, dim).1 + mat.strains(mat.e2, dim).1);
    for (s, model) in [(0, solver.model(0)), (1, solver.model(1))] {
        let u = &r.displacements[s];
        for (n, x) in model.mesh.coords.iter().enumerate() {
            for c in 0..dim {
                let want = mat.exact(x, c, p, dim);
                worst = worst.max((u[n * dim + c] - want).abs() / umax);
            }
        }
    }
    // Total force on the upper block: p times the area.
    let area: f64 = it.weights.iter().sum();
    let total = it.resultant()[dim - 1] * sign;
    worst = worst.max((total - p * area).abs() / (p * area));
    eprintln!(
        "{:?} pairing, {} points, {} iterations: worst relative deviation {worst:.2e}",
        it.pairing.kind,
        it.points.len(),
        r.iterations
    );
    assert!(worst < 1e-8, "worst relative deviation {worst:e}");
    if pairing == Pairing::Auto {
        assert_eq!(it.pairing.kind, PairingKind::Mortar);
    }
    worst
}

fn rect_at(nx: usize, ny: usize, kind: CellType, y0: f64) -> Mesh {
    rect(0.0, y0, 1.0, H, nx, ny, kind)
}

#[test]
fn patch_test_2d_non_matching() {
    let cases = [
        (4, CellType::Quad4, 5, CellType::Quad4),
        (5, CellType::Quad4, 4, CellType::Quad4),
        (3, CellType::Tri3, 7, CellType::Quad4),
        (3, CellType::Quad8, 4, CellType::Quad8),
        (5, CellType::Tri6, 3, CellType::Quad8),
    ];
    for (n1, k1, n2, k2) in cases {
        for top in [Top::Pressure, Top::Displacement(0.01)] {
            for side1_lower in [true, false] {
                eprintln!("lower {n1} x {k1:?}, upper {n2} x {k2:?}, side 1 lower: {side1_lower}");
                patch(
                    rect_at(n1, 2, k1, 0.0),
                    rect_at(n2, 2, k2, H),
                    top,
                    side1_lower,
                    Pairing::Auto,
                    NU0,
                    false,
                );
            }
        }
    }
}

#[test]
fn mortar_on_matching_meshes_is_node_to_node() {
    // Forced mortar on coincident nodes: identity projections up to round-off, same answer.
    let a = patch(
        rect_at(4, 2, CellType::Quad4, 0.0),
        rect_at(4, 2, CellType::Quad4, H),
        Top::Pressure,
        true,
        Pairing::Mortar,
        NU0,
        false,
    );
    let b = patch(
        rect_at(4, 2, CellType::Quad4, 0.0),
        rect_at(4, 2, CellType::Quad4, H),
        Top::Pressure,
        true,
        Pairing::NodeToNode,
        NU0,
        false,
    );
    assert!(a < 1e-8 && b < 1e-8);
}

#[test]
fn patch_test_3d_non_matching() {
    let boxed = |n: usize, kind: CellType, z0: f64| {
        shifted(
            generate::box_mesh([1.0, 1.0, H], [n, n, 1], kind).unwrap(),
            z0,
        )
    };
    let cases = [
        (3, CellType::Hex8, 4, CellType::Hex8),
        (2, CellType::Tet4, 3, CellType::Hex8),
        (2, CellType::Hex8, 3, CellType::Tet10),
    ];
    for (n1, k1, n2, k2) in cases {
        for (top, side1_lower) in [(Top::Pressure, true), (Top::Displacement(0.01), false)] {
            eprintln!("lower {n1} x {k1:?}, upper {n2} x {k2:?}, side 1 lower: {side1_lower}");
            patch(
                boxed(n1, k1, 0.0),
                boxed(n2, k2, H),
                top,
                side1_lower,
                Pairing::Auto,
                NU0,
                false,
            );
        }
    }
}

#[test]
fn linear_lateral_expansion_crosses_non_matching_interfaces() {
    // nu = 0.3, equal moduli: u_x = nu (1 + nu) p x / E varies linearly along the interface;
    // the perfect and the (sticking) contact interfaces must both reproduce it.
    let mat = Materials {
        e1: E1,
        e2: E1,
        nu: 0.3,
    };
    for perfect in [true, false] {
        for side1_lower in [true, false] {
            patch(
                rect_at(4, 2, CellType::Quad4, 0.0),
                rect_at(7, 2, CellType::Tri3, H),
                Top::Pressure,
                side1_lower,
                Pairing::Auto,
                mat,
                perfect,
            );
        }
    }
    let boxed = |n: usize, kind: CellType, z0: f64| {
        shifted(
            generate::box_mesh([1.0, 1.0, H], [n, n, 1], kind).unwrap(),
            z0,
        )
    };
    for perfect in [true, false] {
        patch(
            boxed(3, CellType::Hex8, 0.0),
            boxed(2, CellType::Tet4, H),
            Top::Pressure,
            !perfect,
            Pairing::Auto,
            mat,
            perfect,
        );
    }
}

/// Sides of different extent: a block of width 1 pressed (uniform pressure `p`, frictionless
/// contact, `nu = 0`) on the middle of a wider block of width 2, meshed independently.
/// The points are on the wide block (the coarser side) whichever side is side 1: the wide
/// block's nodes beyond the narrow one are left out and the facets under its edges are
/// partially covered. Both orientations give the applied resultant exactly (equilibrium of the floating block), no
/// force outside the narrow block, and the same top displacement of the narrow block (the two
/// discretisations of the contact differ at the edges only: within 1 %).
#[test]
fn sides_of_different_extent() {
    let mut tops = Vec::new();
    for narrow_is_side1 in [true, false] {
        let lower = model(rect(-1.0, 0.0, 2.0, H, 10, 4, CellType::Quad4), E1, 0.0);
        let upper = model(rect(-0.5, H, 1.0, H, 8, 4, CellType::Quad4), E2, 0.0);
        let mut cl = Constraints::new();
        cl.clamp(&lower.mesh, "ymin").unwrap();
        let mut cu = Constraints::new();
        // The narrow block slides freely in x only through the (frictionless) contact: hold
        // its x at one node of the axis.
        let axis = upper
            .mesh
            .coords
            .iter()
            .position(|x| x[0].abs() < 1e-12 && (x[1] - 2.0 * H).abs() < 1e-12)
            .unwrap();
        cu.fix_direction(axis, [1.0, 0.0, 0.0], 0.0);
        let subs = vec![
            sub("lower", lower, cl),
            with_load(sub("upper", upper, cu), |m, l| {
                l.pressure(m, "ymax", P).unwrap();
            }),
        ];
        let iface = if narrow_is_side1 {
            InterfaceSpec::coulomb("contact", 1, "ymin", 0, "ymax", 0.0)
        } else {
            InterfaceSpec::coulomb("contact", 0, "ymax", 1, "ymin", 0.0)
        };
        let mut solver = LatinSolver::new(
            Assembly {
                subs,
                interfaces: vec![iface],
            },
            LatinOptions {
                tolerance: 1e-10,
                max_iterations: 5000,
                ..Default::default()
            },
        )
        .unwrap();
        let r = solver.run(&RunInput::default()).unwrap();
        assert_eq!(r.status, RunStatus::Converged);
        let it = &r.interfaces[0];
        assert_eq!(it.pairing.kind, PairingKind::Mortar);
        // Resultant on the narrow block = p x 1 (in +y).
        let on_upper = if narrow_is_side1 { -1.0 } else { 1.0 };
        let fy = on_upper * it.resultant()[1];
        assert!((fy - P).abs() < 1e-8 * P, "resultant {fy}");
        let xs: Vec<f64> = it.points.iter().map(|p| p.x[0]).collect();
        eprintln!(
            "narrow side 1: {narrow_is_side1}: {} points, x in [{:.3}, {:.3}], {} iterations",
            xs.len(),
            xs.iter().cloned().fold(f64::INFINITY, f64::min),
            xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
            r.iterations
        );
        // The points are on the coarser side, the wide block, whichever is side 1; normals
        // are side 1's outward ones.
        assert_eq!(xs.len(), 7);
        assert!(xs.iter().all(|x| x.abs() < 0.5 + 0.2 + 1e-9));
        let ny = if narrow_is_side1 { -1.0 } else { 1.0 };
        assert!(it.points.iter().all(|p| (p.normal[1] - ny).abs() < 1e-12));
        for (i, p) in it.points.iter().enumerate() {
            if p.x[0].abs() > 0.5 + 1e-9 {
                let (fn_, _) = it.normal_tangential(i);
                assert!(fn_.abs() < 1e-8 * P, "force {fn_} at x = {}", p.x[0]);
            }
        }
        let (u, _) = r.displacement_at(solver.model(1), 1, [0.0, 2.0 * H, 0.0]);
        tops.push(u[1]);
    }
    eprintln!("top displacement of the narrow block: {tops:?}");
    assert!((tops[0] - tops[1]).abs() < 0.01 * tops[0].abs(), "{tops:?}");
}
