//! Error estimation in a study: the deterministic CRE of every converged run (crate
//! `alea-cre`), stored in its compact form, and the data the stochastic estimator (crate
//! `alea-estimate`) needs from the model.
//!
//! For each converged run: the loads of every substructure as functions (the study's
//! tractions, pressures, body forces and centrifugal inertia - an affine body force - times the
//! run's load factors), the CRE of the LATIN solution (the study's
//! [`alea_cre::LatinEstimator`], built once: EET admissible stresses per substructure, de Saxce
//! interface term), and a [`CreRecord`]: per substructure the phase-2
//! coefficients of the admissible stress (27 numbers per Q4 or T3 cell, the compact form of
//! `sigma_hat`; its samples are rebuilt with [`alea_cre::EnergySampler`]), per interface point the
//! jump `w_hat` (gap included, local stage `n - 1`) and the force `F_hat` (local stage `n`),
//! and the run's Young's factors. The FE stress samples are rebuilt from the run's stored
//! displacement. Nodal (point) forces have no finite stress energy and are refused; so are body
//! loads restricted to part of a substructure.
//!
//! 3D substructures: only the interface part is estimated, as in the thesis's 3D study (5.2.6):
//! the 3D EET exists (`alea_cre::solid`) but costs about twice a LATIN solve per run on the 3D
//! turbine (`BENCHMARKS.md`). They give FE-stress samples only
//! ([`alea_cre::FeEnergySampler`], the stiffness rule), whose energy normalises the relative
//! indicators (crate `alea-estimate`, "Substructures without admissible stress": `e~` is then
//! not a bound of the total error; `I_sto` is complete when the Young's moduli are
//! deterministic). The estimate says so ([`CreSetup::substructures_estimated`]).

use alea_cre::{AffineBody, CreOptions, EnergySampler, FeEnergySampler, LatinEstimator, LoadData};
use alea_estimate::{InterfaceKind, InterfaceLayout, Layout, Parameters, SubLayout};
use alea_latin::{LatinSolver, RunResult};

use crate::build::ProfileTable;
use crate::spec::LoadSpec;
use crate::study::Study;
use crate::{Parametric, StudyError};

/// One load case of a substructure as the estimator needs it.
#[derive(Clone, Debug)]
enum LoadTerm {
    /// Traction vector on a facet group.
    Traction(String, [f64; 3]),
    /// Pressure on a facet group (positive pushes on the surface).
    Pressure(String, f64),
    /// Body force per volume.
    Body([f64; 3]),
    /// Centrifugal inertia `rho omega^2 r_perp`.
    Centrifugal {
        rho_omega2: f64,
        point: [f64; 3],
        axis: [f64; 3],
    },
}

/// What error estimation needs from a study's model, built once.
pub struct CreSetup {
    /// Estimator options.
    pub options: CreOptions,
    samplers: Vec<Option<EnergySampler>>,
    /// The multiresolution estimator (2D substructures only).
    estimator: Option<LatinEstimator>,
    /// FE-only samplers of the substructures without admissible stress (3D).
    norm_samplers: Vec<Option<FeEnergySampler>>,
    loads: Vec<Vec<LoadTerm>>,
    /// The entities as the stochastic estimator sees them.
    pub layout: Layout,
}

impl std::fmt::Debug for CreSetup {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CreSetup")
            .field("layout", &self.layout.subs.len())
            .finish()
    }
}

/// The deterministic CRE of one run in compact form (module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct CreRecord {
    /// Young's factor of each substructure.
    pub young: Vec<f64>,
    /// Phase-2 coefficients of each substructure's admissible stress (empty when the
    /// substructure part is not estimated).
    pub coefficients: Vec<Vec<f64>>,
    /// Per interface and point: `w_hat` (gap included, local stage `n - 1`).
    pub jump: Vec<Vec<[f64; 3]>>,
    /// Per interface and point: `F_hat` on side 2 (local stage `n`).
    pub force: Vec<Vec<[f64; 3]>>,
    /// `theta = sqrt(2) e_CRE` of the run (alea-cre's convention).
    pub theta: f64,
    /// `theta / ||u_h||_K`.
    pub relative: f64,
    /// Wall-clock seconds of the estimate.
    pub seconds: f64,
}

const RECORD_VERSION: f64 = 1.0;

