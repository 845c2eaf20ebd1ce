//! Large sliding: the mortar pairing of a contact interface re-found from the deformed
//! configuration during the solve, until it is the pairing of the solution.
//!
//! **What changes.** The substructures stay linear elastic in their initial configuration
//! `X` (small strains); only the pairing of a contact interface with `Sliding::Large`
//! follows the deformed configuration `y = X + c`, `c` a displacement of every substructure.
//! The mortar pairing ([`crate::mortar`]) is computed on the facets at `y`: segments,
//! weights `m_p`, projection rows `Pi_s(p, a)` and side-1 normals `n_p` are those of the
//! deformed sides. The run then works with total displacements `u` as before, and the
//! unilateral condition holds on the gap in the current configuration
//!
//! ```text
//! g_p = (Pi_2 (X_2 + u_2) - Pi_1 (X_1 + u_1))(p) . n_p + g0(x_p)
//!     = (Pi_2 X_2 - Pi_1 X_1)(p) . n_p  +  [W](p) . n_p  +  g0(x_p),
//! ```
//! so the pairing's geometric gap is `(Pi_2 X_2 - Pi_1 X_1) . n_p` with the rows found at
//! `y` and the initial coordinates (its tangential part, the slide `c` itself, drops out), and
//! the fields `mu(x)`, `g0(x)` are evaluated at the point's initial position
//! `x_p = Pi_P X_P` (`P` the side carrying the points, kept from the first pairing so that
//! points of successive pairings are the same multiplier nodes).
//!
//! **Outer fixed point (per load step).** A step starts with the pairing of a predicted
//! configuration: the one it starts from (the initial one, or the end of the previous step)
//! moved by the change of each substructure's **prescribed translation** (the mean of its
//! prescribed displacement values per component over the nodes that hold it: a block slid by
//! an imposed displacement of its top is predicted slid). The prediction matters: LATIN on a
//! pairing several cells away from the solution converges slowly (measured on the 2D test's
//! 8-cell slide with the pairing of the initial configuration: 10 210 iterations to 1e-6, and
//! "no equilibrium" at the default 2 000, its iterates far from any useful configuration; a
//! cold start on the predicted pairing too: 15 480 iterations to 1e-8), while on the
//! predicted pairing **and** from the predicted state (`W_hat_s = Pi_s c_s`, `F_hat` carried
//! over) it converges as a small slide does (19 iterations). The step is solved by LATIN on
//! that pairing; if the slide since the pairing, `max_p |[W_hat]_t - [Pi c]_t| / h`
//! (module [`crate::sliding`]; `h` the median point size of the interface: a point at the
//! edge of the covered zone may carry a sliver of weight, and its own size says nothing of the
//! mesh), exceeds `tolerance` (default 0.01 of the mesh size), the interface is re-paired in
//! the configuration of that solution and the step solved again, warm-started from it, until
//! the slide since the last pairing is below the tolerance (the pairing is then that of the
//! solution) or `max_pairings` pairings were made. A solve that does not converge ends the
//! step with its status (its iterate is no configuration to re-pair in). A step whose
//! pairing did not settle is reported **not converged** (its equilibrium is that of a pairing
//! the solution no longer fits). A slide that no prescribed displacement drives (a load
//! pushing a part beyond its friction limit, elastic slip) is not predicted: its first solve is
//! on the pairing of the start configuration, and is the predictor of the second (measured on a
//! block stretched 9 cells over the base by a load, `tests/large_sliding_load.rs`: 2 pairings,
//! 62 + 147 iterations). LATIN itself is the limit there: with a block 2 100 times softer than
//! the base the first solve takes 3 469 iterations and the second does not converge in 20 000,
//! and a floating block in gross slip held by a bonded layer does not converge even with small
//! sliding.
//!
//! Why a fixed point around the solve rather than re-pairing at step boundaries with
//! sub-steps: the answer of a step must not depend on how many sub-steps the user chose
//! (friction is already integrated with one backward-Euler increment per step, module
//! [`crate::steps`], and the user writes more `[[step]]`s to follow a path); the fixed point
//! gives the pairing of the step's end configuration whatever the slide, and its passes after
//! the first start from the previous pass and cost few iterations (measured on the 0.8 mm
//! slides of the tests: the predicted pairing settles at once, 11 - 22 iterations; with a
//! tolerance of 1e-5, 2 pairings and 46 iterations). Its cost is one set-up (assembly and
//! factorisation) per pairing. What it does not see: side-2 material swept over *within* one step (a point that
//! crosses a groove and leaves it in the same step never sees it); a path is followed by
//! steps.
//!
//! **Friction state.** The state a step starts from is mapped to each pairing: `W_hat_s =
//! Pi_s u_s` with the displacement `u` at the end of the previous step, so the slip origin of
//! the incremental law, `j0 = [W_hat]_t` ([`crate::steps`]), is the tangential jump of that
//! displacement between the material points the new pairing pairs; `F_hat` is carried over at
//! the points of the same multiplier node (same initial position), zero at new points.
//!
//! **Warm start of a re-pairing.** A pass after the first starts from the previous pass's
//! displacement on the new pairing, `W_hat_s = Pi_s u_s`. Its `F_hat` is carried over (same
//! material point) when the slide since the last pairing stayed within half a cell
//! ([`crate::sliding::SMALL_SLIDING_LIMIT`]: the points still face the material whose forces
//! they carry), and is zero otherwise (after a slide over cells the force at a material point
//! belongs to another contact zone: a base point the block left keeps its pressure). Measured
//! (all the cases measured, so the rule is chosen on them): the second pass of a soft block
//! stretched 9 cells over the base by a load (`tests/large_sliding_load.rs`) takes 332
//! iterations with `F_hat` carried, 147 with zero; with E x 10, 120 and 57; a re-pairing after
//! a slide of 5e-4 cells (the 8-cell slide at a pairing tolerance of 1e-5) takes 27 and 25 at a
//! LATIN tolerance of 1e-8, but at 1e-6 2 pairings and 29 iterations in all carried against 3
//! and 35 with zero. A cold start is worse (20 000 iterations, not converged, on the latter).

