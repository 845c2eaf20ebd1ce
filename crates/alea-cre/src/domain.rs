//! The CRE estimate of one domain (a whole structure, or one isolated substructure).

use alea_fem::{Constraints, DofMap, Model};
use rayon::prelude::*;

use crate::CreError;
use crate::contribution::{DomainSums, ElementContribution, domain_sums};
use crate::data::{LoadData, SideForces};
use crate::eet::phase1::{EdgeTractions, Phase1Input, phase1};
use crate::eet::phase2::{ElementStress, Phase2Rules, element};
use crate::solid::phase1::FaceTractions;
use crate::solid::phase2::{SolidElementStress, SolidRules, element as solid_element};

/// Estimator options.
#[derive(Clone, Copy, Debug)]
pub struct CreOptions {
    /// Extra degree `k` of the phase-2 local spaces (degree `p + k`); 3 as in the thesis.
    pub extra_degree: usize,
    /// Relative tolerance of the interface admissibility checks (3.27).
    pub admissibility_tolerance: f64,
}

impl CreOptions {
    /// Checks the options.
    ///
    /// # Errors
    /// [`CreError::Invalid`] if `extra_degree` is not in `1..=10` or the tolerance is negative or
    /// not finite.
    pub fn validate(&self) -> Result<(), CreError> {
        if !(1..=10).contains(&self.extra_degree) {
            return Err(CreError::Invalid(format!(
                "extra_degree must be in 1..=10, got {}",
                self.extra_degree
            )));
        }
        let t = self.admissibility_tolerance;
        if !(t.is_finite() && t >= 0.0) {
            return Err(CreError::Invalid(format!(
                "admissibility_tolerance must be finite and >= 0, got {t}"
            )));
        }
        Ok(())
    }
}

impl Default for CreOptions {
    fn default() -> Self {
        CreOptions {
            extra_degree: 3,
            admissibility_tolerance: 1e-8,
        }
    }
}

/// Estimate on one domain.
#[derive(Clone, Debug)]
pub struct DomainEstimate {
    /// `theta = (sum_E theta_E^2)^(1/2) = ||sigma_hat - sigma_h||_{K^-1}`.
    pub theta: f64,
    /// `theta_E` of each cell.
    pub element_theta: Vec<f64>,
    /// Energy norm of the FE solution `||u_h||_K = (int sigma_h : eps_h)^(1/2)`.
    pub energy_norm: f64,
    /// Largest relative residual of the phase-1 node systems (0 when the FE solution is in
    /// equilibrium with the given loads).
    pub compatibility_defect: f64,
    /// Largest relative out-of-balance of the element loads of phase 2.
    pub balance_defect: f64,
    /// The statically admissible field: phase-1 densities and phase-2 element stresses.
    pub admissible: Admissible,
    /// Wall-clock seconds of phase 1 and phase 2 (with the element contributions).
    pub seconds: [f64; 2],
}

/// The statically admissible field of an estimate, by dimension.
#[derive(Clone, Debug)]
pub enum Admissible {
    /// 2D: edge densities and element stresses `[s_xx, s_yy, s_xy]`.
    Plane {
        /// Phase-1 edge tractions.
        tractions: EdgeTractions,
        /// Phase-2 admissible stress of each cell.
        stresses: Vec<ElementStress>,
    },
    /// 3D: face densities and element stresses `[xx, yy, zz, yz, xz, xy]`.
    Solid {
        /// Phase-1 face tractions.
        tractions: FaceTractions,
        /// Phase-2 admissible stress of each cell.
        stresses: Vec<SolidElementStress>,
    },
}

impl DomainEstimate {
    /// Phase-1 edge tractions and phase-2 element stresses of a 2D estimate.
    fn plane(&self) -> Option<(&EdgeTractions, &[ElementStress])> {
        match &self.admissible {
            Admissible::Plane {
                tractions,
                stresses,
            } => Some((tractions, stresses)),
            Admissible::Solid { .. } => None,
        }
    }

    /// Phase-1 face tractions and phase-2 element stresses of a 3D estimate.
    fn solid(&self) -> Option<(&FaceTractions, &[SolidElementStress])> {
        match &self.admissible {
            Admissible::Solid {
                tractions,
                stresses,
            } => Some((tractions, stresses)),
            Admissible::Plane { .. } => None,
        }
    }

    /// Phase-1 edge tractions of a 2D estimate.
    pub fn edge_tractions(&self) -> Option<&EdgeTractions> {
        self.plane().map(|(tractions, _)| tractions)
    }

    /// Phase-2 element stresses of a 2D estimate.
    pub fn plane_stresses(&self) -> Option<&[ElementStress]> {
        self.plane().map(|(_, stresses)| stresses)
    }

    /// Phase-1 face tractions of a 3D estimate.
    pub fn face_tractions(&self) -> Option<&FaceTractions> {
        self.solid().map(|(tractions, _)| tractions)
    }

