//! Sub-meshes: the cells of some cell groups, with their nodes renumbered, and joining meshes.
//!
//! [`Mesh::extract`] is how one mesh is split into substructures: each substructure is the
//! sub-mesh of one (or several) cell groups; the returned new -> old node map relates the
//! sub-mesh's nodes to the parent's (two substructures sharing an interface share parent nodes
//! there). [`Mesh::append`] is the converse: it concatenates a mesh **without** merging nodes,
//! which is how two parts with coincident but distinct interface nodes are put in one mesh.

use std::collections::{BTreeMap, HashMap};

use crate::{Facet, Mesh, MeshError};

/// Sorted corner nodes of a facet (at most 4), padded: an orientation-free key.
type FacetKey = [usize; 4];

fn facet_key(corners: &[usize]) -> FacetKey {
    let mut k = [usize::MAX; 4];
    for (slot, &c) in k.iter_mut().zip(corners) {
        *slot = c;
    }
    k.sort_unstable();
    k
}

impl Mesh {
    /// The sub-mesh made of the cells of the named cell groups (their union), and the map from
    /// the sub-mesh's node indices to this mesh's (`map[new] = old`, increasing).
    ///
    /// - Cells keep their relative order; nodes keep their relative order.
    /// - Cell groups are restricted to the kept cells; groups left empty are dropped (the groups
    ///   asked for are always kept).
    /// - A facet of a facet group is kept when all its nodes are in the sub-mesh **and** it is a
    ///   facet of a kept cell; it is re-oriented outward from that cell when it bounds exactly one
    ///   kept cell (an interface facet of the parent becomes a boundary facet of the part).
    ///   Facet groups left empty are dropped.
    /// - Node groups are restricted to the sub-mesh's nodes; groups left empty are dropped.
    ///
    /// # Errors
    /// [`MeshError::UnknownGroup`] if a name is not a cell group; [`MeshError::Invalid`] if no
    /// name is given; the errors of [`Mesh::validate`] for an inconsistent mesh.
    pub fn extract(&self, cell_group_names: &[&str]) -> Result<(Mesh, Vec<usize>), MeshError> {
        self.extract_with_cells(cell_group_names)
            .map(|(m, nodes, _)| (m, nodes))
    }

