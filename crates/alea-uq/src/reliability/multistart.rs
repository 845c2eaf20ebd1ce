//! FORM from several starting points: a limit state may have several design points (local
//! minima of `|u|` on `G(u) = 0`, e.g. a symmetric one), and FORM from the median point finds
//! at most one - or none, when the gradient vanishes there by symmetry.
//!
//! [`axis_starts`] gives the median point and `+-3` along every axis of the standard normal
//! space (`2 d + 1` starts). [`form_from_starts`] runs [`form`] from each and keeps the
//! distinct design points (apart by more than 10 % of the smaller `beta`), smallest `beta`
//! first, with the best one and the options that found it. When more than one lies within
//! `beta_min + 1`, FORM, SORM and importance sampling around the best miss the others' share
//! of the probability: [`MultiStart::several_design_points`] says so.

use super::{FormOptions, FormResult, LimitState, form};

/// The outcome of [`form_from_starts`].
#[derive(Debug, Clone)]
pub struct MultiStart {
    /// The distinct design points, smallest `beta` first.
    pub found: Vec<FormResult>,
    /// The design point of smallest `beta` with the options (start) that found it.
    pub best: Option<(FormResult, FormOptions)>,
    /// The first error of a start that did not converge.
    pub first_error: Option<String>,
}

impl MultiStart {
    /// The warning when more than one distinct design point lies within `beta_min + 1`.
    pub fn several_design_points(&self) -> Option<String> {
        let b0 = self.found.first()?.beta;
        let close = self.found.iter().filter(|f| f.beta <= b0 + 1.0).count();
        (close > 1).then(|| {
            format!(
                "{close} design points within beta {b0:.3} + 1: FORM, SORM and importance sampling around the first miss the others' share of the probability; compare with subset simulation"
            )
        })
    }
}

/// The median point (`None`: FORM's default start) and `+-3` along every axis of the
/// `d`-dimensional standard normal space.
pub fn axis_starts(d: usize) -> Vec<Option<Vec<f64>>> {
    let mut starts = vec![None];
    for j in 0..d {
        for s in [3.0, -3.0] {
            let mut u = vec![0.0; d];
            u[j] = s;
            starts.push(Some(u));
        }
    }
    starts
}

/// FORM with the options `base` from each of `starts` (see the module docs).
pub fn form_from_starts(
    ls: &LimitState,
    starts: &[Option<Vec<f64>>],
    base: &FormOptions,
) -> MultiStart {
    let mut best: Option<(FormResult, FormOptions)> = None;
    let mut found: Vec<FormResult> = Vec::new();
    let mut first_error = None;
    for start in starts {
        let opts = FormOptions {
            start: start.clone(),
            ..base.clone()
        };
        match form(ls, &opts) {
            Ok(f) => {
                let distinct = found.iter().all(|g| {
                    let dist: f64 = g
                        .u_star
                        .iter()
                        .zip(&f.u_star)
                        .map(|(a, b)| (a - b).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    dist > 0.1 * g.beta.min(f.beta).max(1e-3)
                });
                if distinct {
                    found.push(f.clone());
                }
                if best.as_ref().is_none_or(|(b, _)| f.beta < b.beta) {
                    best = Some((f, opts));
                }
            }
            Err(e) => {
                first_error.get_or_insert(e.to_string());
            }
        }
    }
    found.sort_by(|a, b| a.beta.total_cmp(&b.beta));
    MultiStart {
        found,
        best,
        first_error,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::joint::Independent;
    use crate::law::{Marginal, Normal};
    use std::sync::Arc;

    /// `u2 >= 3 - u1^2 / 2`: design points `(+-2, 1)` (beta `sqrt 5`) and the saddle `(0, 3)`
    /// HL-RF reaches from the median by symmetry.
    #[test]
    fn a_symmetric_parabola_has_three_design_points_and_a_warning() {
        let m: Vec<Arc<dyn Marginal>> =
            vec![Arc::new(Normal::standard()), Arc::new(Normal::standard())];
        let law = Independent::new(m).unwrap();
        let ls = LimitState::new(&law, |u| 3.0 - 0.5 * u[0] * u[0] - u[1]);
        let r = form_from_starts(&ls, &axis_starts(2), &FormOptions::default());
        let betas: Vec<f64> = r.found.iter().map(|f| f.beta).collect();
        assert_eq!(betas.len(), 3, "{betas:?}");
        assert!((betas[0] - 5f64.sqrt()).abs() < 1e-6 && (betas[1] - 5f64.sqrt()).abs() < 1e-6);
        assert!((betas[2] - 3.0).abs() < 1e-6);
        let (best, opts) = r.best.as_ref().unwrap();
        assert!((best.beta - 5f64.sqrt()).abs() < 1e-6 && opts.start.is_some());
        let w = r.several_design_points().unwrap();
        assert!(
            w.starts_with("3 design points within beta 2.236 + 1"),
            "{w}"
        );
        // One design point: no warning.
        let ls = LimitState::new(&law, |u| 3.0 - u[1]);
        let r = form_from_starts(&ls, &axis_starts(2), &FormOptions::default());
        assert_eq!(r.found.len(), 1);
        assert!(r.several_design_points().is_none());
    }
}
