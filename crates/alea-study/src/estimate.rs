//! The stochastic error estimate of a study's surrogate (thesis 3.2, 4.1; crate
//! `alea-estimate`): the estimator built from the stored runs, the integration rule, the
//! indicators `e~`, `I_geo`, `I_sto` per entity, and the error-density maps.
//!
//! **Expectations.** The substructure terms are quadratic forms in the surrogate's weights
//! (Gram matrices of the runs' stress samples); the interface terms are not (norm of the
//! interpolated slip, projection on the Coulomb disk of `mu(xi)`). Every term is integrated with
//! one rule: per integration cell a tensor Gauss-Legendre rule of `points_per_cell` points per
//! parameter, weighted by the joint density. The cells are the stochastic mesh's for
//! piecewise-linear and adaptive methods (the rule then follows the kinks of the weights), and a
//! regular partition of the parameter box for global surrogates (`cells_per_dim`). The
//! substructure part is exact for polynomial weights times the density on each cell; the
//! interface part converges with the cells.
//!
//! **Admissibility.** The interpolated fields are admissible for the loads at `xi` only if the
//! surrogate reproduces the load factors; [`SurrogateEstimate::load_defect`] reports the largest
//! relative error of that reproduction on the rule (0 for load factors affine in the
//! parameters), and [`alea_estimate::Estimate::violation_probability`] the probability of points
//! where the interpolated interface fields leave the admissible set (negative gap or normal
//! force). Either makes the estimate no longer a guaranteed bound; both are reported.

use std::time::Instant;

use alea_estimate::density::{PairMap, pair_maps};
use alea_estimate::rule::{CellBox, Rule};
use alea_estimate::{
    Estimate, Estimator, EstimatorOptions, InterfaceVectors, RunSource, Weights, load_defect,
    sub_cell_terms,
};
use alea_latin::LatinSolver;
use alea_latin::interface::{distribute_to_cells, facet_shares};

use crate::StudyError;
use crate::cre::{CreRecord, CreSetup, StudyParameters};
use crate::method::{Method, Surrogate};
use crate::store::Store;
use crate::study::Study;

pub use crate::error_settings::ErrorSettings;

/// Reads and checks the `[error]` table of a loaded study (defaults when absent).
///
/// # Errors
/// [`StudyError::Input`] naming the bad field.
pub fn error_settings(study: &Study) -> Result<ErrorSettings, StudyError> {
    crate::error_settings::read(
        &study.source,
        study.file.error.as_ref(),
        study.params.names.len(),
    )
}

/// The error estimate of one surrogate.
#[derive(Clone, Debug)]
pub struct SurrogateEstimate {
    /// Expectations per entity and in total.
    pub estimate: Estimate,
    /// Runs the surrogate is built on.
    pub runs: usize,
    /// Points of the integration rule.
    pub rule_points: usize,
    /// The integration cells, in the order of their tags in `estimate.cells`.
    pub cells: Vec<(usize, CellBox)>,
    /// Largest relative error of the surrogate's reproduction of the load factors on the rule.
    pub load_defect: f64,
    /// False when some substructure has no admissible-stress construction (3D): interfaces
    /// only.
    pub substructures_estimated: bool,
    /// Seconds to build the estimator and integrate.
    pub seconds: f64,
}

/// Builds the estimator of the runs at `points` (converged, with their error estimates in the
/// store; surrogate run order), substructure by substructure to bound memory
/// ([`Estimator::from_runs`]).
///
/// # Errors
/// [`StudyError::NoEstimate`], [`StudyError::DamagedEstimate`] or
/// [`StudyError::StaleEstimate`] if a run lacks its stored estimate or does not match the model.
pub fn build_estimator(
    setup: &CreSetup,
    solver: &LatinSolver,
    store: &Store,
    points: &[Vec<f64>],
    params: &dyn alea_estimate::Parameters,
) -> Result<Estimator, StudyError> {
    let runs = stored_runs(setup, solver, store, points, true)?;
    Estimator::from_runs(
        setup.layout.clone(),
        &runs,
        points,
        params,
        EstimatorOptions {
            admissibility_tolerance: setup.options.admissibility_tolerance,
        },
    )
}

