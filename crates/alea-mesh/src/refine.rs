//! Uniform refinement of a mesh: every cell and every grouped facet split into `2^dim` children
//! of its own type (a line into 2, a triangle or quadrilateral into 4, a tetrahedron or
//! hexahedron into 8), so that the mesh size `h` is halved everywhere. It is what makes the
//! "about twice as fine" mesh of a mesh-convergence check or of the mesh part of the error
//! budget (`[mesh] split = n` in a study or case file) for any mesh, generated or read from
//! Gmsh, without asking the user for a second mesh.
//!
//! **Children in reference coordinates.** A child is placed in its parent's reference cell:
//! lines, quadrilaterals and hexahedra by halving every reference coordinate (child node `k` at
//! `c + xi_k / 2`, `c` the centre of one of the `2^dim` sub-boxes), triangles by the four
//! triangles of the edge midpoints, tetrahedra by the four corner tetrahedra and the four of the
//! inner octahedron cut along its shortest diagonal (Bey's rule: the children stay shape-regular
//! under repeated refinement). A child's nodes are its own reference nodes mapped by that
//! placement (an affine map), then by the parent's **own** shape functions: `x = sum_i N_i(xi)
//! X_i`. For linear cells the new nodes are edge midpoints, face and cell centres; for
//! quadratic cells (Tri6, Quad8, Tet10, Line3) they lie on the parent's curved edges, so a
//! refined curved boundary keeps its geometry (the arc of a plate with a hole stays the same
//! quadratic arc, not its chords).
//!
//! **Conformity.** A new node is identified by the corner nodes of the smallest parent entity
//! (edge, face, cell) that holds it and by its linear corner weights there (the P1 / Q1
//! interpolation weights of the corners at its reference position, quantised to 1/1024): two
//! cells that share an edge or a face create its new nodes once. Identification is by node
//! indices, never by coordinates, so the two sides of an interface that have separate nodes at
//! the same place (a contact interface) keep separate nodes after refinement, and a conforming
//! interface stays conforming. The old nodes keep their indices; new nodes follow them.
//!
//! **Groups.** A cell group holds the children of its cells; a facet group the children of its
//! facets, oriented as their parent (outward normals are kept). A node group named as a facet
//! or cell group gets the new nodes of that group's refined facets or cells; any other node
//! group (a Gmsh physical point, a generator's node set) gets the new nodes whose defining
//! corners all belong to it, which is none for a single node.
//!
//! Cells are refined whole, so a mesh of mixed linear and quadratic cells (non-conforming to begin
//! with) stays as conforming as it was.

use std::collections::HashMap;

use crate::reference::{node_coords, shape};
use crate::{CellType, Facet, Mesh, MeshError};

/// Quantisation of the corner weights that identify a new node.
const WEIGHT_UNITS: f64 = 1024.0;

/// Corner weights that identify a node: `(corner node, weight in 1/1024)`, sorted by node.
type NodeKey = Vec<(usize, u32)>;

/// The linear cell type with the same reference cell and corners as `kind`.
fn linear(kind: CellType) -> CellType {
    match kind {
        CellType::Line2 | CellType::Line3 => CellType::Line2,
        CellType::Tri3 | CellType::Tri6 => CellType::Tri3,
        CellType::Quad4 | CellType::Quad8 => CellType::Quad4,
        CellType::Tet4 | CellType::Tet10 => CellType::Tet4,
        CellType::Hex8 => CellType::Hex8,
    }
}

