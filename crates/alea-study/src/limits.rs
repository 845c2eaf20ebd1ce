//! Sizes checked up front, before anything is allocated or computed: a study that cannot
//! finish is refused at load time with the estimate in the message, never after its runs.
//!
//! | what | limit |
//! |---|---|
//! | mesh | estimated memory of the factorisations <= available memory (estimate below) |
//! | distinct runs of all methods | <= [`MAX_RUNS`] |
//! | polynomial-chaos terms | <= [`MAX_PC_TERMS`] |
//! | thresholds per quantity | <= [`MAX_THRESHOLDS`] |
//! | Monte Carlo draws on a surrogate | <= [`MAX_SAMPLES`], and their memory <= half the available memory |
//! | KDE curve points | 2 ..= [`MAX_KDE_POINTS`] |
//! | LATIN iterations per run | <= [`MAX_ITERATIONS`] (each run stores its residual history) |
//! | Anderson depth | <= [`MAX_ACCELERATION`] |
//! | worker threads | 1 ..= 4 x the cores, at most [`MAX_THREADS`] |
//! | mean / std fields | their weight-moment matrices <= half the available memory, else refused (set `mean_fields = false`) |
//! | `[solver] linear_stage = "condensed"` | the dense interface operators, `8 n_i^2` bytes per substructure of `n_i` interface unknowns, <= a quarter of the available memory ([`check_condensed`]; `"auto"` keeps volume solves beyond it) |
//!
//! **Memory of a mesh** (measured peak resident memory, release build, METIS ordering;
//! `BENCHMARKS.md`, "memory per node" and "Single-precision factors"): 2D 3.4-4.5 kB per node
//! (Q4 and Q8, 40k-160k nodes); 3D with double-precision factors 22-30 kB per node at 9k-30k
//! nodes (Hex8, Tet10, `alea solve`), growing like `n^(1/3)` (nested-dissection fill); 3D with
//! the default single-precision factors, 2-run studies of the 3D turbine: 14.5 kB per node
//! undivided (27 508 nodes), 13.2 kB in 30 parts (200 700 nodes) and 14.1 kB in 96 parts
//! (722 364 nodes). The estimate is `5 kB x nodes` in 2D and `c x nodes x max(1, (part /
//! 30 000)^(1/3))` in 3D, `part` the nodes of the largest part automatic subdomains leave,
//! `c = 20 kB` in single precision and `30 kB` in double. Nodes are counted from the generator's
//! block counts before generating (exactly for `rectangle`, `box` and the shapes; a Gmsh file's
//! size bounds it).
//! Available memory is `MemAvailable` of `/proc/meminfo` (8 GiB assumed where it cannot be read).

use crate::spec::{MeshSpec, MethodSpec, ModelFile};
use crate::{Source, StudyError};

/// Most validation runs a study may ask for (`[budget] validation_runs`; `crate::validation_runs`).
pub const MAX_VALIDATION_RUNS: usize = 10_000;

/// Distinct runs of a study (each is a full LATIN solve and a row of the store).
pub const MAX_RUNS: usize = 100_000;
/// Terms of a polynomial-chaos basis.
pub const MAX_PC_TERMS: usize = 20_000;
/// Failure thresholds per quantity.
pub const MAX_THRESHOLDS: usize = 1_000;
/// Monte Carlo draws on a surrogate.
pub const MAX_SAMPLES: usize = 100_000_000;
/// Points of a KDE curve.
pub const MAX_KDE_POINTS: usize = 100_000;
/// LATIN iterations per run.
pub const MAX_ITERATIONS: usize = 1_000_000;
/// Anderson acceleration depth.
pub const MAX_ACCELERATION: usize = 100;
/// Worker threads.
pub const MAX_THREADS: usize = 1024;

/// Bytes of memory available to this process: `MemAvailable` (Linux), else 8 GiB.
pub fn available_memory() -> u64 {
    alea_mesh::input::available_memory()
}

