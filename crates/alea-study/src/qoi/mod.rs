//! Quantities of interest: what each run contributes to the statistics.
//!
//! - interface quantities: the work of the interface forces and the friction dissipation
//!   (thesis 2.3.2), a resultant force component, and the contact pressure, slip and status at
//!   a point or integrated over the interface ([`contact`]);
//! - stress quantities of a substructure ([`stress`]): the maximum nodal von Mises stress over
//!   a node set (with nodes, groups or the neighbourhood of points left out), and its
//!   regularised alternative, the average of the von Mises stress over a region;
//! - a displacement component at a node;
//! - fretting quantities over the last load cycle ([`fretting`]): slip amplitude, frictional
//!   work per cycle, Ruiz F1 / F2, SWT, stick zone.
//!
//! A maximum taken on a node where two boundary groups meet is usually a singular value:
//! [`warnings::corner_warnings`] reports it after a study.
//!
//! The quantities of a study file are built, every name checked, in `qoi/build.rs`.

mod build;
pub mod contact;
pub mod fretting;
pub mod stress;
pub mod warnings;

use alea_latin::{LatinSolver, RunResult};
use toml::Spanned;

use crate::spec::QuantitySpec;
use crate::{BuiltModel, Source, StudyError};
use contact::{ContactField, ContactQoi};
use fretting::FrettingQoi;
use stress::{NodeSet, Region};

pub use build::build_qois;

/// What a quantity of interest measures.
#[derive(Clone, Debug)]
pub enum QoiKind {
    /// `int ([W_hat] + g0 n) . F_hat_2 dS` on an interface (thesis 2.3.2; <= 0 for Coulomb).
    InterfaceWork(usize),
    /// `-int [W_hat]_t . F_t dS >= 0` on an interface.
    FrictionDissipation(usize),
    /// Component of the resultant force on side 2 of an interface.
    InterfaceForce(usize, usize),
    /// Maximum nodal von Mises stress over a node set of a substructure.
    MaxVonMises {
        /// Substructure.
        sub: usize,
        /// The nodes.
        set: NodeSet,
    },
    /// Average von Mises stress over a region of a substructure.
    MeanVonMises {
        /// Substructure.
        sub: usize,
        /// The region's quadrature points.
        region: Region,
    },
    /// Displacement component at the node nearest to a point.
    Displacement(usize, [f64; 3], usize),
    /// Contact pressure, slip or status on an interface.
    Contact(ContactQoi),
    /// A fretting quantity over the last load cycle (module `cycle`).
    Fretting(FrettingQoi),
}

/// A named quantity of interest.
#[derive(Clone, Debug)]
pub struct Qoi {
    /// Name.
    pub name: String,
    /// Unit (for the report).
    pub unit: String,
    /// What it measures.
    pub kind: QoiKind,
    /// Failure thresholds.
    pub thresholds: Vec<f64>,
    /// What it measures, in words, with the names of its interface or substructure and the
    /// labelled component (`resultant Fz on side 2 of interface 'I2'`), for the reports;
    /// with `[[step]]`s it ends with the step (`at the end of step 'slide'`).
    pub what: String,
    /// With `[[step]]`s: the index of the step it measures (module `steps`).
    pub step: Option<usize>,
}

const KINDS: &str = "interface_work, friction_dissipation, interface_force, max_von_mises, mean_von_mises, displacement, contact_pressure, contact_slip, contact_status, slip_amplitude, friction_work_cycle, ruiz_f1, ruiz_f2, swt, fatemi_socie or stick_zone";

fn point3(
    src: &Source,
    p: &Spanned<Vec<f64>>,
    dim: usize,
    field: String,
) -> Result<[f64; 3], StudyError> {
    coords(src, p.span(), p.get_ref(), dim, field)
}

