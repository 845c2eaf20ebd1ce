//! Substructure models with their constraints and load cases, and LATIN options of a model
//! file, assembled with its interfaces (`interfaces.rs`) into the built model.

use alea_fem::{Analysis, Constraints, Loads, Material, Model};
use alea_latin::{
    Assembly, FactorPrecision, LatinOptions, LinearStage, SearchDirection, Subdomains, Substructure,
};
use alea_mesh::Mesh;

use super::checks::check_interfaces;
use super::interfaces::build_interfaces;
use super::mesh::build_mesh;
use super::parametric::{BuiltModel, Parametric};
use super::values::{choice, compile, field_place, finite, positive, vec3};
use crate::expr::Expr;
use crate::params::ParamSpace;
use crate::random_field::FieldDomain;
use crate::spec::{LoadSpec, ModelFile, SubstructureSpec};
use crate::{Source, StudyError};

/// The force vector of load `l` on `model` (exactly one kind of load; `field` names it in
/// errors).
fn build_load(
    src: &Source,
    model: &Model,
    l: &LoadSpec,
    field: &str,
) -> Result<Vec<f64>, StudyError> {
    let dim = model.mesh.dim;
    let kinds = [
        l.pressure.is_some(),
        l.traction.is_some(),
        l.force.is_some(),
        l.body.is_some(),
        l.centrifugal.is_some(),
    ];
    let span = l.span();
    if kinds.iter().filter(|&&k| k).count() != 1 {
        return Err(src.error(
            span,
            field,
            "expected exactly one of pressure, traction, force, body, centrifugal",
        ));
    }
    let group = l.group.as_ref().map(|g| g.get_ref().as_str());
    let need_group = || {
        group.ok_or_else(|| {
            src.error(
                span.clone(),
                format!("{field}.group"),
                "missing; this load needs a group",
            )
        })
    };
    let fem = |e: alea_fem::FemError| {
        src.error(
            l.group.as_ref().map_or(0..0, |g| g.span()),
            format!("{field}.group"),
            e.to_string(),
        )
    };
    let mut loads = Loads::new(model);
    if let Some(p) = &l.pressure {
        let p = finite(src, p, &format!("{field}.pressure"))?;
        loads.pressure(model, need_group()?, p).map_err(fem)?;
    } else if let Some(t) = &l.traction {
        let t = vec3(src, t, dim, &format!("{field}.traction"))?;
        loads
            .traction(model, need_group()?, move |_, _| t)
            .map_err(fem)?;
    } else if let Some(f) = &l.force {
        let f = vec3(src, f, dim, &format!("{field}.force"))?;
        loads.nodal_force(model, need_group()?, f).map_err(fem)?;
    } else if let Some(b) = &l.body {
        let b = vec3(src, b, dim, &format!("{field}.body"))?;
        loads.body_force(model, group, move |_, _| b).map_err(fem)?;
    } else if let Some(c) = &l.centrifugal {
        let cs = c.get_ref();
        let omega = finite(src, &cs.omega, &format!("{field}.centrifugal.omega"))?;
        let center = cs.center.clone().unwrap_or_default();
        let axis = cs.axis.clone().unwrap_or_else(|| vec![0.0, 0.0, 1.0]);
        if center.len() > 3 || axis.len() != 3 {
            return Err(src.error(
                c.span(),
                format!("{field}.centrifugal"),
                "center has at most 3 and axis exactly 3 components",
            ));
        }
        let mut p = [0.0; 3];
        p[..center.len()].copy_from_slice(&center);
        loads
            .centrifugal(model, group, omega, p, [axis[0], axis[1], axis[2]])
            .map_err(fem)?;
    }
    Ok(loads.f)
}

/// The names of the variables of a model file's expressions, in slot order.
struct ModelVars<'a> {
    /// The parameters (load factors).
    params: Vec<&'a str>,
    /// `young`'s: the parameters, then every field (only those over the substructure's own
    /// cells may be used).
    young: Vec<&'a str>,
    /// The interface profiles' (`mu`, `gap`): the parameters, `x, y, z`, the defines, then
    /// every field.
    profile: Vec<&'a str>,
}

/// What the substructures of a model file build: the substructures and, per substructure, how
/// the parameters enter it.
struct BuiltSubstructures {
    subs: Vec<Substructure>,
    /// Their names, in order.
    names: Vec<String>,
    /// The names of each one's load cases.
    load_names: Vec<Vec<String>>,
    /// Each one's Young's modulus expression.
    young: Vec<Expr>,
    /// The fields each one's `young` uses.
    young_fields: Vec<Vec<usize>>,
    /// Each one's modulus at the nominal point.
    young_nominal: Vec<f64>,
    /// The factor of each load case of each one.
    load_factors: Vec<Vec<Expr>>,
}