/// A byte count for messages: `1.5 GB`.
pub fn human_bytes(b: f64) -> String {
    let units = ["bytes", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut v = b;
    let mut u = 0;
    while v >= 1000.0 && u + 1 < units.len() {
        v /= 1000.0;
        u += 1;
    }
    if u == 0 {
        format!("{v:.0} {}", units[0])
    } else {
        format!("{v:.1} {}", units[u])
    }
}

/// What the memory of a mesh's factorisations depends on in the `[solver]` table
/// ([`mesh_memory`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FactorLayout {
    /// The largest part, in unknowns, that `[solver] subdomains` leaves a substructure
    /// (`alea_latin::split::plan`): `None` with `"never"`.
    pub part_dofs: Option<usize>,
    /// Large 3D factors stored in single precision (`[solver] factor_precision` other than
    /// `"double"`).
    pub single: bool,
}

impl FactorLayout {
    /// Undivided substructures with double-precision factors (the largest estimate).
    pub const UNDIVIDED_DOUBLE: FactorLayout = FactorLayout {
        part_dofs: None,
        single: false,
    };
}

/// Estimated peak memory (bytes) of the factorisations of a mesh of `nodes` nodes in `dim`
/// dimensions (module doc), its factorised parts at most `layout.part_dofs` unknowns when
/// automatic subdomains may cut it: in 3D the fill of a part grows like the cube root of its
/// size, so cut parts bound it; single-precision factors take 20 kB a node where
/// double-precision ones take 30 kB.
pub fn mesh_memory(nodes: f64, dim: usize, layout: FactorLayout) -> f64 {
    if dim == 2 {
        5e3 * nodes
    } else {
        let part = layout
            .part_dofs
            .map_or(nodes, |d| nodes.min(d as f64 / dim as f64));
        let per_node = if layout.single { 20e3 } else { 30e3 };
        per_node * nodes * (part / 30_000.0).cbrt().max(1.0)
    }
}

/// The [`FactorLayout`] a `[solver]` table asks for.
pub fn factor_layout(solver: &crate::spec::SolverSpec) -> FactorLayout {
    let target = solver
        .subdomain_dofs
        .as_ref()
        .map_or(alea_latin::split::SUBDOMAIN_DOFS, |d| *d.get_ref());
    let part_dofs = match solver.subdomains.as_ref().map(|s| s.get_ref().as_str()) {
        Some("never") => None,
        Some("always") => Some(2 * target),
        // 3D only (`alea_latin::split::plan`); `mesh_memory` caps 3D meshes only.
        _ => Some(alea_latin::split::AUTO_MIN_DOFS.max(target)),
    };
    let single = solver
        .factor_precision
        .as_ref()
        .is_none_or(|p| p.get_ref() != "double");
    FactorLayout { part_dofs, single }
}

/// Nodes per structured block cell (a quad or hex of the generator's lattice) for a cell kind.
fn nodes_per_block_cell(kind: &str) -> f64 {
    match kind {
        "quad8" => 3.0,
        "tri6" => 4.0,
        "tet10" => 8.0,
        _ => 1.0,
    }
}

