//! The result of phase 1 for any cell family: the equilibrated traction density `F_hat` of
//! every side (first-cell orientation: the traction exerted on the side's first cell; the
//! second cell of an interior side sees `eta F_hat` with `eta = -1`), a polynomial part plus
//! prescribed-traction fields, and the compatibility defect of the node systems (3.22).

use super::loads::SideData;
use crate::data::TractionField;

/// Side densities of phase 1 on the sides of topology `T`, with densities `S`.
#[derive(Clone)]
pub struct SideTractions<T, S> {
    /// The sides (edges in 2D, faces in 3D).
    pub topo: T,
    /// Density of each side.
    pub density: Vec<S>,
    /// Prescribed traction fields (indexed by the densities' `field`).
    pub fields: Vec<TractionField>,
    /// Largest residual of the node systems relative to the largest node load (sum of the
    /// absolute element residuals and data at a node) of the domain: 0 when compatible.
    pub compatibility_defect: f64,
}

impl<T, S> std::fmt::Debug for SideTractions<T, S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SideTractions")
            .field("sides", &self.density.len())
            .field("compatibility_defect", &self.compatibility_defect)
            .finish()
    }
}

impl<T, S> SideTractions<T, S> {
    /// The tractions of the kernel's phase-1 parts: polynomial `values` and prescribed `data`
    /// of each side joined by `density`, the prescribed fields of `tractions`.
    pub(crate) fn from_parts<V, const D: usize>(
        topo: T,
        values: Vec<V>,
        data: Vec<Vec<SideData<D>>>,
        tractions: &[(String, TractionField)],
        compatibility_defect: f64,
        density: impl Fn(V, Vec<SideData<D>>) -> S,
    ) -> Self {
        SideTractions {
            topo,
            density: values
                .into_iter()
                .zip(data)
                .map(|(v, d)| density(v, d))
                .collect(),
            fields: tractions.iter().map(|t| t.1.clone()).collect(),
            compatibility_defect,
        }
    }
}
