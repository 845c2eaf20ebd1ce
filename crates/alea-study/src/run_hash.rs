//! What defines a run, hashed: the **run hash** of a study and the **key of each quantity**.
//!
//! The study hash ([`crate::build::input_hash`]) changes with any byte of the study file, so a
//! comment, a threshold or a new method would make every stored run foreign. A run is defined
//! by less: the model (mesh and the files it reads, analysis, substructures with their
//! materials, loads and constraints, interfaces with their laws and `mu` / `gap` expressions,
//! `[[define]]`s, `[[field]]`s, `[[step]]`s), the parameters (names, order and laws: what a
//! physical point means to the model, with the data files of laws from data) and the solver
//! settings. [`run_identity`] hashes a canonical form of exactly these parts of the parsed file
//! (tables with their keys sorted, every number by its value - `2e5` and `200000` are the same
//! -, no comments, no layout), so that any other edit keeps the stored runs: `[study]` (title,
//! seed), `[units]` (labels, never converted), `[joint]` (the dependence changes which points
//! are drawn, not what a point is), `[[quantity]]` (keyed one by one, below), `[[method]]`,
//! `[[reliability]]`, `[budget]`, `[statistics]`, `[error]` and `[output]`, and the `unit` of
//! a parameter or a field.
//!
//! A run stores the values of the study's quantities, so each quantity has a key of its own:
//! the canonical form of its table without `name`, `unit` and `thresholds` (what it measures,
//! not what it is called or compared with). The store maps a run's stored values to the
//! study's quantities by these keys (`Store::open_study`): removing, reordering, renaming a
//! quantity or changing its thresholds keeps every run; a run that lacks a quantity's value
//! (one added or changed) is computed again - a quantity needs the run's interface fields,
//! which are not stored.

use crate::StudyError;
use crate::source::Source;
use crate::spec::ModelFile;

/// Top-level tables of a study file that do not change what a run is (module doc).
const NOT_RUN_DEFINING: &[&str] = &[
    "study",
    "units",
    "joint",
    "quantity",
    "method",
    "reliability",
    "budget",
    "statistics",
    "error",
    "output",
];

/// Keys of a quantity's table that do not change its value at a run.
const NOT_QUANTITY_DEFINING: &[&str] = &["name", "unit", "thresholds"];

/// Version of the canonical form (a change of the form must change every hash).
const FORM: &str = "alea-run-form-1\n";

/// What defines the runs of a study (module doc).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunIdentity {
    /// Hash of the run-defining parts of the study and of the files they read (16 hex digits).
    pub run_hash: String,
    /// The key of each quantity, in study order (16 hex digits each).
    pub quantities: Vec<String>,
}

impl RunIdentity {
    /// The keys the store keeps with each run (`Store::open_study`).
    pub fn keys(&self) -> crate::store::RunKeys<'_> {
        crate::store::RunKeys {
            run_hash: &self.run_hash,
            quantities: &self.quantities,
        }
    }
}

/// The run identity of the study file `src` (parsed as `file`): its run hash, over the
/// canonical form of its run-defining tables and the bytes of its mesh and data files, and
/// its quantities' keys.
///
/// # Errors
/// If a file it names cannot be read, or the text is not TOML (it was parsed before: an
/// internal error).
pub fn run_identity(src: &Source, file: &ModelFile) -> Result<RunIdentity, StudyError> {
    let table: toml::Table = toml::from_str(&src.text)
        .map_err(|e| StudyError::Internal(format!("a parsed study file is not TOML: {e}")))?;
    let inputs = crate::build::input_files(src, file)?;
    let refs: Vec<&[u8]> = inputs.iter().map(|b| b.as_slice()).collect();
    let quantities = match table.get("quantity") {
        Some(toml::Value::Array(qs)) => qs.iter().map(quantity_key).collect(),
        _ => Vec::new(),
    };
    Ok(RunIdentity {
        run_hash: crate::store::study_hash(&run_form(&table), &refs),
        quantities,
    })
}

/// The canonical form of the run-defining parts of a study file's table.
pub fn run_form(table: &toml::Table) -> String {
    let mut kept = table.clone();
    for k in NOT_RUN_DEFINING {
        kept.remove(*k);
    }
    // The ranks a run is spread over change no bit of it (module `alea_latin::ranks`).
    if let Some(toml::Value::Table(solver)) = kept.get_mut("solver") {
        solver.remove("ranks_per_run");
        if solver.is_empty() {
            kept.remove("solver");
        }
    }
    for list in ["parameter", "field"] {
        if let Some(toml::Value::Array(items)) = kept.get_mut(list) {
            for item in items {
                if let toml::Value::Table(t) = item {
                    t.remove("unit");
                }
            }
        }
    }
    let mut out = String::from(FORM);
    canonical(&toml::Value::Table(kept), &mut out);
    out
}

