//! Contact quantities of an interface: pressure, slip and status, at a point or integrated.
//!
//! With the interface normal `n` (side 1's outward normal) and the local-stage fields of a run
//! at interface point `i` (lumped weight `w_i`, length x thickness in 2D, area in 3D):
//! - pressure `p_i = F_hat_2 . n` (the normal force density on side 2, >= 0 for unilateral
//!   contact);
//! - slip `s_i = |[W_hat]_t|`, the tangential part of the displacement jump;
//! - status indicator `1` if the point is in the chosen status (open, stick, slip, or closed =
//!   stick or slip), else `0`.
//!
//! At a point the quantity is the value at the interface point nearest to it (a pointwise
//! value: it follows the mesh near contact edges); over the interface it is
//! `sum_i w_i v_i`: the normal force, the integrated slip, or the measure of the zone in the
//! chosen status.

use alea_latin::{InterfaceResult, PointStatus};
use alea_mesh::vec3::dot;

/// Which contact field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactField {
    /// Normal pressure `F_hat_2 . n`.
    Pressure,
    /// Tangential slip `|[W_hat]_t|`.
    Slip,
    /// Indicator of a status.
    Status(StatusSel),
}

/// A contact status, or the union "closed".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StatusSel {
    /// No contact.
    Open,
    /// Closed and sticking.
    Stick,
    /// Closed and slipping.
    Slip,
    /// Stick or slip.
    Closed,
}

impl StatusSel {
    /// Parses `open`, `stick`, `slip`, `closed`.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "open" => StatusSel::Open,
            "stick" => StatusSel::Stick,
            "slip" => StatusSel::Slip,
            "closed" => StatusSel::Closed,
            _ => return None,
        })
    }

    fn holds(self, s: PointStatus) -> bool {
        match self {
            StatusSel::Open => s == PointStatus::Open,
            StatusSel::Stick => s == PointStatus::Stick,
            StatusSel::Slip => s == PointStatus::Slip,
            StatusSel::Closed => matches!(s, PointStatus::Stick | PointStatus::Slip),
        }
    }
}

/// A contact quantity on one interface.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactQoi {
    /// Interface index.
    pub iface: usize,
    /// Field.
    pub field: ContactField,
    /// Side-1 mesh node of the point (`None`: integrated over the interface).
    pub node: Option<usize>,
}

impl ContactQoi {
    fn value(&self, it: &InterfaceResult, i: usize) -> f64 {
        let n = it.points[i].normal;
        match self.field {
            ContactField::Pressure => dot(&it.side2_force(i), &n),
            ContactField::Slip => {
                let j = it.jump(i);
                let jn = dot(&j, &n);
                let t = [j[0] - jn * n[0], j[1] - jn * n[1], j[2] - jn * n[2]];
                dot(&t, &t).sqrt()
            }
            ContactField::Status(s) => f64::from(u8::from(s.holds(it.status[i]))),
        }
    }

    /// The quantity for a run's interface result (`None` if the point's node is not on it,
    /// which the build step rules out).
    pub fn eval(&self, it: &InterfaceResult) -> Option<f64> {
        match self.node {
            Some(node) => {
                let i = it.nodes[0].iter().position(|&n| n == node)?;
                Some(self.value(it, i))
            }
            None => Some(
                (0..it.points.len())
                    .map(|i| it.weights[i] * self.value(it, i))
                    .sum(),
            ),
        }
    }
}
