//! Writes the ready-made shapes as ParaView files, one `.vtm` collection of parts.
//!
//! Run: `cargo run -p alea-mesh --release --example shapes_vtu -- [output directory]`
//! (default `out/`), then open `<dir>/shapes.vtm` in ParaView and colour by `group_*`.

use alea_mesh::CellType::Quad8;
use alea_mesh::generate::{
    DovetailParams, annulus_sector, dovetail_root_and_disk, plate_with_hole,
};
use alea_mesh::{MeshError, VtuWriter, write_vtm};

fn main() -> Result<(), MeshError> {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "out".into());
    let plate = plate_with_hole(10.0, 100.0, 16, 12, 8.0, Quad8)?;
    let disk = annulus_sector(50.0, 150.0, std::f64::consts::FRAC_PI_4, 8, 12, Quad8)?;
    let dovetail = dovetail_root_and_disk(&DovetailParams::default(), Quad8)?;
    let (root, _) = dovetail.extract(&["root"])?;
    let (sector, _) = dovetail.extract(&["disk"])?;
    std::fs::create_dir_all(&dir).map_err(|source| MeshError::Io {
        path: dir.clone().into(),
        source,
    })?;
    let files = write_vtm(
        std::path::Path::new(&dir).join("shapes.vtm"),
        &[
            ("plate_with_hole", VtuWriter::new(&plate)),
            ("annulus_sector", VtuWriter::new(&disk)),
            ("dovetail_root", VtuWriter::new(&root)),
            ("dovetail_disk", VtuWriter::new(&sector)),
        ],
    )?;
    for f in files {
        println!("wrote {}", f.display());
    }
    Ok(())
}