/// The estimate of the mesh a `[mesh]` table would generate: `(nodes, block cells, dim,
/// span, field)`; `None` for Gmsh files (their size bounds them) and tables missing the counts.
pub fn mesh_estimate(
    spec: &MeshSpec,
) -> Option<(f64, f64, usize, std::ops::Range<usize>, &'static str)> {
    let num = |key: &str, default: f64| -> f64 {
        spec.params
            .as_ref()
            .and_then(|p| p.get_ref().get(key).cloned())
            .and_then(|v| match v {
                toml::Value::Integer(i) => Some(i as f64),
                toml::Value::Float(f) => Some(f),
                _ => None,
            })
            .unwrap_or(default)
    };
    // The generators' default kinds (`build_mesh`).
    let default_kind = match spec.generator.get_ref().as_str() {
        "plate_with_hole" | "annulus_sector" => "quad8",
        "box" | "turbine_3d" => "hex8",
        "turbine_2d" => "quad8",
        _ => "quad4",
    };
    let kind = spec
        .kind
        .as_ref()
        .map_or(default_kind, |k| k.get_ref().as_str())
        .to_ascii_lowercase();
    let (block_cells, dim, span, field): (f64, usize, _, &str) =
        match spec.generator.get_ref().as_str() {
            "rectangle" | "box" => {
                let c = spec.cells.as_ref()?;
                let dim = if spec.generator.get_ref() == "box" {
                    3
                } else {
                    2
                };
                (
                    c.get_ref().iter().map(|&n| n as f64).product(),
                    dim,
                    c.span(),
                    "mesh.cells",
                )
            }
            "plate_with_hole" => (
                num("n_arc", 16.0) * num("n_radial", 16.0),
                2,
                span_of(spec),
                "mesh.params",
            ),
            "annulus_sector" => (
                num("n_radial", 8.0) * num("n_theta", 8.0),
                2,
                span_of(spec),
                "mesh.params",
            ),
            "dovetail" => {
                let d = alea_mesh::generate::DovetailParams::default();
                let (fl, ro, sh, lo, wa, sl, be) = (
                    num("n_flank", d.n_flank as f64),
                    num("n_root", d.n_root as f64),
                    num("n_shank", d.n_shank as f64),
                    num("n_lobe", d.n_lobe as f64),
                    num("n_wall", d.n_wall as f64),
                    num("n_slot", d.n_slot as f64),
                    num("n_below", d.n_below as f64),
                );
                (
                    2.0 * (lo * fl + lo * wa + lo * be + sl * be + ro * fl + ro * sh),
                    2,
                    span_of(spec),
                    "mesh.params",
                )
            }
            "blade_root_simple" => {
                let d = alea_mesh::generate::BladeRootParams::default();
                let (fl, si, ro, sh) = (
                    num("n_flank", d.n_flank as f64),
                    num("n_side", d.n_side as f64),
                    num("n_root", d.n_root as f64),
                    num("n_shank", d.n_shank as f64),
                );
                (
                    2.0 * si * fl + ro * (fl + sh),
                    2,
                    span_of(spec),
                    "mesh.params",
                )
            }
            "stacked_blocks" | "block_on_incline" => {
                let plane = num("n_x", 16.0) * (num("n_lower", 8.0) + num("n_upper", 8.0));
                if kind == "hex8" {
                    (
                        plane * num("n_z", num("n_x", 16.0)),
                        3,
                        span_of(spec),
                        "mesh.params",
                    )
                } else {
                    (plane, 2, span_of(spec), "mesh.params")
                }
            }
            "turbine_2d" | "turbine_3d" => {
                let d = alea_mesh::generate::TurbineParams::default();
                let n = |k: &str, v: usize| num(k, v as f64);
                let nh = n("n_fillet", d.n_fillet) / 2.0;
                let (lobe, below) = (n("n_lobe", d.n_lobe), n("n_below", d.n_below));
                // Per half: the disk's four blocks and the root's two (turbine_2d's doc).
                let plane = 2.0
                    * (lobe * (n("n_flank", d.n_flank) + n("n_runout", d.n_runout) + nh + below)
                        + (nh + n("n_slot", d.n_slot)) * below
                        + n("n_root", d.n_root)
                            * (n("n_flank", d.n_flank) + n("n_shank", d.n_shank)));
                if spec.generator.get_ref() == "turbine_3d" {
                    (plane * num("n_z", 10.0), 3, span_of(spec), "mesh.params")
                } else {
                    (plane, 2, span_of(spec), "mesh.params")
                }
            }
            "concentric_rings" => (
                num("n_theta", 16.0) * (num("n_inner", 8.0) + num("n_outer", 8.0)),
                2,
                span_of(spec),
                "mesh.params",
            ),
            "cylinder_on_block" => {
                let (n, m) = (num("n", 40.0), num("m", 30.0));
                // Two bodies of n^2 + 2 n m cells, twice that for the full model.
                (4.0 * (n * n + 2.0 * n * m), 2, span_of(spec), "mesh.params")
            }
            // A Gmsh file's own size bounds its mesh; other generators check their counts.
            _ => return None,
        };
    Some((
        block_cells * nodes_per_block_cell(&kind),
        block_cells,
        dim,
        span,
        field,
    ))
}

