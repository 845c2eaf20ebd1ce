//! The built model ([`BuiltModel`]) and how the parameters enter it ([`Parametric`]).

use std::sync::Arc;

use alea_latin::{Assembly, LatinOptions, PointField, RunInput};
use alea_mesh::Mesh;

use crate::StudyError;
use crate::expr::Expr;
use crate::random_field::{FieldPoint, StudyField};

/// How the parameters enter the model: expressions evaluated for each run.
#[derive(Clone, Debug)]
pub struct Parametric {
    /// Number of parameters.
    pub nparams: usize,
    /// Young's modulus of each substructure (expression of the parameters, then of the
    /// fields: slots `nparams + j` for field `j`).
    pub young: Vec<Expr>,
    /// Its value at the nominal point (the factorised reference).
    pub young_nominal: Vec<f64>,
    /// Per substructure, the fields (indices in `fields`, each over that substructure's cells)
    /// its `young` uses: with any, the modulus varies from cell to cell, each cell's the
    /// expression at the field's mean over the cell.
    pub young_fields: Vec<Vec<usize>>,
    /// Factor of each load case of each substructure.
    pub load_factors: Vec<Vec<Expr>>,
    /// Friction profile of each interface (expression of the parameters, `x, y, z` and the
    /// defines, in that slot order).
    pub mu: Vec<Expr>,
    /// Gap profile of each interface (same variables).
    pub gap: Vec<Expr>,
    /// The `[[define]]` expressions, evaluated in order after `x, y, z`.
    pub defines: Vec<Expr>,
    /// The `[[field]]`s, whose values at the point are the profile variables after the
    /// defines (module `random_field`).
    pub fields: Vec<Arc<StudyField>>,
}

/// Appends the values at `x` of `fields` (0 for those whose `nodal` values are empty: not used
/// by the expression) to `v`.
fn push_fields(fields: &[Arc<StudyField>], nodal: &[Vec<f64>], x: [f64; 3], v: &mut Vec<f64>) {
    for (f, n) in fields.iter().zip(nodal) {
        v.push(if n.is_empty() {
            0.0
        } else {
            f.interpolate(n, x)
        });
    }
}

impl Parametric {
    /// The nodal values at `theta` of the fields `e` uses (empty for the others): the slots
    /// after the parameters, `x, y, z` and the defines.
    fn field_values(&self, e: &Expr, theta: &[f64]) -> Vec<Vec<f64>> {
        let first = theta.len() + 3 + self.defines.len();
        self.fields
            .iter()
            .enumerate()
            .map(|(j, f)| {
                if e.uses(first + j) {
                    f.at_nodes(theta)
                } else {
                    Vec::new()
                }
            })
            .collect()
    }

    /// The field `x -> e(theta, x, defines, fields)` of an interface profile expression at
    /// `theta`.
    pub(crate) fn profile(&self, e: &Expr, theta: &[f64]) -> PointField {
        let nodal = self.field_values(e, theta);
        let e = e.clone();
        let defines = self.defines.clone();
        let fields = self.fields.clone();
        let theta = theta.to_vec();
        Arc::new(move |x: [f64; 3]| {
            let mut v = Vec::with_capacity(theta.len() + 3 + defines.len() + fields.len());
            v.extend_from_slice(&theta);
            v.extend_from_slice(&x);
            for d in &defines {
                let val = d.eval(&v);
                v.push(val);
            }
            push_fields(&fields, &nodal, x, &mut v);
            e.eval(&v)
        })
    }

    /// Interface profile `e` tabulated on the points `xs` ([`ProfileTable`]).
    pub(crate) fn profile_table(&self, e: &Expr, xs: &[[f64; 3]]) -> ProfileTable {
        let first = self.nparams + 3;
        let nd = self.defines.len();
        let mut needed = vec![false; nd];
        for j in (0..nd).rev() {
            needed[j] = e.uses(first + j)
                || (j + 1..nd).any(|k| needed[k] && self.defines[k].uses(first + j));
        }
        // The fields `e` uses (their slots follow the defines; the others stay 0, as in
        // `profile`).
        let used: Vec<Option<Arc<StudyField>>> = self
            .fields
            .iter()
            .enumerate()
            .map(|(j, f)| e.uses(first + nd + j).then(|| f.clone()))
            .collect();
        let points = xs
            .iter()
            .map(|x| {
                let mut known: Vec<Option<f64>> = vec![None; first + nd];
                for (slot, &xi) in known[self.nparams..first].iter_mut().zip(x) {
                    *slot = Some(xi);
                }
                let mut defines = Vec::new();
                for (j, d) in self.defines.iter().enumerate().filter(|&(j, _)| needed[j]) {
                    let folded = d.fold(&known);
                    match folded.as_constant() {
                        Some(v) => known[first + j] = Some(v),
                        None => defines.push((first + j, folded)),
                    }
                }
                TabulatedPoint {
                    defines,
                    fields: used
                        .iter()
                        .map(|f| f.as_ref().map(|f| f.locate(*x)))
                        .collect(),
                    value: e.fold(&known),
                }
            })
            .collect();
        ProfileTable {
            slots: first + nd + self.fields.len(),
            first_field: first + nd,
            fields: used,
            points,
        }
    }

