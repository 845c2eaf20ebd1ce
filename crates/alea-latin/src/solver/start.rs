//! What a run starts from: the checked [`RunInput`], the Young's-modulus factors `alpha_s`, the
//! interface point data with the run's `mu(x)` and `g0(x)`, the constant part of every
//! right-hand side (prescribed-displacement terms plus the loads times the run's load factors
//! `/ alpha_s`), and the initial local-stage state
//! `(W_hat, F_hat)`: the caller's (multiresolution, thesis 5.1.3: a study's runner gives the
//! state interpolated from the nearest finished runs), the previous load step's, or zero.

use super::{InterfaceState, LatinSolver, Run, RunInput, SubState};
use crate::coarse::macro_inverse;
use crate::{LatinError, PointData, PointStatus, RunTimings};

impl LatinSolver {
    fn check_input(&self, input: &RunInput) -> Result<(), LatinError> {
        let ns = self.subs.len();
        if !input.young_factors.is_empty() && input.young_factors.len() != ns {
            return Err(LatinError::Invalid(format!(
                "{} Young's-modulus factors given for {ns} substructures",
                input.young_factors.len()
            )));
        }
        if let Some((s, a)) = input
            .young_factors
            .iter()
            .enumerate()
            .find(|(_, a)| !(a.is_finite() && **a > 0.0))
        {
            return Err(LatinError::Invalid(format!(
                "Young's-modulus factor of substructure '{}' must be > 0, got {a}",
                self.subs[s].name
            )));
        }
        if !input.load_factors.is_empty() {
            if input.load_factors.len() != ns {
                return Err(LatinError::Invalid(format!(
                    "load factors given for {} substructures, there are {ns}",
                    input.load_factors.len()
                )));
            }
            for (s, lf) in input.load_factors.iter().enumerate() {
                if lf.len() != self.subs[s].r_ext.len() || lf.iter().any(|v| !v.is_finite()) {
                    return Err(LatinError::Invalid(format!(
                        "substructure '{}': {} finite load factors expected, got {:?}",
                        self.subs[s].name,
                        self.subs[s].r_ext.len(),
                        lf
                    )));
                }
            }
        }
        for (name, v) in [("mu", &input.mu), ("gap", &input.gap)] {
            if !v.is_empty() && v.len() != self.ifaces.len() {
                return Err(LatinError::Invalid(format!(
                    "{name} fields given for {} interfaces, there are {}",
                    v.len(),
                    self.ifaces.len()
                )));
            }
        }
        Ok(())
    }