/// The integration rule of a method (module doc): its cells and the rule.
///
/// # Errors
/// Size or law errors of the rule.
pub fn integration_rule(
    study: &Study,
    method: &Method,
    settings: &ErrorSettings,
) -> Result<(Vec<(usize, CellBox)>, Rule), StudyError> {
    let params = &study.params;
    let cells: Vec<(usize, CellBox)> = match method.stochastic_mesh(params) {
        Some(mesh) => mesh
            .leaves()
            .into_iter()
            .map(|c| (c, mesh.cell_bounds(c)))
            .collect(),
        None => Rule::regular_cells(&params.lo, &params.hi, settings.cells_per_dim)
            .map_err(StudyError::from)?
            .into_iter()
            .enumerate()
            .collect(),
    };
    let boxes: Vec<CellBox> = cells.iter().map(|c| c.1.clone()).collect();
    let tags: Vec<usize> = cells.iter().map(|c| c.0).collect();
    let rule = Rule::on_cells(
        &boxes,
        &tags,
        settings.points_per_cell,
        params.joint.as_ref(),
    )
    .map_err(|error| StudyError::MethodRule {
        method: method.label.clone(),
        error,
    })?;
    Ok((cells, rule))
}

/// The stored error estimates and displacement fields of the runs at `points`
/// (`restart_hint`: a missing estimate's message says to run again with `--restart`).
fn stored_runs<'a>(
    setup: &'a CreSetup,
    solver: &'a LatinSolver,
    store: &Store,
    points: &[Vec<f64>],
    restart_hint: bool,
) -> Result<StoredRuns<'a>, StudyError> {
    let mut records = Vec::with_capacity(points.len());
    let mut fields = Vec::with_capacity(points.len());
    for p in points {
        let values = store.cre(p)?.ok_or_else(|| StudyError::NoEstimate {
            params: p.clone(),
            restart_hint,
        })?;
        let rec = CreRecord::from_values(&values)
            .ok_or_else(|| StudyError::DamagedEstimate { params: p.clone() })?;
        records.push(rec);
        fields.push(store.fields(p)?);
    }
    Ok(StoredRuns {
        setup,
        solver,
        records,
        fields,
    })
}

/// The stored runs of a method as the estimator reads them: each run's CRE record and
/// displacement fields, sampled through the estimator set-up ([`CreSetup::sub_samples`]).
struct StoredRuns<'a> {
    setup: &'a CreSetup,
    solver: &'a LatinSolver,
    records: Vec<CreRecord>,
    fields: Vec<Vec<f64>>,
}

impl RunSource for StoredRuns<'_> {
    type Error = StudyError;

    fn num_runs(&self) -> usize {
        self.records.len()
    }

    fn young(&self, k: usize, s: usize) -> Result<f64, StudyError> {
        self.records[k]
            .young
            .get(s)
            .copied()
            .ok_or(StudyError::StaleEstimate {
                restart_hint: false,
            })
    }

    fn samples(&self, k: usize, s: usize) -> Result<(Vec<f64>, Vec<f64>), StudyError> {
        self.setup
            .sub_samples(self.solver, s, &self.records[k], &self.fields[k])
    }

    fn interface_fields(&self, k: usize) -> (InterfaceVectors, InterfaceVectors) {
        let r = &self.records[k];
        (r.jump.clone(), r.force.clone())
    }
}

/// What the stochastic error of one method is computed from: the study, its estimator set-up
/// and solver, the store of its runs, the method, the converged runs `points` its surrogate
/// `sur` is built on, and the `[error]` settings.
#[derive(Clone, Copy)]
pub struct MethodEstimateInput<'a> {
    /// The study.
    pub study: &'a Study,
    /// The estimator set-up of its substructures.
    pub setup: &'a CreSetup,
    /// The LATIN solver the runs were made with.
    pub solver: &'a LatinSolver,
    /// The store holding the runs' records and fields.
    pub store: &'a Store,
    /// The method.
    pub method: &'a Method,
    /// The converged runs the surrogate is built on.
    pub points: &'a [Vec<f64>],
    /// The method's surrogate.
    pub sur: &'a Surrogate,
    /// The `[error]` settings.
    pub settings: &'a ErrorSettings,
}

