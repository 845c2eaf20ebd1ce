//! The standard EET technique (Ladeveze-Leguillon 1983; Ladeveze-Pelle 2004 ch. 2; thesis
//! 3.1.1.4 b): phase 1 ([`phase1`]) builds equilibrated edge tractions, phase 2 ([`phase2`])
//! the admissible stress element by element. Phase 1 is the generic kernel of `crate::kernel`
//! (shared with 3D, [`crate::solid`]) on the edges of the 2D cells. [`phase1_cache`] and [`phase2_cache`] are the same
//! phases with their run-independent matrices computed once ([`crate::DomainEstimator`]).

mod family;
pub mod phase1;
pub mod phase1_cache;
pub mod phase2;
pub mod phase2_cache;
mod projections;
pub mod sides;