/// Checks the size of the mesh a `[mesh]` table would generate, before generating it.
///
/// # Errors
/// [`StudyError::Input`] naming the field, with the cell and memory estimates.
pub fn check_mesh(src: &Source, spec: &MeshSpec, layout: FactorLayout) -> Result<(), StudyError> {
    let Some((nodes, block_cells, dim, span, field)) = mesh_estimate(spec) else {
        return Ok(());
    };
    let need = mesh_memory(nodes, dim, layout);
    let have = available_memory() as f64;
    if need > have || !need.is_finite() {
        return Err(src.error(
            span,
            field,
            format!(
                "this mesh would have about {:.3e} nodes ({:.3e} cells before splitting) and need about {} of memory; {} is available",
                nodes,
                block_cells,
                human_bytes(need),
                human_bytes(have)
            ),
        ));
    }
    Ok(())
}

/// Checks the size of a mesh of `nodes` nodes refined `split` times (`[mesh] split`), before
/// refining it: each refinement multiplies the nodes by about `2^dim`.
///
/// # Errors
/// [`StudyError::Input`] at `mesh.split`, with the node and memory estimates.
pub fn check_split(
    src: &Source,
    span: std::ops::Range<usize>,
    nodes: usize,
    dim: usize,
    split: usize,
    layout: FactorLayout,
) -> Result<(), StudyError> {
    let refined = nodes as f64 * power(1 << dim, split);
    let need = mesh_memory(refined, dim, layout);
    let have = available_memory() as f64;
    if need > have || !need.is_finite() {
        return Err(src.error(
            span,
            "mesh.split",
            format!(
                "{split} refinements of this mesh ({nodes} nodes) would give about {refined:.3e} nodes and need about {} of memory; {} is available",
                human_bytes(need),
                human_bytes(have)
            ),
        ));
    }
    Ok(())
}

fn span_of(spec: &MeshSpec) -> std::ops::Range<usize> {
    spec.params
        .as_ref()
        .map_or(spec.generator.span(), |p| p.span())
}