/// The stochastic error of `method`'s surrogate `sur` built on the converged runs `points`.
///
/// # Errors
/// As [`build_estimator`] and [`integration_rule`].
pub fn estimate_method(
    input: &MethodEstimateInput<'_>,
) -> Result<(Estimator, SurrogateEstimate), StudyError> {
    let t0 = Instant::now();
    let params = StudyParameters::new(&input.study.model.parametric, input.solver);
    let est = build_estimator(
        input.setup,
        input.solver,
        input.store,
        input.points,
        &params,
    )?;
    let (cells, rule) = integration_rule(input.study, input.method, input.settings)?;
    let estimate = est.expectation(&rule, input.sur, &params);
    let load_defect = load_defect(
        &rule,
        input.sur,
        input.points,
        input
            .study
            .model
            .parametric
            .load_factors
            .iter()
            .flatten()
            .map(|e| |x: &[f64]| e.eval(x)),
    );
    Ok((
        est,
        SurrogateEstimate {
            estimate,
            runs: input.points.len(),
            rule_points: rule.len(),
            cells,
            load_defect,
            substructures_estimated: input.setup.substructures_estimated(),
            seconds: t0.elapsed().as_secs_f64(),
        },
    ))
}

/// Largest work of the error-density maps, in interface-point x weight products (one evaluation
/// of the pointwise estimate costs about `sum_i points_i x nnz(w) + sum_s nnz(w)^2`).
pub const MAP_WORK: f64 = 2e8;

/// Error-density maps of a method over every pair of parameters (crate `alea-estimate`,
/// module `density`), within a work budget: at most 400 000 evaluations and at most
/// [`MAP_WORK`] point-weight products (measured on the 3D turbine: 345 600 evaluations of
/// 962 interface points x 16 weights took 41 s, 53 % of the study; the budget keeps the maps
/// near 2 s there). When the budget is short the grid has fewer than `map_points` cells per
/// parameter (never fewer than 8): the map is a picture of where the error sits, not a number
/// the estimate depends on. Deterministic (the budget depends on the model's sizes only).
///
/// # Errors
/// Size errors of the maps.
pub fn density_maps(
    study: &Study,
    solver: &LatinSolver,
    est: &Estimator,
    sur: &Surrogate,
    settings: &ErrorSettings,
) -> Result<Vec<PairMap>, StudyError> {
    let params = StudyParameters::new(&study.model.parametric, solver);
    let d = study.params.lo.len();
    // Weights at a few generic (non-dyadic) points: the most runs a point depends on.
    let mut w = Vec::new();
    let mut nnz = 1usize;
    for t in [0.137, 0.371, 0.629, 0.863] {
        let xi: Vec<f64> = study
            .params
            .lo
            .iter()
            .zip(&study.params.hi)
            .map(|(a, b)| a + t * (b - a))
            .collect();
        Weights::weights(sur, &xi, &mut w);
        nnz = nnz.max(w.len());
    }
    let nnz = nnz as f64;
    let points: usize = (0..solver.num_interfaces())
        .map(|i| solver.interface_points(i).len())
        .sum();
    let work = points as f64 * nnz + solver.num_subs() as f64 * nnz * nnz;
    let budget = (MAP_WORK / work.max(1.0)).clamp(2_000.0, 400_000.0) as usize;
    let pairs = (d * d.saturating_sub(1) / 2).max(1);
    let inner = 2usize.pow(d.saturating_sub(2) as u32);
    let n_fit = ((budget / (pairs * inner)) as f64).sqrt().floor() as usize;
    let n = settings.map_points.min(n_fit.max(8));
    pair_maps(
        est,
        sur,
        &params,
        study.params.joint.as_ref(),
        &study.params.lo,
        &study.params.hi,
        n,
        budget,
    )
    .map_err(StudyError::from)
}

