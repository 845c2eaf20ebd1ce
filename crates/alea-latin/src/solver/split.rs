//! Automatic subdomains (issue 38): large substructures split into parts joined by perfect
//! interfaces, solved by the two-scale LATIN, and the answer given back on the user's
//! substructures and interfaces.
//!
//! A substructure `Omega_s` asked to split in `k` parts is cut along the facets between the
//! parts of a METIS k-way partition of its cells (`alea_fem::partition`): `Omega_s = U_j
//! Omega_s^j`. Every part is a substructure of its own (its cells with their materials, the
//! constraints of its nodes, the load cases' nodal forces of the nodes it owns: a node on a cut
//! belongs to several parts and its force goes to the first, the perfect interface carries the
//! rest), and every pair of parts sharing facets is joined by a perfect interface
//! `Gamma_jm` (thesis (1.3): `W_j = W_m`, `F_j + F_m = 0`), node to node on the coincident
//! copies of the cut's nodes. Each interface of the user between `Omega_s` and `Omega_t` is
//! paired once on the undivided substructures; its points are then shared among pieces, one
//! per pair of parts `(j, m)` holding the point's side-1 and side-2 nodes, each piece solved
//! with the user's points (a given pairing) and the user's search direction (its length and
//! moduli: the same `k_0 = E / L` as undivided, module `solver::setup`). A cut lies inside one
//! body, so its search direction is the stiffness of a layer of cells, `k = E / h` with `h` its
//! mean facet size ([`Split::solver`]). The LATIN answer is
//! that of the undivided model (the cuts' interfaces are perfect), to the solver tolerance;
//! the coarse problem keeps the iteration count nearly flat with the number of parts
//! (`tests/weak_scaling.rs`).
//!
//! [`Split::merge`] gives a run's result back on the user's assembly: each user node's
//! displacement from the part that owns it, each user interface's point data from its
//! pieces, each substructure's equilibrium check from its worst part, and the run's end state
//! on the solved interfaces, cuts included ([`crate::RunResult::split_state`]), so that a run
//! warm-started from it starts its cuts too (measured on the 3D turbine refined once: 68
//! iterations instead of 128 with the cuts started from zero). A modulus varying from cell to
//! cell is taken part by part. Not split: a substructure on a cyclic interface (refused by
//! [`Split::new`]), any substructure of an assembly with a large-sliding interface.
//!
//! **In the solver** ([`LatinOptions::subdomains`], [`plan`], [`build`]): `LatinSolver::new`
//! cuts each 3D substructure of at least [`AUTO_MIN_DOFS`] unknowns (`Auto`), or of at least
//! twice the target (`Always`), into `round(n / subdomain_dofs)` parts, and the solver then
//! runs on the parts while its accessors (`num_subs`, `model`, `interface_points`, ...), its
//! runs' inputs and its results speak of the user's substructures and interfaces: studies,
//! quantities, outputs and the error estimate see the user's model. The stopping indicator's
//! scale is then the user's interfaces' (module `local_stage`): the cuts carry the inner forces
//! of a body, whose size would dilute `eta` (at the same indicator the split model's error was
//! 14x the undivided one's; with the user's scale it is the same, `alea-study
//! tests/subdomains.rs`). Unless the options set one, a run's Anderson depth is
//! [`SPLIT_ACCELERATION`] (`LatinSolver::acceleration`). Over MPI ranks
//! (`LatinSolver::with_ranks`, module `ranks`) the subdomains are spread over the ranks, each
//! factorising its own.
//!
//! **Cost.** The coarse problem has `6` unknowns per interface in 3D (`3` in 2D), cuts
//! included, and is inverted densely per run (module `crate::coarse`): thousands of
//! subdomains would make it the bottleneck; the default target size keeps it to hundreds.
//!
//! Why: a sparse factorisation of a 3D part of `n` unknowns costs `O(n^2)` to build and
//! `O(n^{4/3})` to store and to solve with; `k` parts of `n / k` cost `O(n^2 / k)` and
//! `O(n^{4/3} k^{-1/3})`, plus the interfaces (BENCHMARKS.md "Automatic subdomains").

use std::collections::BTreeMap;
use std::sync::Arc;

use alea_mesh::{Facet, Mesh};

use super::Subdomains;
use crate::interface::{InterfacePairing, SideProjection};
use crate::sides::pair_sides;
use crate::{
    Assembly, InterfaceResult, InterfaceSpec, LatinError, LatinOptions, LatinSolver, LocalState,
    PointData, RunInput, RunResult, SearchDirection, Substructure,
};

