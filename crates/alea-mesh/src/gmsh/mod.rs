//! Reader of Gmsh `.msh` files, format version 4.1, ASCII and binary.
//!
//! Hand-written rather than through `mshio` 0.4: mshio ignores `$PhysicalNames` (so group names
//! would need a second parser anyway) and reports errors from its `nom` combinators without the
//! line and the expected item, while a malformed input file must give
//! [`MeshError::Parse`] naming the line (ASCII; line 0 and the byte offset for binary data),
//! the section and what was expected. The format is small enough that one parser serves both
//! encodings: in binary files every section except `$PhysicalNames` has the same items in the same
//! order as in ASCII, with `size_t` counts and tags (data-size bytes, 4 or 8), `int` entity
//! data and `double` coordinates, in the endianness given by the `int 1` after the header.
//!
//! What is read:
//! - `$MeshFormat` (must be 4.1), `$PhysicalNames`, `$Entities` (physical tags of each entity),
//!   `$Nodes`, `$Elements`; any other section (`$Periodic`, `$NodeData`, ...) is skipped.
//! - Element types 1 (line2), 8 (line3), 2 (tri3), 9 (tri6), 3 (quad4), 16 (quad8), 4 (tet4),
//!   11 (tet10), 5 (hex8), 15 (point). Gmsh's node orders equal VTK's except tet10, whose nodes
//!   8 and 9 Gmsh puts on edges (2,3) and (1,3) (documented ordering: 4:(0,1) 5:(1,2) 6:(2,0)
//!   7:(3,0) 8:(3,2) 9:(3,1)); they are swapped to VTK's 8:(1,3) 9:(2,3).
//!
//! What is built:
//! - The mesh dimension is the largest element dimension present (2 or 3). A 2D mesh must lie in
//!   the xy plane.
//! - Elements of that dimension become the cells, in file order; cells with a negative Jacobian
//!   (e.g. surfaces meshed clockwise) are re-ordered to be positive.
//! - Only the nodes used by cells are kept, renumbered in file order (tags may be sparse).
//! - Physical groups of top-dimension entities become cell groups; of (dim - 1) entities, facet
//!   groups, each facet re-oriented outward from the cell it bounds (via
//!   [`Mesh::attach_facets`]); of points, node groups. Every physical group also gives a node
//!   group of its nodes. A physical group without a name in `$PhysicalNames` is named by its tag
//!   (`"12"`).

mod build;
mod reader;
mod sections;

use std::collections::HashMap;
use std::path::Path;

use crate::{CellType, Mesh, MeshError};
use build::build;
use reader::Reader;

/// Reads a Gmsh `.msh` 4.1 file (ASCII or binary).
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read, is not a regular file or is larger than
/// [`crate::input::max_input_bytes`]; [`MeshError::Parse`] for malformed or
/// unsupported content; [`MeshError::Invalid`] for a mesh that cannot be built (2D mesh out of
/// the xy plane, degenerate cells, a facet that bounds no cell).
pub fn read_msh(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
    let path = path.as_ref();
    let data = crate::input::read_input(path).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_msh(&data, path)
}

/// Parses the bytes of a `.msh` 4.1 file; `path` is only used in error messages.
///
/// # Errors
/// As [`read_msh`].
pub fn parse_msh(data: &[u8], path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
    let mut r = Reader {
        path: path.as_ref().to_path_buf(),
        data,
        pos: 0,
        line: 1,
        section: "(file start)".into(),
        binary: false,
        big_endian: false,
        size_t: 8,
    };
    let mut file = FileData::default();
    let mut seen_format = false;
    loop {
        r.skip_ws();
        if r.pos >= r.data.len() {
            break;
        }
        let (tok, _) = r.token("a section header such as $Nodes")?;
        let tok = tok.to_string();
        if !tok.starts_with('$') || tok.starts_with("$End") {
            return Err(r.err(format!("expected a section header ($Name), found '{tok}'")));
        }
        r.section = tok.clone();
        if !seen_format && tok != "$MeshFormat" {
            return Err(r.err(format!(
                "the file must start with $MeshFormat, found '{tok}'"
            )));
        }
        if r.binary && matches!(tok.as_str(), "$Entities" | "$Nodes" | "$Elements") {
            // Binary data starts right after the header's newline.
            if r.data.get(r.pos) == Some(&b'\r') {
                r.pos += 1;
            }
            if r.data.get(r.pos) != Some(&b'\n') {
                return Err(r.err(format!("expected a newline after {tok}")));
            }
            r.pos += 1;
        }
        match tok.as_str() {
            "$MeshFormat" => {
                r.mesh_format()?;
                seen_format = true;
            }
            "$PhysicalNames" => r.physical_names(&mut file)?,
            "$Entities" => r.entities(&mut file)?,
            "$Nodes" => r.nodes(&mut file)?,
            "$Elements" => r.elements(&mut file)?,
            _ => {
                r.skip_section(&tok)?;
                continue;
            }
        }
        let end = format!("$End{}", &tok[1..]);
        let (t, _) = r.token(&end)?;
        if t != end {
            let t = t.to_string();
            return Err(r.err(format!("expected {end}, found '{t}'")));
        }
    }
    if !seen_format {
        return Err(r.err("empty file: expected $MeshFormat".into()));
    }
    build(file, &r.path)
}

#[derive(Default)]
struct FileData {
    names: HashMap<(i32, i32), String>,
    /// (entity dim, entity tag) -> physical tags.
    entity_phys: HashMap<(i32, i32), Vec<i32>>,
    node_tags: Vec<u64>,
    coords: Vec<[f64; 3]>,
    blocks: Vec<ElementBlock>,
    nodes_seen: bool,
    elements_seen: bool,
}

struct ElementBlock {
    dim: i32,
    entity: i32,
    kind: Option<CellType>, // None for points
    /// Node tags, `nodes_per` per element.
    tags: Vec<u64>,
    nodes_per: usize,
    /// Where the block header is (line, byte offset) for error messages.
    line: usize,
    offset: usize,
}