/// The interface error terms per cell: each interface point's `[E[m_p rho*(w~, F~)],
/// E[m_p sum_k w_k rho_k,p]]` (`per_point`, from [`Estimator::interface_point_terms`]) divided by its
/// weight `m_p` is a density at the point's node on each side; a cell whose facets lie on the
/// interface side gets that density times the lumped share of its facets at the node
/// ([`alea_latin::interface::facet_shares`]). Returns per substructure and cell `[e, geo,
/// interface measure of its facets]`; over the cells of one side the `e` (and `geo`) add up to
/// the interface's `e2` (`geo2`) when that side's lumped weights are the points' (node-to-node
/// pairing of matching sides). The error map of 3D substructures, which carry no admissible
/// stress, cell by cell.
///
/// # Errors
/// A facet group of an interface missing from its substructure's mesh.
pub fn interface_cell_terms(
    study: &Study,
    solver: &LatinSolver,
    per_point: &[Vec<[f64; 2]>],
) -> Result<Vec<Vec<[f64; 3]>>, StudyError> {
    let ns = solver.num_subs();
    let mut cells: Vec<Vec<[f64; 3]>> = (0..ns)
        .map(|s| vec![[0.0; 3]; solver.model(s).mesh.num_cells()])
        .collect();
    for (i, terms) in per_point.iter().enumerate() {
        let spec = &study.model.assembly.interfaces[i];
        let weights = solver.interface_weights(i);
        let (subs, nodes) = solver.interface_nodes(i);
        for (side, group) in [&spec.group1, &spec.group2].into_iter().enumerate() {
            let s = subs[side];
            let model = solver.model(s);
            let facets =
                facet_shares(&model.mesh, group, model.analysis.thickness()).map_err(|error| {
                    StudyError::InterfaceFacets {
                        interface: spec.name.clone(),
                        sub: solver.sub_name(s).to_string(),
                        error: Box::new(error),
                    }
                })?;
            distribute_to_cells(facets, &nodes[side], terms, weights, &mut cells[s]);
        }
    }
    Ok(cells)
}

