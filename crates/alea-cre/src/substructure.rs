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
//!
//! **Multiresolution** ([`LatinEstimator`]): a study estimates many runs of one assembly, so
//! the context keeps per substructure a [`DomainEstimator`] (every run-independent matrix of
//! both EET phases, see [`crate::estimator`]) and per interface side 2's HRZ weights; a run then
//! costs what depends on its displacements, interface forces, loads and Young's factors (the
//! target projections of the interface sides are recomputed with the reference materials and
//! scaled). [`estimate_latin`] builds a context for one run; [`estimate_latin_direct`] is the
//! direct path (every matrix rebuilt from the run's scaled models), the reference the context
//! is tested against.

use std::collections::HashMap;

use alea_fem::{DofMap, Model};
use alea_latin::{Assembly, InterfaceResult, InterfaceSpec, PairingKind, RunResult};

use crate::CreError;
use crate::data::{FaceProjections, FacetProjections, LoadData, SideForces};
use crate::domain::{CreOptions, estimate_with_sides};
use crate::eet::phase1::facet_projections;
use crate::estimator::DomainEstimator;
use crate::interface::interface_term;
use crate::result::CreResult;
use crate::solid::sides::face_projections;

/// Estimates the error of a LATIN run `run` of `assembly` (the same assembly the solver was
/// built from); `loads[s]` are the loads of substructure `s` as functions (the ones its load
/// cases were computed from, times the run's load factors). Builds a [`LatinEstimator`] for
/// this one run: to estimate several runs of one assembly, build the context once.
///
/// # Errors
/// As [`LatinEstimator::new`] and [`LatinEstimator::estimate`].
pub fn estimate_latin(
    assembly: &Assembly,
    loads: &[LoadData],
    run: &RunResult,
    options: &CreOptions,
) -> Result<CreResult, CreError> {
    LatinEstimator::new(assembly, options)?.estimate(loads, run)
}

/// Checks the sizes of a run against an assembly of `ns` substructures and `ni` interfaces.
fn check_run(ns: usize, ni: usize, loads: &[LoadData], run: &RunResult) -> Result<(), CreError> {
    if loads.len() != ns || run.displacements.len() != ns || run.young_factors.len() != ns {
        return Err(CreError::Invalid(format!(
            "{ns} substructures, {} load data, {} displacements",
            loads.len(),
            run.displacements.len()
        )));
    }
    if run.interfaces.len() != ni {
        return Err(CreError::Invalid(format!(
            "{ni} interfaces in the assembly, {} in the run",
            run.interfaces.len()
        )));
    }
    Ok(())
}

/// The sorted, distinct nodes of the facet groups of both sides of an interface.
fn side_group_nodes(
    assembly: &Assembly,
    spec: &InterfaceSpec,
) -> Result<[Vec<usize>; 2], CreError> {
    let nodes = |sub: usize, group: &str| -> Result<Vec<usize>, CreError> {
        let model = &assembly
            .subs
            .get(sub)
            .ok_or_else(|| {
                CreError::Invalid(format!(
                    "interface '{}' refers to substructure {sub}",
                    spec.name
                ))
            })?
            .model;
        let mut nodes: Vec<usize> = model
            .mesh
            .facet_group(group)?
            .iter()
            .flat_map(|f| f.nodes.iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        Ok(nodes)
    };
    Ok([
        nodes(spec.sub1, &spec.group1)?,
        nodes(spec.sub2, &spec.group2)?,
    ])
}

/// The discrete interface forces `Pi_s^T M F_s` of both sides of an interface (the run's
/// point forces through each side's projection: `m_i F_i` for a node-to-node interface), on
/// every node of the side's facet group (zero on nodes the interface points do not reach),
/// pushed to `sides`.
fn push_sides(
    spec: &InterfaceSpec,
    ir: &InterfaceResult,
    group_nodes: &[Vec<usize>; 2],
    refs: [Option<FacetProjections>; 2],
    face_refs: [Option<FaceProjections>; 2],
    sides: &mut [Vec<SideForces>],
) -> Result<(), CreError> {
    let [r1, r2] = refs;
    let [f1, f2] = face_refs;
    for (s, (reference, face_reference)) in [(r1, f1), (r2, f2)].into_iter().enumerate() {
        let (sub, group) = if s == 0 {
            (spec.sub1, &spec.group1)
        } else {
            (spec.sub2, &spec.group2)
        };
        if sub >= sides.len() {
            return Err(CreError::Invalid(format!(
                "interface '{}' refers to substructure {sub}",
                spec.name
            )));
        }
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
        let nodes = &group_nodes[s];
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
            nodes: nodes.clone(),
            forces,
            reference,
            face_reference,
        });
    }
    Ok(())
}

