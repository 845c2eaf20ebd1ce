//! The TOML schema of a model: mesh, analysis, substructures (material, constraints, loads),
//! interfaces and solver settings. Units are the user's, stated in `[units]`, and must be
//! consistent (the examples use mm, N, MPa, tonne/mm^3, s). Every table refuses unknown keys.
//! The reference page is `docs/study-file.md`.

use serde::Deserialize;
use toml::Spanned;

/// A number, or an expression (a string) of the parameters (and, for interface profiles, of the
/// position `x, y, z` and the `[[define]]`d names). See [`crate::expr`].
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum NumOrExpr {
    /// A plain number.
    Num(f64),
    /// An expression.
    Expr(String),
}

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
    /// `rectangle`, `box`, `plate_with_hole`, `annulus_sector`, `dovetail`, `blade_root_simple`,
    /// `turbine_2d` or `gmsh`.
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
    /// grading; annulus_sector: r_in, r_out, angle_deg, n_radial, n_theta; dovetail,
    /// blade_root_simple and turbine_2d: any field of their parameter sets, angles in degrees).
    #[serde(default)]
    pub params: Option<Spanned<toml::Table>>,
    /// Uniform refinements of the mesh once built (0 - 3; each splits every cell into `2^dim`
    /// children: `alea_mesh::Mesh::refined`). Any generator or Gmsh file.
    #[serde(default)]
    pub split: Option<Spanned<i64>>,
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
    /// Load factor: a number or an expression of the parameters. Default 1.
    #[serde(default)]
    pub factor: Option<Spanned<NumOrExpr>>,
}

impl LoadSpec {
    /// Where the load is in its file, for messages: its group, else its name, else unknown.
    pub fn span(&self) -> std::ops::Range<usize> {
        self.group
            .as_ref()
            .map(|g| g.span())
            .or(self.name.as_ref().map(|n| n.span()))
            .unwrap_or(0..0)
    }
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
    /// Young's modulus (stress): a number or an expression of the parameters.
    pub young: Spanned<NumOrExpr>,
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
    /// Friction coefficient (coulomb): a number or an expression of the parameters and the
    /// position. Default 0.
    #[serde(default)]
    pub mu: Option<Spanned<NumOrExpr>>,
    /// Initial normal gap / shape defect (length), positive opens the contact: a number or an
    /// expression of the parameters and the position. Default 0.
    #[serde(default)]
    pub gap: Option<Spanned<NumOrExpr>>,
    /// Pairing of the sides: `auto` (node to node when they match, mortar otherwise; the
    /// default), `node` (node to node only) or `mortar`.
    #[serde(default)]
    pub pairing: Option<Spanned<String>>,
    /// Node-to-node matching tolerance (length): largest distance between paired nodes.
    /// Default 1e-6 x the interface size.
    #[serde(default)]
    pub tolerance: Option<Spanned<f64>>,
    /// Mortar search distance (length): largest normal distance between the sides at which
    /// they are paired. Default 5 % of the interface size.
    #[serde(default)]
    pub search_distance: Option<Spanned<f64>>,
    /// `small` (the pairing of the initial configuration; the default) or `large` (contact
    /// interfaces: the mortar pairing re-found from the deformed configuration during the
    /// solve, module `alea_latin::large_sliding`).
    #[serde(default)]
    pub sliding: Option<Spanned<String>>,
    /// Cyclic symmetry (zero harmonic, perfect interfaces): side 2 is side 1's image by the
    /// rotation of `angle_deg` about `axis` through `center` (module `alea_latin::cyclic`).
    #[serde(default)]
    pub cyclic: Option<Spanned<CyclicSpec>>,
}

/// `cyclic = { angle_deg = 15.0, center = [0, 0], axis = [0, 0, 1] }` of an `[[interface]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CyclicSpec {
    /// Sector angle in degrees, in `(0, 180]`.
    pub angle_deg: Spanned<f64>,
    /// A point of the axis (2 or 3 coordinates). Default the origin.
    #[serde(default)]
    pub center: Option<Spanned<Vec<f64>>>,
    /// Axis direction (3 components, right-hand rule). Default `[0, 0, 1]`.
    #[serde(default)]
    pub axis: Option<Spanned<Vec<f64>>>,
}

