//! Fretting quantities over one load cycle of a contact interface: slip amplitude, frictional
//! work per cycle, stick zone, Ruiz's F1 and F2, and the Smith-Watson-Topper and Fatemi-Socie
//! parameters on critical planes.
//!
//! A **cycle** is a sequence of `K >= 1` load-step results (module [`crate::steps`]: each step
//! starts from the end state of the previous one, the Coulomb law applied incrementally), and
//! the **origin** is the result of the step just before the cycle (the last step of the previous
//! cycle once the response is periodic; `None`: the unloaded state). At interface point `i`
//! (weight `w_i`, side 1's outward normal `n`), with the local-stage fields of step `k`: the
//! tangential jump `j_k = [W_hat]_t` and the tangential force on side 2 `q_k = (F_hat_2)_t`:
//!
//! ```text
//!   slip amplitude      delta_i = 1/2 max_{k,l} |j_k - j_l|          (half the range; 2D: (max - min)/2
//!                                                                      of the jump along the tangent)
//!   work per cycle      W_i = sum_k -(j_k - j_{k-1}) . q_k >= 0       (j_0 from the origin), and
//!                       W = sum_i w_i W_i                             (the energy dissipated per cycle)
//!   shear traction      tau_i = max_k |q_k|
//!   Ruiz F1             F1_i = tau_i delta_i                          (Ruiz, Boddington & Chen 1984)
//!   Ruiz F2             F2_i = sigma_T,i tau_i delta_i,   sigma_T,i = max(0, max_k t.sigma_k.t)
//!   SWT                 SWT_i = max_planes max(0, max_k sigma_n,k) (max_k eps_n,k - min_k eps_n,k) / 2
//!   Fatemi-Socie        FS_i = Delta gamma / 2 max(0, 1 + k sigma_n,max / sigma_y) on the plane of the
//!                       largest Delta gamma / 2 = max_t (max_k t.eps_k.n - min_k t.eps_k.n)
//!   stick zone          measure of the points that stick in every step of the cycle
//! ```
//! The work sum is the backward-Euler form of `int q . dj` over the cycle, exact for steps in
//! which each point's slip keeps its direction (where a point slips, `|q| = mu p` and `q` is
//! opposite to the slip increment: [`crate::steps`]). The slip amplitude is the half range of
//! the jumps of the steps in which the point is closed (the relative motion of surfaces apart
//! is not slip: a point open throughout gets 0, and one that opens during the cycle counts
//! its closed states only). The work counts every step's increment from the end of the step
//! before, as the incremental law does (`crate::steps`): at a point that opens and closes
//! within the cycle the two measures differ, and neither is a fretting slip in the usual sense. `sigma_T` is the stress parallel to the surface on
//! the chosen substructure side (2D: along the in-plane tangent; 3D: the largest eigenvalue of
//! the tangential block of `sigma`), its tensile part (Ruiz et al. use the tensile surface
//! stress). SWT (Smith, Watson & Topper 1970, as a critical-plane parameter: Szolwinski & Farris
//! 1996) scans the planes through the point: 2D, the normals `(cos theta, sin theta)` for
//! `theta = pi j / N`, `j < N`; 3D, `N` Fibonacci directions on the half sphere. Strains come
//! from the stresses by the isotropic compliance of the cell, `eps = ((1 + nu) sigma - nu
//! tr(sigma) I) / E` (plane strain carries `sigma_zz`).
//!
//! **Mesh regularisation.** The slip amplitude, the work (per point and integrated), the stick
//! zone and F1 are interface quantities built from bounded, integrable fields (`|q| <= mu p`,
//! slip continuous): they converge under refinement without regularisation (the stick zone
//! with its edges located inside the segments, [`SlipCycle::stick_zone`]). `sigma_T` and
//! therefore F2, and SWT, are built on the stresses at the contact edge, where the surface
//! stress has an infinite gradient (the Hertz pressure vanishes like a square root, the
//! partial-slip shear likewise): their surface values converge like `h^(1/2)` at best. They
//! take a critical distance `L` ([`Regularisation`], Taylor's theory of critical distances as
//! used in fretting by Araujo & Nowell 2002): the **point method** evaluates the stress at
//! depth `L` below the surface point along the inward normal; the **line method** averages the
//! stress (and strain) tensors of each step over the depth `[0, L]` (Simpson's rule on 17
//! points) before the parameter is formed. `L` is a material length (for the point method, half
//! El Haddad's length `(1/pi) (Delta K_th / Delta sigma_e)^2` in Taylor's form); it must be
//! positive and smaller than the contact zone. [`Regularisation::Surface`] uses the nodal
//! (averaged) stresses at the interface node instead, for comparison.
//!
//! References: D. A. Hills, D. Nowell, *Mechanics of Fretting Fatigue*, Kluwer, 1994;
//! C. Ruiz, P. H. B. Boddington, K. C. Chen, Exp. Mech. 24 (1984) 208-217; M. P. Szolwinski,
//! T. N. Farris, Wear 198 (1996) 93-107; J. A. Araujo, D. Nowell, Int. J. Fatigue 24 (2002)
//! 763-775. The closed-form verification (Cattaneo-Mindlin / Mindlin-Deresiewicz cylinder on a
//! flat) is `tests/fretting.rs`.

