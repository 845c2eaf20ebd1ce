//! The TOML schema of a model: mesh, analysis, substructures (material, constraints, loads),
//! interfaces and solver settings. Units are the user's, stated in `[units]`, and must be
//! consistent (the examples use mm, N, MPa, tonne/mm^3, s). Every table refuses unknown keys.
//! The reference page is `docs/study-file.md`.

use serde::Deserialize;
use toml::Spanned;

/// `[units]`: stated for the reader and copied to outputs; not converted.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitsSpec {
    /// Length unit (e.g. "mm").
    pub length: String,
    /// Force unit (e.g. "N").
    pub force: String,
    /// Stress unit (e.g. "MPa"); must equal force / length^2.
    pub stress: String,
    /// Density unit (e.g. "tonne/mm^3"); must make rho * omega^2 * length a force / length^3.
    #[serde(default)]
    pub density: Option<String>,
}

/// `[mesh]`: a built-in generator with its parameters, or a Gmsh file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    /// `rectangle`, `box`, `plate_with_hole`, `annulus_sector`, `dovetail`, `blade_root_simple`
    /// or `gmsh`.
    pub generator: Spanned<String>,
    /// Cell type: `tri3`, `tri6`, `quad4`, `quad8`, `tet4`, `tet10`, `hex8`.
    #[serde(default)]
    pub kind: Option<Spanned<String>>,
    /// Gmsh `.msh` file (relative to the study file).
    #[serde(default)]
    pub file: Option<Spanned<String>>,
    /// rectangle / box: lengths.
    #[serde(default)]
    pub size: Option<Spanned<Vec<f64>>>,
    /// rectangle / box: cells per direction.
    #[serde(default)]
    pub cells: Option<Spanned<Vec<usize>>>,
    /// Generator parameters by name (plate_with_hole: radius, half_width, n_arc, n_radial,
    /// grading; annulus_sector: r_in, r_out, angle_deg, n_radial, n_theta; dovetail and
    /// blade_root_simple: any field of their parameter sets).
    #[serde(default)]
    pub params: Option<Spanned<toml::Table>>,
}

/// `[analysis]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AnalysisSpec {
    /// `plane_strain`, `plane_stress` or `solid`.
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    /// Out-of-plane thickness (length), 2D only. Default 1.
    #[serde(default)]
    pub thickness: Option<Spanned<f64>>,
}

/// `[[substructure.constraint]]`: imposed displacement components on a node/facet group.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstraintSpec {
    /// Node, facet or cell group.
    pub group: Spanned<String>,
    /// Imposed x displacement (length).
    #[serde(default)]
    pub x: Option<Spanned<f64>>,
    /// Imposed y displacement.
    #[serde(default)]
    pub y: Option<Spanned<f64>>,
    /// Imposed z displacement.
    #[serde(default)]
    pub z: Option<Spanned<f64>>,
    /// Imposed normal displacement on a facet group (skew constraint; symmetry planes).
    #[serde(default)]
    pub normal: Option<Spanned<f64>>,
}

/// `centrifugal = { omega = .., center = [..], axis = [..] }`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CentrifugalSpec {
    /// Angular speed (rad/s).
    pub omega: Spanned<f64>,
    /// A point of the axis. Default origin.
    #[serde(default)]
    pub center: Option<Vec<f64>>,
    /// Axis direction. Default z.
    #[serde(default)]
    pub axis: Option<Vec<f64>>,
}

/// `[[substructure.load]]`: exactly one of the load kinds.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Optional name, so that a parameter can scale this load (`load_factor`).
    #[serde(default)]
    pub name: Option<Spanned<String>>,
    /// Facet group (pressure, traction), node group (force) or cell group (body,
    /// centrifugal; default all cells).
    #[serde(default)]
    pub group: Option<Spanned<String>>,
    /// Pressure (stress), positive pushes on the surface.
    #[serde(default)]
    pub pressure: Option<Spanned<f64>>,
    /// Traction vector (stress).
    #[serde(default)]
    pub traction: Option<Spanned<Vec<f64>>>,
    /// Force per node (force).
    #[serde(default)]
    pub force: Option<Spanned<Vec<f64>>>,
    /// Body force per volume (force / length^3).
    #[serde(default)]
    pub body: Option<Spanned<Vec<f64>>>,
    /// Centrifugal inertia.
    #[serde(default)]
    pub centrifugal: Option<Spanned<CentrifugalSpec>>,
}

/// `[[substructure]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubstructureSpec {
    /// Name (referred to by interfaces, parameters and outputs).
    pub name: Spanned<String>,
    /// Cell group of the mesh forming this substructure (default: every cell).
    #[serde(default)]
    pub cells: Option<Spanned<String>>,
    /// Young's modulus (stress).
    pub young: Spanned<f64>,
    /// Poisson's ratio.
    pub poisson: Spanned<f64>,
    /// Density (mass / volume). Default 0.
    #[serde(default)]
    pub density: Option<Spanned<f64>>,
    /// Constraints.
    #[serde(default)]
    pub constraint: Vec<ConstraintSpec>,
    /// Loads.
    #[serde(default)]
    pub load: Vec<LoadSpec>,
}

/// `[[interface]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpecToml {
    /// Name.
    pub name: Spanned<String>,
    /// `[substructure, facet group]` of side 1 (its outward normal is the interface normal).
    pub side1: Spanned<[String; 2]>,
    /// `[substructure, facet group]` of side 2.
    pub side2: Spanned<[String; 2]>,
    /// `perfect` or `coulomb`.
    pub law: Spanned<String>,
    /// Friction coefficient (coulomb). Default 0.
    #[serde(default)]
    pub mu: Option<Spanned<f64>>,
    /// Initial normal gap (length). Default 0.
    #[serde(default)]
    pub gap: Option<Spanned<f64>>,
}

/// `[solver]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// LATIN tolerance. Default 1e-6.
    #[serde(default)]
    pub tolerance: Option<Spanned<f64>>,
    /// Maximum LATIN iterations. Default 2000.
    #[serde(default)]
    pub max_iterations: Option<Spanned<usize>>,
    /// Relaxation in (0, 1]. Default 1.
    #[serde(default)]
    pub relaxation: Option<Spanned<f64>>,
    /// Search direction factor (k = factor E / L). Default 3.
    #[serde(default)]
    pub search_direction_factor: Option<Spanned<f64>>,
}

/// The model part shared by `alea solve` case files and study files.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    /// Units.
    pub units: UnitsSpec,
    /// Mesh.
    pub mesh: MeshSpec,
    /// Analysis.
    pub analysis: AnalysisSpec,
    /// Substructures (at least one).
    pub substructure: Vec<SubstructureSpec>,
    /// Interfaces.
    #[serde(default)]
    pub interface: Vec<InterfaceSpecToml>,
    /// Solver settings.
    #[serde(default)]
    pub solver: SolverSpec,
}
