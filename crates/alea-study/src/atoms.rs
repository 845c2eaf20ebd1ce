//! A quantity's law as probability atoms and a continuous density (issue 40, item 3).
//!
//! A value that a share of at least [`ATOM_SHARE`] of the samples takes exactly (a contact
//! pressure that is exactly 0 wherever the contact opens, a quantity clamped at a bound) is a
//! probability atom: its mass is the share of samples equal to it, with its Wilson interval
//! (sampling only). The Gaussian kernel density of the other samples, scaled by their share,
//! is the continuous part, so that the atoms' masses and the density's integral sum to 1. A
//! kernel density of all the samples would draw an atom as a spike whose height depends on the
//! bandwidth (and the bandwidth rules, fed with a sample whose interquartile range may be 0,
//! shrink it to nothing: one vertical line).

use alea_uq::kde::{Bandwidth, Kde};
use alea_uq::stats::failure_probability;
use serde::{Deserialize, Serialize};

/// The smallest share of the samples one value must take exactly to be an atom.
pub const ATOM_SHARE: f64 = 0.01;

/// A value the quantity takes with positive probability.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Atom {
    /// The value.
    pub value: f64,
    /// Its probability: the share of the samples equal to it.
    pub probability: f64,
    /// Lower bound of the Wilson interval of the probability (sampling only).
    pub ci_low: f64,
    /// Upper bound.
    pub ci_high: f64,
}

/// A law split into atoms and a continuous density.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SplitLaw {
    /// The atoms, by increasing value.
    pub atoms: Vec<Atom>,
    /// The bandwidth of the continuous part's kernel density (0: none).
    pub bandwidth: f64,
    /// `(x, density)` of the continuous part, scaled by its share of the samples (empty when
    /// fewer than 2 distinct values are left).
    pub kde: Vec<(f64, f64)>,
}

impl SplitLaw {
    /// The continuous part's share of the samples: 1 minus the atoms' probabilities.
    pub fn continuous_share(&self) -> f64 {
        (1.0 - self.atoms.iter().map(|a| a.probability).sum::<f64>()).max(0.0)
    }
}