fn coords(
    src: &Source,
    span: std::ops::Range<usize>,
    v: &[f64],
    dim: usize,
    field: String,
) -> Result<[f64; 3], StudyError> {
    if v.len() != dim || v.iter().any(|x| !x.is_finite()) {
        return Err(src.error(span, field, format!("expected {dim} finite coordinates")));
    }
    let mut x = [0.0; 3];
    x[..dim].copy_from_slice(v);
    Ok(x)
}

fn positive(src: &Source, v: &Spanned<f64>, field: String) -> Result<f64, StudyError> {
    let r = *v.get_ref();
    if !(r.is_finite() && r > 0.0) {
        return Err(src.error(v.span(), field, format!("must be > 0, got {r}")));
    }
    Ok(r)
}

fn dist2(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum()
}

/// Refuses the fields that `kind` does not use (a misplaced key is an input error, not a
/// silently ignored one).
fn check_fields(src: &Source, q: &QuantitySpec, i: usize) -> Result<(), StudyError> {
    let kind = q.kind.get_ref().as_str();
    let is_max = kind == "max_von_mises";
    let stress_fretting = matches!(kind, "ruiz_f2" | "swt" | "fatemi_socie");
    let uses: [(&str, bool, bool, std::ops::Range<usize>); 9] = [
        (
            "exclude_groups",
            !q.exclude_groups.is_empty(),
            is_max,
            q.exclude_groups.first().map_or(0..0, |g| g.span()),
        ),
        (
            "exclude_nodes",
            q.exclude_nodes.is_some(),
            is_max,
            q.exclude_nodes.as_ref().map_or(0..0, |g| g.span()),
        ),
        (
            "exclude_points",
            q.exclude_points.is_some() || q.exclude_radius.is_some(),
            is_max,
            q.exclude_points
                .as_ref()
                .map(|g| g.span())
                .or(q.exclude_radius.as_ref().map(|g| g.span()))
                .unwrap_or(0..0),
        ),
        (
            "radius",
            q.radius.is_some(),
            kind == "mean_von_mises",
            q.radius.as_ref().map_or(0..0, |g| g.span()),
        ),
        (
            "status",
            q.status.is_some(),
            kind == "contact_status",
            q.status.as_ref().map_or(0..0, |g| g.span()),
        ),
        (
            "critical_distance",
            q.critical_distance.is_some(),
            stress_fretting,
            q.critical_distance.as_ref().map_or(0..0, |g| g.span()),
        ),
        (
            "critical_method",
            q.critical_method.is_some(),
            stress_fretting,
            q.critical_method.as_ref().map_or(0..0, |g| g.span()),
        ),
        (
            "normal_stress_factor",
            q.normal_stress_factor.is_some(),
            kind == "fatemi_socie",
            q.normal_stress_factor.as_ref().map_or(0..0, |g| g.span()),
        ),
        (
            "yield_stress",
            q.yield_stress.is_some(),
            kind == "fatemi_socie",
            q.yield_stress.as_ref().map_or(0..0, |g| g.span()),
        ),
    ];
    for (name, given, allowed, span) in uses {
        if given && !allowed {
            return Err(src.error(
                span,
                format!("quantity[{i}].{name}"),
                format!("not used by a '{kind}' quantity"),
            ));
        }
    }
    Ok(())
}

