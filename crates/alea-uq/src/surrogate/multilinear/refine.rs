//! Refinement of the stochastic mesh: isotropic splits, centred and direction-by-direction
//! (anisotropic) refinement, a run at a point, promotion of interpolated nodes, and the
//! classification of the interpolated nodes that keeps the surrogate continuous.

use super::*;

impl StochasticMesh {
    /// Split the given leaf cells into `2^d` children each. Returns the nodes that became runs,
    /// in increasing run index.
    ///
    /// # Errors
    /// If a cell is not a leaf or is already at [`MAX_LEVEL`].
    pub fn refine(&mut self, cells: &[CellId]) -> Result<Vec<NewRun>> {
        let full = self.full_mask();
        let mut todo: Vec<CellId> = cells.to_vec();
        todo.sort_unstable();
        todo.dedup();
        for &c in &todo {
            if !self.is_leaf(c) {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is not a leaf"),
                });
            }
            if self.cells[c].level >= MAX_LEVEL {
                return Err(invalid(
                    "stochastic mesh",
                    "cell level",
                    "below the maximum",
                    self.cells[c].level as f64,
                ));
            }
        }
        for &c in &todo {
            // New nodes: o + half * m, m in {0, 1, 2}^d (placeholder kind, classified below).
            let grid = self.split_grid(c, full);
            self.split_cell(c, full);
            for (key, _, _) in grid {
                self.nodes
                    .entry(key)
                    .or_insert(NodeKind::Hanging(usize::MAX));
            }
        }
        // Anisotropic meshes: split (interpolated) where faces cross (see `crossings`).
        let mut split = todo.clone();
        self.resolve_crossings(&mut split)?;
        // Reclassify every non-run node; nodes with no master become runs.
        let mut pending: Vec<Key> = self
            .nodes
            .iter()
            .filter(|(_, k)| matches!(k, NodeKind::Hanging(_)))
            .map(|(key, _)| *key)
            .collect();
        pending.sort_unstable();
        let mut new_runs = Vec::new();
        for key in pending {
            match self.master_of(&key) {
                Some(mc) => {
                    self.nodes.insert(key, NodeKind::Hanging(mc));
                }
                None => {
                    let run = self.add_run(key);
                    new_runs.push(NewRun {
                        run,
                        point: self.run_point(run).to_vec(),
                    });
                }
            }
        }
        if self.aniso {
            self.classify_interpolated(&split)?;
        }
        self.rebuild()?;
        Ok(new_runs)
    }

    /// Checks that `mask` is a non-empty set of the mesh's directions and that leaf `c` is below
    /// [`MAX_LEVEL`] in each of them.
    fn check_split(&self, c: CellId, mask: u32) -> Result<()> {
        let d = self.d;
        if mask == 0 || mask >> d != 0 {
            return Err(invalid(
                "stochastic mesh",
                "split mask",
                "a non-empty set of directions of the mesh",
                mask as f64,
            ));
        }
        if let Some(j) =
            (0..d).find(|&j| (mask >> j) & 1 == 1 && self.cells[c].levels[j] >= MAX_LEVEL)
        {
            return Err(invalid(
                "stochastic mesh",
                "cell level",
                "below the maximum",
                self.cells[c].levels[j] as f64,
            ));
        }
        Ok(())
    }

    /// Splits leaf `c` along the directions of `mask` and classifies the nodes of the split
    /// ([`StochasticMesh::split_grid`]): if `centre_runs`, the centres are left as they are and
    /// returned (the caller makes them runs); every other node that is neither a corner of `c`,
    /// a run nor already interpolated for good is interpolated from `c` for good.
    pub(super) fn split_interpolated(
        &mut self,
        c: CellId,
        mask: u8,
        centre_runs: bool,
    ) -> Result<Vec<Key>> {
        if !self.is_leaf(c) {
            return Err(UqError::Invalid {
                what: "stochastic mesh",
                message: format!("cell {c} is not a leaf"),
            });
        }
        self.check_split(c, mask as u32)?;
        let grid = self.split_grid(c, mask);
        self.split_cell(c, mask);
        self.aniso |= mask != self.full_mask();
        let mut centres = Vec::new();
        for (key, centre, corner) in grid {
            if centre && centre_runs {
                centres.push(key);
            } else if !corner {
                match self.nodes.get(&key) {
                    Some(NodeKind::Run(_)) | Some(NodeKind::Fixed(_)) => {}
                    _ => {
                        self.nodes.insert(key, NodeKind::Fixed(c));
                    }
                }
            }
        }
        Ok(centres)
    }

    /// Leaves whose interior meets the open box `(lo, hi)` (key units), appended to `out`.
    pub(super) fn leaves_in(&self, lo: &Key, hi: &Key, out: &mut Vec<usize>) {
        let d = self.d;
        let s = 1u64 << MAX_LEVEL;
        let mut rlo = [0usize; MAX_DIM];
        let mut rhi = [0usize; MAX_DIM];
        for j in 0..d {
            if hi[j] <= lo[j] {
                return;
            }
            rlo[j] = (lo[j] / s) as usize;
            rhi[j] = (((hi[j] - 1) / s) as usize).min(self.roots[j] - 1);
            if rlo[j] > rhi[j] {
                return;
            }
        }
        let mut stack = Vec::new();
        let mut idx = rlo;
        'roots: loop {
            let mut root = 0usize;
            let mut stride = 1usize;
            for j in 0..d {
                root += idx[j] * stride;
                stride *= self.roots[j];
            }
            stack.push(root);
            for j in 0..d {
                idx[j] += 1;
                if idx[j] <= rhi[j] {
                    continue 'roots;
                }
                idx[j] = rlo[j];
            }
            break;
        }
        while let Some(c) = stack.pop() {
            let o = self.cells[c].origin;
            if !(0..d).all(|j| o[j] < hi[j] && o[j] + self.size(c, j) > lo[j]) {
                continue;
            }
            match self.cells[c].first_child {
                None => out.push(c),
                Some(first) => {
                    let n = 1usize << self.split_mask[c].count_ones();
                    stack.extend((first..first + n).rev());
                }
            }
        }
    }

    /// Points where two adjacent leaves hold a point of their common boundary inside faces that
    /// do not contain one another (possible with anisotropic cells when the leaves share a
    /// region of dimension 2 or more: a face in 3D, also a 2D region in 4D): no node value can
    /// match both interpolants there. Returns, per leaf to split (the newer of the two), the
    /// directions in which its face through the point exceeds the other's, so that splitting
    /// along them makes the point its corner (sorted by leaf, deterministic).
    /// Only pairs with a leaf of `from` are examined.
    pub(super) fn crossings(&self, from: &[usize]) -> Vec<(usize, u8)> {
        let d = self.d;
        let mut out: Vec<(usize, u8)> = Vec::new();
        let mut across = Vec::new();
        for &a in from {
            let oa = self.cells[a].origin;
            let fa = self.far_corner(a);
            // The regions around `a`: per direction below (0), along (1) or above (2) it.
            'patterns: for pattern in 0..3usize.pow(d as u32) {
                let mut side = [0usize; MAX_DIM];
                let mut r = pattern;
                for v in side.iter_mut().take(d) {
                    *v = r % 3;
                    r /= 3;
                }
                let along = side[..d].iter().filter(|&&v| v == 1).count();
                if along < 2 || along == d {
                    continue;
                }
                let (mut lo, mut hi) = (oa, fa);
                for i in 0..d {
                    let span = (self.roots[i] as u64) << MAX_LEVEL;
                    match side[i] {
                        0 if oa[i] == 0 => continue 'patterns,
                        0 => (lo[i], hi[i]) = (oa[i] - 1, oa[i]),
                        2 if fa[i] == span => continue 'patterns,
                        2 => (lo[i], hi[i]) = (fa[i], fa[i] + 1),
                        _ => {}
                    }
                }
                across.clear();
                self.leaves_in(&lo, &hi, &mut across);
                for &b in &across {
                    let ob = self.cells[b].origin;
                    let fb = self.far_corner(b);
                    for corner in 0..(1usize << d) {
                        if (0..d).any(|i| side[i] != 1 && (corner >> i) & 1 == 1) {
                            continue;
                        }
                        let mut q = [0u64; MAX_DIM];
                        for i in 0..d {
                            q[i] = match side[i] {
                                0 => oa[i],
                                2 => fa[i],
                                _ if (corner >> i) & 1 == 1 => fa[i].min(fb[i]),
                                _ => oa[i].max(ob[i]),
                            };
                        }
                        let (ea, eb) = (self.extent(a, &q), self.extent(b, &q));
                        let ge = (0..d).all(|i| ea[i] >= eb[i]);
                        let le = (0..d).all(|i| ea[i] <= eb[i]);
                        if ge || le {
                            continue;
                        }
                        let (l, el, eo) = if b > a { (b, eb, ea) } else { (a, ea, eb) };
                        let mask = (0..d)
                            .filter(|&i| el[i] > eo[i])
                            .fold(0u8, |m, i| m | (1 << i));
                        match out.iter_mut().find(|e| e.0 == l) {
                            Some(e) => e.1 |= mask,
                            None => out.push((l, mask)),
                        }
                    }
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// The leaves below (or equal to) the given cells, in increasing id order.
    pub(super) fn leaves_below(&self, cells: &[CellId]) -> Vec<CellId> {
        let mut out = Vec::new();
        let mut stack: Vec<CellId> = cells.to_vec();
        while let Some(c) = stack.pop() {
            match self.cells[c].first_child {
                None => out.push(c),
                Some(first) => {
                    stack.extend(first..first + (1usize << self.split_mask[c].count_ones()))
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Splits leaves (interpolated nodes only) until no [`StochasticMesh::crossings`] remain;
    /// the split cells are appended to `split`.
    pub(super) fn resolve_crossings(&mut self, split: &mut Vec<CellId>) -> Result<()> {
        if !self.aniso {
            return Ok(());
        }
        // A crossing involves a leaf made by the splits: look from those only.
        let mut from = self.leaves_below(split);
        loop {
            let todo = self.crossings(&from);
            if todo.is_empty() {
                return Ok(());
            }
            let cells: Vec<CellId> = todo.iter().map(|e| e.0).collect();
            for (l, mask) in todo {
                self.split_interpolated(l, mask, false)?;
                split.push(l);
            }
            from = self.leaves_below(&cells);
        }
    }

    /// Re-classifies the hanging nodes after splits and rebuilds the weights. A hanging node
    /// left without a leaf master lies on a split cell: it is interpolated from it for good.
    ///
    /// On a mesh with anisotropic splits, the interpolated-for-good nodes are re-classified as
    /// well: a node inside a face of a leaf must take that leaf's value for the surrogate to be
    /// continuous (on isotropic meshes this holds by construction), so it hangs on the leaf;
    /// a hanging node whose master leaf was split is interpolated from that cell for good (its
    /// value is unchanged).
    pub(super) fn settle(&mut self, split: &[CellId]) -> Result<()> {
        let mut split = split.to_vec();
        self.resolve_crossings(&mut split)?;
        self.classify_interpolated(&split)?;
        self.rebuild()
    }

    pub(super) fn classify_interpolated(&mut self, split: &[CellId]) -> Result<()> {
        let aniso = self.aniso;
        let mut pending: Vec<Key> = self
            .nodes
            .iter()
            .filter(|(_, k)| match k {
                NodeKind::Hanging(_) => true,
                NodeKind::Fixed(_) => aniso,
                NodeKind::Run(_) => false,
            })
            .map(|(key, _)| *key)
            .collect();
        pending.sort_unstable();
        for key in pending {
            let old = self.nodes[&key];
            let kind = match self.master_of(&key) {
                Some(mc) => NodeKind::Hanging(mc),
                None if aniso && matches!(old, NodeKind::Fixed(_)) => old,
                None if aniso
                    && matches!(old, NodeKind::Hanging(m) if m < self.cells.len() && !self.is_leaf(m)) =>
                {
                    let NodeKind::Hanging(m) = old else {
                        unreachable!()
                    };
                    NodeKind::Fixed(m)
                }
                None => {
                    let owner = split.iter().copied().find(|&c| {
                        let o = self.cells[c].origin;
                        (0..self.d).all(|j| key[j] >= o[j] && key[j] <= o[j] + self.size(c, j))
                    });
                    match owner {
                        Some(c) => NodeKind::Fixed(c),
                        None => {
                            return Err(UqError::Invalid {
                                what: "stochastic mesh",
                                message: "internal error: a hanging node lost its master".into(),
                            });
                        }
                    }
                }
            };
            self.nodes.insert(key, kind);
        }
        Ok(())
    }

    /// Refines leaf cells **at their centres** (the thesis's improved criterion, 4.2.2.2, and
    /// the structured stochastic mesh of 4.2.1 b): each cell is split into `2^d` children, its
    /// centre becomes a run, and every other new node is interpolated from the cell (not run).
    /// The surrogate is unchanged outside the cells and, inside, changes only through the
    /// centres' values; it stays continuous. Returns one new run per cell, in cell order.
    ///
    /// # Errors
    /// If a cell is not a leaf or is already at [`MAX_LEVEL`].
    pub fn refine_centred(&mut self, cells: &[CellId]) -> Result<Vec<NewRun>> {
        let mut todo: Vec<CellId> = cells.to_vec();
        todo.sort_unstable();
        todo.dedup();
        for &c in &todo {
            if !self.is_leaf(c) || self.cells[c].level >= MAX_LEVEL {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is not a leaf below the maximum level"),
                });
            }
        }
        let full = self.full_mask();
        let mut new_runs = Vec::with_capacity(todo.len());
        for &c in &todo {
            for key in self.split_interpolated(c, full, true)? {
                let run = self.add_run(key);
                new_runs.push(NewRun {
                    run,
                    point: self.run_point(run).to_vec(),
                });
            }
        }
        self.settle(&todo)?;
        Ok(new_runs)
    }

    /// Splits each leaf `cell` only along the directions whose bit is set in `mask` (bit j:
    /// direction j; `mask != 0`, only bits below `d`) into `2^popcount(mask)` children, and
    /// makes runs of the **centres** of the split: the new nodes at the cell's midpoint in every
    /// split direction and at a corner value in every other direction (`2^(d - popcount)` of
    /// them; the midpoint of the cell when the mask is full). Every other new node is
    /// interpolated from the cell for good (as [`StochasticMesh::refine_centred`], which this is
    /// with a full mask: same runs, same order, same weights).
    ///
    /// A centre on a face of the cell must be a corner of every leaf around it to be a run (else
    /// the surrogate would jump there): a leaf across that holds it inside a face is split
    /// first, with interpolated nodes only, along the directions in which it holds it inside,
    /// until it is a corner (as [`StochasticMesh::refine_at_point`] does). A centre that is
    /// already a run (shared with a neighbour split the same way) is not returned again; one that
    /// was interpolated becomes a run. On a mesh with anisotropic cells, interpolated nodes inside
    /// a face of a leaf hang on it and crossing faces are split (see the module documentation),
    /// so the surrogate can also change on the leaves next to the refined cells: it stays
    /// continuous.
    ///
    /// Returns the nodes that became runs, in increasing run index.
    ///
    /// # Errors
    /// If a cell is not a leaf, is listed twice with different masks, a mask is empty or has a
    /// bit at or above `d`, or the cell is already at [`MAX_LEVEL`] in a split direction. The
    /// mesh is unchanged then.
    pub fn refine_directions(&mut self, cells: &[(CellId, u32)]) -> Result<Vec<NewRun>> {
        let d = self.d;
        let mut todo: Vec<(CellId, u32)> = cells.to_vec();
        todo.sort_unstable();
        todo.dedup();
        for (i, &(c, mask)) in todo.iter().enumerate() {
            if !self.is_leaf(c) {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is not a leaf"),
                });
            }
            if i > 0 && todo[i - 1].0 == c {
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!("cell {c} is listed with two masks"),
                });
            }
            self.check_split(c, mask)?;
        }
        let mut split: Vec<CellId> = Vec::with_capacity(todo.len());
        let mut centres = Vec::new();
        for &(c, mask) in &todo {
            centres.extend(self.split_interpolated(c, mask as u8, true)?);
            split.push(c);
        }
        let mut new_runs = Vec::with_capacity(centres.len());
        for key in centres {
            if matches!(self.nodes.get(&key), Some(NodeKind::Run(_))) {
                continue;
            }
            // Split the leaves that hold the centre inside a face until it is their corner.
            while let Some(l) = (0..(1usize << d))
                .filter_map(|signs| self.locate_key(&key, signs))
                .find(|&l| !self.is_corner(l, &key))
            {
                let o = self.cells[l].origin;
                let mut mask = 0u8;
                for j in 0..d {
                    if key[j] != o[j] && key[j] != o[j] + self.size(l, j) {
                        mask |= 1 << j;
                    }
                }
                self.split_interpolated(l, mask, false)?;
                split.push(l);
            }
            let run = self.add_run(key);
            new_runs.push(NewRun {
                run,
                point: self.run_point(run).to_vec(),
            });
        }
        self.settle(&split)?;
        Ok(new_runs)
    }

    /// One new run at `xi` (the thesis's maximum-error criterion, 4.2.2.1): the leaves around
    /// `xi` are split, with interpolated nodes only, until `xi` is the centre of a leaf, which
    /// is then refined at its centre. `xi` must be a dyadic point strictly inside a leaf, such
    /// as those of [`StochasticMesh::sub_cell_centres`].
    ///
    /// # Errors
    /// If `xi` is outside the box, not a dyadic point of the mesh, or already a node.
    pub fn refine_at_point(&mut self, xi: &[f64]) -> Result<NewRun> {
        let d = self.d;
        if xi.len() != d {
            return Err(invalid(
                "stochastic mesh",
                "point dimension",
                "the mesh's",
                xi.len() as f64,
            ));
        }
        let mut key = [0u64; MAX_DIM];
        for j in 0..d {
            let span = ((self.roots[j] as u64) << MAX_LEVEL) as f64;
            let t = (xi[j] - self.lo[j]) / (self.hi[j] - self.lo[j]) * span;
            if !(t > 0.0 && t < span) {
                return Err(invalid(
                    "stochastic mesh",
                    "point",
                    "strictly inside the box",
                    xi[j],
                ));
            }
            key[j] = t.round() as u64;
            if (t - key[j] as f64).abs() > 1e-6 {
                return Err(invalid(
                    "stochastic mesh",
                    "point",
                    "a dyadic point of the mesh",
                    xi[j],
                ));
            }
        }
        if self.nodes.contains_key(&key) {
            return Err(UqError::Invalid {
                what: "stochastic mesh",
                message: format!("{xi:?} is already a node of the mesh"),
            });
        }
        let mut split = Vec::new();
        let mut runs = Vec::new();
        loop {
            let p = self.key_point(&key);
            let c = self.locate(&p).ok_or_else(|| UqError::Invalid {
                what: "stochastic mesh",
                message: format!("{xi:?} is outside the mesh"),
            })?;
            let o = self.cells[c].origin;
            let half: Vec<u64> = (0..d).map(|j| self.size(c, j) / 2).collect();
            let is_centre = (0..d).all(|j| key[j] == o[j] + half[j]);
            if half.contains(&0) {
                return Err(invalid(
                    "stochastic mesh",
                    "point",
                    "a dyadic point of the mesh",
                    xi[0],
                ));
            }
            split.push(c);
            let full = self.full_mask();
            for centre in self.split_interpolated(c, full, is_centre)? {
                let run = self.add_run(centre);
                runs.push(NewRun {
                    run,
                    point: self.run_point(run).to_vec(),
                });
            }
            if is_centre {
                break;
            }
            if (0..d).any(|j| key[j] == o[j] + half[j]) {
                // On a split plane but not the centre: never a leaf centre below.
                return Err(UqError::Invalid {
                    what: "stochastic mesh",
                    message: format!(
                        "{xi:?} lies on a face of the refined cells, not a cell centre"
                    ),
                });
            }
        }
        self.settle(&split)?;
        runs.pop().ok_or_else(|| UqError::Invalid {
            what: "stochastic mesh",
            message: "internal error: no run created".into(),
        })
    }

    /// Every node that is not a run (interpolated for good by a centred refinement, or hanging
    /// on a coarser leaf), in increasing key order (deterministic), with the coarsest leaf that
    /// holds it without having it as a corner: `None` when [`StochasticMesh::promote`] can make
    /// it a run now, else the leaf to refine first (its value follows that leaf's interpolant,
    /// which a run there would break).
    pub fn interpolated_nodes(&self) -> Vec<(Vec<f64>, Option<CellId>)> {
        let mut keys: Vec<Key> = self
            .nodes
            .iter()
            .filter(|(_, kind)| !matches!(kind, NodeKind::Run(_)))
            .map(|(key, _)| *key)
            .collect();
        keys.sort_unstable();
        keys.iter()
            .map(|k| (self.key_point(k), self.master_of(k)))
            .collect()
    }

    /// Makes the interpolated node at `xi` (one of [`StochasticMesh::interpolated_nodes`]
    /// without a leaf to refine first) a run: the maximum-error criterion's new run where the
    /// density peaks on a node whose value a centred refinement froze. The surrogate changes
    /// only on the leaves around it (and wherever an interpolated value resolves through it); it
    /// stays continuous.
    ///
    /// # Errors
    /// If `xi` is not such a node.
    pub fn promote(&mut self, xi: &[f64]) -> Result<NewRun> {
        let d = self.d;
        let mut key = [0u64; MAX_DIM];
        for j in 0..d.min(xi.len()) {
            let span = ((self.roots[j] as u64) << MAX_LEVEL) as f64;
            let t = (xi[j] - self.lo[j]) / (self.hi[j] - self.lo[j]) * span;
            if !(t >= 0.0 && t <= span) {
                return Err(invalid("stochastic mesh", "point", "inside the box", xi[j]));
            }
            key[j] = t.round() as u64;
        }
        let ok = xi.len() == d
            && matches!(
                self.nodes.get(&key),
                Some(NodeKind::Fixed(_) | NodeKind::Hanging(_))
            )
            && self.master_of(&key).is_none()
            && (0..d).all(|j| {
                (self.key_point(&key)[j] - xi[j]).abs() <= 1e-9 * (self.hi[j] - self.lo[j])
            });
        if !ok {
            return Err(UqError::Invalid {
                what: "stochastic mesh",
                message: format!("{xi:?} is not an interpolated node that can become a run"),
            });
        }
        let run = self.add_run(key);
        self.rebuild()?;
        Ok(NewRun {
            run,
            point: self.run_point(run).to_vec(),
        })
    }

    /// As [`StochasticMesh::refine`], but also refines coarser neighbours as needed so that
    /// adjacent leaves differ by at most one level (2:1 balance, if the mesh was balanced).
    ///
    /// # Errors
    /// As [`StochasticMesh::refine`].
    pub fn refine_balanced(&mut self, cells: &[CellId]) -> Result<Vec<NewRun>> {
        let mut set: Vec<CellId> = cells.to_vec();
        let mut i = 0;
        while i < set.len() {
            let c = set[i];
            if self.is_leaf(c) {
                let level = self.cells[c].level;
                for n in self.neighbours(c) {
                    if self.cells[n].level < level && !set.contains(&n) {
                        set.push(n);
                    }
                }
            }
            i += 1;
        }
        self.refine(&set)
    }

    /// Refine every leaf once.
    ///
    /// # Errors
    /// As [`StochasticMesh::refine`].
    pub fn refine_all(&mut self) -> Result<Vec<NewRun>> {
        let leaves = self.leaves();
        self.refine(&leaves)
    }
}
