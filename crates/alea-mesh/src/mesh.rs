//! The mesh: node coordinates, cells of mixed types, and named groups of cells, facets and nodes.
//!
//! Cells are the volume elements (topological dimension = `Mesh::dim`); facets are the
//! lower-dimensional entities (edges in 2D, faces in 3D) on which loads, constraints and interfaces
//! are defined. Groups are referred to by name: that is how a study names substructures, loads,
//! constraints and interfaces. Coordinates are always stored as `[x, y, z]` (z = 0 in 2D).

use std::collections::{BTreeMap, HashMap};

use crate::{CellType, MeshError};

/// A facet (edge in 2D, face in 3D) given by its type and global node indices, in the order of
/// [`CellType::facets`] (outward normal with respect to the cell it bounds).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Facet {
    /// Facet type (`Line2`/`Line3` in 2D, `Tri3`/`Tri6`/`Quad4` in 3D).
    pub kind: CellType,
    /// Global node indices.
    pub nodes: Vec<usize>,
}

impl Facet {
    /// Sorted corner nodes: a key identifying the facet whatever its orientation.
    pub fn key(&self) -> Vec<usize> {
        let mut k = self.nodes[..self.kind.num_corners()].to_vec();
        k.sort_unstable();
        k
    }
}

/// A boundary facet found by [`Mesh::boundary_facets`]: the facet and the cell it bounds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BoundaryFacet {
    /// The cell.
    pub cell: usize,
    /// Index of the facet in `CellType::facets()` of that cell.
    pub local: usize,
    /// The facet, oriented outward.
    pub facet: Facet,
}

/// Nodes, cells and named groups.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Spatial dimension: 2 or 3.
    pub dim: usize,
    /// Node coordinates `[x, y, z]` (z = 0 in 2D).
    pub coords: Vec<[f64; 3]>,
    cell_types: Vec<CellType>,
    cell_ptr: Vec<usize>,
    cell_nodes: Vec<usize>,
    /// Named groups of cells (cell indices, sorted, unique).
    pub cell_groups: BTreeMap<String, Vec<usize>>,
    /// Named groups of facets.
    pub facet_groups: BTreeMap<String, Vec<Facet>>,
    /// Named groups of nodes (sorted, unique).
    pub node_groups: BTreeMap<String, Vec<usize>>,
}

impl Mesh {
    /// An empty mesh of spatial dimension `dim` (2 or 3).
    ///
    /// # Panics
    /// If `dim` is not 2 or 3.
    pub fn new(dim: usize) -> Self {
        assert!(dim == 2 || dim == 3, "mesh dimension must be 2 or 3");
        Mesh {
            dim,
            cell_ptr: vec![0],
            ..Default::default()
        }
    }

    /// Adds a node, returns its index.
    pub fn add_node(&mut self, x: [f64; 3]) -> usize {
        self.coords.push(x);
        self.coords.len() - 1
    }

    /// Adds a cell, returns its index.
    ///
    /// # Panics
    /// If the number of nodes does not match the type.
    pub fn add_cell(&mut self, kind: CellType, nodes: &[usize]) -> usize {
        assert_eq!(nodes.len(), kind.num_nodes(), "wrong node count for {kind}");
        self.cell_types.push(kind);
        self.cell_nodes.extend_from_slice(nodes);
        self.cell_ptr.push(self.cell_nodes.len());
        self.cell_types.len() - 1
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.coords.len()
    }

    /// Number of cells.
    pub fn num_cells(&self) -> usize {
        self.cell_types.len()
    }

    /// Type of cell `c`.
    pub fn cell_type(&self, c: usize) -> CellType {
        self.cell_types[c]
    }

    /// Node indices of cell `c`.
    pub fn cell_nodes(&self, c: usize) -> &[usize] {
        &self.cell_nodes[self.cell_ptr[c]..self.cell_ptr[c + 1]]
    }

