//! Building the quantities of interest of a study file: each `[[quantity]]` table's kind,
//! with the interface, substructure, component, nodes or region it names checked.

use toml::Spanned;

use super::contact::{ContactField, ContactQoi, StatusSel};
use super::fretting::{FrettingField, FrettingQoi};
use super::stress::{NodeSet, Region};
use super::{
    KINDS, Qoi, QoiKind, check_fields, check_quantities, coords, describe, dist2, point3, positive,
};
use crate::spec::QuantitySpec;
use crate::{BuiltModel, Source, StudyError};
use alea_latin::fretting::Regularisation;

/// Builds the quantities of interest of a study file, checking every name.
pub fn build_qois(
    src: &Source,
    specs: &[QuantitySpec],
    model: &BuiltModel,
) -> Result<Vec<Qoi>, StudyError> {
    let subs: Vec<&str> = model
        .assembly
        .subs
        .iter()
        .map(|s| s.name.as_str())
        .collect();
    let ifaces: Vec<&str> = model
        .assembly
        .interfaces
        .iter()
        .map(|i| i.name.as_str())
        .collect();
    let mut out = Vec::new();
    for (i, q) in specs.iter().enumerate() {
        check_fields(src, q, i)?;
        let input = QuantityInput {
            src,
            i,
            q,
            model,
            subs: &subs,
            ifaces: &ifaces,
        };
        let kind = quantity_kind(&input)?;
        if q.thresholds.iter().any(|t| !t.is_finite()) {
            return Err(src.error(
                q.name.span(),
                input.f("thresholds"),
                "thresholds must be finite",
            ));
        }
        let what = describe(&kind, model, q.group.as_ref().map(|g| g.get_ref().as_str()));
        out.push(Qoi {
            name: q.name.get_ref().clone(),
            unit: q.unit.clone().unwrap_or_default(),
            kind,
            thresholds: q.thresholds.clone(),
            what,
            step: None,
        });
    }
    check_quantities(src, specs, model, &out)?;
    Ok(out)
}

/// One `[[quantity]]` table (index `i`) and the model whose names it uses.
struct QuantityInput<'a> {
    src: &'a Source,
    i: usize,
    q: &'a QuantitySpec,
    model: &'a BuiltModel,
    /// The substructures' names.
    subs: &'a [&'a str],
    /// The interfaces' names.
    ifaces: &'a [&'a str],
}

impl QuantityInput<'_> {
    /// The field `k` of this quantity, for errors.
    fn f(&self, k: &str) -> String {
        format!("quantity[{}].{k}", self.i)
    }

    /// The index of the quantity's `interface`, which must be given and exist.
    fn interface(&self) -> Result<usize, StudyError> {
        let (src, q) = (self.src, self.q);
        let s = q.interface.as_ref().ok_or_else(|| {
            src.error(
                q.kind.span(),
                self.f("interface"),
                "missing; this quantity needs an interface name",
            )
        })?;
        self.ifaces
            .iter()
            .position(|n| n == s.get_ref())
            .ok_or_else(|| {
                src.error(
                    s.span(),
                    self.f("interface"),
                    format!(
                        "unknown interface '{}'; defined: {}",
                        s.get_ref(),
                        self.ifaces.join(", ")
                    ),
                )
            })
    }

    /// The index of the quantity's `substructure`, which must be given and exist.
    fn substructure(&self) -> Result<usize, StudyError> {
        let (src, q) = (self.src, self.q);
        let s = q.substructure.as_ref().ok_or_else(|| {
            src.error(
                q.kind.span(),
                self.f("substructure"),
                "missing; this quantity needs a substructure name",
            )
        })?;
        self.subs
            .iter()
            .position(|n| n == s.get_ref())
            .ok_or_else(|| {
                src.error(
                    s.span(),
                    self.f("substructure"),
                    format!(
                        "unknown substructure '{}'; defined: {}",
                        s.get_ref(),
                        self.subs.join(", ")
                    ),
                )
            })
    }

    /// The quantity's `component`, which must be given and below `dim`.
    fn component(&self, dim: usize) -> Result<usize, StudyError> {
        let (src, q) = (self.src, self.q);
        let c = q.component.as_ref().ok_or_else(|| {
            src.error(
                q.kind.span(),
                self.f("component"),
                "missing; expected 0, 1 or 2",
            )
        })?;
        if *c.get_ref() >= dim {
            return Err(src.error(c.span(), self.f("component"), format!("must be < {dim}")));
        }
        Ok(*c.get_ref())
    }

    /// A contact quantity of `field` on the quantity's interface: at the side-1 node nearest
    /// its `point`, or integrated over the interface.
    fn contact(&self, field: ContactField) -> Result<QoiKind, StudyError> {
        let (src, q, model) = (self.src, self.q, self.model);
        let dim = model.mesh.dim;
        let k = self.interface()?;
        let spec = &model.assembly.interfaces[k];
        let node = match &q.point {
            Some(p) => {
                let x = point3(src, p, dim, self.f("point"))?;
                let mesh = &model.assembly.subs[spec.sub1].model.mesh;
                let nodes = mesh
                    .group_nodes(&spec.group1)
                    .map_err(|e| src.error(q.kind.span(), self.f("interface"), e.to_string()))?;
                nodes
                    .iter()
                    .copied()
                    .min_by(|&a, &b| {
                        dist2(&mesh.coords[a], &x).total_cmp(&dist2(&mesh.coords[b], &x))
                    })
                    .map(Some)
                    .ok_or_else(|| {
                        src.error(p.span(), self.f("point"), "the interface has no point")
                    })?
            }
            None => None,
        };
        Ok(QoiKind::Contact(ContactQoi {
            iface: k,
            field,
            node,
        }))
    }
}