/// A quantity in words: the kind, the interface or substructure by name, the component by axis
/// label (`Fx`, `Fy`, `Fz` for a resultant, `ux`, `uy`, `uz` for a displacement).
fn describe(kind: &QoiKind, model: &BuiltModel, group: Option<&str>) -> String {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let iface = |i: usize| format!("interface '{}'", model.assembly.interfaces[i].name);
    let sub = |s: usize| format!("substructure '{}'", model.assembly.subs[s].name);
    let on = |s: usize| match group {
        Some(g) => format!("{} / {g}", sub(s)),
        None => sub(s),
    };
    match kind {
        QoiKind::InterfaceWork(i) => format!("work of the forces of {}", iface(*i)),
        QoiKind::FrictionDissipation(i) => format!("friction dissipation on {}", iface(*i)),
        QoiKind::InterfaceForce(i, c) => {
            format!("resultant F{} on side 2 of {}", AXES[*c], iface(*i))
        }
        QoiKind::MaxVonMises { sub: s, .. } => format!("maximum von Mises stress on {}", on(*s)),
        QoiKind::MeanVonMises { sub: s, .. } => format!("mean von Mises stress on {}", on(*s)),
        QoiKind::Displacement(s, p, c) => {
            let dim = model.assembly.subs[*s].model.mesh.dim;
            let at: Vec<String> = p[..dim].iter().map(|x| format!("{x}")).collect();
            format!(
                "displacement u{} of {} at the node nearest to ({})",
                AXES[*c],
                sub(*s),
                at.join(", ")
            )
        }
        QoiKind::Contact(c) => {
            let field = match c.field {
                ContactField::Pressure => "contact pressure",
                ContactField::Slip => "slip",
                ContactField::Status(_) => "contact status",
            };
            match c.node {
                Some(n) => format!("{field} on {} at its side-1 node {n}", iface(c.iface)),
                None => format!("{field} over {}", iface(c.iface)),
            }
        }
        QoiKind::Fretting(f) => {
            let what = match (f.node, f.field) {
                (_, fretting::FrettingField::StickZone) => "measure".to_string(),
                (Some(n), _) => format!("at its side-1 node {n}"),
                (None, fretting::FrettingField::WorkCycle) => "integrated".to_string(),
                (None, _) => "largest".to_string(),
            };
            let cd = match f.regularisation {
                alea_latin::fretting::Regularisation::Surface => String::new(),
                alea_latin::fretting::Regularisation::Point(l) => {
                    format!(", stress at depth {l} (point method)")
                }
                alea_latin::fretting::Regularisation::Line(l) => {
                    format!(", stress averaged over depth {l} (line method)")
                }
            };
            format!("{} on {}, {what}{cd}", f.field.label(), iface(f.iface))
        }
    }
}

/// Where a maximum was found: its value, the substructure node, and the boundary groups that
/// meet there (if any).
#[derive(Clone, Debug, PartialEq)]
pub struct MaxLocation {
    /// The maximum.
    pub value: f64,
    /// Substructure node where it is reached.
    pub node: usize,
    /// Boundary groups meeting at that node.
    pub junction: Option<(String, String)>,
}

impl QoiKind {
    /// True for the quantities that cannot be negative: a friction dissipation, a von Mises
    /// stress, a contact pressure, slip or status length or area.
    pub fn nonnegative(&self) -> bool {
        matches!(
            self,
            QoiKind::FrictionDissipation(_)
                | QoiKind::MaxVonMises { .. }
                | QoiKind::MeanVonMises { .. }
                | QoiKind::Contact(_)
                | QoiKind::Fretting(_)
        )
    }
}

impl Qoi {
    /// The value of this quantity for a run.
    pub fn eval(&self, solver: &LatinSolver, res: &RunResult) -> Result<f64, StudyError> {
        Ok(match &self.kind {
            QoiKind::InterfaceWork(i) => res.interfaces[*i].work(),
            QoiKind::FrictionDissipation(i) => res.interfaces[*i].friction_dissipation(),
            QoiKind::InterfaceForce(i, c) => res.interfaces[*i].resultant()[*c],
            QoiKind::MaxVonMises { sub, .. } => {
                let model = res.scaled_model(solver.model(*sub), *sub);
                self.max_location(&model, &res.displacements[*sub])?
                    .map_or(f64::NAN, |m| m.value)
            }
            QoiKind::MeanVonMises { sub, region } => {
                let model = res.scaled_model(solver.model(*sub), *sub);
                region.mean_von_mises(&model, &res.displacements[*sub])?
            }
            QoiKind::Displacement(s, x, c) => res.displacement_at(solver.model(*s), *s, *x).0[*c],
            QoiKind::Contact(c) => {
                c.eval(&res.interfaces[c.iface])
                    .ok_or_else(|| StudyError::QoiOffInterface {
                        qoi: self.name.clone(),
                        interface: res.interfaces[c.iface].name.clone(),
                    })?
            }
            // Over a cycle: module `steps` evaluates it; a single state has no cycle.
            QoiKind::Fretting(_) => {
                return Err(StudyError::Failed(format!(
                    "quantity '{}' is measured over a load cycle, not on one state",
                    self.name
                )));
            }
        })
    }