    /// The Young's-modulus factor of substructure `s` at `theta` (1 when it varies from cell
    /// to cell) and, when it does, the factor of each of its cells: `young(theta, u_c) /
    /// young_nominal` with `u_c` each field's mean over cell `c` (NaN where a field's
    /// transform overflows: the run's input check then refuses the point).
    pub fn young_at(&self, s: usize, theta: &[f64]) -> (f64, Option<Arc<Vec<f64>>>) {
        let e = &self.young[s];
        let nominal = self.young_nominal[s];
        let mut vars = theta.to_vec();
        vars.resize(self.nparams + self.fields.len(), 0.0);
        let used = self.young_fields.get(s).map_or(&[][..], Vec::as_slice);
        if used.is_empty() {
            return (e.eval(&vars) / nominal, None);
        }
        let cells: Vec<Vec<f64>> = used
            .iter()
            .map(|&j| self.fields[j].cell_values(&self.fields[j].at_nodes(theta)))
            .collect();
        let n = cells.first().map_or(0, Vec::len);
        let factors = (0..n)
            .map(|c| {
                for (&j, values) in used.iter().zip(&cells) {
                    vars[self.nparams + j] = values[c];
                }
                e.eval(&vars) / nominal
            })
            .collect();
        (1.0, Some(Arc::new(factors)))
    }

    /// A copy of substructure `s`'s reference model `base` with its Young's modulus at
    /// `theta` (its factor, or its cells' factors when it varies from cell to cell).
    ///
    /// # Errors
    /// If a cell factor is not finite and > 0 (a field's transform overflowed).
    pub fn scaled_model(
        &self,
        base: &alea_fem::Model,
        s: usize,
        theta: &[f64],
    ) -> Result<alea_fem::Model, StudyError> {
        let (factor, cells) = self.young_at(s, theta);
        let mut model = base.clone();
        model.scale_young(factor);
        if let Some(f) = cells {
            model
                .scale_young_per_cell(&f)
                .map_err(|e| StudyError::Failed(format!("Young's modulus at {theta:?}: {e}")))?;
        }
        Ok(model)
    }