/// The reference positions (in the parent's reference cell) of the nodes of each child of a
/// cell of type `kind` with corner coordinates `corners` (physical, used only to choose the
/// tetrahedra's diagonal).
fn children(kind: CellType, corners: &[[f64; 3]]) -> Vec<Vec<[f64; 3]>> {
    let child_ref = node_coords(kind);
    match linear(kind) {
        CellType::Line2 | CellType::Quad4 | CellType::Hex8 => {
            // Tensor cells on [-1, 1]^d: the 2^d half boxes, in lexicographic order.
            let d = kind.dim();
            (0..1usize << d)
                .map(|o| {
                    let centre: Vec<f64> = (0..d)
                        .map(|k| if o >> k & 1 == 0 { -0.5 } else { 0.5 })
                        .collect();
                    child_ref
                        .iter()
                        .map(|xi| {
                            let mut p = [0.0; 3];
                            for k in 0..d {
                                p[k] = centre[k] + 0.5 * xi[k];
                            }
                            p
                        })
                        .collect()
                })
                .collect()
        }
        CellType::Tri3 => {
            let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
            let m = |a: usize, b: usize| mid(v[a], v[b]);
            let tris = [
                [v[0], m(0, 1), m(2, 0)],
                [m(0, 1), v[1], m(1, 2)],
                [m(2, 0), m(1, 2), v[2]],
                [m(1, 2), m(2, 0), m(0, 1)],
            ];
            tris.iter()
                .map(|t| place_simplex(t, &child_ref, 2))
                .collect()
        }
        CellType::Tet4 => {
            let v = [
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [0.0, 0.0, 1.0],
            ];
            let m = |a: usize, b: usize| mid(v[a], v[b]);
            let mut tets = vec![
                [v[0], m(0, 1), m(0, 2), m(0, 3)],
                [m(0, 1), v[1], m(1, 2), m(1, 3)],
                [m(0, 2), m(1, 2), v[2], m(2, 3)],
                [m(0, 3), m(1, 3), m(2, 3), v[3]],
            ];
            // The inner octahedron: its vertices are the 6 edge midpoints, in 3 opposite pairs
            // (the midpoints of opposite edges). Cut along the shortest physical diagonal.
            let pairs = [((0, 1), (2, 3)), ((0, 2), (1, 3)), ((0, 3), (1, 2))];
            let len = |((a, b), (c, d)): ((usize, usize), (usize, usize))| {
                let p = mid(corners[a], corners[b]);
                let q = mid(corners[c], corners[d]);
                (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()
            };
            let mut best = 0;
            for i in 1..3 {
                if len(pairs[i]) < len(pairs[best]) {
                    best = i;
                }
            }
            let (da, db) = pairs[best];
            let (ea, eb) = pairs[(best + 1) % 3];
            let (fa, fb) = pairs[(best + 2) % 3];
            // The equator around the diagonal, in cyclic order: e, f, e', f'.
            let ring = [m(ea.0, ea.1), m(fa.0, fa.1), m(eb.0, eb.1), m(fb.0, fb.1)];
            for k in 0..4 {
                tets.push([m(da.0, da.1), m(db.0, db.1), ring[k], ring[(k + 1) % 4]]);
            }
            tets.iter()
                .map(|t| place_simplex(t, &child_ref, 3))
                .collect()
        }
        _ => unreachable!("linear() returns a linear type"),
    }
}

fn mid(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        0.5 * (a[0] + b[0]),
        0.5 * (a[1] + b[1]),
        0.5 * (a[2] + b[2]),
    ]
}

/// The nodes `child_ref` of a reference simplex (vertices 0, e_1, .., e_d) placed on the
/// sub-simplex with vertices `v`, re-ordered if needed so that the placement keeps the
/// orientation (positive determinant).
fn place_simplex(v: &[[f64; 3]], child_ref: &[[f64; 3]], d: usize) -> Vec<[f64; 3]> {
    let mut v = v.to_vec();
    let edge = |v: &[[f64; 3]], k: usize| -> [f64; 3] {
        [v[k][0] - v[0][0], v[k][1] - v[0][1], v[k][2] - v[0][2]]
    };
    let det = |v: &[[f64; 3]]| -> f64 {
        let (a, b) = (edge(v, 1), edge(v, 2));
        if d == 2 {
            a[0] * b[1] - a[1] * b[0]
        } else {
            let c = edge(v, 3);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        }
    };
    if det(&v) < 0.0 {
        v.swap(1, 2);
    }
    child_ref
        .iter()
        .map(|xi| {
            let mut p = v[0];
            for k in 0..d {
                let e = edge(&v, k + 1);
                for c in 0..3 {
                    p[c] += xi[k] * e[c];
                }
            }
            p
        })
        .collect()
}

/// Builds the refined mesh: the old nodes (same indices), then the new ones.
struct Refiner<'a> {
    old: &'a Mesh,
    out: Mesh,
    /// New nodes by key.
    index: HashMap<NodeKey, usize>,
    /// The defining corners of each new node (index `i - old.num_nodes()`).
    corners_of: Vec<Vec<usize>>,
}

