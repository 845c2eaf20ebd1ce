//! CRE of a LATIN solution: each substructure isolated and loaded by its prescribed loads and
//! by the interface forces its last linear-stage FE solution is in equilibrium with.
//!
//! The linear stage solves `(K + k M_Gamma) u = f + M_Gamma (F_hat + k W_hat)` with the
//! **lumped** interface mass `M_Gamma = diag(m_i)` and the side's projection `Pi` (identity for
//! node-to-node interfaces, dual mortar otherwise; `alea_latin::mortar`), i.e.
//! `K u = f + Pi^T M_Gamma F` with `F = F_hat - k (W - W_hat)` (`InterfaceResult::f`). The
//! discrete interface forces on the substructure are therefore `Pi^T M_Gamma F`
//! (`InterfaceResult::linear_nodal_forces`; node to node: `m_i F_i` with each side's own lumped
//! weights). Phase 1 turns them into edge densities of degree `p` whose consistent nodal forces are
//! exactly `m_i F_i` ([`crate::eet::phase1::interface_densities`]: at each node the force is split
//! between the side edges around it as close as possible to the average of the two sides' FE
//! traction projections, so that both sides get opposite densities once `F_1 = -F_2`; in the
//! directions constrained at a node the force contains a reaction and is not imposed) and treats
//! the interface edges as loaded boundary edges.
//!
//! The forces are read from the run (`InterfaceResult::f` and the weights), so `K u_h = f +
//! M_Gamma F` holds exactly only with the LATIN relaxation 1 (the default): with relaxation
//! `rho < 1` the stored `F` is relaxed while `u_h` is not, and the phase-1 node systems become
//! slightly incompatible - reported in [`crate::DomainEstimate::compatibility_defect`] (least-squares
//! solution, estimate no longer a bound). Load factors other than 1 must be folded into the
//! [`LoadData`] functions.

use std::collections::HashMap;

use alea_fem::{DofMap, Model};
use alea_latin::{Assembly, PairingKind, RunResult};

use crate::CreError;
use crate::data::{FaceProjections, FacetProjections, LoadData, SideForces};
use crate::domain::{CreOptions, estimate_with_sides};
use crate::eet::phase1::facet_projections;
use crate::interface::interface_term;
use crate::result::CreResult;
use crate::solid::sides::face_projections;

/// Estimates the error of a LATIN run `run` of `assembly` (the same assembly the solver was
/// built from); `loads[s]` are the loads of substructure `s` as functions (the ones its load
/// cases were computed from, load factors 1).
pub fn estimate_latin(
    assembly: &Assembly,
    loads: &[LoadData],
    run: &RunResult,
    options: &CreOptions,
) -> Result<CreResult, CreError> {
    options.validate()?;
    let ns = assembly.subs.len();
    if loads.len() != ns || run.displacements.len() != ns || run.young_factors.len() != ns {
        return Err(CreError::Invalid(format!(
            "{ns} substructures, {} load data, {} displacements",
            loads.len(),
            run.displacements.len()
        )));
    }
    if run.interfaces.len() != assembly.interfaces.len() {
        return Err(CreError::Invalid(format!(
            "{} interfaces in the assembly, {} in the run",
            assembly.interfaces.len(),
            run.interfaces.len()
        )));
    }
    let models: Vec<Model> = (0..ns)
        .map(|s| run.scaled_model(&assembly.subs[s].model, s))
        .collect();
    let mut sides: Vec<Vec<SideForces>> = vec![Vec::new(); ns];
    for (spec, ir) in assembly.interfaces.iter().zip(&run.interfaces) {
        let solid = models.get(spec.sub1).is_some_and(|m| m.mesh.dim == 3);
        let (refs, face_refs) = if solid {
            let r = interface_face_references(spec, ir, &models, run)?;
            ([None, None], [Some(r[0].clone()), Some(r[1].clone())])
        } else {
            let r = interface_references(spec, ir, &models, run)?;
            ([Some(r[0].clone()), Some(r[1].clone())], [None, None])
        };
        for s in 0..2 {
            let (sub, group) = if s == 0 {
                (spec.sub1, &spec.group1)
            } else {
                (spec.sub2, &spec.group2)
            };
            if sub >= ns {
                return Err(CreError::Invalid(format!(
                    "interface '{}' refers to substructure {sub}",
                    spec.name
                )));
            }
            let model = &assembly.subs[sub].model;
            // Nodal forces Pi_s^T M F_s of the run on every node of the side's facet group
            // (zero on nodes the interface points do not reach).
            let proj = &ir.pairing.sides[s];
            if ir.f[s].len() != proj.len() {
                return Err(CreError::Invalid(format!(
                    "interface '{}' side {}: {} points, {} forces",
                    spec.name,
                    s + 1,
                    proj.len(),
                    ir.f[s].len()
                )));
            }
            let reached = proj.side_nodes();
            let nodal = proj.nodal_forces(&ir.f[s]);
            let mut nodes: Vec<usize> = model
                .mesh
                .facet_group(group)?
                .iter()
                .flat_map(|f| f.nodes.iter().copied())
                .collect();
            nodes.sort_unstable();
            nodes.dedup();
            if let Some(n) = reached.iter().find(|n| nodes.binary_search(n).is_err()) {
                return Err(CreError::Invalid(format!(
                    "interface '{}': node {n} not in group '{group}'",
                    spec.name
                )));
            }
            let forces = nodes
                .iter()
                .map(|n| reached.binary_search(n).map_or([0.0; 3], |i| nodal[i]))
                .collect();
            sides[sub].push(SideForces {
                group: group.clone(),
                nodes,
                forces,
                reference: refs[s].clone(),
                face_reference: face_refs[s].clone(),
            });
        }
    }
    let mut subs = Vec::with_capacity(ns);
    for (s, (sub, model)) in assembly.subs.iter().zip(&models).enumerate() {
        let dofs = DofMap::for_mesh(&model.mesh, &sub.constraints)?;
        subs.push(estimate_with_sides(
            model,
            &dofs,
            &loads[s],
            &sides[s],
            &run.displacements[s],
            options,
        )?);
    }
    let interfaces = run
        .interfaces
        .iter()
        .map(|ir| interface_term(ir, options.admissibility_tolerance))
        .collect::<Result<_, _>>()?;
    Ok(CreResult::new(subs, interfaces))
}