/// Builds meshes, models, constraints, loads and interfaces of a model file; parameters enter
/// through `params` (the model is set up at their nominal point).
pub fn build_model(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
) -> Result<BuiltModel, StudyError> {
    let (vars, defines) = model_vars(src, file, params)?;
    let mesh = build_mesh(src, &file.mesh, crate::limits::factor_layout(&file.solver))?;
    let analysis = analysis_of(src, file, mesh.dim)?;
    if file.substructure.is_empty() {
        return Err(src.error(
            0..0,
            "substructure",
            "at least one [[substructure]] is needed",
        ));
    }
    let built_subs = build_substructures(src, file, params, &vars, &mesh, analysis)?;
    let mut parametric = Parametric {
        nparams: params.names.len(),
        young: built_subs.young,
        young_nominal: built_subs.young_nominal,
        young_fields: built_subs.young_fields,
        load_factors: built_subs.load_factors,
        mu: Vec::new(),
        gap: Vec::new(),
        defines,
        fields: params.fields.clone(),
    };
    let subs = built_subs.subs;
    let names = built_subs.names;
    let (interfaces, interface_sites) = build_interfaces(
        src,
        file,
        params,
        &vars.profile,
        &names,
        &subs,
        &mut parametric,
    )?;
    let sv = &file.solver;
    let options = latin_options(src, sv)?;
    let assembly = Assembly { subs, interfaces };
    let repairing = repairing_settings(src, sv, &assembly)?;
    let built = BuiltModel {
        mesh,
        assembly,
        load_names: built_subs.load_names,
        options,
        repairing,
        units: file.units.clone(),
        parametric,
        interface_sites,
    };
    check_interfaces(src, &file.interface, &built)?;
    Ok(built)
}

/// The variables of the model's expressions and the compiled `[[define]]`s (each a new name,
/// an expression of the parameters, `x, y, z` and the defines before it).
fn model_vars<'a>(
    src: &Source,
    file: &'a ModelFile,
    params: &'a ParamSpace,
) -> Result<(ModelVars<'a>, Vec<Expr>), StudyError> {
    let pvars: Vec<&str> = params.names.iter().map(|s| s.as_str()).collect();
    let mut profile_vars: Vec<&str> = pvars.clone();
    profile_vars.extend(["x", "y", "z"]);
    let mut defines = Vec::new();
    for (i, d) in file.define.iter().enumerate() {
        let e = Expr::parse(d.value.get_ref(), &profile_vars)
            .map_err(|e| src.error(d.value.span(), format!("define[{i}].value"), e.to_string()))?;
        let name = d.name.get_ref().as_str();
        if profile_vars.contains(&name)
            || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        {
            return Err(src.error(
                d.name.span(),
                format!("define[{i}].name"),
                format!("'{name}' is not a new usable name"),
            ));
        }
        profile_vars.push(name);
        defines.push(e);
    }
    profile_vars.extend(params.fields.iter().map(|f| f.name.as_str()));
    let mut young_vars: Vec<&str> = pvars.clone();
    young_vars.extend(params.fields.iter().map(|f| f.name.as_str()));
    let vars = ModelVars {
        params: pvars,
        young: young_vars,
        profile: profile_vars,
    };
    Ok((vars, defines))
}

/// The `[analysis]` of the model file (type and thickness), which must fit the mesh's
/// dimension `dim`.
fn analysis_of(src: &Source, file: &ModelFile, dim: usize) -> Result<Analysis, StudyError> {
    let th = file
        .analysis
        .thickness
        .as_ref()
        .map(|t| positive(src, t, "analysis.thickness"))
        .transpose()?
        .unwrap_or(1.0);
    let analysis = match file.analysis.kind.get_ref().as_str() {
        "plane_strain" => Analysis::PlaneStrain { thickness: th },
        "plane_stress" => Analysis::PlaneStress { thickness: th },
        "solid" => Analysis::Solid,
        other => {
            return Err(src.error(
                file.analysis.kind.span(),
                "analysis.type",
                format!("unknown analysis '{other}'; expected plane_strain, plane_stress or solid"),
            ));
        }
    };
    if analysis.dim() != dim {
        return Err(src.error(
            file.analysis.kind.span(),
            "analysis.type",
            format!(
                "a {}D analysis does not fit the {}D mesh",
                analysis.dim(),
                dim
            ),
        ));
    }
    Ok(analysis)
}

