//! `alea solve` and `alea demo`: one deterministic solve of a case file.

use std::path::Path;
use std::time::Instant;

use alea_fem::{Loads, post, solve_elastic, von_mises};
use alea_latin::RunStatus;
use alea_mesh::vtu::VtuWriter;
use alea_study::{Source, build_model, build_params, spec::ModelFile};
use anyhow::{Context, Result};

use crate::out::outln;

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
    outln!("demo '{name}' (the case file is {file})");
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
    let input = built.parametric.run_input(&params.nominal);
    if !params.names.is_empty() {
        outln!(
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
    outln!(
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
        outln!(
            "direct solve of {} unknowns: assembly {:.3} s, factorisation {:.3} s, solve {:.3} s",
            sol.num_free,
            sol.timings.assembly,
            sol.timings.symbolic + sol.timings.numeric,
            sol.timings.solve
        );
        outln!(
            "max von Mises {vmax:.4} {} at ({:.3}, {:.3}, {:.3}); strain energy {energy:.6e}",
            u.stress,
            x[0],
            x[1],
            x[2]
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
        outln!(
            "wrote {} ({:.2} s in all)",
            path.display(),
            t0.elapsed().as_secs_f64()
        );
        return Ok(());
    }
    if let Some(plan) = plan {
        return crate::solve_steps::solve_history(src, &file, &params, built, plan, out, &stem, t0);
    }
    if alea_latin::large_sliding::uses_large_sliding(&built.assembly) {
        let step = crate::solve_steps::large_sliding_solve(&built, &input)?;
        let (solver, res) = (&step.solver, &step.result);
        let path = out.join(format!("{stem}.vtm"));
        crate::run_report::report_run(&file, &built, solver, res, &input, &path, None)?;
        outln!("({:.2} s in all)", t0.elapsed().as_secs_f64());
        if res.status != RunStatus::Converged {
            return Err(crate::run_report::not_converged(solver, res).into());
        }
        return Ok(());
    }
    let solver = built.solver()?;
    outln!(
        "LATIN set-up (assembly + factorisations): {:.3} s",
        solver.setup_seconds
    );
    let res = solver.run_shared(&input)?;
    let path = out.join(format!("{stem}.vtm"));
    crate::run_report::report_run(&file, &built, &solver, &res, &input, &path, None)?;
    outln!("({:.2} s in all)", t0.elapsed().as_secs_f64());
    if res.status != RunStatus::Converged {
        return Err(crate::run_report::not_converged(&solver, &res).into());
    }
    Ok(())
}
