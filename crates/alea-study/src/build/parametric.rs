//! The built model ([`BuiltModel`]) and how the parameters enter it ([`Parametric`]).

use std::sync::Arc;

use alea_latin::{Assembly, LatinOptions, PointField, RunInput};
use alea_mesh::Mesh;

use crate::StudyError;
use crate::expr::Expr;

/// How the parameters enter the model: expressions evaluated for each run.
#[derive(Clone, Debug)]
pub struct Parametric {
    /// Number of parameters.
    pub nparams: usize,
    /// Young's modulus of each substructure (expression of the parameters).
    pub young: Vec<Expr>,
    /// Its value at the nominal point (the factorised reference).
    pub young_nominal: Vec<f64>,
    /// Factor of each load case of each substructure.
    pub load_factors: Vec<Vec<Expr>>,
    /// Friction profile of each interface (expression of the parameters, `x, y, z` and the
    /// defines, in that slot order).
    pub mu: Vec<Expr>,
    /// Gap profile of each interface (same variables).
    pub gap: Vec<Expr>,
    /// The `[[define]]` expressions, evaluated in order after `x, y, z`.
    pub defines: Vec<Expr>,
}

impl Parametric {
    /// The field `x -> e(theta, x, defines)` of an interface profile expression at `theta`.
    pub(crate) fn profile(&self, e: &Expr, theta: &[f64]) -> PointField {
        let e = e.clone();
        let defines = self.defines.clone();
        let theta = theta.to_vec();
        Arc::new(move |x: [f64; 3]| {
            let mut v = Vec::with_capacity(theta.len() + 3 + defines.len());
            v.extend_from_slice(&theta);
            v.extend_from_slice(&x);
            for d in &defines {
                let val = d.eval(&v);
                v.push(val);
            }
            e.eval(&v)
        })
    }

    /// `e` (an interface profile expression) at `theta` at every point of `xs`, into `out`:
    /// the values of [`Parametric::profile`], with one buffer for all points and only the
    /// defines `e` needs (directly or through later defines) evaluated - what the error
    /// estimate calls for every interface at every parameter point of its rules and maps.
    pub(crate) fn eval_profile(&self, e: &Expr, theta: &[f64], xs: &[[f64; 3]], out: &mut [f64]) {
        let first = theta.len() + 3;
        let nd = self.defines.len();
        let mut needed = vec![false; nd];
        for j in (0..nd).rev() {
            needed[j] = e.uses(first + j)
                || (j + 1..nd).any(|k| needed[k] && self.defines[k].uses(first + j));
        }
        let mut v = Vec::with_capacity(first + nd);
        v.extend_from_slice(theta);
        for (o, x) in out.iter_mut().zip(xs) {
            v.truncate(theta.len());
            v.extend_from_slice(x);
            for (d, &need) in self.defines.iter().zip(&needed) {
                let val = if need { d.eval(&v) } else { 0.0 };
                v.push(val);
            }
            *o = e.eval(&v);
        }
    }

    /// The solver input for parameter point `theta`; `params` is the normalised point used
    /// to find the nearest finished run.
    pub fn run_input(&self, theta: &[f64], params: Vec<f64>) -> RunInput {
        RunInput {
            young_factors: self
                .young
                .iter()
                .zip(&self.young_nominal)
                .map(|(e, n)| e.eval(theta) / n)
                .collect(),
            load_factors: self
                .load_factors
                .iter()
                .map(|f| f.iter().map(|e| e.eval(theta)).collect())
                .collect(),
            mu: self
                .mu
                .iter()
                .map(|e| Some(self.profile(e, theta)))
                .collect(),
            gap: self
                .gap
                .iter()
                .map(|e| Some(self.profile(e, theta)))
                .collect(),
            params,
            initial: None,
            previous_step: None,
        }
    }
}

