//! The `[solver]` table of a model file (module [`crate::spec`]): the LATIN solver's settings,
//! validated and turned into `alea_latin::LatinOptions` by `crate::build`. The reference page
//! is `docs/study-file.md`.

use serde::Deserialize;
use toml::Spanned;

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
    /// Tangential search direction on contact interfaces over the normal one (`k_t / k_n`).
    /// Default 1 (isotropic).
    #[serde(default)]
    pub search_direction_tangential: Option<Spanned<f64>>,
    /// Anderson acceleration depth (0: off). Default 5.
    #[serde(default)]
    pub acceleration: Option<Spanned<usize>>,
    /// Coarse problem on the interface resultants and moments (two-scale LATIN). Default true.
    #[serde(default)]
    pub coarse: Option<Spanned<bool>>,
    /// Largest relative imbalance of a substructure for a run to be converged. Default 1e-4.
    #[serde(default)]
    pub equilibrium_tolerance: Option<Spanned<f64>>,
    /// Largest rigid motion of a floating substructure relative to the model size. Default 10.
    #[serde(default)]
    pub max_rigid_motion: Option<Spanned<f64>>,
    /// Large sliding: largest slide since the last pairing, over the median point size of the
    /// interface, for the pairing to be the solution's, in (0, 0.5]. Default 0.01.
    #[serde(default)]
    pub repair_tolerance: Option<Spanned<f64>>,
    /// Large sliding: largest number of pairings per load step, 1 - 100. Default 10.
    #[serde(default)]
    pub max_pairings: Option<Spanned<usize>>,
    /// How the linear stage is solved: `"auto"` (default), `"condensed"` (a dense operator
    /// on each substructure's interface) or `"volume"` (a sparse solve per iteration).
    #[serde(default)]
    pub linear_stage: Option<Spanned<String>>,
    /// Automatic subdomains: `"auto"` (default: substructures above the break-even size cut
    /// into parts), `"always"` or `"never"`.
    #[serde(default)]
    pub subdomains: Option<Spanned<String>>,
    /// Target size of a subdomain, in unknowns. Default 20000.
    #[serde(default)]
    pub subdomain_dofs: Option<Spanned<usize>>,
    /// Precision of the stored factors: `"auto"` (default: single precision, refined, for
    /// large 3D factors on the volume path), `"double"` or `"single"`
    /// (`alea_latin::FactorPrecision`).
    #[serde(default)]
    pub factor_precision: Option<Spanned<String>>,
    /// MPI ranks that solve one run together, each owning some substructures (`alea run`
    /// under `mpirun`, feature `mpi`; `alea_study::distributed`). Default 1. Not part of what
    /// defines a run: the results are the same bits for any value.
    #[serde(default)]
    pub ranks_per_run: Option<Spanned<i64>>,
}
