//! The generators' dispatch of a `[mesh]` table: each generator's parameters read and checked,
//! and its mesh built (or a Gmsh file read).

use alea_mesh::{CellType, Mesh, generate};
use toml::Spanned;

use super::{
    TURBINE_KEYS, cell_type, check_generator_keys, check_params, mesh_file_path, param_f64,
    param_usize, turbine_params,
};
use crate::spec::MeshSpec;
use crate::{Source, StudyError};

/// A `[mesh]` table and the helpers its generators share.
struct MeshInput<'a> {
    src: &'a Source,
    spec: &'a MeshSpec,
}

impl MeshInput<'_> {
    /// The table's cell type (`kind`), `default` when not given.
    fn kind(&self, default: CellType) -> Result<CellType, StudyError> {
        self.spec
            .kind
            .as_ref()
            .map_or(Ok(default), |k| cell_type(self.src, k))
    }

    /// A generator's error, at the `generator` line.
    fn mesh_err(&self, e: alea_mesh::MeshError) -> StudyError {
        self.src
            .error(self.spec.generator.span(), "mesh", e.to_string())
    }

    /// The `n` numbers of the vector field `name` (`v`), which must be given.
    fn vec_field(
        &self,
        name: &str,
        v: &Option<Spanned<Vec<f64>>>,
        n: usize,
    ) -> Result<Vec<f64>, StudyError> {
        let src = self.src;
        let v = v.as_ref().ok_or_else(|| {
            src.error(
                self.spec.generator.span(),
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
    }

    /// The `n` positive cell counts of `cells`, which must be given.
    fn cells(&self, n: usize) -> Result<Vec<usize>, StudyError> {
        let src = self.src;
        let v = self.spec.cells.as_ref().ok_or_else(|| {
            src.error(
                self.spec.generator.span(),
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
    }

    /// The `f64` parameter `key` (`default` if not given).
    fn f64(&self, key: &str, default: Option<f64>) -> Result<f64, StudyError> {
        param_f64(self.src, self.spec, key, default)
    }

    /// The `usize` parameter `key` (`default` if not given).
    fn usize(&self, key: &str, default: Option<usize>) -> Result<usize, StudyError> {
        param_usize(self.src, self.spec, key, default)
    }
}

/// The mesh of the table's generator, before any split.
pub(super) fn build_base_mesh(
    src: &Source,
    spec: &MeshSpec,
    layout: crate::limits::FactorLayout,
) -> Result<Mesh, StudyError> {
    check_generator_keys(src, spec)?;
    crate::limits::check_mesh(src, spec, layout)?;
    let input = MeshInput { src, spec };
    let mesh_err = |e| input.mesh_err(e);
    match spec.generator.get_ref().as_str() {
        "rectangle" => {
            check_params(src, spec, &[])?;
            let s = input.vec_field("size", &spec.size, 2)?;
            let c = input.cells(2)?;
            generate::rectangle(s[0], s[1], c[0], c[1], input.kind(CellType::Quad4)?)
                .map_err(mesh_err)
        }
        "box" => {
            check_params(src, spec, &[])?;
            let s = input.vec_field("size", &spec.size, 3)?;
            let c = input.cells(3)?;
            generate::box_mesh(
                [s[0], s[1], s[2]],
                [c[0], c[1], c[2]],
                input.kind(CellType::Hex8)?,
            )
            .map_err(mesh_err)
        }
        "plate_with_hole" => {
            check_params(
                src,
                spec,
                &["radius", "half_width", "n_arc", "n_radial", "grading"],
            )?;
            generate::plate_with_hole(
                input.f64("radius", None)?,
                input.f64("half_width", None)?,
                input.usize("n_arc", Some(16))?,
                input.usize("n_radial", Some(16))?,
                input.f64("grading", Some(4.0))?,
                input.kind(CellType::Quad8)?,
            )
            .map_err(mesh_err)
        }
        "annulus_sector" => {
            check_params(
                src,
                spec,
                &["r_in", "r_out", "angle_deg", "n_radial", "n_theta"],
            )?;
            generate::annulus_sector(
                input.f64("r_in", None)?,
                input.f64("r_out", None)?,
                input.f64("angle_deg", None)?.to_radians(),
                input.usize("n_radial", Some(8))?,
                input.usize("n_theta", Some(8))?,
                input.kind(CellType::Quad8)?,
            )
            .map_err(mesh_err)
        }
        "dovetail" => dovetail_mesh(&input),
        "blade_root_simple" => blade_root_mesh(&input),
        gen_name @ ("stacked_blocks" | "block_on_incline") => {
            stacked_blocks_mesh(&input, gen_name == "block_on_incline")
        }
        "concentric_rings" => concentric_rings_mesh(&input),
        "cylinder_on_block" => cylinder_on_block_mesh(&input),
        "turbine_2d" => {
            check_params(src, spec, TURBINE_KEYS)?;
            generate::turbine_2d(&turbine_params(src, spec)?, input.kind(CellType::Quad8)?)
                .map_err(mesh_err)
        }
        "turbine_3d" => turbine_3d_mesh(&input),
        "gmsh" => gmsh_mesh(&input),
        other => Err(src.error(
            spec.generator.span(),
            "mesh.generator",
            format!("unknown generator '{other}'; expected rectangle, box, plate_with_hole, annulus_sector, dovetail, blade_root_simple, turbine_2d, turbine_3d, stacked_blocks, block_on_incline, concentric_rings, cylinder_on_block or gmsh"),
        )),
    }
}

/// `dovetail`: a dovetail root in its disk slot.
fn dovetail_mesh(input: &MeshInput) -> Result<Mesh, StudyError> {
    let d = generate::DovetailParams::default();
    check_params(
        input.src,
        input.spec,
        &[
            "r_inner",
            "r_rim",
            "half_angle_deg",
            "neck_half_width",
            "bottom_half_width",
            "flank_height",
            "slot_gap",
            "fillet_radius",
            "shank_height",
            "n_flank",
            "n_root",
            "n_shank",
            "n_lobe",
            "n_wall",
            "n_slot",
            "n_below",
        ],
    )?;
    let p = generate::DovetailParams {
        r_inner: input.f64("r_inner", Some(d.r_inner))?,
        r_rim: input.f64("r_rim", Some(d.r_rim))?,
        half_angle: input
            .f64("half_angle_deg", Some(d.half_angle.to_degrees()))?
            .to_radians(),
        neck_half_width: input.f64("neck_half_width", Some(d.neck_half_width))?,
        bottom_half_width: input.f64("bottom_half_width", Some(d.bottom_half_width))?,
        flank_height: input.f64("flank_height", Some(d.flank_height))?,
        slot_gap: input.f64("slot_gap", Some(d.slot_gap))?,
        fillet_radius: input.f64("fillet_radius", Some(d.fillet_radius))?,
        shank_height: input.f64("shank_height", Some(d.shank_height))?,
        n_flank: input.usize("n_flank", Some(d.n_flank))?,
        n_root: input.usize("n_root", Some(d.n_root))?,
        n_shank: input.usize("n_shank", Some(d.n_shank))?,
        n_lobe: input.usize("n_lobe", Some(d.n_lobe))?,
        n_wall: input.usize("n_wall", Some(d.n_wall))?,
        n_slot: input.usize("n_slot", Some(d.n_slot))?,
        n_below: input.usize("n_below", Some(d.n_below))?,
    };
    generate::dovetail_root_and_disk(&p, input.kind(CellType::Quad4)?)
        .map_err(|e| input.mesh_err(e))
}

/// `blade_root_simple`: the simple blade root in its disk.
fn blade_root_mesh(input: &MeshInput) -> Result<Mesh, StudyError> {
    let d = generate::BladeRootParams::default();
    check_params(
        input.src,
        input.spec,
        &[
            "half_width",
            "bottom_half_width",
            "neck_half_width",
            "flank_height",
            "shank_height",
            "n_flank",
            "n_side",
            "n_root",
            "n_shank",
        ],
    )?;
    let p = generate::BladeRootParams {
        half_width: input.f64("half_width", Some(d.half_width))?,
        bottom_half_width: input.f64("bottom_half_width", Some(d.bottom_half_width))?,
        neck_half_width: input.f64("neck_half_width", Some(d.neck_half_width))?,
        flank_height: input.f64("flank_height", Some(d.flank_height))?,
        shank_height: input.f64("shank_height", Some(d.shank_height))?,
        n_flank: input.usize("n_flank", Some(d.n_flank))?,
        n_side: input.usize("n_side", Some(d.n_side))?,
        n_root: input.usize("n_root", Some(d.n_root))?,
        n_shank: input.usize("n_shank", Some(d.n_shank))?,
    };
    generate::blade_root_simple(&p, input.kind(CellType::Quad4)?).map_err(|e| input.mesh_err(e))
}

/// `stacked_blocks`, or `block_on_incline` (`incline`): two blocks, extruded to Hex8 in 3D.
fn stacked_blocks_mesh(input: &MeshInput, incline: bool) -> Result<Mesh, StudyError> {
    let mesh_err = |e| input.mesh_err(e);
    let d = generate::StackedBlocks::default();
    let mut keys = vec![
        "width", "h_lower", "h_upper", "n_x", "n_lower", "n_upper", "depth", "n_z",
    ];
    if incline {
        keys.push("angle_deg");
    }
    check_params(input.src, input.spec, &keys)?;
    let p = generate::StackedBlocks {
        width: input.f64("width", Some(d.width))?,
        h_lower: input.f64("h_lower", Some(d.h_lower))?,
        h_upper: input.f64("h_upper", Some(d.h_upper))?,
        n_x: input.usize("n_x", Some(d.n_x))?,
        n_lower: input.usize("n_lower", Some(d.n_lower))?,
        n_upper: input.usize("n_upper", Some(d.n_upper))?,
    };
    // Hex8: the Quad4 blocks extruded over `depth` in `n_z` layers (3D).
    let kind = input.kind(CellType::Quad4)?;
    let plane = if kind == CellType::Hex8 {
        CellType::Quad4
    } else {
        kind
    };
    let mesh = if incline {
        let a = input.f64("angle_deg", None)?.to_radians();
        generate::block_on_incline(&p, a, plane).map_err(mesh_err)?
    } else {
        generate::stacked_blocks(&p, plane).map_err(mesh_err)?
    };
    if kind == CellType::Hex8 {
        let depth = input.f64("depth", Some(p.width))?;
        let n_z = input.usize("n_z", Some(p.n_x))?;
        generate::extrude(&mesh, n_z, depth).map_err(mesh_err)
    } else {
        Ok(mesh)
    }
}

/// `concentric_rings`: two rings in contact along a circle.
fn concentric_rings_mesh(input: &MeshInput) -> Result<Mesh, StudyError> {
    let d = generate::ConcentricRings::default();
    check_params(
        input.src,
        input.spec,
        &[
            "r_in",
            "r_contact",
            "r_out",
            "angle_deg",
            "n_inner",
            "n_outer",
            "n_theta",
        ],
    )?;
    let p = generate::ConcentricRings {
        r_in: input.f64("r_in", Some(d.r_in))?,
        r_contact: input.f64("r_contact", Some(d.r_contact))?,
        r_out: input.f64("r_out", Some(d.r_out))?,
        angle: input
            .f64("angle_deg", Some(d.angle.to_degrees()))?
            .to_radians(),
        n_inner: input.usize("n_inner", Some(d.n_inner))?,
        n_outer: input.usize("n_outer", Some(d.n_outer))?,
        n_theta: input.usize("n_theta", Some(d.n_theta))?,
    };
    generate::concentric_rings(&p, input.kind(CellType::Quad4)?).map_err(|e| input.mesh_err(e))
}

/// `cylinder_on_block`: a cylinder (or its half, `half`) pressed on a block.
fn cylinder_on_block_mesh(input: &MeshInput) -> Result<Mesh, StudyError> {
    let (src, spec) = (input.src, input.spec);
    let d = generate::CylinderOnBlock::default();
    check_params(src, spec, &["a", "l", "n", "m", "half"])?;
    let half = match spec.params.as_ref().and_then(|p| p.get_ref().get("half")) {
        None => d.half,
        Some(toml::Value::Boolean(b)) => *b,
        Some(_) => {
            let span = spec
                .params
                .as_ref()
                .map_or(spec.generator.span(), |p| p.span());
            return Err(src.error(span, "mesh.params.half", "expected true or false"));
        }
    };
    let p = generate::CylinderOnBlock {
        a: input.f64("a", Some(d.a))?,
        l: input.f64("l", Some(d.l))?,
        n: input.usize("n", Some(d.n))?,
        m: input.usize("m", Some(d.m))?,
        half,
    };
    generate::cylinder_on_block(&p, input.kind(CellType::Quad4)?).map_err(|e| input.mesh_err(e))
}

/// `turbine_3d`: the 2D turbine's Quad4 model extruded over `depth` in `n_z` layers (Hex8).
fn turbine_3d_mesh(input: &MeshInput) -> Result<Mesh, StudyError> {
    let (src, spec) = (input.src, input.spec);
    let keys: Vec<&str> = TURBINE_KEYS
        .iter()
        .copied()
        .chain(["depth", "n_z"])
        .collect();
    check_params(src, spec, &keys)?;
    if input.kind(CellType::Hex8)? != CellType::Hex8 {
        let span = spec
            .kind
            .as_ref()
            .map_or(spec.generator.span(), |k| k.span());
        return Err(src.error(
            span,
            "mesh.kind",
            "turbine_3d makes HEX8 cells (the Quad4 model extruded)",
        ));
    }
    let depth = input.f64("depth", Some(20.0))?;
    let n_z = input.usize("n_z", Some(10))?;
    generate::turbine_3d(&turbine_params(src, spec)?, depth, n_z).map_err(|e| input.mesh_err(e))
}

/// `gmsh`: the mesh of the Gmsh `.msh` file `file`.
fn gmsh_mesh(input: &MeshInput) -> Result<Mesh, StudyError> {
    let (src, spec) = (input.src, input.spec);
    check_params(src, spec, &[])?;
    let f = spec.file.as_ref().ok_or_else(|| {
        src.error(
            spec.generator.span(),
            "mesh.file",
            "missing; expected the path of a Gmsh .msh file",
        )
    })?;
    let path = mesh_file_path(src, f);
    // Every Gmsh error (missing file, directory, truncated or malformed content) is an
    // input error of this field; the message carries the mesh file's own line.
    alea_mesh::read_msh(&path).map_err(|e| src.error(f.span(), "mesh.file", e.to_string()))
}
