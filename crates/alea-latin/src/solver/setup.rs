//! Set-up of the solver (everything done once per assembly, thesis 5.1.3): validation of the
//! options, pairing of every interface (node to node, or dual mortar: module
//! [`crate::mortar`]; or a pairing given by the caller, found in a deformed configuration by
//! [`crate::large_sliding`]), the search direction `k0 = factor E_side / L_interface`, the assembly and
//! factorisation of every substructure operator `A0 = T^T (K0 + sum Pi^T M_Gamma k Pi) T`, the
//! rigid modes left free by the constraints (module `equilibrium`) and the macro space of the
//! coarse problem (module `coarse`).

use std::sync::Arc;
use std::time::Instant;

use alea_fem::{Cholesky, DofMap, Ordering, SymCsc, assemble_stiffness};
use rayon::prelude::*;

use super::direction::PointDirection;
use super::precision::PrecisionChoice;
use super::ranks::Ranks;
use super::{
    Coarse, FactorInfo, InterfaceOperator, LatinOptions, LatinSolver, Link, SearchDirection,
    SubOperator,
};
use crate::coarse::{InterfaceModes, MacroLink, SubMacro};
use crate::equilibrium::RigidModes;
use crate::interface::{InterfacePairing, side_geometry};
use crate::sides::pair_sides;
use crate::{Assembly, InterfaceSpec, LatinError, PointData, Substructure};

pub(super) fn fem_err(sub: &str) -> impl Fn(alea_fem::FemError) -> LatinError + '_ {
    move |source| LatinError::Fem {
        sub: sub.to_string(),
        source,
    }
}

fn mesh_err(sub: &str) -> impl Fn(alea_mesh::MeshError) -> LatinError + '_ {
    move |source| LatinError::Mesh {
        sub: sub.to_string(),
        source,
    }
}

impl LatinSolver {
    /// Sets up the assembly: pairs interfaces, assembles and factorises every substructure
    /// operator `A0 = K0 + sum k0 M_Gamma` once.
    pub fn new(assembly: Assembly, options: LatinOptions) -> Result<Self, LatinError> {
        Self::with_pairings(assembly, options, Vec::new(), None)
    }

    /// [`LatinSolver::new`] with the pairing of some interfaces given (`pairings[i]`:
    /// `Some` for interface `i`, found by the caller; missing or `None`: paired here as
    /// `spec.pairing` asks), found in the configuration `X + configuration[s]` (node-major
    /// displacement of every substructure; `None`: the initial configuration). Used by
    /// [`crate::large_sliding`] to re-pair sliding interfaces in the deformed configuration.
    pub fn with_pairings(
        assembly: Assembly,
        options: LatinOptions,
        pairings: Vec<Option<InterfacePairing>>,
        configuration: Option<Vec<Vec<f64>>>,
    ) -> Result<Self, LatinError> {
        Self::set_up(assembly, options, pairings, configuration, None)
    }