    /// Iterator over `(cell index, type, nodes)`.
    pub fn cells(&self) -> impl Iterator<Item = (usize, CellType, &[usize])> + '_ {
        (0..self.num_cells()).map(move |c| (c, self.cell_types[c], self.cell_nodes(c)))
    }

    /// The distinct cell types present.
    pub fn cell_types_present(&self) -> Vec<CellType> {
        let mut t = self.cell_types.clone();
        t.sort_unstable();
        t.dedup();
        t
    }

    /// Adds cells to a named cell group (created if needed); keeps it sorted and unique.
    pub fn add_cells_to_group(&mut self, name: &str, cells: impl IntoIterator<Item = usize>) {
        let g = self.cell_groups.entry(name.to_string()).or_default();
        g.extend(cells);
        g.sort_unstable();
        g.dedup();
    }

    /// Adds facets to a named facet group (created if needed).
    pub fn add_facets_to_group(&mut self, name: &str, facets: impl IntoIterator<Item = Facet>) {
        self.facet_groups
            .entry(name.to_string())
            .or_default()
            .extend(facets);
    }

    /// Adds nodes to a named node group (created if needed); keeps it sorted and unique.
    pub fn add_nodes_to_group(&mut self, name: &str, nodes: impl IntoIterator<Item = usize>) {
        let g = self.node_groups.entry(name.to_string()).or_default();
        g.extend(nodes);
        g.sort_unstable();
        g.dedup();
    }

    fn unknown(kind: &'static str, name: &str, keys: impl Iterator<Item = String>) -> MeshError {
        let available: Vec<String> = keys.collect();
        MeshError::UnknownGroup {
            kind,
            name: name.to_string(),
            available: if available.is_empty() {
                "none".into()
            } else {
                available.join(", ")
            },
        }
    }

    /// The cells of a named group.
    pub fn cell_group(&self, name: &str) -> Result<&[usize], MeshError> {
        self.cell_groups
            .get(name)
            .map(|v| v.as_slice())
            .ok_or_else(|| Self::unknown("cell", name, self.cell_groups.keys().cloned()))
    }

    /// The facets of a named group.
    pub fn facet_group(&self, name: &str) -> Result<&[Facet], MeshError> {
        self.facet_groups
            .get(name)
            .map(|v| v.as_slice())
            .ok_or_else(|| Self::unknown("facet", name, self.facet_groups.keys().cloned()))
    }

    /// The nodes of a named group: a node group, or else the nodes of a facet group, or else the
    /// nodes of a cell group (sorted, unique).
    pub fn group_nodes(&self, name: &str) -> Result<Vec<usize>, MeshError> {
        if let Some(n) = self.node_groups.get(name) {
            return Ok(n.clone());
        }
        let mut nodes: Vec<usize> = if let Some(f) = self.facet_groups.get(name) {
            f.iter().flat_map(|f| f.nodes.iter().copied()).collect()
        } else if let Some(c) = self.cell_groups.get(name) {
            c.iter()
                .flat_map(|&c| self.cell_nodes(c).iter().copied())
                .collect()
        } else {
            let keys = self
                .node_groups
                .keys()
                .chain(self.facet_groups.keys())
                .chain(self.cell_groups.keys())
                .cloned();
            return Err(Self::unknown("node, facet or cell", name, keys));
        };
        nodes.sort_unstable();
        nodes.dedup();
        Ok(nodes)
    }

    /// Every facet that belongs to exactly one cell, oriented outward, in cell order.
    pub fn boundary_facets(&self) -> Vec<BoundaryFacet> {
        let mut count: HashMap<Vec<usize>, usize> = HashMap::new();
        let mut all = Vec::new();
        for (c, kind, nodes) in self.cells() {
            for (l, (fk, loc)) in kind.facets().iter().enumerate() {
                let f = Facet {
                    kind: *fk,
                    nodes: loc.iter().map(|&i| nodes[i]).collect(),
                };
                *count.entry(f.key()).or_insert(0) += 1;
                all.push(BoundaryFacet {
                    cell: c,
                    local: l,
                    facet: f,
                });
            }
        }
        all.retain(|b| count[&b.facet.key()] == 1);
        all
    }

    /// For each facet of a group, the cell it bounds and its local index there, with the facet
    /// re-oriented outward from that cell. A facet shared by two cells (an internal interface) is
    /// attached to the first cell found in `cells` (all cells if `None`).
    ///
    /// # Errors
    /// [`MeshError::Invalid`] if a facet bounds none of the cells.
    pub fn attach_facets(
        &self,
        facets: &[Facet],
        cells: Option<&[usize]>,
    ) -> Result<Vec<BoundaryFacet>, MeshError> {
        let mut index: HashMap<Vec<usize>, (usize, usize)> = HashMap::new();
        let all: Vec<usize>;
        let cells = match cells {
            Some(c) => c,
            None => {
                all = (0..self.num_cells()).collect();
                &all
            }
        };
        for &c in cells {
            let kind = self.cell_type(c);
            let nodes = self.cell_nodes(c);
            for (l, (fk, loc)) in kind.facets().iter().enumerate() {
                let f = Facet {
                    kind: *fk,
                    nodes: loc.iter().map(|&i| nodes[i]).collect(),
                };
                index.entry(f.key()).or_insert((c, l));
            }
        }
        facets
            .iter()
            .map(|f| {
                let (c, l) = *index.get(&f.key()).ok_or_else(|| {
                    MeshError::Invalid(format!(
                        "facet with nodes {:?} does not bound any cell of the selection",
                        f.nodes
                    ))
                })?;
                let (fk, loc) = self.cell_type(c).facets()[l];
                let nodes = self.cell_nodes(c);
                Ok(BoundaryFacet {
                    cell: c,
                    local: l,
                    facet: Facet {
                        kind: fk,
                        nodes: loc.iter().map(|&i| nodes[i]).collect(),
                    },
                })
            })
            .collect()
    }

    /// Checks that every cell and facet refers to existing nodes and that cells have the
    /// mesh's dimension.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.num_nodes();
        for (c, kind, nodes) in self.cells() {
            if kind.dim() != self.dim {
                return Err(MeshError::Invalid(format!(
                    "cell {c} is a {kind} in a {}D mesh",
                    self.dim
                )));
            }
            if let Some(&bad) = nodes.iter().find(|&&i| i >= n) {
                return Err(MeshError::NodeOutOfRange {
                    what: format!("cell {c}"),
                    node: bad,
                    num_nodes: n,
                });
            }
        }
        for (name, facets) in &self.facet_groups {
            for f in facets {
                if let Some(&bad) = f.nodes.iter().find(|&&i| i >= n) {
                    return Err(MeshError::NodeOutOfRange {
                        what: format!("a facet of group '{name}'"),
                        node: bad,
                        num_nodes: n,
                    });
                }
            }
        }
        Ok(())
    }

    /// Axis-aligned bounding box `(min, max)`.
    pub fn bounding_box(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in &self.coords {
            for d in 0..3 {
                lo[d] = lo[d].min(x[d]);
                hi[d] = hi[d].max(x[d]);
            }
        }
        (lo, hi)
    }
}