/// A model ready to solve.
#[derive(Clone, Debug)]
pub struct BuiltModel {
    /// The whole mesh (before the split into substructures).
    pub mesh: Mesh,
    /// Substructures and interfaces.
    pub assembly: Assembly,
    /// Names of each substructure's load cases (empty string for unnamed ones).
    pub load_names: Vec<Vec<String>>,
    /// Solver options.
    pub options: LatinOptions,
    /// Units as stated.
    pub units: crate::spec::UnitsSpec,
    /// How the parameters enter the model.
    pub parametric: Parametric,
    /// Where each `[[interface]]` entry is in the model file (for pairing errors).
    pub interface_sites: Vec<InterfaceSite>,
}

/// The file and lines of one `[[interface]]` entry.
#[derive(Clone, Debug)]
pub struct InterfaceSite {
    /// The model file.
    pub file: std::path::PathBuf,
    /// Line of `side2`.
    pub side2: usize,
    /// Line of `tolerance` (of `side2` if not given).
    pub tolerance: usize,
    /// Line of `search_distance` (of `side2` if not given).
    pub search_distance: usize,
    /// Line of `sliding` (of `side2` if not given).
    pub sliding: usize,
}

impl BuiltModel {
    /// Sets up the LATIN solver of the model. An interface whose sides cannot be paired
    /// (node-to-node sides that do not match, no part of side 2 within the mortar search
    /// distance, ...) is an input error naming the file, the `[[interface]]` entry's line and
    /// the field.
    pub fn solver(&self) -> Result<alea_latin::LatinSolver, StudyError> {
        alea_latin::LatinSolver::new(self.assembly.clone(), self.options.clone()).map_err(|e| {
            let (name, unmatched) = match &e {
                alea_latin::LatinError::Unmatched { interface, .. } => (interface, true),
                alea_latin::LatinError::Pairing { interface, .. } => (interface, false),
                _ => return StudyError::Latin(e),
            };
            let found = self
                .assembly
                .interfaces
                .iter()
                .position(|i| &i.name == name);
            match found.and_then(|i| Some((i, self.interface_sites.get(i)?))) {
                Some((i, site)) => {
                    let (field, line) = if unmatched {
                        ("tolerance", site.tolerance)
                    } else if self.assembly.interfaces[i].search_distance.is_some() {
                        ("search_distance", site.search_distance)
                    } else {
                        ("side2", site.side2)
                    };
                    StudyError::Input {
                        file: site.file.clone(),
                        line,
                        field: format!("interface[{i}].{field}"),
                        message: e.to_string(),
                    }
                }
                None => StudyError::Latin(e),
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `eval_profile` skips the defines a profile does not need and gives the values of
    /// `profile`, bit for bit.
    #[test]
    fn profiles_evaluated_in_bulk_are_the_pointwise_ones() {
        let vars = ["a", "b", "x", "y", "z", "s", "xr", "xl", "zw"];
        let e = |t: &str, n: usize| Expr::parse(t, &vars[..n]).unwrap();
        let defines = vec![
            e("(199.84 - y) / 6.55", 5),
            e("0.7 + 0.8 * s", 6),
            e("1.5 - 0.8 * s", 7),
            e("a * (0.075 * z^2 - 0.55 * z + 1) + b * z", 8),
        ];
        let mu = e(
            "0.2 + 0.6 * (a * exp(-(xr - 0.7)^2 / 0.13) + b * exp(-(xr - 1.5)^2 / 0.13)) * zw",
            9,
        );
        let p = Parametric {
            nparams: 2,
            young: vec![],
            young_nominal: vec![],
            load_factors: vec![],
            mu: vec![mu.clone()],
            gap: vec![],
            defines,
        };
        let xs: Vec<[f64; 3]> = (0..50)
            .map(|i| {
                let t = i as f64 / 49.0;
                [3.0 + t, 199.8 - 6.5 * t, 20.0 * t * t]
            })
            .collect();
        for theta in [[0.0, 1.0], [0.3, 0.8], [1.0, 0.0]] {
            let mut out = vec![0.0; xs.len()];
            p.eval_profile(&mu, &theta, &xs, &mut out);
            let f = p.profile(&mu, &theta);
            for (x, o) in xs.iter().zip(&out) {
                assert_eq!(f(*x).to_bits(), o.to_bits(), "{x:?}");
            }
            assert!(out.iter().all(|v| v.is_finite()));
        }
    }
}