    /// [`LatinSolver::with_pairings`] on the ranks of `ranks` (`None`: one process): only the
    /// owned substructures are assembled and factorised (module `ranks`).
    pub(super) fn set_up(
        assembly: Assembly,
        options: LatinOptions,
        mut pairings: Vec<Option<InterfacePairing>>,
        configuration: Option<Vec<Vec<f64>>>,
        mut ranks: Option<Ranks>,
    ) -> Result<Self, LatinError> {
        let t0 = Instant::now();
        check_options(&options)?;
        // Automatic subdomains (module `split`): not for a re-pairing (large sliding).
        if configuration.is_none()
            && pairings.iter().all(Option::is_none)
            && let Some(parts) = super::split::plan(&assembly, &options)
        {
            // Over ranks, the subdomains are spread (module `ranks`).
            let exchange = ranks.map(|r| r.exchange());
            return super::split::build(&assembly, options, &parts, exchange);
        }
        let Assembly { subs, interfaces } = assembly;
        let nsub = subs.len();
        let model_size = bounding_diagonal(subs.iter().flat_map(|s| s.model.mesh.coords.iter()));
        let mut links: Vec<Vec<Link>> = vec![Vec::new(); nsub];
        let mut ifaces = Vec::new();
        for (i, spec) in interfaces.iter().enumerate() {
            let given = pairings.get_mut(i).and_then(Option::take);
            ifaces.push(interface_operator(
                i,
                spec,
                given,
                &subs,
                interfaces.len(),
                &options.search_direction,
                &mut links,
            )?);
        }
        let ordering = options.ordering;
        let precision = PrecisionChoice::new(&options, configuration.is_some());
        let owned: Vec<bool> = (0..nsub)
            .map(|s| ranks.as_ref().is_none_or(|r| r.owns(s)))
            .collect();
        let ops: Result<Vec<Arc<SubOperator>>, LatinError> = subs
            .into_par_iter()
            .zip(links.into_par_iter())
            .zip(owned.into_par_iter())
            .map(|((sub, links), own)| {
                build_operator(sub, links, ordering, precision, own).map(Arc::new)
            })
            .collect();
        let ops = Self::agree(ranks.as_ref(), ops)?;
        let factors: Vec<_> = ops
            .iter()
            .map(|o| o.chol.as_ref().map(factor_info))
            .collect();
        let factors = match &mut ranks {
            Some(r) => {
                r.factors = super::ranks::share_factors(r, &factors);
                r.factors.clone()
            }
            None => factors.into_iter().flatten().collect(),
        };
        let coarse = options
            .coarse
            .then(|| coarse_with(&ops, &ifaces, None, ranks.as_ref()));
        let nnz: Vec<usize> = factors.iter().map(|f| f.entries).collect();
        let want = super::condensed::choose(
            &ops,
            &nnz,
            options.linear_stage,
            options.expected_runs,
            configuration.is_some(),
        )?;
        let condensed = super::condensed::build_all(&ops, coarse.as_ref(), &want);
        let condensed = Self::agree(ranks.as_ref(), condensed)?;
        if let Some(r) = &mut ranks {
            let bytes: Vec<Option<f64>> = condensed
                .iter()
                .map(|c| c.as_ref().map(|c| c.bytes()))
                .collect();
            r.condensed = super::ranks::share_condensed(r, &want, &bytes);
        }
        Ok(LatinSolver {
            subs: ops,
            ifaces,
            options,
            model_size,
            coarse,
            configuration,
            condensed,
            ranks: ranks.map(Arc::new),
            setup_seconds: t0.elapsed().as_secs_f64(),
            split: None,
        })
    }
}

/// Relaxation in (0, 1], equilibrium bounds and tolerance > 0.
fn check_options(options: &LatinOptions) -> Result<(), LatinError> {
    if !(options.relaxation > 0.0 && options.relaxation <= 1.0) {
        return Err(LatinError::Invalid(format!(
            "relaxation must be in (0, 1], got {}",
            options.relaxation
        )));
    }
    if !(options.equilibrium_tolerance > 0.0 && options.max_rigid_motion > 0.0) {
        return Err(LatinError::Invalid(format!(
            "equilibrium tolerance and rigid-motion bound must be > 0, got {} and {}",
            options.equilibrium_tolerance, options.max_rigid_motion
        )));
    }
    if !(options.tolerance > 0.0) {
        return Err(LatinError::Invalid(format!(
            "tolerance must be > 0, got {}",
            options.tolerance
        )));
    }
    Ok(())
}