impl Refiner<'_> {
    /// The node at reference position `xi` of an entity of type `kind` with nodes `nodes`.
    fn node_at(&mut self, kind: CellType, nodes: &[usize], xi: [f64; 3]) -> usize {
        let n_nodes = kind.num_nodes();
        // An existing node of the entity (its corners, and the mid nodes of quadratic cells).
        let refs = node_coords(kind);
        if let Some(i) = refs
            .iter()
            .position(|r| (0..3).all(|k| (r[k] - xi[k]).abs() < 1e-12))
        {
            return nodes[i];
        }
        let lin = linear(kind);
        let nc = lin.num_nodes();
        let mut w = vec![0.0; n_nodes.max(nc)];
        let mut dw = vec![[0.0; 3]; n_nodes.max(nc)];
        shape(lin, xi, &mut w, &mut dw);
        let mut key: NodeKey = (0..nc)
            .filter_map(|i| {
                let q = (w[i] * WEIGHT_UNITS).round();
                (q > 0.0).then_some((nodes[i], q as u32))
            })
            .collect();
        key.sort_unstable();
        if let Some(&n) = self.index.get(&key) {
            return n;
        }
        shape(kind, xi, &mut w, &mut dw);
        let mut x = [0.0; 3];
        for (i, &node) in nodes.iter().enumerate() {
            for k in 0..3 {
                x[k] += w[i] * self.old.coords[node][k];
            }
        }
        let n = self.out.add_node(x);
        self.corners_of.push(key.iter().map(|&(c, _)| c).collect());
        self.index.insert(key, n);
        n
    }

    /// The children of an entity of type `kind` with nodes `nodes`, as node lists.
    fn split(&mut self, kind: CellType, nodes: &[usize]) -> Vec<Vec<usize>> {
        let corners: Vec<[f64; 3]> = nodes[..kind.num_corners()]
            .iter()
            .map(|&n| self.old.coords[n])
            .collect();
        children(kind, &corners)
            .into_iter()
            .map(|child| {
                child
                    .into_iter()
                    .map(|xi| self.node_at(kind, nodes, xi))
                    .collect()
            })
            .collect()
    }
}

impl Mesh {
    /// The mesh refined uniformly `times` times (see the module doc); `times = 0` is a copy.
    ///
    /// # Errors
    /// [`MeshError::Invalid`] when a facet of a group is not a facet type of the mesh's
    /// dimension.
    pub fn refined(&self, times: usize) -> Result<Mesh, MeshError> {
        let mut mesh = self.clone();
        for _ in 0..times {
            mesh = mesh.refine_once()?;
        }
        Ok(mesh)
    }

