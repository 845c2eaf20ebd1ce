//! CRE of a LATIN solution: each substructure isolated and loaded by its prescribed loads and
//! by the interface forces its last linear-stage FE solution is in equilibrium with.
//!
//! The linear stage solves `(K + k M_Gamma) u = f + M_Gamma (F_hat + k W_hat)` with the
//! **lumped** interface mass `M_Gamma = diag(m_i)`, i.e. `K u = f + M_Gamma F` with
//! `F = F_hat - k (W - W_hat)` (`InterfaceResult::f`). The discrete interface forces on the
//! substructure are therefore `m_i F_i` (side 1: the run's weights; side 2: the HRZ weights of
//! side 2's own facet group, recomputed with `alea_latin::interface::side_geometry`, as the solver
//! does). Phase 1 turns them into the piecewise-linear edge density whose consistent nodal forces
//! are exactly `m_i F_i` ([`crate::eet::phase1::interface_densities`]) and treats the interface
//! edges as loaded boundary edges.
//!
//! The forces are read from the run (`InterfaceResult::f` and the weights), so `K u_h = f +
//! M_Gamma F` holds exactly only with the LATIN relaxation 1 (the default): with relaxation
//! `rho < 1` the stored `F` is relaxed while `u_h` is not, and the phase-1 node systems become
//! slightly incompatible - reported in [`crate::DomainEstimate::compatibility_defect`] (least-squares
//! solution, estimate no longer a bound). Load factors other than 1 must be folded into the
//! [`LoadData`] functions.

use std::collections::HashMap;

use alea_fem::DofMap;
use alea_latin::{Assembly, RunResult, interface::side_geometry};

use crate::CreError;
use crate::data::{LoadData, SideForces};
use crate::domain::{CreOptions, estimate_with_sides};
use crate::interface::interface_term;
use crate::result::CreResult;

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
    let mut sides: Vec<Vec<SideForces>> = vec![Vec::new(); ns];
    for (spec, ir) in assembly.interfaces.iter().zip(&run.interfaces) {
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
            let weights: Vec<f64> = if s == 0 {
                ir.weights.clone()
            } else {
                let g = side_geometry(&model.mesh, group, model.analysis.thickness())?;
                let pos: HashMap<usize, f64> = g
                    .nodes
                    .iter()
                    .copied()
                    .zip(g.weights.iter().copied())
                    .collect();
                ir.nodes[1]
                    .iter()
                    .map(|n| {
                        pos.get(n).copied().ok_or_else(|| {
                            CreError::Invalid(format!(
                                "interface '{}': node {n} not in group '{group}'",
                                spec.name
                            ))
                        })
                    })
                    .collect::<Result<_, _>>()?
            };
            if weights.len() != ir.nodes[s].len() || ir.f[s].len() != ir.nodes[s].len() {
                return Err(CreError::Invalid(format!(
                    "interface '{}' side {}: {} nodes, {} weights, {} forces",
                    spec.name,
                    s + 1,
                    ir.nodes[s].len(),
                    weights.len(),
                    ir.f[s].len()
                )));
            }
            let forces = ir.f[s]
                .iter()
                .zip(&weights)
                .map(|(f, m)| [m * f[0], m * f[1], m * f[2]])
                .collect();
            sides[sub].push(SideForces {
                group: group.clone(),
                nodes: ir.nodes[s].clone(),
                forces,
            });
        }
    }
    let mut subs = Vec::with_capacity(ns);
    for (s, sub) in assembly.subs.iter().enumerate() {
        let model = run.scaled_model(&sub.model, s);
        let dofs = DofMap::for_mesh(&model.mesh, &sub.constraints)?;
        subs.push(estimate_with_sides(
            &model,
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