/// What the quantity measures, by its `kind`, with every name it uses checked.
fn quantity_kind(input: &QuantityInput) -> Result<QoiKind, StudyError> {
    let (src, q) = (input.src, input.q);
    let dim = input.model.mesh.dim;
    Ok(match q.kind.get_ref().as_str() {
        "interface_work" => QoiKind::InterfaceWork(input.interface()?),
        "friction_dissipation" => QoiKind::FrictionDissipation(input.interface()?),
        "interface_force" => QoiKind::InterfaceForce(input.interface()?, input.component(dim)?),
        "max_von_mises" => max_von_mises(input)?,
        "mean_von_mises" => mean_von_mises(input)?,
        "displacement" => {
            let s = input.substructure()?;
            let p = q.point.as_ref().ok_or_else(|| {
                src.error(
                    q.kind.span(),
                    input.f("point"),
                    "missing; expected coordinates",
                )
            })?;
            QoiKind::Displacement(
                s,
                point3(src, p, dim, input.f("point"))?,
                input.component(dim)?,
            )
        }
        "contact_pressure" => input.contact(ContactField::Pressure)?,
        "contact_slip" => input.contact(ContactField::Slip)?,
        "contact_status" => {
            let sel = match &q.status {
                Some(st) => StatusSel::parse(st.get_ref()).ok_or_else(|| {
                    src.error(
                        st.span(),
                        input.f("status"),
                        format!(
                            "unknown status '{}'; expected open, stick, slip or closed",
                            st.get_ref()
                        ),
                    )
                })?,
                None => StatusSel::Closed,
            };
            input.contact(ContactField::Status(sel))?
        }
        other => match FrettingField::parse(other) {
            Some(field) => fretting_kind(input, field)?,
            None => {
                return Err(src.error(
                    q.kind.span(),
                    input.f("kind"),
                    format!("unknown quantity '{other}'; expected {KINDS}"),
                ));
            }
        },
    })
}

/// A fretting quantity (module `qoi::fretting`): a frictional interface; `point` (not for
/// `stick_zone`); for `ruiz_f2` and `swt` the side (`substructure`, one of the interface's) and
/// the critical distance (required for `swt`), positive, in 2D, and smaller than the extent of
/// the interface (the largest contact zone it can have).
fn fretting_kind(input: &QuantityInput, field: FrettingField) -> Result<QoiKind, StudyError> {
    let (src, q, model) = (input.src, input.q, input.model);
    let f = |k: &str| input.f(k);
    let kind = q.kind.get_ref();
    let k = input.interface()?;
    let spec = &model.assembly.interfaces[k];
    let iface_span = q.interface.as_ref().map_or(q.kind.span(), |s| s.span());
    if spec.law.name() == "perfect" {
        return Err(src.error(
            iface_span,
            f("interface"),
            format!(
                "interface '{}' is perfect (bonded): it has no slip, friction or stick zone, so no '{kind}'",
                spec.name
            ),
        ));
    }
    let node = match (&q.point, field) {
        (Some(p), FrettingField::StickZone) => {
            return Err(src.error(
                p.span(),
                f("point"),
                "a stick zone is a measure over the interface: leave out point",
            ));
        }
        (Some(_), _) => match input.contact(ContactField::Pressure)? {
            QoiKind::Contact(c) => c.node,
            _ => None,
        },
        (None, _) => None,
    };
    let side = match &q.substructure {
        None => 0,
        Some(s) if !field.uses_stress() => {
            return Err(src.error(
                s.span(),
                f("substructure"),
                format!("not used by a '{kind}' quantity"),
            ));
        }
        Some(s) => {
            let idx = input.substructure()?;
            if idx == spec.sub1 {
                0
            } else if idx == spec.sub2 {
                1
            } else {
                return Err(src.error(
                    s.span(),
                    f("substructure"),
                    format!(
                        "'{}' is not a side of interface '{}'",
                        s.get_ref(),
                        spec.name
                    ),
                ));
            }
        }
    };
    let regularisation = critical_distance(input, field, spec)?;
    let fatemi_socie = match field {
        FrettingField::FatemiSocie => Some(fatemi_socie_constants(input)?),
        _ => None,
    };
    Ok(QoiKind::Fretting(FrettingQoi {
        iface: k,
        field,
        node,
        side,
        regularisation,
        fatemi_socie,
    }))
}