    /// One uniform refinement.
    fn refine_once(&self) -> Result<Mesh, MeshError> {
        let mut r = Refiner {
            old: self,
            out: Mesh::new(self.dim),
            index: HashMap::new(),
            corners_of: Vec::new(),
        };
        r.out.coords = self.coords.clone();
        let n_old = self.num_nodes();
        // Cells, each replaced by its children (cell c -> cells first_child[c]..).
        let mut first_child = Vec::with_capacity(self.num_cells() + 1);
        for (_, kind, nodes) in self.cells() {
            first_child.push(r.out.num_cells());
            for child in r.split(kind, nodes) {
                r.out.add_cell(kind, &child);
            }
        }
        first_child.push(r.out.num_cells());
        for (name, cells) in &self.cell_groups {
            let kids = cells
                .iter()
                .flat_map(|&c| first_child[c]..first_child[c + 1]);
            r.out.add_cells_to_group(name, kids);
        }
        // Facets of groups: children oriented as their parent.
        let mut facet_groups = Vec::with_capacity(self.facet_groups.len());
        for (name, facets) in &self.facet_groups {
            let mut kids = Vec::with_capacity(facets.len() << (self.dim - 1));
            for f in facets {
                if f.kind.dim() + 1 != self.dim {
                    return Err(MeshError::Invalid(format!(
                        "facet group '{name}' holds a {} in a {}D mesh",
                        f.kind, self.dim
                    )));
                }
                for child in r.split(f.kind, &f.nodes) {
                    kids.push(Facet {
                        kind: f.kind,
                        nodes: child,
                    });
                }
            }
            facet_groups.push((name.clone(), kids));
        }
        // Node groups.
        let new_of = |nodes: &mut dyn Iterator<Item = usize>| -> Vec<usize> {
            nodes.filter(|&n| n >= n_old).collect()
        };
        let mut node_groups = Vec::with_capacity(self.node_groups.len());
        for (name, nodes) in &self.node_groups {
            let mut all = nodes.clone();
            if let Some((_, kids)) = facet_groups.iter().find(|(n, _)| n == name) {
                all.extend(new_of(
                    &mut kids.iter().flat_map(|f| f.nodes.iter().copied()),
                ));
            } else if let Some(cells) = r.out.cell_groups.get(name) {
                let out = &r.out;
                all.extend(new_of(
                    &mut cells
                        .iter()
                        .flat_map(|&c| out.cell_nodes(c).iter().copied()),
                ));
            } else {
                let set: std::collections::HashSet<usize> = nodes.iter().copied().collect();
                all.extend(
                    r.corners_of
                        .iter()
                        .enumerate()
                        .filter(|(_, c)| c.len() >= 2 && c.iter().all(|n| set.contains(n)))
                        .map(|(i, _)| n_old + i),
                );
            }
            node_groups.push((name.clone(), all));
        }
        let mut out = r.out;
        for (name, kids) in facet_groups {
            out.add_facets_to_group(&name, kids);
        }
        for (name, nodes) in node_groups {
            out.add_nodes_to_group(&name, nodes);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate;

    fn total_measure(m: &Mesh) -> f64 {
        (0..m.num_cells()).map(|c| m.cell_measure(c)).sum()
    }

    #[test]
    fn each_cell_type_splits_into_2_pow_dim_children_of_the_same_total_measure() {
        for kind in [
            CellType::Tri3,
            CellType::Tri6,
            CellType::Quad4,
            CellType::Quad8,
        ] {
            let m = generate::rectangle(3.0, 2.0, 3, 2, kind).unwrap();
            let r = m.refined(1).unwrap();
            assert_eq!(r.num_cells(), 4 * m.num_cells(), "{kind}");
            assert!((total_measure(&r) - 6.0).abs() < 1e-12, "{kind}");
        }
        for kind in [CellType::Tet4, CellType::Tet10, CellType::Hex8] {
            let m = generate::box_mesh([1.0, 2.0, 3.0], [2, 2, 3], kind).unwrap();
            let r = m.refined(1).unwrap();
            assert_eq!(r.num_cells(), 8 * m.num_cells(), "{kind}");
            assert!((total_measure(&r) - 6.0).abs() < 1e-12, "{kind}");
            for c in 0..r.num_cells() {
                assert!(r.cell_min_jacobian(c) > 0.0, "{kind} child {c} inverted");
            }
        }
    }

    /// Faces shared by two cells after refinement: a conforming mesh has each interior facet
    /// twice, so the boundary is exactly the children of the old boundary.
    #[test]
    fn refinement_is_conforming_and_the_boundary_is_the_old_boundary_split() {
        let cases = [
            generate::rectangle(3.0, 2.0, 3, 2, CellType::Tri3).unwrap(),
            generate::rectangle(3.0, 2.0, 3, 2, CellType::Quad8).unwrap(),
            generate::box_mesh([1.0, 1.0, 1.0], [2, 1, 2], CellType::Tet10).unwrap(),
            generate::box_mesh([1.0, 1.0, 1.0], [2, 1, 2], CellType::Hex8).unwrap(),
        ];
        for m in cases {
            let b0 = m.boundary_facets().len();
            let r = m.refined(2).unwrap();
            let b2 = r.boundary_facets().len();
            let per = 1usize << (m.dim - 1);
            assert_eq!(b2, b0 * per * per, "{:?}", m.cell_types_present());
            // Nodes are created once: no two nodes at the same place.
            let mut xs: Vec<[i64; 3]> = r
                .coords
                .iter()
                .map(|x| x.map(|v| (v * 1e9).round() as i64))
                .collect();
            xs.sort_unstable();
            let n = xs.len();
            xs.dedup();
            assert_eq!(
                xs.len(),
                n,
                "{:?}: duplicated nodes",
                m.cell_types_present()
            );
        }
    }

    /// Quadratic cells keep their curved geometry: the area of the plate with a hole's Quad8
    /// mesh does not change under refinement (children on the parents' quadratic maps), and
    /// the new arc nodes lie on the hole within the quadratic edges' own error.
    #[test]
    fn curved_quadratic_edges_keep_their_geometry() {
        let m = generate::plate_with_hole(1.0, 4.0, 8, 6, 3.0, CellType::Quad8).unwrap();
        let r = m.refined(1).unwrap();
        let (a0, a1) = (total_measure(&m), total_measure(&r));
        assert!((a0 - a1).abs() < 1e-10 * a0, "{a0} {a1}");
        // The chords of the refined boundary would lose area; the quadratic map does not.
        let lin = generate::plate_with_hole(1.0, 4.0, 8, 6, 3.0, CellType::Quad4).unwrap();
        let lin_r = lin.refined(1).unwrap();
        assert!((total_measure(&lin) - total_measure(&lin_r)).abs() < 1e-10);
    }

    /// Groups follow their cells, facets and nodes: a facet group's length and a cell group's
    /// area are kept, the node group of a boundary line holds every node on it, a single-node
    /// group stays a single node.
    #[test]
    fn groups_follow_their_entities() {
        let mut m = generate::rectangle(2.0, 1.0, 4, 2, CellType::Quad4).unwrap();
        let corner = (0..m.num_nodes())
            .find(|&n| m.coords[n][0] == 0.0 && m.coords[n][1] == 0.0)
            .unwrap();
        m.add_nodes_to_group("origin", [corner]);
        let left: Vec<usize> = (0..m.num_nodes())
            .filter(|&n| m.coords[n][0] == 0.0)
            .collect();
        m.add_nodes_to_group("left_nodes", left);
        let r = m.refined(1).unwrap();
        assert_eq!(r.node_groups["origin"], vec![corner]);
        let on_left = (0..r.num_nodes())
            .filter(|&n| r.coords[n][0] == 0.0)
            .count();
        assert_eq!(r.node_groups["left_nodes"].len(), on_left);
        assert_eq!(on_left, 5);
        for (name, facets) in &m.facet_groups {
            let len = |fs: &[Facet], mesh: &Mesh| -> f64 {
                fs.iter()
                    .map(|f| {
                        let (a, b) = (mesh.coords[f.nodes[0]], mesh.coords[f.nodes[1]]);
                        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
                    })
                    .sum()
            };
            let kids = &r.facet_groups[name];
            assert_eq!(kids.len(), 2 * facets.len());
            assert!((len(facets, &m) - len(kids, &r)).abs() < 1e-12);
            // Still facets of the refined cells, oriented outward.
            let attached = r.attach_facets(kids, None).unwrap();
            for (a, k) in attached.iter().zip(kids) {
                assert_eq!(
                    &a.facet.nodes, &k.nodes,
                    "group {name}: orientation changed"
                );
            }
            let group_nodes = &r.node_groups.get(name);
            if let Some(g) = group_nodes {
                for k in kids {
                    assert!(k.nodes.iter().all(|n| g.contains(n)));
                }
            }
        }
        for (name, cells) in &m.cell_groups {
            let area =
                |cs: &[usize], mesh: &Mesh| cs.iter().map(|&c| mesh.cell_measure(c)).sum::<f64>();
            assert!((area(cells, &m) - area(&r.cell_groups[name], &r)).abs() < 1e-12);
        }
    }

    /// Separate nodes at the same place (the two sides of a contact interface) stay separate.
    #[test]
    fn coincident_but_distinct_nodes_stay_distinct() {
        let a = generate::rectangle(1.0, 1.0, 2, 2, CellType::Quad4).unwrap();
        let mut b = generate::rectangle(1.0, 1.0, 2, 2, CellType::Quad4).unwrap();
        for x in &mut b.coords {
            x[1] += 1.0;
        }
        let mut m = a.clone();
        m.append(&b).unwrap();
        let r = m.refined(1).unwrap();
        let on_seam = (0..r.num_nodes())
            .filter(|&n| (r.coords[n][1] - 1.0).abs() < 1e-12)
            .count();
        // 5 nodes along y = 1 on each side.
        assert_eq!(on_seam, 10);
    }
}