/// The default target size of a subdomain, in unknowns ([`LatinOptions::subdomain_dofs`]).
/// Measured on the 3D turbine refined once (602 100 unknowns, `BENCHMARKS.md` "Automatic
/// subdomains"): parts of 33 000 and 19 000 unknowns ran equally fast, the smaller in 12 %
/// less memory.
pub const SUBDOMAIN_DOFS: usize = 20_000;

/// The size from which [`Subdomains::Auto`] cuts a substructure, at the break-even measured
/// on the 3D turbine (`BENCHMARKS.md` "Automatic subdomains", "In studies"): runs 1.8 - 2.3x
/// slower cut at about 20 000 unknowns per substructure, 1.28x faster at 130 000 - 160 000,
/// even at 80 000 - 95 000 by log-interpolation; above it, the memory falls too.
pub const AUTO_MIN_DOFS: usize = 100_000;

/// The Anderson depth on a model cut into subdomains when the options leave it to the solver
/// ([`LatinOptions::acceleration`] `None`). The cuts are perfect interfaces, on which the LATIN
/// map is linear and a longer history acts more like GMRES. Measured on the 3D turbine refined
/// once (602 100 unknowns in 30 parts, two Monte Carlo runs, `BENCHMARKS.md` "Anderson depth"):
/// 112 iterations at depth 5, 96.5 at 10, 90 at 20; each level of the history costs two
/// interface states per run in flight (about 4.5 MB there), and a study keeps up to 16 runs in
/// flight, so 10 rather than 20.
pub const SPLIT_ACCELERATION: usize = 10;

/// The number of parts of each substructure of `assembly` that `options` ask for
/// ([`LatinOptions::subdomains`]); `None` when none is cut. A substructure on a cyclic
/// interface is never cut (its pairing is not shared among pieces), nor is any substructure of
/// an assembly with a large-sliding interface.
pub fn plan(assembly: &Assembly, options: &LatinOptions) -> Option<Vec<usize>> {
    // Large sliding re-pairs the whole assembly at every pass (module `crate::large_sliding`):
    // its passes must solve the same substructures.
    if assembly
        .interfaces
        .iter()
        .any(|spec| spec.sliding == crate::Sliding::Large)
    {
        return None;
    }
    let min = match options.subdomains {
        Subdomains::Never => return None,
        Subdomains::Auto => AUTO_MIN_DOFS,
        Subdomains::Always => 2 * options.subdomain_dofs.max(1),
    };
    let parts: Vec<usize> = assembly
        .subs
        .iter()
        .enumerate()
        .map(|(s, sub)| {
            let special = assembly.interfaces.iter().any(|spec| {
                (spec.sub1 == s || spec.sub2 == s)
                    && (spec.cyclic.is_some() || spec.sliding == crate::Sliding::Large)
            });
            let n = sub.model.mesh.num_nodes() * sub.model.mesh.dim;
            // `Auto` cuts 3D substructures only: the break-even was measured in 3D, where a
            // factor's fill grows like `n^{4/3}`; a 2D factor's grows like `n log n`.
            let auto_2d = options.subdomains == Subdomains::Auto && sub.model.mesh.dim < 3;
            if special || auto_2d || n < min {
                return 1;
            }
            ((n as f64 / options.subdomain_dofs.max(1) as f64).round() as usize).max(2)
        })
        .collect();
    parts.iter().any(|&k| k > 1).then_some(parts)
}

/// The solver of `assembly` cut into `parts[s]` parts per substructure: the LATIN runs on the
/// parts, its accessors, inputs and results speak of the user's assembly (module doc).
///
/// With `exchange`, the subdomains are spread over its ranks (module `ranks`): each rank
/// factorises its own.
pub(super) fn build(
    assembly: &Assembly,
    options: LatinOptions,
    parts: &[usize],
    exchange: Option<Arc<dyn crate::ranks::RankExchange>>,
) -> Result<LatinSolver, LatinError> {
    let t0 = std::time::Instant::now();
    let mut split = Split::new(assembly, parts)?;
    let mut solver = split.solver_on(options.clone(), exchange)?;
    split.user_interfaces = split.user_interfaces(&solver);
    solver.options = options;
    solver.split = Some(Arc::new(split));
    solver.setup_seconds = t0.elapsed().as_secs_f64();
    Ok(solver)
}

/// What the user sees of one of its interfaces when its substructures are split: its
/// pairing on the undivided substructures and its points' data.
#[derive(Clone, Debug)]
pub(super) struct UserInterface {
    pub(super) name: String,
    pub(super) law: &'static str,
    pub(super) subs: [usize; 2],
    pub(super) points: Vec<PointData>,
    pub(super) weights: Vec<f64>,
    pub(super) pairing: Arc<InterfacePairing>,
}