mod repaired;
mod stress;

pub use repaired::{CycleStep, slip_cycle_repaired};

pub use stress::{
    Regularisation, StressCycle, fatemi_socie, fs_of_stresses, plane_normals, stress_cycle,
    swt_of_stresses,
};

use alea_mesh::Mesh;
use alea_mesh::vec3::dot;

use crate::{InterfaceResult, PointStatus};

type V3 = [f64; 3];

/// Why a fretting quantity could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum FrettingError {
    /// The cycle has no step.
    #[error("a load cycle needs at least one step")]
    EmptyCycle,
    /// The interface is perfect (bonded): no slip, friction or stick zone.
    #[error("interface '{0}' is perfect (bonded): it has no slip, friction work or stick zone")]
    PerfectInterface(String),
    /// The steps' interface results do not have the same points.
    #[error("interface '{0}': the steps of the cycle do not have the same interface points")]
    Mismatch(String),
    /// A critical distance that is not a positive finite length.
    #[error("the critical distance must be a positive finite length, got {0}")]
    CriticalDistance(f64),
    /// No probe point at the critical distance lies inside the substructure (or the one asked
    /// for does not).
    #[error(
        "substructure '{sub}': the critical distance below the contact surface at ({:.6}, {:.6}, {:.6}) leaves its mesh (critical distance too large?)",
        at[0], at[1], at[2]
    )]
    Outside {
        /// Substructure name.
        sub: String,
        /// The point.
        at: [f64; 3],
    },
    /// A side that is not 0 or 1, or an interface index out of range.
    #[error("{0}")]
    Invalid(String),
    /// A finite-element error (stress recovery).
    #[error("substructure '{sub}': {source}")]
    Fem {
        /// Substructure name.
        sub: String,
        /// Underlying error.
        #[source]
        source: alea_fem::FemError,
    },
}

/// The interface fields of a cycle, per interface point (side-1 points of the interface).
#[derive(Clone, Debug)]
pub struct SlipCycle {
    /// Position of each point.
    pub x: Vec<V3>,
    /// Interface weight of each point (length x thickness in 2D, area in 3D).
    pub weights: Vec<f64>,
    /// Closed (stick or slip) in at least one step of the cycle.
    pub closed: Vec<bool>,
    /// Stick in every step of the cycle.
    pub stick: Vec<bool>,
    /// `min_k (mu p_k - |q_k|)`: the smallest friction margin over the cycle (>= 0 where the
    /// point sticks throughout; it vanishes like the square root of the distance to the edge
    /// of the stick zone).
    pub stick_margin: Vec<f64>,
    /// Slip amplitude `delta_i` (length): half the range of the jumps of the steps in which
    /// the point is closed.
    pub slip_amplitude: Vec<f64>,
    /// Frictional work per cycle per unit area `W_i` (force / length).
    pub work: Vec<f64>,
    /// Largest tangential traction over the cycle `tau_i`.
    pub tau: Vec<f64>,
    /// Mesh node of each point on the side carrying the points (side 1 for
    /// [`slip_cycle`]: `InterfaceResult::nodes[0]`; the point side for
    /// [`slip_cycle_repaired`]).
    pub nodes: Vec<usize>,
    /// The energy dissipated by friction over the cycle, `sum_k sum_i w_i^k W_i^k` (each
    /// step's contribution with its own weights: with large sliding the weights of the
    /// points at the edge of the covered zone change with the pairing).
    pub dissipated: f64,
}