/// Target projections of both sides of an interface: the average of the two sides' FE traction
/// projections (side 2's taken with the opposite sign, through the node pairing), so that the
/// two sides' densities are exactly opposite once their nodal forces are (converged LATIN).
/// Facets without a matching facet on the other side keep their own projections.
fn interface_references(
    spec: &alea_latin::InterfaceSpec,
    ir: &alea_latin::InterfaceResult,
    models: &[Model],
    run: &RunResult,
) -> Result<[FacetProjections; 2], CreError> {
    let (s1, s2) = (spec.sub1, spec.sub2);
    if s1 >= models.len() || s2 >= models.len() || ir.nodes[0].len() != ir.nodes[1].len() {
        return Err(CreError::Invalid(format!(
            "interface '{}': inconsistent substructures or node pairs",
            spec.name
        )));
    }
    let p1 = facet_projections(&models[s1], &run.displacements[s1], &spec.group1)?;
    let p2 = facet_projections(&models[s2], &run.displacements[s2], &spec.group2)?;
    if ir.pairing.kind != PairingKind::NodeToNode {
        // Mortar: the facets of the two sides do not correspond; each side keeps its own.
        return Ok([p1, p2]);
    }
    let partner: HashMap<usize, usize> = ir.nodes[0]
        .iter()
        .copied()
        .zip(ir.nodes[1].iter().copied())
        .collect();
    let mut r1 = p1.clone();
    let mut r2 = p2.clone();
    for (key, list1) in &p1 {
        let (Some(&a), Some(&b)) = (partner.get(&key[0]), partner.get(&key[1])) else {
            continue;
        };
        let key2 = [a.min(b), a.max(b)];
        let Some(list2) = p2.get(&key2) else {
            continue;
        };
        let mut avg1 = Vec::with_capacity(list1.len());
        let mut avg2 = Vec::with_capacity(list1.len());
        let mut complete = true;
        for &(n1, v1) in list1 {
            let found = partner
                .get(&n1)
                .and_then(|n2| list2.iter().find(|(m, _)| m == n2).map(|&(m, v)| (m, v)));
            match found {
                Some((n2, v2)) => {
                    let avg = [0.5 * (v1[0] - v2[0]), 0.5 * (v1[1] - v2[1])];
                    avg1.push((n1, avg));
                    avg2.push((n2, [-avg[0], -avg[1]]));
                }
                None => complete = false,
            }
        }
        if complete {
            r1.insert(*key, avg1);
            r2.insert(key2, avg2);
        }
    }
    Ok([r1, r2])
}

/// The 3D counterpart of [`interface_references`]: the average of the two sides' FE traction
/// projections on each pair of matching faces (side 2's with the opposite sign, through the
/// node pairing).
fn interface_face_references(
    spec: &alea_latin::InterfaceSpec,
    ir: &alea_latin::InterfaceResult,
    models: &[Model],
    run: &RunResult,
) -> Result<[FaceProjections; 2], CreError> {
    let (s1, s2) = (spec.sub1, spec.sub2);
    if s1 >= models.len() || s2 >= models.len() || ir.nodes[0].len() != ir.nodes[1].len() {
        return Err(CreError::Invalid(format!(
            "interface '{}': inconsistent substructures or node pairs",
            spec.name
        )));
    }
    let p1 = face_projections(&models[s1], &run.displacements[s1], &spec.group1)?;
    let p2 = face_projections(&models[s2], &run.displacements[s2], &spec.group2)?;
    let partner: HashMap<usize, usize> = ir.nodes[0]
        .iter()
        .copied()
        .zip(ir.nodes[1].iter().copied())
        .collect();
    let mut r1 = p1.clone();
    let mut r2 = p2.clone();
    for (key, list1) in &p1 {
        let Some(mut key2) = key
            .iter()
            .map(|n| partner.get(n).copied())
            .collect::<Option<Vec<usize>>>()
        else {
            continue;
        };
        key2.sort_unstable();
        let Some(list2) = p2.get(&key2) else {
            continue;
        };
        let mut avg1 = Vec::with_capacity(list1.len());
        let mut avg2 = Vec::with_capacity(list1.len());
        let mut complete = true;
        for &(n1, v1) in list1 {
            let found = partner
                .get(&n1)
                .and_then(|n2| list2.iter().find(|(m, _)| m == n2).map(|&(m, v)| (m, v)));
            match found {
                Some((n2, v2)) => {
                    let avg = [0, 1, 2].map(|c| 0.5 * (v1[c] - v2[c]));
                    avg1.push((n1, avg));
                    avg2.push((n2, avg.map(|v| -v)));
                }
                None => complete = false,
            }
        }
        if complete {
            r1.insert(key.clone(), avg1);
            r2.insert(key2, avg2);
        }
    }
    Ok([r1, r2])
}
