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

use alea_uq::basis::PcBasis;
use alea_uq::design::{self, Design};
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::{
    LinearSurrogate, MonomialSurface, ParentLevel, PcSurrogate, StochasticMesh,
};

pub use crate::error::SurrogateError;
use crate::goal_settings::goal;
pub use crate::goal_settings::{Goal, Tolerance};
use crate::spec::MethodSpec;
use crate::{ParamSpace, Source, StudyError};

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

fn rows(d: &Design) -> Vec<Vec<f64>> {
    d.iter().map(|p| p.to_vec()).collect()
}

/// Builds the methods of a study file with their designs.
pub fn build_methods(
    src: &Source,
    specs: &[MethodSpec],
    params: &ParamSpace,
    quantities: &[String],
    seed: u64,
) -> Result<Vec<Method>, StudyError> {
    let d = params.names.len();
    let mut out = Vec::new();
    for (i, m) in specs.iter().enumerate() {
        crate::limits::check_method(src, i, m, d)?;
        let f = |k: &str| format!("method[{i}].{k}");
        let uq =
            |e: alea_uq::UqError| src.error(m.kind.span(), format!("method[{i}]"), e.to_string());
        let degree = m.degree.as_ref().map(|v| *v.get_ref());
        let ppd = m.points_per_dim.as_ref().map(|v| *v.get_ref());
        if ppd == Some(0) || ppd == Some(1) {
            return Err(src.error(
                m.points_per_dim
                    .as_ref()
                    .map_or(m.kind.span(), |v| v.span()),
                f("points_per_dim"),
                "must be at least 2",
            ));
        }
        let runs = m.runs.as_ref().map(|v| *v.get_ref());
        if let Some(r) = &m.runs {
            let least = if m.kind.get_ref() == "monte_carlo" {
                2
            } else {
                1
            };
            if *r.get_ref() < least {
                return Err(src.error(
                    r.span(),
                    f("runs"),
                    format!(
                        "must be at least {least} (got {}){}",
                        r.get_ref(),
                        if least == 2 {
                            ": Monte Carlo statistics need two runs"
                        } else {
                            ""
                        }
                    ),
                ));
            }
        }
        let design_name = m.design.as_ref().map(|s| s.get_ref().as_str());
        let design_span = m.design.as_ref().map_or(m.kind.span(), |s| s.span());
        let generic_design = |name: &str, default_runs: usize| -> Result<Design, StudyError> {
            let n = runs.unwrap_or(default_runs);
            match name {
                "lhs" => Ok(design::latin_hypercube(params.joint.as_ref(), n, seed)),
                "monte_carlo" => Ok(design::monte_carlo(params.joint.as_ref(), n, seed)),
                "sobol" => design::sobol(params.joint.as_ref(), n, Some(seed)).map_err(uq),
                "grid" => {
                    let k = ppd.unwrap_or(3);
                    design::tensor_grid(&params.lo, &params.hi, &vec![k; d]).map_err(uq)
                }
                "corners_centre" => design::corners_and_centre(&params.lo, &params.hi).map_err(uq),
                other => Err(src.error(design_span.clone(), f("design"), format!("unknown design '{other}'; expected pc_collocation, grid, lhs, sobol, monte_carlo or corners_centre"))),
            }
        };
        if d == 0 {
            return Err(src.error(
                m.kind.span(),
                f("type"),
                "a method needs at least one [[parameter]]",
            ));
        }
        if let Some(g) = &m.goal
            && m.kind.get_ref() != "adaptive"
        {
            return Err(src.error(
                g.span(),
                f("goal"),
                "only an adaptive method has a goal (it chooses its runs by it)",
            ));
        }
        let (kind, points, rule, description) = match m.kind.get_ref().as_str() {
            "pc_regression" => {
                let p = degree.unwrap_or(2);
                let basis = PcBasis::total_degree(&params.marginals, p).map_err(uq)?;
                let basis_len = basis.len();
                let full = (p + 1).saturating_pow(d as u32);
                let dflt = full.min((2 * basis_len).max(basis_len + 1));
                let too_few = |n: usize| {
                    format!(
                        "PC of degree {p} in {d} parameters has {basis_len} terms: at least that many runs are needed, got {n}"
                    )
                };
                if let Some(r) = &m.runs
                    && *r.get_ref() < basis_len
                {
                    return Err(src.error(r.span(), f("runs"), too_few(*r.get_ref())));
                }
                let des = match design_name.unwrap_or("pc_collocation") {
                    "pc_collocation" => {
                        if let Some(r) = &m.runs
                            && *r.get_ref() > full
                        {
                            return Err(src.error(r.span(), f("runs"), format!("the pc_collocation design of degree {p} in {d} parameters has {full} candidate points (the (degree + 1)^{d} roots): at most that many runs, got {}", r.get_ref())));
                        }
                        design::pc_collocation(&params.marginals, p, runs.unwrap_or(dflt))
                            .map_err(uq)?
                    }
                    other => generic_design(other, 2 * basis_len)?,
                };
                let (span, field) = design_origin(m);
                if des.len() < basis_len {
                    return Err(src.error(span, f(field), too_few(des.len())));
                }
                check_information(&basis, &des, &params.names)
                    .map_err(|why| src.error(span, f(field), why))?;
                let n = des.len();
                (
                    MethodKind::PcRegression { degree: p },
                    rows(&des),
                    None,
                    format!(
                        "polynomial chaos of degree {p} ({basis_len} terms), least squares on {n} runs"
                    ),
                )
            }
            "pc_sparse" => {
                let p = degree.unwrap_or(3);
                let basis_len = PcBasis::total_degree(&params.marginals, p)
                    .map_err(uq)?
                    .len();
                let des = generic_design(design_name.unwrap_or("lhs"), 10 * d)?;
                if des.len() < 3 {
                    return Err(src.error(
                        m.kind.span(),
                        f("runs"),
                        "sparse chaos needs at least 3 runs",
                    ));
                }
                let n = des.len();
                (
                    MethodKind::PcSparse { degree: p },
                    rows(&des),
                    None,
                    format!(
                        "sparse polynomial chaos of degree {p} ({basis_len} candidate terms): terms selected by LARS with the corrected leave-one-out error for each quantity, their union fitted by least squares on {n} runs"
                    ),
                )
            }
            "pc_projection" => {
                let p = degree.unwrap_or(2);
                let q = ppd.unwrap_or(p + 1);
                let rule =
                    QuadratureRule::tensor_gauss(&params.marginals, &vec![q; d]).map_err(uq)?;
                let pts: Vec<Vec<f64>> = (0..rule.len()).map(|k| rule.node(k).to_vec()).collect();
                let n = pts.len();
                (
                    MethodKind::PcProjection { degree: p },
                    pts,
                    Some(rule),
                    format!(
                        "polynomial chaos of degree {p}, projection on a {q}-point-per-parameter Gauss rule ({n} runs)"
                    ),
                )
            }
            "polynomial" => {
                let p = degree.unwrap_or(2);
                let des = generic_design(design_name.unwrap_or("grid"), 0)?;
                let n = des.len();
                (
                    MethodKind::Polynomial { degree: p },
                    rows(&des),
                    None,
                    format!("standard polynomial of degree {p}, least squares on {n} runs"),
                )
            }
            "piecewise_linear" => {
                let k = ppd.unwrap_or(3);
                if let Some(dn) = design_name
                    && dn != "grid"
                {
                    return Err(src.error(
                        design_span,
                        f("design"),
                        "piecewise_linear runs on the grid of its stochastic mesh nodes",
                    ));
                }
                let mesh =
                    StochasticMesh::new(&params.lo, &params.hi, &vec![k - 1; d]).map_err(uq)?;
                let pts: Vec<Vec<f64>> = (0..mesh.num_runs())
                    .map(|r| mesh.run_point(r).to_vec())
                    .collect();
                let n = pts.len();
                (
                    MethodKind::PiecewiseLinear { nodes: k },
                    pts,
                    None,
                    format!("piecewise multilinear on a regular {k}^{d} grid ({n} runs)"),
                )
            }
            "adaptive" => {
                let settings = adaptive_settings(src, m, i, d, quantities)?;
                if let Some(dn) = design_name
                    && dn != "corners_centre"
                {
                    return Err(src.error(
                        design_span,
                        f("design"),
                        "an adaptive method starts from the corners and the centre of the parameter box (design = \"corners_centre\")",
                    ));
                }
                let mut mesh =
                    StochasticMesh::new(&params.lo, &params.hi, &vec![1; d]).map_err(uq)?;
                mesh.refine_centred(&[0]).map_err(uq)?;
                let pts: Vec<Vec<f64>> = (0..mesh.num_runs())
                    .map(|r| mesh.run_point(r).to_vec())
                    .collect();
                let crit = match settings.criterion {
                    Criterion::Improved { fraction } => format!(
                        "improved criterion (cells above {:.0} % of the largest error)",
                        100.0 * fraction
                    ),
                    Criterion::MaxError { .. } => "maximum-error criterion".to_string(),
                };
                let stop = match (&settings.goal, settings.target) {
                    (Some(g), _) => {
                        let q = &quantities[g.quantity];
                        let stat = match g.threshold {
                            Some(t) => format!("P({q} > {t})"),
                            None => format!("the mean and std of {q}"),
                        };
                        let tol = match g.tolerance {
                            Tolerance::Absolute(t) => format!("{t}"),
                            Tolerance::Relative(r) => format!("{} % of its value", 100.0 * r),
                        };
                        format!("goal: the error budget of {stat} <= {tol}")
                    }
                    (None, Some(t)) => format!("i_sto <= {t}"),
                    (None, None) => "i_sto <= i_geo".to_string(),
                };
                let max_runs = settings.max_runs;
                (
                    MethodKind::Adaptive(settings),
                    pts,
                    None,
                    format!(
                        "adaptive piecewise multilinear from the {} corners and the centre, {crit}, until {stop} or {max_runs} runs",
                        1usize << d,
                    ),
                )
            }
            "monte_carlo" => {
                let des = generic_design(design_name.unwrap_or("monte_carlo"), 100)?;
                let n = des.len();
                (
                    MethodKind::MonteCarlo,
                    rows(&des),
                    None,
                    format!("Monte Carlo on the model ({n} runs)"),
                )
            }
            other => {
                return Err(src.error(
                    m.kind.span(),
                    f("type"),
                    format!("unknown method '{other}'; expected pc_regression, pc_sparse, pc_projection, polynomial, piecewise_linear, adaptive or monte_carlo"),
                ));
            }
        };
        let label = m.label.clone().unwrap_or_else(|| match &kind {
            MethodKind::PcRegression { degree } => format!("PC regression p={degree}"),
            MethodKind::PcSparse { degree } => format!("sparse PC p={degree}"),
            MethodKind::PcProjection { degree } => format!("PC projection p={degree}"),
            MethodKind::Polynomial { degree } => format!("polynomial p={degree}"),
            MethodKind::PiecewiseLinear { nodes } => format!("piecewise linear {nodes}^{d}"),
            MethodKind::MonteCarlo => "Monte Carlo".into(),
            MethodKind::Adaptive(a) => match a.criterion {
                Criterion::Improved { .. } => "adaptive (improved)".into(),
                Criterion::MaxError { .. } => "adaptive (max error)".into(),
            },
        });
        out.push(Method {
            label,
            kind,
            points,
            rule,
            description,
            mesh: None,
            sparse_basis: None,
        });
    }
    Ok(out)
}