/// The parts of one user substructure.
#[derive(Clone, Debug)]
struct Parts {
    /// Inner substructure of each part.
    inner: Vec<usize>,
    /// Per part, its node of each user node (`usize::MAX`: not in the part).
    local: Vec<Vec<usize>>,
    /// Per part, the user cell of each of its cells.
    cells: Vec<Vec<usize>>,
    /// The part and node that own each user node (its displacement, its nodal forces).
    owner: Vec<(usize, usize)>,
}

/// The pieces of one user interface.
#[derive(Clone, Debug)]
enum Pieces {
    /// Neither side split: the inner interface is the user's.
    Whole(usize),
    /// Its pairing on the undivided substructures and, per piece, the inner interface and
    /// the user points it holds.
    Split {
        pairing: Arc<InterfacePairing>,
        pieces: Vec<(usize, Vec<usize>)>,
    },
}

/// A user assembly with some substructures split into parts (module doc).
#[derive(Clone)]
pub struct Split {
    /// The assembly the LATIN runs on: the parts, the pieces and the cuts' interfaces.
    pub inner: Assembly,
    pub(super) user: Arc<Assembly>,
    /// The user's interfaces as the accessors of a split solver give them (empty until the
    /// solver is built, [`build`]).
    user_interfaces: Vec<UserInterface>,
    pairings: Vec<Option<InterfacePairing>>,
    parts: Vec<Parts>,
    pieces: Vec<Pieces>,
    /// The cuts' interfaces (their `direction_scale` length is their mean facet size).
    cuts: Vec<usize>,
}

impl Split {
    /// Splits substructure `s` of `assembly` into `parts[s]` parts (1 or a missing entry: not
    /// split).
    ///
    /// # Errors
    /// A substructure on a cyclic or large-sliding interface asked to split, a partition that
    /// fails, and the pairing errors of the interfaces of split substructures.
    pub fn new(assembly: &Assembly, parts: &[usize]) -> Result<Split, LatinError> {
        let want = |s: usize| parts.get(s).copied().unwrap_or(1).max(1);
        for spec in &assembly.interfaces {
            let special = spec.cyclic.is_some() || spec.sliding == crate::Sliding::Large;
            if special && (want(spec.sub1) > 1 || want(spec.sub2) > 1) {
                return Err(LatinError::Invalid(format!(
                    "interface '{}' is cyclic or in large sliding: its substructures cannot be \
                     split into subdomains",
                    spec.name
                )));
            }
        }
        let mut inner = Assembly::default();
        let mut all_parts = Vec::with_capacity(assembly.subs.len());
        let mut cut_groups = Vec::new();
        for (s, sub) in assembly.subs.iter().enumerate() {
            let (subs, p, cuts) = split_substructure(sub, want(s), inner.subs.len())?;
            inner.subs.extend(subs);
            all_parts.push(p);
            cut_groups.push(cuts);
        }
        let mut pairings = Vec::new();
        let mut pieces = Vec::with_capacity(assembly.interfaces.len());
        for spec in &assembly.interfaces {
            let (s1, s2) = (spec.sub1, spec.sub2);
            if all_parts[s1].inner.len() == 1 && all_parts[s2].inner.len() == 1 {
                let mut whole = spec.clone();
                whole.sub1 = all_parts[s1].inner[0];
                whole.sub2 = all_parts[s2].inner[0];
                pieces.push(Pieces::Whole(inner.interfaces.len()));
                inner.interfaces.push(whole);
                pairings.push(None);
                continue;
            }
            let scale = crate::solver::direction_scale(spec, &assembly.subs)?;
            let pairing = pair_sides(spec, [&assembly.subs[s1], &assembly.subs[s2]], None)?;
            let mut by_parts: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
            for p in 0..pairing.len() {
                let j = part_of(&all_parts[s1], &pairing.sides[0], p, &spec.name)?;
                let m = part_of(&all_parts[s2], &pairing.sides[1], p, &spec.name)?;
                by_parts.entry((j, m)).or_default().push(p);
            }
            let mut list = Vec::new();
            for ((j, m), points) in by_parts {
                let (a, b) = (all_parts[s1].inner[j], all_parts[s2].inner[m]);
                for (sub, group) in [(a, &spec.group1), (b, &spec.group2)] {
                    let mesh = &mut inner.subs[sub].model.mesh;
                    mesh.facet_groups.entry(group.clone()).or_default();
                }
                let piece = InterfaceSpec {
                    name: format!("{}#{j}-{m}", spec.name),
                    sub1: a,
                    sub2: b,
                    direction_scale: Some(scale),
                    ..spec.clone()
                };
                let restricted = restrict(
                    &pairing,
                    &points,
                    [&all_parts[s1].local[j], &all_parts[s2].local[m]],
                );
                list.push((inner.interfaces.len(), points));
                inner.interfaces.push(piece);
                pairings.push(Some(restricted));
            }
            pieces.push(Pieces::Split {
                pairing: Arc::new(pairing),
                pieces: list,
            });
        }
        let mut cuts = Vec::new();
        for (s, pairs) in cut_groups.into_iter().enumerate() {
            for (j, m) in pairs {
                let (a, b) = (all_parts[s].inner[j], all_parts[s].inner[m]);
                let mut cut = InterfaceSpec::perfect(
                    &format!("{}#cut{j}-{m}", assembly.subs[s].name),
                    a,
                    &cut_group(m),
                    b,
                    &cut_group(j),
                );
                // A cut is inside one body: its search direction is the stiffness of a cell
                // layer, `E / h` (h the cut's mean facet size; [`Split::solver`]), not `E / L`
                // of the whole interface (BENCHMARKS.md "Automatic subdomains").
                let mut scale = crate::solver::direction_scale(&cut, &inner.subs)?;
                let facets = inner.subs[a].model.mesh.facet_groups[&cut_group(m)].len();
                let dim = inner.subs[a].model.mesh.dim;
                scale.length /= (facets.max(1) as f64).powf(1.0 / (dim as f64 - 1.0));
                cut.direction_scale = Some(scale);
                cuts.push(inner.interfaces.len());
                inner.interfaces.push(cut);
                pairings.push(None);
            }
        }
        Ok(Split {
            inner,
            user: Arc::new(assembly.clone()),
            user_interfaces: Vec::new(),
            pairings,
            parts: all_parts,
            pieces,
            cuts,
        })
    }

