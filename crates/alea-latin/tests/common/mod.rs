//! Small fixtures shared by the LATIN tests.
#![allow(dead_code)]

pub mod contact;
pub mod contact3d;

use alea_fem::{Analysis, Constraints, Loads, Material, Model};
use alea_latin::{Assembly, InterfaceSpec, Substructure};
use alea_mesh::{CellType, Mesh, generate};

/// Structured rectangle `[x0, x0 + lx] x [y0, y0 + ly]`.
pub fn rect(x0: f64, y0: f64, lx: f64, ly: f64, nx: usize, ny: usize, kind: CellType) -> Mesh {
    let mut m = generate::rectangle(lx, ly, nx, ny, kind).unwrap();
    for x in m.coords.iter_mut() {
        x[0] += x0;
        x[1] += y0;
    }
    m
}

/// A plane-strain model with one material.
pub fn model(mesh: Mesh, young: f64, poisson: f64) -> Model {
    let mut m = Model::new(mesh, Analysis::PlaneStrain { thickness: 1.0 }).unwrap();
    m.set_material_all(Material::new(young, poisson, 0.0).unwrap());
    m
}

/// A substructure with no load cases.
pub fn sub(name: &str, model: Model, constraints: Constraints) -> Substructure {
    Substructure {
        name: name.into(),
        model,
        constraints,
        load_cases: vec![],
    }
}

/// Adds one load case from a closure on the model.
pub fn with_load(mut s: Substructure, f: impl FnOnce(&Model, &mut Loads)) -> Substructure {
    let mut l = Loads::new(&s.model);
    f(&s.model, &mut l);
    s.load_cases.push(l.f);
    s
}

/// The base of the sliding tests: steel `[0, 4] x [-1, 0]` in 40 x 10 Quad4 cells (h = 0.1),
/// clamped below.
pub fn clamped_base() -> Substructure {
    let m = model(
        rect(0.0, -1.0, 4.0, 1.0, 40, 10, CellType::Quad4),
        210e3,
        0.3,
    );
    let mut c = Constraints::new();
    c.clamp(&m.mesh, "ymin").unwrap();
    sub("base", m, c)
}

/// Energy norm squared `u^T K u` of a displacement on a model (via internal forces).
pub fn energy(model: &Model, u: &[f64]) -> f64 {
    let f = alea_fem::post::internal_forces(model, u).unwrap();
    f.iter().zip(u).map(|(a, b)| a * b).sum()
}

/// Displacement of `reference` (on `ref_mesh`) at the nodes of `mesh`, matched by position.
pub fn restrict(ref_mesh: &Mesh, reference: &[f64], mesh: &Mesh) -> Vec<f64> {
    let d = mesh.dim;
    let mut out = vec![0.0; mesh.num_nodes() * d];
    for (n, x) in mesh.coords.iter().enumerate() {
        let m = (0..ref_mesh.num_nodes())
            .min_by(|&a, &b| {
                let da: f64 = (0..3).map(|k| (ref_mesh.coords[a][k] - x[k]).powi(2)).sum();
                let db: f64 = (0..3).map(|k| (ref_mesh.coords[b][k] - x[k]).powi(2)).sum();
                da.total_cmp(&db)
            })
            .unwrap();
        let dist: f64 = (0..3)
            .map(|k| (ref_mesh.coords[m][k] - x[k]).powi(2))
            .sum::<f64>();
        assert!(dist.sqrt() < 1e-9, "node {n} has no reference partner");
        out[n * d..n * d + d].copy_from_slice(&reference[m * d..m * d + d]);
    }
    out
}

/// The relative energy `E(u - u_ref) / E(u_ref)` of the difference between the substructures'
/// displacements `displacements` and a reference solution `reference` on one mesh `whole` of
/// the assembly (restricted to each substructure's nodes by coordinates).
#[allow(dead_code)]
pub fn relative_energy_error(
    whole: &Mesh,
    reference: &[f64],
    subs: &[Substructure],
    displacements: &[Vec<f64>],
) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (sub, u) in subs.iter().zip(displacements) {
        let m = &sub.model;
        let r = restrict(whole, reference, &m.mesh);
        let diff: Vec<f64> = r.iter().zip(u).map(|(a, b)| a - b).collect();
        num += energy(m, &diff);
        den += energy(m, &r);
    }
    num / den
}