/// Builds every `[[substructure]]` (distinct names, modulus, material, cells, constraints and
/// load cases) at the nominal point.
fn build_substructures(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
    vars: &ModelVars,
    mesh: &Mesh,
    analysis: Analysis,
) -> Result<BuiltSubstructures, StudyError> {
    let mut out = BuiltSubstructures {
        subs: Vec::new(),
        names: Vec::new(),
        load_names: Vec::new(),
        young: Vec::new(),
        young_fields: Vec::new(),
        young_nominal: Vec::new(),
        load_factors: Vec::new(),
    };
    for (i, s) in file.substructure.iter().enumerate() {
        let f = |k: &str| format!("substructure[{i}].{k}");
        let name = s.name.get_ref().clone();
        if out.names.contains(&name) {
            return Err(src.error(
                s.name.span(),
                f("name"),
                format!("duplicate substructure name '{name}'"),
            ));
        }
        out.names.push(name.clone());
        let (ye, used) = young_expression(src, file, params, vars, i, s, &name)?;
        let young = ye.eval(&nominal_with_fields(params));
        out.young.push(ye);
        out.young_fields.push(used);
        out.young_nominal.push(young);
        let material = material_of(src, i, s, young)?;
        let sub_mesh = match &s.cells {
            Some(c) => {
                mesh.extract(&[c.get_ref().as_str()])
                    .map_err(|e| src.error(c.span(), f("cells"), e.to_string()))?
                    .0
            }
            None => mesh.clone(),
        };
        let mut model = Model::new(sub_mesh, analysis)
            .map_err(|e| src.error(s.name.span(), f("name"), e.to_string()))?;
        model.set_material_all(material);
        let cons = constraints_of(src, i, s, &model)?;
        let (cases, lnames, factors) = load_cases_of(src, i, s, &model, &vars.params)?;
        out.load_factors.push(factors);
        out.subs.push(Substructure {
            name,
            model,
            constraints: cons,
            load_cases: cases,
        });
        out.load_names.push(lnames);
    }
    Ok(out)
}

/// Substructure `i`'s compiled `young` and the fields it uses (each must live over that
/// substructure's cells).
fn young_expression(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
    vars: &ModelVars,
    i: usize,
    s: &SubstructureSpec,
    name: &str,
) -> Result<(Expr, Vec<usize>), StudyError> {
    let f = |k: &str| format!("substructure[{i}].{k}");
    let ye = compile(src, &s.young, &vars.young, &f("young"))?;
    let mut used = Vec::new();
    for (j, fld) in params.fields.iter().enumerate() {
        if !ye.uses(vars.params.len() + j) {
            continue;
        }
        if fld.domain != FieldDomain::Substructure(i) {
            let place = field_place(file, fld.domain);
            return Err(src.error(
                s.young.span(),
                f("young"),
                format!(
                    "field '{}' lives {place}, not over the cells of '{name}'",
                    fld.name
                ),
            ));
        }
        used.push(j);
    }
    Ok((ye, used))
}

/// The reference point of the modulus: the parameters' nominal values, each field at its
/// nominal value (all KL variables 0: the transform of the Gaussian mean, the same at every
/// node).
fn nominal_with_fields(params: &ParamSpace) -> Vec<f64> {
    let mut nominal = params.nominal.clone();
    for fld in params.fields.iter() {
        nominal.push(
            fld.at_nodes(&params.nominal)
                .first()
                .copied()
                .unwrap_or(0.0),
        );
    }
    nominal
}

/// Substructure `i`'s material with modulus `young` (the error points at the value at fault).
fn material_of(
    src: &Source,
    i: usize,
    s: &SubstructureSpec,
    young: f64,
) -> Result<Material, StudyError> {
    let f = |k: &str| format!("substructure[{i}].{k}");
    let poisson = *s.poisson.get_ref();
    let density = s.density.as_ref().map_or(0.0, |d| *d.get_ref());
    Material::new(young, poisson, density).map_err(|e| {
        let (span, field) = if !(young.is_finite() && young > 0.0) {
            (s.young.span(), f("young"))
        } else if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
            (s.poisson.span(), f("poisson"))
        } else {
            (
                s.density.as_ref().map_or(s.name.span(), |d| d.span()),
                f("density"),
            )
        };
        src.error(span, field, e.to_string())
    })
}