    /// The number of parts of each user substructure.
    pub fn parts(&self) -> Vec<usize> {
        self.parts.iter().map(|p| p.inner.len()).collect()
    }

    /// Whether solved interface `i` is a cut between two subdomains (not a piece of a user
    /// interface).
    pub fn is_cut(&self, i: usize) -> bool {
        self.cuts.binary_search(&i).is_ok()
    }

    /// The solved substructures (indices in [`Split::inner`]) of user substructure `s`.
    pub fn parts_of(&self, s: usize) -> &[usize] {
        &self.parts[s].inner
    }

    /// The LATIN solver of the split assembly.
    ///
    /// # Errors
    /// As [`LatinSolver::with_pairings`].
    ///
    /// The cuts' search direction is `k = CUT_DIRECTION E / h`, whatever the options' factor
    /// (which is tuned for the user's interfaces, often contact).
    pub fn solver(&self, options: LatinOptions) -> Result<LatinSolver, LatinError> {
        self.solver_on(options, None)
    }

    /// [`Split::solver`], spread over the ranks of `exchange` when given
    /// ([`LatinSolver::with_ranks`]).
    fn solver_on(
        &self,
        options: LatinOptions,
        exchange: Option<Arc<dyn crate::ranks::RankExchange>>,
    ) -> Result<LatinSolver, LatinError> {
        let mut inner = self.inner.clone();
        let mut options = options;
        options.subdomains = Subdomains::Never;
        let factor = match options.search_direction {
            SearchDirection::Auto { factor } | SearchDirection::Split { factor, .. } => factor,
            SearchDirection::Fixed(_) => 1.0,
        };
        for &k in &self.cuts {
            if let Some(scale) = inner.interfaces[k].direction_scale.as_mut() {
                scale.length *= factor / CUT_DIRECTION;
            }
        }
        let ranks = exchange.map(|e| super::ranks::Ranks::for_assembly(e, &inner));
        LatinSolver::set_up(inner, options, self.pairings.clone(), None, ranks)
    }

