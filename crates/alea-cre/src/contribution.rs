//! What phase 2 gives per cell, in 2D and 3D alike, and the domain sums (thesis (3.23) and the
//! element contributions of the CRE): `theta^2 = sum_E theta_E^2`, `theta_E^2 = ||sigma_hat -
//! sigma_h||^2_{K^-1,E}`, `||u_h||^2_K = sum_E ||u_h||^2_{K,E}`, and the largest element
//! balance defect.

use crate::CreError;

/// Phase-2 result of one element, with its admissible stress `S`.
#[derive(Clone, Debug)]
pub struct ElementContribution<S> {
    /// `theta_E^2` (thickness included in 2D).
    pub theta2: f64,
    /// `||u_h||^2_{K,E}` (thickness included in 2D).
    pub energy2: f64,
    /// Relative out-of-balance of the element loads (force and moment resultants over the sum
    /// of absolute contributions): zero when phase 1 is exact.
    pub balance_defect: f64,
    /// The admissible stress.
    pub stress: S,
}

/// The balance defect of an element's loads: `(sum |force resultants| + sum |moment
/// resultants| / h) / sum of the absolute contributions`, `h` the element's size (0 without
/// loads).
pub(crate) fn balance_defect(forces: &[f64], moments: &[f64], h: f64, abs_sum: f64) -> f64 {
    if abs_sum > 0.0 {
        (forces.iter().map(|v| v.abs()).sum::<f64>()
            + moments.iter().map(|v| v.abs()).sum::<f64>() / h)
            / abs_sum
    } else {
        0.0
    }
}

/// The domain sums of the element contributions.
pub(crate) struct DomainSums<S> {
    /// `theta = (sum_E theta_E^2)^(1/2)`.
    pub theta: f64,
    /// `theta_E` of each cell.
    pub element_theta: Vec<f64>,
    /// `||u_h||_K`.
    pub energy_norm: f64,
    /// Largest element balance defect.
    pub balance_defect: f64,
    /// The admissible stress of each cell.
    pub stresses: Vec<S>,
}

/// Sums the element contributions of a domain (in cell order).
pub(crate) fn domain_sums<S>(per: Vec<ElementContribution<S>>) -> Result<DomainSums<S>, CreError> {
    let theta2: f64 = per.iter().map(|r| r.theta2).sum();
    if !theta2.is_finite() {
        return Err(CreError::Invalid(
            "non-finite error estimate (degenerate cell or non-finite load data)".into(),
        ));
    }
    let energy2: f64 = per.iter().map(|r| r.energy2).sum();
    let balance_defect = per.iter().fold(0.0f64, |m, r| m.max(r.balance_defect));
    let element_theta = per.iter().map(|r| r.theta2.max(0.0).sqrt()).collect();
    let stresses = per.into_iter().map(|r| r.stress).collect();
    Ok(DomainSums {
        theta: theta2.max(0.0).sqrt(),
        element_theta,
        energy_norm: energy2.max(0.0).sqrt(),
        balance_defect,
        stresses,
    })
}