/// Largest condition number of the information matrix `Psi^T Psi` of a regression design
/// accepted at load: the fit would amplify errors in the runs' values by up to
/// `sqrt(1e12) = 1e6` (`alea_uq::design::information`).
pub const MAX_INFORMATION_CONDITION: f64 = 1e12;

/// The span and field that fix a method's design: `runs` if given, else `points_per_dim` of a
/// grid, else `design` if given, else the method's `type` line (field `design`: its default).
fn design_origin(m: &MethodSpec) -> (std::ops::Range<usize>, &'static str) {
    if let Some(r) = &m.runs {
        return (r.span(), "runs");
    }
    let design = m.design.as_ref();
    if let (Some(k), Some("grid")) = (&m.points_per_dim, design.map(|s| s.get_ref().as_str())) {
        return (k.span(), "points_per_dim");
    }
    (design.map_or(m.kind.span(), |s| s.span()), "design")
}

/// Whether a design determines the chaos `basis`: its information matrix `Psi^T Psi` has full
/// rank and a condition number of at most [`MAX_INFORMATION_CONDITION`]. The error says why not,
/// naming the first term the runs cannot tell from the ones before it.
fn check_information(basis: &PcBasis, des: &Design, names: &[String]) -> Result<(), String> {
    let n = des.len();
    let terms = basis.len();
    let psi = basis
        .design_matrix(des.points())
        .map_err(|e| e.to_string())?;
    let advice = "more runs or another design are needed";
    match design::information(&psi, n, terms) {
        Ok(info) if info.condition() <= MAX_INFORMATION_CONDITION => Ok(()),
        Ok(info) => Err(format!(
            "the information matrix Psi^T Psi of the {terms} chaos terms on these {n} runs has condition number {:.1e} (at most {MAX_INFORMATION_CONDITION:.0e}): the fit would amplify the runs' errors up to {:.0e} times; {advice}",
            info.condition(),
            info.condition().sqrt()
        )),
        Err(alea_uq::UqError::Singular { pivot, .. }) => Err(format!(
            "these {n} runs cannot determine the {terms} chaos terms: on them the term {} is a combination of the terms before it (Psi^T Psi is rank deficient); {advice}",
            term_name(basis.indices().get(pivot), names)
        )),
        Err(e) => Err(e.to_string()),
    }
}

