//! The mesh of a `[mesh]` table: the generators' parameters, a mesh file, the split, and the
//! hash of a study's inputs; the generators' dispatch is in `build/mesh/generators.rs`.

mod generators;

use std::path::Path;

use alea_mesh::{CellType, Mesh, generate};
use toml::Spanned;

use crate::spec::{MeshSpec, ModelFile};
use crate::{Source, StudyError};
use generators::build_base_mesh;

fn cell_type(src: &Source, s: &Spanned<String>) -> Result<CellType, StudyError> {
    Ok(match s.get_ref().to_ascii_lowercase().as_str() {
        "tri3" => CellType::Tri3,
        "tri6" => CellType::Tri6,
        "quad4" => CellType::Quad4,
        "quad8" => CellType::Quad8,
        "tet4" => CellType::Tet4,
        "tet10" => CellType::Tet10,
        "hex8" => CellType::Hex8,
        other => {
            return Err(src.error(
                s.span(),
                "mesh.kind",
                format!("unknown cell type '{other}'; expected tri3, tri6, quad4, quad8, tet4, tet10 or hex8"),
            ));
        }
    })
}

fn param_f64(
    src: &Source,
    spec: &MeshSpec,
    key: &str,
    default: Option<f64>,
) -> Result<f64, StudyError> {
    let Some(p) = &spec.params else {
        return default.ok_or_else(|| {
            src.error(
                spec.generator.span(),
                format!("mesh.params.{key}"),
                "missing; expected a number",
            )
        });
    };
    match p.get_ref().get(key) {
        Some(toml::Value::Float(v)) => Ok(*v),
        Some(toml::Value::Integer(v)) => Ok(*v as f64),
        Some(_) => Err(src.error(p.span(), format!("mesh.params.{key}"), "expected a number")),
        None => default.ok_or_else(|| {
            src.error(
                p.span(),
                format!("mesh.params.{key}"),
                "missing; expected a number",
            )
        }),
    }
}

fn param_usize(
    src: &Source,
    spec: &MeshSpec,
    key: &str,
    default: Option<usize>,
) -> Result<usize, StudyError> {
    let v = param_f64(src, spec, key, default.map(|d| d as f64))?;
    if v < 1.0 || v.fract() != 0.0 {
        let span = spec
            .params
            .as_ref()
            .map_or(spec.generator.span(), |p| p.span());
        return Err(src.error(
            span,
            format!("mesh.params.{key}"),
            format!("expected a positive integer, got {v}"),
        ));
    }
    Ok(v as usize)
}

/// Refuses a `mesh.params` key that the generator does not read (`allowed`: the keys it reads;
/// none for `rectangle`, `box` and `gmsh`).
fn check_params(src: &Source, spec: &MeshSpec, allowed: &[&str]) -> Result<(), StudyError> {
    let Some(p) = &spec.params else {
        return Ok(());
    };
    let Some(k) = p.get_ref().keys().find(|k| !allowed.contains(&k.as_str())) else {
        return Ok(());
    };
    if allowed.is_empty() {
        return Err(src.error(
            p.span(),
            "mesh.params",
            format!("{} (got params.{k})", no_params(spec)),
        ));
    }
    Err(src.error(
        p.span(),
        format!("mesh.params.{k}"),
        format!(
            "unknown parameter for generator '{}'; expected one of: {}",
            spec.generator.get_ref(),
            allowed.join(", ")
        ),
    ))
}

/// What a generator without parameters takes instead, and for `gmsh` whether `file` is missing.
fn no_params(spec: &MeshSpec) -> String {
    let generator = spec.generator.get_ref();
    match generator.as_str() {
        "gmsh" => format!(
            "the gmsh generator takes no params, only file = \"<mesh>.msh\" (a Gmsh 4.1 file, relative to the study file){}",
            if spec.file.is_none() {
                "; file is missing"
            } else {
                ""
            }
        ),
        _ => format!("generator '{generator}' takes no params, only size and cells"),
    }
}

/// The generators of `[mesh] generator` (an unknown one is refused by `build_base_mesh`).
const GENERATORS: &[&str] = &[
    "rectangle",
    "box",
    "plate_with_hole",
    "annulus_sector",
    "dovetail",
    "blade_root_simple",
    "turbine_2d",
    "turbine_3d",
    "stacked_blocks",
    "block_on_incline",
    "concentric_rings",
    "cylinder_on_block",
    "gmsh",
];

/// Refuses the `[mesh]` keys that a known generator does not read: `size` and `cells` but with
/// `rectangle` and `box`, `file` but with `gmsh`.
fn check_generator_keys(src: &Source, spec: &MeshSpec) -> Result<(), StudyError> {
    let generator = spec.generator.get_ref().as_str();
    if !GENERATORS.contains(&generator) {
        return Ok(());
    }
    let used: &[&str] = match generator {
        "rectangle" | "box" => &["size", "cells"],
        "gmsh" => &["file"],
        _ => &[],
    };
    let given = [
        ("size", spec.size.as_ref().map(|v| v.span())),
        ("cells", spec.cells.as_ref().map(|v| v.span())),
        ("file", spec.file.as_ref().map(|v| v.span())),
    ];
    for (key, span) in given {
        if let Some(span) = span
            && !used.contains(&key)
        {
            let takes = match used {
                [] => "its parameters go in params = { ... }".to_string(),
                keys => format!("it takes {}", keys.join(" and ")),
            };
            return Err(src.error(
                span,
                format!("mesh.{key}"),
                format!("generator '{generator}' does not use '{key}' ({takes})"),
            ));
        }
    }
    Ok(())
}