pub use crate::solver_spec::SolverSpec;

/// `[study]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudySpec {
    /// Title shown in the report.
    #[serde(default)]
    pub title: Option<String>,
    /// Seed of every random draw (designs, Monte Carlo). Default 1.
    #[serde(default)]
    pub seed: Option<u64>,
}

/// `[[parameter]]`: a random parameter and its marginal law.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSpec {
    /// Name used in expressions.
    pub name: Spanned<String>,
    /// `uniform`, `normal`, `truncated_normal`, `lognormal`, `beta`, `triangular`.
    pub law: Spanned<String>,
    /// Mean (normal, truncated_normal: of the parent normal; lognormal: of the variable).
    #[serde(default)]
    pub mean: Option<Spanned<f64>>,
    /// Standard deviation (same conventions as `mean`).
    #[serde(default)]
    pub std: Option<Spanned<f64>>,
    /// Lower bound (uniform, truncated_normal, beta, triangular).
    #[serde(default)]
    pub lo: Option<Spanned<f64>>,
    /// Upper bound.
    #[serde(default)]
    pub hi: Option<Spanned<f64>>,
    /// Mode (triangular).
    #[serde(default)]
    pub mode: Option<Spanned<f64>>,
    /// Shape parameters (beta).
    #[serde(default)]
    pub alpha: Option<Spanned<f64>>,
    /// Shape parameters (beta).
    #[serde(default)]
    pub beta: Option<Spanned<f64>>,
    /// Measured values (`empirical`, `kde`, `fit`): a CSV file relative to the study file.
    #[serde(default)]
    pub data: Option<Spanned<String>>,
    /// The column of `data` (by its header name) when it has several.
    #[serde(default)]
    pub column: Option<Spanned<String>>,
    /// Candidate families of `fit` (default normal, lognormal, gamma, uniform).
    #[serde(default)]
    pub families: Option<Spanned<Vec<String>>>,
    /// Bandwidth of `kde` (default: Silverman's rule).
    #[serde(default)]
    pub bandwidth: Option<Spanned<f64>>,
    /// Unit (for the report).
    #[serde(default)]
    pub unit: Option<String>,
}

/// `[joint]`: how the parameters depend on each other. Default: independent.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    /// `independent`, `gaussian_copula`, `student`, `clayton`, `gumbel`, `frank` or `density`.
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    /// Correlation matrix of the Gaussian copula (rows).
    #[serde(default)]
    pub correlation: Option<Spanned<Vec<Vec<f64>>>>,
    /// Joint density on the box of the marginals' bounds (expression of the parameters; need
    /// not be normalised). The marginal laws then only give the box.
    #[serde(default)]
    pub density: Option<Spanned<String>>,
    /// Parameter of the `clayton`, `gumbel` and `frank` copulas.
    #[serde(default)]
    pub theta: Option<Spanned<f64>>,
    /// Degrees of freedom of the `student` copula.
    #[serde(default)]
    pub nu: Option<Spanned<f64>>,
}

/// `[[define]]`: a named helper quantity for interface profiles, e.g. an abscissa along the
/// contact line `s = (y - 120) / 10`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DefineSpec {
    /// Name.
    pub name: Spanned<String>,
    /// Expression of `x, y, z`, the parameters and earlier defines.
    pub value: Spanned<String>,
}