use std::collections::HashMap;
use std::sync::Arc;

use alea_fem::DofMap;
use alea_mesh::Mesh;
use alea_mesh::vec3::{dot, sub};

use crate::interface::InterfacePairing;
use crate::mortar::pair_mortar_sided;
use crate::sliding::point_slides;
use crate::{
    Assembly, InterfaceSpec, LatinError, LatinOptions, LatinSolver, LocalState, RunInput,
    RunResult, RunStatus, Sliding,
};

type V3 = [f64; 3];

/// Settings of the outer fixed point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Repairing {
    /// Largest slide since the last pairing, over the median point size of the interface, for
    /// the pairing to be that of the solution (default 0.01).
    pub tolerance: f64,
    /// Largest number of pairings per step (default 10).
    pub max_pairings: usize,
}

impl Default for Repairing {
    fn default() -> Self {
        Repairing {
            tolerance: 0.01,
            max_pairings: 10,
        }
    }
}

/// One load step solved with large sliding.
pub struct SlidingStep {
    /// The solver of the last pairing (its interfaces are those of `result`).
    pub solver: LatinSolver,
    /// The run of the last pairing; not converged if the pairing did not settle.
    pub result: RunResult,
    /// Pairings made in this step (1: the pairing it started with was the solution's).
    pub pairings: usize,
    /// Slide since the last pairing over the median point size, largest over the re-paired
    /// interfaces (0 if there is none).
    pub mismatch: f64,
    /// True if `mismatch <= tolerance`.
    pub pairing_settled: bool,
    /// LATIN iterations summed over the pairings.
    pub iterations: usize,
    /// Set-up seconds (pairing, assembly, factorisation) summed over the pairings.
    pub setup_seconds: f64,
    /// Side carrying the points of each re-paired interface (0 or 1; `None`: not re-paired).
    pub point_sides: Vec<Option<usize>>,
    /// The prescribed translation of every substructure in this step (the predictor, module
    /// doc).
    pub translation: Vec<[f64; 3]>,
}

/// True if interface `spec` is re-paired (large sliding on a contact law).
pub fn is_repaired(spec: &InterfaceSpec) -> bool {
    spec.sliding == Sliding::Large && spec.law.uses_gap()
}

/// True if some interface of `assembly` is re-paired.
pub fn uses_large_sliding(assembly: &Assembly) -> bool {
    assembly.interfaces.iter().any(is_repaired)
}

