//! Fretting quantities of an interface over the last load cycle of a run (`[cycle]`, module
//! `cycle`): the formulas, their references and which need a critical distance are in
//! `alea_latin::fretting`.
//!
//! | kind                  | at `point` (nearest side-1 point)       | without `point`                  |
//! |-----------------------|-----------------------------------------|----------------------------------|
//! | `slip_amplitude`      | `delta_i` (length)                      | largest over the interface       |
//! | `friction_work_cycle` | `W_i` (energy per area per cycle)       | `sum_i w_i W_i` (energy / cycle) |
//! | `ruiz_f1`             | `tau_i delta_i`                         | largest                          |
//! | `ruiz_f2`             | `sigma_T tau_i delta_i`                 | largest                          |
//! | `swt`                 | SWT on the critical plane               | largest                          |
//! | `stick_zone`          | -                                       | length (2D) / area (3D)          |
//!
//! `ruiz_f2` and `swt` take their stresses in the interface's side-1 substructure, or in
//! `substructure` (one of the interface's two); `swt` needs a `critical_distance` (point or line
//! method, `critical_method`), `ruiz_f2` takes one optionally (default: the surface nodal
//! stresses, Ruiz's definition). The largest value along the interface is taken over the points
//! whose probe at the critical distance stays inside the substructure (at the ends of a flank,
//! near a corner of the body, it can leave it).

use alea_latin::fretting::{
    CycleStep, Regularisation, StressCycle, fatemi_socie, max_with_index, slip_cycle,
    slip_cycle_repaired, stress_cycle,
};
use alea_latin::{LatinSolver, RunResult};

use crate::StudyError;

/// Planes scanned by SWT (2D: one degree apart).
pub const SWT_PLANES: usize = 180;

/// Which fretting quantity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrettingField {
    /// Half the range of the tangential jump over the cycle.
    SlipAmplitude,
    /// Frictional work per cycle.
    WorkCycle,
    /// Ruiz's F1 = tau delta.
    RuizF1,
    /// Ruiz's F2 = sigma_T tau delta.
    RuizF2,
    /// Smith-Watson-Topper on the critical plane.
    Swt,
    /// Fatemi-Socie on the plane of the largest shear strain range.
    FatemiSocie,
    /// Measure of the zone that sticks throughout the cycle.
    StickZone,
}

impl FrettingField {
    /// Parses a `[[quantity]]` kind.
    pub fn parse(kind: &str) -> Option<Self> {
        Some(match kind {
            "slip_amplitude" => FrettingField::SlipAmplitude,
            "friction_work_cycle" => FrettingField::WorkCycle,
            "ruiz_f1" => FrettingField::RuizF1,
            "ruiz_f2" => FrettingField::RuizF2,
            "swt" => FrettingField::Swt,
            "fatemi_socie" => FrettingField::FatemiSocie,
            "stick_zone" => FrettingField::StickZone,
            _ => return None,
        })
    }

    /// In words, for the reports.
    pub fn label(self) -> &'static str {
        match self {
            FrettingField::SlipAmplitude => "slip amplitude",
            FrettingField::WorkCycle => "frictional work per cycle",
            FrettingField::RuizF1 => "Ruiz F1",
            FrettingField::RuizF2 => "Ruiz F2",
            FrettingField::Swt => "Smith-Watson-Topper parameter",
            FrettingField::FatemiSocie => "Fatemi-Socie parameter",
            FrettingField::StickZone => "stick zone",
        }
    }

    /// True for the quantities built on stresses.
    pub fn uses_stress(self) -> bool {
        matches!(
            self,
            FrettingField::RuizF2 | FrettingField::Swt | FrettingField::FatemiSocie
        )
    }
}

/// A fretting quantity on one interface.
#[derive(Clone, Debug, PartialEq)]
pub struct FrettingQoi {
    /// Interface index.
    pub iface: usize,
    /// Which quantity.
    pub field: FrettingField,
    /// Side-1 mesh node of the point (`None`: over the interface).
    pub node: Option<usize>,
    /// Side whose substructure carries the stresses (0: side 1, 1: side 2).
    pub side: usize,
    /// Where the stresses are taken.
    pub regularisation: Regularisation,
    /// Fatemi-Socie's material constants `(k, sigma_y)` (`None` for the other quantities).
    pub fatemi_socie: Option<(f64, f64)>,
}

/// True for the quantities a re-paired interface (large sliding) cannot give meaning to, or
/// not at a given point (module doc): Ruiz's F2 and any quantity at a `point`.
pub fn refused_with_large_sliding(field: FrettingField, at_point: bool) -> bool {
    field == FrettingField::RuizF2 || at_point
}

fn failed(e: alea_latin::fretting::FrettingError) -> StudyError {
    StudyError::Failed(format!("fretting quantity: {e}"))
}

impl FrettingQoi {
    /// The Fatemi-Socie parameter at every point of a stress cycle, with this quantity's
    /// material constants.
    fn fatemi_socie_values(&self, st: &StressCycle) -> Result<Vec<f64>, StudyError> {
        let Some((k, sy)) = self.fatemi_socie else {
            return Err(StudyError::Internal(
                "a Fatemi-Socie quantity without its material constants".into(),
            ));
        };
        Ok(st
            .fs_shear
            .iter()
            .zip(&st.fs_normal)
            .map(|(&g, &sn)| fatemi_socie(g, sn, k, sy))
            .collect())
    }