/// Structured box `[x0, x0 + l] ` (per direction) of `Hex8`, `Tet4` or `Tet10` cells.
pub fn cuboid(x0: [f64; 3], l: [f64; 3], n: [usize; 3], kind: CellType) -> Mesh {
    let mut m = generate::box_mesh(l, n, kind).unwrap();
    for x in m.coords.iter_mut() {
        for d in 0..3 {
            x[d] += x0[d];
        }
    }
    m
}

/// A 3D solid model with one material.
pub fn solid(mesh: Mesh, young: f64, poisson: f64) -> Model {
    let mut m = Model::new(mesh, Analysis::Solid).unwrap();
    m.set_material_all(Material::new(young, poisson, 0.0).unwrap());
    m
}

/// The spacing a zone edge is extrapolated over ([`zone_edge`]).
pub enum EdgeStep {
    /// To the first node outside the zone (2D profiles).
    Outward,
    /// Between the last two nodes inside (3D profiles along a radius).
    Inward,
}

/// The edge of a zone (stick, slip, reverse slip) of a profile of interface nodes sorted by
/// their abscissa `x`, walking from the node at `x = 0` (which must be inside) in direction
/// `dir` (+1 or -1): the last node inside, plus the extrapolation to zero of `margin^2` (which
/// vanishes like the distance to the edge) from the last two nodes inside, over the spacing
/// `step`, clamped to the interval between the last node inside and the first outside.
pub fn zone_edge<T>(
    prof: &[T],
    x: impl Fn(&T) -> f64,
    dir: i32,
    inside: impl Fn(&T) -> bool,
    margin: impl Fn(&T) -> f64,
    step: EdgeStep,
) -> f64 {
    let centre = prof
        .iter()
        .position(|p| x(p).abs() < 1e-12)
        .expect("node at the origin");
    assert!(inside(&prof[centre]), "the zone contains the origin");
    let next = |i: usize| -> Option<usize> {
        if dir > 0 {
            (i + 1 < prof.len()).then_some(i + 1)
        } else {
            i.checked_sub(1)
        }
    };
    let mut i = centre;
    while let Some(j) = next(i) {
        if !inside(&prof[j]) {
            break;
        }
        i = j;
    }
    let o = next(i).expect("zone edge inside the interface");
    let prev = if dir > 0 { i - 1 } else { i + 1 };
    let (xi, xo) = (x(&prof[i]).abs(), x(&prof[o]).abs());
    let (di, dp) = (margin(&prof[i]).powi(2), margin(&prof[prev]).powi(2));
    let h = match step {
        EdgeStep::Outward => xo - xi,
        EdgeStep::Inward => (x(&prof[i]) - x(&prof[prev])).abs(),
    };
    (xi + h * di / (dp - di)).clamp(xi, xo)
}

/// Two bodies in contact (`tests/split.rs`, `tests/ranks.rs`): a clamped base, a block pressed
/// and sheared on it by a traction on its top, Coulomb contact with `mu = 0.3` (partial slip);
/// paired by mortar in 3D, and in 2D when `mortar`, else node to node.
pub fn press_and_shear(dim: usize, mortar: bool) -> Assembly {
    let (base, block) = if dim == 3 {
        (
            solid(
                cuboid([0.0; 3], [4.0, 4.0, 1.0], [8, 8, 3], CellType::Hex8),
                200e3,
                0.3,
            ),
            solid(
                cuboid([1.0, 1.0, 1.0], [2.0, 2.0, 1.0], [4, 4, 3], CellType::Hex8),
                70e3,
                0.3,
            ),
        )
    } else {
        (
            model(rect(0.0, 0.0, 4.0, 1.0, 24, 6, CellType::Quad4), 200e3, 0.3),
            model(rect(0.0, 1.0, 4.0, 1.0, 24, 6, CellType::Quad4), 70e3, 0.3),
        )
    };
    let (bottom, top) = if dim == 3 {
        ("zmin", "zmax")
    } else {
        ("ymin", "ymax")
    };
    let mut c = Constraints::new();
    c.clamp(&base.mesh, bottom).unwrap();
    let base = sub("base", base, c);
    let block = with_load(sub("block", block, Constraints::new()), |m, l| {
        l.traction(m, top, |_, _| {
            if dim == 3 {
                [25.0, 10.0, -100.0]
            } else {
                [25.0, -100.0, 0.0]
            }
        })
        .unwrap();
    });
    let mut contact = InterfaceSpec::coulomb("contact", 0, top, 1, bottom, 0.3);
    contact.pairing = if dim == 3 || mortar {
        alea_latin::Pairing::Mortar
    } else {
        alea_latin::Pairing::NodeToNode
    };
    Assembly {
        subs: vec![base, block],
        interfaces: vec![contact],
    }
}