/// Checks an interface's substructure indices and node pairing.
fn check_pairs(spec: &InterfaceSpec, ir: &InterfaceResult, ns: usize) -> Result<(), CreError> {
    if spec.sub1 >= ns || spec.sub2 >= ns || ir.nodes[0].len() != ir.nodes[1].len() {
        return Err(CreError::Invalid(format!(
            "interface '{}': inconsistent substructures or node pairs",
            spec.name
        )));
    }
    Ok(())
}

/// The direct path of [`estimate_latin`]: every matrix rebuilt from the run's models scaled by
/// their Young's factors (the reference of [`LatinEstimator`]; 3D substructures always take
/// this path).
///
/// # Errors
/// Sizes of the run or loads that do not match the assembly, estimator errors.
pub fn estimate_latin_direct(
    assembly: &Assembly,
    loads: &[LoadData],
    run: &RunResult,
    options: &CreOptions,
) -> Result<CreResult, CreError> {
    options.validate()?;
    let ns = assembly.subs.len();
    check_run(ns, assembly.interfaces.len(), loads, run)?;
    let models: Vec<Model> = (0..ns)
        .map(|s| run.scaled_model(&assembly.subs[s].model, s))
        .collect();
    let mut sides: Vec<Vec<SideForces>> = vec![Vec::new(); ns];
    for (spec, ir) in assembly.interfaces.iter().zip(&run.interfaces) {
        check_pairs(spec, ir, ns)?;
        let u = |s: usize| &run.displacements[s];
        let solid = models[spec.sub1].mesh.dim == 3;
        let (refs, face_refs) = if solid {
            let p1 = face_projections(&models[spec.sub1], u(spec.sub1), &spec.group1)?;
            let p2 = face_projections(&models[spec.sub2], u(spec.sub2), &spec.group2)?;
            let [a, b] = average_references(ir, p1, p2);
            ([None, None], [Some(a), Some(b)])
        } else {
            let p1 = facet_projections(&models[spec.sub1], u(spec.sub1), &spec.group1)?;
            let p2 = facet_projections(&models[spec.sub2], u(spec.sub2), &spec.group2)?;
            let [a, b] = average_references(ir, p1, p2);
            ([Some(a), Some(b)], [None, None])
        };
        let group_nodes = side_group_nodes(assembly, spec)?;
        push_sides(spec, ir, &group_nodes, refs, face_refs, &mut sides)?;
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

/// The error estimator of the runs of one assembly, with everything that does not depend on the
/// run computed once (module doc).
#[derive(Debug)]
pub struct LatinEstimator {
    options: CreOptions,
    subs: Vec<DomainEstimator>,
    /// Each interface with the nodes of its two sides' facet groups.
    interfaces: Vec<(InterfaceSpec, [Vec<usize>; 2])>,
}

impl LatinEstimator {
    /// The context of `assembly` (reference materials).
    ///
    /// # Errors
    /// Invalid options, unsupported or degenerate cells, interfaces that refer to missing
    /// substructures or groups.
    pub fn new(assembly: &Assembly, options: &CreOptions) -> Result<Self, CreError> {
        options.validate()?;
        let subs = assembly
            .subs
            .iter()
            .map(|sub| DomainEstimator::new(&sub.model, &sub.constraints, options))
            .collect::<Result<_, _>>()?;
        let interfaces = assembly
            .interfaces
            .iter()
            .map(|spec| {
                if spec.sub1 >= assembly.subs.len() {
                    return Err(CreError::Invalid(format!(
                        "interface '{}' refers to substructure {}",
                        spec.name, spec.sub1
                    )));
                }
                Ok((spec.clone(), side_group_nodes(assembly, spec)?))
            })
            .collect::<Result<_, _>>()?;
        Ok(LatinEstimator {
            options: *options,
            subs,
            interfaces,
        })
    }

    /// The estimator of each substructure.
    pub fn substructures(&self) -> &[DomainEstimator] {
        &self.subs
    }

    /// Bytes of run-independent data held (models and dof maps excluded).
    pub fn cache_bytes(&self) -> usize {
        self.subs
            .iter()
            .map(DomainEstimator::cache_bytes)
            .sum::<usize>()
            + self
                .interfaces
                .iter()
                .map(|(_, [a, b])| 8 * (a.len() + b.len()))
                .sum::<usize>()
    }

    /// Estimates the error of a LATIN run of the assembly; `loads[s]` are the loads of
    /// substructure `s` as functions, load factors folded in. The same result as
    /// [`estimate_latin_direct`] to round-off.
    ///
    /// # Errors
    /// Sizes of the run or loads that do not match the assembly, estimator errors.
    pub fn estimate(&self, loads: &[LoadData], run: &RunResult) -> Result<CreResult, CreError> {
        let ns = self.subs.len();
        check_run(ns, self.interfaces.len(), loads, run)?;
        let mut sides: Vec<Vec<SideForces>> = vec![Vec::new(); ns];
        for ((spec, group_nodes), ir) in self.interfaces.iter().zip(&run.interfaces) {
            check_pairs(spec, ir, ns)?;
            let (s1, s2) = (spec.sub1, spec.sub2);
            let (m1, m2) = (self.subs[s1].model(), self.subs[s2].model());
            let (u1, u2) = (&run.displacements[s1], &run.displacements[s2]);
            let (a1, a2) = (run.young_factors[s1], run.young_factors[s2]);
            let (refs, face_refs) = if m1.mesh.dim == 3 {
                let mut p1 = face_projections(m1, u1, &spec.group1)?;
                let mut p2 = face_projections(m2, u2, &spec.group2)?;
                scale_projections(&mut p1, a1);
                scale_projections(&mut p2, a2);
                let [a, b] = average_references(ir, p1, p2);
                ([None, None], [Some(a), Some(b)])
            } else {
                let mut p1 = facet_projections(m1, u1, &spec.group1)?;
                let mut p2 = facet_projections(m2, u2, &spec.group2)?;
                scale_projections(&mut p1, a1);
                scale_projections(&mut p2, a2);
                let [a, b] = average_references(ir, p1, p2);
                ([Some(a), Some(b)], [None, None])
            };
            push_sides(spec, ir, group_nodes, refs, face_refs, &mut sides)?;
        }
        let mut subs = Vec::with_capacity(ns);
        for (s, est) in self.subs.iter().enumerate() {
            subs.push(est.estimate(
                &loads[s],
                &sides[s],
                &run.displacements[s],
                run.young_factors[s],
            )?);
        }
        let interfaces = run
            .interfaces
            .iter()
            .map(|ir| interface_term(ir, self.options.admissibility_tolerance))
            .collect::<Result<_, _>>()?;
        Ok(CreResult::new(subs, interfaces))
    }
}

/// Multiplies every projection by `alpha` (FE tractions of the reference materials turned into
/// those of the run).
fn scale_projections<K, const D: usize>(p: &mut HashMap<K, Vec<(usize, [f64; D])>>, alpha: f64) {
    if alpha == 1.0 {
        return;
    }
    for list in p.values_mut() {
        for (_, v) in list.iter_mut() {
            for x in v.iter_mut() {
                *x *= alpha;
            }
        }
    }
}

/// Target projections `(node, b)` per facet key (2D: [`FacetProjections`], 3D:
/// [`FaceProjections`]).
type Projections<K, const D: usize> = HashMap<K, Vec<(usize, [f64; D])>>;

/// The key of a facet's partner on the other side of an interface (`partner` the node pairing):
/// the sorted partner nodes, if every node has one.
trait FacetKey: Sized {
    fn partner(&self, partner: &HashMap<usize, usize>) -> Option<Self>;
}

impl FacetKey for [usize; 2] {
    fn partner(&self, partner: &HashMap<usize, usize>) -> Option<Self> {
        let (Some(&a), Some(&b)) = (partner.get(&self[0]), partner.get(&self[1])) else {
            return None;
        };
        Some([a.min(b), a.max(b)])
    }
}

impl FacetKey for Vec<usize> {
    fn partner(&self, partner: &HashMap<usize, usize>) -> Option<Self> {
        let mut key = self
            .iter()
            .map(|n| partner.get(n).copied())
            .collect::<Option<Vec<usize>>>()?;
        key.sort_unstable();
        Some(key)
    }
}

/// Target projections of both sides of an interface (2D facets or 3D faces): the average of the
/// two sides' FE traction projections (side 2's taken with the opposite sign, through the node
/// pairing), so that the two sides' densities are exactly opposite once their nodal forces are
/// (converged LATIN). Facets without a matching facet on the other side keep their own
/// projections.
fn average_references<K: FacetKey + Clone + Eq + std::hash::Hash, const D: usize>(
    ir: &InterfaceResult,
    p1: Projections<K, D>,
    p2: Projections<K, D>,
) -> [Projections<K, D>; 2] {
    if ir.pairing.kind != PairingKind::NodeToNode {
        // Mortar: the facets of the two sides do not correspond; each side keeps its own.
        return [p1, p2];
    }
    let partner: HashMap<usize, usize> = ir.nodes[0]
        .iter()
        .copied()
        .zip(ir.nodes[1].iter().copied())
        .collect();
    let mut r1 = p1.clone();
    let mut r2 = p2.clone();
    for (key, list1) in &p1 {
        let Some(key2) = key.partner(&partner) else {
            continue;
        };
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
                    let avg: [f64; D] = std::array::from_fn(|c| 0.5 * (v1[c] - v2[c]));
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
    [r1, r2]
}
