//! What a study gives without writing any output: the statistics of every method and the
//! results of its reliability tables ([`analyse`], the same for `alea run`, `alea report` and
//! Python's `alea.run`), the parameter points of their draws, and the runs kept in a study
//! directory's store. Nothing here solves: the budget's mesh and sliding parts come from the
//! paired solves the run stored (`alea_study::paired_runs`).

use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

use alea_study::analysis::{AnalysisSettings, MethodResult, analyse_method};
use alea_study::budget::paired::{PairedResult, Part};
use alea_study::method::{Method, MethodKind};
use alea_study::reliability::{ReliabilityResult, analyse_reliability};
use alea_study::runner::{Study, StudyRuns};
use alea_study::store::{RunRecord, Store, point_key};

use crate::Error;

/// The analysis of a study whose runs are done.
pub struct Analysis {
    /// The surrogate and Monte Carlo statistics of every method, in method order
    /// ([`analyse_all`]).
    pub results: Vec<MethodResult>,
    /// Seconds of `results`.
    pub seconds: f64,
    /// The results of the `[[reliability]]` tables, in table order.
    pub reliability: Vec<ReliabilityResult>,
}

/// The statistics of every method ([`analyse_all`]) and the results of the reliability tables
/// of a study whose runs are done.
pub fn analyse(study: &Study, runs: &StudyRuns, settings: &AnalysisSettings) -> Analysis {
    let t0 = Instant::now();
    let results = analyse_all(study, runs, settings);
    let seconds = t0.elapsed().as_secs_f64();
    let reliability = analyse_reliability(
        study,
        &study.reliability,
        &runs.methods,
        &runs.records,
        settings.confidence,
    );
    Analysis {
        results,
        seconds,
        reliability,
    }
}

/// The surrogate and Monte Carlo statistics of every method of a study, in method order.
pub fn analyse_all(
    study: &Study,
    runs: &StudyRuns,
    settings: &AnalysisSettings,
) -> Vec<MethodResult> {
    let mut results: Vec<MethodResult> = runs
        .methods
        .iter()
        .map(|m| analyse_method(study, m, &runs.records, settings))
        .collect();
    if let Some(check) = &runs.paired.mesh {
        apply_paired_part(study, check, Part::Mesh, &mut results);
    }
    if let Some(check) = &runs.paired.sliding {
        apply_paired_part(study, check, Part::Sliding, &mut results);
    }
    results
}

/// The mesh part (`[budget] refined_mesh`) or the sliding part (`[budget] large_sliding`) of
/// every statistic's budget from the paired solves of the study and of its refined or
/// large-sliding model (`alea_study::budget::paired`), solved by the run and read from the store
/// (`alea_study::paired_runs`: nothing is solved here), or why it is not estimated.
fn apply_paired_part(
    study: &Study,
    check: &PairedResult,
    which: Part,
    results: &mut [MethodResult],
) {
    use alea_study::budget::paired::apply;
    let check = check.as_ref();
    for r in results.iter_mut() {
        for (q, stats) in r.qois.iter_mut().enumerate() {
            let samples = std::mem::take(&mut stats.samples);
            if let Some(budget) = stats.budget.as_mut() {
                let factor = if which == Part::Mesh { 2.0 } else { 1.0 };
                let bounds = check.as_ref().map(|c| (c, c.bounds(q, factor)));
                let not_estimated = match bounds {
                    Ok((c, Some((d, s)))) => {
                        // The sliding change scales with the response (the geometric effect grows
                        // with the displacements): its largest relative size at the points,
                        // times the spread, bounds the change of the spread when the change is
                        // proportional to the quantity, which S / 2 over a few points misses.
                        let relative = (which == Part::Sliding).then(|| c.relative(q)).flatten();
                        // How far the difference may reach at each draw, `|delta~| + A` from
                        // the model of the differences (for the `P(q > t)` rows).
                        let shifts: Option<Vec<f64>> = c.shift_model(q, factor).and_then(|m| {
                            let dim = study.params.names.len();
                            (dim > 0 && r.points.len() == samples.len() * dim)
                                .then(|| r.points.chunks(dim).map(|x| m.reach(x)).collect())
                        });
                        let p_rows = if shifts.is_some() {
                            "P(q > t): the draws within their own shift of t, from a model of the differences: first order along each parameter, plus the pair terms fitted at the two diagonal points"
                        } else {
                            "P(q > t): the draws within D of t"
                        };
                        let basis = match which {
                            Part::Mesh => format!(
                                "paired solves on this mesh ({} nodes) and the refined one ({} nodes) at {} design points: D = 2 max |q_h - q_h/2| = {d:.3e}, spread S = {s:.3e} (Richardson, first order); {p_rows}",
                                c.nodes.0,
                                c.nodes.1,
                                c.points.len()
                            ),
                            Part::Sliding => format!(
                                "paired solves in small and in large sliding (the pairing and its normals re-found in the deformed configuration) at {} design points: D = max |q_small - q_large| = {d:.3e}, spread S = {s:.3e}, largest relative change r = {:.3} (std part max(S / 2, r std)); {p_rows}; the change toward the large-sliding model, not a large-deformation error",
                                c.points.len(),
                                relative.unwrap_or(0.0)
                            ),
                        };
                        apply(
                            budget,
                            &samples,
                            shifts.as_deref(),
                            (d, s),
                            relative,
                            which,
                            basis,
                        );
                        None
                    }
                    Ok((_, None)) => Some(match which {
                        Part::Mesh => "no paired solve converged on both meshes".to_string(),
                        Part::Sliding => {
                            "no paired solve converged in both small and large sliding".to_string()
                        }
                    }),
                    Err(why) => Some(why.to_string()),
                };
                if let Some(why) = not_estimated {
                    let why = format!("not estimated: {why}");
                    match which {
                        Part::Mesh => budget.mesh_basis = why,
                        Part::Sliding => budget.sliding_basis = Some(why),
                    }
                }
            }
            stats.samples = samples;
        }
    }
}

