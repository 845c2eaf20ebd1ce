//! The LATIN iteration and its multiresolution state.
//!
//! **Linear stage** (per substructure, in parallel): with `k_s = alpha_s k0_s` proportional to
//! the substructure's Young's-modulus factor `alpha_s`, `K + k M_Gamma = alpha_s (K0 + k0 M_Gamma)
//! = alpha_s A0`, so the factorisation of `A0 = T^T (K0 + sum k0 M_Gamma) T` made once at set-up
//! serves every run and iteration:
//! `A0 u = (f + M_Gamma (F_hat + k W_hat)) / alpha - A0 u_p`, then `W = u|Gamma`,
//! `F = F_hat - k (W - W_hat)`; `k` is a tensor per interface point, isotropic or split along
//! the normal (`k_n n n^T + k_t (I - n n^T)`, module `direction`,
//! [`SearchDirection::Split`]), `k M_Gamma` standing for `Pi^T M k Pi`. With relaxation `rho`, `(W, F) <- rho (W, F) + (1 - rho)
//! (W, F)_previous`. Where it pays, the linear stage of a substructure is condensed on its
//! interface (module `condensed`, issue 41): `W = w0 + H v` with the dense interface operator
//! `H = Pi T A0^-1 S` computed at set-up, the same iterates to round-off, the volume solution
//! recovered once per run ([`LinearStage`]).
//!
//! **Local stage** (per interface point, in parallel): closed form of [`crate::law`].
//!
//! **Error indicator** (k-weighted distance between the two half-iterates):
//! `eta = ||s - s_hat|| / max(1/2 (||s|| + ||s_hat||), ||s_0||)`,
//! `||s||^2 = sum_points m (W . k W + F . k^-1 F)` over both sides of every interface, `s_0` the
//! state the run started from (zero cold; module `local_stage`: a run whose answer is zero, or
//! tiny next to the warm start's, converges as the iterates shrink). The indicator is relative to the size of the iterates,
//! so on its own it cannot tell convergence from a floating substructure drifting away (the
//! iterates grow, the indicator shrinks). When `eta < tol`, the run is **converged** only if
//! every substructure is also in equilibrium under its loads and the local-stage interface
//! forces and no floating substructure moved rigidly by more than a bound (module
//! `equilibrium`, options `equilibrium_tolerance` and `max_rigid_motion`); otherwise it goes on
//! for a few iterations and ends as [`RunStatus::NoEquilibrium`]. A run that reaches
//! `max_iterations` is not converged, or has no equilibrium when a substructure drifts beyond
//! the bound or its sampled imbalance did not decrease over the second half of the run.
//!
//! **Coarse problem** (`LatinOptions::coarse`, default on; module `coarse`): after the plain
//! linear stages, a small global problem on the interface resultants and moments corrects every
//! substructure so that the linear-stage interface forces balance macroscopically across every
//! interface (two-scale LATIN): loads reach floating and distant substructures in one
//! iteration instead of hundreds.
//!
//! **Acceleration** (`LatinOptions::acceleration`, default depth 5): the sequence of local-stage
//! states is a fixed-point iteration; Anderson mixing of the last iterates (module
//! `anderson`) removes the slow global modes that the single-scale LATIN leaves to hundreds of
//! iterations when substructures float (measured: 877 -> 100 iterations on the 23k-dof
//! dovetail, 655 -> 131 on the perfect 2 x 2 test). The reported state is always a true local
//! stage; the acceleration only changes the input of the next linear stage.
//!
//! **Multiresolution** (thesis 5.1.3): the solver keeps the set-up (meshes, dof maps, pairings,
//! factorisations) between runs; a run may change the Young's-modulus factors, load factors,
//! `mu(x)` and `g0(x)` without refactorisation, and starts from the local-stage solution
//! `(W_hat, F_hat)` its caller gives (`RunInput::initial`): a study's runner interpolates it
//! from the nearest finished runs (`alea_study`'s schedule), which it stores on disk with every
//! run. The solver keeps no runs of its own.
//!
//! **Files**: the types (this file); the LATIN loop, one for a run alone (`run_shared`, a batch
//! of one) and for runs in lockstep (`run_batch`, `batch.rs`); set-up
//! (`setup.rs`); what a run starts from, with the warm start (`start.rs`); the linear stage
//! (`linear_stage.rs`) and its interface-condensed form (`condensed.rs`); the coarse step (`coarse.rs`); the local stage and the error indicator
//! (`local_stage.rs`); Anderson acceleration (`acceleration.rs`); stopping, status and the
//! equilibrium check (`convergence.rs`); the run's result (`result.rs`); one run spread over
//! ranks, each owning some substructures (`ranks.rs`, module [`crate::ranks`]).

