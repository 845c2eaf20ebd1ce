//! Methods: a design (the collocation points to run) and a linear surrogate built on the runs
//! (thesis chapter 1.3 and 2.3): polynomial chaos by regression on PC collocation points (roots
//! of the next-degree orthogonal polynomials) or by projection on a tensor Gauss rule; a
//! standard (monomial) polynomial by least squares on a grid; piecewise multilinear
//! interpolation on a regular stochastic mesh; piecewise multilinear interpolation on an
//! **adaptive** stochastic mesh that chooses its own runs with the stochastic error estimate
//! (thesis 4.2; the loop is in the `adaptive` module); or plain Monte Carlo on the model.
//!
//! A chaos fitted by regression must be determined by its design: at load the information
//! matrix `Psi^T Psi` of the basis at the design points is checked (`alea_uq::design::
//! information`: rank by Cholesky, condition number at most [`MAX_INFORMATION_CONDITION`]) and a
//! design that fails is an input error at the line that fixes it. The default design,
//! `pc_collocation`, takes `min((p + 1)^d, 2 P)` points of the tensor grid of roots, chosen
//! greedily D-optimal when fewer than the whole grid (`alea_uq::design::pc_collocation`).
//!
//! The methods of a study file are built, with their designs, in `method/build.rs`.

use alea_uq::basis::PcBasis;
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::{
    LinearSurrogate, MonomialSurface, ParentLevel, PcSurrogate, StochasticMesh,
};

mod build;

use crate::ParamSpace;
pub use crate::error::SurrogateError;
pub use crate::goal_settings::{Goal, Tolerance};
pub use build::build_methods;

/// The kinds of methods.
#[derive(Clone, Debug, PartialEq)]
pub enum MethodKind {
    /// PC of total degree `degree`, coefficients by least squares.
    PcRegression {
        /// Degree.
        degree: usize,
    },
    /// Sparse PC: for each quantity LARS (corrected leave-one-out) selects terms of the
    /// total-degree-`degree` basis; the union of the selections is fitted by least squares
    /// (`crate::sparse`).
    PcSparse {
        /// Degree of the candidate basis.
        degree: usize,
    },
    /// PC of total degree `degree`, coefficients by projection on a tensor Gauss rule.
    PcProjection {
        /// Degree.
        degree: usize,
    },
    /// Monomials of total degree `degree` (on the parameter box mapped to [-1, 1]).
    Polynomial {
        /// Degree.
        degree: usize,
    },
    /// Piecewise multilinear interpolation on a regular grid of the parameter box.
    PiecewiseLinear {
        /// Nodes per parameter.
        nodes: usize,
    },
    /// Statistics of the model runs themselves.
    MonteCarlo,
    /// Piecewise multilinear on a stochastic mesh refined by the stochastic error estimate.
    Adaptive(AdaptiveSettings),
}

/// The refinement criterion of an adaptive method (thesis 4.2.2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Criterion {
    /// Every cell whose stochastic error is at least `fraction` of the largest gets a run at its
    /// centre; several runs per estimate.
    Improved {
        /// Fraction of the largest cell contribution (the thesis: 0.5).
        fraction: f64,
    },
    /// One run per estimate where the stochastic error density is largest (searched over the
    /// centres of the `2^(d depth)` sub-cells of every cell and the interpolated nodes): at
    /// that node, or at the centre of the cell that holds the sub-cell centre.
    MaxError {
        /// Sub-cell depth of the candidate points of the search.
        depth: u32,
    },
}

/// Settings of an adaptive method.
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptiveSettings {
    /// Refinement criterion.
    pub criterion: Criterion,
    /// Stop when `i_sto <= target` (`None`: when `i_sto <= i_geo` and `i_geo` is stable).
    pub target: Option<f64>,
    /// Run budget.
    pub max_runs: usize,
    /// A goal quantity: refinement and stop follow its statistic's error budget instead
    /// (`crate::goal`).
    pub goal: Option<Goal>,
}