/// Interface `i`: checks its substructures, pairs its sides (node to node or mortar, as
/// `spec.pairing` asks), derives the search direction of both sides and the point data at the
/// set-up's `mu` and gap fields, and adds one [`Link`] to each side's substructure.
fn interface_operator(
    i: usize,
    spec: &InterfaceSpec,
    given: Option<InterfacePairing>,
    subs: &[Substructure],
    num_interfaces: usize,
    search_direction: &SearchDirection,
    links: &mut [Vec<Link>],
) -> Result<InterfaceOperator, LatinError> {
    let nsub = subs.len();
    for (s, sub) in [spec.sub1, spec.sub2].into_iter().enumerate() {
        if sub >= nsub {
            return Err(LatinError::Invalid(format!(
                "interface '{}': side {} refers to substructure {sub}, but there are {nsub}",
                spec.name,
                s + 1
            )));
        }
    }
    crate::cyclic::check_spec(spec, subs)?;
    if spec.sub1 == spec.sub2 && spec.cyclic.is_none() {
        return Err(LatinError::Invalid(format!(
            "interface '{}' joins substructure '{}' to itself",
            spec.name, subs[spec.sub1].name
        )));
    }
    let s1 = &subs[spec.sub1];
    let s2 = &subs[spec.sub2];
    s1.model
        .mesh
        .facet_group(&spec.group1)
        .map_err(mesh_err(&s1.name))?;
    s2.model
        .mesh
        .facet_group(&spec.group2)
        .map_err(mesh_err(&s2.name))?;
    let pairing = pair_sides(spec, [s1, s2], given)?;
    let tangential = match search_direction {
        SearchDirection::Split { tangential, .. } => *tangential,
        SearchDirection::Auto { .. } | SearchDirection::Fixed(_) => 1.0,
    };
    if !(tangential > 0.0 && tangential.is_finite()) {
        return Err(LatinError::Invalid(format!(
            "tangential search direction ratio must be > 0, got {tangential}"
        )));
    }
    let k0 = match search_direction {
        SearchDirection::Auto { factor } | SearchDirection::Split { factor, .. } => {
            let scale = match spec.direction_scale {
                Some(scale) => scale,
                None => direction_scale(spec, subs)?,
            };
            let [e1, e2] = scale.young;
            [factor * e1 / scale.length, factor * e2 / scale.length]
        }
        SearchDirection::Fixed(k) => *k.get(i).ok_or_else(|| {
            LatinError::Invalid(format!(
                "fixed search direction given for {} interfaces, but there are {}",
                k.len(),
                num_interfaces
            ))
        })?,
    };
    if !(k0[0] > 0.0 && k0[1] > 0.0) {
        return Err(LatinError::Invalid(format!(
            "interface '{}': search direction must be > 0, got {k0:?}",
            spec.name
        )));
    }
    let points: Vec<PointData> = pairing
        .x
        .iter()
        .zip(&pairing.normals)
        .zip(&pairing.geometric_gap)
        .map(|((&x, &normal), &g)| PointData {
            x,
            normal,
            mu: (spec.mu)(x),
            gap: (spec.gap)(x) + g,
        })
        .collect();
    let dirs = directions(&pairing, &spec.law, k0, tangential);
    let l1 = links[spec.sub1].len();
    let [side1, side2] = pairing.sides.clone();
    links[spec.sub1].push(Link {
        iface: i,
        side: 0,
        proj: Arc::new(side1),
        dir: Arc::new(dirs[0].clone()),
    });
    let l2 = links[spec.sub2].len();
    links[spec.sub2].push(Link {
        iface: i,
        side: 1,
        proj: Arc::new(side2),
        dir: Arc::new(dirs[1].clone()),
    });
    Ok(InterfaceOperator {
        name: spec.name.clone(),
        law: spec.law.clone(),
        sub: [spec.sub1, spec.sub2],
        link: [l1, l2],
        points,
        weights: pairing.weights.clone(),
        mu: spec.mu.clone(),
        gap: spec.gap.clone(),
        pairing: Arc::new(pairing),
    })
}

/// The search direction of both sides at every point of an interface (module `direction`)
/// from the sides' `k0`: isotropic, or split along the normal with `k_t = tangential k_n` on
/// a contact interface (a law that uses the gap).
fn directions(
    pairing: &InterfacePairing,
    law: &Arc<dyn crate::InterfaceLaw>,
    k0: [f64; 2],
    tangential: f64,
) -> [Vec<PointDirection>; 2] {
    let tnr = if law.uses_gap() { tangential } else { 1.0 };
    [0, 1].map(|s| {
        pairing
            .normals
            .iter()
            .map(|&n| {
                let k = k0[s];
                if tnr == 1.0 {
                    PointDirection::isotropic(n, k)
                } else {
                    PointDirection {
                        normal: n,
                        kn: k,
                        kt: tnr * k,
                    }
                }
            })
            .collect()
    })
}

