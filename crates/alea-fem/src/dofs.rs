//! Displacement constraints and the map from mesh-node displacements to free unknowns.
//!
//! Every constraint is `u(node) . d = g` for a unit direction `d`: a component constraint uses an
//! axis, a **normal (skew) constraint** on a facet group uses the nodal normal (area-averaged
//! facet normals), which is how symmetry sides of a disk sector that are not axis-aligned are
//! held. At each node the constraint directions are orthonormalised (Gram-Schmidt) into `Q`;
//! the node displacement is written `u = T u_free + u_p`, where the columns of `T` span the
//! orthogonal complement of `Q` and `u_p in span(Q)` satisfies every constraint. The reduced
//! stiffness is `T^T K T` and the reduced load `T^T (f - K u_p)`, assembled node block by node
//! block, so no global transformation matrix is ever built. Consistent repeated constraints are
//! accepted; contradictory ones are an error.

use alea_mesh::Mesh;
use alea_mesh::vec3::{dot, norm};

use crate::FemError;

/// A list of constraints `u(node) . dir = value`.
#[derive(Clone, Debug, Default)]
pub struct Constraints {
    items: Vec<(usize, [f64; 3], f64)>,
}

fn axis(c: usize) -> [f64; 3] {
    let mut d = [0.0; 3];
    d[c] = 1.0;
    d
}

impl Constraints {
    /// No constraints.
    pub fn new() -> Self {
        Self::default()
    }

    /// Imposes component `comp` (0 = x, 1 = y, 2 = z) of the displacement of every node of
    /// `group` (a node, facet or cell group) to `value(x)`.
    pub fn fix_component_with(
        &mut self,
        mesh: &Mesh,
        group: &str,
        comp: usize,
        value: impl Fn([f64; 3]) -> f64,
    ) -> Result<&mut Self, FemError> {
        if comp >= mesh.dim {
            return Err(FemError::Setup(format!(
                "component {comp} does not exist in a {}D mesh (group '{group}')",
                mesh.dim
            )));
        }
        for n in mesh.group_nodes(group)? {
            self.items.push((n, axis(comp), value(mesh.coords[n])));
        }
        Ok(self)
    }

    /// Imposes component `comp` of the nodes of `group` to a constant.
    pub fn fix_component(
        &mut self,
        mesh: &Mesh,
        group: &str,
        comp: usize,
        value: f64,
    ) -> Result<&mut Self, FemError> {
        self.fix_component_with(mesh, group, comp, |_| value)
    }

    /// Clamps every component of the nodes of `group` to zero.
    pub fn clamp(&mut self, mesh: &Mesh, group: &str) -> Result<&mut Self, FemError> {
        for c in 0..mesh.dim {
            self.fix_component(mesh, group, c, 0.0)?;
        }
        Ok(self)
    }

    /// Imposes the normal displacement `u . n = value` on the nodes of facet group `group`,
    /// with `n` the nodal normal (average of the adjacent facets' normals at the node, weighted
    /// by their measure factor there) and oriented like the facets (outward for boundary groups
    /// of generated meshes). Use it for symmetry planes that are not aligned with an axis.
    pub fn fix_normal(
        &mut self,
        mesh: &Mesh,
        group: &str,
        value: f64,
    ) -> Result<&mut Self, FemError> {
        let facets = mesh.facet_group(group)?;
        let mut normals: std::collections::BTreeMap<usize, [f64; 3]> = Default::default();
        for f in facets {
            let coords: Vec<[f64; 3]> = f.nodes.iter().map(|&n| mesh.coords[n]).collect();
            // The facet's normal at each of its nodes (not at its centre: on a curved group
            // the end nodes would get a normal tilted by half a facet's turning angle).
            let at_nodes = crate::reference::node_coords(f.kind);
            for (&n, &xi) in f.nodes.iter().zip(&at_nodes) {
                let g = crate::kinematics::facet_geometry(f.kind, &coords, xi);
                let e = normals.entry(n).or_insert([0.0; 3]);
                for k in 0..3 {
                    e[k] += g.normal[k] * g.jac;
                }
            }
        }
        for (n, v) in normals {
            let len = norm(&v);
            if len == 0.0 {
                return Err(FemError::Setup(format!(
                    "normal of facet group '{group}' vanishes at node {n}"
                )));
            }
            self.items
                .push((n, [v[0] / len, v[1] / len, v[2] / len], value));
        }
        Ok(self)
    }