    /// Checks `input` and sets up the working state of its run (before the first iteration).
    pub(super) fn start<'a>(&self, input: &'a RunInput) -> Result<Run<'a>, LatinError> {
        self.check_input(input)?;
        let alpha: Vec<f64> = if input.young_factors.is_empty() {
            vec![1.0; self.subs.len()]
        } else {
            input.young_factors.clone()
        };
        let points = self.run_points(input)?;
        let base = self.constant_rhs(input, &alpha);
        let zero = input.previous_step.is_none() && self.zero_answer(&base, &points);
        let istate = self.initial_state(input, zero)?;
        let macro_active = self.initially_closed(&points);
        let slip_origin = match &input.previous_step {
            Some(prev) => crate::steps::slip_origins(prev, &points),
            None => Vec::new(),
        };
        let macro_inv = self.coarse.as_ref().map(|cs| {
            let mask = cs.mask(&macro_active);
            macro_inverse(cs.n, &cs.subs, &alpha, &mask)
        });
        let condensed = self
            .condensed
            .iter()
            .enumerate()
            .map(|(s, c)| {
                c.as_ref().map(|cd| {
                    cd.for_run(
                        input.load_factors.get(s).map(Vec::as_slice),
                        alpha[s],
                        &base[s],
                    )
                })
            })
            .collect();
        Ok(Run {
            input,
            alpha,
            points,
            base,
            condensed,
            istate,
            sstate: self.sub_states(),
            macro_inv,
            macro_active,
            slip_origin,
            residuals: Vec::new(),
            start_norm: None,
            max_iterations: if input.damped {
                2 * self.options.max_iterations
            } else {
                self.options.max_iterations
            },
            acceleration: if input.damped { 0 } else { self.acceleration() },
            timings: RunTimings::default(),
        })
    }

    /// Interface point data for this run: the run's (or the set-up's) `mu(x)` and `g0(x)`, plus
    /// the geometric gap of mortar points.
    fn run_points(&self, input: &RunInput) -> Result<Vec<Vec<PointData>>, LatinError> {
        let mut points: Vec<Vec<PointData>> = Vec::with_capacity(self.ifaces.len());
        for (i, op) in self.ifaces.iter().enumerate() {
            let mu = input
                .mu
                .get(i)
                .cloned()
                .flatten()
                .unwrap_or_else(|| op.mu.clone());
            let gap = input
                .gap
                .get(i)
                .cloned()
                .flatten()
                .unwrap_or_else(|| op.gap.clone());
            let mut pts = op.points.clone();
            for (p, g) in pts.iter_mut().zip(&op.pairing.geometric_gap) {
                p.mu = mu(p.x);
                p.gap = gap(p.x) + g;
                if !(p.mu.is_finite() && p.mu >= 0.0) {
                    return Err(LatinError::Invalid(format!(
                        "interface '{}': friction coefficient must be finite and >= 0, got {} at ({}, {}, {})",
                        op.name, p.mu, p.x[0], p.x[1], p.x[2]
                    )));
                }
                if !p.gap.is_finite() {
                    return Err(LatinError::Invalid(format!(
                        "interface '{}': gap is not finite at ({}, {}, {})",
                        op.name, p.x[0], p.x[1], p.x[2]
                    )));
                }
            }
            points.push(pts);
        }
        Ok(points)
    }

    /// Constant part of each right-hand side: `(r_presc + sum_j lf_j r_ext_j / alpha)`.
    fn constant_rhs(&self, input: &RunInput, alpha: &[f64]) -> Vec<Vec<f64>> {
        self.subs
            .iter()
            .enumerate()
            .map(|(s, op)| {
                let mut r = op.r_presc.clone();
                for (j, rj) in op.r_ext.iter().enumerate() {
                    let lf = input.load_factors.get(s).map_or(1.0, |v| v[j]);
                    for (a, b) in r.iter_mut().zip(rj) {
                        *a += lf * b / alpha[s];
                    }
                }
                r
            })
            .collect()
    }

    /// True when the run's answer is exactly zero: no load and no imposed displacement (every
    /// constant right-hand side vanishes), and the law of every interface point answers the
    /// zero state with a zero force and jump (a contact whose gap opens it, a perfect
    /// interface). The cold start then converges in one iteration, while a warm start from a
    /// neighbour whose contact is closed would shrink towards zero iterate by iterate (issue 35:
    /// a loose shrink fit).
    /// With ranks, the owners' right-hand sides (the others' are empty here).
    fn zero_answer(&self, base: &[Vec<f64>], points: &[Vec<PointData>]) -> bool {
        self.everywhere(base.iter().flatten().all(|&v| v == 0.0))
            && self.ifaces.iter().zip(points).all(|(op, pts)| {
                pts.iter().all(|p| {
                    let sol = op.law.local_stage(p, [0.0; 3], 1.0);
                    sol.force == [0.0; 3] && sol.jump == [0.0; 3]
                })
            })
    }

    /// The state a run starts from: the caller's or the previous step's, else zero; always zero when `zero` (the run's answer is zero,
    /// [`LatinSolver::zero_answer`]).
    fn initial_state(
        &self,
        input: &RunInput,
        zero: bool,
    ) -> Result<Vec<InterfaceState>, LatinError> {
        let mut istate: Vec<InterfaceState> = self
            .ifaces
            .iter()
            .map(|op| {
                let n = op.points.len();
                InterfaceState {
                    what: [vec![[0.0; 3]; n], vec![[0.0; 3]; n]],
                    fhat: [vec![[0.0; 3]; n], vec![[0.0; 3]; n]],
                    what_prev: [vec![[0.0; 3]; n], vec![[0.0; 3]; n]],
                    what_last: [vec![[0.0; 3]; n], vec![[0.0; 3]; n]],
                    status: vec![PointStatus::Open; n],
                }
            })
            .collect();
        if zero {
            return Ok(istate);
        }
        if let Some(init) = input.initial.as_ref().or(input.previous_step.as_ref()) {
            if init.what.len() != istate.len()
                || init
                    .what
                    .iter()
                    .zip(&istate)
                    .any(|(w, st)| w[0].len() != st.what[0].len())
            {
                return Err(LatinError::Invalid(
                    "initial (or previous-step) local-stage state does not match the interfaces"
                        .into(),
                ));
            }
            for (i, st) in istate.iter_mut().enumerate() {
                st.what = init.what[i].clone();
                st.what_last = init.what[i].clone();
                st.fhat = init.fhat[i].clone();
            }
        }
        Ok(istate)
    }

    /// Zeroed linear-stage state of every substructure.
    fn sub_states(&self) -> Vec<SubState> {
        self.subs
            .iter()
            .zip(&self.condensed)
            .map(|(op, cd)| SubState {
                v: vec![0.0; cd.as_ref().map_or(0, |c| c.n)],
                wi: vec![0.0; cd.as_ref().map_or(0, |c| c.n)],
                stale: false,
                // No volume vector for another rank's substructure (module `ranks`).
                rhs: vec![
                    0.0;
                    if op.chol.is_some() {
                        op.dofs.num_free()
                    } else {
                        0
                    }
                ],
                coarse_u: Vec::new(),
                w: op
                    .links
                    .iter()
                    .map(|l| vec![[0.0; 3]; l.proj.len()])
                    .collect(),
                f: op
                    .links
                    .iter()
                    .map(|l| vec![[0.0; 3]; l.proj.len()])
                    .collect(),
                w_new: op
                    .links
                    .iter()
                    .map(|l| vec![[0.0; 3]; l.proj.len()])
                    .collect(),
                f_new: op
                    .links
                    .iter()
                    .map(|l| vec![[0.0; 3]; l.proj.len()])
                    .collect(),
            })
            .collect()
    }
}