/// The macro space of the coarse problem (interface resultants and moments, module `coarse`)
/// and every substructure's responses to it, keeping the responses of `previous` where
/// `changed` is false (the same macro space: same interfaces); with `ranks`, each
/// substructure's responses computed by its owner and its interface values shared.
pub(super) fn coarse_with(
    ops: &[Arc<SubOperator>],
    ifaces: &[InterfaceOperator],
    previous: Option<(&Coarse, &[bool])>,
    ranks: Option<&Ranks>,
) -> Coarse {
    let dim = ops.first().map_or(2, |o| o.model.mesh.dim);
    let mut offset = 0;
    let modes: Vec<InterfaceModes> = ifaces
        .iter()
        .map(|op| {
            let m = InterfaceModes::new(dim, &op.pairing.x, &op.pairing.weights, offset);
            offset += m.len();
            m
        })
        .collect();
    let rotated: Vec<Option<InterfaceModes>> = ifaces
        .iter()
        .zip(&modes)
        .map(|(op, m)| op.pairing.rotation.map(|r| m.rotated(&r)))
        .collect();
    let side_modes = |l: &Link| match (&rotated[l.iface], l.side) {
        (Some(m), 1) => m,
        _ => &modes[l.iface],
    };
    let fresh = |s: usize| previous.is_none_or(|(_, changed)| changed[s]);
    let mut subs: Vec<SubMacro> = ops
        .par_iter()
        .enumerate()
        .map(|(s, op)| {
            if let Some((prev, _)) = previous
                && !fresh(s)
            {
                return prev.subs[s].clone();
            }
            let Some(chol) = &op.chol else {
                // Another rank's: shared below.
                return SubMacro {
                    columns: Vec::new(),
                    l0: Vec::new(),
                };
            };
            let links: Vec<MacroLink<'_>> = op
                .links
                .iter()
                .map(|l| MacroLink {
                    proj: &l.proj,
                    dir: &l.dir,
                    modes: side_modes(l),
                })
                .collect();
            SubMacro::new(&op.dofs, chol, &links, &op.rigid, &op.model.mesh.coords)
        })
        .collect();
    if let Some(r) = ranks {
        let want: Vec<bool> = (0..ops.len()).map(fresh).collect();
        super::ranks::share_macros(r, &mut subs, &want);
    }
    Coarse {
        n: offset,
        modes,
        rotated,
        subs,
    }
}

/// Mean Young's modulus of the cells along a facet group.
/// The characteristic length and side moduli of interface `spec`'s default search direction:
/// the length of side 1 (2D; the square root of its area in 3D) and the mean modulus of the
/// cells along each side.
///
/// # Errors
/// A group that is not a facet group of its substructure.
pub(crate) fn direction_scale(
    spec: &InterfaceSpec,
    subs: &[Substructure],
) -> Result<crate::DirectionScale, LatinError> {
    let (s1, s2) = (&subs[spec.sub1], &subs[spec.sub2]);
    let g1 = side_geometry(&s1.model.mesh, &spec.group1, s1.model.analysis.thickness())
        .map_err(mesh_err(&s1.name))?;
    let total: f64 = g1.weights.iter().sum();
    let length = if s1.model.mesh.dim == 2 {
        total / s1.model.analysis.thickness()
    } else {
        total.sqrt()
    };
    let e1 = side_young(&s1.model, &spec.group1).map_err(fem_err(&s1.name))?;
    let e2 = side_young(&s2.model, &spec.group2).map_err(fem_err(&s2.name))?;
    Ok(crate::DirectionScale {
        length,
        young: [e1, e2],
    })
}