/// `[[quantity]]`: a quantity of interest computed from each run.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuantitySpec {
    /// Name.
    pub name: Spanned<String>,
    /// With `[[step]]`s: the step whose end state the quantity measures (default the last).
    #[serde(default)]
    pub step: Option<Spanned<String>>,
    /// `interface_work` (int ([W] + g0 n) . F dS), `friction_dissipation`,
    /// `interface_force` (resultant component), `max_von_mises`, `mean_von_mises`,
    /// `displacement`, `contact_pressure`, `contact_slip`, `contact_status`.
    pub kind: Spanned<String>,
    /// Interface (interface_work, friction_dissipation, interface_force, contact_*).
    #[serde(default)]
    pub interface: Option<Spanned<String>>,
    /// Substructure (max_von_mises, mean_von_mises, displacement).
    #[serde(default)]
    pub substructure: Option<Spanned<String>>,
    /// max_von_mises: cell, facet or node group (default all nodes of the substructure);
    /// mean_von_mises: cell group (default all cells).
    #[serde(default)]
    pub group: Option<Spanned<String>>,
    /// Point (displacement: the nearest node; mean_von_mises: centre of the ball of radius
    /// `radius`; contact_*: the nearest interface point, else the interface integral).
    #[serde(default)]
    pub point: Option<Spanned<Vec<f64>>>,
    /// mean_von_mises: radius of the ball around `point` (length).
    #[serde(default)]
    pub radius: Option<Spanned<f64>>,
    /// max_von_mises: groups whose nodes are left out.
    #[serde(default)]
    pub exclude_groups: Vec<Spanned<String>>,
    /// max_von_mises: nodes left out (numbers of the substructure's own mesh, as in its
    /// ParaView file).
    #[serde(default)]
    pub exclude_nodes: Option<Spanned<Vec<usize>>>,
    /// max_von_mises: points around which the nodes within `exclude_radius` are left out.
    #[serde(default)]
    pub exclude_points: Option<Spanned<Vec<Vec<f64>>>>,
    /// max_von_mises: radius around `exclude_points` (length).
    #[serde(default)]
    pub exclude_radius: Option<Spanned<f64>>,
    /// contact_status: `open`, `stick`, `slip` or `closed` (default; stick or slip).
    #[serde(default)]
    pub status: Option<Spanned<String>>,
    /// Component 0, 1, 2 (displacement, interface_force).
    #[serde(default)]
    pub component: Option<Spanned<usize>>,
    /// Unit (for the report).
    #[serde(default)]
    pub unit: Option<String>,
    /// Failure thresholds: P(q > threshold) is reported.
    #[serde(default)]
    pub thresholds: Vec<f64>,
    /// ruiz_f2, swt, fatemi_socie: critical distance `L` below the surface (length; module
    /// `qoi::fretting`).
    #[serde(default)]
    pub critical_distance: Option<Spanned<f64>>,
    /// ruiz_f2, swt, fatemi_socie: `point` (default: the stress at depth `L`) or `line`
    /// (averaged over `[0, L]`).
    #[serde(default)]
    pub critical_method: Option<Spanned<String>>,
    /// fatemi_socie: the material's normal-stress sensitivity `k` (dimensionless, >= 0).
    #[serde(default)]
    pub normal_stress_factor: Option<Spanned<f64>>,
    /// fatemi_socie: the material's yield stress `sigma_y` (stress units, > 0).
    #[serde(default)]
    pub yield_stress: Option<Spanned<f64>>,
}

/// `[[method]]`: how runs become a surrogate. The first method is the study's answer; the
/// others are computed for comparison (runs at the same points are shared).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MethodSpec {
    /// `pc_regression`, `pc_projection`, `polynomial`, `piecewise_linear`, `monte_carlo`.
    #[serde(rename = "type")]
    pub kind: Spanned<String>,
    /// Label in tables and plots (default from the type).
    #[serde(default)]
    pub label: Option<String>,
    /// Polynomial degree (pc_*, polynomial).
    #[serde(default)]
    pub degree: Option<Spanned<usize>>,
    /// Design: `pc_collocation` (roots of the next orthogonal polynomial), `grid`, `lhs`,
    /// `sobol`, `monte_carlo`, `corners_centre`. Default by method.
    #[serde(default)]
    pub design: Option<Spanned<String>>,
    /// Points per parameter (grid; pc_projection quadrature; piecewise_linear nodes).
    #[serde(default)]
    pub points_per_dim: Option<Spanned<usize>>,
    /// Number of runs (lhs, sobol, monte_carlo, pc_collocation).
    #[serde(default)]
    pub runs: Option<Spanned<usize>>,
    /// `adaptive`: refinement criterion, `improved` (default) or `max_error` (thesis 4.2.2).
    #[serde(default)]
    pub criterion: Option<Spanned<String>>,
    /// `adaptive`: stop when `i_sto` is at most this (default: when `i_sto <= i_geo`).
    #[serde(default)]
    pub target: Option<Spanned<f64>>,
    /// `adaptive`: run budget (default 100).
    #[serde(default)]
    pub max_runs: Option<Spanned<usize>>,
    /// `adaptive`, improved criterion: refine every cell whose stochastic error is at least
    /// this fraction of the largest (default 0.5).
    #[serde(default)]
    pub fraction: Option<Spanned<f64>>,
    /// `adaptive`, maximum-error criterion: the density maximum is searched over the centres of
    /// the `2^(d depth)` sub-cells of each cell (default 3) and the interpolated nodes.
    #[serde(default)]
    pub depth: Option<Spanned<u32>>,
    /// `adaptive`: a goal quantity (goal-oriented refinement and stop, `crate::goal`).
    #[serde(default)]
    pub goal: Option<Spanned<GoalSpec>>,
}

