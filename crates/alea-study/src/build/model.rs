//! Substructure models with their constraints and load cases, interfaces and LATIN options of
//! a model file.

use alea_fem::{Analysis, Constraints, Loads, Material, Model};
use alea_latin::{
    Assembly, InterfaceSpec, LatinOptions, LinearStage, Pairing, SearchDirection, Substructure,
};
use toml::Spanned;

use super::checks::check_interfaces;
use super::mesh::build_mesh;
use super::parametric::{BuiltModel, InterfaceSite, Parametric};
use crate::expr::Expr;
use crate::params::ParamSpace;
use crate::random_field::FieldDomain;
use crate::spec::{LoadSpec, ModelFile, NumOrExpr};
use crate::{Source, StudyError};

/// Compiles a number-or-expression against `vars`.
fn compile(
    src: &Source,
    v: &Spanned<NumOrExpr>,
    vars: &[&str],
    field: &str,
) -> Result<Expr, StudyError> {
    match v.get_ref() {
        NumOrExpr::Num(x) => {
            if !x.is_finite() {
                return Err(src.error(v.span(), field, format!("must be finite, got {x}")));
            }
            Ok(Expr::constant(*x))
        }
        NumOrExpr::Expr(t) => Expr::parse(t, vars).map_err(|e| {
            let t = crate::expr::abbreviate(t);
            src.error(v.span(), field, format!("expression '{t}': {e}"))
        }),
    }
}

fn positive(src: &Source, v: &Spanned<f64>, field: &str) -> Result<f64, StudyError> {
    let x = *v.get_ref();
    if !(x.is_finite() && x > 0.0) {
        return Err(src.error(
            v.span(),
            field,
            format!("must be a finite number > 0, got {x}"),
        ));
    }
    Ok(x)
}

fn finite(src: &Source, v: &Spanned<f64>, field: &str) -> Result<f64, StudyError> {
    let x = *v.get_ref();
    if !x.is_finite() {
        return Err(src.error(v.span(), field, format!("must be finite, got {x}")));
    }
    Ok(x)
}

fn vec3(
    src: &Source,
    v: &Spanned<Vec<f64>>,
    dim: usize,
    field: &str,
) -> Result<[f64; 3], StudyError> {
    let a = v.get_ref();
    if a.len() != dim || a.iter().any(|x| !x.is_finite()) {
        return Err(src.error(
            v.span(),
            field,
            format!("expected {dim} finite components, got {a:?}"),
        ));
    }
    let mut o = [0.0; 3];
    o[..dim].copy_from_slice(a);
    Ok(o)
}

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

/// Where a field lives, in words (for the errors of expressions that use it elsewhere).
fn field_place(file: &ModelFile, domain: FieldDomain) -> String {
    match domain {
        FieldDomain::Interface(k) => format!("on interface '{}'", file.interface[k].name.get_ref()),
        FieldDomain::Substructure(k) => format!(
            "over the cells of substructure '{}'",
            file.substructure[k].name.get_ref()
        ),
    }
}