mod acceleration;
mod batch;
mod cell_young;
mod coarse;
mod condensed;
mod convergence;
pub(crate) mod direction;
mod existence;
mod linear_stage;
mod local_stage;
mod precision;
mod ranks;
mod result;
mod setup;
pub mod split;
mod start;

pub use precision::{FactorPrecision, SINGLE_MIN_ENTRIES};
pub(crate) use setup::direction_scale;

use std::sync::Arc;

use alea_fem::{Cholesky, DofMap, Ordering};

use crate::coarse::{InterfaceModes, SubMacro};
use crate::equilibrium::RigidModes;
use crate::interface::{InterfacePairing, SideProjection};
use crate::state::LocalState;
use crate::{InterfaceLaw, LatinError, PointData, PointField, PointStatus, RunResult, RunTimings};
use direction::PointDirection;

type V3 = [f64; 3];

/// The Anderson depth of [`LatinOptions::acceleration`] by default (models not cut into
/// subdomains). Measured on the 225-run 2D turbine study (BENCHMARKS.md, "Where the iteration
/// count stands"): deeper histories saturate (12: 59.7 iterations per run against 65.9, 30:
/// 59.4; with the split search direction 42.1 against 44.8).
pub const DEFAULT_ACCELERATION: usize = 5;

/// Search direction choice.
#[derive(Clone, Debug, PartialEq)]
pub enum SearchDirection {
    /// `k = factor * E_side / L_interface` on each side, with `E_side` the mean Young's
    /// modulus of the cells along the side and `L` the interface length (2D) or the square root
    /// of its area (3D). Default factor 3, with the coarse problem (module `coarse`): measured
    /// with Anderson acceleration, four-part dovetail 64 iterations to 1e-6 (1: 69, 10: 128;
    /// without the coarse problem the best factor was 0.5 with 105), Hertz 23 / 30 / 39 at
    /// three mesh sizes (10: 28 / 28 / 30, mesh-independent; 1: 38 / 52 / 64). Without the
    /// coarse problem the best factor depends on the assembly (block on a plane 3, blade root
    /// between two disk parts 1-3, four-part dovetail 0.5).
    Auto {
        /// Multiplier (3 by default).
        factor: f64,
    },
    /// `k_n = factor * E_side / L_interface` as [`SearchDirection::Auto`] along the normal of
    /// the points of contact interfaces (laws that use the gap) and `k_t = tangential * k_n`
    /// across it: `k = k_n n n^T + k_t (I - n n^T)` per point (module `direction`); perfect
    /// interfaces keep `k_n` in every direction. Measured on the 225-run 2D turbine study
    /// (Coulomb contact, `BENCHMARKS.md`, issue 20): factor 1 with `tangential = 0.25` needs
    /// 44.8 iterations per run where the isotropic factor 0.5 needs 66.0, at equal true
    /// accuracy; ratios `k_n / k_t` of 10 and 16 left runs cycling without converging (8:
    /// all converged).
    Split {
        /// Multiplier of the normal direction.
        factor: f64,
        /// `k_t / k_n` on contact interfaces, > 0.
        tangential: f64,
    },
    /// Explicit `k0` per interface and side (`[side1, side2]`), at the reference materials.
    Fixed(Vec<[f64; 2]>),
}

/// How the linear stage of a substructure is solved (module `condensed`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LinearStage {
    /// Condensed where the dense interface operator costs less than the sparse solve and the
    /// operators fit in memory, volume solves elsewhere (module `condensed`, "When").
    #[default]
    Auto,
    /// Every substructure condensed on its interface (refused at set-up when the dense
    /// operators would not fit in a quarter of the available memory).
    Condensed,
    /// A sparse volume solve per substructure and iteration.
    Volume,
}