    /// A user run's input on the split assembly (`solver` from [`Split::solver`]): each
    /// part with its substructure's factors, each piece with its interface's fields, the
    /// start states restricted to the pieces (the cuts start from zero) - or, given as a state
    /// of the split assembly (an inner run's `end_state()`, cuts included), taken as they are.
    ///
    /// # Errors
    /// A modulus varying from cell to cell (not supported), a start state of another
    /// assembly.
    pub fn input(&self, solver: &LatinSolver, input: &RunInput) -> Result<RunInput, LatinError> {
        let mut out = input.clone();
        out.cell_young = self.cell_young(&input.cell_young)?;
        let per_part = |v: &dyn Fn(usize) -> Option<f64>| -> Vec<f64> {
            let mut o = vec![1.0; self.inner.subs.len()];
            for (s, p) in self.parts.iter().enumerate() {
                for &i in &p.inner {
                    o[i] = v(s).unwrap_or(1.0);
                }
            }
            o
        };
        if !input.young_factors.is_empty() {
            out.young_factors = per_part(&|s| input.young_factors.get(s).copied());
        }
        if !input.load_factors.is_empty() {
            let mut lf = vec![Vec::new(); self.inner.subs.len()];
            for (s, p) in self.parts.iter().enumerate() {
                for &i in &p.inner {
                    lf[i] = input.load_factors.get(s).cloned().unwrap_or_default();
                }
            }
            out.load_factors = lf;
        }
        let n = self.inner.interfaces.len();
        for (field, user) in [(&mut out.mu, &input.mu), (&mut out.gap, &input.gap)] {
            if user.is_empty() {
                continue;
            }
            *field = vec![None; n];
            for (i, pieces) in self.pieces.iter().enumerate() {
                for k in pieces.inner() {
                    field[k] = user.get(i).cloned().flatten();
                }
            }
        }
        out.initial = match &input.initial {
            Some(st) => Some(Arc::new(self.state(solver, st)?)),
            None => None,
        };
        out.previous_step = match &input.previous_step {
            Some(st) => Some(Arc::new(self.state(solver, st)?)),
            None => None,
        };
        Ok(out)
    }

    /// A user's local-stage state on the split assembly: the pieces take their points'
    /// values, the cuts zero.
    fn state(&self, solver: &LatinSolver, user: &LocalState) -> Result<LocalState, LatinError> {
        // A state of the split assembly itself (a previous inner run's end, with its cuts):
        // taken as it is.
        if user.what.len() == self.inner.interfaces.len() {
            return Ok(user.clone());
        }
        if user.what.len() != self.pieces.len() {
            return Err(LatinError::Invalid(format!(
                "a start state of {} interfaces for {}",
                user.what.len(),
                self.pieces.len()
            )));
        }
        let n = self.inner.interfaces.len();
        let zeros = |i: usize| {
            let np = solver.ifaces[i].points.len();
            [vec![[0.0; 3]; np], vec![[0.0; 3]; np]]
        };
        let mut what: Vec<[Vec<[f64; 3]>; 2]> = (0..n).map(zeros).collect();
        let mut fhat = what.clone();
        for (i, pieces) in self.pieces.iter().enumerate() {
            match pieces {
                Pieces::Whole(k) => {
                    what[*k] = user.what[i].clone();
                    fhat[*k] = user.fhat[i].clone();
                }
                Pieces::Split { pieces, .. } => {
                    for (k, points) in pieces {
                        for s in 0..2 {
                            what[*k][s] = points.iter().map(|&p| user.what[i][s][p]).collect();
                            fhat[*k][s] = points.iter().map(|&p| user.fhat[i][s][p]).collect();
                        }
                    }
                }
            }
        }
        Ok(LocalState { what, fhat })
    }

    /// A run's result on the split assembly given back on the user's assembly (module doc).
    pub fn merge(&self, input: &RunInput, r: RunResult) -> RunResult {
        let dim = self.user.subs.first().map_or(2, |s| s.model.mesh.dim);
        let displacements = self
            .parts
            .iter()
            .map(|p| {
                let mut u = vec![0.0; p.owner.len() * dim];
                for (n, &(j, l)) in p.owner.iter().enumerate() {
                    let v = &r.displacements[p.inner[j]];
                    u[n * dim..n * dim + dim].copy_from_slice(&v[l * dim..l * dim + dim]);
                }
                u
            })
            .collect();
        let interfaces = self
            .pieces
            .iter()
            .enumerate()
            .map(|(i, pieces)| self.merge_interface(i, pieces, &r.interfaces))
            .collect();
        let equilibrium = self
            .parts
            .iter()
            .map(|p| {
                p.inner
                    .iter()
                    .map(|&i| r.equilibrium[i])
                    .max_by(|a, b| a.relative_imbalance.total_cmp(&b.relative_imbalance))
                    .expect("a substructure has at least one part")
            })
            .collect();
        let young_factors = (0..self.parts.len())
            .map(|s| input.young_factors.get(s).copied().unwrap_or(1.0))
            .collect();
        let split_state = Some(Arc::new(r.end_state()));
        RunResult {
            status: r.status,
            iterations: r.iterations,
            residuals: r.residuals,
            displacements,
            interfaces,
            young_factors,
            cell_young: input.cell_young.clone(),
            equilibrium,
            timings: r.timings,
            split_state,
        }
    }