    /// Phase-2 element stresses of a 3D estimate.
    pub fn solid_stresses(&self) -> Option<&[SolidElementStress]> {
        self.solid().map(|(_, stresses)| stresses)
    }

    /// The estimate of a domain from its element sums, phase-1 defect, timings and admissible
    /// field (`admissible(stresses)`).
    pub(crate) fn from_sums<S>(
        sums: DomainSums<S>,
        compatibility_defect: f64,
        seconds: [f64; 2],
        admissible: impl FnOnce(Vec<S>) -> Admissible,
    ) -> Result<Self, CreError> {
        Ok(DomainEstimate {
            theta: sums.theta,
            element_theta: sums.element_theta,
            energy_norm: sums.energy_norm,
            compatibility_defect,
            balance_defect: sums.balance_defect,
            admissible: admissible(sums.stresses),
            seconds,
        })
    }

    /// Energy density of the error per cell, `theta_E^2 / |E|` (for plots).
    pub fn error_density(&self, model: &Model) -> Vec<f64> {
        self.element_theta
            .iter()
            .enumerate()
            .map(|(c, t)| {
                let m = model.mesh.cell_measure(c) * model.analysis.thickness();
                if m > 0.0 { t * t / m } else { 0.0 }
            })
            .collect()
    }
}

/// Estimates the error of the FE displacement `u` of `model` under `constraints` and `loads`.
/// `u_hat = u_h` must be kinematically admissible: the constraints hold exactly (they do for
/// the FE solution when the prescribed values are those of the exact problem).
pub fn estimate_domain(
    model: &Model,
    constraints: &Constraints,
    loads: &LoadData,
    u: &[f64],
    options: &CreOptions,
) -> Result<DomainEstimate, CreError> {
    let dofs = DofMap::for_mesh(&model.mesh, constraints)?;
    estimate_with_sides(model, &dofs, loads, &[], u, options)
}

/// As [`estimate_domain`], with discrete interface forces on facet groups (substructures).
pub fn estimate_with_sides(
    model: &Model,
    dofs: &DofMap,
    loads: &LoadData,
    sides: &[SideForces],
    u: &[f64],
    options: &CreOptions,
) -> Result<DomainEstimate, CreError> {
    options.validate()?;
    model.check()?;
    if let Some(i) = u.iter().position(|v| !v.is_finite()) {
        return Err(CreError::Invalid(format!(
            "displacement entry {i} is not finite"
        )));
    }
    let t0 = std::time::Instant::now();
    let input = Phase1Input {
        model,
        dofs,
        u,
        body: loads.body.as_ref(),
        tractions: &loads.tractions,
        sides,
    };
    let body = loads.body.as_ref();
    // Local degree p + k for cells of order p (1: T3/Q4/Tet4/Hex8, 2: T6/Q8/Tet10).
    let (k1, k2) = (1 + options.extra_degree, 2 + options.extra_degree);
    if model.mesh.dim == 3 {
        // Module [`crate::solid`].
        let tr = crate::solid::phase1::phase1(&input)?;
        let t1 = t0.elapsed().as_secs_f64();
        let rules = [SolidRules::new(k1, 1), SolidRules::new(k2, 2)];
        return phase2_estimate(
            model,
            tr.compatibility_defect,
            tr,
            t1,
            |tr, c, order| solid_element(model, c, u, body, tr, &rules[order - 1]),
            |tractions, stresses| Admissible::Solid {
                tractions,
                stresses,
            },
        );
    }
    let tr = phase1(&input)?;
    let t1 = t0.elapsed().as_secs_f64();
    let rules = [Phase2Rules::new(k1), Phase2Rules::new(k2)];
    phase2_estimate(
        model,
        tr.compatibility_defect,
        tr,
        t1,
        |tr, c, order| element(model, c, u, body, tr, &rules[order - 1]),
        |tractions, stresses| Admissible::Plane {
            tractions,
            stresses,
        },
    )
}

/// Phase 2 on every cell of `model` (`element(tractions, cell, cell order 1 or 2)`) and the
/// estimate of the domain (phase 1: `tractions`, its `compatibility_defect` and seconds `t1`).
fn phase2_estimate<T: Sync, S: Send>(
    model: &Model,
    compatibility_defect: f64,
    tractions: T,
    t1: f64,
    element: impl Fn(&T, usize, usize) -> Result<ElementContribution<S>, CreError> + Sync,
    admissible: impl FnOnce(T, Vec<S>) -> Admissible,
) -> Result<DomainEstimate, CreError> {
    let t0 = std::time::Instant::now();
    let per: Vec<_> = (0..model.mesh.num_cells())
        .into_par_iter()
        .map(|c| element(&tractions, c, model.mesh.cell_type(c).order().clamp(1, 2)))
        .collect::<Result<_, _>>()?;
    DomainEstimate::from_sums(
        domain_sums(per)?,
        compatibility_defect,
        [t1, t0.elapsed().as_secs_f64()],
        |stresses| admissible(tractions, stresses),
    )
}