/// The mortar pairing of interface `i` of `assembly` found in the configuration `X + u`
/// (`u[s]`: node-major displacement of substructure `s`), with the points on `point_side`
/// (`None`: the coarser side), expressed for a run in total displacements (module doc):
/// initial positions `x_p = Pi_P X_P` and geometric gaps `(Pi_2 X_2 - Pi_1 X_1) . n_p`. Returns
/// the pairing and the side carrying its points.
///
/// # Errors
/// A displacement of the wrong length, or the errors of [`pair_mortar_sided`].
pub fn pair_in_configuration(
    assembly: &Assembly,
    i: usize,
    u: &[Vec<f64>],
    point_side: Option<usize>,
) -> Result<(InterfacePairing, usize), LatinError> {
    let spec = &assembly.interfaces[i];
    let subs = [spec.sub1, spec.sub2];
    let mut moved: Vec<Mesh> = Vec::with_capacity(2);
    let mut held: Vec<DofMap> = Vec::with_capacity(2);
    for &s in &subs {
        let sub = assembly.subs.get(s).ok_or_else(|| {
            LatinError::Invalid(format!(
                "interface '{}' refers to substructure {s}, but there are {}",
                spec.name,
                assembly.subs.len()
            ))
        })?;
        let mut mesh = sub.model.mesh.clone();
        let d = mesh.dim;
        let us = u.get(s).filter(|v| v.len() == mesh.num_nodes() * d);
        let us = us.ok_or_else(|| {
            LatinError::Invalid(format!(
                "interface '{}': no displacement of {} values for substructure '{}' to re-pair in",
                spec.name,
                mesh.num_nodes() * d,
                sub.name
            ))
        })?;
        for (n, x) in mesh.coords.iter_mut().enumerate() {
            for k in 0..d {
                x[k] += us[n * d + k];
            }
        }
        moved.push(mesh);
        held.push(
            DofMap::for_mesh(&sub.model.mesh, &sub.constraints).map_err(|source| {
                LatinError::Fem {
                    sub: sub.name.clone(),
                    source,
                }
            })?,
        );
    }
    let fixed1 = |n: usize| held[0].node_dofs(n).is_empty();
    let fixed2 = |n: usize| held[1].node_dofs(n).is_empty();
    let th = |s: usize| assembly.subs[subs[s]].model.analysis.thickness();
    let (mut pairing, side) = pair_mortar_sided(
        &spec.name,
        [
            (&moved[0], spec.group1.as_str(), th(0)),
            (&moved[1], spec.group2.as_str(), th(1)),
        ],
        spec.search_distance,
        true,
        [&fixed1, &fixed2],
        point_side,
    )?;
    let initial = |s: usize, p: usize| -> V3 {
        let coords = &assembly.subs[subs[s]].model.mesh.coords;
        let mut x = [0.0; 3];
        for (a, c) in pairing.sides[s].row(p) {
            for k in 0..3 {
                x[k] += c * coords[a][k];
            }
        }
        x
    };
    let (x, gap): (Vec<V3>, Vec<f64>) = (0..pairing.len())
        .map(|p| {
            let (x1, x2) = (initial(0, p), initial(1, p));
            let xp = if side == 0 { x1 } else { x2 };
            (xp, dot(&sub(&x2, &x1), &pairing.normals[p]))
        })
        .unzip();
    pairing.x = x;
    pairing.geometric_gap = gap;
    Ok((pairing, side))
}

/// A solver for `assembly` with its re-paired interfaces paired in the configuration `X + u`
/// (`point_sides` updated with the side carrying their points).
fn solver_in(
    assembly: &Assembly,
    options: &LatinOptions,
    u: &[Vec<f64>],
    point_sides: &mut [Option<usize>],
) -> Result<LatinSolver, LatinError> {
    let mut pairings = Vec::with_capacity(assembly.interfaces.len());
    for (i, spec) in assembly.interfaces.iter().enumerate() {
        if is_repaired(spec) {
            let (p, side) = pair_in_configuration(assembly, i, u, point_sides[i])?;
            point_sides[i] = Some(side);
            pairings.push(Some(p));
        } else {
            pairings.push(None);
        }
    }
    LatinSolver::with_pairings(
        assembly.clone(),
        options.clone(),
        pairings,
        Some(u.to_vec()),
    )
}

/// A local-stage state on the interfaces of `solver`: `W_hat_s = Pi_s u_s` with the
/// displacement `u`, `F_hat` of the point of `from` (a run on other pairings) at the same
/// initial position (zero if none, or without `from`: the warm start of a re-pairing, module
/// doc).
fn mapped_state(solver: &LatinSolver, u: &[Vec<f64>], from: Option<&RunResult>) -> LocalState {
    let mut what = Vec::with_capacity(solver.num_interfaces());
    let mut fhat = Vec::with_capacity(solver.num_interfaces());
    for i in 0..solver.num_interfaces() {
        let pairing = solver.interface_pairing(i);
        let (subs, _) = solver.interface_nodes(i);
        let w = [0, 1].map(|s| {
            let dim = solver.model(subs[s]).mesh.dim;
            pairing.sides[s].interpolate(&u[subs[s]], dim)
        });
        let key = |x: &V3| x.map(f64::to_bits);
        let old = from.and_then(|r| r.interfaces.get(i));
        let index: HashMap<[u64; 3], usize> = old.map_or_else(HashMap::new, |it| {
            it.points
                .iter()
                .enumerate()
                .map(|(q, p)| (key(&p.x), q))
                .collect()
        });
        let f = [0, 1].map(|s| {
            pairing
                .x
                .iter()
                .map(|x| match (old, index.get(&key(x))) {
                    (Some(it), Some(&q)) => it.fhat[s][q],
                    _ => [0.0; 3],
                })
                .collect::<Vec<V3>>()
        });
        what.push(w);
        fhat.push(f);
    }
    LocalState { what, fhat }
}