    /// The runs of `inputs` (the user's) on `solver`, the split solver built by [`build`]:
    /// each input mapped onto the parts, the batch solved, each result merged back.
    pub(super) fn run_batch(
        &self,
        solver: &LatinSolver,
        inputs: &[RunInput],
    ) -> Vec<Result<RunResult, LatinError>> {
        let mapped: Vec<Result<RunInput, LatinError>> =
            inputs.iter().map(|i| self.input(solver, i)).collect();
        let valid: Vec<RunInput> = mapped
            .iter()
            .filter_map(|m| m.as_ref().ok())
            .cloned()
            .collect();
        let mut results = solver.run_solved(&valid).into_iter();
        mapped
            .into_iter()
            .zip(inputs)
            .map(|(m, input)| {
                m?;
                let r = results
                    .next()
                    .ok_or_else(|| LatinError::Invalid("a batch gave fewer results".into()))??;
                Ok(self.merge(input, r))
            })
            .collect()
    }

    /// The user's interface `i` (module doc; a solver built by [`build`]).
    pub(super) fn user_interface(&self, i: usize) -> &UserInterface {
        &self.user_interfaces[i]
    }

    /// The user's interfaces seen from `solver`, the solver of the parts: a whole interface
    /// as the solver paired it, a split one with its undivided pairing and its pieces' points.
    fn user_interfaces(&self, solver: &LatinSolver) -> Vec<UserInterface> {
        self.pieces
            .iter()
            .enumerate()
            .map(|(i, pieces)| {
                let spec = &self.user.interfaces[i];
                let subs = [spec.sub1, spec.sub2];
                match pieces {
                    Pieces::Whole(k) => {
                        let op = &solver.ifaces[*k];
                        UserInterface {
                            name: spec.name.clone(),
                            law: op.law.name(),
                            subs,
                            points: op.points.clone(),
                            weights: op.weights.clone(),
                            pairing: op.pairing.clone(),
                        }
                    }
                    Pieces::Split { pairing, pieces } => {
                        let first = &solver.ifaces[pieces[0].0];
                        let np = pairing.len();
                        let mut points = vec![first.points[0]; np];
                        let mut weights = vec![0.0; np];
                        for (k, list) in pieces {
                            let op = &solver.ifaces[*k];
                            for (q, &p) in list.iter().enumerate() {
                                points[p] = op.points[q];
                                weights[p] = op.weights[q];
                            }
                        }
                        UserInterface {
                            name: spec.name.clone(),
                            law: first.law.name(),
                            subs,
                            points,
                            weights,
                            pairing: pairing.clone(),
                        }
                    }
                }
            })
            .collect()
    }

    /// The user's cell factors of Young's modulus (`RunInput::cell_young`) on the parts: each
    /// part takes its cells' factors.
    ///
    /// # Errors
    /// A factor list that has not one entry per cell of its substructure.
    fn cell_young(
        &self,
        user: &[Option<Arc<Vec<f64>>>],
    ) -> Result<Vec<Option<Arc<Vec<f64>>>>, LatinError> {
        if user.iter().all(Option::is_none) {
            return Ok(Vec::new());
        }
        let mut out = vec![None; self.inner.subs.len()];
        for (s, factors) in user.iter().enumerate() {
            let Some(factors) = factors.as_ref().filter(|f| !f.is_empty()) else {
                continue;
            };
            let p = self.parts.get(s).ok_or_else(|| {
                LatinError::Invalid(format!(
                    "cell Young's-modulus factors given for {} substructures, there are {}",
                    user.len(),
                    self.parts.len()
                ))
            })?;
            let cells = self.user.subs[s].model.mesh.num_cells();
            if factors.len() != cells {
                return Err(LatinError::Invalid(format!(
                    "substructure '{}': {} cell Young's-modulus factors for {cells} cells",
                    self.user.subs[s].name,
                    factors.len()
                )));
            }
            for (j, &i) in p.inner.iter().enumerate() {
                out[i] = Some(Arc::new(p.cells[j].iter().map(|&c| factors[c]).collect()));
            }
        }
        Ok(out)
    }

