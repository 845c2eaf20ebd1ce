//! Quantities of interest: what each run contributes to the statistics.

use alea_latin::{LatinSolver, RunResult};

use crate::spec::QuantitySpec;
use crate::{BuiltModel, Source, StudyError};

/// What a quantity of interest measures.
#[derive(Clone, Debug, PartialEq)]
pub enum QoiKind {
    /// `int ([W_hat] + g0 n) . F_hat_2 dS` on an interface (thesis 2.3.2; <= 0 for Coulomb).
    InterfaceWork(usize),
    /// `-int [W_hat]_t . F_t dS >= 0` on an interface.
    FrictionDissipation(usize),
    /// Component of the resultant force on side 2 of an interface.
    InterfaceForce(usize, usize),
    /// Maximum nodal von Mises stress over the nodes of a cell, facet or node group (`None`:
    /// all nodes) of a substructure.
    MaxVonMises(usize, Option<String>),
    /// Displacement component at the node nearest to a point.
    Displacement(usize, [f64; 3], usize),
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
}

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
        let f = |k: &str| format!("quantity[{i}].{k}");
        let iface = || -> Result<usize, StudyError> {
            let s = q.interface.as_ref().ok_or_else(|| {
                src.error(
                    q.kind.span(),
                    f("interface"),
                    "missing; this quantity needs an interface name",
                )
            })?;
            ifaces.iter().position(|n| n == s.get_ref()).ok_or_else(|| {
                src.error(
                    s.span(),
                    f("interface"),
                    format!(
                        "unknown interface '{}'; defined: {}",
                        s.get_ref(),
                        ifaces.join(", ")
                    ),
                )
            })
        };
        let sub = || -> Result<usize, StudyError> {
            let s = q.substructure.as_ref().ok_or_else(|| {
                src.error(
                    q.kind.span(),
                    f("substructure"),
                    "missing; this quantity needs a substructure name",
                )
            })?;
            subs.iter().position(|n| n == s.get_ref()).ok_or_else(|| {
                src.error(
                    s.span(),
                    f("substructure"),
                    format!(
                        "unknown substructure '{}'; defined: {}",
                        s.get_ref(),
                        subs.join(", ")
                    ),
                )
            })
        };
        let comp = |dim: usize| -> Result<usize, StudyError> {
            let c = q.component.as_ref().ok_or_else(|| {
                src.error(q.kind.span(), f("component"), "missing; expected 0, 1 or 2")
            })?;
            if *c.get_ref() >= dim {
                return Err(src.error(c.span(), f("component"), format!("must be < {dim}")));
            }
            Ok(*c.get_ref())
        };
        let dim = model.mesh.dim;
        let kind = match q.kind.get_ref().as_str() {
            "interface_work" => QoiKind::InterfaceWork(iface()?),
            "friction_dissipation" => QoiKind::FrictionDissipation(iface()?),
            "interface_force" => QoiKind::InterfaceForce(iface()?, comp(dim)?),
            "max_von_mises" => {
                let s = sub()?;
                let g = match &q.group {
                    Some(g) => {
                        if let Err(e) = model.assembly.subs[s].model.mesh.group_nodes(g.get_ref()) {
                            return Err(src.error(
                                g.span(),
                                f("group"),
                                format!("substructure '{}': {e}", subs[s]),
                            ));
                        }
                        Some(g.get_ref().clone())
                    }
                    None => None,
                };
                QoiKind::MaxVonMises(s, g)
            }
            "displacement" => {
                let s = sub()?;
                let p = q.point.as_ref().ok_or_else(|| {
                    src.error(q.kind.span(), f("point"), "missing; expected coordinates")
                })?;
                let v = p.get_ref();
                if v.len() != dim || v.iter().any(|x| !x.is_finite()) {
                    return Err(src.error(
                        p.span(),
                        f("point"),
                        format!("expected {dim} finite coordinates"),
                    ));
                }
                let mut x = [0.0; 3];
                x[..dim].copy_from_slice(v);
                QoiKind::Displacement(s, x, comp(dim)?)
            }
            other => {
                return Err(src.error(
                    q.kind.span(),
                    f("kind"),
                    format!("unknown quantity '{other}'; expected interface_work, friction_dissipation, interface_force, max_von_mises or displacement"),
                ));
            }
        };
        if q.thresholds.iter().any(|t| !t.is_finite()) {
            return Err(src.error(q.name.span(), f("thresholds"), "thresholds must be finite"));
        }
        out.push(Qoi {
            name: q.name.get_ref().clone(),
            unit: q.unit.clone().unwrap_or_default(),
            kind,
            thresholds: q.thresholds.clone(),
        });
    }
    crate::checks::check_quantities(src, specs, model, &out)?;
    Ok(out)
}

impl Qoi {
    /// The value of this quantity for a run.
    pub fn eval(&self, solver: &LatinSolver, res: &RunResult) -> Result<f64, StudyError> {
        Ok(match &self.kind {
            QoiKind::InterfaceWork(i) => res.interfaces[*i].work(),
            QoiKind::FrictionDissipation(i) => res.interfaces[*i].friction_dissipation(),
            QoiKind::InterfaceForce(i, c) => res.interfaces[*i].resultant()[*c],
            QoiKind::MaxVonMises(s, g) => {
                let model = res.scaled_model(solver.model(*s), *s);
                let nodes: Vec<usize> = match g {
                    Some(g) => model
                        .mesh
                        .group_nodes(g)
                        .map_err(alea_fem::FemError::from)?,
                    None => (0..model.mesh.num_nodes()).collect(),
                };
                let stresses = alea_fem::post::nodal_stresses(&model, &res.displacements[*s])?;
                nodes
                    .iter()
                    .map(|&n| alea_fem::von_mises(&stresses[n]))
                    .fold(0.0, f64::max)
            }
            QoiKind::Displacement(s, x, c) => res.displacement_at(solver.model(*s), *s, *x).0[*c],
        })
    }
}