impl CreRecord {
    /// Flat little-endian `f64` form: version, counts, scalars, then the arrays.
    pub fn to_values(&self) -> Vec<f64> {
        let mut v = vec![
            RECORD_VERSION,
            self.young.len() as f64,
            self.jump.len() as f64,
            self.theta,
            self.relative,
            self.seconds,
        ];
        v.extend_from_slice(&self.young);
        for c in &self.coefficients {
            v.push(c.len() as f64);
            v.extend_from_slice(c);
        }
        for (j, f) in self.jump.iter().zip(&self.force) {
            v.push(j.len() as f64);
            for p in j.iter().chain(f) {
                v.extend_from_slice(p);
            }
        }
        v
    }

    /// Inverse of [`CreRecord::to_values`]; `None` if the values are not a record.
    pub fn from_values(v: &[f64]) -> Option<Self> {
        let mut pos = 0usize;
        let mut take = |n: usize| -> Option<&[f64]> {
            let s = v.get(pos..pos.checked_add(n)?)?;
            pos += n;
            Some(s)
        };
        let count = |x: f64| -> Option<usize> {
            (x >= 0.0 && x.fract() == 0.0 && x < 1e12).then_some(x as usize)
        };
        let head = take(6)?;
        if head[0] != RECORD_VERSION {
            return None;
        }
        let (ns, ni) = (count(head[1])?, count(head[2])?);
        let (theta, relative, seconds) = (head[3], head[4], head[5]);
        let young = take(ns)?.to_vec();
        let mut coefficients = Vec::with_capacity(ns.min(v.len()));
        for _ in 0..ns {
            let n = count(take(1)?[0])?;
            coefficients.push(take(n)?.to_vec());
        }
        let mut jump = Vec::with_capacity(ni.min(v.len()));
        let mut force = Vec::with_capacity(ni.min(v.len()));
        for _ in 0..ni {
            let n = count(take(1)?[0])?;
            let all = take(n.checked_mul(6)?)?;
            let pts: Vec<[f64; 3]> = all.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            jump.push(pts[..n].to_vec());
            force.push(pts[n..].to_vec());
        }
        (pos == v.len()).then_some(CreRecord {
            young,
            coefficients,
            jump,
            force,
            theta,
            relative,
            seconds,
        })
    }
}

fn load_term(
    study: &Study,
    model: &alea_fem::Model,
    s: usize,
    j: usize,
    l: &LoadSpec,
) -> Result<LoadTerm, StudyError> {
    let src = &study.source;
    let field = format!("substructure[{s}].load[{j}]");
    let span = l.span();
    let vec3 = |v: &[f64]| {
        let mut a = [0.0; 3];
        for (o, x) in a.iter_mut().zip(v) {
            *o = *x;
        }
        a
    };
    // Body loads must act on the whole substructure: the estimator's body force is a
    // function of the position only.
    let whole = |group: &Option<toml::Spanned<String>>| -> Result<(), StudyError> {
        if let Some(g) = group {
            let cells = model
                .mesh
                .cell_group(g.get_ref())
                .map_err(|e| src.error(g.span(), format!("{field}.group"), e.to_string()))?;
            if cells.len() != model.mesh.num_cells() {
                return Err(src.error(
                    g.span(),
                    format!("{field}.group"),
                    "error estimation needs body loads on whole substructures; this group covers part of it",
                ));
            }
        }
        Ok(())
    };
    let group = || {
        l.group
            .as_ref()
            .map(|g| g.get_ref().clone())
            .unwrap_or_default()
    };
    if let Some(p) = &l.pressure {
        Ok(LoadTerm::Pressure(group(), *p.get_ref()))
    } else if let Some(t) = &l.traction {
        Ok(LoadTerm::Traction(group(), vec3(t.get_ref())))
    } else if let Some(b) = &l.body {
        whole(&l.group)?;
        Ok(LoadTerm::Body(vec3(b.get_ref())))
    } else if let Some(c) = &l.centrifugal {
        whole(&l.group)?;
        let c = c.get_ref();
        let rho = model.material(0).map(|m| m.density).unwrap_or(0.0);
        if (0..model.mesh.num_cells())
            .any(|e| model.material(e).map(|m| m.density).unwrap_or(rho) != rho)
        {
            return Err(src.error(
                span,
                field,
                "error estimation needs one density per substructure for centrifugal loads",
            ));
        }
        let omega = *c.omega.get_ref();
        let axis = c.axis.clone().unwrap_or_else(|| vec![0.0, 0.0, 1.0]);
        let len = (axis.iter().map(|v| v * v).sum::<f64>()).sqrt();
        Ok(LoadTerm::Centrifugal {
            rho_omega2: rho * omega * omega,
            point: vec3(&c.center.clone().unwrap_or_default()),
            axis: vec3(&axis.iter().map(|v| v / len).collect::<Vec<_>>()),
        })
    } else {
        Err(src.error(
            span,
            field,
            "error estimation needs distributed loads: a nodal force has no finite stress energy (use a traction on a small facet group)",
        ))
    }
}