/// How the linear stage of one substructure is solved ([`LatinSolver::linear_stage_summary`]).
#[derive(Clone, Debug, PartialEq)]
pub struct LinearStageSummary {
    /// Substructure name.
    pub name: String,
    /// Free unknowns of its volume.
    pub dofs: usize,
    /// Entries of its sparse factor.
    pub factor_entries: usize,
    /// Interface unknowns (`dim` per point of every interface side).
    pub interface_unknowns: usize,
    /// Condensed on its interface (module `condensed`), else volume solves.
    pub condensed: bool,
    /// Bytes of its dense interface operator and responses (0 on the volume path).
    pub bytes: f64,
    /// Its factor stored in single precision (module `precision`).
    pub single_precision: bool,
    /// Bytes of its factor (in single precision with the matrix kept for the refinement).
    pub factor_bytes: f64,
}

/// The factorisation of a substructure, as the set-up made it ([`LatinSolver::factor_summary`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct FactorInfo {
    n: usize,
    entries: usize,
    supernodal: bool,
    single: bool,
    bytes: usize,
}

/// Solver options.
#[derive(Clone, Debug)]
pub struct LatinOptions {
    /// Convergence tolerance on the error indicator.
    pub tolerance: f64,
    /// Maximum number of iterations.
    pub max_iterations: usize,
    /// Relaxation of the linear stage, in (0, 1] (1 = none).
    pub relaxation: f64,
    /// Search direction.
    pub search_direction: SearchDirection,
    /// Fill-reducing ordering of the substructure factorisations.
    pub ordering: Ordering,
    /// Anderson acceleration depth (0: off): see the `anderson` module. `None` (the default):
    /// [`DEFAULT_ACCELERATION`], or [`split::SPLIT_ACCELERATION`] on a model cut into
    /// subdomains.
    pub acceleration: Option<usize>,
    /// Two-scale LATIN: the coarse problem on the interface resultants and moments (module
    /// `coarse`; default on). Without acceleration (`acceleration = 0`) the linear stage is then
    /// relaxed by at most 0.8 (`min(relaxation, 0.8)`), which the macro correction of floating
    /// substructures needs.
    pub coarse: bool,
    /// Largest relative imbalance of a substructure under its loads and the local-stage
    /// interface forces for a run to be called converged (module `equilibrium`; default 1e-4).
    pub equilibrium_tolerance: f64,
    /// Largest rigid displacement of a floating substructure, relative to the model size (the
    /// diagonal of the assembly's bounding box), for a run to be called converged (default 10).
    /// Linear elasticity scales with the load, so no physical bound applies; this one catches a
    /// substructure drifting away (measured: 1e3 to 1e8 model sizes within a few hundred
    /// iterations) even where its imbalance looks small, and leaves any balanced linear answer
    /// alone (manufactured solutions move floating parts by half the model size). The rigid
    /// motion of every run is reported in [`RunResult::equilibrium`].
    pub max_rigid_motion: f64,
    /// Condensed or volume linear stage (module `condensed`; default [`LinearStage::Auto`]).
    pub linear_stage: LinearStage,
    /// Runs the solver's set-up is expected to serve (default 1): [`LinearStage::Auto`]
    /// weighs the condensed stage's set-up against the iterations of that many runs.
    pub expected_runs: usize,
    /// Automatic subdomains (module [`split`]): whether large substructures are cut into
    /// parts joined by perfect interfaces (default [`Subdomains::Auto`]).
    pub subdomains: Subdomains,
    /// The target size of a subdomain, in unknowns (default [`split::SUBDOMAIN_DOFS`]).
    pub subdomain_dofs: usize,
    /// Precision of the stored factors (module `precision`; default [`FactorPrecision::Auto`]).
    pub factor_precision: FactorPrecision,
}

/// Whether the solver cuts substructures into subdomains (module [`split`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Subdomains {
    /// 3D substructures of at least [`split::AUTO_MIN_DOFS`] unknowns are cut into parts of
    /// about `subdomain_dofs` (the break-even size measured in `BENCHMARKS.md`).
    #[default]
    Auto,
    /// Every substructure of at least `2 x subdomain_dofs` unknowns is cut into parts of about
    /// `subdomain_dofs`.
    Always,
    /// No substructure is cut.
    Never,
}