/// `[budget]`: `refined_mesh = { params = { n_flank = 48 } }` (or `cells = [..]`, or
/// `file = "fine.msh"`): the keys of `[mesh]` that make a mesh about twice as fine; the model is
/// solved on both meshes at a few design points and the differences give the mesh part of every
/// statistic's error budget (`crate::budget::paired`). `large_sliding = true`: the model is also
/// solved with every small-sliding contact interface in large sliding at the same points, and
/// the differences give the sliding part (`crate::budget::paired`). At least one of the two.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BudgetSpec {
    /// Keys replacing those of `[mesh]` (`params` merged key by key).
    #[serde(default)]
    pub refined_mesh: Option<Spanned<toml::Table>>,
    /// Paired solves in large sliding.
    #[serde(default)]
    pub large_sliding: Option<Spanned<bool>>,
    /// Validation runs of the solver (`crate::validation_runs`; 0: none; default automatic).
    #[serde(default)]
    pub validation_runs: Option<Spanned<usize>>,
}

/// `[[reliability]]`: `P(q > threshold)` of a quantity by FORM, SORM, importance sampling and
/// subset simulation on the surrogate of one method (`crate::reliability`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReliabilitySpec {
    /// Name of a `[[quantity]]`.
    pub quantity: Spanned<String>,
    /// Threshold (the quantity's unit).
    pub threshold: Spanned<f64>,
    /// Label of the `[[method]]` whose surrogate is the limit state (default: the first method
    /// with a surrogate).
    #[serde(default)]
    pub method: Option<Spanned<String>>,
    /// Any of `form`, `sorm`, `importance`, `subset` (default: all four).
    #[serde(default)]
    pub algorithms: Option<Spanned<Vec<String>>>,
    /// Coefficient of variation at which importance sampling stops (default 0.05).
    #[serde(default)]
    pub target_cov: Option<Spanned<f64>>,
    /// Runs of the solver itself for importance sampling at the surrogate's FORM design point,
    /// confirming the surrogate's probability (default 0: none).
    #[serde(default)]
    pub solver_runs: Option<Spanned<i64>>,
}

/// `goal = { quantity = "vm_fillet", threshold = 1165.0, tolerance = 0.005 }` of an adaptive
/// method: refine where the surrogate error of this quantity's statistic is largest and stop
/// when the statistic's error budget is below the tolerance. The statistic is `P(q > threshold)`
/// when a threshold is given, else the mean and the standard deviation (both).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalSpec {
    /// Name of a `[[quantity]]`.
    pub quantity: Spanned<String>,
    /// Threshold of the failure probability `P(q > threshold)` (the quantity's unit).
    #[serde(default)]
    pub threshold: Option<Spanned<f64>>,
    /// Absolute tolerance on the statistic's error budget (a probability, or the quantity's
    /// unit for the mean and std).
    #[serde(default)]
    pub tolerance: Option<Spanned<f64>>,
    /// Tolerance relative to the statistic's value (e.g. 0.05: 5 %).
    #[serde(default)]
    pub relative_tolerance: Option<Spanned<f64>>,
}

