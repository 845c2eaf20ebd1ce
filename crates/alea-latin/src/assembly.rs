//! Description of an assembly: substructures and the interfaces that join them.

use std::sync::Arc;

use alea_fem::{Constraints, Model};

use crate::InterfaceLaw;
use crate::interface::Pairing;
use crate::rotation::Cyclic;

/// A scalar field along an interface: `x -> value` (friction coefficient, initial gap, ...).
pub type PointField = Arc<dyn Fn([f64; 3]) -> f64 + Send + Sync>;

/// A constant field.
pub fn constant(v: f64) -> PointField {
    Arc::new(move |_| v)
}

/// One linear-elastic substructure.
#[derive(Clone, Debug)]
pub struct Substructure {
    /// Name (used in messages and outputs).
    pub name: String,
    /// Mesh, analysis and reference materials. A run may scale every Young's modulus of the
    /// substructure by one factor without refactorisation.
    pub model: Model,
    /// Displacement constraints of its own (none for a floating substructure).
    pub constraints: Constraints,
    /// Load cases: full node-major external force vectors. A run multiplies case `j` by its
    /// load factor (1 by default) and sums them.
    pub load_cases: Vec<Vec<f64>>,
}

/// An interface between facet group `group1` of substructure `sub1` (side 1, whose outward
/// normal is the interface normal) and facet group `group2` of substructure `sub2`.
#[derive(Clone)]
pub struct InterfaceSpec {
    /// Name.
    pub name: String,
    /// Side-1 substructure index.
    pub sub1: usize,
    /// Side-1 facet group.
    pub group1: String,
    /// Side-2 substructure index.
    pub sub2: usize,
    /// Side-2 facet group.
    pub group2: String,
    /// Behaviour.
    pub law: Arc<dyn InterfaceLaw>,
    /// Default friction coefficient field `mu(x)` (runs may override it).
    pub mu: PointField,
    /// Default initial normal gap / shape defect `g0(x)` (runs may override it).
    pub gap: PointField,
    /// How the sides are paired (default: node to node when they match, mortar otherwise).
    pub pairing: Pairing,
    /// Node matching tolerance: the largest distance between paired nodes (default: 1e-6 x the
    /// interface size).
    pub match_tolerance: Option<f64>,
    /// Mortar search distance: the largest normal distance between the sides at which they are
    /// paired (default: 5 % of the interface size; see [`crate::mortar`]).
    pub search_distance: Option<f64>,
    /// Small sliding (the pairing of the initial configuration, default) or large sliding
    /// (the pairing re-found from the deformed configuration during the solve, contact
    /// interfaces only; module [`crate::large_sliding`]).
    pub sliding: Sliding,
    /// Cyclic symmetry: side 2 is side 1's image by this rotation, and the interface ties
    /// `u_2 = R u_1`, `F_2 = -R F_1` (perfect interfaces only; module `cyclic`).
    pub cyclic: Option<Cyclic>,
    /// The length and side moduli of the default search direction `k_0 = factor E / L`
    /// (`None`: from the sides' groups, module `solver::setup`): a piece of a split interface
    /// keeps its whole interface's (module [`crate::split`]).
    pub direction_scale: Option<DirectionScale>,
}

/// Whether a contact interface keeps the pairing of the initial configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Sliding {
    /// The pairing of the initial configuration throughout (module [`crate::sliding`] says
    /// when a slide exceeds what it can represent).
    #[default]
    Small,
    /// The mortar pairing re-found from the deformed configuration until it is that of the
    /// solution (module [`crate::large_sliding`]).
    Large,
}

impl std::fmt::Debug for InterfaceSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InterfaceSpec")
            .field("name", &self.name)
            .field("side1", &(self.sub1, &self.group1))
            .field("side2", &(self.sub2, &self.group2))
            .field("law", &self.law.name())
            .field("pairing", &self.pairing)
            .field("sliding", &self.sliding)
            .field("cyclic", &self.cyclic)
            .finish()
    }
}

impl InterfaceSpec {
    /// A perfect interface.
    pub fn perfect(name: &str, sub1: usize, group1: &str, sub2: usize, group2: &str) -> Self {
        InterfaceSpec {
            name: name.into(),
            sub1,
            group1: group1.into(),
            sub2,
            group2: group2.into(),
            law: Arc::new(crate::Perfect),
            mu: constant(0.0),
            gap: constant(0.0),
            pairing: Pairing::Auto,
            match_tolerance: None,
            search_distance: None,
            sliding: Sliding::Small,
            cyclic: None,
            direction_scale: None,
        }
    }

    /// A frictional contact interface with constant `mu` and zero gap.
    pub fn coulomb(
        name: &str,
        sub1: usize,
        group1: &str,
        sub2: usize,
        group2: &str,
        mu: f64,
    ) -> Self {
        InterfaceSpec {
            law: Arc::new(crate::CoulombContact),
            mu: constant(mu),
            ..Self::perfect(name, sub1, group1, sub2, group2)
        }
    }
}

/// The length `L` and the side moduli `[E_1, E_2]` of an interface's default search
/// direction (module `solver::setup`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionScale {
    /// Characteristic length (2D: the side-1 length; 3D: the square root of its area).
    pub length: f64,
    /// Mean Young's modulus of the cells along each side.
    pub young: [f64; 2],
}

/// Substructures and interfaces.
#[derive(Clone, Debug, Default)]
pub struct Assembly {
    /// The substructures.
    pub subs: Vec<Substructure>,
    /// The interfaces.
    pub interfaces: Vec<InterfaceSpec>,
}
