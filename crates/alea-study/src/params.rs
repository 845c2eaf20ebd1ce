//! The random parameters of a study: marginal laws, joint law, nominal point and the box used
//! by grids and the stochastic mesh. A `[[parameter]]` key that its law does not use is
//! refused (module `law_keys`).

use std::sync::Arc;

use alea_uq::copula::{ClaytonCopula, FrankCopula, GumbelCopula, StudentCopula};
use alea_uq::joint::{BoxDensity, GaussianCopula, Independent, JointLaw, ProductJoint};
use alea_uq::law::{Beta, LogNormal, Marginal, Normal, Triangular, TruncatedNormal, Uniform};
use toml::Spanned;

use crate::expr::Expr;
use crate::spec::{ModelFile, ParameterSpec};
use crate::{Source, StudyError};

/// The law of zero parameters (a deterministic case): one point, probability 1.
#[derive(Debug)]
struct NoParameters;

impl JointLaw for NoParameters {
    fn dim(&self) -> usize {
        0
    }
    fn pdf(&self, _x: &[f64]) -> f64 {
        1.0
    }
    fn x_to_unit(&self, _x: &[f64], _u: &mut [f64]) {}
    fn unit_to_x(&self, _u: &[f64], _x: &mut [f64]) {}
    fn bounds(&self) -> (Vec<f64>, Vec<f64>) {
        (Vec::new(), Vec::new())
    }
    fn is_independent(&self) -> bool {
        true
    }
}

/// Parameters, laws and the joint law.
#[derive(Clone, Debug)]
pub struct ParamSpace {
    /// Names (the expression variables, in order).
    pub names: Vec<String>,
    /// Units (for the report).
    pub units: Vec<String>,
    /// Human-readable law descriptions.
    pub descriptions: Vec<String>,
    /// Marginal laws.
    pub marginals: Vec<Arc<dyn Marginal>>,
    /// Joint law.
    pub joint: Arc<dyn JointLaw>,
    /// Nominal point (marginal means): used by `alea solve` and as the reference of scale
    /// factors.
    pub nominal: Vec<f64>,
    /// Lower corner of the parameter box (support, or the 1e-6 quantile if unbounded).
    pub lo: Vec<f64>,
    /// Upper corner.
    pub hi: Vec<f64>,
    /// Random fields (`[[field]]`): their KL variables are the last parameters.
    pub fields: Vec<Arc<crate::random_field::StudyField>>,
}

fn need(
    src: &Source,
    p: &ParameterSpec,
    v: &Option<Spanned<f64>>,
    field: &str,
    i: usize,
) -> Result<f64, StudyError> {
    v.as_ref().map(|s| *s.get_ref()).ok_or_else(|| {
        src.error(
            p.law.span(),
            format!("parameter[{i}].{field}"),
            format!("law '{}' needs '{field}'", p.law.get_ref()),
        )
    })
}

fn marginal(
    src: &Source,
    p: &ParameterSpec,
    i: usize,
) -> Result<(Arc<dyn Marginal>, String), StudyError> {
    let f = |k: &str| {
        need(
            src,
            p,
            match k {
                "mean" => &p.mean,
                "std" => &p.std,
                "lo" => &p.lo,
                "hi" => &p.hi,
                "mode" => &p.mode,
                "alpha" => &p.alpha,
                _ => &p.beta,
            },
            k,
            i,
        )
    };
    let bad = |e: alea_uq::UqError| {
        src.error(
            p.law.span(),
            format!("parameter[{i}] ({})", p.name.get_ref()),
            e.to_string(),
        )
    };
    let law = p.law.get_ref().as_str();
    let from_data = crate::data_law::DATA_LAWS.contains(&law);
    crate::data_law::check_data_keys(src, p, i)?;
    if let Some(d) = &p.data
        && !from_data
    {
        return Err(src.error(
            d.span(),
            format!("parameter[{i}].data"),
            format!(
                "law '{law}' takes no data; data goes with law = \"empirical\", \"kde\" or \"fit\""
            ),
        ));
    }
    crate::law_keys::check(src, p, i)?;
    if from_data {
        return crate::data_law::data_law(src, p, i);
    }
    let (m, d): (Arc<dyn Marginal>, String) = match law {
        "uniform" => {
            let (a, b) = (f("lo")?, f("hi")?);
            (
                Arc::new(Uniform::new(a, b).map_err(bad)?),
                format!("uniform on [{a}, {b}]"),
            )
        }
        "normal" => {
            let (m, s) = (f("mean")?, f("std")?);
            (
                Arc::new(Normal::new(m, s).map_err(bad)?),
                format!("normal (mean {m}, std {s})"),
            )
        }
        "truncated_normal" => {
            let (m, s, a, b) = (f("mean")?, f("std")?, f("lo")?, f("hi")?);
            (
                Arc::new(TruncatedNormal::new(m, s, a, b).map_err(bad)?),
                format!("truncated normal (mean {m}, std {s}) on [{a}, {b}]"),
            )
        }
        "lognormal" => {
            let (m, s) = (f("mean")?, f("std")?);
            (
                Arc::new(LogNormal::from_mean_std(m, s).map_err(bad)?),
                format!("lognormal (mean {m}, std {s})"),
            )
        }
        "beta" => {
            let (al, be, a, b) = (f("alpha")?, f("beta")?, f("lo")?, f("hi")?);
            (
                Arc::new(Beta::new(al, be, a, b).map_err(bad)?),
                format!("beta ({al}, {be}) on [{a}, {b}]"),
            )
        }
        "triangular" => {
            let (a, c, b) = (f("lo")?, f("mode")?, f("hi")?);
            (
                Arc::new(Triangular::new(a, c, b).map_err(bad)?),
                format!("triangular ({a}, {c}, {b})"),
            )
        }
        other => {
            return Err(src.error(
                p.law.span(),
                format!("parameter[{i}].law"),
                format!("unknown law '{other}'; expected uniform, normal, truncated_normal, lognormal, beta, triangular, or from data: empirical, kde, fit"),
            ));
        }
    };
    Ok((m, d))
}