    /// The solver input for parameter point `theta` (cold: the caller sets its start).
    pub fn run_input(&self, theta: &[f64]) -> RunInput {
        let young: Vec<(f64, Option<Arc<Vec<f64>>>)> = (0..self.young.len())
            .map(|s| self.young_at(s, theta))
            .collect();
        let cell_young = if young.iter().any(|y| y.1.is_some()) {
            young.iter().map(|y| y.1.clone()).collect()
        } else {
            Vec::new()
        };
        RunInput {
            young_factors: young.iter().map(|y| y.0).collect(),
            cell_young,
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
            initial: None,
            previous_step: None,
            damped: false,
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
    /// Settings of the re-pairing of large-sliding interfaces (`[solver] repair_tolerance`,
    /// `max_pairings`).
    pub repairing: alea_latin::large_sliding::Repairing,
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
    /// Line of `cyclic` (of `side2` if not given).
    pub cyclic: usize,
}

impl BuiltModel {
    /// Sets up the LATIN solver of the model. An interface whose sides cannot be paired
    /// (node-to-node sides that do not match, no part of side 2 within the mortar search
    /// distance, ...) is an input error naming the file, the `[[interface]]` entry's line and
    /// the field.
    pub fn solver(&self) -> Result<alea_latin::LatinSolver, StudyError> {
        self.solver_on(None)
    }

    /// [`BuiltModel::solver`] spread over the ranks of `ranks` (`None`: one process; module
    /// `alea_latin::ranks`).
    pub fn solver_on(
        &self,
        ranks: Option<std::sync::Arc<dyn alea_latin::RankExchange>>,
    ) -> Result<alea_latin::LatinSolver, StudyError> {
        let (asm, options) = (self.assembly.clone(), self.options.clone());
        let built = match ranks {
            Some(r) => alea_latin::LatinSolver::with_ranks(asm, options, r),
            None => alea_latin::LatinSolver::new(asm, options),
        };
        built.map_err(|e| {
            let (name, unmatched, cyclic) = match &e {
                alea_latin::LatinError::Unmatched { interface, .. } => (interface, true, false),
                alea_latin::LatinError::Pairing { interface, .. } => (interface, false, false),
                alea_latin::LatinError::Cyclic { interface, .. } => (interface, false, true),
                _ => return StudyError::Latin(e),
            };
            let found = self
                .assembly
                .interfaces
                .iter()
                .position(|i| &i.name == name);
            match found.and_then(|i| Some((i, self.interface_sites.get(i)?))) {
                Some((i, site)) => {
                    let (field, line) = if cyclic {
                        ("cyclic", site.cyclic)
                    } else if unmatched {
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

/// An interface profile `e(theta, x, defines)` tabulated on a fixed point set (issue 20,
/// item 4): at each point, what depends on the point only - its coordinates, the defines that
/// do not depend on the parameters, every such subtree of `e` and of the parameter-dependent
/// defines - is evaluated once ([`Expr::fold`]), so that a parameter point costs the
/// parameter-dependent operations only. The error estimate evaluates the friction profile of
/// every interface at every point of its integration rules and maps (on the 3D turbine, 962
/// interface points at each of ~10^5 map points); the values are those of
/// [`Parametric::profile`], bit for bit (the folded parts are computed by the same
/// arithmetic in the same order).
pub(crate) struct ProfileTable {
    /// Length of the slot vector: parameters, `x, y, z`, the defines, the fields.
    slots: usize,
    /// Slot of the first field.
    first_field: usize,
    /// The fields the profile uses (`None`: not used, its slot stays 0).
    fields: Vec<Option<Arc<StudyField>>>,
    points: Vec<TabulatedPoint>,
}

/// One point of a [`ProfileTable`].
struct TabulatedPoint {
    /// The defines that depend on the parameters, folded, with their slots, in order.
    defines: Vec<(usize, Expr)>,
    /// Where the point falls in the mesh of each field the profile uses.
    fields: Vec<Option<FieldPoint>>,
    /// The profile, folded.
    value: Expr,
}

impl ProfileTable {
    /// The profile at parameter point `theta` at every point, into `out`.
    pub(crate) fn eval(&self, theta: &[f64], out: &mut [f64]) {
        let mut v = vec![0.0; self.slots];
        v[..theta.len()].copy_from_slice(theta);
        let nodal: Vec<Option<Vec<f64>>> = self
            .fields
            .iter()
            .map(|f| f.as_ref().map(|f| f.at_nodes(theta)))
            .collect();
        for (o, p) in out.iter_mut().zip(&self.points) {
            for (slot, d) in &p.defines {
                v[*slot] = d.eval(&v);
            }
            for (j, (at, values)) in p.fields.iter().zip(&nodal).enumerate() {
                if let (Some(at), Some(values)) = (at, values) {
                    v[self.first_field + j] = at.value(values);
                }
            }
            *o = p.value.eval(&v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profile tabulated on a point set (`profile_table`: point-only parts folded, the
    /// defines it does not need skipped) gives the values of `profile`, bit for bit.
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
            young_fields: vec![],
            load_factors: vec![],
            mu: vec![mu.clone()],
            gap: vec![],
            defines,
            fields: vec![],
        };
        let xs: Vec<[f64; 3]> = (0..50)
            .map(|i| {
                let t = i as f64 / 49.0;
                [3.0 + t, 199.8 - 6.5 * t, 20.0 * t * t]
            })
            .collect();
        let table = p.profile_table(&mu, &xs);
        for theta in [[0.0, 1.0], [0.3, 0.8], [1.0, 0.0]] {
            let mut out = vec![0.0; xs.len()];
            table.eval(&theta, &mut out);
            let f = p.profile(&mu, &theta);
            for (x, o) in xs.iter().zip(&out) {
                assert_eq!(f(*x).to_bits(), o.to_bits(), "{x:?}");
            }
            assert!(out.iter().all(|v| v.is_finite()));
        }
    }

    /// With random fields in the profiles (`examples/blade-root-simple-field.toml`, mu a
    /// bounded field on each flank, its mesh coarsened): the table (fields located once per
    /// point) gives the values of `profile`, bit for bit, at the solver's interface points.
    #[test]
    fn profiles_with_random_fields_tabulated_are_the_pointwise_ones() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../examples/blade-root-simple-field.toml"
        );
        let text = std::fs::read_to_string(path).unwrap().replace(
            "n_flank = 36, n_side = 45, n_root = 36, n_shank = 27",
            "n_flank = 12, n_side = 15, n_root = 12, n_shank = 9",
        );
        let study =
            crate::study::Study::from_source(crate::Source::from_text(path, &text)).unwrap();
        let p = &study.model.parametric;
        assert!(!p.fields.is_empty());
        let solver =
            alea_latin::LatinSolver::new(study.model.assembly.clone(), study.model.options.clone())
                .unwrap();
        let n = p.nparams;
        for i in 0..solver.num_interfaces() {
            let xs: Vec<[f64; 3]> = solver.interface_points(i).iter().map(|q| q.x).collect();
            for e in [&p.mu[i], &p.gap[i]] {
                let table = p.profile_table(e, &xs);
                for k in 0..4 {
                    let theta: Vec<f64> = (0..n)
                        .map(|j| 0.6 * (((j + 3 * k) % 7) as f64 - 3.0) + 0.1 * k as f64)
                        .collect();
                    let mut out = vec![0.0; xs.len()];
                    table.eval(&theta, &mut out);
                    let f = p.profile(e, &theta);
                    for (x, o) in xs.iter().zip(&out) {
                        assert_eq!(f(*x).to_bits(), o.to_bits(), "interface {i} at {x:?}");
                    }
                }
            }
        }
    }
}
