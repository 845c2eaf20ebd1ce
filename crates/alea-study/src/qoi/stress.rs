//! Stress quantities of a substructure, evaluated only where they are needed.
//!
//! - **Nodal maximum** over a node set ([`NodeSet`]): the nodal von Mises stress is recovered
//!   as in `alea_fem::post::nodal_stresses` (the mean, over the cells of the node, of the
//!   stress each cell gives at that node), but only for the nodes of the set. The maximum of a
//!   nodal stress is a pointwise value: on a re-entrant corner or where two boundary conditions
//!   meet it follows the singularity and grows without bound as the mesh is refined. Each node
//!   where two boundary groups meet ([`junctions`]) is remembered, so that a maximum found
//!   there can be reported (see `super::warnings`).
//! - **Region average** ([`Region`]): `sigma_bar = int_R sigma_VM dV / int_R dV` over a region
//!   `R` (a cell group, the part of the substructure within a radius of a point, or both),
//!   integrated with the cells' stiffness quadrature: the points of `R` are the quadrature
//!   points inside it, weighted by `w_q det J` (times the thickness in 2D). An integrable
//!   singularity gives a finite average, converging as the mesh is refined (the region's
//!   boundary is resolved to one cell size): a regularised alternative to the maximum.

use std::collections::{BTreeMap, BTreeSet};

use alea_fem::kinematics::point_geometry;
use alea_fem::post::stress_at;
use alea_fem::reference::node_coords;
use alea_fem::{FemError, Model, Quadrature, von_mises};
use alea_mesh::Mesh;

/// For each node where two boundary (facet) groups meet, their names (the first pair in
/// name order). Groups "meet" at a node when a facet at the node belongs to the first and
/// not the second, and another belongs to the second and not the first (so nested groups,
/// e.g. a group and one of its parts, do not meet).
pub fn junctions(mesh: &Mesh) -> BTreeMap<usize, (String, String)> {
    // node -> facet key -> groups of that facet
    let mut at: BTreeMap<usize, BTreeMap<Vec<usize>, BTreeSet<&str>>> = BTreeMap::new();
    for (name, facets) in &mesh.facet_groups {
        for f in facets {
            let key = f.key();
            for &n in &f.nodes {
                at.entry(n)
                    .or_default()
                    .entry(key.clone())
                    .or_default()
                    .insert(name.as_str());
            }
        }
    }
    let mut out = BTreeMap::new();
    for (node, facets) in at {
        let groups: BTreeSet<&str> = facets.values().flatten().copied().collect();
        'pairs: for a in &groups {
            for b in &groups {
                if a >= b {
                    continue;
                }
                let a_not_b = facets.values().any(|g| g.contains(a) && !g.contains(b));
                let b_not_a = facets.values().any(|g| g.contains(b) && !g.contains(a));
                if a_not_b && b_not_a {
                    out.insert(node, (a.to_string(), b.to_string()));
                    break 'pairs;
                }
            }
        }
    }
    out
}

/// Nodes over which a maximum is taken, with the cells needed to recover their stress.
#[derive(Clone, Debug)]
pub struct NodeSet {
    /// Substructure nodes (sorted).
    pub nodes: Vec<usize>,
    /// For each node, the `(cell, local node index)` pairs around it.
    around: Vec<Vec<(usize, usize)>>,
    /// For each node, the boundary groups meeting there, if any.
    pub junction: Vec<Option<(String, String)>>,
}

impl NodeSet {
    /// The set `nodes` of `mesh` (sorted, deduplicated here).
    pub fn new(mesh: &Mesh, mut nodes: Vec<usize>) -> Self {
        nodes.sort_unstable();
        nodes.dedup();
        let index: BTreeMap<usize, usize> =
            nodes.iter().enumerate().map(|(i, &n)| (n, i)).collect();
        let mut around = vec![Vec::new(); nodes.len()];
        for (c, _, cell_nodes) in mesh.cells() {
            for (a, n) in cell_nodes.iter().enumerate() {
                if let Some(&i) = index.get(n) {
                    around[i].push((c, a));
                }
            }
        }
        let junctions = junctions(mesh);
        let junction = nodes.iter().map(|n| junctions.get(n).cloned()).collect();
        NodeSet {
            nodes,
            around,
            junction,
        }
    }

    /// The maximum nodal von Mises stress over the set and the index (into `nodes`) where it
    /// is reached (the first in node order on ties). `None` for an empty set.
    pub fn max_von_mises(
        &self,
        model: &Model,
        u: &[f64],
    ) -> Result<Option<(f64, usize)>, FemError> {
        let mut best: Option<(f64, usize)> = None;
        for (i, cells) in self.around.iter().enumerate() {
            if cells.is_empty() {
                continue;
            }
            let mut s = [0.0; 6];
            for &(c, a) in cells {
                let xi = node_coords(model.mesh.cell_type(c))[a];
                let sc = stress_at(model, c, u, xi)?;
                for k in 0..6 {
                    s[k] += sc[k];
                }
            }
            for v in s.iter_mut() {
                *v /= cells.len() as f64;
            }
            let vm = von_mises(&s);
            if best.is_none_or(|(b, _)| vm > b) {
                best = Some((vm, i));
            }
        }
        Ok(best)
    }
}