fn side_young(model: &alea_fem::Model, group: &str) -> Result<f64, alea_fem::FemError> {
    let facets = model
        .mesh
        .attach_facets(model.mesh.facet_group(group)?, None)?;
    let mut sum = 0.0;
    for f in &facets {
        sum += model.material(f.cell)?.young;
    }
    Ok(sum / facets.len().max(1) as f64)
}

/// Order, factor entries, storage and precision of a factorisation.
pub(super) fn factor_info(c: &Cholesky) -> FactorInfo {
    FactorInfo {
        n: c.n(),
        entries: c.nnz_factor(),
        supernodal: c.is_supernodal(),
        single: c.is_single(),
        bytes: c.factor_bytes(),
    }
}

/// The operator of one substructure; `own`: this rank computes it (module `ranks`), else
/// no operator, factor nor right-hand sides are made.
fn build_operator(
    sub: Substructure,
    links: Vec<Link>,
    ordering: Ordering,
    precision: PrecisionChoice,
    own: bool,
) -> Result<SubOperator, LatinError> {
    let name = sub.name.clone();
    let model = sub.model;
    let dofs = DofMap::for_mesh(&model.mesh, &sub.constraints).map_err(fem_err(&name))?;
    let (chol, r_presc) = if own {
        let (a0, r_presc) = operator_matrix(&name, &model, &dofs, &links)?;
        let mut chol =
            Cholesky::new(&a0, ordering, Some(&dofs.node_of_dof())).map_err(fem_err(&name))?;
        chol.factorize(&a0).map_err(fem_err(&name))?;
        let interface_unknowns = super::condensed::interface_unknowns(model.mesh.dim, &links);
        precision.apply(&mut chol, &a0, interface_unknowns);
        (Some(chol), r_presc)
    } else {
        (None, Vec::new())
    };
    let dim = model.mesh.dim;
    let n_nodes = model.mesh.num_nodes() * model.mesh.dim;
    if let Some(f) = sub.load_cases.iter().find(|f| f.len() != n_nodes) {
        return Err(LatinError::Invalid(format!(
            "substructure '{name}': load case of length {} for {n_nodes} dofs",
            f.len()
        )));
    }
    let rigid = RigidModes::new(
        dim,
        &model.mesh.coords,
        |n, v| dofs.constrained_part(n, v),
        &sub.load_cases,
        (0..model.mesh.num_nodes()).any(|n| dofs.prescribed(n).iter().any(|&v| v != 0.0)),
    );
    let r_ext: Vec<Vec<f64>> = sub
        .load_cases
        .iter()
        .map(|f| if own { dofs.reduce(f) } else { Vec::new() })
        .collect();
    Ok(SubOperator {
        name,
        model,
        dofs,
        chol,
        r_ext,
        r_presc,
        links,
        rigid,
    })
}

