//! The rotation of a cyclic-symmetry interface (module [`crate::cyclic`]): the sector's angle,
//! axis and centre, its matrix `R` (Rodrigues) and `R v`, `R^T v`. A leaf module: the
//! assembly's description holds a [`Cyclic`] without depending on the cyclic pairing.

use crate::LatinError;

type V3 = [f64; 3];

/// A 3 x 3 matrix, row-major.
pub type Mat3 = [[f64; 3]; 3];

/// The rotation of a cyclic interface: by `angle` (radians) about the axis `axis` (unit)
/// through `center`; side 2 is side 1's image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cyclic {
    /// Sector angle (radians), in `(0, pi]`.
    pub angle: f64,
    /// A point of the axis.
    pub center: V3,
    /// Unit axis (right-hand rule; in 2D `[0, 0, 1]` or `[0, 0, -1]`).
    pub axis: V3,
}

impl Cyclic {
    /// A rotation by `angle_deg` degrees about `axis` through `center`.
    ///
    /// # Errors
    /// [`LatinError::Invalid`] if the angle is not finite and in `(0, 180]`, or the axis is
    /// not finite and non-zero.
    pub fn new(angle_deg: f64, center: V3, axis: V3) -> Result<Self, LatinError> {
        check_angle(angle_deg).map_err(LatinError::Invalid)?;
        let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if !(len.is_finite() && len > 0.0) || center.iter().any(|v| !v.is_finite()) {
            return Err(LatinError::Invalid(format!(
                "cyclic axis {axis:?} must be finite and non-zero and the centre {center:?} finite"
            )));
        }
        Ok(Cyclic {
            angle: angle_deg.to_radians(),
            center,
            axis: [axis[0] / len, axis[1] / len, axis[2] / len],
        })
    }

    /// The rotation matrix `R` (Rodrigues).
    pub fn matrix(&self) -> Mat3 {
        let [x, y, z] = self.axis;
        let (s, c) = self.angle.sin_cos();
        let t = 1.0 - c;
        [
            [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
            [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
            [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
        ]
    }

    /// The image of point `x`, `c + R (x - c)`.
    pub fn map_point(&self, x: &V3) -> V3 {
        let d = [
            x[0] - self.center[0],
            x[1] - self.center[1],
            x[2] - self.center[2],
        ];
        let r = apply(&self.matrix(), &d);
        [
            self.center[0] + r[0],
            self.center[1] + r[1],
            self.center[2] + r[2],
        ]
    }

    /// The pre-image of point `x`, `c + R^T (x - c)`.
    pub fn unmap_point(&self, x: &V3) -> V3 {
        let d = [
            x[0] - self.center[0],
            x[1] - self.center[1],
            x[2] - self.center[2],
        ];
        let r = apply_transpose(&self.matrix(), &d);
        [
            self.center[0] + r[0],
            self.center[1] + r[1],
            self.center[2] + r[2],
        ]
    }
}

/// Checks a sector angle in degrees: finite and in `(0, 180]` (the faces of a sector of more
/// than half a turn would overlap their images). 360 need not be a multiple of it (the zero
/// harmonic of any repeated sector is the same equations). Returns what is wrong.
///
/// # Errors
/// The message for an angle outside `(0, 180]` or not finite.
pub fn check_angle(angle_deg: f64) -> Result<(), String> {
    if angle_deg.is_finite() && angle_deg > 0.0 && angle_deg <= 180.0 {
        Ok(())
    } else {
        Err(format!(
            "the cyclic sector angle must be finite and in (0, 180] degrees, got {angle_deg}"
        ))
    }
}

/// `R v`.
pub fn apply(r: &Mat3, v: &V3) -> V3 {
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

/// `R^T v`.
pub fn apply_transpose(r: &Mat3, v: &V3) -> V3 {
    [0, 1, 2].map(|i| r[0][i] * v[0] + r[1][i] * v[1] + r[2][i] * v[2])
}
