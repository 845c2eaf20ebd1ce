//! From a parsed model file to solver inputs: mesh, substructure models with their
//! constraints and load cases, interfaces and LATIN options. Every semantic error names the
//! file, line and field.

use std::path::Path;

use alea_fem::{Analysis, Constraints, Loads, Material, Model};
use std::sync::Arc;

use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, Pairing, PointField, RunInput, SearchDirection,
    Substructure,
};
use alea_mesh::{CellType, Mesh, generate};
use toml::Spanned;

use crate::expr::Expr;
use crate::params::ParamSpace;
use crate::spec::{LoadSpec, MeshSpec, ModelFile, NumOrExpr};
use crate::{Source, StudyError};

/// How the parameters enter the model: expressions evaluated for each run.
#[derive(Clone, Debug)]
pub struct Parametric {
    /// Number of parameters.
    pub nparams: usize,
    /// Young's modulus of each substructure (expression of the parameters).
    pub young: Vec<Expr>,
    /// Its value at the nominal point (the factorised reference).
    pub young_nominal: Vec<f64>,
    /// Factor of each load case of each substructure.
    pub load_factors: Vec<Vec<Expr>>,
    /// Friction profile of each interface (expression of the parameters, `x, y, z` and the
    /// defines, in that slot order).
    pub mu: Vec<Expr>,
    /// Gap profile of each interface (same variables).
    pub gap: Vec<Expr>,
    /// The `[[define]]` expressions, evaluated in order after `x, y, z`.
    pub defines: Vec<Expr>,
}

impl Parametric {
    /// The field `x -> e(theta, x, defines)` of an interface profile expression at `theta`.
    pub(crate) fn profile(&self, e: &Expr, theta: &[f64]) -> PointField {
        let e = e.clone();
        let defines = self.defines.clone();
        let theta = theta.to_vec();
        Arc::new(move |x: [f64; 3]| {
            let mut v = Vec::with_capacity(theta.len() + 3 + defines.len());
            v.extend_from_slice(&theta);
            v.extend_from_slice(&x);
            for d in &defines {
                let val = d.eval(&v);
                v.push(val);
            }
            e.eval(&v)
        })
    }

    /// `e` (an interface profile expression) at `theta` at every point of `xs`, into `out`:
    /// the values of [`Parametric::profile`], with one buffer for all points and only the
    /// defines `e` needs (directly or through later defines) evaluated - what the error
    /// estimate calls for every interface at every parameter point of its rules and maps.
    pub(crate) fn eval_profile(&self, e: &Expr, theta: &[f64], xs: &[[f64; 3]], out: &mut [f64]) {
        let first = theta.len() + 3;
        let nd = self.defines.len();
        let mut needed = vec![false; nd];
        for j in (0..nd).rev() {
            needed[j] = e.uses(first + j)
                || (j + 1..nd).any(|k| needed[k] && self.defines[k].uses(first + j));
        }
        let mut v = Vec::with_capacity(first + nd);
        v.extend_from_slice(theta);
        for (o, x) in out.iter_mut().zip(xs) {
            v.truncate(theta.len());
            v.extend_from_slice(x);
            for (d, &need) in self.defines.iter().zip(&needed) {
                let val = if need { d.eval(&v) } else { 0.0 };
                v.push(val);
            }
            *o = e.eval(&v);
        }
    }

    /// The solver input for parameter point `theta`; `params` is the normalised point used
    /// to find the nearest finished run.
    pub fn run_input(&self, theta: &[f64], params: Vec<f64>) -> RunInput {
        RunInput {
            young_factors: self
                .young
                .iter()
                .zip(&self.young_nominal)
                .map(|(e, n)| e.eval(theta) / n)
                .collect(),
            load_factors: self
                .load_factors
                .iter()
                .map(|f| f.iter().map(|e| e.eval(theta)).collect())
                .collect(),
            mu: self
                .mu
                .iter()
                .map(|e| Some(self.profile(e, theta)))
                .collect(),
            gap: self
                .gap
                .iter()
                .map(|e| Some(self.profile(e, theta)))
                .collect(),
            params,
            initial: None,
        }
    }
}

/// A model ready to solve.
#[derive(Clone, Debug)]
pub struct BuiltModel {
    /// The whole mesh (before the split into substructures).
    pub mesh: Mesh,
    /// Substructures and interfaces.
    pub assembly: Assembly,
    /// Names of each substructure's load cases (empty string for unnamed ones).
    pub load_names: Vec<Vec<String>>,
    /// Solver options.
    pub options: LatinOptions,
    /// Units as stated.
    pub units: crate::spec::UnitsSpec,
    /// How the parameters enter the model.
    pub parametric: Parametric,
    /// Where each `[[interface]]` entry is in the model file (for pairing errors).
    pub interface_sites: Vec<InterfaceSite>,
}