impl Default for LatinOptions {
    fn default() -> Self {
        LatinOptions {
            tolerance: 1e-6,
            max_iterations: 2000,
            relaxation: 1.0,
            search_direction: SearchDirection::Auto { factor: 3.0 },
            ordering: Ordering::Metis,
            acceleration: None,
            coarse: true,
            equilibrium_tolerance: 1e-4,
            max_rigid_motion: 10.0,
            linear_stage: LinearStage::Auto,
            expected_runs: 1,
            subdomains: Subdomains::Auto,
            subdomain_dofs: split::SUBDOMAIN_DOFS,
            factor_precision: FactorPrecision::Auto,
        }
    }
}

/// What changes from one run to the next. Empty vectors / `None` mean "as set up".
#[derive(Clone, Default)]
pub struct RunInput {
    /// Young's-modulus factor per substructure.
    pub young_factors: Vec<f64>,
    /// Load-case factors per substructure.
    pub load_factors: Vec<Vec<f64>>,
    /// Friction coefficient field per interface.
    pub mu: Vec<Option<PointField>>,
    /// Initial gap field per interface.
    pub gap: Vec<Option<PointField>>,
    /// The local-stage state the run starts from (the warm start; `None`: cold, or the end of
    /// `previous_step`).
    pub initial: Option<Arc<LocalState>>,
    /// Young's-modulus factor of every cell of some substructures (`cell_young[s]`: one factor
    /// per cell of substructure `s`, multiplying its reference materials and its factor in
    /// `young_factors`; `None` or an empty vector: the substructure's materials as set up). A
    /// run with such factors solves on operators assembled and factorised for it
    /// ([`LatinSolver::with_cell_young`]): a modulus varying from cell to cell is not a scalar
    /// multiple of the factorised reference.
    pub cell_young: Vec<Option<Arc<Vec<f64>>>>,
    /// The local-stage state at the end of the previous load step (module [`crate::steps`]):
    /// the run starts from it (unless `initial` is given: a re-paired pass of a large-sliding
    /// step, module [`crate::large_sliding`], starts from its previous pass) and applies the Coulomb
    /// law incrementally, slip being measured from its tangential jump. `None`: one static
    /// step from the unloaded state.
    pub previous_step: Option<Arc<LocalState>>,
    /// The retry settings of a run that did not converge with the options' (issue 35): no
    /// Anderson acceleration (the plain, relaxed LATIN iteration: slower, but it does not
    /// cycle) and twice the iteration limit. `false`: the options as set up.
    pub damped: bool,
}

/// One side of one interface seen from its substructure: the projection of the side's nodal
/// displacements to the interface points (module `interface`, identity for node-to-node).
#[derive(Clone, Debug)]
struct Link {
    iface: usize,
    side: usize,
    proj: Arc<SideProjection>,
    /// The search direction at every point of the interface, at the reference materials
    /// (module `direction`).
    dir: Arc<Vec<PointDirection>>,
}

struct SubOperator {
    name: String,
    model: alea_fem::Model,
    dofs: DofMap,
    /// `None`: the substructure is another rank's (module `ranks`).
    chol: Option<Cholesky>,
    r_ext: Vec<Vec<f64>>,
    r_presc: Vec<f64>,
    links: Vec<Link>,
    rigid: RigidModes,
}

#[derive(Clone)]
struct InterfaceOperator {
    name: String,
    law: Arc<dyn InterfaceLaw>,
    sub: [usize; 2],
    link: [usize; 2],
    points: Vec<PointData>,
    weights: Vec<f64>,
    mu: PointField,
    gap: PointField,
    pairing: Arc<InterfacePairing>,
}