/// The converged runs among `points`, in the order of `points`, each with its point.
pub fn converged_runs<'a>(
    points: &'a [Vec<f64>],
    records: &'a [RunRecord],
) -> Vec<(&'a Vec<f64>, &'a RunRecord)> {
    let by_key: HashMap<String, &RunRecord> =
        records.iter().map(|r| (point_key(&r.params), r)).collect();
    points
        .iter()
        .filter_map(|p| by_key.get(&point_key(p)).map(|r| (p, *r)))
        .filter(|(_, r)| r.converged())
        .collect()
}

/// The parameter points of `result`'s draws, row-major (`draws x d`), in the order of its
/// samples: a surrogate's Monte Carlo points, or for a Monte Carlo method its converged runs in
/// design order - the latter only if they reproduce the method's samples bit for bit (so a
/// sample is never mislabelled). `None` when there are no such points.
pub fn sample_points(
    method: &Method,
    records: &[RunRecord],
    result: &MethodResult,
) -> Option<Vec<f64>> {
    if method.kind == MethodKind::MonteCarlo && !result.qois.is_empty() {
        let used = converged_runs(&method.points, records);
        let same = used.len() == result.account.runs_used
            && result.qois.iter().enumerate().all(|(q, s)| {
                s.samples.len() == used.len()
                    && s.samples.iter().zip(&used).all(|(v, (_, r))| {
                        r.qois.get(q).is_some_and(|x| x.to_bits() == v.to_bits())
                    })
            });
        same.then(|| {
            used.iter()
                .flat_map(|(_, r)| r.params.iter().copied())
                .collect()
        })
    } else if result.points.is_empty() {
        None
    } else {
        Some(result.points.clone())
    }
}

/// The runs kept in a study directory's store.
pub struct StoredRuns {
    /// The study hash the store belongs to.
    pub hash: String,
    /// The study file, when given (then the store holds that version of it).
    pub study: Option<Study>,
    /// The finished runs, in the store's order.
    pub records: Vec<RunRecord>,
}

/// Reads the runs stored in study directory `dir`, running nothing. With `study` (the study
/// file), the store must hold that version of it; without, the store's own hash is used.
///
/// # Errors
/// [`Error::NoStore`] without `study.db`; [`Error::Store`] if it is not a study store; the
/// errors of loading `study` and of reading the store ([`Error::Study`]).
pub fn stored_runs(dir: &Path, study: Option<&Path>) -> Result<StoredRuns, Error> {
    let db = dir.join("study.db");
    if !db.is_file() {
        return Err(Error::NoStore {
            dir: dir.to_path_buf(),
        });
    }
    let (hash, study) = match study {
        Some(path) => {
            let s = Study::load(path)?;
            (s.hash.clone(), Some(s))
        }
        None => (stored_hash(&db)?, None),
    };
    let records = Store::open(dir, &hash, false).and_then(|s| s.runs_without_states())?;
    Ok(StoredRuns {
        hash,
        study,
        records,
    })
}

/// The study hash recorded in a store's database `db` (read only).
fn stored_hash(db: &Path) -> Result<String, Error> {
    let conn =
        rusqlite::Connection::open_with_flags(db, rusqlite::OpenFlags::SQLITE_OPEN_READ_ONLY)
            .map_err(|e| Error::Store {
                path: db.to_path_buf(),
                message: e.to_string(),
            })?;
    conn.query_row("SELECT value FROM meta WHERE key = 'study_hash'", [], |r| {
        r.get::<_, String>(0)
    })
    .map_err(|e| Error::Store {
        path: db.to_path_buf(),
        message: format!("not a study store ({e})"),
    })
}