    fn merge_interface(
        &self,
        i: usize,
        pieces: &Pieces,
        inner: &[InterfaceResult],
    ) -> InterfaceResult {
        let spec = &self.user.interfaces[i];
        let (pairing, list) = match pieces {
            Pieces::Whole(k) => {
                let mut r = inner[*k].clone();
                r.subs = [spec.sub1, spec.sub2];
                return r;
            }
            Pieces::Split { pairing, pieces } => (pairing, pieces),
        };
        let np = pairing.len();
        let first = &inner[list[0].0];
        let mut out = InterfaceResult {
            name: spec.name.clone(),
            law: first.law,
            subs: [spec.sub1, spec.sub2],
            nodes: [0, 1].map(|s| {
                let proj = &pairing.sides[s];
                (0..proj.len()).map(|p| proj.main_node(p)).collect()
            }),
            pairing: pairing.clone(),
            points: vec![first.points[0]; np],
            weights: pairing.weights.clone(),
            w: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
            f: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
            what: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
            what_prev: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
            fhat: [vec![[0.0; 3]; np], vec![[0.0; 3]; np]],
            status: vec![first.status[0]; np],
        };
        for (k, points) in list {
            let piece = &inner[*k];
            for (q, &p) in points.iter().enumerate() {
                out.points[p] = piece.points[q];
                out.status[p] = piece.status[q];
                for s in 0..2 {
                    out.w[s][p] = piece.w[s][q];
                    out.f[s][p] = piece.f[s][q];
                    out.what[s][p] = piece.what[s][q];
                    out.what_prev[s][p] = piece.what_prev[s][q];
                    out.fhat[s][p] = piece.fhat[s][q];
                }
            }
        }
        out
    }
}

impl Pieces {
    /// The inner interfaces of a user interface.
    fn inner(&self) -> Vec<usize> {
        match self {
            Pieces::Whole(k) => vec![*k],
            Pieces::Split { pieces, .. } => pieces.iter().map(|(k, _)| *k).collect(),
        }
    }
}

/// The factor of the cuts' search direction `k = CUT_DIRECTION E / h` (module doc).
/// Measured with the stopping test on the user's interfaces (session 16; mean LATIN
/// iterations of two cold runs of the 3D turbine, user factor 0.5): refined once, 602 100 dof
/// in 8 / 8 / 7 / 7 parts (undivided: 86), 0.125: 127, **0.25: 110.5**, 0.5: 118.5, 1: 155;
/// unrefined, 82 524 dof in 10 parts (undivided 59.5), 0.25: 61, 0.5: 63.5, 1: 65.5, 2: 71.5,
/// 4: 86. Earlier, with the indicator over every interface: flat from 0.25 to 2 on the
/// unrefined turbine and the contact tests of `tests/split.rs`; the user's `factor E / L`
/// instead of `E / h`: 97 / 98 iterations on the turbine (undivided: 55 / 44).
const CUT_DIRECTION: f64 = 0.25;

fn cut_group(neighbour: usize) -> String {
    format!("__cut_{neighbour}")
}

/// The part of `parts` holding every node of row `p` of `proj` (the first such part).
fn part_of(
    parts: &Parts,
    proj: &SideProjection,
    p: usize,
    name: &str,
) -> Result<usize, LatinError> {
    let row = &proj.nodes[proj.ptr[p]..proj.ptr[p + 1]];
    (0..parts.inner.len())
        .find(|&j| row.iter().all(|&n| parts.local[j][n] != usize::MAX))
        .ok_or_else(|| {
            LatinError::Invalid(format!(
                "interface '{name}': point {p} spans two subdomains of a split substructure"
            ))
        })
}

/// The pairing's points `points`, their nodes renumbered to the parts' (`local[s][user]`).
fn restrict(
    pairing: &InterfacePairing,
    points: &[usize],
    local: [&Vec<usize>; 2],
) -> InterfacePairing {
    let pick = |v: &[[f64; 3]]| points.iter().map(|&p| v[p]).collect::<Vec<_>>();
    let sides = [0, 1].map(|s| {
        let proj = &pairing.sides[s];
        let mut ptr = vec![0];
        let (mut nodes, mut coef) = (Vec::new(), Vec::new());
        for &p in points {
            for e in proj.ptr[p]..proj.ptr[p + 1] {
                nodes.push(local[s][proj.nodes[e]]);
                coef.push(proj.coef[e]);
            }
            ptr.push(nodes.len());
        }
        SideProjection {
            weights: points.iter().map(|&p| proj.weights[p]).collect(),
            ptr,
            nodes,
            coef,
        }
    });
    InterfacePairing {
        kind: pairing.kind,
        x: pick(&pairing.x),
        normals: pick(&pairing.normals),
        weights: points.iter().map(|&p| pairing.weights[p]).collect(),
        geometric_gap: points.iter().map(|&p| pairing.geometric_gap[p]).collect(),
        sides,
        rotation: pairing.rotation,
        // Used by large sliding only, which a split substructure does not take.
        point_nodes: Vec::new(),
    }
}

