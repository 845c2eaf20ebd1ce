//! The `[[field]]` tables of a model file (schema only; the checks, the Karhunen-Loeve
//! expansion and the evaluation along the contact or over the cells are in module
//! `random_field`).

use serde::Deserialize;
use toml::Spanned;

/// `[[field]]`: a random field along an interface or over a substructure's cells, discretised
/// by Karhunen-Loeve; its KL variables `<name>_1 .. <name>_m` (independent standard normal)
/// become study parameters, and `<name>` is the field's value at the point in the interface's
/// `mu` and `gap` expressions, or its mean over each cell in the substructure's `young`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldSpec {
    /// Name (used in `mu` / `gap` expressions; its KL variables are `<name>_1`, ...).
    pub name: Spanned<String>,
    /// The `[[interface]]` the field lives on: over the facets of its side 1, parametrised by
    /// their points (exactly one of `interface` and `substructure`).
    #[serde(default)]
    pub interface: Option<Spanned<String>>,
    /// The `[[substructure]]` the field lives on: over its cells (2D), a variable of its
    /// `young` expression.
    #[serde(default)]
    pub substructure: Option<Spanned<String>>,
    /// `squared_exponential`, `exponential`, `matern32` or `matern52`.
    pub covariance: Spanned<String>,
    /// Correlation length (length, the unit of `[units] length`).
    pub correlation_length: Spanned<f64>,
    /// `gaussian` (default), `lognormal` or `bounded`.
    #[serde(default)]
    pub transform: Option<Spanned<String>>,
    /// Mean of the field (gaussian, lognormal), in the unit of the quantity it enters.
    #[serde(default)]
    pub mean: Option<Spanned<f64>>,
    /// Pointwise standard deviation of the field (gaussian, lognormal).
    #[serde(default)]
    pub std: Option<Spanned<f64>>,
    /// Lower bound of a bounded field.
    #[serde(default)]
    pub lower: Option<Spanned<f64>>,
    /// Upper bound of a bounded field.
    #[serde(default)]
    pub upper: Option<Spanned<f64>>,
    /// Keep the fewest modes holding at least this fraction, in (0, 1], of the variance
    /// `int sigma^2` (exactly one of `variance_fraction` and `modes`).
    #[serde(default)]
    pub variance_fraction: Option<Spanned<f64>>,
    /// Keep this many modes (at least 1, at most the number of the field mesh's nodes).
    #[serde(default)]
    pub modes: Option<Spanned<usize>>,
    /// A field over a substructure's cells only: discretise it on a regular grid of this many
    /// boxes per axis over the substructure's bounding box (`[nx, ny]` in 2D, `[nx, ny, nz]`
    /// in 3D) instead of on the cells' corners (module `cell_field`).
    #[serde(default)]
    pub grid: Option<Spanned<Vec<usize>>>,
    /// Unit of the field's values (for the report).
    #[serde(default)]
    pub unit: Option<String>,
}