/// A term of the chaos by its multi-index and leading monomial, e.g. `(3, 0) (leading monomial
/// E^3)`.
fn term_name(alpha: &[u16], names: &[String]) -> String {
    let index: Vec<String> = alpha.iter().map(|a| a.to_string()).collect();
    let factors: Vec<String> = alpha
        .iter()
        .zip(names)
        .filter(|(a, _)| **a > 0)
        .map(|(a, x)| {
            if *a == 1 {
                x.clone()
            } else {
                format!("{x}^{a}")
            }
        })
        .collect();
    let monomial = if factors.is_empty() {
        "1".to_string()
    } else {
        factors.join(" ")
    };
    format!("({}) (leading monomial {monomial})", index.join(", "))
}

fn adaptive_settings(
    src: &Source,
    m: &MethodSpec,
    i: usize,
    d: usize,
    quantities: &[String],
) -> Result<AdaptiveSettings, StudyError> {
    let f = |k: &str| format!("method[{i}].{k}");
    if d > alea_uq::surrogate::MAX_DIM {
        return Err(src.error(
            m.kind.span(),
            f("type"),
            format!(
                "an adaptive stochastic mesh has at most {} parameters, the study has {d}",
                alea_uq::surrogate::MAX_DIM
            ),
        ));
    }
    let fraction = match &m.fraction {
        Some(v) => {
            let x = *v.get_ref();
            if !(x > 0.0 && x <= 1.0) {
                return Err(src.error(
                    v.span(),
                    f("fraction"),
                    format!("must be in (0, 1], got {x}"),
                ));
            }
            x
        }
        None => 0.5,
    };
    let depth = match &m.depth {
        Some(v) => {
            let x = *v.get_ref();
            if x == 0 || (x as usize) * d > 18 {
                return Err(src.error(
                    v.span(),
                    f("depth"),
                    format!("must be in 1..={} for {d} parameters (2^(d depth) candidate points per cell)", 18 / d.max(1)),
                ));
            }
            x
        }
        None => (18 / d.max(1)).min(3) as u32,
    };
    let criterion = match m.criterion.as_ref().map(|c| c.get_ref().as_str()) {
        None | Some("improved") => Criterion::Improved { fraction },
        Some("max_error") => Criterion::MaxError { depth },
        Some(other) => {
            let sp = m.criterion.as_ref().map_or(m.kind.span(), |c| c.span());
            return Err(src.error(
                sp,
                f("criterion"),
                format!("unknown criterion '{other}'; expected improved or max_error"),
            ));
        }
    };
    let target = match &m.target {
        Some(v) => {
            let x = *v.get_ref();
            if !(x > 0.0 && x < 1.0) {
                return Err(src.error(
                    v.span(),
                    f("target"),
                    format!("must be in (0, 1), got {x}"),
                ));
            }
            Some(x)
        }
        None => None,
    };
    let start = (1usize << d) + 1;
    let max_runs = match &m.max_runs {
        Some(v) => {
            let x = *v.get_ref();
            if x < start || x > 100_000 {
                return Err(src.error(
                    v.span(),
                    f("max_runs"),
                    format!(
                        "must be in {start}..=100000 (the start design has {start} runs), got {x}"
                    ),
                ));
            }
            x
        }
        None => 100.max(start),
    };
    let goal = match &m.goal {
        Some(g) => Some(goal(src, g, i, quantities)?),
        None => None,
    };
    Ok(AdaptiveSettings {
        criterion,
        target,
        max_runs,
        goal,
    })
}

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
