//! Runs whose Young's modulus varies from cell to cell (`RunInput::cell_young`, e.g. a random
//! field over a substructure's cells). The multiresolution shortcut of the linear stage,
//! `K + k M_Gamma = alpha (K0 + k0 M_Gamma)`, needs one factor `alpha` per substructure; with
//! `E_c = alpha f_c E0_c` cell by cell the stiffness is no multiple of the reference, so such a
//! run gets its own operators: for every substructure with cell factors,
//! `A0 = T^T (K(f E0) + sum k0 Pi^T M_Gamma Pi) T` assembled and factorised again (same dof map,
//! links, search direction `k0` and the set-up's ordering and symbolic analysis - the pattern
//! is the same; the search direction is a free parameter of the iteration, its solution does
//! not depend on it), the other substructures' factorisations shared with the set-up, and the
//! coarse problem's responses of the changed substructures recomputed
//! ([`LatinSolver::with_cell_young`]). Pairings and interface data are the set-up's.
//!
//! The run then proceeds as any other on that solver, from the state its input gives.

use std::sync::Arc;
use std::time::Instant;

use super::setup::{coarse_with, fem_err, operator_matrix};
use super::{LatinSolver, RunInput, SubOperator};
use crate::{LatinError, RunResult};

impl LatinSolver {
    /// A solver sharing this one's pairings, interfaces, options and the factorisations of the
    /// substructures without cell factors, whose substructures `s` with `cell_young[s]` given
    /// (one factor per cell, > 0) are assembled and factorised with their cells' Young's
    /// moduli multiplied by those factors.
    ///
    /// # Errors
    /// If `cell_young` names more substructures than there are, a factor list has not one
    /// finite positive entry per cell, or a factorisation fails.
    pub fn with_cell_young(
        &self,
        cell_young: &[Option<Arc<Vec<f64>>>],
    ) -> Result<LatinSolver, LatinError> {
        let t0 = Instant::now();
        if cell_young.len() > self.subs.len() {
            return Err(LatinError::Invalid(format!(
                "cell Young's-modulus factors given for {} substructures, there are {}",
                cell_young.len(),
                self.subs.len()
            )));
        }
        let mut subs = self.subs.clone();
        let mut changed = vec![false; subs.len()];
        let mut rebuild = || -> Result<(), LatinError> {
            for (s, factors) in cell_young.iter().enumerate() {
                let Some(factors) = factors.as_ref().filter(|f| !f.is_empty()) else {
                    continue;
                };
                let op = &self.subs[s];
                let mut model = op.model.clone();
                model
                    .scale_young_per_cell(factors)
                    .map_err(fem_err(&op.name))?;
                changed[s] = true;
                // Another rank's substructure: its scaled model only (module `ranks`).
                let (chol, r_presc) = match &op.chol {
                    Some(c) => {
                        let (a0, r_presc) = operator_matrix(&op.name, &model, &op.dofs, &op.links)?;
                        // Same mesh, dofs and links: the pattern of the set-up's operator.
                        let mut chol = c.same_pattern();
                        chol.factorize(&a0).map_err(fem_err(&op.name))?;
                        (Some(chol), r_presc)
                    }
                    None => (None, Vec::new()),
                };
                subs[s] = Arc::new(SubOperator {
                    name: op.name.clone(),
                    model,
                    dofs: op.dofs.clone(),
                    chol,
                    r_ext: op.r_ext.clone(),
                    r_presc,
                    links: op.links.clone(),
                    rigid: op.rigid.clone(),
                });
            }
            Ok(())
        };
        let built = rebuild();
        Self::agree(self.ranks.as_deref(), built)?;
        let ifaces = self.ifaces.clone();
        let coarse = self
            .coarse
            .as_ref()
            .map(|c| coarse_with(&subs, &ifaces, Some((c, &changed)), self.ranks.as_deref()));
        Ok(LatinSolver {
            subs,
            ifaces,
            options: self.options.clone(),
            model_size: self.model_size,
            coarse,
            configuration: self.configuration.clone(),
            // The changed substructures' operators are the run's own: volume solves there; the
            // others keep their condensed stage (their coarse columns are kept too).
            condensed: self
                .condensed
                .iter()
                .zip(&changed)
                .map(|(c, &ch)| if ch { None } else { c.clone() })
                .collect(),
            // The same ranks and owners (the set-up's factor sizes reported).
            ranks: self.ranks.clone(),
            setup_seconds: t0.elapsed().as_secs_f64(),
            split: None,
        })
    }

    /// [`LatinSolver::run_shared`] of a run with cell factors: on the solver of
    /// [`LatinSolver::with_cell_young`], the result carrying the factors.
    pub(super) fn run_with_cell_young(&self, input: &RunInput) -> Result<RunResult, LatinError> {
        let t_start = Instant::now();
        let derived = self.with_cell_young(&input.cell_young)?;
        let mut plain = input.clone();
        plain.cell_young = Vec::new();
        let mut result = derived
            .run_solved(std::slice::from_ref(&plain))
            .pop()
            .expect("a batch of one gives one result")?;
        result.cell_young = input.cell_young.clone();
        // The run's own assembly and factorisations count in its time.
        result.timings.total = t_start.elapsed().as_secs_f64();
        Ok(result)
    }
}