struct SubState {
    /// The last plain linear stage's reduced displacement `u^0` (solved in place); the run's
    /// displacement is `u^0` plus the coarse correction `coarse_u` ([`LatinSolver::displacement`]).
    rhs: Vec<f64>,
    /// The coarse correction of the last linear stage, `(column, lambda)` of the substructure's
    /// macro responses (module `coarse`), applied only where the displacement is read.
    coarse_u: Vec<(usize, f64)>,
    /// Linear-stage `W`, `F` per link (relaxed).
    w: Vec<Vec<V3>>,
    f: Vec<Vec<V3>>,
    /// This iteration's `W`, `F` before the relaxation.
    w_new: Vec<Vec<V3>>,
    f_new: Vec<Vec<V3>>,
    /// Condensed substructure (module `condensed`): the last linear stage's interface data
    /// `v`, its interface displacements `W = w0 + H v`, and whether `rhs` is yet to be
    /// recovered from `v` (empty and false on the volume path).
    v: Vec<f64>,
    wi: Vec<f64>,
    stale: bool,
}

#[derive(Clone)]
struct InterfaceState {
    /// Input of the next linear stage (the last local stage, or an accelerated state).
    what: [Vec<V3>; 2],
    fhat: [Vec<V3>; 2],
    /// Local-stage output before the last one.
    what_prev: [Vec<V3>; 2],
    /// Last local-stage output.
    what_last: [Vec<V3>; 2],
    status: Vec<PointStatus>,
}

/// The substructured LATIN solver with its multiresolution state.
pub struct LatinSolver {
    subs: Vec<Arc<SubOperator>>,
    ifaces: Vec<InterfaceOperator>,
    options: LatinOptions,
    /// Diagonal of the assembly's bounding box (the scale of the rigid-motion bound).
    model_size: f64,
    /// The coarse problem (`LatinOptions::coarse`).
    coarse: Option<Coarse>,
    /// Displacement of every substructure in the configuration the interfaces were paired in
    /// (`None`: the initial configuration; module [`crate::large_sliding`]).
    configuration: Option<Vec<Vec<f64>>>,
    /// The condensed linear stage of each substructure (`None`: volume solves; module
    /// `condensed`).
    condensed: Vec<condensed::SharedCondensed>,
    /// The ranks one run is spread over (module `ranks`; `None`: one process).
    ranks: Option<Arc<ranks::Ranks>>,
    /// Seconds spent in set-up (assembly + factorisation).
    pub setup_seconds: f64,
    /// The user's assembly when the solved one is its substructures cut into subdomains
    /// (module [`split`]): the public accessors and the runs' inputs and results then speak of
    /// the user's substructures and interfaces.
    split: Option<Arc<split::Split>>,
}

/// The macro space and the substructures' responses (module `coarse`).
struct Coarse {
    /// Number of macro unknowns.
    n: usize,
    modes: Vec<InterfaceModes>,
    /// Side 2's macro basis where it differs from side 1's: the rotated modes `R e_j` of a
    /// cyclic interface (module `crate::cyclic`).
    rotated: Vec<Option<InterfaceModes>>,
    subs: Vec<SubMacro>,
}

impl Coarse {
    /// The macro basis of side `side` of interface `i`.
    fn side_modes(&self, i: usize, side: usize) -> &InterfaceModes {
        match (&self.rotated[i], side) {
            (Some(m), 1) => m,
            _ => &self.modes[i],
        }
    }
}

/// The working state of one run.
struct Run<'a> {
    input: &'a RunInput,
    /// Young's-modulus factor per substructure.
    alpha: Vec<f64>,
    /// Interface point data with the run's `mu` and gap.
    points: Vec<Vec<PointData>>,
    /// Constant part of each substructure's right-hand side.
    base: Vec<Vec<f64>>,
    /// Per condensed substructure, the run's constant interface response and rigid moments.
    condensed: Vec<Option<condensed::RunCondensed>>,
    istate: Vec<InterfaceState>,
    sstate: Vec<SubState>,
    /// Inverse of the macro operator at `alpha` (with the coarse problem).
    macro_inv: Option<Vec<f64>>,
    /// Per interface: in the coarse problem (not open at every point; module `coarse`, "Open
    /// interfaces"); `macro_inv` is the inverse for this active set.
    macro_active: Vec<bool>,
    /// Per interface, per point: the tangential jump the load step starts from (empty without
    /// a previous step; module [`crate::steps`]).
    slip_origin: Vec<Vec<V3>>,
    residuals: Vec<f64>,
    /// `||s_0||`, the norm of the state the run started from (set by its first local stage):
    /// the floor of the error indicator's scale (module `local_stage`).
    start_norm: Option<f64>,
    /// The run's iteration limit and Anderson depth: the options', or the retry settings of
    /// [`RunInput::damped`].
    max_iterations: usize,
    acceleration: usize,
    timings: RunTimings,
}

