//! Which substructure factors are stored in single precision (`LatinOptions::factor_precision`;
//! the refinement is alea-fem's `Cholesky::store_single`).
//!
//! On the volume path the linear stage of a large 3D substructure is a triangular solve bound
//! by memory traffic (issue 38: the 3D turbine refined once, 30 parts of 20 000 unknowns, has
//! 10 million factor entries a part and spends 80 % of its run in these solves). With the
//! factor rounded to `f32` a solve reads half the bytes: 0.4 - 0.5x its time
//! (BENCHMARKS.md). The LATIN iteration itself supplies the refinement: each linear stage
//! solves `A0 u_n = b_n` by **one** step from the previous iterate,
//!
//! ```text
//! u_n = u_{n-1} + A0~^{-1} (b_n - A0 u_{n-1})       (A0 u_{n-1} in f64)
//! ```
//!
//! whose error is `delta |u*_n - u*_{n-1}|` (`delta ~ eps_32 kappa(A0)`, measured per factor
//! and at most 1e-2): a fraction of the iteration's own change, which vanishes as the
//! iteration converges, so the converged answer is the double-precision one (`tests/precision.rs`
//! measures the true error against a reference). The set-up's solves (coarse responses,
//! condensed operators) and a run's final recovery refine to full accuracy.
//!
//! [`FactorPrecision::Auto`] stores in single precision the supernodal factors of at least
//! [`SINGLE_MIN_ENTRIES`] entries of the substructures expected on the volume path (the
//! condensed ones use their factor only at set-up and recovery, where refinement costs several
//! solves); [`FactorPrecision::Single`] every factor that refines fast enough, `Double` none.
//! A factor whose refinement would contract by more than 1e-2 per step stays in double
//! precision whatever the setting.

use alea_fem::{Cholesky, SymCsc};

use super::{LatinOptions, LinearStage};

/// Precision of the stored factors (module `precision`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FactorPrecision {
    /// Single precision for large supernodal factors on the volume path (module doc).
    #[default]
    Auto,
    /// Every factor in double precision.
    Double,
    /// Every factor in single precision where its refinement contracts fast enough.
    Single,
}

/// [`FactorPrecision::Auto`]: smallest factor stored in single precision (8 MB in `f64`,
/// beyond the caches, where the solve is bound by memory traffic).
pub const SINGLE_MIN_ENTRIES: usize = 1_000_000;

/// What the set-up knows when it decides a factor's precision.
#[derive(Clone, Copy, Debug)]
pub(super) struct PrecisionChoice {
    precision: FactorPrecision,
    linear_stage: LinearStage,
    expected_runs: usize,
    /// Set up in a deformed configuration (large sliding): always the volume path.
    deformed: bool,
}

impl PrecisionChoice {
    pub(super) fn new(options: &LatinOptions, deformed: bool) -> Self {
        PrecisionChoice {
            precision: options.factor_precision,
            linear_stage: options.linear_stage,
            expected_runs: options.expected_runs,
            deformed,
        }
    }

    /// Stores `chol` (the factor of `a0`; `interface_unknowns` on the substructure's
    /// interfaces) in single precision if the setting asks for it (module doc).
    pub(super) fn apply(&self, chol: &mut Cholesky, a0: &SymCsc, interface_unknowns: usize) {
        let single = match self.precision {
            FactorPrecision::Double => false,
            FactorPrecision::Single => true,
            FactorPrecision::Auto => {
                let condensed = match self.linear_stage {
                    LinearStage::Volume => false,
                    LinearStage::Condensed => true,
                    LinearStage::Auto => {
                        !self.deformed
                            && super::condensed::pays(
                                interface_unknowns,
                                chol.nnz_factor(),
                                self.expected_runs,
                            )
                    }
                };
                chol.is_supernodal() && chol.nnz_factor() >= SINGLE_MIN_ENTRIES && !condensed
            }
        };
        if single {
            chol.store_single(a0);
        }
    }
}
