//! Ready-made assemblies shared by benchmarks (and usable as examples): a four-substructure
//! dovetail blade root in its disk sector, and Hertz's cylinder on a block ([`hertz`]).
//!
//! ```text
//!          root_left | root_right          root: floating, blade pull + bending on its top
//!        ---flank---cut---flank---         flank_left / flank_right: Coulomb contact (mu 0.5)
//!          disk_left | disk_right          root_cut / disk_cut: perfect interfaces on x = 0
//!                                          disk sides: normal (sector symmetry) constraints
//! ```
//! The mesh is `alea_mesh::generate::dovetail_root_and_disk(DovetailParams::default()
//! .refined(refine), Quad4)` with the root and the disk each cut in halves at x = 0
//! (`refine = 6`: 23 240 dof). Plane strain, E = 200 GPa, nu = 0.3, rho = 7.8e-9 t/mm^3.

mod hertz;

pub use hertz::{ContactLayout, HertzCase, hertz_cylinder_on_block};

use alea_fem::{Analysis, Constraints, Loads, Material, Model};
use alea_mesh::generate::{DovetailParams, dovetail_root_and_disk};
use alea_mesh::{CellType, Facet, Mesh};

use crate::{Assembly, InterfaceSpec, LatinError, LatinOptions, SearchDirection, Substructure};

/// Young's modulus of both parts (MPa).
pub const YOUNG: f64 = 200e3;
/// Poisson's ratio.
pub const POISSON: f64 = 0.3;
/// Blade pull on the root top (MPa).
pub const PULL: f64 = 200.0;
/// Tangential (bending) part of the blade load on the root top (MPa).
pub const SHEAR: f64 = 30.0;

fn mesh_err(sub: &str) -> impl Fn(alea_mesh::MeshError) -> LatinError + '_ {
    move |source| LatinError::Mesh {
        sub: sub.to_string(),
        source,
    }
}

fn fem_err(sub: &str) -> impl Fn(alea_fem::FemError) -> LatinError + '_ {
    move |source| LatinError::Fem {
        sub: sub.to_string(),
        source,
    }
}

/// Cell group `part` of `mesh`, cut at x = 0 (`left`: cell centroid x < 0), with the cut
/// facets as the facet/node group `"cut"`.
fn half(mesh: &Mesh, part: &str, left: bool, name: &str) -> Result<Mesh, LatinError> {
    let mut m = mesh.clone();
    let cells: Vec<usize> = m
        .cell_group(part)
        .map_err(mesh_err(name))?
        .iter()
        .copied()
        .filter(|&c| {
            let xs = m.cell_coords(c);
            let cx = xs.iter().map(|x| x[0]).sum::<f64>() / xs.len() as f64;
            (cx < 0.0) == left
        })
        .collect();
    m.add_cells_to_group(name, cells);
    let (mut sub, _) = m.extract(&[name]).map_err(mesh_err(name))?;
    let (lo, hi) = sub.bounding_box();
    let tol = 1e-9 * (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let cut: Vec<Facet> = sub
        .boundary_facets()
        .into_iter()
        .filter(|b| b.facet.nodes.iter().all(|&n| sub.coords[n][0].abs() <= tol))
        .map(|b| b.facet)
        .collect();
    if cut.is_empty() {
        return Err(LatinError::Invalid(format!("{name}: no facet on x = 0")));
    }
    let nodes: Vec<usize> = cut.iter().flat_map(|f| f.nodes.clone()).collect();
    sub.add_facets_to_group("cut", cut);
    sub.add_nodes_to_group("cut", nodes);
    Ok(sub)
}

/// The four-part dovetail assembly: substructures 0 `root_left`, 1 `root_right`, 2
/// `disk_left`, 3 `disk_right`; interfaces 0 `flank_left`, 1 `flank_right` (Coulomb, mu 0.5),
/// 2 `root_cut`, 3 `disk_cut` (perfect). One load case: the blade load on the root top.
pub fn four_part_dovetail(refine: usize) -> Result<Assembly, LatinError> {
    let p = DovetailParams::default().refined(refine);
    let mesh = dovetail_root_and_disk(&p, CellType::Quad4).map_err(mesh_err("dovetail"))?;
    let mut subs = Vec::new();
    for (part, left) in [
        ("root", true),
        ("root", false),
        ("disk", true),
        ("disk", false),
    ] {
        let name = format!("{part}_{}", if left { "left" } else { "right" });
        let mut m = Model::new(
            half(&mesh, part, left, &name)?,
            Analysis::PlaneStrain { thickness: 1.0 },
        )
        .map_err(fem_err(&name))?;
        m.set_material_all(Material::new(YOUNG, POISSON, 7.8e-9).map_err(fem_err(&name))?);
        let mut c = Constraints::new();
        let mut loads = Loads::new(&m);
        if part == "disk" {
            let side = if left {
                "disk_side_left"
            } else {
                "disk_side_right"
            };
            c.fix_normal(&m.mesh, side, 0.0).map_err(fem_err(&name))?;
        } else {
            loads
                .traction(&m, "root_top", |_, _| [SHEAR, PULL, 0.0])
                .map_err(fem_err(&name))?;
        }
        subs.push(Substructure {
            name,
            model: m,
            constraints: c,
            load_cases: vec![loads.f],
        });
    }
    let interfaces = vec![
        InterfaceSpec::coulomb(
            "flank_left",
            0,
            "flank_left_root",
            2,
            "flank_left_disk",
            0.5,
        ),
        InterfaceSpec::coulomb(
            "flank_right",
            1,
            "flank_right_root",
            3,
            "flank_right_disk",
            0.5,
        ),
        InterfaceSpec::perfect("root_cut", 0, "cut", 1, "cut"),
        InterfaceSpec::perfect("disk_cut", 2, "cut", 3, "cut"),
    ];
    Ok(Assembly { subs, interfaces })
}

/// Options used with it: tolerance 1e-6 and the solver's defaults (two-scale LATIN with the
/// coarse problem, search direction `k = 3 E / L`, Anderson depth 5). Without the coarse
/// problem the fastest factor of 0.1, 0.2, 0.3, 0.5, 1 and 3 was 0.5 (see
/// `crates/alea-latin/BENCHMARKS.md`).
pub fn four_part_dovetail_options() -> LatinOptions {
    LatinOptions {
        tolerance: 1e-6,
        max_iterations: 5000,
        ..Default::default()
    }
}

/// The single-scale configuration it was tuned for before the coarse problem: no coarse
/// problem, `k = 0.5 E / L` (for comparisons).
pub fn four_part_dovetail_single_scale_options() -> LatinOptions {
    LatinOptions {
        coarse: false,
        search_direction: SearchDirection::Auto { factor: 0.5 },
        ..four_part_dovetail_options()
    }
}