/// Writes the mean error density of a method for ParaView (`<dir>/paraview/error.vtm`, one
/// `.vtu` per substructure). Per cell of every substructure with admissible stresses:
/// `space_error_density` `= E[geo_E^2] / |E|` (the thesis's `I_geo` per unit area: where to
/// refine the space mesh), `error_density` `= E[e_E^2] / |E|`, and the per-cell values
/// themselves (the moments of the weights come from the method's integration rule, so the cells
/// add up to the estimate's substructure terms). On the interface nodes of both sides, per unit
/// interface measure: `interface_error_density` `= E[m_p rho*(w~, F~)] / m_p`,
/// `interface_space_error_density` (the runs' own interface errors interpolated) and
/// `interface_stochastic_error_density` (their difference; crate `alea-estimate`, "Interfaces"); per cell, the same interface terms distributed to the cells
/// whose facets carry them ([`interface_cell_terms`]: `interface_cell_error`,
/// `interface_cell_space_error`, `interface_cell_stochastic_error`, and
/// `interface_cell_error_density` per unit interface measure) - the only error fields of
/// substructures without admissible stresses (3D: interface part only). `est`: the method's estimator if at hand (else it is
/// rebuilt from the store). Returns the path, or `None` when there is nothing to map.
///
/// # Errors
/// Store, sample or write errors.
pub fn write_error_fields(
    input: &MethodEstimateInput<'_>,
    est: Option<&Estimator>,
    dir: &std::path::Path,
) -> Result<Option<std::path::PathBuf>, StudyError> {
    let MethodEstimateInput {
        study,
        setup,
        solver,
        store,
        method,
        points,
        sur,
        settings,
    } = *input;
    use alea_mesh::vtu::{VtuWriter, write_vtm};
    let ns = solver.num_subs();
    let estimated: Vec<bool> = setup.layout.subs.iter().map(|l| l.is_estimated()).collect();
    if !estimated.contains(&true) && solver.num_interfaces() == 0 {
        return Ok(None);
    }
    let (_, rule) = integration_rule(study, method, settings)?;
    let params = StudyParameters::new(&study.model.parametric, solver);
    let mut cell_fields: Vec<Option<[Vec<f64>; 4]>> = vec![None; ns];
    if estimated.contains(&true) {
        let moments = alea_estimate::weight_moments(&rule, sur, &params, ns, points.len());
        let runs = stored_runs(setup, solver, store, points, false)?;
        for s in (0..ns).filter(|&s| estimated[s]) {
            let terms = sub_cell_terms(&runs, s, &setup.layout.subs[s].cell_offsets, &moments[s])?;
            let model = solver.model(s);
            let th = model.analysis.thickness();
            let area: Vec<f64> = (0..model.mesh.num_cells())
                .map(|c| model.mesh.cell_measure(c) * th)
                .collect();
            let per = |v: &dyn Fn(&(f64, f64)) -> f64| -> Vec<f64> {
                terms.iter().map(|t| v(t).max(0.0)).collect()
            };
            let geo = per(&|t| t.0);
            let tot = per(&|t| t.1);
            let density = |v: &[f64]| -> Vec<f64> {
                v.iter()
                    .zip(&area)
                    .map(|(g, a)| if *a > 0.0 { g / a } else { 0.0 })
                    .collect()
            };
            cell_fields[s] = Some([density(&geo), density(&tot), geo, tot]);
        }
    }
    // Interface densities on the interface nodes of both sides (0 elsewhere).
    let built;
    let est = match est {
        Some(e) => e,
        None => {
            built = build_estimator(setup, solver, store, points, &params)?;
            &built
        }
    };
    let per_point = est.interface_point_terms(&rule, sur, &params);
    let iface_cells = interface_cell_terms(study, solver, &per_point)?;
    let mut node_fields: Vec<[Vec<f64>; 3]> = (0..ns)
        .map(|s| {
            let n = solver.model(s).mesh.num_nodes();
            [vec![0.0; n], vec![0.0; n], vec![0.0; n]]
        })
        .collect();
    for (i, terms) in per_point.iter().enumerate() {
        let weights = solver.interface_weights(i);
        let (subs, nodes) = solver.interface_nodes(i);
        for side in 0..2 {
            let f = &mut node_fields[subs[side]];
            for (p, (&node, t)) in nodes[side].iter().zip(terms).enumerate() {
                let m = weights[p];
                if m > 0.0 {
                    f[0][node] = t[0] / m;
                    f[1][node] = t[1] / m;
                    f[2][node] = (t[0] - t[1]) / m;
                }
            }
        }
    }
    // Per cell: the interface error of its facets, its space and stochastic parts, and the
    // error per unit interface measure (0 off the interfaces).
    let cell_iface: Vec<[Vec<f64>; 4]> = iface_cells
        .iter()
        .map(|cells| {
            let col = |f: &dyn Fn(&[f64; 3]) -> f64| cells.iter().map(f).collect::<Vec<f64>>();
            [
                col(&|c| c[0].max(0.0)),
                col(&|c| c[1].max(0.0)),
                col(&|c| (c[0] - c[1]).max(0.0)),
                col(&|c| {
                    if c[2] > 0.0 {
                        c[0].max(0.0) / c[2]
                    } else {
                        0.0
                    }
                }),
            ]
        })
        .collect();
    let names: Vec<String> = (0..ns).map(|s| solver.sub_name(s).to_string()).collect();
    let parts: Vec<(&str, VtuWriter<'_>)> = (0..ns)
        .map(|s| {
            let mesh = &solver.model(s).mesh;
            let [e, g, st] = &node_fields[s];
            let [ce, cg, cst, cd] = &cell_iface[s];
            let mut w = VtuWriter::new(mesh)
                .point_scalar("interface_error_density", e)
                .point_scalar("interface_space_error_density", g)
                .point_scalar("interface_stochastic_error_density", st)
                .cell_scalar("interface_cell_error", ce)
                .cell_scalar("interface_cell_space_error", cg)
                .cell_scalar("interface_cell_stochastic_error", cst)
                .cell_scalar("interface_cell_error_density", cd);
            if let Some([gd, td, g, t]) = &cell_fields[s] {
                w = w
                    .cell_scalar("space_error_density", gd)
                    .cell_scalar("error_density", td)
                    .cell_scalar("space_error", g)
                    .cell_scalar("error", t);
            }
            (names[s].as_str(), w)
        })
        .collect();
    let path = dir.join("paraview").join("error.vtm");
    std::fs::create_dir_all(dir.join("paraview")).map_err(|source| StudyError::Io {
        path: dir.join("paraview"),
        source,
    })?;
    write_vtm(&path, &parts)?;
    Ok(Some(path))
}