impl SlipCycle {
    /// Records point `i`'s state in one step of the cycle: its tangential force `q` and force
    /// `f` on side 2, normal `n`, friction coefficient `mu`, status. Returns whether it is
    /// closed in that step (its jump then counts in the slip amplitude).
    pub(crate) fn record_step(
        &mut self,
        i: usize,
        q: [f64; 3],
        f: [f64; 3],
        n: [f64; 3],
        mu: f64,
        status: PointStatus,
    ) -> bool {
        let qn = dot(&q, &q).sqrt();
        self.tau[i] = self.tau[i].max(qn);
        let margin = mu * dot(&f, &n).max(0.0) - qn;
        self.stick_margin[i] = self.stick_margin[i].min(margin);
        let closed = matches!(status, PointStatus::Stick | PointStatus::Slip);
        self.closed[i] |= closed;
        self.stick[i] &= status == PointStatus::Stick;
        closed
    }

    /// Point `i`'s slip amplitude, half the largest distance between the tangential jumps
    /// `jumps` of its closed steps (0 with none), and its stick margin floored at 0 where it
    /// does not stick throughout.
    pub(crate) fn finish_point(&mut self, i: usize, jumps: &[[f64; 3]]) {
        let mut range = 0.0f64;
        for (a, ja) in jumps.iter().enumerate() {
            for jb in &jumps[a + 1..] {
                range = range.max(dist(ja, jb));
            }
        }
        self.slip_amplitude[i] = 0.5 * range;
        if !self.stick[i] {
            self.stick_margin[i] = self.stick_margin[i].min(0.0);
        }
    }
}

fn tangential(v: V3, n: V3) -> V3 {
    let vn = dot(&v, &n);
    [v[0] - vn * n[0], v[1] - vn * n[1], v[2] - vn * n[2]]
}

fn dist(a: &V3, b: &V3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The interface fields of the cycle `cycle` (one interface result per step, the same
/// interface) from the state `origin` (the step before the cycle; `None`: unloaded).
///
/// # Errors
/// [`FrettingError::EmptyCycle`], [`FrettingError::PerfectInterface`],
/// [`FrettingError::Mismatch`] (steps or origin with other points).
pub fn slip_cycle(
    origin: Option<&InterfaceResult>,
    cycle: &[&InterfaceResult],
) -> Result<SlipCycle, FrettingError> {
    let first = *cycle.first().ok_or(FrettingError::EmptyCycle)?;
    if first.law == "perfect" {
        return Err(FrettingError::PerfectInterface(first.name.clone()));
    }
    let np = first.points.len();
    if cycle.iter().chain(origin.iter()).any(|r| {
        r.points.len() != np || r.fhat[1].len() != np || r.what[0].len() != np || r.law != first.law
    }) {
        return Err(FrettingError::Mismatch(first.name.clone()));
    }
    let jump = |r: &InterfaceResult, p: usize| {
        let (a, b) = (r.what[0][p], r.what[1][p]);
        tangential(
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            first.points[p].normal,
        )
    };
    let mut out = SlipCycle {
        x: first.points.iter().map(|p| p.x).collect(),
        weights: first.weights.clone(),
        closed: vec![false; np],
        stick: vec![true; np],
        stick_margin: vec![f64::INFINITY; np],
        slip_amplitude: vec![0.0; np],
        work: vec![0.0; np],
        tau: vec![0.0; np],
        nodes: first.nodes[0].clone(),
        dissipated: 0.0,
    };
    for p in 0..np {
        let n = first.points[p].normal;
        let mut prev = origin.map_or([0.0; 3], |o| jump(o, p));
        let mut jumps = Vec::with_capacity(cycle.len());
        for r in cycle {
            let j = jump(r, p);
            let f = r.fhat[1][p];
            let q = tangential(f, n);
            let d = [j[0] - prev[0], j[1] - prev[1], j[2] - prev[2]];
            out.work[p] -= dot(&d, &q);
            if out.record_step(p, q, f, n, r.points[p].mu, r.status[p]) {
                jumps.push(j);
            }
            prev = j;
        }
        out.finish_point(p, &jumps);
    }
    out.dissipated = out.weights.iter().zip(&out.work).map(|(w, v)| w * v).sum();
    Ok(out)
}

/// Largest value of `v` and its index (`None` if `v` is empty; NaN values are skipped).
pub fn max_with_index(v: &[f64]) -> Option<(f64, usize)> {
    v.iter()
        .enumerate()
        .filter(|(_, x)| !x.is_nan())
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, x)| (*x, i))
}

