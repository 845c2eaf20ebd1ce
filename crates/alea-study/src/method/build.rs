//! Building a study file's methods with their designs: the checks of each `[[method]]` table,
//! the design and description of each kind, the default label, a regression design's
//! information check and an adaptive method's settings.

use std::ops::Range;

use alea_uq::basis::PcBasis;
use alea_uq::design::{self, Design};
use alea_uq::quadrature::QuadratureRule;
use alea_uq::surrogate::StochasticMesh;

use super::{
    AdaptiveSettings, Criterion, MAX_INFORMATION_CONDITION, Method, MethodKind, Tolerance,
};
use crate::goal_settings::goal;
use crate::spec::MethodSpec;
use crate::{ParamSpace, Source, StudyError};

fn rows(d: &Design) -> Vec<Vec<f64>> {
    d.iter().map(|p| p.to_vec()).collect()
}

/// A method of one kind: its kind, design points, quadrature rule (projection) and
/// description.
type KindOfMethod = (MethodKind, Vec<Vec<f64>>, Option<QuadratureRule>, String);

/// One `[[method]]` table (index `i`) with what its kinds read from it.
struct MethodInput<'a> {
    src: &'a Source,
    i: usize,
    m: &'a MethodSpec,
    params: &'a ParamSpace,
    seed: u64,
    /// `degree`.
    degree: Option<usize>,
    /// `points_per_dim`.
    ppd: Option<usize>,
    /// `runs`.
    runs: Option<usize>,
    /// `design`.
    design_name: Option<&'a str>,
    /// Where the design is given (the `type` line when it is not).
    design_span: Range<usize>,
}

impl MethodInput<'_> {
    /// The field `k` of this method, for errors.
    fn f(&self, k: &str) -> String {
        format!("method[{}].{k}", self.i)
    }

    /// An error of `alea_uq` at the method's `type` line.
    fn uq(&self, e: alea_uq::UqError) -> StudyError {
        self.src.error(
            self.m.kind.span(),
            format!("method[{}]", self.i),
            e.to_string(),
        )
    }

    /// The number of parameters.
    fn d(&self) -> usize {
        self.params.names.len()
    }

    /// A design by its `name` of `runs` points (`default_runs` if not given).
    fn generic_design(&self, name: &str, default_runs: usize) -> Result<Design, StudyError> {
        let (params, seed, d) = (self.params, self.seed, self.d());
        let uq = |e| self.uq(e);
        let n = self.runs.unwrap_or(default_runs);
        match name {
            "lhs" => Ok(design::latin_hypercube(params.joint.as_ref(), n, seed)),
            "monte_carlo" => Ok(design::monte_carlo(params.joint.as_ref(), n, seed)),
            "sobol" => design::sobol(params.joint.as_ref(), n, Some(seed)).map_err(uq),
            "grid" => {
                let k = self.ppd.unwrap_or(3);
                design::tensor_grid(&params.lo, &params.hi, &vec![k; d]).map_err(uq)
            }
            "corners_centre" => design::corners_and_centre(&params.lo, &params.hi).map_err(uq),
            other => Err(self.src.error(self.design_span.clone(), self.f("design"), format!("unknown design '{other}'; expected pc_collocation, grid, lhs, sobol, monte_carlo or corners_centre"))),
        }
    }
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
        let input = MethodInput {
            src,
            i,
            m,
            params,
            seed,
            degree: m.degree.as_ref().map(|v| *v.get_ref()),
            ppd: m.points_per_dim.as_ref().map(|v| *v.get_ref()),
            runs: m.runs.as_ref().map(|v| *v.get_ref()),
            design_name: m.design.as_ref().map(|s| s.get_ref().as_str()),
            design_span: m.design.as_ref().map_or(m.kind.span(), |s| s.span()),
        };
        check_method_table(&input)?;
        let (kind, points, rule, description) = match m.kind.get_ref().as_str() {
            "pc_regression" => pc_regression_method(&input)?,
            "pc_sparse" => pc_sparse_method(&input)?,
            "pc_projection" => pc_projection_method(&input)?,
            "polynomial" => {
                let p = input.degree.unwrap_or(2);
                let des = input.generic_design(input.design_name.unwrap_or("grid"), 0)?;
                let n = des.len();
                (
                    MethodKind::Polynomial { degree: p },
                    rows(&des),
                    None,
                    format!("standard polynomial of degree {p}, least squares on {n} runs"),
                )
            }
            "piecewise_linear" => piecewise_linear_method(&input)?,
            "adaptive" => adaptive_method(&input, quantities)?,
            "monte_carlo" => {
                let des = input.generic_design(input.design_name.unwrap_or("monte_carlo"), 100)?;
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
                    input.f("type"),
                    format!("unknown method '{other}'; expected pc_regression, pc_sparse, pc_projection, polynomial, piecewise_linear, adaptive or monte_carlo"),
                ));
            }
        };
        let label = m.label.clone().unwrap_or_else(|| default_label(&kind, d));
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

