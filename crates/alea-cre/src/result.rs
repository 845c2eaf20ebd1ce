//! The estimate of an assembly: global, per substructure, per interface, per element.

use std::path::Path;

use alea_fem::Model;
use alea_mesh::vtu::VtuWriter;

use crate::CreError;
use crate::domain::DomainEstimate;
use crate::interface::InterfaceEstimate;

/// CRE estimate of a substructured (LATIN) solution.
#[derive(Clone, Debug)]
pub struct CreResult {
    /// `theta = (sum_s theta_s^2 + 2 sum_I term_I)^(1/2)` (`= sqrt(2) e_CRE`, (3.26)).
    pub theta: f64,
    /// `theta / ||u_h||_K`.
    pub relative: f64,
    /// `||u_h||_K = (sum_s int sigma_h : eps_h)^(1/2)`.
    pub energy_norm: f64,
    /// Per substructure (element contributions inside).
    pub substructures: Vec<DomainEstimate>,
    /// Per interface.
    pub interfaces: Vec<InterfaceEstimate>,
}

impl CreResult {
    /// Assembles the global quantities.
    pub fn new(substructures: Vec<DomainEstimate>, interfaces: Vec<InterfaceEstimate>) -> Self {
        let t2: f64 = substructures.iter().map(|d| d.theta * d.theta).sum::<f64>()
            + 2.0 * interfaces.iter().map(|i| i.term).sum::<f64>();
        let e2: f64 = substructures
            .iter()
            .map(|d| d.energy_norm * d.energy_norm)
            .sum();
        let theta = t2.max(0.0).sqrt();
        let energy_norm = e2.sqrt();
        CreResult {
            theta,
            relative: if energy_norm > 0.0 {
                theta / energy_norm
            } else {
                0.0
            },
            energy_norm,
            substructures,
            interfaces,
        }
    }

    /// `theta_s` of each substructure.
    pub fn substructure_theta(&self) -> Vec<f64> {
        self.substructures.iter().map(|d| d.theta).collect()
    }

    /// Interface part of `theta^2` (`2 sum_I term_I`).
    pub fn interface_theta2(&self) -> f64 {
        2.0 * self.interfaces.iter().map(|i| i.term).sum::<f64>()
    }

    /// Worst phase-1 compatibility defect over the substructures.
    pub fn compatibility_defect(&self) -> f64 {
        self.substructures
            .iter()
            .fold(0.0, |m, d| m.max(d.compatibility_defect))
    }
}

/// Writes a VTU file of `model`'s mesh with the cell fields `error_density` (`theta_E^2 / |E|`)
/// and `theta_E`.
pub fn write_error_vtu(
    model: &Model,
    estimate: &DomainEstimate,
    path: impl AsRef<Path>,
) -> Result<(), CreError> {
    if estimate.element_theta.len() != model.mesh.num_cells() {
        return Err(CreError::Invalid(format!(
            "{} element contributions for {} cells",
            estimate.element_theta.len(),
            model.mesh.num_cells()
        )));
    }
    VtuWriter::new(&model.mesh)
        .cell_scalar("error_density", &estimate.error_density(model))
        .cell_scalar("theta_E", &estimate.element_theta)
        .write(path)?;
    Ok(())
}
