//! Isotropic linear elasticity: Hooke's law in Voigt notation.
//!
//! Strain vectors use engineering shears. 2D: `eps = [e_xx, e_yy, g_xy]`; 3D:
//! `eps = [e_xx, e_yy, e_zz, g_yz, g_xz, g_xy]`. With Lame constants
//! `lambda = E nu / ((1 + nu)(1 - 2 nu))`, `mu = E / (2 (1 + nu))`:
//! - 3D and plane strain: `sigma = lambda tr(eps) I + 2 mu eps` (plane strain adds
//!   `sigma_zz = nu (sigma_xx + sigma_yy)`);
//! - plane stress: `D = E/(1 - nu^2) [[1, nu, 0], [nu, 1, 0], [0, 0, (1 - nu)/2]]`.
//!
//! Stresses are reported as full 3D tensors `[s_xx, s_yy, s_zz, s_yz, s_xz, s_xy]`.

use crate::FemError;

/// How a 2D mesh is read (3D meshes are always `Solid`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Analysis {
    /// Plane strain with out-of-plane thickness (forces are per `thickness`).
    PlaneStrain {
        /// Out-of-plane thickness (length).
        thickness: f64,
    },
    /// Plane stress with thickness.
    PlaneStress {
        /// Out-of-plane thickness (length).
        thickness: f64,
    },
    /// Three-dimensional solid.
    Solid,
}

impl Analysis {
    /// Out-of-plane thickness (1 for solids).
    pub fn thickness(self) -> f64 {
        match self {
            Analysis::PlaneStrain { thickness } | Analysis::PlaneStress { thickness } => thickness,
            Analysis::Solid => 1.0,
        }
    }

    /// Number of Voigt strain components (3 in 2D, 6 in 3D).
    pub fn n_voigt(self) -> usize {
        match self {
            Analysis::Solid => 6,
            _ => 3,
        }
    }

    /// Spatial dimension (2 or 3).
    pub fn dim(self) -> usize {
        match self {
            Analysis::Solid => 3,
            _ => 2,
        }
    }
}

/// An isotropic linear-elastic material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Young's modulus (stress unit, e.g. MPa).
    pub young: f64,
    /// Poisson's ratio (-1 < nu < 0.5).
    pub poisson: f64,
    /// Mass density (mass / volume, e.g. tonne/mm^3), used by centrifugal and gravity loads.
    pub density: f64,
}

impl Material {
    /// A validated material.
    ///
    /// # Errors
    /// [`FemError::InvalidMaterial`] if `E <= 0`, `nu` outside `(-1, 0.5)`, `rho < 0` or any is
    /// not finite.
    pub fn new(young: f64, poisson: f64, density: f64) -> Result<Self, FemError> {
        let bad = |m: String| Err(FemError::InvalidMaterial(m));
        if !(young.is_finite() && young > 0.0) {
            return bad(format!("Young's modulus must be > 0, got {young}"));
        }
        if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
            return bad(format!(
                "Poisson's ratio must be in (-1, 0.5), got {poisson}"
            ));
        }
        if !(density.is_finite() && density >= 0.0) {
            return bad(format!("density must be >= 0, got {density}"));
        }
        Ok(Material {
            young,
            poisson,
            density,
        })
    }

    /// Lame constants `(lambda, mu)`.
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }

    /// Hooke matrix `D` (row-major, `n_voigt x n_voigt`) for `analysis`.
    pub fn hooke(&self, analysis: Analysis) -> Vec<f64> {
        let (lam, mu) = self.lame();
        match analysis {
            Analysis::PlaneStrain { .. } => vec![
                lam + 2.0 * mu,
                lam,
                0.0,
                lam,
                lam + 2.0 * mu,
                0.0,
                0.0,
                0.0,
                mu,
            ],
            Analysis::PlaneStress { .. } => {
                let (e, nu) = (self.young, self.poisson);
                let c = e / (1.0 - nu * nu);
                vec![
                    c,
                    c * nu,
                    0.0,
                    c * nu,
                    c,
                    0.0,
                    0.0,
                    0.0,
                    c * (1.0 - nu) / 2.0,
                ]
            }
            Analysis::Solid => {
                let mut d = vec![0.0; 36];
                for i in 0..3 {
                    for j in 0..3 {
                        d[i * 6 + j] = lam;
                    }
                    d[i * 6 + i] = lam + 2.0 * mu;
                    d[(i + 3) * 6 + i + 3] = mu;
                }
                d
            }
        }
    }

    /// Full stress `[xx, yy, zz, yz, xz, xy]` from a Voigt strain.
    pub fn stress(&self, analysis: Analysis, eps: &[f64]) -> [f64; 6] {
        let (lam, mu) = self.lame();
        match analysis {
            Analysis::Solid => {
                let tr = eps[0] + eps[1] + eps[2];
                [
                    lam * tr + 2.0 * mu * eps[0],
                    lam * tr + 2.0 * mu * eps[1],
                    lam * tr + 2.0 * mu * eps[2],
                    mu * eps[3],
                    mu * eps[4],
                    mu * eps[5],
                ]
            }
            Analysis::PlaneStrain { .. } => {
                let tr = eps[0] + eps[1];
                let sxx = lam * tr + 2.0 * mu * eps[0];
                let syy = lam * tr + 2.0 * mu * eps[1];
                [sxx, syy, self.poisson * (sxx + syy), 0.0, 0.0, mu * eps[2]]
            }
            Analysis::PlaneStress { .. } => {
                let c = self.young / (1.0 - self.poisson * self.poisson);
                let nu = self.poisson;
                [
                    c * (eps[0] + nu * eps[1]),
                    c * (nu * eps[0] + eps[1]),
                    0.0,
                    0.0,
                    0.0,
                    c * (1.0 - nu) / 2.0 * eps[2],
                ]
            }
        }
    }
}

/// Von Mises equivalent stress of `[xx, yy, zz, yz, xz, xy]`.
pub fn von_mises(s: &[f64; 6]) -> f64 {
    let d = (s[0] - s[1]).powi(2) + (s[1] - s[2]).powi(2) + (s[2] - s[0]).powi(2);
    (0.5 * d + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5])).sqrt()
}