/// The checks of a method table common to its kinds: `points_per_dim` and `runs` large
/// enough, at least one parameter, a goal only on an adaptive method.
fn check_method_table(input: &MethodInput) -> Result<(), StudyError> {
    let (src, m) = (input.src, input.m);
    let f = |k: &str| input.f(k);
    let ppd = input.ppd;
    if ppd == Some(0) || ppd == Some(1) {
        return Err(src.error(
            m.points_per_dim
                .as_ref()
                .map_or(m.kind.span(), |v| v.span()),
            f("points_per_dim"),
            "must be at least 2",
        ));
    }
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
    if input.d() == 0 {
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
    Ok(())
}

/// `pc_regression`: the chaos of `degree` (default 2) fitted by least squares on its design
/// (`pc_collocation` by default), which must determine it.
fn pc_regression_method(input: &MethodInput) -> Result<KindOfMethod, StudyError> {
    let (src, m, params, d) = (input.src, input.m, input.params, input.d());
    let f = |k: &str| input.f(k);
    let uq = |e| input.uq(e);
    let p = input.degree.unwrap_or(2);
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
    let des = match input.design_name.unwrap_or("pc_collocation") {
        "pc_collocation" => {
            if let Some(r) = &m.runs
                && *r.get_ref() > full
            {
                return Err(src.error(r.span(), f("runs"), format!("the pc_collocation design of degree {p} in {d} parameters has {full} candidate points (the (degree + 1)^{d} roots): at most that many runs, got {}", r.get_ref())));
            }
            design::pc_collocation(&params.marginals, p, input.runs.unwrap_or(dflt)).map_err(uq)?
        }
        other => input.generic_design(other, 2 * basis_len)?,
    };
    let (span, field) = design_origin(m);
    if des.len() < basis_len {
        return Err(src.error(span, f(field), too_few(des.len())));
    }
    check_information(&basis, &des, &params.names).map_err(|why| src.error(span, f(field), why))?;
    let n = des.len();
    Ok((
        MethodKind::PcRegression { degree: p },
        rows(&des),
        None,
        format!("polynomial chaos of degree {p} ({basis_len} terms), least squares on {n} runs"),
    ))
}

/// `pc_sparse`: the candidate chaos of `degree` (default 3) on its design (`lhs` by default,
/// `10 d` runs), at least 3 runs.
fn pc_sparse_method(input: &MethodInput) -> Result<KindOfMethod, StudyError> {
    let (params, d) = (input.params, input.d());
    let p = input.degree.unwrap_or(3);
    let basis_len = PcBasis::total_degree(&params.marginals, p)
        .map_err(|e| input.uq(e))?
        .len();
    let des = input.generic_design(input.design_name.unwrap_or("lhs"), 10 * d)?;
    if des.len() < 3 {
        return Err(input.src.error(
            input.m.kind.span(),
            input.f("runs"),
            "sparse chaos needs at least 3 runs",
        ));
    }
    let n = des.len();
    Ok((
        MethodKind::PcSparse { degree: p },
        rows(&des),
        None,
        format!(
            "sparse polynomial chaos of degree {p} ({basis_len} candidate terms): terms selected by LARS with the corrected leave-one-out error for each quantity, their union fitted by least squares on {n} runs"
        ),
    ))
}

/// `pc_projection`: the chaos of `degree` (default 2) projected on a tensor Gauss rule of
/// `points_per_dim` (default `degree + 1`) points per parameter.
fn pc_projection_method(input: &MethodInput) -> Result<KindOfMethod, StudyError> {
    let (params, d) = (input.params, input.d());
    let p = input.degree.unwrap_or(2);
    let q = input.ppd.unwrap_or(p + 1);
    let rule =
        QuadratureRule::tensor_gauss(&params.marginals, &vec![q; d]).map_err(|e| input.uq(e))?;
    let pts: Vec<Vec<f64>> = (0..rule.len()).map(|k| rule.node(k).to_vec()).collect();
    let n = pts.len();
    Ok((
        MethodKind::PcProjection { degree: p },
        pts,
        Some(rule),
        format!(
            "polynomial chaos of degree {p}, projection on a {q}-point-per-parameter Gauss rule ({n} runs)"
        ),
    ))
}

/// `piecewise_linear`: a regular stochastic mesh of `points_per_dim` (default 3) nodes per
/// parameter, its nodes the runs (no other design).
fn piecewise_linear_method(input: &MethodInput) -> Result<KindOfMethod, StudyError> {
    let (params, d) = (input.params, input.d());
    let k = input.ppd.unwrap_or(3);
    if let Some(dn) = input.design_name
        && dn != "grid"
    {
        return Err(input.src.error(
            input.design_span.clone(),
            input.f("design"),
            "piecewise_linear runs on the grid of its stochastic mesh nodes",
        ));
    }
    let mesh =
        StochasticMesh::new(&params.lo, &params.hi, &vec![k - 1; d]).map_err(|e| input.uq(e))?;
    let pts: Vec<Vec<f64>> = (0..mesh.num_runs())
        .map(|r| mesh.run_point(r).to_vec())
        .collect();
    let n = pts.len();
    Ok((
        MethodKind::PiecewiseLinear { nodes: k },
        pts,
        None,
        format!("piecewise multilinear on a regular {k}^{d} grid ({n} runs)"),
    ))
}

/// `adaptive`: its settings, and the corners and the centre of the parameter box as its start
/// design.
fn adaptive_method(input: &MethodInput, quantities: &[String]) -> Result<KindOfMethod, StudyError> {
    let (params, d) = (input.params, input.d());
    let uq = |e| input.uq(e);
    let settings = adaptive_settings(input.src, input.m, input.i, d, quantities)?;
    if let Some(dn) = input.design_name
        && dn != "corners_centre"
    {
        return Err(input.src.error(
            input.design_span.clone(),
            input.f("design"),
            "an adaptive method starts from the corners and the centre of the parameter box (design = \"corners_centre\")",
        ));
    }
    let mut mesh = StochasticMesh::new(&params.lo, &params.hi, &vec![1; d]).map_err(uq)?;
    mesh.refine_centred(&[0]).map_err(uq)?;
    let pts: Vec<Vec<f64>> = (0..mesh.num_runs())
        .map(|r| mesh.run_point(r).to_vec())
        .collect();
    let description = adaptive_description(&settings, quantities, d);
    Ok((MethodKind::Adaptive(settings), pts, None, description))
}

/// An adaptive method's description: its start, criterion and stop.
fn adaptive_description(settings: &AdaptiveSettings, quantities: &[String], d: usize) -> String {
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
    format!(
        "adaptive piecewise multilinear from the {} corners and the centre, {crit}, until {stop} or {max_runs} runs",
        1usize << d,
    )
}

/// The label of a method without one, from its kind (`d` parameters).
fn default_label(kind: &MethodKind, d: usize) -> String {
    match kind {
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
    }
}

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

/// An adaptive method's settings (criterion, target, run budget, goal), checked.
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