impl LatinSolver {
    /// The Anderson depth of a run ([`LatinOptions::acceleration`]; by default
    /// [`DEFAULT_ACCELERATION`], or [`split::SPLIT_ACCELERATION`] on a model cut into
    /// subdomains).
    pub fn acceleration(&self) -> usize {
        self.options.acceleration.unwrap_or(match self.split {
            Some(_) => split::SPLIT_ACCELERATION,
            None => DEFAULT_ACCELERATION,
        })
    }

    /// Options in force.
    pub fn options(&self) -> &LatinOptions {
        &self.options
    }

    /// Changes the iteration options (tolerance, iterations, relaxation); the search direction
    /// and ordering are fixed at set-up.
    pub fn set_iteration_options(
        &mut self,
        tolerance: f64,
        max_iterations: usize,
        relaxation: f64,
    ) {
        self.options.tolerance = tolerance;
        self.options.max_iterations = max_iterations;
        self.options.relaxation = relaxation;
    }

    /// Number of substructures (the user's: a substructure cut into subdomains counts once).
    pub fn num_subs(&self) -> usize {
        match &self.split {
            Some(split) => split.user.subs.len(),
            None => self.subs.len(),
        }
    }

    /// The model of substructure `s`.
    pub fn model(&self, s: usize) -> &alea_fem::Model {
        match &self.split {
            Some(split) => &split.user.subs[s].model,
            None => &self.subs[s].model,
        }
    }

    /// The user's substructures cut into subdomains (module [`split`]), if any was.
    pub fn split(&self) -> Option<&split::Split> {
        self.split.as_deref()
    }

    /// Number of substructures solved: the subdomains when the model is split, else
    /// [`LatinSolver::num_subs`].
    pub fn num_solved_subs(&self) -> usize {
        self.subs.len()
    }

    /// The factorisation of solved substructure `s` (`s < num_solved_subs()`): its order, the
    /// entries of its factor and whether the factor is stored in supernodes
    /// ([`alea_fem::FactorKind`]). On a solver spread over ranks, the owner's factor
    /// ([`LatinSolver::with_ranks`]).
    pub fn factor_summary(&self, s: usize) -> (usize, usize, bool) {
        let f = self.factor_info(s);
        (f.n, f.entries, f.supernodal)
    }

    fn factor_info(&self, s: usize) -> FactorInfo {
        match (&self.subs[s].chol, &self.ranks) {
            (Some(c), _) => setup::factor_info(c),
            (None, Some(r)) => r.factors[s],
            (None, None) => FactorInfo::default(),
        }
    }

    /// How each solved substructure's linear stage is solved: condensed on its interface or by
    /// volume solves (module `condensed`), with the sizes the choice was made from.
    pub fn linear_stage_summary(&self) -> Vec<LinearStageSummary> {
        self.subs
            .iter()
            .zip(&self.condensed)
            .enumerate()
            .map(|(s, (op, cd))| {
                let bytes = match &self.ranks {
                    Some(r) => r.condensed[s],
                    None => cd.as_ref().map(|c| c.bytes()),
                };
                let factor = self.factor_info(s);
                LinearStageSummary {
                    name: op.name.clone(),
                    dofs: op.dofs.num_free(),
                    factor_entries: factor.entries,
                    single_precision: factor.single,
                    factor_bytes: factor.bytes as f64,
                    interface_unknowns: condensed::interface_unknowns(op.dofs.dim, &op.links),
                    condensed: bytes.is_some(),
                    bytes: bytes.unwrap_or(0.0),
                }
            })
            .collect()
    }

    /// Name of substructure `s`.
    pub fn sub_name(&self, s: usize) -> &str {
        match &self.split {
            Some(split) => &split.user.subs[s].name,
            None => &self.subs[s].name,
        }
    }