/// The key of one `[[quantity]]` table (module doc).
pub fn quantity_key(q: &toml::Value) -> String {
    let mut q = q.clone();
    if let toml::Value::Table(t) = &mut q {
        for k in NOT_QUANTITY_DEFINING {
            t.remove(*k);
        }
    }
    let mut out = String::from(FORM);
    canonical(&q, &mut out);
    crate::store::study_hash(&out, &[])
}

/// Appends the canonical form of `v`: length-prefixed strings, numbers by the bits of their
/// value as f64 (integers included, `-0` as `0`), tables with their keys sorted.
fn canonical(v: &toml::Value, out: &mut String) {
    use std::fmt::Write;
    match v {
        toml::Value::String(s) => {
            let _ = write!(out, "s{}:{s}", s.len());
        }
        toml::Value::Integer(i) => number(*i as f64, out),
        toml::Value::Float(f) => number(*f, out),
        toml::Value::Boolean(b) => out.push_str(if *b { "t" } else { "f" }),
        toml::Value::Datetime(d) => {
            let d = d.to_string();
            let _ = write!(out, "d{}:{d}", d.len());
        }
        toml::Value::Array(items) => {
            let _ = write!(out, "[{}:", items.len());
            for item in items {
                canonical(item, out);
            }
            out.push(']');
        }
        toml::Value::Table(t) => {
            let mut keys: Vec<&String> = t.keys().collect();
            keys.sort();
            let _ = write!(out, "{{{}:", keys.len());
            for k in keys {
                let _ = write!(out, "k{}:{k}", k.len());
                canonical(&t[k.as_str()], out);
            }
            out.push('}');
        }
    }
}

/// A number by the bits of its value (`-0` and `0` alike).
fn number(x: f64, out: &mut String) {
    use std::fmt::Write;
    let x = if x == 0.0 { 0.0 } else { x };
    let _ = write!(out, "n{:016x}", x.to_bits());
}

#[cfg(test)]
mod tests {
    use super::*;

    fn form(text: &str) -> String {
        run_form(&toml::from_str(text).unwrap())
    }

    const BASE: &str = "[mesh]\ngenerator = \"rectangle\"\nsize = [100.0, 20.0]\n\
        [[substructure]]\nname = \"plate\"\nyoung = \"E\"\npoisson = 0.0\n\
        [[parameter]]\nname = \"E\"\nlaw = \"uniform\"\nlo = 1.0\nhi = 2.0\n";

    #[test]
    fn layout_comments_and_settings_do_not_change_the_run_form() {
        let base = form(BASE);
        // Comments, key order, integer vs float, units and the settings of the study.
        let same = "# a comment\n[[parameter]]\nhi = 2\nname = \"E\"\nlo = 1.0\nlaw = \"uniform\"\n\
            unit = \"MPa\"\n[mesh]\nsize = [100, 20.0] # mm\ngenerator = \"rectangle\"\n\
            [[substructure]]\npoisson = -0.0\nname = \"plate\"\nyoung = \"E\"\n\
            [[method]]\ntype = \"monte_carlo\"\nruns = 60\n[statistics]\nsamples = 10\n\
            [study]\ntitle = \"t\"\nseed = 3\n[output]\nreport = false\n";
        assert_eq!(form(same), base);
    }

    #[test]
    fn the_model_and_the_solver_change_the_run_form() {
        let base = form(BASE);
        for edit in [
            BASE.replace("poisson = 0.0", "poisson = 0.3"),
            BASE.replace("young = \"E\"", "young = \"2 * E\""),
            BASE.replace("hi = 2.0", "hi = 3.0"),
            BASE.replace("[100.0, 20.0]", "[100.0, 21.0]"),
            format!("{BASE}[solver]\ntolerance = 1e-8\n"),
        ] {
            assert_ne!(form(&edit), base, "{edit}");
        }
    }

    #[test]
    fn a_quantity_key_ignores_its_name_unit_and_thresholds() {
        let q = |t: &str| quantity_key(&toml::Value::Table(toml::from_str(t).unwrap()));
        let a = q("name = \"tip\"\nkind = \"displacement\"\ncomponent = 0\nthresholds = [1.0]");
        let b = q("kind = \"displacement\"\ncomponent = 0\nname = \"u\"\nunit = \"mm\"");
        let c = q("name = \"tip\"\nkind = \"displacement\"\ncomponent = 1");
        assert_eq!(a, b);
        assert_ne!(a, c);
    }
}
