//! The statistic a budget row, a goal or a report names: the mean, the standard deviation, a
//! quantile or an exceedance probability. Written (`Display`, serde) as it always was in
//! `summary.json` and the reports - `mean`, `std`, `q0.05`, `P(> 1165)` - and read back
//! (`FromStr`, serde) from the same words.

use std::borrow::Cow;
use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One statistic of a quantity of interest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Statistic {
    /// The mean (`mean`).
    Mean,
    /// The standard deviation (`std`).
    Std,
    /// The quantile of order `p` (`q0.05` for `p = 0.05`).
    Quantile(f64),
    /// `P(q > t)`, the probability of exceeding the threshold `t` (`P(> 1165)`).
    Exceedance(f64),
}

impl Statistic {
    /// Its threshold, for an exceedance probability.
    pub fn threshold(self) -> Option<f64> {
        match self {
            Statistic::Exceedance(t) => Some(t),
            _ => None,
        }
    }

    /// Its order, for a quantile.
    pub fn order(self) -> Option<f64> {
        match self {
            Statistic::Quantile(p) => Some(p),
            _ => None,
        }
    }

    /// True for an exceedance probability, a statistic in `[0, 1]`.
    pub fn is_probability(self) -> bool {
        matches!(self, Statistic::Exceedance(_))
    }
}

impl fmt::Display for Statistic {
    /// Padded as a string is (`{:<12}` in the statistics table).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let word: Cow<str> = match self {
            Statistic::Mean => "mean".into(),
            Statistic::Std => "std".into(),
            Statistic::Quantile(p) => format!("q{p}").into(),
            Statistic::Exceedance(t) => format!("P(> {t})").into(),
        };
        f.pad(&word)
    }
}

/// A word that names no statistic.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("'{0}' is not a statistic (mean, std, q<order> or P(> <threshold>))")]
pub struct UnknownStatistic(pub String);

impl FromStr for Statistic {
    type Err = UnknownStatistic;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let number = |t: &str| t.parse::<f64>().ok().filter(|v| v.is_finite());
        let parsed = match s {
            "mean" => Some(Statistic::Mean),
            "std" => Some(Statistic::Std),
            _ => {
                if let Some(t) = s.strip_prefix("P(> ").and_then(|r| r.strip_suffix(')')) {
                    number(t).map(Statistic::Exceedance)
                } else {
                    s.strip_prefix('q')
                        .and_then(number)
                        .map(Statistic::Quantile)
                }
            }
        };
        parsed.ok_or_else(|| UnknownStatistic(s.to_string()))
    }
}

impl Serialize for Statistic {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for Statistic {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let s = String::deserialize(deserializer)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every statistic is written as before and read back to itself.
    #[test]
    fn words_round_trip() {
        for (s, word) in [
            (Statistic::Mean, "mean"),
            (Statistic::Std, "std"),
            (Statistic::Quantile(0.05), "q0.05"),
            (Statistic::Quantile(0.5), "q0.5"),
            (Statistic::Exceedance(1165.0), "P(> 1165)"),
            (Statistic::Exceedance(0.13), "P(> 0.13)"),
            (Statistic::Exceedance(-2.5e-7), "P(> -0.00000025)"),
        ] {
            assert_eq!(s.to_string(), word);
            assert_eq!(format!("{s:<12}|"), format!("{word:<12}|"));
            assert_eq!(word.parse::<Statistic>(), Ok(s));
            let json = serde_json::to_string(&s).unwrap();
            assert_eq!(json, format!("\"{word}\""));
            assert_eq!(serde_json::from_str::<Statistic>(&json).unwrap(), s);
        }
        for bad in ["", "median", "q", "qx", "P(> )", "P(> 1", "P(1)", "qNaN"] {
            assert!(bad.parse::<Statistic>().is_err(), "{bad}");
        }
    }
}
