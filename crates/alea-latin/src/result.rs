//! Results of a LATIN run and the quantities of interest computed from them.

use alea_fem::{Model, post};
use alea_mesh::vec3::dot;

use std::sync::Arc;

use crate::PointStatus;
use crate::equilibrium::SubEquilibrium;
use crate::interface::InterfacePairing;

/// Outcome of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunStatus {
    /// The error indicator went below the tolerance.
    Converged,
    /// The iteration limit was reached first.
    NotConverged,
    /// The indicator became non-finite.
    Diverged,
    /// No static equilibrium: some substructure is not balanced by its loads and the interface
    /// forces the law allows. Reported when the error indicator falls below the tolerance on an
    /// unbalanced state (the iterates drift and the relative indicator shrinks), when a
    /// floating substructure moves rigidly by more than the bound, or when the iteration limit
    /// is reached with an imbalance that did not decrease over the second half of the run. The
    /// problem most likely has no static solution (a body pushed beyond its sliding limit,
    /// contacts all open under a net load). See [`RunResult::equilibrium`] and
    /// `LatinSolver::equilibrium_report`.
    NoEquilibrium,
}

impl RunStatus {
    /// Lower-case label for messages and files ("converged", "not converged", "diverged",
    /// "no equilibrium").
    pub fn label(self) -> &'static str {
        match self {
            RunStatus::Converged => "converged",
            RunStatus::NotConverged => "not converged",
            RunStatus::Diverged => "diverged",
            RunStatus::NoEquilibrium => "no equilibrium",
        }
    }
}

/// Wall-clock seconds of a run.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunTimings {
    /// All linear stages (including right-hand sides and extraction).
    pub linear: f64,
    /// Of which triangular solves (summed over substructures, so it can exceed `linear`
    /// when substructures run in parallel).
    pub triangular_solves: f64,
    /// All local stages and error indicators.
    pub local: f64,
    /// The whole run.
    pub total: f64,
}

/// Interface fields of a run, per interface point (side-1 nodes: every node of a node-to-node
/// interface, the multiplier nodes of a mortar one; see [`crate::mortar`]).
#[derive(Clone, Debug)]
pub struct InterfaceResult {
    /// Interface name.
    pub name: String,
    /// Law name.
    pub law: &'static str,
    /// Substructures of sides 1 and 2.
    pub subs: [usize; 2],
    /// Mesh node of each point on each side: for a node-to-node interface the paired nodes;
    /// for a mortar interface the node of largest coefficient of each side's projection row
    /// (side 1: the point's own node). The exact relation is in [`InterfaceResult::pairing`].
    pub nodes: [Vec<usize>; 2],
    /// The pairing: point weights and both sides' projections (node to node or mortar).
    pub pairing: Arc<InterfacePairing>,
    /// Point data used in this run (position, normal, mu, gap; a mortar contact interface's
    /// gap includes the nominal distance between the sides).
    pub points: Vec<crate::PointData>,
    /// Interface weight of each point (side 1's lumped weight; the dual-mortar weight
    /// `int psi_p dS` of a mortar interface): the integration weight of interface integrals.
    pub weights: Vec<f64>,
    /// Linear-stage displacements `W_s`.
    pub w: [Vec<[f64; 3]>; 2],
    /// Linear-stage tractions `F_s` (on substructure `s`).
    pub f: [Vec<[f64; 3]>; 2],
    /// Local-stage displacements `W_hat_s` (last stage).
    pub what: [Vec<[f64; 3]>; 2],
    /// Local-stage displacements of the stage before the last (for the CRE, thesis 3.1.3.2b).
    pub what_prev: [Vec<[f64; 3]>; 2],
    /// Local-stage tractions `F_hat_s`; `F_hat_2 = -F_hat_1`.
    pub fhat: [Vec<[f64; 3]>; 2],
    /// Contact status per point.
    pub status: Vec<PointStatus>,
}

impl InterfaceResult {
    /// Local-stage jump including the shape defect, `[W_hat] + g0 n` at point `i` (on a
    /// cyclic interface in side 1's frame, `R^T W_hat_2 - W_hat_1`, module [`crate::cyclic`]).
    pub fn jump(&self, i: usize) -> [f64; 3] {
        let (a, b) = (self.what[0][i], self.pairing.to_points(1, self.what[1][i]));
        let p = &self.points[i];
        [
            b[0] - a[0] + p.gap * p.normal[0],
            b[1] - a[1] + p.gap * p.normal[1],
            b[2] - a[2] + p.gap * p.normal[2],
        ]
    }

    /// The local-stage force on side 2 at point `i`, `F_hat_2`, in the points' frame (side 1's:
    /// `R^T F_hat_2` on a cyclic interface, module [`crate::cyclic`]; `fhat[1]` holds it in
    /// side 2's own frame).
    pub fn side2_force(&self, i: usize) -> [f64; 3] {
        self.pairing.to_points(1, self.fhat[1][i])
    }

    /// Work of the interface forces `int ([W_hat] + g0 n) . F_hat_2 dS` (thesis 2.3.2: the
    /// work of the friction forces; with the gap included, the normal part vanishes by
    /// complementarity, so this is `int [W_hat]_t . F_t dS <= 0` for Coulomb contact).
    pub fn work(&self) -> f64 {
        (0..self.points.len())
            .map(|i| self.weights[i] * dot(&self.jump(i), &self.side2_force(i)))
            .sum()
    }