impl CreSetup {
    /// Checks that the study's loads can be given to the estimator and builds the samplers
    /// (reference materials: the solver's models).
    ///
    /// # Errors
    /// [`StudyError::Input`] naming the load that cannot be estimated; estimator set-up errors.
    pub fn new(study: &Study, solver: &LatinSolver) -> Result<Self, StudyError> {
        let options = CreOptions::default();
        let ns = solver.num_subs();
        let mut loads = Vec::with_capacity(ns);
        let mut samplers = Vec::with_capacity(ns);
        let mut norm_samplers = Vec::with_capacity(ns);
        let mut subs = Vec::with_capacity(ns);
        for s in 0..ns {
            let model = solver.model(s);
            let spec = &study.file.substructure[s];
            loads.push(
                spec.load
                    .iter()
                    .enumerate()
                    .map(|(j, l)| load_term(study, model, s, j, l))
                    .collect::<Result<Vec<_>, _>>()?,
            );
            let sampler = if model.mesh.dim == 2 {
                Some(
                    EnergySampler::new(model, &options)
                        .map_err(|error| sub_estimator(solver, s, error))?,
                )
            } else {
                None
            };
            let norm_sampler = norm_sampler(solver, s, sampler.is_none())?;
            subs.push(SubLayout {
                name: solver.sub_name(s).to_string(),
                cell_offsets: match (&sampler, &norm_sampler) {
                    (Some(sm), _) => sm.cell_offsets().to_vec(),
                    (None, Some(sm)) => sm.cell_offsets().to_vec(),
                    (None, None) => Vec::new(),
                },
                admissible: sampler.is_some(),
            });
            samplers.push(sampler);
            norm_samplers.push(norm_sampler);
        }
        let interfaces = (0..solver.num_interfaces())
            .map(|i| InterfaceLayout {
                name: solver.interface_name(i).to_string(),
                kind: if solver.interface_law(i) == "perfect" {
                    InterfaceKind::Perfect
                } else {
                    InterfaceKind::Contact
                },
                weights: solver.interface_weights(i).to_vec(),
                normals: solver
                    .interface_points(i)
                    .iter()
                    .map(|p| p.normal)
                    .collect(),
            })
            .collect();
        let estimator = if samplers.iter().all(|s| s.is_some()) {
            Some(
                LatinEstimator::new(&study.model.assembly, &options)
                    .map_err(StudyError::EstimatorSetup)?,
            )
        } else {
            None
        };
        Ok(CreSetup {
            options,
            samplers,
            estimator,
            norm_samplers,
            loads,
            layout: Layout { subs, interfaces },
        })
    }

    /// True if every substructure has its part of the estimate (2D cells).
    pub fn substructures_estimated(&self) -> bool {
        self.samplers.iter().all(|s| s.is_some())
    }

    /// The loads of substructure `s` as functions, with load factors `factors`.
    fn load_data(&self, s: usize, factors: &[f64]) -> LoadData {
        let mut data = LoadData::new();
        let mut bodies: Vec<(f64, LoadTerm)> = Vec::new();
        for (j, t) in self.loads[s].iter().enumerate() {
            let f = factors.get(j).copied().unwrap_or(1.0);
            match t.clone() {
                LoadTerm::Traction(g, v) => {
                    data = data.traction(&g, move |_, _| [f * v[0], f * v[1], f * v[2]]);
                }
                LoadTerm::Pressure(g, p) => {
                    data = data.traction(&g, move |_, n| {
                        [-f * p * n[0], -f * p * n[1], -f * p * n[2]]
                    });
                }
                other => bodies.push((f, other)),
            }
        }
        if !bodies.is_empty() {
            // Constant and centrifugal body forces sum to an affine one.
            let mut b = AffineBody::default();
            for (f, t) in bodies {
                match t {
                    LoadTerm::Body(v) => {
                        for c in 0..3 {
                            b.constant[c] += f * v[c];
                        }
                    }
                    LoadTerm::Centrifugal {
                        rho_omega2,
                        point,
                        axis,
                    } => {
                        // rho omega^2 (I - a a^T)(x - x_0).
                        for i in 0..3 {
                            for j in 0..3 {
                                let pij = f
                                    * rho_omega2
                                    * (if i == j { 1.0 } else { 0.0 } - axis[i] * axis[j]);
                                b.gradient[i][j] += pij;
                                b.constant[i] -= pij * point[j];
                            }
                        }
                    }
                    _ => {}
                }
            }
            data = data.affine_body(b);
        }
        data
    }

