//! The pairing of an interface's two sides as its specification asks (node to node, dual
//! mortar, or node to node when the sides match and mortar otherwise), through the rotation of
//! a cyclic interface (module `cyclic`); used by the solver's set-up, the load-time check of
//! cyclic faces and the split of substructures (module `split`).

use alea_fem::DofMap;

use crate::LatinError;
use crate::cyclic::{self, check_spec};
use crate::interface::{InterfacePairing, Pairing, pair_node_to_node};
use crate::mortar::pair_mortar;
use crate::{InterfaceSpec, Substructure};

/// Pairs the two sides of interface `spec` (substructures `subs = [side 1's, side 2's]`) as
/// `spec.pairing` asks - node to node, mortar, or node to node when the sides match and
/// mortar otherwise - unless the caller `given` the pairing; a cyclic interface pairs side 1
/// with side 2 mapped back by its rotation and checks that the faces cover each other (module
/// [`crate::cyclic`]). Mortar points are not put on nodes held in every direction by their
/// substructure's constraints (module [`crate::mortar`]).
///
/// # Errors
/// The pairing's errors ([`LatinError::Unmatched`], [`LatinError::Pairing`]; for a cyclic
/// interface [`LatinError::Cyclic`]) and a substructure's constraints that do not apply.
pub(crate) fn pair_sides(
    spec: &InterfaceSpec,
    subs: [&Substructure; 2],
    given: Option<InterfacePairing>,
) -> Result<InterfacePairing, LatinError> {
    let [s1, s2] = subs;
    let fem = |sub: &str| {
        let sub = sub.to_string();
        move |source| LatinError::Fem {
            sub: sub.clone(),
            source,
        }
    };
    // A cyclic interface pairs side 1 with side 2 mapped back by its rotation.
    let mapped = spec
        .cyclic
        .as_ref()
        .map(|c| cyclic::mapped_back(c, &s2.model.mesh));
    let sides = [
        (
            &s1.model.mesh,
            spec.group1.as_str(),
            s1.model.analysis.thickness(),
        ),
        (
            mapped.as_ref().unwrap_or(&s2.model.mesh),
            spec.group2.as_str(),
            s2.model.analysis.thickness(),
        ),
    ];
    let held1 = DofMap::for_mesh(&s1.model.mesh, &s1.constraints).map_err(fem(&s1.name))?;
    let held2 = DofMap::for_mesh(&s2.model.mesh, &s2.constraints).map_err(fem(&s2.name))?;
    let fixed1 = |n: usize| held1.node_dofs(n).is_empty();
    let fixed2 = |n: usize| held2.node_dofs(n).is_empty();
    let mortar = || {
        pair_mortar(
            &spec.name,
            sides,
            spec.search_distance,
            spec.law.uses_gap() || spec.cyclic.is_some(),
            [&fixed1, &fixed2],
        )
    };
    let cyc = |e| cyclic::pairing_error(spec, e);
    let pairing = match (given, spec.pairing) {
        (Some(p), _) => p,
        (None, Pairing::NodeToNode) => {
            pair_node_to_node(&spec.name, sides, spec.match_tolerance).map_err(cyc)?
        }
        (None, Pairing::Mortar) => mortar().map_err(cyc)?,
        (None, Pairing::Auto) => match pair_node_to_node(&spec.name, sides, spec.match_tolerance) {
            Ok(p) => p,
            Err(LatinError::Unmatched { .. }) => mortar().map_err(cyc)?,
            Err(e) => return Err(e),
        },
    };
    let pairing = cyclic::finish(spec, pairing, sides)?;
    Ok(pairing)
}

/// The checks of a cyclic interface that the solver's set-up makes (`cyclic::check_spec`, then the
/// pairing of side 1 with side 2 mapped back by the rotation and the cover of the mapped faces,
/// `cyclic::finish`), without building a solver: a study checks its file with it when it is loaded.
/// Nothing for an interface without `cyclic`.
///
/// # Errors
/// [`LatinError::Cyclic`] (or [`LatinError::Invalid`] for a substructure index out of range).
pub fn check_faces(spec: &InterfaceSpec, subs: &[Substructure]) -> Result<(), LatinError> {
    if spec.cyclic.is_none() {
        return Ok(());
    }
    let (Some(s1), Some(s2)) = (subs.get(spec.sub1), subs.get(spec.sub2)) else {
        return Err(LatinError::Invalid(format!(
            "interface '{}': a side refers to a missing substructure",
            spec.name
        )));
    };
    check_spec(spec, subs)?;
    pair_sides(spec, [s1, s2], None).map(|_| ())
}