/// Substructure `sub` in `k` parts (inner indices from `first`): the parts, their maps, and
/// the pairs of parts `(j, m)`, `j < m`, that share facets (each part's mesh then has the
/// facet group `__cut_m` of its facets shared with part `m`).
#[allow(clippy::type_complexity)]
fn split_substructure(
    sub: &Substructure,
    k: usize,
    first: usize,
) -> Result<(Vec<Substructure>, Parts, Vec<(usize, usize)>), LatinError> {
    let mesh = &sub.model.mesh;
    let n = mesh.num_nodes();
    if k == 1 {
        return Ok((
            vec![sub.clone()],
            Parts {
                inner: vec![first],
                local: vec![(0..n).collect()],
                cells: vec![(0..mesh.num_cells()).collect()],
                owner: (0..n).map(|i| (0, i)).collect(),
            },
            Vec::new(),
        ));
    }
    let fem = |source| LatinError::Fem {
        sub: sub.name.clone(),
        source,
    };
    let part = alea_fem::partition::partition_cells(mesh, k).map_err(fem)?;
    let mut marked = mesh.clone();
    for j in 0..k {
        let cells: Vec<usize> = (0..part.len()).filter(|&c| part[c] == j).collect();
        marked.add_cells_to_group(&format!("__part_{j}"), cells);
    }
    let mut meshes = Vec::with_capacity(k);
    let mut nodes = Vec::with_capacity(k);
    let mut cells = Vec::with_capacity(k);
    for j in 0..k {
        let (m, nm, cm) = marked
            .extract_with_cells(&[&format!("__part_{j}")])
            .map_err(|e| LatinError::Invalid(format!("substructure '{}': {e}", sub.name)))?;
        meshes.push(m);
        nodes.push(nm);
        cells.push(cm);
    }
    let mut local = vec![vec![usize::MAX; n]; k];
    for j in 0..k {
        for (l, &u) in nodes[j].iter().enumerate() {
            local[j][u] = l;
        }
    }
    let mut owner = vec![(usize::MAX, usize::MAX); n];
    for j in (0..k).rev() {
        for (l, &u) in nodes[j].iter().enumerate() {
            owner[u] = (j, l);
        }
    }
    let cuts = add_cut_groups(mesh, &part, &local, &mut meshes);
    let dim = mesh.dim;
    let mut subs = Vec::with_capacity(k);
    for (j, m) in meshes.into_iter().enumerate() {
        let model = sub.model.restricted(m, &cells[j]).map_err(fem)?;
        let constraints = sub.constraints.restricted(|u| {
            let l = local[j][u];
            (l != usize::MAX).then_some(l)
        });
        let load_cases = sub
            .load_cases
            .iter()
            .map(|f| {
                let mut g = vec![0.0; nodes[j].len() * dim];
                for (l, &u) in nodes[j].iter().enumerate() {
                    if owner[u] == (j, l) {
                        g[l * dim..l * dim + dim].copy_from_slice(&f[u * dim..u * dim + dim]);
                    }
                }
                g
            })
            .collect();
        subs.push(Substructure {
            name: format!("{}#{j}", sub.name),
            model,
            constraints,
            load_cases,
        });
    }
    Ok((
        subs,
        Parts {
            inner: (first..first + k).collect(),
            local,
            cells,
            owner,
        },
        cuts,
    ))
}

/// Adds to each part's mesh the facet groups `__cut_m` of its cells' facets shared with part
/// `m` (oriented outward from the part), and returns the pairs `(j, m)`, `j < m`, that share
/// facets.
fn add_cut_groups(
    mesh: &Mesh,
    part: &[usize],
    local: &[Vec<usize>],
    meshes: &mut [Mesh],
) -> Vec<(usize, usize)> {
    // Ordered by facet key: the cut groups, hence the cuts' points, the same in every process.
    let mut by_key: BTreeMap<Vec<usize>, Vec<(usize, Facet)>> = BTreeMap::new();
    for (c, kind, nodes) in mesh.cells() {
        for (fk, loc) in kind.facets() {
            let f = Facet {
                kind: *fk,
                nodes: loc.iter().map(|&i| nodes[i]).collect(),
            };
            by_key.entry(f.key()).or_default().push((c, f));
        }
    }
    let mut groups: BTreeMap<(usize, usize), Vec<Facet>> = BTreeMap::new();
    for shared in by_key.values() {
        if let [(a, fa), (b, fb)] = shared.as_slice() {
            let (pa, pb) = (part[*a], part[*b]);
            if pa != pb {
                for (p, q, f) in [(pa, pb, fa), (pb, pa, fb)] {
                    groups.entry((p, q)).or_default().push(Facet {
                        kind: f.kind,
                        nodes: f.nodes.iter().map(|&u| local[p][u]).collect(),
                    });
                }
            }
        }
    }
    let mut pairs = Vec::new();
    for ((p, q), facets) in groups {
        meshes[p].add_facets_to_group(&cut_group(q), facets);
        if p < q {
            pairs.push((p, q));
        }
    }
    pairs
}