    /// Imposes `u . dir = value` at a single node.
    pub fn fix_direction(&mut self, node: usize, dir: [f64; 3], value: f64) -> &mut Self {
        let len = norm(&dir);
        self.items
            .push((node, [dir[0] / len, dir[1] / len, dir[2] / len], value));
        self
    }

    /// The constraints of the nodes kept by `map` (`map(old) = Some(new)`), renumbered: the
    /// constraints of a part of the mesh (module `alea_latin::split`).
    pub fn restricted(&self, map: impl Fn(usize) -> Option<usize>) -> Constraints {
        Constraints {
            items: self
                .items
                .iter()
                .filter_map(|&(n, d, v)| map(n).map(|m| (m, d, v)))
                .collect(),
        }
    }

    /// Number of individual constraints.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
}

/// Per-node reduction `u = T u_free + u_p` and numbering of the free unknowns.
#[derive(Clone, Debug)]
pub struct DofMap {
    /// Spatial dimension.
    pub dim: usize,
    /// First free unknown of each node (the node's unknowns are contiguous).
    first: Vec<usize>,
    /// Number of free unknowns of each node (0..=dim).
    nfree: Vec<u8>,
    /// Free directions of constrained nodes (rows); `None` for unconstrained nodes (identity).
    basis: Vec<Option<[[f64; 3]; 3]>>,
    /// Prescribed part `u_p` of each node's displacement.
    prescribed: Vec<[f64; 3]>,
    n_free: usize,
}

impl DofMap {
    /// Builds the map for `num_nodes` nodes of dimension `dim`.
    ///
    /// # Errors
    /// [`FemError::ConflictingConstraints`] if a node's constraints contradict each other.
    pub fn new(num_nodes: usize, dim: usize, constraints: &Constraints) -> Result<Self, FemError> {
        let mut per_node: Vec<Vec<([f64; 3], f64)>> = vec![Vec::new(); num_nodes];
        for &(n, d, v) in &constraints.items {
            if n >= num_nodes {
                return Err(FemError::Setup(format!(
                    "constraint on node {n} out of range"
                )));
            }
            per_node[n].push((d, v));
        }
        let mut first = Vec::with_capacity(num_nodes);
        let mut nfree = Vec::with_capacity(num_nodes);
        let mut basis = Vec::with_capacity(num_nodes);
        let mut prescribed = Vec::with_capacity(num_nodes);
        let mut next = 0;
        for (node, cons) in per_node.iter().enumerate() {
            first.push(next);
            if cons.is_empty() {
                nfree.push(dim as u8);
                basis.push(None);
                prescribed.push([0.0; 3]);
                next += dim;
                continue;
            }
            let mut q: Vec<[f64; 3]> = Vec::new();
            let mut p = [0.0; 3];
            for &(d, val) in cons {
                let mut v = d;
                for qi in &q {
                    let c = dot(&d, qi);
                    for k in 0..3 {
                        v[k] -= c * qi[k];
                    }
                }
                let norm = dot(&v, &v).sqrt();
                if norm < 1e-8 {
                    let have = dot(&p, &d);
                    if (have - val).abs() > 1e-9 * (1.0 + val.abs().max(have.abs())) {
                        return Err(FemError::ConflictingConstraints {
                            node,
                            detail: format!(
                                "direction {d:?} is already imposed to {have}, now asked {val}"
                            ),
                        });
                    }
                    continue;
                }
                let qn = [v[0] / norm, v[1] / norm, v[2] / norm];
                let alpha = (val - dot(&p, &d)) / dot(&qn, &d);
                for k in 0..3 {
                    p[k] += alpha * qn[k];
                }
                q.push(qn);
            }
            // Complete Q to an orthonormal basis of R^dim: the new vectors are the free ones.
            let mut free = [[0.0; 3]; 3];
            let mut nf = 0;
            for c in 0..dim {
                let mut v = axis(c);
                for qi in q.iter().chain(free[..nf].iter()) {
                    let s = dot(&v, qi);
                    for k in 0..3 {
                        v[k] -= s * qi[k];
                    }
                }
                let norm = dot(&v, &v).sqrt();
                if norm > 1e-6 {
                    free[nf] = [v[0] / norm, v[1] / norm, v[2] / norm];
                    nf += 1;
                }
            }
            debug_assert_eq!(nf + q.len(), dim);
            nfree.push(nf as u8);
            basis.push(Some(free));
            prescribed.push(p);
            next += nf;
        }
        Ok(DofMap {
            dim,
            first,
            nfree,
            basis,
            prescribed,
            n_free: next,
        })
    }

