//! A loaded, validated study ([`Study`]): its file, random parameters, model, quantities of
//! interest and methods. The leaf of the study layer: it depends on the input and model
//! modules only (spec, params, build, qoi, method, limits), never on the runner or the
//! services that use it.

mod load_checks;

use std::path::Path;

use alea_latin::LatinSolver;

use crate::StudyError;
use crate::build::{BuiltModel, build_model, input_hash};
use crate::limits::{available_memory, check_total_runs, human_bytes, mean_fields_memory};
use crate::method::{Method, MethodKind, build_methods};
use crate::params::{ParamSpace, build_params};
use crate::points::{PointIndex, canonicalise};
use crate::qoi::{Qoi, build_qois};
use crate::source::Source;
use crate::spec::{ModelFile, OutputSpec};
use crate::store::point_key;
use load_checks::{check_error_estimate_fits, check_study_tables};

/// A loaded, validated study.
pub struct Study {
    /// The study file.
    pub source: Source,
    /// Its parsed content.
    pub file: ModelFile,
    /// Random parameters.
    pub params: ParamSpace,
    /// The mechanical model.
    pub model: BuiltModel,
    /// Quantities of interest.
    pub qois: Vec<Qoi>,
    /// Methods (the first is the study's answer).
    pub methods: Vec<Method>,
    /// Seed of all random draws.
    pub seed: u64,
    /// Hash of the study's inputs (its file's text and its mesh file).
    pub hash: String,
    /// What defines its runs: the run hash and the quantities' keys (a study directory keeps
    /// its runs across edits that leave them unchanged, `crate::run_hash`).
    pub identity: crate::run_hash::RunIdentity,
    /// Outputs.
    pub output: OutputSpec,
    /// Draws written to `samples.csv` (the first ones; `None`: every draw), checked at load
    /// (`crate::output_settings`).
    pub samples_rows: Option<usize>,
    /// The `[[reliability]]` analyses, checked.
    pub reliability: Vec<crate::reliability::task::ReliabilityTask>,
    /// `[budget] refined_mesh`: the same study on the finer mesh (built and checked at load).
    pub refined: Option<Box<Study>>,
    /// `[budget] large_sliding`: the same study with its small-sliding contact interfaces in
    /// large sliding (built and checked at load, `sliding_study`).
    pub large_sliding: Option<Box<Study>>,
    /// `[budget] validation_runs` (`None`: the automatic number; `crate::validation_runs`).
    pub validation_runs: Option<usize>,
    /// `[[step]]`: the load history of every run (module `steps`).
    pub steps: Option<crate::steps::Plan>,
    /// The models of the steps' other sets of imposed displacements (`steps.files[1..]`),
    /// built at load; empty without steps or when the steps change loads only.
    pub step_models: Vec<BuiltModel>,
    /// Their solvers, built (assembled and factorised) on the first run that needs them.
    step_solvers: std::sync::OnceLock<Result<Vec<std::sync::Arc<LatinSolver>>, String>>,
}

impl std::fmt::Debug for Study {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Study")
            .field("file", &self.source.path)
            .finish()
    }
}

impl Study {
    /// Number of values of a run's displacement field (its field data in the store): every substructure's
    /// nodes times the dimension.
    pub fn field_values(&self) -> usize {
        self.model
            .assembly
            .subs
            .iter()
            .map(|s| s.model.mesh.num_nodes() * s.model.mesh.dim)
            .sum()
    }

