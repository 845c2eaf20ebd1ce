//! Sobol' indices of every parameter (each KL variable of a random field is one) on a method's
//! surrogate, written for every study whose inputs are independent: which parameter - and with
//! random fields (`[[field]]`), which modes of which field - drives a quantity.
//!
//! * Polynomial chaos (regression, sparse, projection): exact for the expansion `q~ = sum_a c_a
//!   Psi_a`, `S_i = sum_{a: only xi_i} c_a^2 / V`, `S_Ti = sum_{a: xi_i in a} c_a^2 / V`, `V =
//!   sum_{a != 0} c_a^2` (`alea_uq::surrogate::PcExpansion`); per field, the closed index of its
//!   KL variables `S_F = sum_{a: only F's variables} c_a^2 / V` and the total `T_F = 1 - (closed
//!   index of the other variables)`.
//! * Other surrogates (standard polynomial, piecewise linear, adaptive): Saltelli's first-order
//!   and Jansen's total estimators (`alea_uq::sobol`) on [`PICK_FREEZE_SAMPLES`] base draws of
//!   the surrogate (`N (d + 2)` evaluations, seeded from the study's seed: the same for any
//!   thread count), with their standard errors; the per-field indices are left out (they would
//!   need a group pick-freeze).
//!
//! A surrogate of zero variance (a constant quantity) has no indices: the quantity's entry is
//! left out rather than written as 0 / 0. Neither has a study whose `[joint]` makes its
//! parameters dependent: Sobol' indices split the variance among independent inputs.

use serde::Serialize;

use alea_uq::basis::PcBasis;
use alea_uq::surrogate::PcSurrogate;

use crate::method::{Method, MethodKind, Surrogate};
use crate::study::Study;

/// Base sample size of the pick-freeze estimators.
pub const PICK_FREEZE_SAMPLES: usize = 8192;

/// The indices of one field (a group of KL variables).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct FieldSobol {
    /// The field's name.
    pub field: String,
    /// Closed index: the variance share of the terms in its KL variables only.
    pub closed: f64,
    /// Total index: the share of every term with one of its KL variables.
    pub total: f64,
}

/// Sobol' indices of one quantity under one method.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SobolStats {
    /// `pc_expansion` (exact for the surrogate) or `pick_freeze` (Monte Carlo).
    pub estimator: &'static str,
    /// First-order index of each parameter, in the study's parameter order.
    pub first: Vec<f64>,
    /// Total index of each parameter.
    pub total: Vec<f64>,
    /// Standard errors of `first` (pick-freeze only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub first_se: Vec<f64>,
    /// Standard errors of `total` (pick-freeze only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub total_se: Vec<f64>,
    /// Per random field (chaos only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub fields: Vec<FieldSobol>,
}

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The Sobol' indices of quantity values `values` (at `points`, the runs the surrogate `sur` of
/// `method` is built on); `None` for a study without fields, with dependent parameters, a
/// method without a surrogate, or a constant quantity.
pub fn sobol_stats(
    study: &Study,
    method: &Method,
    sur: &Surrogate,
    points: &[Vec<f64>],
    values: &[f64],
) -> Option<SobolStats> {
    let params = &study.params;
    // With a dependent `[joint]` (a copula of the parameters beside the KL variables) the
    // variance does not split into the shares of independent inputs: no classical indices.
    if !params.joint.is_independent() {
        return None;
    }
    let d = params.names.len();
    let pc = match &method.kind {
        MethodKind::PcRegression { degree } => {
            let flat: Vec<f64> = points.iter().flatten().copied().collect();
            let basis = PcBasis::total_degree(&params.marginals, *degree).ok()?;
            Some(PcSurrogate::regression(basis, &flat).ok()?)
        }
        MethodKind::PcSparse { .. } => {
            let flat: Vec<f64> = points.iter().flatten().copied().collect();
            let set = alea_uq::basis::MultiIndexSet::from_indices(d, method.sparse_basis.as_ref()?)
                .ok()?;
            let basis = PcBasis::new(&params.marginals, set).ok()?;
            Some(PcSurrogate::regression(basis, &flat).ok()?)
        }
        MethodKind::PcProjection { degree } => {
            let basis = PcBasis::total_degree(&params.marginals, *degree).ok()?;
            Some(PcSurrogate::projection(basis, method.rule.as_ref()?).ok()?)
        }
        MethodKind::MonteCarlo => return None,
        _ => None,
    };
    if let Some(pc) = pc {
        let e = pc.expansion(values).ok()?;
        if !(e.variance() > 0.0) {
            return None;
        }
        let fields = params
            .fields
            .iter()
            .map(|f| {
                let mine: Vec<usize> =
                    (f.first_variable..f.first_variable + f.num_variables()).collect();
                let others: Vec<usize> = (0..d).filter(|j| !mine.contains(j)).collect();
                FieldSobol {
                    field: f.name.clone(),
                    closed: e.sobol_closed(&mine),
                    total: 1.0 - e.sobol_closed(&others),
                }
            })
            .collect::<Vec<_>>();
        let (first, total) = (e.sobol_first(), e.sobol_total());
        let ok = finite(&first)
            && finite(&total)
            && fields
                .iter()
                .all(|f| f.closed.is_finite() && f.total.is_finite());
        return ok.then_some(SobolStats {
            estimator: "pc_expansion",
            first,
            total,
            first_se: Vec::new(),
            total_se: Vec::new(),
            fields,
        });
    }
    pick_freeze(study, sur, values)
}

/// Saltelli / Jansen pick-freeze indices of the surrogate `sur` with run values `values`, on
/// [`PICK_FREEZE_SAMPLES`] base draws (`None` for a constant quantity or a dependent law).
pub fn pick_freeze(study: &Study, sur: &Surrogate, values: &[f64]) -> Option<SobolStats> {
    let params = &study.params;
    // Centred on the runs' mean: Saltelli's first-order estimator averages f(B) (f(AB_i) -
    // f(A)), whose variance grows with the mean squared (a stress of mean 3 300 MPa and std 9
    // gives first-order indices of standard error 5 uncentred).
    let centre = values.iter().sum::<f64>() / values.len().max(1) as f64;
    let model = |x: &[f64]| {
        let (mut t, mut w) = (vec![0.0; x.len()], Vec::new());
        sur.weights(x, &mut t, &mut w);
        w.iter()
            .map(|&(k, wk)| wk * (values[k] - centre))
            .sum::<f64>()
    };
    let s = alea_uq::sobol::sobol_indices(
        params.joint.as_ref(),
        PICK_FREEZE_SAMPLES,
        study.seed.wrapping_add(0x50b0_1000),
        model,
    )
    .ok()?;
    let ok = s.variance > 0.0
        && finite(&s.first)
        && finite(&s.total)
        && finite(&s.first_se)
        && finite(&s.total_se);
    ok.then_some(SobolStats {
        estimator: "pick_freeze",
        first: s.first,
        total: s.total,
        first_se: s.first_se,
        total_se: s.total_se,
        fields: Vec::new(),
    })
}