/// The atoms of `samples` (finite values) and the kernel density of the rest on `points`
/// evenly spaced abscissae from 3 bandwidths below its smallest value to 3 above its largest
/// (as `analysis::qoi_stats` does for the whole sample), with the bandwidth rule `bandwidth`
/// (Silverman's where it fails); intervals at `confidence`. `None` when no value is an atom
/// (the whole sample's density is then the one to draw).
pub fn split_atoms(
    samples: &[f64],
    bandwidth: Bandwidth,
    points: usize,
    confidence: f64,
) -> Option<SplitLaw> {
    let n = samples.len();
    if n == 0 {
        return None;
    }
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    // At least two equal samples, and at least the share.
    let least = ((ATOM_SHARE * n as f64).ceil() as usize).max(2);
    let mut atoms = Vec::new();
    let mut rest = Vec::with_capacity(n);
    let mut i = 0;
    while i < n {
        let v = sorted[i];
        let run = sorted[i..].iter().take_while(|&&x| x == v).count();
        if run >= least {
            // Wilson interval of `run` successes out of `n`: as P(indicator > 0.5).
            let indicator: Vec<f64> = (0..n).map(|k| f64::from(u8::from(k < run))).collect();
            let f = failure_probability(&indicator, 0.5, confidence);
            atoms.push(Atom {
                value: v,
                probability: f.p,
                ci_low: f.lower,
                ci_high: f.upper,
            });
        } else {
            rest.extend_from_slice(&sorted[i..i + run]);
        }
        i += run;
    }
    if atoms.is_empty() {
        return None;
    }
    let share = rest.len() as f64 / n as f64;
    let kde = Kde::new(&rest, bandwidth).or_else(|_| Kde::new(&rest, Bandwidth::Silverman));
    let (bandwidth, kde) = match kde {
        Ok(k) => {
            let h = k.bandwidth();
            let (lo, hi) = (rest[0] - 3.0 * h, rest[rest.len() - 1] + 3.0 * h);
            let m = points.max(2);
            let xs: Vec<f64> = (0..m)
                .map(|j| lo + (hi - lo) * j as f64 / (m - 1) as f64)
                .collect();
            let ys = k.eval_binned(&xs);
            (
                h,
                xs.into_iter()
                    .zip(ys.into_iter().map(|y| share * y))
                    .collect(),
            )
        }
        // Fewer than 2 distinct values left: their mass is not drawn as a density.
        Err(_) => (0.0, Vec::new()),
    };
    Some(SplitLaw {
        atoms,
        bandwidth,
        kde,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Trapezoidal integral of a curve.
    fn integral(c: &[(f64, f64)]) -> f64 {
        c.windows(2)
            .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
            .sum()
    }

    /// Half the samples exactly 0 (a contact that opens), the others uniform on (1, 2): one
    /// atom at 0 of mass 0.5 whose 95 % interval is 0.5 +- 1.96 sqrt(0.25 / n) (Wilson, to
    /// 1e-4), and a continuous density integrating to 0.5 that carries no mass at 0.
    #[test]
    fn half_exact_zeros_make_an_atom_of_one_half() {
        let n = 20_000;
        let samples: Vec<f64> = (0..n)
            .map(|i| {
                if i % 2 == 0 {
                    0.0
                } else {
                    1.0 + (i as f64 + 0.5) / n as f64
                }
            })
            .collect();
        let law = split_atoms(&samples, Bandwidth::Silverman, 512, 0.95).unwrap();
        assert_eq!(law.atoms.len(), 1, "{:?}", law.atoms);
        let a = &law.atoms[0];
        assert_eq!((a.value, a.probability), (0.0, 0.5));
        let half = 1.959_964 * (0.25 / n as f64).sqrt();
        assert!((a.ci_low - (0.5 - half)).abs() < 1e-4, "{a:?}");
        assert!((a.ci_high - (0.5 + half)).abs() < 1e-4, "{a:?}");
        assert!((law.continuous_share() - 0.5).abs() < 1e-15);
        let mass = integral(&law.kde);
        assert!((mass - 0.5).abs() < 5e-3, "continuous mass {mass}");
        // No spike: the curve spans the continuous part only (from 3 bandwidths below 1), and
        // its peak is that of a uniform of mass 0.5 on a width of 1 (0.5, up to the kernel's
        // smoothing).
        assert!(law.kde[0].0 > 0.5, "{:?}", law.kde[0]);
        let peak = law.kde.iter().map(|p| p.1).fold(0.0, f64::max);
        assert!((0.45..0.56).contains(&peak), "peak {peak}");
    }

    /// No value repeated in 1 % of the samples: no atom (the whole sample's density stands);
    /// every sample equal: one atom of mass 1 and no density.
    #[test]
    fn continuous_and_constant_samples() {
        let smooth: Vec<f64> = (0..1000).map(|i| f64::from(i).sqrt()).collect();
        assert!(split_atoms(&smooth, Bandwidth::Silverman, 64, 0.95).is_none());
        // 9 ties of 1000 samples: under 1 %.
        let mut ties = smooth.clone();
        ties[..9].fill(7.5);
        assert!(split_atoms(&ties, Bandwidth::Silverman, 64, 0.95).is_none());
        let law = split_atoms(&[4.0; 50], Bandwidth::Isj, 64, 0.95).unwrap();
        assert_eq!(law.atoms.len(), 1);
        assert_eq!((law.atoms[0].probability, law.atoms[0].ci_high), (1.0, 1.0));
        assert!(law.kde.is_empty() && law.continuous_share() == 0.0);
        assert!(split_atoms(&[], Bandwidth::Isj, 64, 0.95).is_none());
    }
}