    /// Number of interfaces (the user's: the cuts between subdomains are not counted).
    pub fn num_interfaces(&self) -> usize {
        match &self.split {
            Some(split) => split.user.interfaces.len(),
            None => self.ifaces.len(),
        }
    }

    /// Interface point data (positions, normals, default mu and gap) of interface `i`.
    pub fn interface_points(&self, i: usize) -> &[PointData] {
        match &self.split {
            Some(split) => &split.user_interface(i).points,
            None => &self.ifaces[i].points,
        }
    }

    /// The pairing of interface `i` (node to node or mortar, point weights, projections).
    pub fn interface_pairing(&self, i: usize) -> &InterfacePairing {
        match &self.split {
            Some(split) => &split.user_interface(i).pairing,
            None => &self.ifaces[i].pairing,
        }
    }

    /// Displacement of every substructure (node-major) in the configuration the interfaces
    /// were paired in; `None`: the initial one ([`crate::large_sliding`] re-pairs in the
    /// deformed configuration).
    pub fn pairing_configuration(&self) -> Option<&[Vec<f64>]> {
        self.configuration.as_deref()
    }

    /// Name of interface `i`.
    pub fn interface_name(&self, i: usize) -> &str {
        match &self.split {
            Some(split) => &split.user_interface(i).name,
            None => &self.ifaces[i].name,
        }
    }

    /// Substructures `[side 1, side 2]` of interface `i` and, for each side, the mesh node of
    /// each interface point (in its substructure's mesh, point order): the paired nodes of a
    /// node-to-node interface; for a mortar interface the node of largest coefficient in the
    /// point's projection row (side 1: the point's own node), as in
    /// [`crate::InterfaceResult::nodes`].
    pub fn interface_nodes(&self, i: usize) -> ([usize; 2], [Vec<usize>; 2]) {
        let (subs, pairing) = match &self.split {
            Some(split) => {
                let u = split.user_interface(i);
                (u.subs, &u.pairing)
            }
            None => (self.ifaces[i].sub, &self.ifaces[i].pairing),
        };
        let nodes = |s: usize| {
            let proj = &pairing.sides[s];
            (0..proj.len()).map(|p| proj.main_node(p)).collect()
        };
        (subs, [nodes(0), nodes(1)])
    }

    /// Lumped integration weight of each point of interface `i` (side 1).
    pub fn interface_weights(&self, i: usize) -> &[f64] {
        match &self.split {
            Some(split) => &split.user_interface(i).weights,
            None => &self.ifaces[i].weights,
        }
    }

    /// Law name of interface `i` ("perfect", "coulomb").
    pub fn interface_law(&self, i: usize) -> &'static str {
        match &self.split {
            Some(split) => split.user_interface(i).law,
            None => self.ifaces[i].law.name(),
        }
    }

    /// The shape of the [`LocalState`] a run starts from and ends with
    /// ([`RunResult::end_state`]): the number of points of each interface solved - with
    /// subdomains, the pieces of the user's interfaces and the cuts between subdomains
    /// (module [`split`]), so that a warm start keeps the cuts' state too.
    pub fn interface_sizes(&self) -> Vec<usize> {
        self.ifaces.iter().map(|i| i.points.len()).collect()
    }

    /// Runs the LATIN iteration for one parameter point. A run that does not reach the
    /// tolerance is returned with status [`RunStatus::NotConverged`] and its residual history.
    ///
    /// [`RunStatus::NotConverged`]: crate::RunStatus::NotConverged
    pub fn run(&mut self, input: &RunInput) -> Result<RunResult, LatinError> {
        self.run_shared(input)
    }

    /// [`LatinSolver::run`] through a shared reference: several runs may proceed at once on
    /// different threads (each allocates its own scratch; the factorisations are shared). The
    /// run is a batch of one ([`LatinSolver::run_batch`], module `batch`): one LATIN loop for
    /// a run alone and for runs in lockstep, the same bits either way.
    pub fn run_shared(&self, input: &RunInput) -> Result<RunResult, LatinError> {
        self.run_batch(std::slice::from_ref(input))
            .pop()
            .unwrap_or_else(|| Err(LatinError::Invalid("a batch of one gave no result".into())))
    }
}