/// A method with its design.
#[derive(Clone, Debug)]
pub struct Method {
    /// Label for tables and plots.
    pub label: String,
    /// Kind.
    pub kind: MethodKind,
    /// Design points (physical), one per run.
    pub points: Vec<Vec<f64>>,
    /// Quadrature weights (projection only).
    pub rule: Option<QuadratureRule>,
    /// A one-line description for the report.
    pub description: String,
    /// Adaptive methods: the stochastic mesh once the loop has run (its runs are `points`).
    pub mesh: Option<StochasticMesh>,
    /// Sparse chaos: the multi-indices selected once the runs are done (`crate::sparse`).
    pub sparse_basis: Option<Vec<Vec<u16>>>,
}

impl Method {
    /// The method of a study without random parameters: one deterministic run, whose
    /// quantities are reported as they are (no surrogate, no sampling).
    pub fn deterministic() -> Self {
        Method {
            label: "deterministic".into(),
            kind: MethodKind::MonteCarlo,
            points: vec![Vec::new()],
            rule: None,
            description: "one deterministic run (the study has no random parameter)".into(),
            mesh: None,
            sparse_basis: None,
        }
    }
}

/// Largest condition number of the information matrix `Psi^T Psi` of a regression design
/// accepted at load: the fit would amplify errors in the runs' values by up to
/// `sqrt(1e12) = 1e6` (`alea_uq::design::information`).
pub const MAX_INFORMATION_CONDITION: f64 = 1e12;

/// A surrogate in physical coordinates, whatever its internal coordinates.
pub struct Surrogate {
    inner: Box<dyn LinearSurrogate>,
    /// Map physical -> internal: `(x - shift) * scale`, per coordinate.
    shift: Vec<f64>,
    scale: Vec<f64>,
    /// Clamp physical points into `[lo, hi]` before evaluation (piecewise linear).
    clamp: Option<(Vec<f64>, Vec<f64>)>,
}

impl std::fmt::Debug for Surrogate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Surrogate")
            .field("runs", &self.inner.num_runs())
            .finish()
    }
}

impl Surrogate {
    /// The interpolant one level coarser than a stochastic mesh where it can be coarsened
    /// (`ParentLevel::coarsenable`: every family of leaves merged), on the box.
    pub fn coarsenable_level(mesh: StochasticMesh, params: &ParamSpace) -> Self {
        let d = params.names.len();
        Surrogate {
            inner: Box::new(ParentLevel::coarsenable(mesh)),
            shift: vec![0.0; d],
            scale: vec![1.0; d],
            clamp: Some((params.lo.clone(), params.hi.clone())),
        }
    }

    /// Number of runs it is built on.
    pub fn num_runs(&self) -> usize {
        self.inner.num_runs()
    }

    /// Non-zero weights at physical point `x` (scratch `t` of the parameter dimension).
    pub fn weights(&self, x: &[f64], t: &mut [f64], w: &mut Vec<(usize, f64)>) {
        for j in 0..x.len() {
            let mut v = x[j];
            if let Some((lo, hi)) = &self.clamp {
                v = v.clamp(lo[j], hi[j]);
            }
            t[j] = (v - self.shift[j]) * self.scale[j];
        }
        self.inner.weights(t, w);
    }
}

impl alea_estimate::Weights for Surrogate {
    fn weights(&self, xi: &[f64], w: &mut Vec<(usize, f64)>) {
        let mut t = vec![0.0; xi.len()];
        Surrogate::weights(self, xi, &mut t, w);
    }
}

impl Method {
    /// The stochastic mesh of a piecewise-linear or adaptive method (its cells are the
    /// integration cells of the error estimate); `None` for global surrogates.
    pub fn stochastic_mesh(&self, params: &ParamSpace) -> Option<StochasticMesh> {
        match &self.kind {
            MethodKind::PiecewiseLinear { nodes } => {
                let d = params.names.len();
                StochasticMesh::new(&params.lo, &params.hi, &vec![nodes - 1; d]).ok()
            }
            MethodKind::Adaptive(_) => self.mesh.clone(),
            _ => None,
        }
    }