/// Substructure `i`'s constraints on `model` (each imposes a component or the normal).
fn constraints_of(
    src: &Source,
    i: usize,
    s: &SubstructureSpec,
    model: &Model,
) -> Result<Constraints, StudyError> {
    let mut cons = Constraints::new();
    for (j, c) in s.constraint.iter().enumerate() {
        let cf = |k: &str| format!("substructure[{i}].constraint[{j}].{k}");
        let g = c.group.get_ref().as_str();
        let ge = |e: alea_fem::FemError| src.error(c.group.span(), cf("group"), e.to_string());
        let mut any = false;
        for (comp, v) in [&c.x, &c.y, &c.z].into_iter().enumerate() {
            if let Some(v) = v {
                let val = finite(src, v, &cf(["x", "y", "z"][comp]))?;
                if comp >= model.mesh.dim {
                    return Err(src.error(v.span(), cf("z"), "no z component in a 2D model"));
                }
                cons.fix_component(&model.mesh, g, comp, val).map_err(ge)?;
                any = true;
            }
        }
        if let Some(v) = &c.normal {
            let val = finite(src, v, &cf("normal"))?;
            cons.fix_normal(&model.mesh, g, val).map_err(ge)?;
            any = true;
        }
        if !any {
            return Err(src.error(
                c.group.span(),
                cf("group"),
                "constraint imposes nothing; give x, y, z and/or normal",
            ));
        }
    }
    Ok(cons)
}

/// The load cases of substructure `i` on `model`: force vectors, names and factors
/// (expressions of the parameters `pvars`).
#[allow(clippy::type_complexity)]
fn load_cases_of(
    src: &Source,
    i: usize,
    s: &SubstructureSpec,
    model: &Model,
    pvars: &[&str],
) -> Result<(Vec<Vec<f64>>, Vec<String>, Vec<Expr>), StudyError> {
    let mut cases = Vec::new();
    let mut lnames = Vec::new();
    let mut factors = Vec::new();
    for (j, l) in s.load.iter().enumerate() {
        let field = format!("substructure[{i}].load[{j}]");
        cases.push(build_load(src, model, l, &field)?);
        lnames.push(
            l.name
                .as_ref()
                .map_or(String::new(), |n| n.get_ref().clone()),
        );
        factors.push(match &l.factor {
            Some(fe) => compile(src, fe, pvars, &format!("{field}.factor"))?,
            None => Expr::constant(1.0),
        });
    }
    Ok((cases, lnames, factors))
}

/// The LATIN options of the `[solver]` table (the defaults where a key is absent).
fn latin_options(src: &Source, sv: &crate::spec::SolverSpec) -> Result<LatinOptions, StudyError> {
    let mut options = LatinOptions::default();
    if let Some(t) = &sv.tolerance {
        options.tolerance = positive(src, t, "solver.tolerance")?;
    }
    if let Some(m) = &sv.max_iterations {
        options.max_iterations = *m.get_ref();
    }
    if let Some(r) = &sv.relaxation {
        let v = *r.get_ref();
        if !(v > 0.0 && v <= 1.0) {
            return Err(src.error(
                r.span(),
                "solver.relaxation",
                format!("must be in (0, 1], got {v}"),
            ));
        }
        options.relaxation = v;
    }
    if let Some(a) = &sv.acceleration {
        options.acceleration = Some(*a.get_ref());
    }
    if let Some(c) = &sv.coarse {
        options.coarse = *c.get_ref();
    }
    if let Some(t) = &sv.equilibrium_tolerance {
        options.equilibrium_tolerance = positive(src, t, "solver.equilibrium_tolerance")?;
    }
    if let Some(t) = &sv.max_rigid_motion {
        options.max_rigid_motion = positive(src, t, "solver.max_rigid_motion")?;
    }
    if let Some(m) = &sv.linear_stage {
        options.linear_stage = choice(
            src,
            m,
            "solver.linear_stage",
            &[
                ("auto", LinearStage::Auto),
                ("condensed", LinearStage::Condensed),
                ("volume", LinearStage::Volume),
            ],
        )?;
    }
    subdomain_options(src, sv, &mut options)?;
    if let Some(m) = &sv.factor_precision {
        options.factor_precision = choice(
            src,
            m,
            "solver.factor_precision",
            &[
                ("auto", FactorPrecision::Auto),
                ("double", FactorPrecision::Double),
                ("single", FactorPrecision::Single),
            ],
        )?;
    }
    if let Some(k) = &sv.search_direction_factor {
        options.search_direction = SearchDirection::Auto {
            factor: positive(src, k, "solver.search_direction_factor")?,
        };
    }
    if let Some(t) = &sv.search_direction_tangential {
        let tangential = positive(src, t, "solver.search_direction_tangential")?;
        if tangential != 1.0 {
            let factor = match options.search_direction {
                SearchDirection::Auto { factor } | SearchDirection::Split { factor, .. } => factor,
                SearchDirection::Fixed(_) => 3.0,
            };
            options.search_direction = SearchDirection::Split { factor, tangential };
        }
    }
    Ok(options)
}