/// The path of a mesh file named in a study file (relative to the study file).
fn mesh_file_path(src: &Source, f: &Spanned<String>) -> std::path::PathBuf {
    src.path
        .parent()
        .unwrap_or(Path::new("."))
        .join(f.get_ref())
}

/// The hash of a study's inputs: its file's text and, for a Gmsh mesh, the mesh file's bytes,
/// and the data files of laws from data (a changed input file makes a different study).
pub fn input_hash(src: &Source, file: &ModelFile) -> Result<String, StudyError> {
    let inputs = input_files(src, file)?;
    let refs: Vec<&[u8]> = inputs.iter().map(|b| b.as_slice()).collect();
    Ok(crate::store::study_hash(&src.text, &refs))
}

/// The bytes of the files a study reads besides its own: the Gmsh mesh file, then the data
/// files of laws from data, in order.
pub fn input_files(src: &Source, file: &ModelFile) -> Result<Vec<Vec<u8>>, StudyError> {
    let mut inputs: Vec<Vec<u8>> = Vec::new();
    if let (Some(f), "gmsh") = (&file.mesh.file, file.mesh.generator.get_ref().as_str()) {
        let path = mesh_file_path(src, f);
        inputs.push(
            alea_mesh::input::read_input(&path).map_err(|e| {
                src.error(f.span(), "mesh.file", format!("{}: {e}", path.display()))
            })?,
        );
    }
    // The data files of laws from data (a changed file makes a different study).
    inputs.extend(crate::data_law::data_bytes(src, &file.parameter)?);
    Ok(inputs)
}

/// Geometry and in-plane counts of the turbine generators (`mesh.params`).
const TURBINE_KEYS: &[&str] = &[
    "r_inner",
    "r_rim",
    "half_angle_deg",
    "neck_half_width",
    "flank_angle_deg",
    "contact_length",
    "runout",
    "fillet_radius",
    "shank_height",
    "n_flank",
    "n_runout",
    "n_fillet",
    "n_lobe",
    "n_slot",
    "n_below",
    "n_root",
    "n_shank",
    "lobe_grading",
    "below_grading",
];

/// The [`generate::TurbineParams`] of a `[mesh]` table (defaults for the missing keys).
fn turbine_params(src: &Source, spec: &MeshSpec) -> Result<generate::TurbineParams, StudyError> {
    let d = generate::TurbineParams::default();
    Ok(generate::TurbineParams {
        r_inner: param_f64(src, spec, "r_inner", Some(d.r_inner))?,
        r_rim: param_f64(src, spec, "r_rim", Some(d.r_rim))?,
        half_angle: param_f64(src, spec, "half_angle_deg", Some(d.half_angle.to_degrees()))?
            .to_radians(),
        neck_half_width: param_f64(src, spec, "neck_half_width", Some(d.neck_half_width))?,
        flank_angle: param_f64(
            src,
            spec,
            "flank_angle_deg",
            Some(d.flank_angle.to_degrees()),
        )?
        .to_radians(),
        contact_length: param_f64(src, spec, "contact_length", Some(d.contact_length))?,
        runout: param_f64(src, spec, "runout", Some(d.runout))?,
        fillet_radius: param_f64(src, spec, "fillet_radius", Some(d.fillet_radius))?,
        shank_height: param_f64(src, spec, "shank_height", Some(d.shank_height))?,
        n_flank: param_usize(src, spec, "n_flank", Some(d.n_flank))?,
        n_runout: param_usize(src, spec, "n_runout", Some(d.n_runout))?,
        n_fillet: param_usize(src, spec, "n_fillet", Some(d.n_fillet))?,
        n_lobe: param_usize(src, spec, "n_lobe", Some(d.n_lobe))?,
        n_slot: param_usize(src, spec, "n_slot", Some(d.n_slot))?,
        n_below: param_usize(src, spec, "n_below", Some(d.n_below))?,
        n_root: param_usize(src, spec, "n_root", Some(d.n_root))?,
        n_shank: param_usize(src, spec, "n_shank", Some(d.n_shank))?,
        lobe_grading: param_f64(src, spec, "lobe_grading", Some(d.lobe_grading))?,
        below_grading: param_f64(src, spec, "below_grading", Some(d.below_grading))?,
    })
}

/// Builds the mesh of a `[mesh]` table.
/// The largest `[mesh] split`: each refinement multiplies the cells by 4 (2D) or 8 (3D).
pub const MAX_SPLIT: i64 = 3;