    /// Builds the map for a mesh.
    pub fn for_mesh(mesh: &Mesh, constraints: &Constraints) -> Result<Self, FemError> {
        Self::new(mesh.num_nodes(), mesh.dim, constraints)
    }

    /// Number of free unknowns.
    pub fn num_free(&self) -> usize {
        self.n_free
    }

    /// Number of nodes.
    pub fn num_nodes(&self) -> usize {
        self.first.len()
    }

    /// Free unknowns of `node` (a range, possibly empty).
    pub fn node_dofs(&self, node: usize) -> std::ops::Range<usize> {
        self.first[node]..self.first[node] + self.nfree[node] as usize
    }

    /// True if `node` has no constraint.
    pub fn is_free_node(&self, node: usize) -> bool {
        self.basis[node].is_none()
    }

    /// Prescribed displacement part of `node`.
    pub fn prescribed(&self, node: usize) -> [f64; 3] {
        self.prescribed[node]
    }

    /// For each free unknown, the node it belongs to (for block orderings).
    pub fn node_of_dof(&self) -> Vec<usize> {
        let mut v = vec![0; self.n_free];
        for n in 0..self.num_nodes() {
            for d in self.node_dofs(n) {
                v[d] = n;
            }
        }
        v
    }

    /// Full node-major displacement `u = T u_free + u_p` from free unknowns.
    pub fn expand(&self, free: &[f64]) -> Vec<f64> {
        let d = self.dim;
        let mut u = vec![0.0; self.num_nodes() * d];
        for n in 0..self.num_nodes() {
            let r = self.node_dofs(n);
            match &self.basis[n] {
                None => u[n * d..n * d + d].copy_from_slice(&free[r]),
                Some(b) => {
                    for c in 0..d {
                        u[n * d + c] = self.prescribed[n][c];
                    }
                    for (i, g) in r.enumerate() {
                        for c in 0..d {
                            u[n * d + c] += b[i][c] * free[g];
                        }
                    }
                }
            }
        }
        u
    }

    /// Adds `T_n^T v` (a force-like vector at `node`) into the free-unknown vector `out`.
    #[inline]
    pub fn add_node_force(&self, node: usize, v: &[f64; 3], out: &mut [f64]) {
        let r = self.node_dofs(node);
        match &self.basis[node] {
            None => {
                for (c, g) in r.enumerate() {
                    out[g] += v[c];
                }
            }
            Some(b) => {
                for (i, g) in r.enumerate() {
                    out[g] += (0..self.dim).map(|c| b[i][c] * v[c]).sum::<f64>();
                }
            }
        }
    }

    /// Displacement `T_n u_free + u_p` of `node` (components beyond `dim` are 0).
    #[inline]
    pub fn node_displacement(&self, node: usize, free: &[f64]) -> [f64; 3] {
        let r = self.node_dofs(node);
        let mut u = [0.0; 3];
        match &self.basis[node] {
            None => {
                for (c, g) in r.enumerate() {
                    u[c] = free[g];
                }
            }
            Some(b) => {
                u = self.prescribed[node];
                for (i, g) in r.enumerate() {
                    for c in 0..self.dim {
                        u[c] += b[i][c] * free[g];
                    }
                }
            }
        }
        u
    }

    /// The part of `v` in the constrained directions of `node`: `v` minus its projection on the
    /// node's free directions (zero for an unconstrained node; components beyond `dim` are
    /// kept, they are never free).
    pub fn constrained_part(&self, node: usize, v: [f64; 3]) -> [f64; 3] {
        let Some(b) = &self.basis[node] else {
            let mut out = [0.0; 3];
            out[self.dim..].copy_from_slice(&v[self.dim..]);
            return out;
        };
        let mut out = v;
        for bi in &b[..self.nfree[node] as usize] {
            let s = dot(bi, &v);
            for c in 0..3 {
                out[c] -= s * bi[c];
            }
        }
        out
    }

    /// Adds `s I` (an isotropic node block, e.g. a lumped interface stiffness `k m_i`) at
    /// `node` to `a`: on the free unknowns this is `s T_n^T T_n = s I_r` (orthonormal `T_n`).
    pub fn add_node_diagonal(&self, node: usize, s: f64, a: &mut crate::SymCsc) {
        for g in self.node_dofs(node) {
            a.add(g, g, s);
        }
    }