/// Builds the parameter space of a study file (empty if it has no parameters).
pub fn build_params(src: &Source, file: &ModelFile) -> Result<ParamSpace, StudyError> {
    let mut names: Vec<String> = Vec::new();
    let mut marginals = Vec::new();
    let mut descriptions = Vec::new();
    let reserved = ["x", "y", "z", "pi"];
    for (i, p) in file.parameter.iter().enumerate() {
        let n = p.name.get_ref();
        let valid = n
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !valid || reserved.contains(&n.as_str()) || names.contains(n) {
            return Err(src.error(
                p.name.span(),
                format!("parameter[{i}].name"),
                format!(
                    "'{n}' is not a usable name (letters, digits, '_'; unique; not x, y, z or pi)"
                ),
            ));
        }
        names.push(n.clone());
        let (m, d) = marginal(src, p, i)?;
        marginals.push(m);
        descriptions.push(d);
    }
    let mut taken = names.clone();
    taken.extend(file.define.iter().map(|d| d.name.get_ref().clone()));
    let (fields, variables) = crate::random_field::build_fields(src, file, &taken, names.len())?;
    for f in &fields {
        for k in 0..f.num_variables() {
            marginals.push(Arc::new(Normal::new(0.0, 1.0).map_err(StudyError::from)?));
            descriptions.push(format!(
                "standard normal: KL variable {} of field '{}' (eigenvalue {:.4e}; {})",
                k + 1,
                f.name,
                f.field.kl().eigenvalues()[k],
                f.description
            ));
        }
    }
    names.extend(variables);
    let d = names.len();
    let nominal: Vec<f64> = marginals.iter().map(|m| m.mean()).collect();
    let (mut lo, mut hi) = (Vec::new(), Vec::new());
    for m in &marginals {
        let (a, b) = m.support();
        // A law on a half-line (lognormal, gamma) has its finite end as a limit its draws do
        // not reach - where a lognormal modulus would vanish -, so its box is its 1e-6 and
        // 1 - 1e-6 quantiles at both ends, as for a law on the whole line: a design over the
        // box (grids, the adaptive mesh's corners) never runs at that end.
        let half_line = a.is_finite() != b.is_finite();
        lo.push(if a.is_finite() && !half_line {
            a
        } else {
            m.quantile(1e-6)
        });
        hi.push(if b.is_finite() && !half_line {
            b
        } else {
            m.quantile(1.0 - 1e-6)
        });
    }
    // A dependent `[joint]` spans the `[[parameter]]`s; the fields' KL variables are
    // independent standard normal, a block of their own (`ProductJoint`).
    let k = file.parameter.len();
    let joint: Arc<dyn JointLaw> = match &file.joint {
        None if d == 0 => Arc::new(NoParameters),
        None => Arc::new(Independent::new(marginals.clone()).map_err(StudyError::from)?),
        Some(j) if j.kind.get_ref() == "independent" => {
            Arc::new(Independent::new(marginals.clone()).map_err(StudyError::from)?)
        }
        Some(j) if k == 0 => {
            return Err(src.error(
                j.kind.span(),
                "joint.type",
                "a dependent [joint] needs [[parameter]]s (the KL variables of [[field]]s are independent)",
            ));
        }
        Some(j) => {
            let law = dependent_joint(src, j, &marginals[..k], &names[..k], &lo[..k], &hi[..k])?;
            if d == k {
                law
            } else {
                let kl = Independent::new(marginals[k..].to_vec()).map_err(StudyError::from)?;
                Arc::new(ProductJoint::new(vec![law, Arc::new(kl)]).map_err(StudyError::from)?)
            }
        }
    };
    let mut units: Vec<String> = file
        .parameter
        .iter()
        .map(|p| p.unit.clone().unwrap_or_default())
        .collect();
    units.resize(names.len(), String::new());
    Ok(ParamSpace {
        units,
        fields,
        names,
        descriptions,
        marginals,
        joint,
        nominal,
        lo,
        hi,
    })
}