/// `[mesh] split` checked (`0 ..= MAX_SPLIT`, default 0).
///
/// # Errors
/// [`StudyError::Input`] at `mesh.split`.
pub fn split_count(src: &Source, spec: &MeshSpec) -> Result<usize, StudyError> {
    match &spec.split {
        None => Ok(0),
        Some(s) if (0..=MAX_SPLIT).contains(s.get_ref()) => Ok(*s.get_ref() as usize),
        Some(s) => Err(src.error(
            s.span(),
            "mesh.split",
            format!(
                "expected 0 to {MAX_SPLIT} uniform refinements (each multiplies the cells by 4 in 2D, 8 in 3D), got {}",
                s.get_ref()
            ),
        )),
    }
}

/// The mesh of a `[mesh]` table: generated or read, then refined `split` times; its size
/// checked against the memory of its factorisations (`layout`: the parts automatic subdomains
/// leave and the factors' precision, [`crate::limits::factor_layout`]).
///
/// # Errors
/// [`StudyError::Input`] naming the field of the table at fault.
pub fn build_mesh(
    src: &Source,
    spec: &MeshSpec,
    layout: crate::limits::FactorLayout,
) -> Result<Mesh, StudyError> {
    let split = split_count(src, spec)?;
    let mesh = build_base_mesh(src, spec, layout)?;
    if split == 0 {
        return Ok(mesh);
    }
    let span = spec
        .split
        .as_ref()
        .map_or(spec.generator.span(), |s| s.span());
    crate::limits::check_split(src, span.clone(), mesh.num_nodes(), mesh.dim, split, layout)?;
    mesh.refined(split)
        .map_err(|e| src.error(span, "mesh.split", e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generators_checked_for_their_keys_are_the_generators_built() {
        let spec: MeshSpec = toml::from_str("generator = \"disc\"").unwrap();
        let e = build_mesh(
            &Source::from_text("t.toml", ""),
            &spec,
            crate::limits::FactorLayout::UNDIVIDED_DOUBLE,
        )
        .unwrap_err()
        .to_string();
        let list = e
            .split("; expected ")
            .nth(1)
            .expect("the list of generators");
        let named: Vec<&str> = list
            .split([',', ' '])
            .filter(|w| !w.is_empty() && *w != "or")
            .collect();
        assert_eq!(named.len(), GENERATORS.len(), "{e}");
        for g in GENERATORS {
            assert!(named.contains(g), "{g}: {e}");
        }
    }

    #[test]
    fn node_estimates_match_the_generated_meshes() {
        #[derive(serde::Deserialize)]
        struct F {
            mesh: MeshSpec,
        }
        let cases = [
            "generator = \"rectangle\"\nsize = [2.0, 1.0]\ncells = [30, 7]",
            "generator = \"rectangle\"\nkind = \"quad8\"\nsize = [2.0, 1.0]\ncells = [30, 7]",
            "generator = \"rectangle\"\nkind = \"tri6\"\nsize = [2.0, 1.0]\ncells = [30, 7]",
            "generator = \"box\"\nsize = [1.0, 1.0, 1.0]\ncells = [5, 6, 7]",
            "generator = \"box\"\nkind = \"tet10\"\nsize = [1.0, 1.0, 1.0]\ncells = [5, 6, 7]",
            "generator = \"plate_with_hole\"\nparams = { radius = 1.0, half_width = 5.0 }",
            "generator = \"annulus_sector\"\nparams = { r_in = 1.0, r_out = 2.0, angle_deg = 90.0, n_theta = 20 }",
            "generator = \"dovetail\"",
            "generator = \"dovetail\"\nparams = { n_flank = 30, n_below = 2 }",
            "generator = \"blade_root_simple\"",
            "generator = \"stacked_blocks\"",
            "generator = \"stacked_blocks\"\nkind = \"hex8\"\nparams = { n_z = 3 }",
            "generator = \"concentric_rings\"",
            "generator = \"turbine_2d\"\nparams = { n_flank = 6, n_runout = 2, n_fillet = 4, n_lobe = 3, n_slot = 2, n_below = 3, n_root = 4, n_shank = 4 }",
            "generator = \"turbine_3d\"\nparams = { n_flank = 6, n_runout = 2, n_fillet = 4, n_lobe = 3, n_slot = 2, n_below = 3, n_root = 4, n_shank = 4, n_z = 3 }",
            "generator = \"cylinder_on_block\"\nparams = { n = 12, m = 9, half = false }",
        ];
        for text in cases {
            let f: F = toml::from_str(&format!("[mesh]\n{text}\n")).unwrap();
            let src = Source::from_text("t.toml", text);
            let mesh =
                build_mesh(&src, &f.mesh, crate::limits::FactorLayout::UNDIVIDED_DOUBLE).unwrap();
            let (nodes, ..) = crate::limits::mesh_estimate(&f.mesh).unwrap();
            let ratio = nodes / mesh.num_nodes() as f64;
            assert!(
                (0.5..=2.0).contains(&ratio),
                "{text}: estimate {nodes}, mesh {}",
                mesh.num_nodes()
            );
        }
    }
}