/// Fatemi-Socie's `normal_stress_factor` `k` (finite, >= 0) and `yield_stress` (> 0), both
/// required: material constants have no default.
fn fatemi_socie_constants(input: &QuantityInput) -> Result<(f64, f64), StudyError> {
    let (src, q) = (input.src, input.q);
    let f = |k: &str| input.f(k);
    let missing = |key: &str, what: &str| {
        src.error(
            q.kind.span(),
            f(key),
            format!("missing; a fatemi_socie quantity needs the material's {what}"),
        )
    };
    let k = q.normal_stress_factor.as_ref().ok_or_else(|| {
        missing(
            "normal_stress_factor",
            "normal-stress sensitivity k (dimensionless, typically 0.3 - 1)",
        )
    })?;
    let kv = *k.get_ref();
    if !(kv.is_finite() && kv >= 0.0) {
        return Err(src.error(
            k.span(),
            f("normal_stress_factor"),
            format!("must be finite and >= 0, got {kv}"),
        ));
    }
    let sy = q
        .yield_stress
        .as_ref()
        .ok_or_else(|| missing("yield_stress", "yield stress (stress units, > 0)"))?;
    Ok((kv, positive(src, sy, f("yield_stress"))?))
}

/// The `critical_distance` and `critical_method` of a fretting quantity.
fn critical_distance(
    input: &QuantityInput,
    field: FrettingField,
    spec: &alea_latin::InterfaceSpec,
) -> Result<Regularisation, StudyError> {
    let (src, q, model) = (input.src, input.q, input.model);
    let f = |k: &str| input.f(k);
    let Some(d) = &q.critical_distance else {
        if let Some(m) = &q.critical_method {
            return Err(src.error(
                m.span(),
                f("critical_distance"),
                "missing; critical_method needs a critical_distance",
            ));
        }
        if matches!(field, FrettingField::Swt | FrettingField::FatemiSocie) {
            return Err(src.error(
                q.kind.span(),
                f("critical_distance"),
                format!(
                    "missing; {} at a contact edge depends on the mesh without a critical distance (a material length, e.g. half El Haddad's length for the point method)",
                    field.label()
                ),
            ));
        }
        return Ok(Regularisation::Surface);
    };
    let l = positive(src, d, f("critical_distance"))?;
    if model.mesh.dim != 2 {
        return Err(src.error(
            d.span(),
            f("critical_distance"),
            "a critical distance is implemented in 2D only",
        ));
    }
    let mesh = &model.assembly.subs[spec.sub1].model.mesh;
    let nodes = mesh
        .group_nodes(&spec.group1)
        .map_err(|e| src.error(d.span(), f("interface"), e.to_string()))?;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for &n in &nodes {
        for c in 0..3 {
            lo[c] = lo[c].min(mesh.coords[n][c]);
            hi[c] = hi[c].max(mesh.coords[n][c]);
        }
    }
    let extent = (0..3)
        .map(|c| (hi[c] - lo[c]).max(0.0).powi(2))
        .sum::<f64>()
        .sqrt();
    if l >= extent {
        return Err(src.error(
            d.span(),
            f("critical_distance"),
            format!(
                "{l} is not smaller than the contact zone: interface '{}' spans {extent:.6e}",
                spec.name
            ),
        ));
    }
    Ok(
        match q
            .critical_method
            .as_ref()
            .map(|m| (m, m.get_ref().as_str()))
        {
            None | Some((_, "point")) => Regularisation::Point(l),
            Some((_, "line")) => Regularisation::Line(l),
            Some((m, other)) => {
                return Err(src.error(
                    m.span(),
                    f("critical_method"),
                    format!("unknown method '{other}'; expected point or line"),
                ));
            }
        },
    )
}

