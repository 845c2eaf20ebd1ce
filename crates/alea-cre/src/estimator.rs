//! The multiresolution estimator of one domain: everything that does not depend on the run
//! (topology, constraint frames, node systems and their least-change operators, element
//! stiffnesses, traction-projection operators, the Cholesky factors of the phase-2 local
//! problems and the matrices that turn a displacement into `theta_E`) computed once at
//! construction, the per-run work reduced to what depends on the displacement, the interface
//! forces, the loads and the Young's factor ([`crate::eet::phase1_cache`],
//! [`crate::eet::phase2_cache`]). The result is the direct path's ([`crate::estimate_with_sides`])
//! to round-off.
//!
//! 3D domains keep the direct path (the run's model is rebuilt with its Young's factor): only
//! the constraints' dof map is cached.

use std::sync::Arc;

use alea_fem::{Constraints, DofMap, Model};
use rayon::prelude::*;

use crate::CreError;
use crate::contribution::domain_sums;
use crate::data::{LoadData, SideForces};
use crate::domain::{Admissible, CreOptions, DomainEstimate, estimate_with_sides};
use crate::eet::phase1_cache::Phase1Cache;
use crate::eet::phase2_cache::{Phase2Cache, Scratch};
use crate::topology::Topology;

/// Cached data by dimension.
#[derive(Debug)]
enum Cache {
    /// 2D: topology and both phases.
    Plane {
        topo: Arc<Topology>,
        phase1: Box<Phase1Cache>,
        phase2: Box<Phase2Cache>,
    },
    /// 3D: nothing beyond the dof map.
    Solid,
}

/// The estimator of one domain with its run-independent data (module doc).
#[derive(Debug)]
pub struct DomainEstimator {
    model: Model,
    dofs: DofMap,
    options: CreOptions,
    cache: Cache,
}

impl DomainEstimator {
    /// The estimator of `model` (reference materials: Young's factor 1) under `constraints`.
    ///
    /// # Errors
    /// Invalid options or model, unsupported or degenerate cells, a local problem that is not
    /// positive definite.
    pub fn new(
        model: &Model,
        constraints: &Constraints,
        options: &CreOptions,
    ) -> Result<Self, CreError> {
        let dofs = DofMap::for_mesh(&model.mesh, constraints)?;
        Self::with_dofs(model, dofs, options)
    }

    /// As [`DomainEstimator::new`] with the constraints' dof map.
    ///
    /// # Errors
    /// As [`DomainEstimator::new`].
    pub fn with_dofs(model: &Model, dofs: DofMap, options: &CreOptions) -> Result<Self, CreError> {
        options.validate()?;
        model.check()?;
        let cache = if model.mesh.dim == 3 {
            Cache::Solid
        } else {
            let topo = Arc::new(Topology::new(&model.mesh)?);
            let phase1 = Box::new(Phase1Cache::new(model, &dofs, &topo)?);
            let phase2 = Box::new(Phase2Cache::new(model, options.extra_degree)?);
            Cache::Plane {
                topo,
                phase1,
                phase2,
            }
        };
        Ok(DomainEstimator {
            model: model.clone(),
            dofs,
            options: *options,
            cache,
        })
    }

    /// The reference model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The constraints' dof map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// Bytes of run-independent data held beyond the model and the dof map (0 in 3D).
    pub fn cache_bytes(&self) -> usize {
        match &self.cache {
            Cache::Plane {
                topo,
                phase1,
                phase2,
            } => topology_bytes(topo) + phase1.bytes() + phase2.bytes(),
            Cache::Solid => 0,
        }
    }

    /// Estimates the error of the FE displacement `u` (node-major) of the model with every
    /// Young's modulus multiplied by `young_factor`, under `loads` (load factors folded in) and
    /// the discrete interface forces `sides`: [`estimate_with_sides`] on the scaled model, to
    /// round-off.
    ///
    /// # Errors
    /// Sizes that do not match the model, non-finite data, a non-positive Young's factor, load
    /// groups that are not boundary edges.
    pub fn estimate(
        &self,
        loads: &LoadData,
        sides: &[SideForces],
        u: &[f64],
        young_factor: f64,
    ) -> Result<DomainEstimate, CreError> {
        let model = &self.model;
        let mesh = &model.mesh;
        let alpha = young_factor;
        if !(alpha.is_finite() && alpha > 0.0) {
            return Err(CreError::Invalid(format!(
                "Young's factor must be finite and > 0, got {alpha}"
            )));
        }
        if u.len() != mesh.dim * mesh.num_nodes() {
            return Err(CreError::Invalid(format!(
                "displacement of length {} for {} nodes in {}D",
                u.len(),
                mesh.num_nodes(),
                mesh.dim
            )));
        }
        if let Some(i) = u.iter().position(|v| !v.is_finite()) {
            return Err(CreError::Invalid(format!(
                "displacement entry {i} is not finite"
            )));
        }
        let (topo, phase1, phase2) = match &self.cache {
            Cache::Plane {
                topo,
                phase1,
                phase2,
            } => (topo, phase1, phase2),
            Cache::Solid => {
                let scaled;
                let m = if alpha == 1.0 {
                    model
                } else {
                    let mut s = model.clone();
                    s.scale_young(alpha);
                    scaled = s;
                    &scaled
                };
                return estimate_with_sides(m, &self.dofs, loads, sides, u, &self.options);
            }
        };
        let affine = loads.affine();
        if affine.is_some_and(|a| !a.is_finite()) {
            return Err(CreError::Invalid(
                "the affine body force has a non-finite entry".into(),
            ));
        }
        let t0 = std::time::Instant::now();
        let tr = phase1.run(
            model,
            topo,
            u,
            alpha,
            loads.body.as_ref(),
            affine,
            &loads.tractions,
            sides,
        )?;
        let t1 = t0.elapsed().as_secs_f64();
        let t0 = std::time::Instant::now();
        let per: Vec<_> = (0..mesh.num_cells())
            .into_par_iter()
            .map_init(Scratch::default, |scratch, c| {
                phase2.element(
                    model,
                    c,
                    u,
                    alpha,
                    loads.body.as_ref(),
                    affine,
                    &tr,
                    scratch,
                )
            })
            .collect::<Result<_, _>>()?;
        let compatibility_defect = tr.compatibility_defect;
        DomainEstimate::from_sums(
            domain_sums(per)?,
            compatibility_defect,
            [t1, t0.elapsed().as_secs_f64()],
            |stresses| Admissible::Plane {
                tractions: tr,
                stresses,
            },
        )
    }
}

/// Approximate heap size of a topology.
fn topology_bytes(t: &Topology) -> usize {
    let vecs = |v: &[Vec<usize>]| v.iter().map(|x| 24 + 8 * x.len()).sum::<usize>();
    t.edges
        .iter()
        .map(|e| std::mem::size_of_val(e) + 16 * e.cells.len())
        .sum::<usize>()
        + t.cell_edges
            .iter()
            .map(|x| 24 + 16 * x.len())
            .sum::<usize>()
        + vecs(&t.node_edges)
        + vecs(&t.node_cells)
        + 40 * t.edges.len()
}