/// Interface unknowns of each substructure of an assembly, estimated before pairing: `dim`
/// per node of the side-1 facet group of each of its interfaces (the points of a node-to-node
/// pairing, and of a mortar pairing up to the side's ends), counted on both sides.
pub fn interface_unknowns(assembly: &alea_latin::Assembly) -> Vec<usize> {
    let mut n = vec![0usize; assembly.subs.len()];
    for i in &assembly.interfaces {
        let Some(s1) = assembly.subs.get(i.sub1) else {
            continue;
        };
        let mesh = &s1.model.mesh;
        let Ok(facets) = mesh.facet_group(&i.group1) else {
            continue;
        };
        let mut nodes: Vec<usize> = facets
            .iter()
            .flat_map(|f| f.nodes.iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        for s in [i.sub1, i.sub2] {
            if let Some(v) = n.get_mut(s) {
                *v += mesh.dim * nodes.len();
            }
        }
    }
    n
}

/// Bytes of the dense interface operators of substructures with `unknowns` interface
/// unknowns each (`8 n^2`).
pub fn condensed_memory(unknowns: &[usize]) -> f64 {
    unknowns.iter().map(|&n| 8.0 * (n as f64).powi(2)).sum()
}

/// The forced condensed linear stage (`[solver] linear_stage = "condensed"`): its dense
/// interface operators at most a quarter of the available memory (the solver's own rule).
///
/// # Errors
/// [`StudyError::Input`] at `solver.linear_stage`, with the estimate.
pub fn check_condensed(
    src: &Source,
    span: std::ops::Range<usize>,
    assembly: &alea_latin::Assembly,
) -> Result<(), StudyError> {
    let unknowns = interface_unknowns(assembly);
    let need = condensed_memory(&unknowns);
    let have = available_memory() as f64 / 4.0;
    if need > have || !need.is_finite() {
        let (s, n) = unknowns
            .iter()
            .enumerate()
            .max_by_key(|(_, n)| **n)
            .map_or((0, 0), |(s, n)| (s, *n));
        return Err(src.error(
            span,
            "solver.linear_stage",
            format!(
                "the condensed linear stage's dense interface operators would need about {} of memory (substructure '{}': about {n} interface unknowns), more than a quarter of the {} available; use \"auto\" or \"volume\"",
                human_bytes(need),
                assembly.subs.get(s).map_or("", |x| x.name.as_str()),
                human_bytes(4.0 * have)
            ),
        ));
    }
    Ok(())
}

/// `n^d` without overflow (saturating in f64).
fn power(n: usize, d: usize) -> f64 {
    (n as f64).powi(d.min(i32::MAX as usize) as i32)
}

/// Number of terms of a total-degree polynomial basis, `C(p + d, d)`, in f64.
pub fn total_degree_terms(p: usize, d: usize) -> f64 {
    (1..=d).fold(1.0, |acc, k| acc * (p + k) as f64 / k as f64)
}

/// Checks the number of runs a `[[method]]` would ask for in `d` parameters, before its
/// design is built.
///
/// # Errors
/// [`StudyError::Input`] naming the field, with the count.
pub fn check_method(src: &Source, i: usize, m: &MethodSpec, d: usize) -> Result<(), StudyError> {
    let degree = m.degree.as_ref().map_or(2, |v| *v.get_ref());
    let ppd = m.points_per_dim.as_ref().map(|v| *v.get_ref());
    let kind = m.kind.get_ref().as_str();
    let design = m.design.as_ref().map(|s| s.get_ref().as_str());
    if kind.starts_with("pc_") || kind == "polynomial" {
        let terms = total_degree_terms(degree, d);
        if terms > MAX_PC_TERMS as f64 {
            return Err(src.error(
                m.degree.as_ref().map_or(m.kind.span(), |v| v.span()),
                format!("method[{i}].degree"),
                format!(
                    "a total-degree basis of degree {degree} in {d} parameters has {terms:.3e} terms; at most {MAX_PC_TERMS} are allowed"
                ),
            ));
        }
    }
    let (runs, span, field) = match (kind, design) {
        ("pc_projection", _) => (
            power(ppd.unwrap_or(degree + 1), d),
            m.points_per_dim
                .as_ref()
                .map_or(m.kind.span(), |v| v.span()),
            "points_per_dim",
        ),
        ("piecewise_linear", _) | (_, Some("grid")) | ("polynomial", None) => (
            power(ppd.unwrap_or(3), d),
            m.points_per_dim
                .as_ref()
                .map_or(m.kind.span(), |v| v.span()),
            "points_per_dim",
        ),
        (_, Some("corners_centre")) => (power(2, d) + 1.0, m.kind.span(), "design"),
        _ => (
            m.runs.as_ref().map_or(0.0, |v| *v.get_ref() as f64),
            m.runs.as_ref().map_or(m.kind.span(), |v| v.span()),
            "runs",
        ),
    };
    if runs > MAX_RUNS as f64 {
        return Err(src.error(
            span,
            format!("method[{i}].{field}"),
            format!(
                "this design has {runs:.3e} runs (each a full LATIN solve); at most {MAX_RUNS} are allowed"
            ),
        ));
    }
    Ok(())
}

/// Checks the sizes of a study file that do not depend on the mesh: thresholds, statistics
/// settings, solver settings, and the memory of the Monte Carlo analysis.
///
/// # Errors
/// [`StudyError::Input`] naming the field, with the estimate.
pub fn check_study_file(src: &Source, file: &ModelFile, nparams: usize) -> Result<(), StudyError> {
    for (i, q) in file.quantity.iter().enumerate() {
        if q.thresholds.len() > MAX_THRESHOLDS {
            return Err(src.error(
                q.name.span(),
                format!("quantity[{i}].thresholds"),
                format!(
                    "{} thresholds; at most {MAX_THRESHOLDS} are allowed",
                    q.thresholds.len()
                ),
            ));
        }
    }
    let st = &file.statistics;
    if let Some(s) = &st.samples {
        let n = *s.get_ref();
        let nq = file.quantity.len().max(1) as f64;
        let methods = file.method.len().max(1) as f64;
        // Per draw and method: the point, the surrogate values and the samples per quantity,
        // a sorted copy; plus the report's copy and its JSON text.
        let per_draw = methods * (8.0 * nparams as f64 + 16.0 * nq + 8.0) + 40.0 * nq;
        // A goal-oriented loop's step (module `goal`, before the analysis, on the same draws):
        // six columns of surrogate values, the leaf of each draw and a clamped point.
        let goal_step = if file.method.iter().any(|m| m.goal.is_some()) {
            6.0 * 8.0 + 16.0 + 8.0 * nparams as f64
        } else {
            0.0
        };
        let need = n as f64 * per_draw.max(goal_step);
        let have = available_memory() as f64 / 2.0;
        if !(2..=MAX_SAMPLES).contains(&n) || need > have {
            return Err(src.error(
                s.span(),
                "statistics.samples",
                format!(
                    "{n} draws: must be in 2 ..= {MAX_SAMPLES}, and the analysis would need about {} of memory ({} usable)",
                    human_bytes(need),
                    human_bytes(have)
                ),
            ));
        }
    }
    if let Some(k) = &st.kde_points {
        let n = *k.get_ref();
        if !(2..=MAX_KDE_POINTS).contains(&n) {
            return Err(src.error(
                k.span(),
                "statistics.kde_points",
                format!("must be in 2 ..= {MAX_KDE_POINTS}, got {n}"),
            ));
        }
    }
    if let Some(m) = &file.solver.max_iterations {
        let n = *m.get_ref();
        if !(1..=MAX_ITERATIONS).contains(&n) {
            return Err(src.error(
                m.span(),
                "solver.max_iterations",
                format!(
                    "must be in 1 ..= {MAX_ITERATIONS} (each run keeps its residual history), got {n}"
                ),
            ));
        }
    }
    if let Some(a) = &file.solver.acceleration {
        let n = *a.get_ref();
        if n > MAX_ACCELERATION {
            return Err(src.error(
                a.span(),
                "solver.acceleration",
                format!("must be at most {MAX_ACCELERATION}, got {n}"),
            ));
        }
    }
    Ok(())
}

/// Checks the distinct run count of a whole study (methods share points).
///
/// # Errors
/// [`StudyError::TooLarge`].
pub fn check_total_runs(runs: usize) -> Result<(), StudyError> {
    if runs > MAX_RUNS {
        return Err(StudyError::TooLarge(format!(
            "the methods ask for {runs} distinct runs; at most {MAX_RUNS} are allowed"
        )));
    }
    Ok(())
}

/// Memory (bytes) of the weight moments of the mean / std fields for `runs` surrogate runs
/// whose weights at one draw involve at most `support` runs (`fields.rs`,
/// `WeightMoments::estimate`): about 56 bytes per pair of runs non-zero together (the sums of
/// each support, the `(a, b, value)` entries sorted before assembly, the assembled matrix),
/// `runs^2` pairs for a global surrogate (`support >= runs`: chaos, polynomials) and at most
/// `runs support^2` for a local one (one `support x support` block per cell of a stochastic
/// mesh), plus the 256 MB to which `estimate` bounds the chunk sums held at once.
///
/// Measured (`cargo bench -p alea-study --bench scale`): a piecewise-linear study of 10 000
/// runs peaks at about 300 MB; the former estimate, `128 runs^2` bytes for every surrogate,
/// said 12.8 GB and refused it.
pub fn mean_fields_memory(runs: usize, support: usize) -> f64 {
    let k = runs as f64;
    let pairs = if support >= runs {
        k * k
    } else {
        k * (support as f64) * (support as f64)
    };
    56.0 * pairs + 256.0 * 1024.0 * 1024.0
}

/// Checks a `--threads` value against the machine.
///
/// # Errors
/// [`StudyError::Usage`] outside `1 ..= min(4 x cores, MAX_THREADS)`.
pub fn check_threads(n: usize) -> Result<usize, StudyError> {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    let max = (4 * cores).clamp(4, MAX_THREADS);
    if n == 0 || n > max {
        return Err(StudyError::Usage(format!(
            "--threads {n}: must be in 1 ..= {max} (this machine has {cores} core(s); results do not depend on the thread count)"
        )));
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_degree_terms_are_binomials() {
        assert_eq!(total_degree_terms(2, 2), 6.0);
        assert_eq!(total_degree_terms(3, 4), 35.0);
        assert_eq!(total_degree_terms(0, 7), 1.0);
        assert!(total_degree_terms(1000, 100) > 1e100);
    }

    #[test]
    fn byte_counts_read_well() {
        assert_eq!(human_bytes(512.0), "512 bytes");
        assert_eq!(human_bytes(1.6e10), "16.0 GB");
    }

    #[test]
    fn threads_beyond_the_machine_are_refused() {
        assert!(check_threads(1).is_ok());
        let e = check_threads(100_000).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("core"), "{e}");
        assert!(check_threads(0).is_err());
    }
}