/// `[error]`: the stochastic error estimate (thesis 3.2, 4.1).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorSpec {
    /// Estimate the error of every method with a surrogate. Default true when the table is
    /// present (an `adaptive` method always estimates).
    #[serde(default)]
    pub enabled: Option<bool>,
    /// Warn when `i_geo` or `i_sto` exceeds this. Default 0.1.
    #[serde(default)]
    pub warn: Option<Spanned<f64>>,
    /// Cells per parameter of the integration partition of global surrogates (piecewise-linear
    /// and adaptive methods integrate on their own stochastic cells). Default 16 / 8 / 4 / 2 for
    /// 1-2 / 3 / 4 / 5-6 parameters.
    #[serde(default)]
    pub cells_per_dim: Option<Spanned<usize>>,
    /// Gauss points per parameter in each integration cell. Default 4.
    #[serde(default)]
    pub points_per_cell: Option<Spanned<usize>>,
    /// Grid points per parameter of the error-density maps. Default 80.
    #[serde(default)]
    pub map_points: Option<Spanned<usize>>,
}

/// `[analysis]` of the surrogate.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StatsSpec {
    /// Monte Carlo draws on the surrogate. Default 250 000.
    #[serde(default)]
    pub samples: Option<Spanned<usize>>,
    /// KDE bandwidth rule: `silverman` or `isj`. Default `isj` (falls back to Silverman).
    #[serde(default)]
    pub bandwidth: Option<Spanned<String>>,
    /// Points of the KDE curve. Default 512.
    #[serde(default)]
    pub kde_points: Option<Spanned<usize>>,
    /// Confidence level of intervals. Default 0.95.
    #[serde(default)]
    pub confidence: Option<Spanned<f64>>,
}

/// `[output]`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// Write a ParaView file for every run. Default false.
    #[serde(default)]
    pub vtu: Option<bool>,
    /// Write the HTML report and plots. Default true.
    #[serde(default)]
    pub report: Option<bool>,
    /// Write samples.csv. Default true.
    #[serde(default)]
    pub samples_csv: Option<bool>,
    /// Draws written to samples.csv: a number (the first draws) or `"all"`. Default 10 000
    /// (`crate::output_settings`).
    #[serde(default)]
    pub samples_rows: Option<Spanned<SamplesRows>>,
    /// Write mean and standard-deviation fields (ParaView) of the main method. Default true.
    #[serde(default)]
    pub mean_fields: Option<bool>,
}

/// `[output] samples_rows`: a number of draws or a word (`"all"`), checked at load
/// (`crate::output_settings`).
#[derive(Clone, Debug, Deserialize)]
#[serde(untagged)]
pub enum SamplesRows {
    /// A number of draws.
    Count(i64),
    /// A word.
    Word(String),
}

/// A study (or a deterministic case: a study without parameters) file.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFile {
    /// Title and seed.
    #[serde(default)]
    pub study: StudySpec,
    /// Random parameters.
    #[serde(default)]
    pub parameter: Vec<ParameterSpec>,
    /// Their dependence.
    #[serde(default)]
    pub joint: Option<JointSpec>,
    /// Helper quantities for interface profiles.
    #[serde(default)]
    pub define: Vec<DefineSpec>,
    /// Random fields along interfaces (module `random_field`).
    #[serde(default)]
    pub field: Vec<crate::field_spec::FieldSpec>,
    /// Quantities of interest.
    #[serde(default)]
    pub quantity: Vec<QuantitySpec>,
    /// Methods.
    #[serde(default)]
    pub method: Vec<MethodSpec>,
    /// `[[reliability]]`: rare-event probabilities of a quantity on a method's surrogate.
    #[serde(default)]
    pub reliability: Vec<ReliabilitySpec>,
    /// `[budget]`: how the error budget's mesh and sliding parts are estimated.
    #[serde(default)]
    pub budget: Option<Spanned<BudgetSpec>>,
    /// Statistics settings (`[statistics]`).
    #[serde(default)]
    pub statistics: StatsSpec,
    /// Stochastic error estimate (`[error]`).
    #[serde(default)]
    pub error: Option<ErrorSpec>,
    /// Outputs.
    #[serde(default)]
    pub output: OutputSpec,
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
    /// `[[step]]`: a load history (module `steps`).
    #[serde(default)]
    pub step: Vec<Spanned<crate::step_spec::StepSpec>>,
    /// `[cycle]`: the last steps repeated as a load cycle (module `cycle`).
    #[serde(default)]
    pub cycle: Option<Spanned<crate::step_spec::CycleSpec>>,
}