/// Quadrature points of a region, with their weights.
#[derive(Clone, Debug)]
pub struct Region {
    /// `(cell, reference point, weight)`.
    points: Vec<(usize, [f64; 3], f64)>,
    /// Total weight (the region's measure as integrated).
    pub measure: f64,
}

impl Region {
    /// The stiffness-quadrature points of `cells` lying within `ball = (centre, radius)` when
    /// given (all of them otherwise).
    pub fn new(model: &Model, cells: &[usize], ball: Option<([f64; 3], f64)>) -> Self {
        let th = if model.mesh.dim == 2 {
            model.analysis.thickness()
        } else {
            1.0
        };
        let mut points = Vec::new();
        for &c in cells {
            let kind = model.mesh.cell_type(c);
            let coords = model.cell_coords(c);
            let q = Quadrature::stiffness(kind);
            for (xi, w) in q.points.iter().zip(&q.weights) {
                let g = point_geometry(kind, &coords, *xi);
                let inside = ball.is_none_or(|(p, r)| {
                    (0..3).map(|k| (g.x[k] - p[k]).powi(2)).sum::<f64>() <= r * r
                });
                if inside {
                    points.push((c, *xi, w * g.det.abs() * th));
                }
            }
        }
        let measure = points.iter().map(|p| p.2).sum();
        Region { points, measure }
    }

    /// Number of quadrature points in the region.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True if no quadrature point lies in the region.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// `int_R sigma_VM dV / int_R dV`.
    pub fn mean_von_mises(&self, model: &Model, u: &[f64]) -> Result<f64, FemError> {
        let mut acc = 0.0;
        for &(c, xi, w) in &self.points {
            acc += w * von_mises(&stress_at(model, c, u, xi)?);
        }
        Ok(acc / self.measure)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use alea_fem::{Analysis, Material};
    use alea_mesh::CellType;
    use alea_mesh::generate::rectangle;

    fn plate() -> Model {
        let mesh = rectangle(4.0, 2.0, 8, 4, CellType::Quad4).unwrap();
        let mut m = Model::new(mesh, Analysis::PlaneStress { thickness: 0.5 }).unwrap();
        m.set_material_all(Material::new(100.0, 0.0, 0.0).unwrap());
        m
    }

    #[test]
    fn rectangle_corners_are_the_junctions_of_its_sides() {
        let m = plate();
        let j = junctions(&m.mesh);
        let corners: Vec<[f64; 2]> = j
            .keys()
            .map(|&n| [m.mesh.coords[n][0], m.mesh.coords[n][1]])
            .collect();
        assert_eq!(j.len(), 4, "{corners:?}");
        for c in corners {
            assert!((c[0] == 0.0 || c[0] == 4.0) && (c[1] == 0.0 || c[1] == 2.0));
        }
    }

    #[test]
    fn linear_field_gives_exact_nodal_maximum_and_region_average() {
        // u_x = a x y: sigma_xx = E a y (nu = 0), sigma_xy = E a x / 2 (shear modulus E/2).
        let m = plate();
        let a = 1e-3;
        let u: Vec<f64> = m
            .mesh
            .coords
            .iter()
            .flat_map(|x| [a * x[0] * x[1], 0.0])
            .collect();
        let vm = |x: f64, y: f64| {
            let (sxx, sxy) = (100.0 * a * y, 50.0 * a * x);
            (sxx * sxx + 3.0 * sxy * sxy).sqrt()
        };
        let all: Vec<usize> = (0..m.mesh.num_nodes()).collect();
        let set = NodeSet::new(&m.mesh, all);
        let (v, i) = set.max_von_mises(&m, &u).unwrap().unwrap();
        let n = set.nodes[i];
        // Bilinear elements reproduce u = a x y exactly: the nodal stresses are exact, and the
        // maximum is at the corner (4, 2).
        assert_eq!([m.mesh.coords[n][0], m.mesh.coords[n][1]], [4.0, 2.0]);
        assert!((v - vm(4.0, 2.0)).abs() < 1e-9 * v);
        assert!(set.junction[i].is_some());
        // Average of sigma_xx over the whole plate: E a mean(y) = 100 a; of von Mises: compare
        // with a fine midpoint rule of the exact field.
        let cells: Vec<usize> = (0..m.mesh.num_cells()).collect();
        let r = Region::new(&m, &cells, None);
        assert!((r.measure - 4.0 * 2.0 * 0.5).abs() < 1e-12);
        let k = 400;
        let mut exact = 0.0;
        for i in 0..k {
            for j in 0..k {
                exact += vm(
                    4.0 * (i as f64 + 0.5) / k as f64,
                    2.0 * (j as f64 + 0.5) / k as f64,
                );
            }
        }
        exact /= (k * k) as f64;
        let got = r.mean_von_mises(&m, &u).unwrap();
        // 2 x 2 Gauss points per 0.5 x 0.5 cell on a smooth (non-polynomial) integrand.
        assert!((got - exact).abs() < 2e-3 * exact, "{got} vs {exact}");
        // A ball around the centre holds only the points within its radius.
        let ball = Region::new(&m, &cells, Some(([2.0, 1.0, 0.0], 0.3)));
        assert!(!ball.is_empty() && ball.len() < 16);
        assert!(ball.measure < std::f64::consts::PI * 0.3 * 0.3 * 0.5 * 2.0);
    }
}
