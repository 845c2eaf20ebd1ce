//! The Gmsh `.msh` 4.1 reader (`alea_mesh::gmsh::parse_msh`, ASCII and binary): any bytes give
//! a mesh or an error, never a panic, and never an allocation beyond the input's size allows
//! (libFuzzer's `-rss_limit_mb` and `-malloc_limit_mb` catch over-allocation).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(mesh) = alea_mesh::gmsh::parse_msh(data, "fuzz.msh") {
        let _ = mesh.num_nodes();
    }
});