    /// A parameter point in words for messages: `a = 0.25, b = 1`.
    pub fn describe_point(&self, theta: &[f64]) -> String {
        self.params
            .names
            .iter()
            .zip(theta)
            .map(|(n, v)| format!("{n} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Why a design point reaches where the model is not defined, when it sits at an end of the
    /// parameter box that a law without a bound there put at its 1e-6 tail quantile (grids and
    /// adaptive meshes span the box): names the parameters and the way out.
    fn box_end_hint(&self, theta: &[f64]) -> String {
        let p = &self.params;
        let at_open_end: Vec<String> = theta
            .iter()
            .enumerate()
            .filter(|&(j, &v)| {
                let (a, b) = p.marginals[j].support();
                (v == p.lo[j] && !a.is_finite()) || (v == p.hi[j] && !b.is_finite())
            })
            .map(|(j, &v)| format!("{} = {v} ({})", p.names[j], p.descriptions[j]))
            .collect();
        if at_open_end.is_empty() {
            return String::new();
        }
        format!(
            "; the design spans each parameter's box, which for a law without a bound is its 1e-6 and 1 - 1e-6 quantiles: {} is such an end - a law that keeps the value valid (`truncated_normal` with `lo`, `lognormal`) avoids it",
            at_open_end.join(", ")
        )
    }

    /// Loads and checks a study from its source text.
    pub fn from_source(source: Source) -> Result<Self, StudyError> {
        let file: ModelFile = source.parse()?;
        let params = build_params(&source, &file)?;
        check_study_tables(&source, &file, &params)?;
        let model = build_model(&source, &file, &params)?;
        let mut qois = build_qois(&source, &file.quantity, &model)?;
        let steps = crate::steps::study_steps(&source, &file, &mut qois)?;
        if steps.as_ref().is_some_and(|p| p.cycle.is_some()) {
            // Also for the sliding part of the budget, at the quantity's line of this file.
            let budget = file
                .budget
                .as_ref()
                .and_then(|b| b.get_ref().large_sliding.as_ref())
                .is_some_and(|f| *f.get_ref());
            let (src, a) = (&source, &model.assembly);
            crate::cycle::check_large_sliding_fretting(src, &file, &qois, a, budget)?;
        }
        let step_models = match &steps {
            Some(plan) => plan.files[1..]
                .iter()
                .map(|f| build_model(&source, f, &params))
                .collect::<Result<Vec<_>, _>>()?,
            None => Vec::new(),
        };
        let seed = file.study.seed.unwrap_or(1);
        let mut methods = if params.names.is_empty() {
            vec![Method::deterministic()]
        } else {
            let names: Vec<String> = qois.iter().map(|q| q.name.clone()).collect();
            build_methods(&source, &file.method, &params, &names, seed)?
        };
        // Points that differ by round-off only are one run (module `points`).
        let mut index = PointIndex::new(&params.lo, &params.hi);
        canonicalise(&mut index, methods.iter_mut().map(|m| &mut m.points));
        add_goal_thresholds(&methods, &mut qois);
        let reliability = crate::reliability::task::build_reliability(
            &source,
            &file.reliability,
            &qois,
            &methods,
            &params,
        )?;
        let refined = refined_budget_study(&source, &file, &params)?;
        let large_sliding = match &file.budget {
            Some(b) => sliding_study(&source, b)?.map(Box::new),
            None => None,
        };
        let validation_runs = validation_runs_setting(&source, &file)?;
        let hash = input_hash(&source, &file)?;
        let identity = crate::run_hash::run_identity(&source, &file)?;
        let output = file.output.clone();
        let samples_rows = crate::output_settings::samples_rows(&source, &output)?;
        let study = Study {
            source,
            file,
            params,
            model,
            qois,
            methods,
            seed,
            hash,
            identity,
            output,
            samples_rows,
            reliability,
            refined,
            large_sliding,
            validation_runs,
            steps,
            step_models,
            step_solvers: std::sync::OnceLock::new(),
        };
        check_error_estimate_fits(&study)?;
        check_cell_fields(&study)?;
        check_built(&study)?;
        // The runs the solver's set-up serves: what the condensed linear stage's set-up is
        // weighed against (`[solver] linear_stage = "auto"`).
        let mut study = study;
        study.model.options.expected_runs = study.all_points().len().max(1);
        Ok(study)
    }

    /// The solvers of [`Study::step_models`] (the steps' other sets of imposed displacements),
    /// built on first use and then shared by every run.
    ///
    /// # Errors
    /// A solver that cannot be built (as the study's own solver would fail).
    pub fn step_solvers(&self) -> Result<&[std::sync::Arc<LatinSolver>], StudyError> {
        let built = self.step_solvers.get_or_init(|| {
            self.step_models
                .iter()
                .map(|m| {
                    m.solver()
                        .map(std::sync::Arc::new)
                        .map_err(|e| e.to_string())
                })
                .collect()
        });
        built.as_deref().map_err(|e| {
            StudyError::Failed(format!("the solver of a step's imposed displacements: {e}"))
        })
    }

    /// Loads a study file.
    pub fn load(path: &Path) -> Result<Self, StudyError> {
        Self::from_source(Source::read(path)?)
    }

    /// The study file's name as written in the outputs (`summary.json`, the report): its file
    /// name only, so that `alea run` (path as given) and `alea report` (the path kept in the
    /// store, absolute) write the same outputs, and no output depends on where the study was.
    pub fn file_name(&self) -> String {
        self.source.path.file_name().map_or_else(
            || self.source.path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    }

    /// The title (from `[study]`, else the file name).
    pub fn title(&self) -> String {
        self.file.study.title.clone().unwrap_or_else(|| {
            self.source
                .path
                .file_stem()
                .map_or("study".into(), |s| s.to_string_lossy().into_owned())
        })
    }

    /// Every distinct design point, in method order.
    pub fn all_points(&self) -> Vec<Vec<f64>> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for m in &self.methods {
            for p in &m.points {
                if seen.insert(point_key(p)) {
                    out.push(p.clone());
                }
            }
        }
        out
    }

    /// A point scaled to the unit cube of the parameter box.
    pub fn normalise(&self, p: &[f64]) -> Vec<f64> {
        p.iter()
            .enumerate()
            .map(|(j, v)| (v - self.params.lo[j]) / (self.params.hi[j] - self.params.lo[j]))
            .collect()
    }

    /// Checks the parameter-dependent model data at a design point (Young's moduli > 0, finite
    /// load factors, mu >= 0 and finite gaps at every interface point): errors name the field.
    pub(crate) fn check_point(
        &self,
        solver: &LatinSolver,
        theta: &[f64],
    ) -> Result<(), StudyError> {
        let src = &self.source;
        let at = || self.describe_point(theta);
        let par = &self.model.parametric;
        for s in 0..par.young.len() {
            // The modulus itself (a factor of a positive reference), or on every cell when it
            // varies from cell to cell.
            let (factor, cells) = par.young_at(s, theta);
            let bad = std::iter::once((None, factor))
                .chain(
                    cells
                        .iter()
                        .flat_map(|f| f.iter().copied().enumerate().map(|(c, v)| (Some(c), v))),
                )
                .find(|(_, v)| !(v.is_finite() && *v > 0.0));
            if let Some((cell, v)) = bad {
                let sp = &self.file.substructure[s].young;
                let place = cell.map_or_else(String::new, |c| format!(" on cell {c}"));
                return Err(src.error(
                    sp.span(),
                    format!("substructure[{s}].young"),
                    format!(
                        "evaluates to {}{place} at {}; must be > 0{}",
                        v * par.young_nominal[s],
                        at(),
                        self.box_end_hint(theta)
                    ),
                ));
            }
        }
        for (s, fs) in par.load_factors.iter().enumerate() {
            for (j, e) in fs.iter().enumerate() {
                let v = e.eval(theta);
                if !v.is_finite() {
                    let sp = self.file.substructure[s].load[j]
                        .factor
                        .as_ref()
                        .map_or(0..0, |f| f.span());
                    return Err(src.error(
                        sp,
                        format!("substructure[{s}].load[{j}].factor"),
                        format!("evaluates to {v} at {}", at()),
                    ));
                }
            }
        }
        let input = par.run_input(theta);
        for i in 0..solver.num_interfaces() {
            for p in solver.interface_points(i) {
                let mu = input.mu[i].as_ref().map_or(p.mu, |f| f(p.x));
                let gap = input.gap[i].as_ref().map_or(p.gap, |f| f(p.x));
                let spec = &self.file.interface[i];
                if !(mu.is_finite() && mu >= 0.0) {
                    let sp = spec.mu.as_ref().map_or(spec.name.span(), |m| m.span());
                    return Err(src.error(sp, format!("interface[{i}].mu"), format!(
                        "friction coefficient {mu} at ({:.4}, {:.4}, {:.4}) for {}; must be finite and >= 0",
                        p.x[0], p.x[1], p.x[2], at()
                    )));
                }
                if !gap.is_finite() {
                    let sp = spec.gap.as_ref().map_or(spec.name.span(), |m| m.span());
                    return Err(src.error(
                        sp,
                        format!("interface[{i}].gap"),
                        format!(
                            "gap {gap} at ({:.4}, {:.4}, {:.4}) for {}",
                            p.x[0],
                            p.x[1],
                            p.x[2],
                            at()
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// A field over a substructure's cells (a Young's modulus varying from cell to cell) is
/// refused where what needs the study cannot follow it: the error estimate (`[error]`,
/// adaptive methods: the stochastic CRE takes one Young's factor per substructure and run)
/// and `[budget] refined_mesh` (the field's KL on the finer mesh would be another field).
fn check_cell_fields(study: &Study) -> Result<(), StudyError> {
    let Some((i, _)) = study
        .params
        .fields
        .iter()
        .enumerate()
        .find(|(_, f)| matches!(f.domain, crate::random_field::FieldDomain::Substructure(_)))
    else {
        return Ok(());
    };
    let spec = &study.file.field[i];
    let span = spec
        .substructure
        .as_ref()
        .map_or(spec.name.span(), |s| s.span());
    let field = format!("field[{i}].substructure");
    if estimates_error(study) {
        return Err(study.source.error(
            span,
            field,
            "a field over a substructure's cells makes the Young's modulus vary from cell to cell, which the error estimate ([error], adaptive methods) does not handle (one Young's factor per substructure and run): leave out [error] and adaptive methods",
        ));
    }
    if study.refined.is_some() {
        return Err(study.source.error(
            span,
            field,
            "a field over a substructure's cells is discretised on that substructure's mesh, so [budget] refined_mesh would compare another field: leave out refined_mesh",
        ));
    }
    Ok(())
}

/// True if the study estimates its error: an `[error]` table (not disabled) or an adaptive
/// method.
pub fn estimates_error(study: &Study) -> bool {
    study
        .file
        .error
        .as_ref()
        .is_some_and(|e| e.enabled.unwrap_or(true))
        || study
            .methods
            .iter()
            .any(|m| matches!(m.kind, MethodKind::Adaptive(_)))
}

/// Checks the sizes of a built study: distinct runs, and the memory of the mean / std fields.
///
/// # Errors
/// [`StudyError::TooLarge`] with the estimate.
pub fn check_built(study: &Study) -> Result<(), StudyError> {
    check_total_runs(study.all_points().len())?;
    if let Some(m) = &study.file.solver.linear_stage
        && m.get_ref() == "condensed"
    {
        crate::limits::check_condensed(&study.source, m.span(), &study.model.assembly)?;
    }
    if study.output.mean_fields.unwrap_or(true)
        && let Some(m) = study
            .methods
            .iter()
            .find(|m| m.kind != MethodKind::MonteCarlo)
    {
        let support = weight_support(&m.kind, m.points.len(), study.params.names.len());
        let need = mean_fields_memory(m.points.len(), support);
        let have = available_memory() as f64 / 2.0;
        if need > have {
            return Err(StudyError::TooLarge(format!(
                "the mean / std fields of method '{}' on {} runs would need about {} of memory ({} usable); \
                 set mean_fields = false in [output]",
                m.label,
                m.points.len(),
                human_bytes(need),
                human_bytes(have)
            )));
        }
    }
    Ok(())
}

/// Runs at most non-zero together at one draw in a surrogate of `kind` on `runs` runs in `d`
/// parameters: `2^d` for piecewise multilinear interpolation on a grid, `4^d` for an adaptive
/// stochastic mesh (an estimate made before its mesh exists: a corner that is a hanging node
/// is interpolated from the corners of a coarser neighbour's face), `runs` for the global
/// surrogates.
fn weight_support(kind: &MethodKind, runs: usize, d: usize) -> usize {
    let local = |base: usize| base.checked_pow(d as u32).unwrap_or(usize::MAX).min(runs);
    match kind {
        MethodKind::PiecewiseLinear { .. } => local(2),
        MethodKind::Adaptive(_) => local(4),
        _ => runs,
    }
}

/// The study of `source` with `[mesh]` patched by `[budget] refined_mesh` (and no `[budget]`).
///
/// # Errors
/// [`StudyError::Input`] at `budget.refined_mesh` when the patched study does not build.
fn refined_study(
    source: &Source,
    refined_mesh: &toml::Spanned<toml::Table>,
) -> Result<Study, StudyError> {
    let span = refined_mesh.span();
    let field = "budget.refined_mesh";
    let fail = |why: String| source.error(span.clone(), field, why);
    let mut doc: toml::Table = toml::from_str(&source.text).map_err(|e| fail(e.to_string()))?;
    doc.remove("budget");
    let mesh = doc
        .get_mut("mesh")
        .and_then(|m| m.as_table_mut())
        .ok_or_else(|| fail("the study has no [mesh] table to refine".into()))?;
    for (key, value) in refined_mesh.get_ref() {
        match (key.as_str(), value, mesh.get_mut(key)) {
            ("params", toml::Value::Table(new), Some(toml::Value::Table(old))) => {
                for (k, v) in new {
                    old.insert(k.clone(), v.clone());
                }
            }
            _ => {
                mesh.insert(key.clone(), value.clone());
            }
        }
    }
    let text = toml::to_string(&doc).map_err(|e| fail(e.to_string()))?;
    let refined = Source {
        path: source.path.clone(),
        text,
    };
    Study::from_source(refined).map_err(|e| fail(format!("the refined study does not build: {e}")))
}

/// The sliding part of the error budget: what small sliding, the pairing of the initial
/// configuration kept throughout, changes in each statistic. With `[budget] large_sliding =
/// true` the study is also built with every small-sliding contact interface in large sliding
/// (`alea_latin::large_sliding`: the pairing and its normals re-found in the deformed
/// configuration of each run, the bodies still linear) and both are solved at the `2 d + 3`
/// design points of the mesh part (`crate::budget::paired::design_points`: the nominal point,
/// along each parameter its 5 % and 95 % quantiles, and the two diagonal points); with
/// `delta_i = q_small(xi_i) - q_large(xi_i)`,
///
/// ```text
/// D = max_i |delta_i|,   S = max_i delta_i - min_i delta_i,
/// ```
///
/// and the part is `D` for the mean and the quantiles, `max(S / 2, r sigma)` for the standard
/// deviation (`r = max_i |delta_i / q_small(xi_i)|`, `sigma` the draws' standard deviation: the
/// change grows with the displacements, so it is often nearly proportional to the quantity, and
/// then changes the spread by about `r sigma`, which `S / 2` over a few points misses) and
/// for `P(q > t)` the share of draws within their own shift of `t` under the model of the
/// differences (the propagation of the mesh part,
/// `crate::budget::paired::apply`, without Richardson's factor: the difference is the change
/// itself, not one term of a converging sequence).
///
/// What it measures: the first-order effect of the deformed geometry on the contact (where the
/// points meet, and the normals' turn), which small sliding leaves out and which grows with
/// the displacements. It is the change toward the large-sliding model, not the error against a
/// large-deformation analysis (the bodies stay linear in both). Measured on the simple blade
/// root (`examples/blade-root-simple.toml`, header): T changes by +20 to +75 % between the two
/// models, both mesh-converged.
///
/// The study of `source` with every small-sliding contact interface in large sliding, without
/// `[budget]`, `[error]`, `[[reliability]]` and with a two-run Monte Carlo as its method (the
/// paired solves use its model only; the error estimate and adaptive methods refuse large
/// sliding). `None` without `large_sliding = true`.
///
/// # Errors
/// [`StudyError::Input`] at `budget` when it asks for no part, and at `budget.large_sliding`
/// when the study has no small-sliding contact interface or the patched study does not build.
fn sliding_study(
    source: &Source,
    budget: &toml::Spanned<crate::spec::BudgetSpec>,
) -> Result<Option<Study>, StudyError> {
    let spec = budget.get_ref();
    let sliding = spec.large_sliding.as_ref().is_some_and(|f| *f.get_ref());
    if spec.refined_mesh.is_none() && !sliding && spec.validation_runs.is_none() {
        return Err(source.error(
            budget.span(),
            "budget",
            "[budget] asks for no part: give refined_mesh (the mesh part), large_sliding = true (the sliding part) and / or validation_runs (the validation runs)",
        ));
    }
    let Some(flag) = spec.large_sliding.as_ref().filter(|f| *f.get_ref()) else {
        return Ok(None);
    };
    let field = "budget.large_sliding";
    let fail = |why: String| source.error(flag.span(), field, why);
    let mut doc: toml::Table = toml::from_str(&source.text).map_err(|e| fail(e.to_string()))?;
    for key in ["budget", "error", "reliability"] {
        doc.remove(key);
    }
    let mut patched = 0;
    if let Some(toml::Value::Array(interfaces)) = doc.get_mut("interface") {
        for it in interfaces.iter_mut().filter_map(toml::Value::as_table_mut) {
            let contact = it.get("law").and_then(toml::Value::as_str) == Some("coulomb");
            let small = it
                .get("sliding")
                .and_then(toml::Value::as_str)
                .is_none_or(|s| s == "small");
            if contact && small {
                it.insert("sliding".into(), toml::Value::String("large".into()));
                patched += 1;
            }
        }
    }
    if patched == 0 {
        return Err(fail(
            "the study has no contact interface in small sliding (law = \"coulomb\" without sliding = \"large\"): there is no sliding part to estimate; leave out large_sliding".into(),
        ));
    }
    let mut method = toml::Table::new();
    method.insert("type".into(), toml::Value::String("monte_carlo".into()));
    method.insert("runs".into(), toml::Value::Integer(2));
    method.insert("label".into(), toml::Value::String("large sliding".into()));
    doc.insert(
        "method".into(),
        toml::Value::Array(vec![toml::Value::Table(method)]),
    );
    let text = toml::to_string(&doc).map_err(|e| fail(e.to_string()))?;
    let study = Study::from_source(Source {
        path: source.path.clone(),
        text,
    })
    .map_err(|e| fail(format!("the large-sliding study does not build: {e}")))?;
    Ok(Some(study))
}

/// `[budget] validation_runs`, checked: at most [`crate::limits::MAX_VALIDATION_RUNS`] (each is
/// a run of the solver), and none asked of a study without random parameters.
fn validation_runs_setting(
    source: &Source,
    file: &crate::spec::ModelFile,
) -> Result<Option<usize>, StudyError> {
    let Some(v) = file
        .budget
        .as_ref()
        .and_then(|b| b.get_ref().validation_runs.as_ref())
    else {
        return Ok(None);
    };
    let n = *v.get_ref();
    let most = crate::limits::MAX_VALIDATION_RUNS;
    if n > most {
        return Err(source.error(
            v.span(),
            "budget.validation_runs",
            format!("must be at most {most} (each is a run of the solver), got {n}"),
        ));
    }
    if n == 1 {
        return Err(source.error(
            v.span(),
            "budget.validation_runs",
            "must be 0 (none) or at least 2: one run gives no interval",
        ));
    }
    if n > 0 && file.parameter.is_empty() && file.field.is_empty() {
        return Err(source.error(
            v.span(),
            "budget.validation_runs",
            "the study has no random parameter: there is no surrogate to validate",
        ));
    }
    Ok(Some(n))
}

/// Adds the threshold of every adaptive method's goal `P(q > t)` to its quantity's thresholds:
/// it is reported with its budget like the quantity's own.
fn add_goal_thresholds(methods: &[Method], qois: &mut [Qoi]) {
    for m in methods {
        if let MethodKind::Adaptive(a) = &m.kind
            && let Some(g) = &a.goal
            && let Some(t) = g.threshold
            && !qois[g.quantity].thresholds.contains(&t)
        {
            qois[g.quantity].thresholds.push(t);
        }
    }
}

/// The `[budget] refined_mesh` study, built and checked (the same parameters as the study's).
fn refined_budget_study(
    source: &Source,
    file: &ModelFile,
    params: &ParamSpace,
) -> Result<Option<Box<Study>>, StudyError> {
    let Some(mesh) = file
        .budget
        .as_ref()
        .and_then(|b| b.get_ref().refined_mesh.as_ref())
    else {
        return Ok(None);
    };
    let r = refined_study(source, mesh)?;
    // A field truncated by variance fraction may keep another number of modes on the finer
    // mesh: the paired solves need the same parameters.
    if r.params.names != params.names {
        return Err(source.error(
            mesh.span(),
            "budget.refined_mesh",
            format!(
                "the refined study's parameters ({}) differ from the study's ({}): a [[field]] keeps another number of KL modes on the finer mesh; give its `modes`",
                r.params.names.join(", "),
                params.names.join(", ")
            ),
        ));
    }
    Ok(Some(Box::new(r)))
}