/// The file and lines of one `[[interface]]` entry.
#[derive(Clone, Debug)]
pub struct InterfaceSite {
    /// The model file.
    pub file: std::path::PathBuf,
    /// Line of `side2`.
    pub side2: usize,
    /// Line of `tolerance` (of `side2` if not given).
    pub tolerance: usize,
    /// Line of `search_distance` (of `side2` if not given).
    pub search_distance: usize,
}

impl BuiltModel {
    /// Sets up the LATIN solver of the model. An interface whose sides cannot be paired
    /// (node-to-node sides that do not match, no part of side 2 within the mortar search
    /// distance, ...) is an input error naming the file, the `[[interface]]` entry's line and
    /// the field.
    pub fn solver(&self) -> Result<alea_latin::LatinSolver, StudyError> {
        alea_latin::LatinSolver::new(self.assembly.clone(), self.options.clone()).map_err(|e| {
            let (name, unmatched) = match &e {
                alea_latin::LatinError::Unmatched { interface, .. } => (interface, true),
                alea_latin::LatinError::Pairing { interface, .. } => (interface, false),
                _ => return StudyError::Latin(e),
            };
            let found = self
                .assembly
                .interfaces
                .iter()
                .position(|i| &i.name == name);
            match found.and_then(|i| Some((i, self.interface_sites.get(i)?))) {
                Some((i, site)) => {
                    let (field, line) = if unmatched {
                        ("tolerance", site.tolerance)
                    } else if self.assembly.interfaces[i].search_distance.is_some() {
                        ("search_distance", site.search_distance)
                    } else {
                        ("side2", site.side2)
                    };
                    StudyError::Input {
                        file: site.file.clone(),
                        line,
                        field: format!("interface[{i}].{field}"),
                        message: e.to_string(),
                    }
                }
                None => StudyError::Latin(e),
            }
        })
    }
}

/// Compiles a number-or-expression against `vars`.
fn compile(
    src: &Source,
    v: &Spanned<NumOrExpr>,
    vars: &[&str],
    field: &str,
) -> Result<Expr, StudyError> {
    match v.get_ref() {
        NumOrExpr::Num(x) => {
            if !x.is_finite() {
                return Err(src.error(v.span(), field, format!("must be finite, got {x}")));
            }
            Ok(Expr::constant(*x))
        }
        NumOrExpr::Expr(t) => Expr::parse(t, vars)
            .map_err(|e| src.error(v.span(), field, format!("expression '{t}': {e}"))),
    }
}

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

