//! Partition of a mesh's cells into parts of nearly equal size with few shared facets: METIS's
//! multilevel k-way partition (`METIS_PartGraphKway`, Karypis & Kumar 1998) of the cells' dual
//! graph, whose vertices are the cells and whose edges join two cells sharing a facet. Used to
//! split a large substructure into subdomains joined by perfect interfaces (module
//! `alea_latin::split`). METIS is already the ordering of the sparse factorisations (module
//! `solver`); no Rust crate partitions graphs.

use std::collections::HashMap;

use alea_mesh::Mesh;

use crate::FemError;
use crate::solver::METIS_LOCK;

/// The part (`0..parts`) of every cell of `mesh`, with every part non-empty and connected
/// through facets as METIS makes it (`METIS_OPTION_CONTIG`). The same mesh gives the same
/// parts (METIS seeds its generator on every call; calls are serialised).
///
/// # Errors
/// If `parts` is 0 or exceeds the number of cells, or METIS fails.
pub fn partition_cells(mesh: &Mesh, parts: usize) -> Result<Vec<usize>, FemError> {
    let n = mesh.num_cells();
    if parts == 0 || parts > n {
        return Err(FemError::Setup(format!(
            "cannot split {n} cells into {parts} parts"
        )));
    }
    if parts == 1 {
        return Ok(vec![0; n]);
    }
    // Dual graph: cells sharing a facet (its sorted corner nodes).
    let mut by_facet: HashMap<Vec<usize>, Vec<usize>> = HashMap::new();
    for (c, kind, nodes) in mesh.cells() {
        for (fk, loc) in kind.facets() {
            let mut key: Vec<usize> = loc[..fk.num_corners()].iter().map(|&i| nodes[i]).collect();
            key.sort_unstable();
            by_facet.entry(key).or_default().push(c);
        }
    }
    let mut adj: Vec<Vec<i32>> = vec![Vec::new(); n];
    for cells in by_facet.values() {
        for (i, &a) in cells.iter().enumerate() {
            for &b in &cells[i + 1..] {
                adj[a].push(b as i32);
                adj[b].push(a as i32);
            }
        }
    }
    let (mut xadj, mut adjncy) = crate::solver::metis_graph(adj);
    let mut nvtxs = n as i32;
    let mut ncon = 1i32;
    let mut nparts = parts as i32;
    let mut objval = 0i32;
    let mut part = vec![0i32; n];
    let mut options = [0i32; metis_sys::METIS_NOPTIONS as usize];
    let _guard = METIS_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    // SAFETY: METIS reads the CSR graph (nvtxs + 1 offsets, no self loops, symmetric) and
    // writes n entries to `part`; null weights mean unit weights; options is METIS_NOPTIONS
    // long.
    let status = unsafe {
        metis_sys::METIS_SetDefaultOptions(options.as_mut_ptr());
        options[metis_sys::moptions_et_METIS_OPTION_CONTIG as usize] = 1;
        options[metis_sys::moptions_et_METIS_OPTION_SEED as usize] = 1;
        metis_sys::METIS_PartGraphKway(
            &mut nvtxs,
            &mut ncon,
            xadj.as_mut_ptr(),
            adjncy.as_mut_ptr(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            &mut nparts,
            std::ptr::null_mut(),
            std::ptr::null_mut(),
            options.as_mut_ptr(),
            &mut objval,
            part.as_mut_ptr(),
        )
    };
    if status != metis_sys::rstatus_et_METIS_OK {
        return Err(FemError::Solver(format!(
            "METIS_PartGraphKway failed with status {status}"
        )));
    }
    let part: Vec<usize> = part.into_iter().map(|p| p as usize).collect();
    let mut size = vec![0usize; parts];
    for &p in &part {
        size[p] += 1;
    }
    if let Some(empty) = size.iter().position(|&s| s == 0) {
        return Err(FemError::Solver(format!(
            "METIS left part {empty} of {parts} empty ({n} cells)"
        )));
    }
    Ok(part)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_splits_into_balanced_connected_parts() {
        let mesh =
            alea_mesh::generate::box_mesh([4.0, 2.0, 2.0], [8, 4, 4], alea_mesh::CellType::Hex8)
                .unwrap();
        let part = partition_cells(&mesh, 4).unwrap();
        let mut size = [0usize; 4];
        for &p in &part {
            size[p] += 1;
        }
        // 128 cells in 4 parts: METIS's default imbalance is 3 %.
        assert!(size.iter().all(|&s| (30..=34).contains(&s)), "{size:?}");
        assert_eq!(part, partition_cells(&mesh, 4).unwrap());
    }
}