/// Builds meshes, models, constraints, loads and interfaces of a model file; parameters enter
/// through `params` (the model is set up at their nominal point).
pub fn build_model(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
) -> Result<BuiltModel, StudyError> {
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
    // `young`: the parameters, then every field (only those over the substructure's own cells
    // may be used, checked below).
    let mut young_vars: Vec<&str> = pvars.clone();
    young_vars.extend(params.fields.iter().map(|f| f.name.as_str()));
    let mut young_e = Vec::new();
    let mut young_fields = Vec::new();
    let mut young_nominal = Vec::new();
    let mut load_factors = Vec::new();
    let mesh = build_mesh(src, &file.mesh)?;
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
    if analysis.dim() != mesh.dim {
        return Err(src.error(
            file.analysis.kind.span(),
            "analysis.type",
            format!(
                "a {}D analysis does not fit the {}D mesh",
                analysis.dim(),
                mesh.dim
            ),
        ));
    }
    if file.substructure.is_empty() {
        return Err(src.error(
            0..0,
            "substructure",
            "at least one [[substructure]] is needed",
        ));
    }
    let mut subs = Vec::new();
    let mut load_names = Vec::new();
    let mut names: Vec<String> = Vec::new();
    for (i, s) in file.substructure.iter().enumerate() {
        let f = |k: &str| format!("substructure[{i}].{k}");
        let name = s.name.get_ref().clone();
        if names.contains(&name) {
            return Err(src.error(
                s.name.span(),
                f("name"),
                format!("duplicate substructure name '{name}'"),
            ));
        }
        names.push(name.clone());
        let ye = compile(src, &s.young, &young_vars, &f("young"))?;
        let mut used = Vec::new();
        for (j, fld) in params.fields.iter().enumerate() {
            if !ye.uses(pvars.len() + j) {
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
        // The reference modulus: the parameters' nominal values, each field at its nominal
        // value (all KL variables 0: the transform of the Gaussian mean, the same at every node).
        let mut nominal = params.nominal.clone();
        for fld in params.fields.iter() {
            nominal.push(
                fld.at_nodes(&params.nominal)
                    .first()
                    .copied()
                    .unwrap_or(0.0),
            );
        }
        let young = ye.eval(&nominal);
        young_e.push(ye);
        young_fields.push(used);
        young_nominal.push(young);
        let poisson = *s.poisson.get_ref();
        let density = s.density.as_ref().map_or(0.0, |d| *d.get_ref());
        let material = Material::new(young, poisson, density).map_err(|e| {
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
        })?;
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
        let mut cases = Vec::new();
        let mut lnames = Vec::new();
        let mut factors = Vec::new();
        for (j, l) in s.load.iter().enumerate() {
            let field = format!("substructure[{i}].load[{j}]");
            cases.push(build_load(src, &model, l, &field)?);
            lnames.push(
                l.name
                    .as_ref()
                    .map_or(String::new(), |n| n.get_ref().clone()),
            );
            factors.push(match &l.factor {
                Some(fe) => compile(src, fe, &pvars, &format!("{field}.factor"))?,
                None => Expr::constant(1.0),
            });
        }
        load_factors.push(factors);
        subs.push(Substructure {
            name,
            model,
            constraints: cons,
            load_cases: cases,
        });
        load_names.push(lnames);
    }
    let mut parametric = Parametric {
        nparams: params.names.len(),
        young: young_e,
        young_nominal,
        young_fields,
        load_factors,
        mu: Vec::new(),
        gap: Vec::new(),
        defines,
        fields: params.fields.clone(),
    };
    let mut interfaces = Vec::new();
    let mut interface_sites = Vec::new();
    for (i, it) in file.interface.iter().enumerate() {
        let f = |k: &str| format!("interface[{i}].{k}");
        let side = |v: &Spanned<[String; 2]>, key: &str| -> Result<(usize, String), StudyError> {
            let [sub, group] = v.get_ref();
            let idx = names.iter().position(|n| n == sub).ok_or_else(|| {
                src.error(
                    v.span(),
                    f(key),
                    format!(
                        "unknown substructure '{sub}'; defined: {}",
                        names.join(", ")
                    ),
                )
            })?;
            if subs[idx].model.mesh.facet_group(group).is_err() {
                let avail: Vec<&String> = subs[idx].model.mesh.facet_groups.keys().collect();
                return Err(src.error(
                    v.span(),
                    f(key),
                    format!("substructure '{sub}' has no facet group '{group}'; it has: {avail:?}"),
                ));
            }
            Ok((idx, group.clone()))
        };
        let (s1, g1) = side(&it.side1, "side1")?;
        let (s2, g2) = side(&it.side2, "side2")?;
        let name = it.name.get_ref();
        let mut spec = match it.law.get_ref().as_str() {
            "perfect" => InterfaceSpec::perfect(name, s1, &g1, s2, &g2),
            "coulomb" => InterfaceSpec::coulomb(name, s1, &g1, s2, &g2, 0.0),
            other => {
                return Err(src.error(
                    it.law.span(),
                    f("law"),
                    format!("unknown law '{other}'; expected perfect or coulomb"),
                ));
            }
        };
        let mu = match &it.mu {
            Some(m) => {
                if let NumOrExpr::Num(v) = m.get_ref()
                    && !(v.is_finite() && *v >= 0.0)
                {
                    return Err(src.error(
                        m.span(),
                        f("mu"),
                        format!("friction coefficient must be finite and >= 0, got {v}"),
                    ));
                }
                compile(src, m, &profile_vars, &f("mu"))?
            }
            None => Expr::constant(0.0),
        };
        let gap = match &it.gap {
            Some(g) => compile(src, g, &profile_vars, &f("gap"))?,
            None => Expr::constant(0.0),
        };
        let first_field = profile_vars.len() - params.fields.len();
        for (j, fld) in params.fields.iter().enumerate() {
            for (e, key, v) in [(&mu, "mu", &it.mu), (&gap, "gap", &it.gap)] {
                if fld.domain != FieldDomain::Interface(i) && e.uses(first_field + j) {
                    let place = field_place(file, fld.domain);
                    return Err(src.error(
                        v.as_ref().map_or(it.name.span(), |v| v.span()),
                        f(key),
                        format!("field '{}' lives {place}, not on '{name}'", fld.name),
                    ));
                }
            }
        }
        if let Some(p) = &it.pairing {
            spec.pairing = match p.get_ref().as_str() {
                "auto" => Pairing::Auto,
                "node" => Pairing::NodeToNode,
                "mortar" => Pairing::Mortar,
                other => {
                    return Err(src.error(
                        p.span(),
                        f("pairing"),
                        format!("unknown pairing '{other}'; expected auto, node or mortar"),
                    ));
                }
            };
        }
        if let Some(sl) = &it.sliding {
            spec.sliding = match sl.get_ref().as_str() {
                "small" => alea_latin::Sliding::Small,
                "large" if spec.law.uses_gap() => alea_latin::Sliding::Large,
                "large" => {
                    return Err(src.error(
                        sl.span(),
                        f("sliding"),
                        "large sliding applies to contact interfaces (law = \"coulomb\"); a perfect interface keeps its pairing".to_string(),
                    ));
                }
                other => {
                    return Err(src.error(
                        sl.span(),
                        f("sliding"),
                        format!("unknown sliding '{other}'; expected small or large"),
                    ));
                }
            };
        }
        if let Some(t) = &it.tolerance {
            spec.match_tolerance = Some(positive(src, t, &f("tolerance"))?);
        }
        if let Some(d) = &it.search_distance {
            let v = *d.get_ref();
            if !(v.is_finite() && v >= 0.0) {
                return Err(src.error(
                    d.span(),
                    f("search_distance"),
                    format!("must be finite and >= 0, got {v}"),
                ));
            }
            spec.search_distance = Some(v);
        }
        let side2_line = src.line_of(it.side2.span().start);
        let line_or =
            |v: Option<std::ops::Range<usize>>| v.map_or(side2_line, |r| src.line_of(r.start));
        interface_sites.push(InterfaceSite {
            file: src.path.clone(),
            side2: side2_line,
            tolerance: line_or(it.tolerance.as_ref().map(|t| t.span())),
            search_distance: line_or(it.search_distance.as_ref().map(|t| t.span())),
            sliding: line_or(it.sliding.as_ref().map(|t| t.span())),
        });
        spec.mu = parametric.profile(&mu, &params.nominal);
        spec.gap = parametric.profile(&gap, &params.nominal);
        parametric.mu.push(mu);
        parametric.gap.push(gap);
        interfaces.push(spec);
    }
    let sv = &file.solver;
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
        options.acceleration = *a.get_ref();
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
        options.linear_stage = match m.get_ref().as_str() {
            "auto" => LinearStage::Auto,
            "condensed" => LinearStage::Condensed,
            "volume" => LinearStage::Volume,
            other => {
                return Err(src.error(
                    m.span(),
                    "solver.linear_stage",
                    format!("must be \"auto\", \"condensed\" or \"volume\", got \"{other}\""),
                ));
            }
        };
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
    let assembly = Assembly { subs, interfaces };
    let repairing = repairing_settings(src, sv, &assembly)?;
    let built = BuiltModel {
        mesh,
        assembly,
        load_names,
        options,
        repairing,
        units: file.units.clone(),
        parametric,
        interface_sites,
    };
    check_interfaces(src, &file.interface, &built)?;
    Ok(built)
}

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