    /// For a maximum-type quantity, the maximum for displacement `u` of its substructure
    /// (`model` carrying the run's Young's modulus) and where it is reached; `None` for other
    /// quantities.
    pub fn max_location(
        &self,
        model: &alea_fem::Model,
        u: &[f64],
    ) -> Result<Option<MaxLocation>, StudyError> {
        let QoiKind::MaxVonMises { set, .. } = &self.kind else {
            return Ok(None);
        };
        Ok(set.max_von_mises(model, u)?.map(|(value, i)| MaxLocation {
            value,
            node: set.nodes[i],
            junction: set.junction[i].clone(),
        }))
    }
}

/// Checks the quantities of interest, when the file is loaded: unique names (they head the
/// columns of `samples.csv`); a `displacement` point lies within one cell size of its nearest
/// node (else it is outside the substructure, and the nearest node would silently be somewhere
/// else).
///
/// # Errors
/// [`StudyError::Input`] at the offending quantity.
pub fn check_quantities(
    src: &Source,
    specs: &[QuantitySpec],
    model: &BuiltModel,
    qois: &[Qoi],
) -> Result<(), StudyError> {
    for (i, q) in specs.iter().enumerate() {
        if q.name.get_ref().trim().is_empty() {
            return Err(src.error(
                q.name.span(),
                format!("quantity[{i}].name"),
                "is empty; names head the columns of samples.csv and the report's sections",
            ));
        }
        if let Some(j) = specs[..i]
            .iter()
            .position(|p| p.name.get_ref() == q.name.get_ref())
        {
            return Err(src.error(
                q.name.span(),
                format!("quantity[{i}].name"),
                format!(
                    "'{}' is already the name of quantity[{j}]; names head the columns of samples.csv and must be unique",
                    q.name.get_ref()
                ),
            ));
        }
    }
    for (i, (q, spec)) in qois.iter().zip(specs).enumerate() {
        if let QoiKind::Displacement(s, x, _) = &q.kind {
            let mesh = &model.assembly.subs[*s].model.mesh;
            let d2 = |n: usize| -> f64 { (0..3).map(|k| (mesh.coords[n][k] - x[k]).powi(2)).sum() };
            let Some(node) = (0..mesh.num_nodes()).min_by(|&a, &b| d2(a).total_cmp(&d2(b))) else {
                continue;
            };
            let dist = d2(node).sqrt();
            // Size of the cells around that node: the farthest node of any cell holding it.
            let mut h = 0.0f64;
            for c in 0..mesh.num_cells() {
                let nodes = mesh.cell_nodes(c);
                if nodes.contains(&node) {
                    for &m in nodes {
                        let e: f64 = (0..3)
                            .map(|k| (mesh.coords[m][k] - mesh.coords[node][k]).powi(2))
                            .sum();
                        h = h.max(e.sqrt());
                    }
                }
            }
            if dist > h {
                let p = mesh.coords[node];
                return Err(src.error(
                    spec.point.as_ref().map_or(spec.name.span(), |p| p.span()),
                    format!("quantity[{i}].point"),
                    format!(
                        "no node of substructure '{}' near this point: the nearest, at ({:.6}, {:.6}, {:.6}), is {dist:.4e} away, more than the size of its cells ({h:.4e}); is the point outside the substructure?",
                        model.assembly.subs[*s].name, p[0], p[1], p[2]
                    ),
                ));
            }
        }
    }
    Ok(())
}