    /// Builds the surrogate on the runs at `points` (a subset of the design: the converged
    /// runs). Methods that need every design point (projection, piecewise linear) refuse a
    /// subset.
    pub fn surrogate(
        &self,
        params: &ParamSpace,
        points: &[Vec<f64>],
    ) -> Result<Surrogate, SurrogateError> {
        let d = params.names.len();
        let flat: Vec<f64> = points.iter().flatten().copied().collect();
        let identity = || (vec![0.0; d], vec![1.0; d]);
        let complete = points.len() == self.points.len();
        let (inner, (shift, scale), clamp): (Box<dyn LinearSurrogate>, _, _) = match &self.kind {
            MethodKind::PcRegression { degree } => {
                let basis = PcBasis::total_degree(&params.marginals, *degree)?;
                (
                    Box::new(PcSurrogate::regression(basis, &flat)?),
                    identity(),
                    None,
                )
            }
            MethodKind::PcSparse { .. } => {
                let set = self.sparse_basis.as_ref().ok_or(SurrogateError::Unavailable(
                    "no sparse basis: it is selected once the runs are done, and none is kept when LARS fails or the union of the selections has as many terms as runs",
                ))?;
                let set = alea_uq::basis::MultiIndexSet::from_indices(d, set)?;
                let basis = PcBasis::new(&params.marginals, set)?;
                (
                    Box::new(PcSurrogate::regression(basis, &flat)?),
                    identity(),
                    None,
                )
            }
            MethodKind::PcProjection { degree } => {
                if !complete {
                    return Err(SurrogateError::Unavailable(
                        "projection needs a run at every quadrature node",
                    ));
                }
                let basis = PcBasis::total_degree(&params.marginals, *degree)?;
                let rule = self
                    .rule
                    .as_ref()
                    .ok_or(SurrogateError::Unavailable("projection without a rule"))?;
                (
                    Box::new(PcSurrogate::projection(basis, rule)?),
                    identity(),
                    None,
                )
            }
            MethodKind::Polynomial { degree } => {
                // Fit on the box mapped to [-1, 1]^d: monomials of raw parameters (e.g. E ~ 2e5
                // and mu ~ 0.5) would be hopelessly ill-conditioned.
                let shift: Vec<f64> = (0..d)
                    .map(|j| 0.5 * (params.lo[j] + params.hi[j]))
                    .collect();
                let scale: Vec<f64> = (0..d)
                    .map(|j| 2.0 / (params.hi[j] - params.lo[j]))
                    .collect();
                let t: Vec<f64> = points
                    .iter()
                    .flat_map(|p| {
                        (0..d)
                            .map(|j| (p[j] - shift[j]) * scale[j])
                            .collect::<Vec<_>>()
                    })
                    .collect();
                (
                    Box::new(MonomialSurface::fit(d, *degree, &t)?),
                    (shift, scale),
                    None,
                )
            }
            MethodKind::PiecewiseLinear { nodes } => {
                if !complete {
                    return Err(SurrogateError::Unavailable(
                        "piecewise-linear interpolation needs a run at every grid node",
                    ));
                }
                let mesh = StochasticMesh::new(&params.lo, &params.hi, &vec![nodes - 1; d])?;
                (
                    Box::new(mesh),
                    identity(),
                    Some((params.lo.clone(), params.hi.clone())),
                )
            }
            MethodKind::Adaptive(_) => {
                let mesh = self.mesh.as_ref().ok_or(SurrogateError::Unavailable(
                    "the adaptive loop has not built its stochastic mesh",
                ))?;
                if !complete || mesh.num_runs() != points.len() {
                    return Err(SurrogateError::Unavailable(
                        "the adaptive stochastic mesh needs a run at every node",
                    ));
                }
                (
                    Box::new(mesh.clone()),
                    identity(),
                    Some((params.lo.clone(), params.hi.clone())),
                )
            }
            MethodKind::MonteCarlo => {
                return Err(SurrogateError::Unavailable("Monte Carlo has no surrogate"));
            }
        };
        Ok(Surrogate {
            inner,
            shift,
            scale,
            clamp,
        })
    }
}
