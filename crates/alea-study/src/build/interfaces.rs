//! The interfaces of a model file: their sides, law, friction and gap profiles (the fields
//! they use must live on the interface), settings, and the lines of those settings.

use alea_latin::{InterfaceSpec, Pairing, Substructure};
use toml::Spanned;

use super::parametric::{InterfaceSite, Parametric};
use super::values::{compile, field_place, positive};
use crate::expr::Expr;
use crate::params::ParamSpace;
use crate::random_field::FieldDomain;
use crate::spec::{CyclicSpec, InterfaceSpecToml, ModelFile, NumOrExpr};
use crate::{Source, StudyError};

/// Builds every `[[interface]]` between the substructures `subs` (named `names`) at the
/// nominal point, pushing each one's friction and gap expressions on `parametric`; with the
/// lines of their settings.
pub(super) fn build_interfaces(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
    profile_vars: &[&str],
    names: &[String],
    subs: &[Substructure],
    parametric: &mut Parametric,
) -> Result<(Vec<InterfaceSpec>, Vec<InterfaceSite>), StudyError> {
    let mut interfaces = Vec::new();
    let mut interface_sites = Vec::new();
    for (i, it) in file.interface.iter().enumerate() {
        let ((s1, g1), (s2, g2)) = (
            interface_side(src, i, &it.side1, "side1", names, subs)?,
            interface_side(src, i, &it.side2, "side2", names, subs)?,
        );
        let mut spec = interface_law(src, i, it, s1, &g1, s2, &g2)?;
        let (mu, gap) = friction_and_gap(src, file, params, profile_vars, i, it)?;
        apply_interface_settings(src, i, it, &mut spec)?;
        interface_sites.push(interface_site(src, it));
        spec.mu = parametric.profile(&mu, &params.nominal);
        spec.gap = parametric.profile(&gap, &params.nominal);
        parametric.mu.push(mu);
        parametric.gap.push(gap);
        interfaces.push(spec);
    }
    Ok((interfaces, interface_sites))
}

/// One side (`key`) of interface `i`: the substructure's index and the facet group, which must
/// exist.
fn interface_side(
    src: &Source,
    i: usize,
    v: &Spanned<[String; 2]>,
    key: &str,
    names: &[String],
    subs: &[Substructure],
) -> Result<(usize, String), StudyError> {
    let f = |k: &str| format!("interface[{i}].{k}");
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
}

/// Interface `i`'s specification for its law (`perfect` or `coulomb`), before its settings.
fn interface_law(
    src: &Source,
    i: usize,
    it: &InterfaceSpecToml,
    s1: usize,
    g1: &str,
    s2: usize,
    g2: &str,
) -> Result<InterfaceSpec, StudyError> {
    let name = it.name.get_ref();
    Ok(match it.law.get_ref().as_str() {
        "perfect" => InterfaceSpec::perfect(name, s1, g1, s2, g2),
        "coulomb" => InterfaceSpec::coulomb(name, s1, g1, s2, g2, 0.0),
        other => {
            return Err(src.error(
                it.law.span(),
                format!("interface[{i}].law"),
                format!("unknown law '{other}'; expected perfect or coulomb"),
            ));
        }
    })
}

/// Interface `i`'s compiled friction and gap profiles (of `profile_vars`; the fields they use
/// must live on that interface).
fn friction_and_gap(
    src: &Source,
    file: &ModelFile,
    params: &ParamSpace,
    profile_vars: &[&str],
    i: usize,
    it: &InterfaceSpecToml,
) -> Result<(Expr, Expr), StudyError> {
    let f = |k: &str| format!("interface[{i}].{k}");
    let name = it.name.get_ref();
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
            compile(src, m, profile_vars, &f("mu"))?
        }
        None => Expr::constant(0.0),
    };
    let gap = match &it.gap {
        Some(g) => compile(src, g, profile_vars, &f("gap"))?,
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
    Ok((mu, gap))
}

/// Sets interface `i`'s `pairing`, `sliding`, `cyclic`, `tolerance` and `search_distance` on
/// `spec`.
fn apply_interface_settings(
    src: &Source,
    i: usize,
    it: &InterfaceSpecToml,
    spec: &mut InterfaceSpec,
) -> Result<(), StudyError> {
    let f = |k: &str| format!("interface[{i}].{k}");
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
    if let Some(c) = &it.cyclic {
        spec.cyclic = Some(cyclic(src, i, c, spec.law.name())?);
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
    Ok(())
}

/// Interface `i`'s `cyclic` table (law `law`): a perfect interface, an angle in `(0, 180]`
/// degrees, a finite centre of 2 or 3 coordinates, a finite non-zero axis of 3 components.
fn cyclic(
    src: &Source,
    i: usize,
    c: &Spanned<CyclicSpec>,
    law: &str,
) -> Result<alea_latin::Cyclic, StudyError> {
    let f = |k: &str| format!("interface[{i}].cyclic{k}");
    if law != "perfect" {
        return Err(src.error(
            c.span(),
            f(""),
            format!(
                "cyclic symmetry applies to perfect interfaces (law = \"perfect\"), not to '{law}'"
            ),
        ));
    }
    let cs = c.get_ref();
    let angle = *cs.angle_deg.get_ref();
    alea_latin::cyclic::check_angle(angle)
        .map_err(|m| src.error(cs.angle_deg.span(), f(".angle_deg"), m))?;
    let center = match &cs.center {
        Some(v) => {
            let x = v.get_ref();
            if !(x.len() == 2 || x.len() == 3) || x.iter().any(|c| !c.is_finite()) {
                return Err(src.error(
                    v.span(),
                    f(".center"),
                    format!("must be 2 or 3 finite coordinates, got {x:?}"),
                ));
            }
            [x[0], x[1], x.get(2).copied().unwrap_or(0.0)]
        }
        None => [0.0; 3],
    };
    let axis = match &cs.axis {
        Some(v) => {
            let x = v.get_ref();
            if x.len() != 3 || x.iter().any(|c| !c.is_finite()) || x.iter().all(|&c| c == 0.0) {
                return Err(src.error(
                    v.span(),
                    f(".axis"),
                    format!("must be 3 finite components, not all zero, got {x:?}"),
                ));
            }
            [x[0], x[1], x[2]]
        }
        None => [0.0, 0.0, 1.0],
    };
    alea_latin::Cyclic::new(angle, center, axis)
        .map_err(|e| src.error(c.span(), f(""), e.to_string()))
}

/// The lines of the model file where interface `it`'s settings are (or would go: `side2`'s),
/// for the messages that suggest changing them.
fn interface_site(src: &Source, it: &InterfaceSpecToml) -> InterfaceSite {
    let side2_line = src.line_of(it.side2.span().start);
    let line_or =
        |v: Option<std::ops::Range<usize>>| v.map_or(side2_line, |r| src.line_of(r.start));
    InterfaceSite {
        file: src.path.clone(),
        side2: side2_line,
        tolerance: line_or(it.tolerance.as_ref().map(|t| t.span())),
        search_distance: line_or(it.search_distance.as_ref().map(|t| t.span())),
        sliding: line_or(it.sliding.as_ref().map(|t| t.span())),
        cyclic: line_or(it.cyclic.as_ref().map(|t| t.span())),
    }
}