/// The `[solver]` settings of automatic subdomains (`alea_latin::split`): `subdomains` one of
/// `"auto"`, `"always"`, `"never"`; `subdomain_dofs` at least [`MIN_SUBDOMAIN_DOFS`], and
/// refused with `"never"` (it would have no effect).
fn subdomain_options(
    src: &Source,
    sv: &crate::spec::SolverSpec,
    options: &mut LatinOptions,
) -> Result<(), StudyError> {
    if let Some(m) = &sv.subdomains {
        options.subdomains = choice(
            src,
            m,
            "solver.subdomains",
            &[
                ("auto", Subdomains::Auto),
                ("always", Subdomains::Always),
                ("never", Subdomains::Never),
            ],
        )?;
    }
    if let Some(d) = &sv.subdomain_dofs {
        let v = *d.get_ref();
        if v < MIN_SUBDOMAIN_DOFS {
            return Err(src.error(
                d.span(),
                "solver.subdomain_dofs",
                format!("must be at least {MIN_SUBDOMAIN_DOFS} unknowns, got {v}"),
            ));
        }
        if options.subdomains == Subdomains::Never {
            return Err(src.error(
                d.span(),
                "solver.subdomain_dofs",
                "has no effect with subdomains = \"never\"".to_string(),
            ));
        }
        options.subdomain_dofs = v;
    }
    Ok(())
}

/// The smallest subdomain `[solver] subdomain_dofs` takes: a few cells of quadratic elements.
pub const MIN_SUBDOMAIN_DOFS: usize = 100;

/// The `[solver]` settings of large sliding (`alea_latin::large_sliding::Repairing`):
/// `repair_tolerance` in (0, 0.5] (beyond half the mesh size a pairing no longer pairs the
/// points that face each other, module `alea_latin::sliding`) and `max_pairings` in 1 - 100
/// (each pairing is one assembly and factorisation); refused when no interface has
/// `sliding = "large"` (they would have no effect).
fn repairing_settings(
    src: &Source,
    sv: &crate::spec::SolverSpec,
    assembly: &Assembly,
) -> Result<alea_latin::large_sliding::Repairing, StudyError> {
    let mut r = alea_latin::large_sliding::Repairing::default();
    let large = alea_latin::large_sliding::uses_large_sliding(assembly);
    let unused = |span: std::ops::Range<usize>, field: &str| {
        src.error(
            span,
            field,
            "no interface has sliding = \"large\": this setting of large sliding has no effect; \
             leave it out or set sliding = \"large\" on a contact [[interface]]",
        )
    };
    if let Some(t) = &sv.repair_tolerance {
        let field = "solver.repair_tolerance";
        if !large {
            return Err(unused(t.span(), field));
        }
        let v = *t.get_ref();
        if !(v.is_finite() && v > 0.0 && v <= alea_latin::sliding::SMALL_SLIDING_LIMIT) {
            return Err(src.error(
                t.span(),
                field,
                format!(
                    "must be in (0, {}] (a slide since the last pairing, over the mesh size; beyond {} the pairing no longer pairs the points that face each other), got {v}",
                    alea_latin::sliding::SMALL_SLIDING_LIMIT,
                    alea_latin::sliding::SMALL_SLIDING_LIMIT
                ),
            ));
        }
        r.tolerance = v;
    }
    if let Some(m) = &sv.max_pairings {
        let field = "solver.max_pairings";
        if !large {
            return Err(unused(m.span(), field));
        }
        let v = *m.get_ref();
        if !(1..=100).contains(&v) {
            return Err(src.error(
                m.span(),
                field,
                format!(
                    "must be between 1 and 100 (pairings per load step, each one assembly and factorisation), got {v}"
                ),
            ));
        }
        r.max_pairings = v;
    }
    Ok(r)
}