    /// The deterministic CRE of a converged run at `theta`.
    ///
    /// # Errors
    /// Estimator errors (e.g. cells it cannot handle).
    pub fn estimate_run(
        &self,
        study: &Study,
        solver: &LatinSolver,
        theta: &[f64],
        res: &RunResult,
    ) -> Result<CreRecord, StudyError> {
        let t0 = std::time::Instant::now();
        let input = study.model.parametric.run_input(theta);
        let ns = solver.num_subs();
        let loads: Vec<LoadData> = (0..ns)
            .map(|s| {
                self.load_data(
                    s,
                    input.load_factors.get(s).map_or(&[][..], |v| v.as_slice()),
                )
            })
            .collect();
        let err = |error| StudyError::RunEstimate {
            theta: theta.to_vec(),
            error,
        };
        let (coefficients, theta_run, relative) = if let Some(estimator) = &self.estimator {
            let cre = estimator.estimate(&loads, res).map_err(err)?;
            let coefficients = self
                .samplers
                .iter()
                .zip(&cre.substructures)
                .map(|(sm, d)| sm.as_ref().map_or(Ok(Vec::new()), |sm| sm.coefficients(d)))
                .collect::<Result<Vec<_>, _>>()
                .map_err(err)?;
            (coefficients, cre.theta, cre.relative)
        } else {
            let terms = res
                .interfaces
                .iter()
                .map(|ir| alea_cre::interface_term(ir, self.options.admissibility_tolerance))
                .collect::<Result<Vec<_>, _>>()
                .map_err(err)?;
            let t2 = 2.0 * terms.iter().map(|t| t.term).sum::<f64>();
            (vec![Vec::new(); ns], t2.max(0.0).sqrt(), 0.0)
        };
        let jump = res
            .interfaces
            .iter()
            .map(|ir| {
                (0..ir.points.len())
                    .map(|i| {
                        // Side 2 in the points' frame (a cyclic interface's `R^T W_2`).
                        let (a, b) = (
                            ir.what_prev[0][i],
                            ir.pairing.to_points(1, ir.what_prev[1][i]),
                        );
                        let p = &ir.points[i];
                        [
                            b[0] - a[0] + p.gap * p.normal[0],
                            b[1] - a[1] + p.gap * p.normal[1],
                            b[2] - a[2] + p.gap * p.normal[2],
                        ]
                    })
                    .collect()
            })
            .collect();
        let force = res
            .interfaces
            .iter()
            .map(|ir| (0..ir.points.len()).map(|i| ir.side2_force(i)).collect())
            .collect();
        Ok(CreRecord {
            young: res.young_factors.clone(),
            coefficients,
            jump,
            force,
            theta: theta_run,
            relative,
            seconds: t0.elapsed().as_secs_f64(),
        })
    }

    /// The stress samples of substructure `s` of a stored run: admissible samples from the
    /// record's coefficients, FE samples from its displacement (`fields`: every substructure's
    /// node-major displacement, concatenated as in the store). Without admissible stress (3D):
    /// no admissible samples, FE samples on the stiffness rule.
    ///
    /// # Errors
    /// [`StudyError::StaleEstimate`], [`StudyError::ShortField`] or
    /// [`StudyError::EstimateMesh`] if the record or the fields do not match the model.
    pub fn sub_samples(
        &self,
        solver: &LatinSolver,
        s: usize,
        record: &CreRecord,
        fields: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>), StudyError> {
        let ns = solver.num_subs();
        if record.young.len() != ns || record.coefficients.len() != ns {
            return Err(StudyError::StaleEstimate { restart_hint: true });
        }
        let off: usize = (0..s)
            .map(|t| solver.model(t).mesh.num_nodes() * solver.model(t).mesh.dim)
            .sum();
        let model = solver.model(s);
        let n = model.mesh.num_nodes() * model.mesh.dim;
        let u = fields.get(off..off + n).ok_or(StudyError::ShortField)?;
        let Some(sm) = &self.samplers[s] else {
            return match &self.norm_samplers[s] {
                Some(fe) => Ok((
                    Vec::new(),
                    fe.fe_stress(model, u, record.young[s])
                        .map_err(StudyError::from)?,
                )),
                None => Ok((Vec::new(), Vec::new())),
            };
        };
        let c = &record.coefficients[s];
        if c.len() != *sm.coefficient_offsets().last().unwrap_or(&0) {
            return Err(StudyError::EstimateMesh {
                sub: solver.sub_name(s).to_string(),
            });
        }
        let alpha = record.young[s];
        let mut a = Vec::with_capacity(sm.len());
        sm.admissible_from_coefficients(c, alpha, 0..model.mesh.num_cells(), &mut a);
        Ok((a, sm.fe_stress(model, u, alpha)))
    }
}