/// `max_von_mises`: the nodes of the substructure's `group` (all by default) but the
/// excluded ones, at least one left.
fn max_von_mises(input: &QuantityInput) -> Result<QoiKind, StudyError> {
    let (src, q) = (input.src, input.q);
    let f = |k: &str| input.f(k);
    let s = input.substructure()?;
    let mesh = &input.model.assembly.subs[s].model.mesh;
    let group_nodes = |g: &Spanned<String>, key: &str| {
        mesh.group_nodes(g.get_ref()).map_err(|e| {
            src.error(
                g.span(),
                f(key),
                format!("substructure '{}': {e}", input.subs[s]),
            )
        })
    };
    let mut nodes = match &q.group {
        Some(g) => group_nodes(g, "group")?,
        None => (0..mesh.num_nodes()).collect(),
    };
    let mut excluded = std::collections::BTreeSet::new();
    for g in &q.exclude_groups {
        excluded.extend(group_nodes(g, "exclude_groups")?);
    }
    if let Some(ns) = &q.exclude_nodes {
        if let Some(bad) = ns.get_ref().iter().find(|&&n| n >= mesh.num_nodes()) {
            return Err(src.error(
                ns.span(),
                f("exclude_nodes"),
                format!(
                    "node {bad} is not in substructure '{}' ({} nodes, numbered from 0)",
                    input.subs[s],
                    mesh.num_nodes()
                ),
            ));
        }
        excluded.extend(ns.get_ref().iter().copied());
    }
    excluded.extend(nodes_near_points(input, mesh, &nodes)?);
    nodes.retain(|n| !excluded.contains(n));
    if nodes.is_empty() {
        return Err(src.error(
            q.kind.span(),
            f("group"),
            "no node left once the exclusions are removed",
        ));
    }
    Ok(QoiKind::MaxVonMises {
        sub: s,
        set: NodeSet::new(mesh, nodes),
    })
}

/// The `nodes` within `exclude_radius` of one of the `exclude_points` (both or neither given).
fn nodes_near_points(
    input: &QuantityInput,
    mesh: &alea_mesh::Mesh,
    nodes: &[usize],
) -> Result<Vec<usize>, StudyError> {
    let (src, q) = (input.src, input.q);
    let f = |k: &str| input.f(k);
    let dim = input.model.mesh.dim;
    let mut near = Vec::new();
    match (&q.exclude_points, &q.exclude_radius) {
        (Some(ps), Some(r)) => {
            let r = positive(src, r, f("exclude_radius"))?;
            for p in ps.get_ref() {
                let x = coords(src, ps.span(), p, dim, f("exclude_points"))?;
                near.extend(
                    nodes
                        .iter()
                        .copied()
                        .filter(|&n| dist2(&mesh.coords[n], &x) <= r * r),
                );
            }
        }
        (Some(ps), None) => {
            return Err(src.error(
                ps.span(),
                f("exclude_radius"),
                "missing; exclude_points needs a radius",
            ));
        }
        (None, Some(r)) => {
            return Err(src.error(
                r.span(),
                f("exclude_points"),
                "missing; exclude_radius needs points",
            ));
        }
        (None, None) => {}
    }
    Ok(near)
}

/// `mean_von_mises`: the region of the substructure's cell `group` (all by default) and/or
/// the ball of `point` and `radius`, holding at least one quadrature point.
fn mean_von_mises(input: &QuantityInput) -> Result<QoiKind, StudyError> {
    let (src, q) = (input.src, input.q);
    let f = |k: &str| input.f(k);
    let dim = input.model.mesh.dim;
    let s = input.substructure()?;
    let m = &input.model.assembly.subs[s].model;
    let cells: Vec<usize> = match &q.group {
        Some(g) => m
            .mesh
            .cell_group(g.get_ref())
            .map_err(|e| {
                src.error(
                    g.span(),
                    f("group"),
                    format!(
                        "substructure '{}': {e} (a mean_von_mises region is a cell group and/or a ball given by point and radius)",
                        input.subs[s]
                    ),
                )
            })?
            .to_vec(),
        None => (0..m.mesh.num_cells()).collect(),
    };
    let ball = match (&q.point, &q.radius) {
        (Some(p), Some(r)) => Some((
            point3(src, p, dim, f("point"))?,
            positive(src, r, f("radius"))?,
        )),
        (Some(p), None) => {
            return Err(src.error(
                p.span(),
                f("radius"),
                "missing; the region around point needs a radius",
            ));
        }
        (None, Some(r)) => {
            return Err(src.error(r.span(), f("point"), "missing; radius needs a centre point"));
        }
        (None, None) => None,
    };
    let region = Region::new(m, &cells, ball);
    if region.is_empty() {
        return Err(src.error(
            q.radius.as_ref().map_or(q.kind.span(), |r| r.span()),
            f("radius"),
            format!(
                "no quadrature point of substructure '{}' lies in the region; enlarge the radius or move the point",
                input.subs[s]
            ),
        ));
    }
    Ok(QoiKind::MeanVonMises { sub: s, region })
}
