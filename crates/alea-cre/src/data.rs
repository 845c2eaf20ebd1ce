//! The loading data the estimator needs as functions (the FE solver only saw nodal vectors):
//! body force and prescribed tractions, plus the discrete interface forces of a substructure.

use std::collections::HashMap;
use std::sync::Arc;

/// A body force `b(x)` (force per volume).
pub type VectorField = Arc<dyn Fn([f64; 3]) -> [f64; 3] + Send + Sync>;

/// A traction `t(x, n)` (force per area) on a facet group; `n` is the outward unit normal.
pub type TractionField = Arc<dyn Fn([f64; 3], [f64; 3]) -> [f64; 3] + Send + Sync>;

/// An affine body force `b(x) = constant + gradient x` (`gradient[i][j] = d b_i / d x_j`):
/// constant and centrifugal loads (`rho omega^2 (I - a a^T)(x - x_0)` about an axis `a`
/// through `x_0`) are affine.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AffineBody {
    /// `b(0)`.
    pub constant: [f64; 3],
    /// `d b_i / d x_j`.
    pub gradient: [[f64; 3]; 3],
}

impl AffineBody {
    /// `b(x)`.
    pub fn eval(&self, x: [f64; 3]) -> [f64; 3] {
        let (c, g) = (&self.constant, &self.gradient);
        [0, 1, 2].map(|i| c[i] + g[i][0] * x[0] + g[i][1] * x[1] + g[i][2] * x[2])
    }

    /// True if every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.constant
            .iter()
            .chain(self.gradient.iter().flatten())
            .all(|v| v.is_finite())
    }
}

/// The prescribed loads of one (sub)domain, as given to `alea_fem::Loads` (`body_force` with
/// the same function, `traction` on the same groups). Boundary edges in no traction group and
/// not constrained are free (zero traction).
#[derive(Clone, Default)]
pub struct LoadData {
    /// Body force (none: zero). Set it with [`LoadData::body`] or [`LoadData::affine_body`]:
    /// after [`LoadData::affine_body`] the estimator contexts ([`crate::LatinEstimator`],
    /// [`crate::DomainEstimator`]) integrate the affine form exactly from cached moments and do
    /// not call this function, so it must not be replaced by another one afterwards.
    pub body: Option<VectorField>,
    /// Tractions on facet groups.
    pub tractions: Vec<(String, TractionField)>,
    /// The affine form of `body`, if it was given as one.
    affine: Option<AffineBody>,
}

impl std::fmt::Debug for LoadData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LoadData")
            .field("body", &self.body.is_some())
            .field("affine", &self.affine)
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

    /// Sets the body force (a general function: integrated by quadrature).
    pub fn body(mut self, b: impl Fn([f64; 3]) -> [f64; 3] + Send + Sync + 'static) -> Self {
        self.body = Some(Arc::new(b));
        self.affine = None;
        self
    }

    /// Sets an affine body force `b(x) = constant + gradient x` (see [`AffineBody`]): the same
    /// function as [`LoadData::body`] for the direct estimators, integrated exactly from cached
    /// moments by the estimator contexts.
    pub fn affine_body(mut self, b: AffineBody) -> Self {
        self.body = Some(Arc::new(move |x| b.eval(x)));
        self.affine = Some(b);
        self
    }

    /// The body force's affine form, if it was set with [`LoadData::affine_body`].
    pub fn affine(&self) -> Option<&AffineBody> {
        self.affine.as_ref()
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