/// The largest slide since the last pairing over the re-paired interfaces of `assembly`, each
/// over its median point size (module doc).
fn mismatch(assembly: &Assembly, solver: &LatinSolver, res: &RunResult) -> f64 {
    let mut worst = 0.0f64;
    for (i, spec) in assembly.interfaces.iter().enumerate() {
        if !is_repaired(spec) {
            continue;
        }
        let slides = point_slides(solver, res, i);
        let mut h: Vec<f64> = slides.iter().map(|s| s.2).collect();
        h.sort_by(f64::total_cmp);
        let Some(&median) = h.get(h.len() / 2) else {
            continue;
        };
        let slip = slides.iter().map(|s| s.1).fold(0.0, f64::max);
        worst = worst.max(slip / median);
    }
    worst
}

/// Solves one load step of `assembly` (this step's imposed displacements and loads: `input`)
/// with large sliding (module doc), from the end of step `start` (`None`: the unloaded
/// initial configuration). `input.previous_step` and `input.initial` are set here.
///
/// # Errors
/// A pairing or set-up error, or an invalid input.
pub fn run_step(
    assembly: &Assembly,
    options: &LatinOptions,
    settings: &Repairing,
    start: Option<&SlidingStep>,
    input: &RunInput,
) -> Result<SlidingStep, LatinError> {
    if !(settings.tolerance > 0.0 && settings.max_pairings >= 1) {
        return Err(LatinError::Invalid(format!(
            "large sliding: tolerance must be > 0 and at least one pairing allowed, got {} and {}",
            settings.tolerance, settings.max_pairings
        )));
    }
    let translation = prescribed_translation(assembly)?;
    if let Some(s) = start {
        let same = s.result.displacements.len() == assembly.subs.len()
            && assembly
                .subs
                .iter()
                .zip(&s.result.displacements)
                .all(|(sub, u)| u.len() == sub.model.mesh.num_nodes() * sub.model.mesh.dim);
        if !same {
            return Err(LatinError::Invalid(
                "large sliding: the step's substructures differ from those of the step it \
                 starts from"
                    .into(),
            ));
        }
    }
    let mut sides = start.map_or_else(
        || vec![None; assembly.interfaces.len()],
        |s| s.point_sides.clone(),
    );
    // Predicted configuration: the start one moved by the change of the prescribed translation.
    let config: Vec<Vec<f64>> = assembly
        .subs
        .iter()
        .enumerate()
        .map(|(k, sub)| {
            let d = sub.model.mesh.dim;
            let n = sub.model.mesh.num_nodes();
            (0..n * d)
                .map(|i| {
                    let c = i % d;
                    let from =
                        start.map_or(0.0, |s| s.result.displacements[k][i] - s.translation[k][c]);
                    from + translation[k][c]
                })
                .collect()
        })
        .collect();
    let mut solver = solver_in(assembly, options, &config, &mut sides)?;
    let previous = |solver: &LatinSolver| {
        start.map(|s| {
            Arc::new(mapped_state(
                solver,
                &s.result.displacements,
                Some(&s.result),
            ))
        })
    };
    let mut input = input.clone();
    input.previous_step = previous(&solver);
    // The first solve starts from the predicted configuration (module doc).
    input.initial = Some(Arc::new(mapped_state(
        &solver,
        &config,
        start.map(|s| &s.result),
    )));
    let (mut pairings, mut iterations, mut setup) = (1, 0, solver.setup_seconds);
    loop {
        let mut result = solver.run_shared(&input)?;
        iterations += result.iterations;
        let gap = mismatch(assembly, &solver, &result);
        let settled = gap <= settings.tolerance;
        if result.status == RunStatus::Converged && !settled && pairings < settings.max_pairings {
            // Re-pair in the configuration of this solution and solve again from it.
            let u = result.displacements.clone();
            solver = solver_in(assembly, options, &u, &mut sides)?;
            setup += solver.setup_seconds;
            pairings += 1;
            input.previous_step = previous(&solver);
            // Warm start: the solution's displacement on the new pairing; `F_hat` carried over
            // only if the slide since the last pairing stayed within half a cell (module doc).
            let carry = gap <= crate::sliding::SMALL_SLIDING_LIMIT;
            let from = carry.then_some(&result);
            input.initial = Some(Arc::new(mapped_state(&solver, &u, from)));
            continue;
        }
        if result.status == RunStatus::Converged && !settled {
            result.status = RunStatus::NotConverged;
        }
        return Ok(SlidingStep {
            solver,
            result,
            pairings,
            mismatch: gap,
            pairing_settled: settled,
            iterations,
            setup_seconds: setup,
            point_sides: sides,
            translation,
        });
    }
}