    /// Adds `s T_a^T T_b` (an isotropic coupling block between two distinct nodes, e.g. a mortar
    /// interface stiffness `k m_p N_a N_b`) to `a`; the matrix is symmetric, so this also sets
    /// the `(b, a)` block. Both nodes' unknowns must be coupled in the pattern.
    ///
    /// # Panics
    /// If `node_a == node_b` (use [`DofMap::add_node_diagonal`]) or an entry is not in the
    /// pattern.
    pub fn add_node_coupling(&self, node_a: usize, node_b: usize, s: f64, a: &mut crate::SymCsc) {
        assert_ne!(node_a, node_b, "coupling block of a node with itself");
        let frame = |n: usize| -> [[f64; 3]; 3] {
            match &self.basis[n] {
                None => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                Some(b) => *b,
            }
        };
        let (ba, bb) = (frame(node_a), frame(node_b));
        for (i, ga) in self.node_dofs(node_a).enumerate() {
            for (j, gb) in self.node_dofs(node_b).enumerate() {
                let v = (0..self.dim).map(|c| ba[i][c] * bb[j][c]).sum::<f64>();
                if v != 0.0 {
                    a.add(ga, gb, s * v);
                }
            }
        }
    }

    /// Free-unknown vector `T^T f` of a full node-major vector (loads, not displacements).
    pub fn reduce(&self, full: &[f64]) -> Vec<f64> {
        let d = self.dim;
        let mut out = vec![0.0; self.n_free];
        for n in 0..self.num_nodes() {
            let r = self.node_dofs(n);
            match &self.basis[n] {
                None => out[r].copy_from_slice(&full[n * d..n * d + d]),
                Some(b) => {
                    for (i, g) in r.enumerate() {
                        out[g] = (0..d).map(|c| b[i][c] * full[n * d + c]).sum();
                    }
                }
            }
        }
        out
    }

    /// Reduces an element-like block `ke` (row-major, node-major dofs of `nodes`) and its
    /// prescribed-displacement load: returns the free unknowns of the block (`usize::MAX` never
    /// occurs; constrained directions are simply absent), writes `T^T ke T` into `ke_red` and
    /// `-T^T ke u_p` into `f_red`.
    pub fn reduce_block(
        &self,
        nodes: &[usize],
        ke: &[f64],
        dofs: &mut Vec<usize>,
        ke_red: &mut Vec<f64>,
        f_red: &mut Vec<f64>,
    ) {
        let d = self.dim;
        let m = nodes.len() * d;
        dofs.clear();
        for &n in nodes {
            dofs.extend(self.node_dofs(n));
        }
        let mr = dofs.len();
        ke_red.clear();
        f_red.clear();
        f_red.resize(mr, 0.0);
        if nodes.iter().all(|&n| self.basis[n].is_none()) {
            ke_red.extend_from_slice(&ke[..m * m]);
            return;
        }
        // Dense T (m x mr), column-major by reduced index.
        let mut t = vec![0.0; m * mr];
        let mut up = vec![0.0; m];
        let mut col = 0;
        for (a, &n) in nodes.iter().enumerate() {
            let nf = self.nfree[n] as usize;
            match &self.basis[n] {
                None => {
                    for c in 0..d {
                        t[(col + c) * m + a * d + c] = 1.0;
                    }
                }
                Some(b) => {
                    for i in 0..nf {
                        for c in 0..d {
                            t[(col + i) * m + a * d + c] = b[i][c];
                        }
                    }
                    up[a * d..a * d + d].copy_from_slice(&self.prescribed[n][..d]);
                }
            }
            col += nf;
        }
        // kt = ke T (m x mr), then ke_red = T^T kt.
        let mut kt = vec![0.0; m * mr];
        for j in 0..mr {
            let tj = &t[j * m..(j + 1) * m];
            for r in 0..m {
                let row = &ke[r * m..(r + 1) * m];
                kt[j * m + r] = row.iter().zip(tj).map(|(a, b)| a * b).sum();
            }
        }
        ke_red.resize(mr * mr, 0.0);
        for i in 0..mr {
            let ti = &t[i * m..(i + 1) * m];
            for j in 0..mr {
                ke_red[i * mr + j] = ti
                    .iter()
                    .zip(&kt[j * m..(j + 1) * m])
                    .map(|(a, b)| a * b)
                    .sum();
            }
        }
        if up.iter().any(|&v| v != 0.0) {
            let mut kup = vec![0.0; m];
            for r in 0..m {
                kup[r] = (0..m).map(|c| ke[r * m + c] * up[c]).sum();
            }
            for i in 0..mr {
                f_red[i] = -t[i * m..(i + 1) * m]
                    .iter()
                    .zip(&kup)
                    .map(|(a, b)| a * b)
                    .sum::<f64>();
            }
        }
    }
}
