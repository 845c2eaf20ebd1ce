//! `alea solve` and `alea demo`: one deterministic solve of a case file.

use std::path::Path;
use std::time::Instant;

use alea_fem::{Loads, post, solve_elastic, von_mises};
use alea_latin::RunStatus;
use alea_mesh::vtu::VtuWriter;
use alea_study::{Source, build_model, build_params, spec::ModelFile};
use anyhow::{Context, Result};

const DEMO_DOVETAIL: &str = include_str!("../../../examples/dovetail-contact.toml");
const DEMO_KIRSCH: &str = include_str!("../../../examples/kirsch.toml");

/// Runs a built-in demo.
pub fn demo(name: &str, out: &Path) -> Result<()> {
    let (file, text) = match name {
        "dovetail" => ("examples/dovetail-contact.toml", DEMO_DOVETAIL),
        "kirsch" => ("examples/kirsch.toml", DEMO_KIRSCH),
        other => {
            return Err(alea_study::StudyError::Usage(format!(
                "unknown demo '{other}'; available: dovetail, kirsch"
            ))
            .into());
        }
    };
    println!("demo '{name}' (the case file is {file})");
    solve_source(&Source::from_text(file, text), out)
}

/// Solves a case file.
pub fn solve_file(case: &Path, out: &Path) -> Result<()> {
    let src = Source::read(case)?;
    solve_source(&src, out)
}