/// The mean prescribed displacement of every substructure, per component, over the nodes
/// whose constraints hold that component (0 where none does): the rigid translation that
/// predicts the configuration of a step (module doc).
fn prescribed_translation(assembly: &Assembly) -> Result<Vec<[f64; 3]>, LatinError> {
    assembly
        .subs
        .iter()
        .map(|sub| {
            let dofs = DofMap::for_mesh(&sub.model.mesh, &sub.constraints).map_err(|source| {
                LatinError::Fem {
                    sub: sub.name.clone(),
                    source,
                }
            })?;
            let dim = sub.model.mesh.dim;
            let (mut sum, mut count) = ([0.0; 3], [0usize; 3]);
            for n in 0..sub.model.mesh.num_nodes() {
                if dofs.is_free_node(n) {
                    continue;
                }
                let value = dofs.prescribed(n);
                for c in 0..dim {
                    let mut e = [0.0; 3];
                    e[c] = 1.0;
                    if dofs.constrained_part(n, e)[c] > 0.5 {
                        sum[c] += value[c];
                        count[c] += 1;
                    }
                }
            }
            Ok([0, 1, 2].map(|c| {
                if count[c] > 0 {
                    sum[c] / count[c] as f64
                } else {
                    0.0
                }
            }))
        })
        .collect()
}

/// Runs a load history with large sliding: step `k` is `steps[k] = (assembly, input)` (the
/// assemblies share meshes and interfaces and may differ by their imposed displacements),
/// solved by [`run_step`] from the end of step `k - 1`. Stops after the first step that is
/// not converged.
///
/// # Errors
/// As [`run_step`].
pub fn run_history(
    steps: &[(&Assembly, RunInput)],
    options: &LatinOptions,
    settings: &Repairing,
) -> Result<Vec<SlidingStep>, LatinError> {
    let mut out: Vec<SlidingStep> = Vec::with_capacity(steps.len());
    for (assembly, input) in steps {
        if out
            .last()
            .is_some_and(|s| s.result.status != RunStatus::Converged)
        {
            break;
        }
        let step = run_step(assembly, options, settings, out.last(), input)?;
        out.push(step);
    }
    Ok(out)
}

/// The slip origin `j0` of every point of every interface of `step`: `[Pi u]_t`, the
/// tangential jump, between the points the step's last pairing pairs, of the displacement `u`
/// at the end of `previous` (`None`: the unloaded state, `j0 = 0`), as the incremental law of
/// the step measured it (module doc, "Friction state"). The counterpart of
/// [`crate::steps::step_origins`] for re-paired interfaces.
pub fn step_origins(step: &SlidingStep, previous: Option<&SlidingStep>) -> Vec<Vec<V3>> {
    step.result
        .interfaces
        .iter()
        .map(|it| {
            let Some(p) = previous else {
                return vec![[0.0; 3]; it.points.len()];
            };
            let u = [0, 1].map(|s| {
                let sub = it.subs[s];
                let dim = step.solver.model(sub).mesh.dim;
                it.pairing.sides[s].interpolate(&p.result.displacements[sub], dim)
            });
            (0..it.points.len())
                .map(|q| crate::steps::tangential(u[0][q], u[1][q], it.points[q].normal))
                .collect()
        })
        .collect()
}

/// Energy dissipated by friction within step `step` on interface `i`:
/// `-int ([W_hat] - j0)_t . Phi_t dS`, as [`crate::steps::step_friction_dissipation`] but with
/// `j0` of [`step_origins`].
pub fn step_friction_dissipation(
    step: &SlidingStep,
    previous: Option<&SlidingStep>,
    i: usize,
) -> f64 {
    let origins = step_origins(step, previous);
    step.result.interfaces[i].step_friction_dissipation(&origins[i])
}