/// The FE-only sampler of substructure `s` when it has no admissible stress (`needed`).
fn norm_sampler(
    solver: &LatinSolver,
    s: usize,
    needed: bool,
) -> Result<Option<FeEnergySampler>, StudyError> {
    if !needed {
        return Ok(None);
    }
    FeEnergySampler::new(solver.model(s))
        .map(Some)
        .map_err(|error| sub_estimator(solver, s, error))
}

/// The failed set-up of substructure `s`'s estimator or sampler.
fn sub_estimator(solver: &LatinSolver, s: usize, error: alea_cre::CreError) -> StudyError {
    StudyError::SubEstimator {
        sub: solver.sub_name(s).to_string(),
        error,
    }
}

/// The study's parameters as the estimator sees them: Young's factors and friction profiles
/// at any parameter point.
pub struct StudyParameters<'a> {
    parametric: &'a Parametric,
    /// The friction profile of each interface tabulated on its points.
    friction: Vec<ProfileTable>,
}

impl<'a> StudyParameters<'a> {
    /// For the study's parametric map and the solver's interface points.
    pub fn new(parametric: &'a Parametric, solver: &LatinSolver) -> Self {
        StudyParameters {
            parametric,
            friction: (0..solver.num_interfaces())
                .map(|i| {
                    let xs: Vec<[f64; 3]> =
                        solver.interface_points(i).iter().map(|p| p.x).collect();
                    parametric.profile_table(&parametric.mu[i], &xs)
                })
                .collect(),
        }
    }
}

impl Parameters for StudyParameters<'_> {
    fn young(&self, xi: &[f64], out: &mut [f64]) {
        for ((o, e), n) in out
            .iter_mut()
            .zip(&self.parametric.young)
            .zip(&self.parametric.young_nominal)
        {
            *o = e.eval(xi) / n;
        }
    }

    fn friction(&self, xi: &[f64], interface: usize, out: &mut [f64]) {
        self.friction[interface].eval(xi, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The body and centrifugal loads of a substructure, with load factors, become one affine
    /// body force equal to the sum of the terms (`rho omega^2 (x - x_0)_perp` about any axis).
    #[test]
    fn body_loads_sum_to_an_affine_body_force() {
        let axis = {
            let a: [f64; 3] = [0.3, -0.2, 1.0];
            let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
            a.map(|v| v / n)
        };
        let terms = vec![
            LoadTerm::Body([1.0, 2.0, -0.5]),
            LoadTerm::Pressure("top".into(), 7.0),
            LoadTerm::Centrifugal {
                rho_omega2: 3.0,
                point: [1.0, -2.0, 0.0],
                axis: [0.0, 0.0, 1.0],
            },
            LoadTerm::Centrifugal {
                rho_omega2: 0.7,
                point: [-4.0, 0.5, 2.0],
                axis,
            },
        ];
        let setup = CreSetup {
            options: CreOptions::default(),
            samplers: vec![None],
            estimator: None,
            norm_samplers: vec![None],
            loads: vec![terms.clone()],
            layout: Layout {
                subs: vec![],
                interfaces: vec![],
            },
        };
        let factors = [2.0, 1.0, 0.5, 1.5];
        let data = setup.load_data(0, &factors);
        assert!(data.affine().is_some());
        assert_eq!(data.tractions.len(), 1);
        let body = data.body.as_ref().unwrap();
        for x in [[0.0, 0.0, 0.0], [3.0, -1.0, 0.5], [-2.5, 4.0, -1.0]] {
            let mut want = [0.0; 3];
            for (t, f) in terms.iter().zip(factors) {
                let v = match t {
                    LoadTerm::Body(v) => *v,
                    LoadTerm::Centrifugal {
                        rho_omega2,
                        point,
                        axis,
                    } => {
                        let r = [0, 1, 2].map(|i| x[i] - point[i]);
                        let s: f64 = (0..3).map(|i| r[i] * axis[i]).sum();
                        [0, 1, 2].map(|i| rho_omega2 * (r[i] - s * axis[i]))
                    }
                    _ => [0.0; 3],
                };
                for c in 0..3 {
                    want[c] += f * v[c];
                }
            }
            let got = body(x);
            for c in 0..3 {
                assert!((got[c] - want[c]).abs() < 1e-13, "{got:?} vs {want:?}");
            }
        }
    }
}