/// The dependent joint law of `[joint]` (not `independent`) over the `[[parameter]]`s: their
/// marginals, names and box `[lo, hi]`.
fn dependent_joint(
    src: &Source,
    j: &crate::spec::JointSpec,
    marginals: &[Arc<dyn Marginal>],
    names: &[String],
    lo: &[f64],
    hi: &[f64],
) -> Result<Arc<dyn JointLaw>, StudyError> {
    let d = marginals.len();
    let marginals = marginals.to_vec();
    let (lo, hi) = (lo.to_vec(), hi.to_vec());
    Ok(match j.kind.get_ref().as_str() {
        kind @ ("clayton" | "gumbel" | "frank") => {
            let t = j.theta.as_ref().ok_or_else(|| {
                src.error(
                    j.kind.span(),
                    "joint.theta",
                    format!("a {kind} copula needs theta"),
                )
            })?;
            let theta = *t.get_ref();
            let err = |e: alea_uq::UqError| src.error(t.span(), "joint.theta", e.to_string());
            match kind {
                "clayton" => Arc::new(ClaytonCopula::new(marginals.clone(), theta).map_err(err)?)
                    as Arc<dyn JointLaw>,
                "gumbel" => Arc::new(GumbelCopula::new(marginals.clone(), theta).map_err(err)?),
                _ => Arc::new(FrankCopula::new(marginals.clone(), theta).map_err(err)?),
            }
        }
        "student" => {
            let nu = j
                .nu
                .as_ref()
                .ok_or_else(|| src.error(j.kind.span(), "joint.nu", "a Student copula needs nu"))?;
            let flat = correlation(src, j, d, "a Student copula")?;
            Arc::new(
                StudentCopula::new(marginals.clone(), flat, *nu.get_ref())
                    .map_err(|e| src.error(nu.span(), "joint", e.to_string()))?,
            )
        }
        "gaussian_copula" => {
            let flat = correlation(src, j, d, "a Gaussian copula")?;
            let span = j.correlation.as_ref().map_or(j.kind.span(), |c| c.span());
            Arc::new(
                GaussianCopula::new(marginals.clone(), flat)
                    .map_err(|e| src.error(span, "joint.correlation", e.to_string()))?,
            )
        }
        "density" => {
            let t = j.density.as_ref().ok_or_else(|| {
                src.error(
                    j.kind.span(),
                    "joint.density",
                    "a density joint law needs 'density' (an expression of the parameters)",
                )
            })?;
            let vars: Vec<&str> = names.iter().map(|s| s.as_str()).collect();
            let e = Expr::parse(t.get_ref(), &vars)
                .map_err(|e| src.error(t.span(), "joint.density", e.to_string()))?;
            let n = if d <= 2 {
                256
            } else if d == 3 {
                48
            } else {
                12
            };
            Arc::new(
                BoxDensity::from_fn(lo.clone(), hi.clone(), n, move |x| e.eval(x))
                    .map_err(|e| src.error(t.span(), "joint.density", e.to_string()))?,
            )
        }
        other => {
            return Err(src.error(
                    j.kind.span(),
                    "joint.type",
                    format!("unknown joint law '{other}'; expected independent, gaussian_copula, student, clayton, gumbel, frank or density"),
                ));
        }
    })
}

/// The `[joint] correlation` matrix of `d` parameters, row-major, checked for its shape.
fn correlation(
    src: &Source,
    j: &crate::spec::JointSpec,
    d: usize,
    what: &str,
) -> Result<Vec<f64>, StudyError> {
    let c = j.correlation.as_ref().ok_or_else(|| {
        src.error(
            j.kind.span(),
            "joint.correlation",
            format!("{what} needs a correlation matrix"),
        )
    })?;
    let rows = c.get_ref();
    if rows.len() != d || rows.iter().any(|r| r.len() != d) {
        return Err(src.error(
            c.span(),
            "joint.correlation",
            format!("expected a {d} x {d} matrix (one row per parameter)"),
        ));
    }
    Ok(rows.iter().flatten().copied().collect())
}
