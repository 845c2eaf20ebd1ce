//! Consistency checks of a built model, done when the file is loaded so that every mistake is
//! an input error naming file, line and field (exit code 2), never a failure of the solver
//! set-up: two sides on two different substructures (or, for a cyclic interface, side 2 mapped
//! back by its rotation falling on side 1: `alea_latin::sides::check_faces`); when the sides' nodes pair one to one
//! (the same pairing as the solver's, [`alea_latin::interface::pair_nodes`]), paired nodes have
//! opposite normals (`n1 . n2 < -0.5`: the sides face each other); no facet belongs to two
//! interfaces (sides that do not match are paired by the mortar method, whose errors are
//! reported when the solver is built, [`BuiltModel::solver`]). The quantities are checked where
//! they are built (module `qoi`).

use std::collections::HashMap;

use alea_latin::interface::{pair_nodes, side_geometry};
use alea_mesh::vec3::dot;

use super::parametric::BuiltModel;
use crate::spec::InterfaceSpecToml;
use crate::{Source, StudyError};

/// Checks the interfaces of a built model (module doc).
///
/// # Errors
/// [`StudyError::Input`] at the offending interface.
pub fn check_interfaces(
    src: &Source,
    specs: &[InterfaceSpecToml],
    model: &BuiltModel,
) -> Result<(), StudyError> {
    let subs = &model.assembly.subs;
    // (substructure, sorted facet nodes) -> interface index
    let mut owner: HashMap<(usize, Vec<usize>), usize> = HashMap::new();
    for (i, (spec, it)) in specs.iter().zip(&model.assembly.interfaces).enumerate() {
        let field = format!("interface[{i}]");
        if let Some(c) = &spec.cyclic {
            // Side 2 mapped back by the rotation must fall on side 1 (the solver's own
            // pairing and cover checks, module `alea_latin::cyclic`).
            alea_latin::sides::check_faces(it, subs)
                .map_err(|e| src.error(c.span(), format!("{field}.cyclic"), e.to_string()))?;
        } else if it.sub1 == it.sub2 {
            return Err(src.error(
                spec.side2.span(),
                format!("{field}.side2"),
                format!(
                    "both sides are on substructure '{}'; an interface joins two different substructures",
                    subs[it.sub1].name
                ),
            ));
        }
        for (side, sub, group, span) in [
            (1, it.sub1, &it.group1, spec.side1.span()),
            (2, it.sub2, &it.group2, spec.side2.span()),
        ] {
            let facets = subs[sub].model.mesh.facet_group(group).map_err(|e| {
                src.error(span.clone(), format!("{field}.side{side}"), e.to_string())
            })?;
            for f in facets {
                let mut key = f.nodes.clone();
                key.sort_unstable();
                if let Some(&j) = owner.get(&(sub, key.clone())) {
                    if j != i {
                        return Err(src.error(
                            span,
                            format!("{field}.side{side}"),
                            format!(
                                "facets of '{group}' on substructure '{}' already belong to interface[{j}] '{}'; a facet can be in one interface only",
                                subs[sub].name, model.assembly.interfaces[j].name
                            ),
                        ));
                    }
                } else {
                    owner.insert((sub, key), i);
                }
            }
        }
        let geom = |sub: usize, group: &str, span: std::ops::Range<usize>, side: usize| {
            let m = &subs[sub].model;
            side_geometry(&m.mesh, group, m.analysis.thickness())
                .map_err(|e| src.error(span, format!("{field}.side{side}"), e.to_string()))
        };
        let g1 = geom(it.sub1, &it.group1, spec.side1.span(), 1)?;
        let g2 = geom(it.sub2, &it.group2, spec.side2.span(), 2)?;
        let x = |sub: usize, nodes: &[usize]| -> Vec<[f64; 3]> {
            nodes
                .iter()
                .map(|&n| subs[sub].model.mesh.coords[n])
                .collect()
        };
        // Sides that do not match node to node are paired by the mortar method or rejected
        // when the solver is built (`BuiltModel::solver`, naming the tolerance or search
        // distance field); the facing check below is for coincident nodes.
        if it.cyclic.is_some() {
            continue;
        }
        let Ok(partner) = pair_nodes(
            &it.name,
            &x(it.sub1, &g1.nodes),
            &x(it.sub2, &g2.nodes),
            it.match_tolerance,
        ) else {
            continue;
        };
        for (k, &j) in partner.iter().enumerate() {
            let (a, b) = (g1.normals[k], g2.normals[j]);
            let c = dot(&a, &b);
            if c > -0.5 {
                let p = subs[it.sub1].model.mesh.coords[g1.nodes[k]];
                return Err(src.error(
                    spec.side1.span(),
                    field,
                    format!(
                        "the sides do not face each other: at ({:.6}, {:.6}, {:.6}) the outward normals of side 1 ({:.3}, {:.3}, {:.3}) and side 2 ({:.3}, {:.3}, {:.3}) are not opposite (the two bodies overlap, or a facet group is on the wrong face)",
                        p[0], p[1], p[2], a[0], a[1], a[2], b[0], b[1], b[2]
                    ),
                ));
            }
        }
    }
    Ok(())
}