fn solve_source(src: &Source, out: &Path) -> Result<()> {
    let t0 = Instant::now();
    let file: ModelFile = src.parse()?;
    let params = build_params(src, &file)?;
    let built = build_model(src, &file, &params)?;
    let plan = alea_study::steps::plan_steps(src, &file)?;
    let input = built.parametric.run_input(&params.nominal, vec![]);
    if !params.names.is_empty() {
        println!(
            "parameters at their nominal (mean) values: {}",
            params
                .names
                .iter()
                .zip(&params.nominal)
                .map(|(n, v)| format!("{n} = {v:.6}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let stem = src
        .path
        .file_stem()
        .map_or("case".into(), |s| s.to_string_lossy().into_owned());
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let u = &built.units;
    println!(
        "units: length {}, force {}, stress {}; mesh: {} nodes, {} cells; {} substructure(s), {} interface(s)",
        u.length,
        u.force,
        u.stress,
        built.mesh.num_nodes(),
        built.mesh.num_cells(),
        built.assembly.subs.len(),
        built.assembly.interfaces.len()
    );
    if built.assembly.subs.len() == 1 && built.assembly.interfaces.is_empty() {
        if plan.is_some() {
            return Err(src
                .error(
                    file.step[0].span(),
                    "step",
                    "[[step]] load histories are for assemblies with interfaces: a single linear body does not depend on the path, so solve each load as its own case",
                )
                .into());
        }
        let sub = &built.assembly.subs[0];
        let mut loads = Loads::new(&sub.model);
        for (case, factor) in sub.load_cases.iter().zip(&input.load_factors[0]) {
            for (a, b) in loads.f.iter_mut().zip(case) {
                *a += factor * b;
            }
        }
        let mut model = sub.model.clone();
        model.scale_young(input.young_factors[0]);
        let sub = alea_latin::Substructure {
            model,
            ..sub.clone()
        };
        let sub = &sub;
        let sol = match solve_elastic(
            &sub.model,
            &sub.constraints,
            &loads,
            alea_fem::Ordering::Metis,
        ) {
            // A single body is solved directly: a rigid-body motion its constraints leave free
            // is an input error at its constraints (exit 2), not a failed computation.
            Err(alea_fem::FemError::NotPositiveDefinite) => {
                let spec = &file.substructure[0];
                return Err(src
                    .error(
                        spec.name.span(),
                        "substructure[0].constraint",
                        format!(
                            "substructure '{}' can move as a rigid body (its stiffness matrix is singular): a single body is solved directly and its constraints must hold every rigid-body motion (e.g. a fixed point and a roller, or the symmetry planes), even under a self-equilibrated load",
                            spec.name.get_ref()
                        ),
                    )
                    .into());
            }
            r => r?,
        };
        let stresses = post::nodal_stresses(&sub.model, &sol.u)?;
        let vm: Vec<f64> = stresses.iter().map(von_mises).collect();
        let (imax, vmax) = vm
            .iter()
            .enumerate()
            .fold((0, 0.0), |a, (i, &v)| if v > a.1 { (i, v) } else { a });
        let x = sub.model.mesh.coords[imax];
        let energy = post::strain_energy(&sub.model, &sol.u)?;
        println!(
            "direct solve of {} unknowns: assembly {:.3} s, factorisation {:.3} s, solve {:.3} s",
            sol.num_free,
            sol.timings.assembly,
            sol.timings.symbolic + sol.timings.numeric,
            sol.timings.solve
        );
        println!(
            "max von Mises {vmax:.4} {} at ({:.3}, {:.3}, {:.3}); strain energy {energy:.6e}",
            u.stress, x[0], x[1], x[2]
        );
        let stress6: Vec<f64> = stresses
            .iter()
            .flat_map(|s| [s[0], s[1], s[2], s[5], s[3], s[4]])
            .collect();
        let path = out.join(format!("{stem}.vtu"));
        VtuWriter::new(&sub.model.mesh)
            .point_vector("displacement", sub.model.mesh.dim, &sol.u)
            .point_vector("reaction", sub.model.mesh.dim, &sol.reactions)
            .point_tensor("stress", 6, &stress6)
            .point_scalar("von_mises", &vm)
            .write(&path)?;
        println!(
            "wrote {} ({:.2} s in all)",
            path.display(),
            t0.elapsed().as_secs_f64()
        );
        return Ok(());
    }
    if let Some(plan) = plan {
        return crate::solve_steps::solve_history(src, &file, &params, built, plan, out, &stem, t0);
    }
    let solver = built.solver()?;
    println!(
        "LATIN set-up (assembly + factorisations): {:.3} s",
        solver.setup_seconds
    );
    let res = solver.run_shared(&input)?;
    let path = out.join(format!("{stem}.vtm"));
    report_run(&file, &built, &solver, &res, &input, &path)?;
    println!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    if res.status != RunStatus::Converged {
        return Err(not_converged(&solver, &res).into());
    }
    Ok(())
}

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
/// (`path`: the `.vtm`, with the `.vtu` and interface `.csv` files beside it).
pub(crate) fn report_run(
    file: &ModelFile,
    built: &alea_study::BuiltModel,
    solver: &alea_latin::LatinSolver,
    res: &alea_latin::RunResult,
    input: &alea_latin::RunInput,
    path: &Path,
) -> Result<()> {
    let u = &built.units;
    let last = res.residuals.last().copied().unwrap_or(0.0);
    match res.status {
        RunStatus::Converged => println!(
            "converged in {} iterations (error indicator {last:.2e}, every substructure in equilibrium), {:.3} s",
            res.iterations, res.timings.total
        ),
        RunStatus::NoEquilibrium => println!(
            "NO STATIC EQUILIBRIUM after {} iterations (error indicator {last:.2e}): {}; results below are the last iterate",
            res.iterations,
            solver
                .equilibrium_report(res)
                .unwrap_or_else(|| "a floating substructure drifts".into())
        ),
        _ => println!(
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
        println!("  error indicator by iteration: {}", shown.join(", "));
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
        println!(
            "  substructure {:>10}: max von Mises {vm:.4} {}{balance}",
            sub.name, u.stress
        );
    }
    let dim = built.mesh.dim;
    for it in &res.interfaces {
        let c = it.status_counts();
        let dim = solver.model(it.subs[1]).mesh.dim;
        println!(
            "  interface {:>12} ({}): open {} stick {} slip {}; resultant on side 2 ({}) {}; work of interface forces {:e}",
            it.name,
            it.law,
            c[1],
            c[2],
            c[3],
            labelled(it.resultant(), dim, "F"),
            u.force,
            it.work()
        );
    }
    for c in alea_latin::sliding::slide_checks(solver, res) {
        if c.beyond_small_sliding() {
            let it = &res.interfaces[c.interface];
            let x = it.points[c.point].x;
            println!(
                "  warning: interface '{}' slid by {:.4e} {} at ({:.4}, {:.4}, {:.4}), {:.2} x the local mesh size: beyond small sliding (> {} x), the pairing of the initial configuration no longer pairs the points that face each other and the contact zone, gap and pressure may be wrong (the pairing is not updated during the solve)",
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
            println!(
                "  reaction on {:>10} / {g}: {} {}",
                sub.name,
                labelled(sum, dim, "R"),
                u.force
            );
        }
        reactions.push(r);
    }
    let written =
        alea_latin::output::write_run_with_reactions(path, solver, res, Some(&reactions))?;
    println!(
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
