//! The loading data the estimator needs as functions (the FE solver only saw nodal vectors):
//! body force and prescribed tractions, plus the discrete interface forces of a substructure.

use std::collections::HashMap;
use std::sync::Arc;

/// A body force `b(x)` (force per volume).
pub type VectorField = Arc<dyn Fn([f64; 3]) -> [f64; 3] + Send + Sync>;

/// A traction `t(x, n)` (force per area) on a facet group; `n` is the outward unit normal.
pub type TractionField = Arc<dyn Fn([f64; 3], [f64; 3]) -> [f64; 3] + Send + Sync>;

/// The prescribed loads of one (sub)domain, as given to `alea_fem::Loads` (`body_force` with
/// the same function, `traction` on the same groups). Boundary edges in no traction group and
/// not constrained are free (zero traction).
#[derive(Clone, Default)]
pub struct LoadData {
    /// Body force (none: zero).
    pub body: Option<VectorField>,
    /// Tractions on facet groups.
    pub tractions: Vec<(String, TractionField)>,
}

impl std::fmt::Debug for LoadData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LoadData")
            .field("body", &self.body.is_some())
            .field(
                "tractions",
                &self.tractions.iter().map(|t| &t.0).collect::<Vec<_>>(),
            )
            .finish()
    }
}

impl LoadData {
    /// No loads.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the body force.
    pub fn body(mut self, b: impl Fn([f64; 3]) -> [f64; 3] + Send + Sync + 'static) -> Self {
        self.body = Some(Arc::new(b));
        self
    }

    /// Adds a traction on facet group `group`.
    pub fn traction(
        mut self,
        group: &str,
        t: impl Fn([f64; 3], [f64; 3]) -> [f64; 3] + Send + Sync + 'static,
    ) -> Self {
        self.tractions.push((group.to_string(), Arc::new(t)));
        self
    }
}

/// Per facet of a side (key: sorted end nodes), target projections `(node, int_facet t phi_node)`
/// per unit thickness, in the orientation of the side's own outward normal.
pub type FacetProjections = HashMap<[usize; 2], Vec<(usize, [f64; 2])>>;

/// Per face of a 3D side (key: sorted corner nodes), target projections `(node, int_face t
/// phi_node dS)`, in the orientation of the side's own outward normal.
pub type FaceProjections = HashMap<Vec<usize>, Vec<(usize, [f64; 3])>>;

/// Discrete nodal forces applied to the nodes of a facet group (an interface side): force on
/// `nodes[i]` is `forces[i]` (total, thickness included, as in the FE right-hand side).
/// `reference` serves 2D sides (edges), `face_reference` 3D sides (faces).
#[derive(Clone, Debug)]
pub struct SideForces {
    /// Facet group of the side.
    pub group: String,
    /// Mesh nodes.
    pub nodes: Vec<usize>,
    /// Nodal forces.
    pub forces: Vec<[f64; 3]>,
    /// Target projections of the side's traction density (the split of each nodal force
    /// between the edges around the node is the one closest to them). `None`: the projections of
    /// the domain's own FE traction `sigma_h n`. For an interface, the average of the two sides'
    /// FE tractions makes the two sides' densities opposite once the forces are.
    pub reference: Option<FacetProjections>,
    /// The same targets for a 3D side (faces); `None`: the domain's own FE tractions.
    pub face_reference: Option<FaceProjections>,
}