    /// As [`Mesh::extract`], also returning the map from the sub-mesh's cells to this mesh's
    /// (`cells[new] = old`, increasing), e.g. to carry per-cell data into a substructure or back.
    ///
    /// # Errors
    /// As [`Mesh::extract`].
    pub fn extract_with_cells(
        &self,
        cell_group_names: &[&str],
    ) -> Result<(Mesh, Vec<usize>, Vec<usize>), MeshError> {
        if cell_group_names.is_empty() {
            return Err(MeshError::Invalid(
                "extract() needs at least one cell group name".into(),
            ));
        }
        self.validate()?;
        let mut keep = vec![false; self.num_cells()];
        for name in cell_group_names {
            for &c in self.cell_group(name)? {
                if c < keep.len() {
                    keep[c] = true;
                }
            }
        }
        let mut old_to_new = vec![usize::MAX; self.num_nodes()];
        for (c, k) in keep.iter().enumerate() {
            if *k {
                for &n in self.cell_nodes(c) {
                    if n < old_to_new.len() {
                        old_to_new[n] = 0;
                    }
                }
            }
        }
        let mut map = Vec::new();
        for (old, slot) in old_to_new.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = map.len();
                map.push(old);
            }
        }
        let mut sub = Mesh::new(self.dim);
        for &old in &map {
            sub.add_node(self.coords[old]);
        }
        let mut cell_old_to_new = vec![usize::MAX; self.num_cells()];
        let mut cell_map = Vec::new();
        for (c, kind, nodes) in self.cells() {
            if keep[c] {
                let n: Vec<usize> = nodes.iter().map(|&i| old_to_new[i]).collect();
                if n.contains(&usize::MAX) {
                    return Err(MeshError::NodeOutOfRange {
                        what: format!("cell {c}"),
                        node: *nodes.iter().max().unwrap_or(&0),
                        num_nodes: self.num_nodes(),
                    });
                }
                cell_old_to_new[c] = sub.add_cell(kind, &n);
                cell_map.push(c);
            }
        }
        for (name, cells) in &self.cell_groups {
            let kept: Vec<usize> = cells
                .iter()
                .filter(|&&c| c < keep.len() && keep[c])
                .map(|&c| cell_old_to_new[c])
                .collect();
            if !kept.is_empty() || cell_group_names.contains(&name.as_str()) {
                sub.add_cells_to_group(name, kept);
            }
        }
        // Group facets mapped to the new numbering (None if a node is not in the sub-mesh).
        let mapped: Vec<(&String, Vec<Option<Facet>>)> = self
            .facet_groups
            .iter()
            .map(|(name, facets)| {
                let v = facets
                    .iter()
                    .map(|f| {
                        let nodes: Option<Vec<usize>> = f
                            .nodes
                            .iter()
                            .map(|&n| old_to_new.get(n).copied().filter(|&m| m != usize::MAX))
                            .collect();
                        nodes
                            .filter(|n| n.len() >= f.kind.num_corners())
                            .map(|nodes| Facet {
                                kind: f.kind,
                                nodes,
                            })
                    })
                    .collect();
                (name, v)
            })
            .collect();
        // For each wanted key: how many kept cells it bounds, and its outward form in the first.
        let mut wanted: HashMap<FacetKey, (usize, Option<Facet>)> = HashMap::new();
        for (_, facets) in &mapped {
            for f in facets.iter().flatten() {
                wanted.insert(facet_key(&f.nodes[..f.kind.num_corners()]), (0, None));
            }
        }
        if !wanted.is_empty() {
            for (_, kind, nodes) in sub.cells() {
                for (fk, loc) in kind.facets() {
                    let corners: Vec<usize> =
                        loc[..fk.num_corners()].iter().map(|&i| nodes[i]).collect();
                    if let Some(w) = wanted.get_mut(&facet_key(&corners)) {
                        w.0 += 1;
                        if w.1.is_none() {
                            w.1 = Some(Facet {
                                kind: *fk,
                                nodes: loc.iter().map(|&i| nodes[i]).collect(),
                            });
                        }
                    }
                }
            }
        }
        for (name, facets) in mapped {
            let mut kept = Vec::new();
            for f in facets.into_iter().flatten() {
                match wanted.get(&facet_key(&f.nodes[..f.kind.num_corners()])) {
                    Some((1, Some(outward))) => kept.push(outward.clone()),
                    Some((n, _)) if *n >= 2 => kept.push(f),
                    _ => {}
                }
            }
            if !kept.is_empty() {
                sub.add_facets_to_group(name, kept);
            }
        }
        for (name, nodes) in &self.node_groups {
            let kept: Vec<usize> = nodes
                .iter()
                .filter_map(|&n| old_to_new.get(n).copied().filter(|&m| m != usize::MAX))
                .collect();
            if !kept.is_empty() {
                sub.add_nodes_to_group(name, kept);
            }
        }
        Ok((sub, map, cell_map))
    }

    /// Appends `other` to this mesh **without merging nodes** (coincident nodes stay distinct);
    /// groups of the same name are united. Returns the offset added to `other`'s node indices
    /// (its cells are numbered from the previous `num_cells()` on).
    ///
    /// # Errors
    /// [`MeshError::Invalid`] if the dimensions differ.
    pub fn append(&mut self, other: &Mesh) -> Result<usize, MeshError> {
        if self.dim != other.dim {
            return Err(MeshError::Invalid(format!(
                "cannot append a {}D mesh to a {}D mesh",
                other.dim, self.dim
            )));
        }
        let off = self.num_nodes();
        let coff = self.num_cells();
        for &x in &other.coords {
            self.add_node(x);
        }
        for (_, kind, nodes) in other.cells() {
            let n: Vec<usize> = nodes.iter().map(|&i| i + off).collect();
            self.add_cell(kind, &n);
        }
        let groups: BTreeMap<String, Vec<usize>> = other.cell_groups.clone();
        for (name, cells) in groups {
            self.add_cells_to_group(&name, cells.into_iter().map(|c| c + coff));
        }
        for (name, facets) in &other.facet_groups {
            self.add_facets_to_group(
                name,
                facets.iter().map(|f| Facet {
                    kind: f.kind,
                    nodes: f.nodes.iter().map(|&i| i + off).collect(),
                }),
            );
        }
        for (name, nodes) in &other.node_groups {
            self.add_nodes_to_group(name, nodes.iter().map(|&i| i + off));
        }
        Ok(off)
    }
}