    /// Energy dissipated by friction, `-int [W_hat]_t . F_t dS >= 0`.
    pub fn friction_dissipation(&self) -> f64 {
        (0..self.points.len())
            .map(|i| {
                let n = self.points[i].normal;
                let j = self.jump(i);
                let f = self.side2_force(i);
                let (jn, fn_) = (dot(&j, &n), dot(&f, &n));
                let jt = [j[0] - jn * n[0], j[1] - jn * n[1], j[2] - jn * n[2]];
                let ft = [f[0] - fn_ * n[0], f[1] - fn_ * n[1], f[2] - fn_ * n[2]];
                -self.weights[i] * dot(&jt, &ft)
            })
            .sum()
    }

    /// Resultant force exerted on side 2, `int F_hat_2 dS` (in side 2's frame).
    pub fn resultant(&self) -> [f64; 3] {
        let mut r = [0.0; 3];
        for (m, f) in self.weights.iter().zip(&self.fhat[1]) {
            for c in 0..3 {
                r[c] += m * f[c];
            }
        }
        r
    }

    /// Normal and tangential magnitudes of the force on side 2 at point `i`.
    pub fn normal_tangential(&self, i: usize) -> (f64, f64) {
        let n = self.points[i].normal;
        let f = self.side2_force(i);
        let fn_ = dot(&f, &n);
        let ft = [f[0] - fn_ * n[0], f[1] - fn_ * n[1], f[2] - fn_ * n[2]];
        (fn_, dot(&ft, &ft).sqrt())
    }

    /// Nodal forces on side `s` of the linear-stage tractions `F_s` (`Pi_s^T M F_s`, the
    /// interface loads of its last FE solve), on the nodes of
    /// `pairing.sides[s].side_nodes()`.
    pub fn linear_nodal_forces(&self, s: usize) -> Vec<[f64; 3]> {
        self.pairing.sides[s].nodal_forces(&self.f[s])
    }

    /// Nodal forces on side `s` of the local-stage tractions `F_hat_s`, on the nodes of
    /// `pairing.sides[s].side_nodes()`.
    pub fn local_nodal_forces(&self, s: usize) -> Vec<[f64; 3]> {
        self.pairing.sides[s].nodal_forces(&self.fhat[s])
    }

    /// Number of points in each status `[perfect, open, stick, slip]`.
    pub fn status_counts(&self) -> [usize; 4] {
        let mut c = [0; 4];
        for s in &self.status {
            c[s.code() as usize] += 1;
        }
        c
    }
}

/// Everything a run produces.
#[derive(Clone, Debug)]
pub struct RunResult {
    /// Converged or not.
    pub status: RunStatus,
    /// Iterations done.
    pub iterations: usize,
    /// Error indicator after each iteration.
    pub residuals: Vec<f64>,
    /// Node-major displacement of each substructure.
    pub displacements: Vec<Vec<f64>>,
    /// Interface fields.
    pub interfaces: Vec<InterfaceResult>,
    /// Young's-modulus factor of each substructure in this run.
    pub young_factors: Vec<f64>,
    /// Young's-modulus factor of every cell of the substructures whose modulus varied from
    /// cell to cell in this run ([`crate::RunInput::cell_young`]; empty: none did).
    pub cell_young: Vec<Option<std::sync::Arc<Vec<f64>>>>,
    /// Equilibrium check of each substructure at the end of the run (applied loads + local-stage
    /// interface forces, rigid motion); see [`RunStatus::NoEquilibrium`].
    pub equilibrium: Vec<SubEquilibrium>,
    /// Timings.
    pub timings: RunTimings,
    /// The local-stage state of the solved interfaces when the model was cut into subdomains
    /// (the pieces of the user's interfaces and the cuts, module [`crate::split`]): what
    /// [`RunResult::end_state`] gives, so that a run warm-started from this one starts its
    /// cuts too. `None`: the state is that of [`RunResult::interfaces`].
    pub split_state: Option<std::sync::Arc<crate::state::LocalState>>,
}

impl RunResult {
    /// A copy of substructure `s`'s model with this run's Young's modulus (its factor, and
    /// its cells' factors when the modulus varied from cell to cell).
    pub fn scaled_model(&self, model: &Model, s: usize) -> Model {
        let mut m = model.clone();
        m.scale_young(self.young_factors[s]);
        if let Some(Some(f)) = self.cell_young.get(s)
            && !f.is_empty()
        {
            // The run was solved with these factors, checked then (one per cell, > 0).
            if m.scale_young_per_cell(f).is_err() {
                m.scale_young(f64::NAN);
            }
        }
        m
    }

    /// Maximum nodal (averaged) von Mises stress over the nodes of cell group `group` of
    /// substructure `s`.
    pub fn max_von_mises(
        &self,
        model: &Model,
        s: usize,
        group: &str,
    ) -> Result<f64, alea_fem::FemError> {
        let m = self.scaled_model(model, s);
        let cells = m.mesh.cell_group(group)?.to_vec();
        let stresses = post::nodal_stresses(&m, &self.displacements[s])?;
        let mut best = 0.0f64;
        for c in cells {
            for &n in m.mesh.cell_nodes(c) {
                best = best.max(alea_fem::von_mises(&stresses[n]));
            }
        }
        Ok(best)
    }

    /// Displacement of substructure `s` at the node nearest to `x`, and that node.
    pub fn displacement_at(&self, model: &Model, s: usize, x: [f64; 3]) -> ([f64; 3], usize) {
        let mesh = &model.mesh;
        let d = mesh.dim;
        let node = (0..mesh.num_nodes())
            .min_by(|&a, &b| {
                let da: f64 = (0..3).map(|k| (mesh.coords[a][k] - x[k]).powi(2)).sum();
                let db: f64 = (0..3).map(|k| (mesh.coords[b][k] - x[k]).powi(2)).sum();
                da.total_cmp(&db)
            })
            .unwrap_or(0);
        let mut u = [0.0; 3];
        u[..d].copy_from_slice(&self.displacements[s][node * d..node * d + d]);
        (u, node)
    }
}