/// The operator `A0 = T^T (K + sum Pi^T M_Gamma k Pi) T` (`k` the search direction of each
/// interface point, module `direction`) of a substructure's `model` (its
/// materials as they are) under `dofs`, and the right-hand side `-T^T A u_p` of its prescribed
/// displacements.
pub(super) fn operator_matrix(
    name: &str,
    model: &alea_fem::Model,
    dofs: &DofMap,
    links: &[Link],
) -> Result<(SymCsc, Vec<f64>), LatinError> {
    let asm = assemble_stiffness(model, dofs).map_err(fem_err(name))?;
    let mut a0: SymCsc = with_interface_couplings(asm.k, dofs, links);
    let mut r_presc = asm.f_prescribed;
    // Scratch for T_a^T n (the normal seen by a node's free unknowns).
    let mut tn = vec![0.0; dofs.num_free()];
    for l in links {
        // Pi^T M k Pi: node blocks m_p c_pa c_pb (k_t I + (k_n - k_t) n n^T).
        for (p, &m) in l.proj.weights.iter().enumerate() {
            let d = &l.dir[p];
            let km = d.kt * m;
            for (a, ca) in l.proj.row(p) {
                for (b, cb) in l.proj.row(p) {
                    if a == b {
                        dofs.add_node_diagonal(a, km * ca * cb, &mut a0);
                    } else if a < b {
                        dofs.add_node_coupling(a, b, km * ca * cb, &mut a0);
                    }
                }
            }
            if !d.is_isotropic() {
                let kr = (d.kn - d.kt) * m;
                let tnode = |a: usize, tn: &mut [f64]| -> Vec<(usize, f64)> {
                    dofs.add_node_force(a, &d.normal, tn);
                    dofs.node_dofs(a)
                        .map(|g| (g, std::mem::take(&mut tn[g])))
                        .collect()
                };
                for (a, ca) in l.proj.row(p) {
                    let ta = tnode(a, &mut tn);
                    for (b, cb) in l.proj.row(p) {
                        if a > b {
                            continue;
                        }
                        let tb = tnode(b, &mut tn);
                        for &(ga, va) in &ta {
                            for &(gb, vb) in &tb {
                                if a < b || ga <= gb {
                                    a0.add(ga, gb, kr * ca * cb * va * vb);
                                }
                            }
                        }
                    }
                }
            }
            // -T^T (Pi^T M k Pi) u_p for prescribed interface nodes.
            let mut up = [0.0; 3];
            for (b, cb) in l.proj.row(p) {
                let u = dofs.prescribed(b);
                for c in 0..3 {
                    up[c] += cb * u[c];
                }
            }
            if up.iter().any(|&v| v != 0.0) {
                // Isotropic: -(k m c_a) u_p, as the scalar direction always made it.
                let (kup, scale) = if d.is_isotropic() {
                    (up, km)
                } else {
                    (d.apply(1.0, &up), m)
                };
                for (a, ca) in l.proj.row(p) {
                    let s = -(scale * ca);
                    let v = [s * kup[0], s * kup[1], s * kup[2]];
                    dofs.add_node_force(a, &v, &mut r_presc);
                }
            }
        }
    }
    Ok((a0, r_presc))
}

/// The stiffness matrix on a pattern that also couples the nodes of every interface point
/// (mortar rows join nodes of different cells); unchanged when they are already coupled (always
/// for node-to-node interfaces).
fn with_interface_couplings(k: SymCsc, dofs: &DofMap, links: &[Link]) -> SymCsc {
    let mut extra: Vec<(usize, usize)> = Vec::new();
    for l in links {
        for p in 0..l.proj.len() {
            for (a, _) in l.proj.row(p) {
                for (b, _) in l.proj.row(p) {
                    let (ra, rb) = (dofs.node_dofs(a), dofs.node_dofs(b));
                    if a < b
                        && !ra.is_empty()
                        && !rb.is_empty()
                        && k.position(ra.start, rb.start).is_none()
                    {
                        extra.push((a, b));
                    }
                }
            }
        }
    }
    if extra.is_empty() {
        return k;
    }
    let mut adj: std::collections::HashMap<usize, Vec<usize>> = Default::default();
    for &(a, b) in &extra {
        adj.entry(a).or_default().push(b);
        adj.entry(b).or_default().push(a);
    }
    let node_of = dofs.node_of_dof();
    let mut out = SymCsc::from_couplings(k.n, |j, buf| {
        buf.extend_from_slice(&k.row_idx[k.col_ptr[j]..k.col_ptr[j + 1]]);
        if let Some(list) = adj.get(&node_of[j]) {
            for &m in list {
                buf.extend(dofs.node_dofs(m));
            }
        }
    });
    for j in 0..k.n {
        for q in k.col_ptr[j]..k.col_ptr[j + 1] {
            out.add(k.row_idx[q], j, k.values[q]);
        }
    }
    out
}

/// Diagonal of the bounding box of a set of points (0 for none).
fn bounding_diagonal<'a>(points: impl Iterator<Item = &'a [f64; 3]>) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for x in points {
        for c in 0..3 {
            lo[c] = lo[c].min(x[c]);
            hi[c] = hi[c].max(x[c]);
        }
    }
    if lo[0] > hi[0] {
        return 0.0;
    }
    (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt()
}
