//! What `alea solve` prints and writes for one LATIN run (a whole solve, or one step of a
//! history): status, stresses, interfaces, the small-sliding check, reactions, and the `.vtm`
//! with its `.vtu` and interface `.csv` files; and the error of a run that did not converge.

use std::path::Path;

use alea_latin::RunStatus;
use alea_study::spec::ModelFile;
use anyhow::Result;

use crate::out::outln;

/// The error of a run that did not converge (exit 4).
pub(crate) fn not_converged(
    solver: &alea_latin::LatinSolver,
    res: &alea_latin::RunResult,
) -> alea_study::StudyError {
    let last = res.residuals.last().copied().unwrap_or(0.0);
    alea_study::StudyError::Failed(format!(
        "the solve did not converge (status '{}' after {} iterations, error indicator {last:.2e}, tolerance {:.1e}); \
         the files hold the last iterate",
        res.status.label(),
        res.iterations,
        solver.options().tolerance
    ))
}

/// Prints the status, stresses, interfaces and reactions of a LATIN run and writes its files
/// (`path`: the `.vtm`, with the `.vtu` and interface `.csv` files beside it). For a step of a
/// load history, `origins` holds the tangential jump of every interface point at the start of
/// the step (`alea_latin::steps::step_origins`): the work and the slip written are then the
/// step's own, and the total slip is written beside it.
pub(crate) fn report_run(
    file: &ModelFile,
    built: &alea_study::BuiltModel,
    solver: &alea_latin::LatinSolver,
    res: &alea_latin::RunResult,
    input: &alea_latin::RunInput,
    path: &Path,
    origins: Option<&[Vec<[f64; 3]>]>,
) -> Result<()> {
    let u = &built.units;
    let last = res.residuals.last().copied().unwrap_or(0.0);
    match res.status {
        RunStatus::Converged => outln!(
            "converged in {} iterations (error indicator {last:.2e}, every substructure in equilibrium), {:.3} s",
            res.iterations,
            res.timings.total
        ),
        RunStatus::NoEquilibrium => outln!(
            "NO STATIC EQUILIBRIUM after {} iterations (error indicator {last:.2e}): {}; results below are the last iterate",
            res.iterations,
            solver
                .equilibrium_report(res)
                .unwrap_or_else(|| "a floating substructure drifts".into())
        ),
        _ => outln!(
            "NOT CONVERGED after {} iterations: error indicator {last:.2e} (tolerance {:.1e}); results below are the last iterate",
            res.iterations,
            solver.options().tolerance
        ),
    }
    if res.status != RunStatus::Converged {
        let h = &res.residuals;
        let shown: Vec<String> = h
            .iter()
            .enumerate()
            .filter(|(i, _)| (i + 1).is_power_of_two() || *i + 1 == h.len())
            .map(|(i, v)| format!("{}: {v:.2e}", i + 1))
            .collect();
        outln!("  error indicator by iteration: {}", shown.join(", "));
    }
    for (s, sub) in built.assembly.subs.iter().enumerate() {
        let all = (0..sub.model.mesh.num_cells()).collect::<Vec<_>>();
        let mut m = res.scaled_model(solver.model(s), s);
        m.mesh.cell_groups.insert("__all".into(), all);
        let vm = res.max_von_mises(&m, s, "__all")?;
        let eq = &res.equilibrium[s];
        let balance = if eq.free_modes > 0 {
            format!(
                "; {} free rigid mode(s): unbalanced load {:.2e} of its load, rigid motion {:.2e} x the model size",
                eq.free_modes, eq.relative_imbalance, eq.relative_rigid_motion
            )
        } else {
            String::new()
        };
        outln!(
            "  substructure {:>10}: max von Mises {vm:.4} {}{balance}",
            sub.name,
            u.stress
        );
    }
    let dim = built.mesh.dim;
    for (i, it) in res.interfaces.iter().enumerate() {
        let c = it.status_counts();
        let dim = solver.model(it.subs[1]).mesh.dim;
        let (work, within) = match origins.and_then(|o| o.get(i)) {
            Some(o) => (it.step_work(o), " in this step"),
            None => (it.work(), ""),
        };
        outln!(
            "  interface {:>12} ({}): open {} stick {} slip {}; resultant on side 2 ({}) {}; work of interface forces{within} {work:e}",
            it.name,
            it.law,
            c[1],
            c[2],
            c[3],
            labelled(it.resultant(), dim, "F"),
            u.force,
        );
    }
    for c in alea_latin::sliding::slide_checks(solver, res) {
        if c.beyond_small_sliding() {
            let it = &res.interfaces[c.interface];
            let x = it.points[c.point].x;
            let since = if solver.pairing_configuration().is_some() {
                " since its last pairing"
            } else {
                ""
            };
            outln!(
                "  warning: interface '{}' slid{since} by {:.4e} {} at ({:.4}, {:.4}, {:.4}), {:.2} x the local mesh size: beyond small sliding (> {} x), the pairing no longer pairs the points that face each other and the contact zone, gap and pressure may be wrong (sliding = \"large\" on the interface re-pairs it in the deformed configuration during the solve)",
                it.name,
                c.slip,
                u.length,
                x[0],
                x[1],
                x[2],
                c.ratio,
                alea_latin::sliding::SMALL_SLIDING_LIMIT
            );
        }
    }
    // Reactions on every constrained group (the forces the constraints exert).
    let mut reactions = Vec::new();
    for (s, sub) in built.assembly.subs.iter().enumerate() {
        let mut loads = vec![0.0; sub.model.mesh.num_nodes() * dim];
        for (case, factor) in sub.load_cases.iter().zip(&input.load_factors[s]) {
            for (a, b) in loads.iter_mut().zip(case) {
                *a += factor * b;
            }
        }
        let r = alea_latin::reactions::nodal_reactions(solver, res, s, &loads)?;
        for c in &file.substructure[s].constraint {
            let g = c.group.get_ref();
            let nodes = sub.model.mesh.group_nodes(g)?;
            let sum = alea_latin::reactions::group_sum(&r, dim, &nodes);
            outln!(
                "  reaction on {:>10} / {g}: {} {}",
                sub.name,
                labelled(sum, dim, "R"),
                u.force
            );
        }
        reactions.push(r);
    }
    let written = alea_latin::output::write_step(path, solver, res, Some(&reactions), origins)?;
    outln!(
        "wrote {} and {} file(s) beside it",
        path.display(),
        written.len(),
    );
    Ok(())
}

/// The components of a resultant force, labelled, at full precision (the shortest decimal that
/// reads back to the same `f64`): `Fx = .., Fy = ..` in 2D, `.., Fz = ..` in 3D (`prefix` "F"),
/// `Rx = ..` for reactions.
fn labelled(r: [f64; 3], dim: usize, prefix: &str) -> String {
    ["x", "y", "z"]
        .iter()
        .zip(r)
        .take(dim)
        .map(|(axis, v)| format!("{prefix}{axis} = {v:e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::labelled;

    #[test]
    fn resultants_are_labelled_and_read_back_exactly() {
        let r = [1.0 / 3.0, -2.5e-7, 3846.153856573441];
        let t3 = labelled(r, 3, "F");
        assert!(t3.starts_with("Fx = ") && t3.contains(", Fy = ") && t3.contains(", Fz = "));
        let back: Vec<f64> = t3
            .split(", ")
            .map(|p| p.split(" = ").nth(1).unwrap().parse().unwrap())
            .collect();
        assert_eq!(back, r.to_vec());
        let t2 = labelled(r, 2, "F");
        assert!(!t2.contains("Fz"), "{t2}");
        assert_eq!(t2.split(", ").count(), 2);
    }
}