impl SlipCycle {
    /// Ruiz's `F1_i = tau_i delta_i` per point.
    pub fn f1(&self) -> Vec<f64> {
        self.tau
            .iter()
            .zip(&self.slip_amplitude)
            .map(|(t, d)| t * d)
            .collect()
    }

    /// Ruiz's `F2_i = sigma_T,i tau_i delta_i` per point, for the tensile surface stresses
    /// `sigma_t` of [`StressCycle::sigma_t`] (same points).
    pub fn f2(&self, sigma_t: &[f64]) -> Vec<f64> {
        self.f1().iter().zip(sigma_t).map(|(f, s)| f * s).collect()
    }

    /// The energy dissipated by friction over the cycle, `sum_i w_i W_i` (>= 0;
    /// [`SlipCycle::dissipated`]).
    pub fn total_work(&self) -> f64 {
        self.dissipated
    }

    /// Measure of the zone that sticks throughout the cycle. 2D (`mesh` of dimension 2: side
    /// 1's mesh, `nodes` the mesh node of each point, `InterfaceResult::nodes[0]`): its
    /// length, from the boundary segments of `mesh` joining two points; a segment with both
    /// ends sticking counts whole, one with a single end sticking counts up to the edge of the
    /// zone, found by extrapolating the square of the friction margin (linear in the distance
    /// to the edge, where the margin vanishes like its square root) from that end and its other
    /// sticking neighbour, clamped to the segment (half the segment without such a neighbour).
    /// 3D: the summed weights of the points that stick throughout (an area times no thickness;
    /// first order in the mesh size at the zone's edge).
    pub fn stick_zone(&self, mesh: &Mesh, nodes: &[usize]) -> f64 {
        if mesh.dim != 2 || nodes.len() != self.x.len() {
            return self
                .weights
                .iter()
                .zip(&self.stick)
                .filter(|(_, s)| **s)
                .map(|(w, _)| *w)
                .sum();
        }
        let mut point_of = std::collections::HashMap::new();
        for (p, &n) in nodes.iter().enumerate() {
            point_of.insert(n, p);
        }
        let mut segments: Vec<(usize, usize)> = Vec::new();
        for b in mesh.boundary_facets() {
            let f = &b.facet.nodes;
            if f.len() < 2 {
                continue;
            }
            if let (Some(&a), Some(&c)) = (point_of.get(&f[0]), point_of.get(&f[1])) {
                segments.push((a.min(c), a.max(c)));
            }
        }
        segments.sort_unstable();
        segments.dedup();
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); self.x.len()];
        for &(a, c) in &segments {
            neighbours[a].push(c);
            neighbours[c].push(a);
        }
        let mut length = 0.0;
        for &(a, c) in &segments {
            let l = dist(&self.x[a], &self.x[c]);
            length += match (self.stick[a], self.stick[c]) {
                (true, true) => l,
                (false, false) => 0.0,
                (true, false) => self.edge_inside(a, c, l, &neighbours[a]),
                (false, true) => self.edge_inside(c, a, l, &neighbours[c]),
            };
        }
        length
    }

    /// Length of the sticking part of segment `(i, o)` of length `l` (`i` sticks, `o` does
    /// not), by the extrapolation of `margin^2` from `i` and its sticking neighbour.
    fn edge_inside(&self, i: usize, o: usize, l: f64, neighbours: &[usize]) -> f64 {
        let Some(&p) = neighbours.iter().find(|&&p| p != o && self.stick[p]) else {
            return 0.5 * l;
        };
        let (mi, mp) = (self.stick_margin[i].powi(2), self.stick_margin[p].powi(2));
        if mp <= mi {
            return 0.5 * l;
        }
        (mi * dist(&self.x[i], &self.x[p]) / (mp - mi)).clamp(0.0, l)
    }
}