fn check_params(src: &Source, spec: &MeshSpec, allowed: &[&str]) -> Result<(), StudyError> {
    if let Some(p) = &spec.params {
        for k in p.get_ref().keys() {
            if !allowed.contains(&k.as_str()) {
                return Err(src.error(
                    p.span(),
                    format!("mesh.params.{k}"),
                    format!(
                        "unknown parameter for generator '{}'; expected one of: {}",
                        spec.generator.get_ref(),
                        allowed.join(", ")
                    ),
                ));
            }
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

/// The hash of a study's inputs: its file's text and, for a Gmsh mesh, the mesh file's bytes
/// (a changed mesh file makes a different study).
pub fn input_hash(src: &Source, file: &ModelFile) -> Result<String, StudyError> {
    match (&file.mesh.file, file.mesh.generator.get_ref().as_str()) {
        (Some(f), "gmsh") => {
            let path = mesh_file_path(src, f);
            let bytes = std::fs::read(&path).map_err(|e| {
                src.error(f.span(), "mesh.file", format!("{}: {e}", path.display()))
            })?;
            Ok(crate::store::study_hash(&src.text, &[&bytes]))
        }
        _ => Ok(crate::store::study_hash(&src.text, &[])),
    }
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
pub fn build_mesh(src: &Source, spec: &MeshSpec) -> Result<Mesh, StudyError> {
    crate::limits::check_mesh(src, spec)?;
    let kind = |default: CellType| -> Result<CellType, StudyError> {
        spec.kind
            .as_ref()
            .map_or(Ok(default), |k| cell_type(src, k))
    };
    let gen_name = spec.generator.get_ref().as_str();
    let mesh_err =
        |e: alea_mesh::MeshError| src.error(spec.generator.span(), "mesh", e.to_string());
    let vec_field =
        |name: &str, v: &Option<Spanned<Vec<f64>>>, n: usize| -> Result<Vec<f64>, StudyError> {
            let v = v.as_ref().ok_or_else(|| {
                src.error(
                    spec.generator.span(),
                    format!("mesh.{name}"),
                    format!("missing; expected {n} numbers"),
                )
            })?;
            if v.get_ref().len() != n {
                return Err(src.error(
                    v.span(),
                    format!("mesh.{name}"),
                    format!("expected {n} values, got {}", v.get_ref().len()),
                ));
            }
            Ok(v.get_ref().clone())
        };
    let cells = |n: usize| -> Result<Vec<usize>, StudyError> {
        let v = spec.cells.as_ref().ok_or_else(|| {
            src.error(
                spec.generator.span(),
                "mesh.cells",
                format!("missing; expected {n} cell counts"),
            )
        })?;
        if v.get_ref().len() != n || v.get_ref().contains(&0) {
            return Err(src.error(
                v.span(),
                "mesh.cells",
                format!("expected {n} positive cell counts"),
            ));
        }
        Ok(v.get_ref().clone())
    };
    match gen_name {
        "rectangle" => {
            check_params(src, spec, &[])?;
            let s = vec_field("size", &spec.size, 2)?;
            let c = cells(2)?;
            generate::rectangle(s[0], s[1], c[0], c[1], kind(CellType::Quad4)?).map_err(mesh_err)
        }
        "box" => {
            check_params(src, spec, &[])?;
            let s = vec_field("size", &spec.size, 3)?;
            let c = cells(3)?;
            generate::box_mesh([s[0], s[1], s[2]], [c[0], c[1], c[2]], kind(CellType::Hex8)?).map_err(mesh_err)
        }
        "plate_with_hole" => {
            check_params(src, spec, &["radius", "half_width", "n_arc", "n_radial", "grading"])?;
            generate::plate_with_hole(
                param_f64(src, spec, "radius", None)?,
                param_f64(src, spec, "half_width", None)?,
                param_usize(src, spec, "n_arc", Some(16))?,
                param_usize(src, spec, "n_radial", Some(16))?,
                param_f64(src, spec, "grading", Some(4.0))?,
                kind(CellType::Quad8)?,
            )
            .map_err(mesh_err)
        }
        "annulus_sector" => {
            check_params(src, spec, &["r_in", "r_out", "angle_deg", "n_radial", "n_theta"])?;
            generate::annulus_sector(
                param_f64(src, spec, "r_in", None)?,
                param_f64(src, spec, "r_out", None)?,
                param_f64(src, spec, "angle_deg", None)?.to_radians(),
                param_usize(src, spec, "n_radial", Some(8))?,
                param_usize(src, spec, "n_theta", Some(8))?,
                kind(CellType::Quad8)?,
            )
            .map_err(mesh_err)
        }
        "dovetail" => {
            let d = generate::DovetailParams::default();
            check_params(src, spec, &[
                "r_inner", "r_rim", "half_angle_deg", "neck_half_width", "bottom_half_width", "flank_height",
                "slot_gap", "fillet_radius", "shank_height", "n_flank", "n_root", "n_shank", "n_lobe", "n_wall",
                "n_slot", "n_below",
            ])?;
            let p = generate::DovetailParams {
                r_inner: param_f64(src, spec, "r_inner", Some(d.r_inner))?,
                r_rim: param_f64(src, spec, "r_rim", Some(d.r_rim))?,
                half_angle: param_f64(src, spec, "half_angle_deg", Some(d.half_angle.to_degrees()))?.to_radians(),
                neck_half_width: param_f64(src, spec, "neck_half_width", Some(d.neck_half_width))?,
                bottom_half_width: param_f64(src, spec, "bottom_half_width", Some(d.bottom_half_width))?,
                flank_height: param_f64(src, spec, "flank_height", Some(d.flank_height))?,
                slot_gap: param_f64(src, spec, "slot_gap", Some(d.slot_gap))?,
                fillet_radius: param_f64(src, spec, "fillet_radius", Some(d.fillet_radius))?,
                shank_height: param_f64(src, spec, "shank_height", Some(d.shank_height))?,
                n_flank: param_usize(src, spec, "n_flank", Some(d.n_flank))?,
                n_root: param_usize(src, spec, "n_root", Some(d.n_root))?,
                n_shank: param_usize(src, spec, "n_shank", Some(d.n_shank))?,
                n_lobe: param_usize(src, spec, "n_lobe", Some(d.n_lobe))?,
                n_wall: param_usize(src, spec, "n_wall", Some(d.n_wall))?,
                n_slot: param_usize(src, spec, "n_slot", Some(d.n_slot))?,
                n_below: param_usize(src, spec, "n_below", Some(d.n_below))?,
            };
            generate::dovetail_root_and_disk(&p, kind(CellType::Quad4)?).map_err(mesh_err)
        }
        "blade_root_simple" => {
            let d = generate::BladeRootParams::default();
            check_params(src, spec, &[
                "half_width", "bottom_half_width", "neck_half_width", "flank_height", "shank_height",
                "n_flank", "n_side", "n_root", "n_shank",
            ])?;
            let p = generate::BladeRootParams {
                half_width: param_f64(src, spec, "half_width", Some(d.half_width))?,
                bottom_half_width: param_f64(src, spec, "bottom_half_width", Some(d.bottom_half_width))?,
                neck_half_width: param_f64(src, spec, "neck_half_width", Some(d.neck_half_width))?,
                flank_height: param_f64(src, spec, "flank_height", Some(d.flank_height))?,
                shank_height: param_f64(src, spec, "shank_height", Some(d.shank_height))?,
                n_flank: param_usize(src, spec, "n_flank", Some(d.n_flank))?,
                n_side: param_usize(src, spec, "n_side", Some(d.n_side))?,
                n_root: param_usize(src, spec, "n_root", Some(d.n_root))?,
                n_shank: param_usize(src, spec, "n_shank", Some(d.n_shank))?,
            };
            generate::blade_root_simple(&p, kind(CellType::Quad4)?).map_err(mesh_err)
        }
        "stacked_blocks" | "block_on_incline" => {
            let d = generate::StackedBlocks::default();
            let incline = gen_name == "block_on_incline";
            let mut keys = vec!["width", "h_lower", "h_upper", "n_x", "n_lower", "n_upper", "depth", "n_z"];
            if incline {
                keys.push("angle_deg");
            }
            check_params(src, spec, &keys)?;
            let p = generate::StackedBlocks {
                width: param_f64(src, spec, "width", Some(d.width))?,
                h_lower: param_f64(src, spec, "h_lower", Some(d.h_lower))?,
                h_upper: param_f64(src, spec, "h_upper", Some(d.h_upper))?,
                n_x: param_usize(src, spec, "n_x", Some(d.n_x))?,
                n_lower: param_usize(src, spec, "n_lower", Some(d.n_lower))?,
                n_upper: param_usize(src, spec, "n_upper", Some(d.n_upper))?,
            };
            // Hex8: the Quad4 blocks extruded over `depth` in `n_z` layers (3D).
            let kind = kind(CellType::Quad4)?;
            let plane = if kind == CellType::Hex8 { CellType::Quad4 } else { kind };
            let mesh = if incline {
                let a = param_f64(src, spec, "angle_deg", None)?.to_radians();
                generate::block_on_incline(&p, a, plane).map_err(mesh_err)?
            } else {
                generate::stacked_blocks(&p, plane).map_err(mesh_err)?
            };
            if kind == CellType::Hex8 {
                let depth = param_f64(src, spec, "depth", Some(p.width))?;
                let n_z = param_usize(src, spec, "n_z", Some(p.n_x))?;
                generate::extrude(&mesh, n_z, depth).map_err(mesh_err)
            } else {
                Ok(mesh)
            }
        }
        "concentric_rings" => {
            let d = generate::ConcentricRings::default();
            check_params(src, spec, &["r_in", "r_contact", "r_out", "angle_deg", "n_inner", "n_outer", "n_theta"])?;
            let p = generate::ConcentricRings {
                r_in: param_f64(src, spec, "r_in", Some(d.r_in))?,
                r_contact: param_f64(src, spec, "r_contact", Some(d.r_contact))?,
                r_out: param_f64(src, spec, "r_out", Some(d.r_out))?,
                angle: param_f64(src, spec, "angle_deg", Some(d.angle.to_degrees()))?.to_radians(),
                n_inner: param_usize(src, spec, "n_inner", Some(d.n_inner))?,
                n_outer: param_usize(src, spec, "n_outer", Some(d.n_outer))?,
                n_theta: param_usize(src, spec, "n_theta", Some(d.n_theta))?,
            };
            generate::concentric_rings(&p, kind(CellType::Quad4)?).map_err(mesh_err)
        }
        "cylinder_on_block" => {
            let d = generate::CylinderOnBlock::default();
            check_params(src, spec, &["a", "l", "n", "m", "half"])?;
            let half = match spec.params.as_ref().and_then(|p| p.get_ref().get("half")) {
                None => d.half,
                Some(toml::Value::Boolean(b)) => *b,
                Some(_) => {
                    let span = spec.params.as_ref().map_or(spec.generator.span(), |p| p.span());
                    return Err(src.error(span, "mesh.params.half", "expected true or false"));
                }
            };
            let p = generate::CylinderOnBlock {
                a: param_f64(src, spec, "a", Some(d.a))?,
                l: param_f64(src, spec, "l", Some(d.l))?,
                n: param_usize(src, spec, "n", Some(d.n))?,
                m: param_usize(src, spec, "m", Some(d.m))?,
                half,
            };
            generate::cylinder_on_block(&p, kind(CellType::Quad4)?).map_err(mesh_err)
        }
        "turbine_2d" => {
            check_params(src, spec, TURBINE_KEYS)?;
            generate::turbine_2d(&turbine_params(src, spec)?, kind(CellType::Quad8)?).map_err(mesh_err)
        }
        "turbine_3d" => {
            let keys: Vec<&str> = TURBINE_KEYS.iter().copied().chain(["depth", "n_z"]).collect();
            check_params(src, spec, &keys)?;
            if kind(CellType::Hex8)? != CellType::Hex8 {
                let span = spec.kind.as_ref().map_or(spec.generator.span(), |k| k.span());
                return Err(src.error(span, "mesh.kind", "turbine_3d makes HEX8 cells (the Quad4 model extruded)"));
            }
            let depth = param_f64(src, spec, "depth", Some(20.0))?;
            let n_z = param_usize(src, spec, "n_z", Some(10))?;
            generate::turbine_3d(&turbine_params(src, spec)?, depth, n_z).map_err(mesh_err)
        }
        "gmsh" => {
            check_params(src, spec, &[])?;
            let f = spec.file.as_ref().ok_or_else(|| src.error(spec.generator.span(), "mesh.file", "missing; expected the path of a Gmsh .msh file"))?;
            let path = mesh_file_path(src, f);
            // Every Gmsh error (missing file, directory, truncated or malformed content) is an
            // input error of this field; the message carries the mesh file's own line.
            alea_mesh::read_msh(&path).map_err(|e| src.error(f.span(), "mesh.file", e.to_string()))
        }
        other => Err(src.error(
            spec.generator.span(),
            "mesh.generator",
            format!("unknown generator '{other}'; expected rectangle, box, plate_with_hole, annulus_sector, dovetail, blade_root_simple, turbine_2d, turbine_3d, stacked_blocks, block_on_incline, concentric_rings, cylinder_on_block or gmsh"),
        )),
    }
}

fn positive(src: &Source, v: &Spanned<f64>, field: &str) -> Result<f64, StudyError> {
    let x = *v.get_ref();
    if !(x.is_finite() && x > 0.0) {
        return Err(src.error(
            v.span(),
            field,
            format!("must be a finite number > 0, got {x}"),
        ));
    }
    Ok(x)
}

fn finite(src: &Source, v: &Spanned<f64>, field: &str) -> Result<f64, StudyError> {
    let x = *v.get_ref();
    if !x.is_finite() {
        return Err(src.error(v.span(), field, format!("must be finite, got {x}")));
    }
    Ok(x)
}

fn vec3(
    src: &Source,
    v: &Spanned<Vec<f64>>,
    dim: usize,
    field: &str,
) -> Result<[f64; 3], StudyError> {
    let a = v.get_ref();
    if a.len() != dim || a.iter().any(|x| !x.is_finite()) {
        return Err(src.error(
            v.span(),
            field,
            format!("expected {dim} finite components, got {a:?}"),
        ));
    }
    let mut o = [0.0; 3];
    o[..dim].copy_from_slice(a);
    Ok(o)
}

fn build_load(
    src: &Source,
    model: &Model,
    l: &LoadSpec,
    field: &str,
) -> Result<Vec<f64>, StudyError> {
    let dim = model.mesh.dim;
    let kinds = [
        l.pressure.is_some(),
        l.traction.is_some(),
        l.force.is_some(),
        l.body.is_some(),
        l.centrifugal.is_some(),
    ];
    let span = l
        .group
        .as_ref()
        .map(|g| g.span())
        .or(l.name.as_ref().map(|n| n.span()))
        .unwrap_or(0..0);
    if kinds.iter().filter(|&&k| k).count() != 1 {
        return Err(src.error(
            span,
            field,
            "expected exactly one of pressure, traction, force, body, centrifugal",
        ));
    }
    let group = l.group.as_ref().map(|g| g.get_ref().as_str());
    let need_group = || {
        group.ok_or_else(|| {
            src.error(
                span.clone(),
                format!("{field}.group"),
                "missing; this load needs a group",
            )
        })
    };
    let fem = |e: alea_fem::FemError| {
        src.error(
            l.group.as_ref().map_or(0..0, |g| g.span()),
            format!("{field}.group"),
            e.to_string(),
        )
    };
    let mut loads = Loads::new(model);
    if let Some(p) = &l.pressure {
        let p = finite(src, p, &format!("{field}.pressure"))?;
        loads.pressure(model, need_group()?, p).map_err(fem)?;
    } else if let Some(t) = &l.traction {
        let t = vec3(src, t, dim, &format!("{field}.traction"))?;
        loads
            .traction(model, need_group()?, move |_, _| t)
            .map_err(fem)?;
    } else if let Some(f) = &l.force {
        let f = vec3(src, f, dim, &format!("{field}.force"))?;
        loads.nodal_force(model, need_group()?, f).map_err(fem)?;
    } else if let Some(b) = &l.body {
        let b = vec3(src, b, dim, &format!("{field}.body"))?;
        loads.body_force(model, group, move |_, _| b).map_err(fem)?;
    } else if let Some(c) = &l.centrifugal {
        let cs = c.get_ref();
        let omega = finite(src, &cs.omega, &format!("{field}.centrifugal.omega"))?;
        let center = cs.center.clone().unwrap_or_default();
        let axis = cs.axis.clone().unwrap_or_else(|| vec![0.0, 0.0, 1.0]);
        if center.len() > 3 || axis.len() != 3 {
            return Err(src.error(
                c.span(),
                format!("{field}.centrifugal"),
                "center has at most 3 and axis exactly 3 components",
            ));
        }
        let mut p = [0.0; 3];
        p[..center.len()].copy_from_slice(&center);
        loads
            .centrifugal(model, group, omega, p, [axis[0], axis[1], axis[2]])
            .map_err(fem)?;
    }
    Ok(loads.f)
}

/// Builds meshes, models, constraints, loads and interfaces of a model file.
/// Builds meshes, models, constraints, loads and interfaces of a model file; parameters enter
/// through `params` (the model is set up at their nominal point).
pub fn build_model(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
) -> Result<BuiltModel, StudyError> {
    let pvars: Vec<&str> = params.names.iter().map(|s| s.as_str()).collect();
    let mut profile_vars: Vec<&str> = pvars.clone();
    profile_vars.extend(["x", "y", "z"]);
    let mut defines = Vec::new();
    for (i, d) in file.define.iter().enumerate() {
        let e = Expr::parse(d.value.get_ref(), &profile_vars)
            .map_err(|e| src.error(d.value.span(), format!("define[{i}].value"), e.to_string()))?;
        let name = d.name.get_ref().as_str();
        if profile_vars.contains(&name)
            || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        {
            return Err(src.error(
                d.name.span(),
                format!("define[{i}].name"),
                format!("'{name}' is not a new usable name"),
            ));
        }
        profile_vars.push(name);
        defines.push(e);
    }
    let mut young_e = Vec::new();
    let mut young_nominal = Vec::new();
    let mut load_factors = Vec::new();
    let mesh = build_mesh(src, &file.mesh)?;
    let th = file
        .analysis
        .thickness
        .as_ref()
        .map(|t| positive(src, t, "analysis.thickness"))
        .transpose()?
        .unwrap_or(1.0);
    let analysis = match file.analysis.kind.get_ref().as_str() {
        "plane_strain" => Analysis::PlaneStrain { thickness: th },
        "plane_stress" => Analysis::PlaneStress { thickness: th },
        "solid" => Analysis::Solid,
        other => {
            return Err(src.error(
                file.analysis.kind.span(),
                "analysis.type",
                format!("unknown analysis '{other}'; expected plane_strain, plane_stress or solid"),
            ));
        }
    };
    if analysis.dim() != mesh.dim {
        return Err(src.error(
            file.analysis.kind.span(),
            "analysis.type",
            format!(
                "a {}D analysis does not fit the {}D mesh",
                analysis.dim(),
                mesh.dim
            ),
        ));
    }
    if file.substructure.is_empty() {
        return Err(src.error(
            0..0,
            "substructure",
            "at least one [[substructure]] is needed",
        ));
    }
    let mut subs = Vec::new();
    let mut load_names = Vec::new();
    let mut names: Vec<String> = Vec::new();
    for (i, s) in file.substructure.iter().enumerate() {
        let f = |k: &str| format!("substructure[{i}].{k}");
        let name = s.name.get_ref().clone();
        if names.contains(&name) {
            return Err(src.error(
                s.name.span(),
                f("name"),
                format!("duplicate substructure name '{name}'"),
            ));
        }
        names.push(name.clone());
        let ye = compile(src, &s.young, &pvars, &f("young"))?;
        let young = ye.eval(&params.nominal);
        young_e.push(ye);
        young_nominal.push(young);
        let poisson = *s.poisson.get_ref();
        let density = s.density.as_ref().map_or(0.0, |d| *d.get_ref());
        let material = Material::new(young, poisson, density).map_err(|e| {
            let (span, field) = if !(young.is_finite() && young > 0.0) {
                (s.young.span(), f("young"))
            } else if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
                (s.poisson.span(), f("poisson"))
            } else {
                (
                    s.density.as_ref().map_or(s.name.span(), |d| d.span()),
                    f("density"),
                )
            };
            src.error(span, field, e.to_string())
        })?;
        let sub_mesh = match &s.cells {
            Some(c) => {
                mesh.extract(&[c.get_ref().as_str()])
                    .map_err(|e| src.error(c.span(), f("cells"), e.to_string()))?
                    .0
            }
            None => mesh.clone(),
        };
        let mut model = Model::new(sub_mesh, analysis)
            .map_err(|e| src.error(s.name.span(), f("name"), e.to_string()))?;
        model.set_material_all(material);
        let mut cons = Constraints::new();
        for (j, c) in s.constraint.iter().enumerate() {
            let cf = |k: &str| format!("substructure[{i}].constraint[{j}].{k}");
            let g = c.group.get_ref().as_str();
            let ge = |e: alea_fem::FemError| src.error(c.group.span(), cf("group"), e.to_string());
            let mut any = false;
            for (comp, v) in [&c.x, &c.y, &c.z].into_iter().enumerate() {
                if let Some(v) = v {
                    let val = finite(src, v, &cf(["x", "y", "z"][comp]))?;
                    if comp >= model.mesh.dim {
                        return Err(src.error(v.span(), cf("z"), "no z component in a 2D model"));
                    }
                    cons.fix_component(&model.mesh, g, comp, val).map_err(ge)?;
                    any = true;
                }
            }
            if let Some(v) = &c.normal {
                let val = finite(src, v, &cf("normal"))?;
                cons.fix_normal(&model.mesh, g, val).map_err(ge)?;
                any = true;
            }
            if !any {
                return Err(src.error(
                    c.group.span(),
                    cf("group"),
                    "constraint imposes nothing; give x, y, z and/or normal",
                ));
            }
        }
        let mut cases = Vec::new();
        let mut lnames = Vec::new();
        let mut factors = Vec::new();
        for (j, l) in s.load.iter().enumerate() {
            let field = format!("substructure[{i}].load[{j}]");
            cases.push(build_load(src, &model, l, &field)?);
            lnames.push(
                l.name
                    .as_ref()
                    .map_or(String::new(), |n| n.get_ref().clone()),
            );
            factors.push(match &l.factor {
                Some(fe) => compile(src, fe, &pvars, &format!("{field}.factor"))?,
                None => Expr::constant(1.0),
            });
        }
        load_factors.push(factors);
        subs.push(Substructure {
            name,
            model,
            constraints: cons,
            load_cases: cases,
        });
        load_names.push(lnames);
    }
    let mut parametric = Parametric {
        nparams: params.names.len(),
        young: young_e,
        young_nominal,
        load_factors,
        mu: Vec::new(),
        gap: Vec::new(),
        defines,
    };
    let mut interfaces = Vec::new();
    let mut interface_sites = Vec::new();
    for (i, it) in file.interface.iter().enumerate() {
        let f = |k: &str| format!("interface[{i}].{k}");
        let side = |v: &Spanned<[String; 2]>, key: &str| -> Result<(usize, String), StudyError> {
            let [sub, group] = v.get_ref();
            let idx = names.iter().position(|n| n == sub).ok_or_else(|| {
                src.error(
                    v.span(),
                    f(key),
                    format!(
                        "unknown substructure '{sub}'; defined: {}",
                        names.join(", ")
                    ),
                )
            })?;
            if subs[idx].model.mesh.facet_group(group).is_err() {
                let avail: Vec<&String> = subs[idx].model.mesh.facet_groups.keys().collect();
                return Err(src.error(
                    v.span(),
                    f(key),
                    format!("substructure '{sub}' has no facet group '{group}'; it has: {avail:?}"),
                ));
            }
            Ok((idx, group.clone()))
        };
        let (s1, g1) = side(&it.side1, "side1")?;
        let (s2, g2) = side(&it.side2, "side2")?;
        let name = it.name.get_ref();
        let mut spec = match it.law.get_ref().as_str() {
            "perfect" => InterfaceSpec::perfect(name, s1, &g1, s2, &g2),
            "coulomb" => InterfaceSpec::coulomb(name, s1, &g1, s2, &g2, 0.0),
            other => {
                return Err(src.error(
                    it.law.span(),
                    f("law"),
                    format!("unknown law '{other}'; expected perfect or coulomb"),
                ));
            }
        };
        let mu = match &it.mu {
            Some(m) => {
                if let NumOrExpr::Num(v) = m.get_ref()
                    && !(v.is_finite() && *v >= 0.0)
                {
                    return Err(src.error(
                        m.span(),
                        f("mu"),
                        format!("friction coefficient must be finite and >= 0, got {v}"),
                    ));
                }
                compile(src, m, &profile_vars, &f("mu"))?
            }
            None => Expr::constant(0.0),
        };
        let gap = match &it.gap {
            Some(g) => compile(src, g, &profile_vars, &f("gap"))?,
            None => Expr::constant(0.0),
        };
        if let Some(p) = &it.pairing {
            spec.pairing = match p.get_ref().as_str() {
                "auto" => Pairing::Auto,
                "node" => Pairing::NodeToNode,
                "mortar" => Pairing::Mortar,
                other => {
                    return Err(src.error(
                        p.span(),
                        f("pairing"),
                        format!("unknown pairing '{other}'; expected auto, node or mortar"),
                    ));
                }
            };
        }
        if let Some(t) = &it.tolerance {
            spec.match_tolerance = Some(positive(src, t, &f("tolerance"))?);
        }
        if let Some(d) = &it.search_distance {
            let v = *d.get_ref();
            if !(v.is_finite() && v >= 0.0) {
                return Err(src.error(
                    d.span(),
                    f("search_distance"),
                    format!("must be finite and >= 0, got {v}"),
                ));
            }
            spec.search_distance = Some(v);
        }
        let side2_line = src.line_of(it.side2.span().start);
        let line_or =
            |v: Option<std::ops::Range<usize>>| v.map_or(side2_line, |r| src.line_of(r.start));
        interface_sites.push(InterfaceSite {
            file: src.path.clone(),
            side2: side2_line,
            tolerance: line_or(it.tolerance.as_ref().map(|t| t.span())),
            search_distance: line_or(it.search_distance.as_ref().map(|t| t.span())),
        });
        spec.mu = parametric.profile(&mu, &params.nominal);
        spec.gap = parametric.profile(&gap, &params.nominal);
        parametric.mu.push(mu);
        parametric.gap.push(gap);
        interfaces.push(spec);
    }
    let sv = &file.solver;
    let mut options = LatinOptions::default();
    if let Some(t) = &sv.tolerance {
        options.tolerance = positive(src, t, "solver.tolerance")?;
    }
    if let Some(m) = &sv.max_iterations {
        options.max_iterations = *m.get_ref();
    }
    if let Some(r) = &sv.relaxation {
        let v = *r.get_ref();
        if !(v > 0.0 && v <= 1.0) {
            return Err(src.error(
                r.span(),
                "solver.relaxation",
                format!("must be in (0, 1], got {v}"),
            ));
        }
        options.relaxation = v;
    }
    if let Some(a) = &sv.acceleration {
        options.acceleration = *a.get_ref();
    }
    if let Some(c) = &sv.coarse {
        options.coarse = *c.get_ref();
    }
    if let Some(t) = &sv.equilibrium_tolerance {
        options.equilibrium_tolerance = positive(src, t, "solver.equilibrium_tolerance")?;
    }
    if let Some(t) = &sv.max_rigid_motion {
        options.max_rigid_motion = positive(src, t, "solver.max_rigid_motion")?;
    }
    if let Some(k) = &sv.search_direction_factor {
        options.search_direction = SearchDirection::Auto {
            factor: positive(src, k, "solver.search_direction_factor")?,
        };
    }
    let built = BuiltModel {
        mesh,
        assembly: Assembly { subs, interfaces },
        load_names,
        options,
        units: file.units.clone(),
        parametric,
        interface_sites,
    };
    crate::checks::check_interfaces(src, &file.interface, &built)?;
    Ok(built)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `eval_profile` skips the defines a profile does not need and gives the values of
    /// `profile`, bit for bit.
    #[test]
    fn profiles_evaluated_in_bulk_are_the_pointwise_ones() {
        let vars = ["a", "b", "x", "y", "z", "s", "xr", "xl", "zw"];
        let e = |t: &str, n: usize| Expr::parse(t, &vars[..n]).unwrap();
        let defines = vec![
            e("(199.84 - y) / 6.55", 5),
            e("0.7 + 0.8 * s", 6),
            e("1.5 - 0.8 * s", 7),
            e("a * (0.075 * z^2 - 0.55 * z + 1) + b * z", 8),
        ];
        let mu = e(
            "0.2 + 0.6 * (a * exp(-(xr - 0.7)^2 / 0.13) + b * exp(-(xr - 1.5)^2 / 0.13)) * zw",
            9,
        );
        let p = Parametric {
            nparams: 2,
            young: vec![],
            young_nominal: vec![],
            load_factors: vec![],
            mu: vec![mu.clone()],
            gap: vec![],
            defines,
        };
        let xs: Vec<[f64; 3]> = (0..50)
            .map(|i| {
                let t = i as f64 / 49.0;
                [3.0 + t, 199.8 - 6.5 * t, 20.0 * t * t]
            })
            .collect();
        for theta in [[0.0, 1.0], [0.3, 0.8], [1.0, 0.0]] {
            let mut out = vec![0.0; xs.len()];
            p.eval_profile(&mu, &theta, &xs, &mut out);
            let f = p.profile(&mu, &theta);
            for (x, o) in xs.iter().zip(&out) {
                assert_eq!(f(*x).to_bits(), o.to_bits(), "{x:?}");
            }
            assert!(out.iter().all(|v| v.is_finite()));
        }
    }
}
