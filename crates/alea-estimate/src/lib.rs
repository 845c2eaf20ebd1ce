//! The stochastic constitutive-relation error of a non-intrusive study (thesis 3.2 and 4.1-4.2,
//! SEED-NOTES section 4), split into a space part `I_geo` and a stochastic part `I_sto`, its
//! density over the parameter space, and the adaptive refinement criteria.
//!
//! # Data
//! A study runs `K` deterministic solves at points `xi_k`; a surrogate interpolates any run data
//! with weights `w_k(xi)` (every surrogate of `alea_uq` is linear in the run data). For each
//! converged run the deterministic CRE (crate `alea-cre`) provides an admissible solution
//! (thesis 3.1.3): per substructure the admissible stress `sigma_hat_k` and the FE stress
//! `sigma_h,k`, per interface point the jump `w_hat_k` (gap included, local stage `n - 1`) and
//! the force `F_hat_k` (local stage `n`). A [`RunData`] holds them: stresses as **sample
//! vectors** in compliance coordinates of the reference material (`alea_cre::EnergySampler`:
//! `int sigma : D0^-1 : tau = y(sigma) . y(tau)`), so that the substructure `s` with Young's
//! factor `alpha_s` (`K_s = alpha_s K0_s`) has `||sigma||^2_{K_s^-1} = |y(sigma)|^2 / alpha_s`.
//!
//! # The stochastic admissible fields (3.2.3 b)
//! `sigma~(xi) = sum_k w_k(xi) sigma_hat_k`, `w~(xi) = sum_k w_k w_hat_k`,
//! `F~(xi) = sum_k w_k F_hat_k`, and `u~ = sum_k w_k u_h,k`. They are admissible at `xi` when the
//! surrogate reproduces the loads and the shape defects (affine in the parameters, reproduced by
//! every surrogate here); a load factor that is not affine in the parameters makes
//! `sigma~` slightly out of balance and the estimate no longer a bound.
//!
//! # Substructures (3.30, 4.1-4.3)
//! With `sigma_h1(xi) = K(xi) eps(u~(xi)) = alpha(xi) sum_k w_k sigma_h,k / alpha_k`
//! (interpolated displacements, then Hooke) and `sigma_h2(xi) = sum_k w_k sigma_h,k`
//! (interpolated stresses):
//!
//! ```text
//! e_s^2(xi)   = 1/2 ||sigma~ - sigma_h1||^2_{K(xi)^-1}          (the CRE density, 3.28)
//! geo_s^2(xi) = 1/2 ||sigma~ - sigma_h2||^2_{K(xi)^-1}          (4.2)
//! sto_s^2(xi) = e_s^2 - geo_s^2                                 (4.3)
//! ```
//!
//! (4.2) is written in the thesis without the factor 1/2 of (3.30); we keep the 1/2 on both, the
//! reading under which `I_sto = 0` when the stochastic approximation is exact). Every term is a
//! quadratic form in the weights through the per-substructure **Gram matrices**
//! `A_kl = y(sigma_hat_k) . y(sigma_hat_l)`, `B_kl = y(sigma_hat_k) . y(sigma_h,l)`,
//! `C_kl = y(sigma_h,k) . y(sigma_h,l)` ([`gram`]): with `c = w`, `d_k = alpha w_k / alpha_k`,
//! `e_s^2 = (c^T A c - 2 c^T B d + d^T C d) / (2 alpha)`. So the expectation over the parameters
//! is `E[e_s^2] = 1/2 [tr(M_{1/alpha} A) - 2 tr(M_1 B D) + tr(M_alpha D C D)]` with the weight
//! moments `M_f = E[f(xi) w w^T]` and `D = diag(1 / alpha_k)`: exact whenever the moments are
//! ([`Estimator::substructure_moments`]). When the Young's moduli are deterministic,
//! `sigma_h1 = sigma_h2` and the substructure part is pure space error: the stochastic error then
//! lives in the interfaces, as the thesis observes on its turbine (5.2.4).
//! The mean / standard-deviation split (3.32) of `e_s^2 = 1/2 E|delta|^2` with
//! `delta = (y(sigma~) - y(sigma_h1)) / sqrt(alpha)`: mean part `1/2 |E delta|^2`, std part the
//! rest.
//!
//! # Substructures without admissible stress
//! A substructure may come with FE samples only ([`SubLayout::admissible`] false: e.g. 3D cells
//! in a study that estimates, as the thesis's 3D turbine (5.2.6), only the interface part). It
//! then has no error term (`e_s^2 = geo_s^2 = 0`), but its FE energy
//! `||sigma_h1(xi)||^2_{K(xi)^-1} = ||u~(xi)||^2_{K(xi)} = d^T C d / alpha` (the energy of the
//! interpolated displacement, `C` alone: [`gram::Gram::fe_only`]) takes the place of
//! `||sigma~||^2` in the normalisation of the relative indicators, so that they stay relative
//! to the energy of the solution. What this means for the bound: `e~` then lacks the
//! substructures' (non-negative) terms and is **not** an upper bound of the total error, only of
//! the interfaces' share; `I_sto` is unaffected when the Young's moduli are deterministic (the
//! substructure part is then pure space error, see above), so a stochastic refinement driven by
//! `I_sto` loses nothing; `I_geo` holds the interfaces' space error only. The two
//! normalisations agree to first order (`||sigma~||^2 - ||sigma_h1||^2 = O(e~ ||sigma~||)`).
//!
//! # Interfaces (3.31, 4.4-4.5)
//! Per interface point with weight `m_i` and normal `n_i`: `w~`, `F_2 = F~` (interpolated force)
//! and `F_1` = the same normal force with the tangential force the law at `xi` allows given the
//! interpolated normal force and `mu(xi)`: the tangential force brought onto the Coulomb disk
//! (`F_t1 = F_t2` if `|F_t2| <= mu(xi) F_n`, else `mu(xi) F_n F_t2 / |F_t2|`), the allowed force
//! closest to the interpolated one. (The thesis writes `F_t1 = mu(xi) F_n t`, the force of a
//! slipping point; on a slipping point the two agree, on a sticking point ours leaves
//! `F_1 = F_2`, so that at a run point, where the interpolated fields satisfy the law, the
//! stochastic part vanishes.) `F_1` depends continuously on `xi`, so the stochastic part tends
//! to 0 as `xi` approaches a run, also next to a run whose neighbour opens the contact at that
//! point: there `w~_n > 0` while `F~_n > 0`, and zeroing `F_t1` on the opening jump (as a
//! previous version did) made the density jump to `|w_t . F_t|` of the closed run right beside
//! it, a sawtooth that sent the maximum-error criterion chasing the run (runs converging to
//! one point). The space part (4.4) takes the interpolated force as it is: where
//! runs with different statuses are interpolated, `w~` and `F~` are not consistent and
//! `rho(w~, F~) > 0` although every run is converged - part of the interpolation error lands in
//! `I_geo` of the interfaces by the thesis's definition, and shrinks with the runs. The finite part of the bipotential density
//! `rho(w, F) = mu F_n |w_t| + w_n F_n + w_t . F_t` is linear in `F`, hence
//!
//! ```text
//! e_I(xi)   = sum_i m_i rho(w~, F_1)       geo_I(xi) = sum_i m_i rho(w~, F_2)   (4.4)
//! sto_I(xi) = e_I - geo_I = sum_i m_i w~_t . (F_t1 - F_t2)                      (4.5)
//! ```
//!
//! A perfect interface has `rho = w . F` and no stochastic part. The indicator functions of the
//! bipotential (`w~_n >= 0`, `F_n >= 0`) are checked, never evaluated as infinite: violations are
//! reported ([`Estimate::violation_probability`]) and make the estimate no longer a bound.
//! The interface terms are not quadratic in the weights (the norm of `w~_t`, the projection, and
//! `mu(xi)`): their expectations are computed by quadrature ([`Rule`]).
//!
//! # Totals (4.6-4.9)
//! `e~^2 = E[sum_s e_s^2 + sum_I e_I]` (3.28), `I_geo^2`, `I_sto^2 = e~^2 - I_geo^2` (so
//! `e~^2 = I_geo^2 + I_sto^2` by construction), relative values divided by
//! `(E[sum_s ||sigma~_s||^2_{K^-1}])^(1/2)` (with `||sigma_h1||^2` for substructures without
//! admissible samples). A part may come out slightly negative (the split of a
//! square into two terms is not a sum of squares): such a part is reported as 0 in the relative
//! indicators and with its sign in the squared ones.
//!
//! # Expectations
//! [`Estimator::expectation`] sums the pointwise terms over an integration [`Rule`] (points and
//! probability weights, each point tagged with the stochastic cell it belongs to): per cell of a
//! partition of the parameter box (the leaves of the stochastic mesh, or a regular partition for
//! global surrogates), a tensor Gauss-Legendre rule weighted by the joint density - the thesis's
//! third discretisation level (4.2.1 b). The **stochastic error density**
//! `rho_sto(xi) = sto(xi) f(xi)` (the contribution per unit parameter volume, `f` the joint
//! density) is evaluated on it and on a regular grid for maps ([`density`]); the refinement
//! criteria ([`refine`]) integrate it per cell (improved criterion) or search its maximum
//! (maximum-error criterion).
//!
//! # Against a reference
//! [`reference`] computes the true error of the surrogate's interpolated-displacement stress
//! against a reference solution (finer space mesh and stochastic grid) with the same Gram and
//! rule machinery, for the efficiency index of 3.3.3.

pub mod data;
pub mod density;
mod error;
pub mod estimator;
pub mod gram;
pub mod reference;
pub mod refine;
pub mod rule;

pub use data::{InterfaceKind, InterfaceLayout, Layout, RunData, SubLayout};
pub use error::EstimateError;
pub use estimator::{
    EntityEstimate, Estimate, Estimator, InterfacePoint, Options as EstimatorOptions, Parameters,
    PointEstimate, SubPoint, SubstructureMoments, Weights, cell_terms, weight_moments,
};
pub use rule::{CellBox, Rule};