    /// The value over the cycle `cycle` (the results of its steps, solved by `solver`) from the
    /// state `origin` (the step before the cycle; `None`: unloaded).
    pub fn eval(
        &self,
        solver: &LatinSolver,
        origin: Option<&RunResult>,
        cycle: &[&RunResult],
    ) -> Result<f64, StudyError> {
        let its: Vec<_> = cycle
            .iter()
            .map(|r| r.interfaces.get(self.iface))
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| StudyError::Internal("fretting: no such interface".into()))?;
        let origin_it = origin.and_then(|o| o.interfaces.get(self.iface));
        let sc = slip_cycle(origin_it, &its).map_err(failed)?;
        let last = its[its.len() - 1];
        let point =
            match self.node {
                Some(node) => Some(last.nodes[0].iter().position(|&n| n == node).ok_or_else(
                    || StudyError::QoiOffInterface {
                        qoi: self.field.label().into(),
                        interface: last.name.clone(),
                    },
                )?),
                None => None,
            };
        let at_or_max = |v: &[f64]| match point {
            Some(p) => v[p],
            None => max_with_index(v).map_or(0.0, |m| m.0),
        };
        Ok(match self.field {
            FrettingField::SlipAmplitude => at_or_max(&sc.slip_amplitude),
            FrettingField::WorkCycle => match point {
                Some(p) => sc.work[p],
                None => sc.total_work(),
            },
            FrettingField::RuizF1 => at_or_max(&sc.f1()),
            FrettingField::StickZone => {
                let mesh = &solver.model(last.subs[0]).mesh;
                sc.stick_zone(mesh, &last.nodes[0])
            }
            FrettingField::RuizF2 | FrettingField::Swt | FrettingField::FatemiSocie => {
                let st = stress_cycle(
                    solver,
                    self.iface,
                    self.side,
                    cycle,
                    self.regularisation,
                    SWT_PLANES,
                )
                .map_err(failed)?;
                if let Some(p) = point
                    && !st.probed[p]
                {
                    return Err(failed(alea_latin::fretting::FrettingError::Outside {
                        sub: solver.sub_name(last.subs[self.side]).to_string(),
                        at: last.points[p].x,
                    }));
                }
                match self.field {
                    FrettingField::Swt => at_or_max(&st.swt),
                    FrettingField::FatemiSocie => at_or_max(&self.fatemi_socie_values(&st)?),
                    _ => at_or_max(&sc.f2(&st.sigma_t)),
                }
            }
        })
    }

    /// The value over the cycle `cycle` of a run with large sliding, whose interface is
    /// re-paired with its points on side `point_side` (module doc): step `k` on its own
    /// pairing, its slip counted from `origins[k]` (per point of the step,
    /// `alea_latin::large_sliding::step_origins`).
    pub fn eval_repaired(
        &self,
        solver: &LatinSolver,
        cycle: &[&RunResult],
        origins: &[&[[f64; 3]]],
        point_side: usize,
    ) -> Result<f64, StudyError> {
        if refused_with_large_sliding(self.field, self.node.is_some()) {
            return Err(StudyError::Internal(format!(
                "{} is refused at load with large sliding",
                self.field.label()
            )));
        }
        let steps: Vec<CycleStep<'_>> = cycle
            .iter()
            .zip(origins)
            .map(|(r, o)| {
                r.interfaces.get(self.iface).map(|it| CycleStep {
                    result: it,
                    origin: o,
                })
            })
            .collect::<Option<Vec<_>>>()
            .filter(|s| s.len() == cycle.len())
            .ok_or_else(|| StudyError::Internal("fretting: no such interface".into()))?;
        let sc = slip_cycle_repaired(&steps, point_side).map_err(failed)?;
        let max = |v: &[f64]| max_with_index(v).map_or(0.0, |m| m.0);
        Ok(match self.field {
            FrettingField::SlipAmplitude => max(&sc.slip_amplitude),
            FrettingField::WorkCycle => sc.total_work(),
            FrettingField::RuizF1 => max(&sc.f1()),
            FrettingField::StickZone => {
                let sub = steps[0].result.subs[point_side];
                sc.stick_zone(&solver.model(sub).mesh, &sc.nodes)
            }
            FrettingField::Swt | FrettingField::FatemiSocie => {
                // The stresses at the material points of the step with the most points (the
                // largest covered zone), through every step of the cycle: SWT and
                // Fatemi-Socie are maxima and ranges over the steps, in any order.
                let widest = (0..cycle.len())
                    .max_by_key(|&k| steps[k].result.points.len())
                    .unwrap_or(0);
                let mut order: Vec<&RunResult> = vec![cycle[widest]];
                order.extend((0..cycle.len()).filter(|&k| k != widest).map(|k| cycle[k]));
                let st = stress_cycle(
                    solver,
                    self.iface,
                    self.side,
                    &order,
                    self.regularisation,
                    SWT_PLANES,
                )
                .map_err(failed)?;
                match self.field {
                    FrettingField::FatemiSocie => max(&self.fatemi_socie_values(&st)?),
                    _ => max(&st.swt),
                }
            }
            FrettingField::RuizF2 => return Err(StudyError::Internal("refused at load".into())),
        })
    }
}
