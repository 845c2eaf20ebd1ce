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

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::geometry::jacobian_det;
use crate::{CellType, Mesh, MeshError};

/// Reads a Gmsh `.msh` 4.1 file (ASCII or binary).
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read; [`MeshError::Parse`] for malformed or
/// unsupported content; [`MeshError::Invalid`] for a mesh that cannot be built (2D mesh out of
/// the xy plane, degenerate cells, a facet that bounds no cell).
pub fn read_msh(path: impl AsRef<Path>) -> Result<Mesh, MeshError> {
    let path = path.as_ref();
    let data = std::fs::read(path).map_err(|source| MeshError::Io {
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

struct Reader<'a> {
    path: PathBuf,
    data: &'a [u8],
    pos: usize,
    line: usize,
    section: String,
    binary: bool,
    big_endian: bool,
    size_t: usize,
}

fn element_type(code: i64) -> Option<(Option<CellType>, usize, i32)> {
    use CellType::*;
    Some(match code {
        1 => (Some(Line2), 2, 1),
        8 => (Some(Line3), 3, 1),
        2 => (Some(Tri3), 3, 2),
        9 => (Some(Tri6), 6, 2),
        3 => (Some(Quad4), 4, 2),
        16 => (Some(Quad8), 8, 2),
        4 => (Some(Tet4), 4, 3),
        11 => (Some(Tet10), 10, 3),
        5 => (Some(Hex8), 8, 3),
        15 => (None, 1, 0),
        _ => return None,
    })
}

impl<'a> Reader<'a> {
    fn err(&self, message: String) -> MeshError {
        if self.binary && self.section != "$MeshFormat" && self.section != "$PhysicalNames" {
            MeshError::Parse {
                path: self.path.clone(),
                line: 0,
                section: self.section.clone(),
                message: format!("at byte offset {}: {message}", self.pos),
            }
        } else {
            MeshError::Parse {
                path: self.path.clone(),
                line: self.line,
                section: self.section.clone(),
                message,
            }
        }
    }

    fn skip_ws(&mut self) {
        while let Some(&b) = self.data.get(self.pos) {
            match b {
                b'\n' => self.line += 1,
                b' ' | b'\t' | b'\r' => {}
                _ => break,
            }
            self.pos += 1;
        }
    }

    /// The next whitespace-separated token and its line.
    fn token(&mut self, what: &str) -> Result<(&'a str, usize), MeshError> {
        self.skip_ws();
        let start = self.pos;
        let data: &'a [u8] = self.data;
        while let Some(&b) = data.get(self.pos) {
            if b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err(format!("unexpected end of file, expected {what}")));
        }
        match std::str::from_utf8(&data[start..self.pos]) {
            Ok(s) => Ok((s, self.line)),
            Err(_) => {
                self.pos = start;
                Err(self.err(format!("found non-text bytes, expected {what}")))
            }
        }
    }

    fn parse_tok<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, MeshError> {
        let (t, _) = self.token(what)?;
        t.parse::<T>()
            .map_err(|_| self.err(format!("expected {what}, found '{t}'")))
    }

    fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], MeshError> {
        let data: &'a [u8] = self.data;
        if self.pos + n > data.len() {
            return Err(self.err(format!(
                "unexpected end of file in binary data, expected {what}"
            )));
        }
        let b = &data[self.pos..self.pos + n];
        self.pos += n;
        Ok(b)
    }

    fn uint_bytes(&self, b: &[u8]) -> u64 {
        let mut v = 0u64;
        if self.big_endian {
            for &x in b {
                v = (v << 8) | x as u64;
            }
        } else {
            for &x in b.iter().rev() {
                v = (v << 8) | x as u64;
            }
        }
        v
    }

    /// A `size_t` count or tag.
    fn size(&mut self, what: &str) -> Result<u64, MeshError> {
        if self.binary {
            let b = self.bytes(self.size_t, what)?;
            Ok(self.uint_bytes(b))
        } else {
            self.parse_tok(what)
        }
    }

    /// An `int`.
    fn int(&mut self, what: &str) -> Result<i32, MeshError> {
        if self.binary {
            let b = self.bytes(4, what)?;
            Ok(self.uint_bytes(b) as u32 as i32)
        } else {
            self.parse_tok(what)
        }
    }

    /// A finite `double`.
    fn double(&mut self, what: &str) -> Result<f64, MeshError> {
        let v = if self.binary {
            let b = self.bytes(8, what)?;
            f64::from_bits(self.uint_bytes(b))
        } else {
            self.parse_tok::<f64>(what)?
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(format!("expected {what} (a finite number), found {v}")))
        }
    }

    /// A count, checked against the bytes left (each item takes at least `min_bytes`).
    fn count(&mut self, what: &str, min_bytes: usize) -> Result<usize, MeshError> {
        let n = self.size(what)?;
        let left = (self.data.len() - self.pos.min(self.data.len())) as u64;
        if n.saturating_mul(min_bytes as u64) > left {
            return Err(self.err(format!(
                "{what} is {n}, more than the rest of the file can hold (truncated file or wrong count?)"
            )));
        }
        Ok(n as usize)
    }

    fn mesh_format(&mut self) -> Result<(), MeshError> {
        let (v, _) = self.token("the format version (4.1)")?;
        if v != "4.1" {
            let v = v.to_string();
            return Err(self.err(format!(
                "unsupported format version {v}: only 4.1 is read (re-export with Mesh.MshFileVersion = 4.1)"
            )));
        }
        let ft: i32 = self.parse_tok("the file type (0 ASCII, 1 binary)")?;
        let ds: usize = self.parse_tok("the data size (sizeof size_t)")?;
        if ft != 0 && ft != 1 {
            return Err(self.err(format!("file type must be 0 or 1, found {ft}")));
        }
        if ds != 4 && ds != 8 {
            return Err(self.err(format!("data size must be 4 or 8, found {ds}")));
        }
        self.size_t = ds;
        if ft == 1 {
            // One newline, then the int 1 in the file's endianness.
            if self.data.get(self.pos) == Some(&b'\r') {
                self.pos += 1;
            }
            if self.data.get(self.pos) != Some(&b'\n') {
                return Err(self.err("expected a newline before the binary endianness int".into()));
            }
            self.pos += 1;
            self.line += 1;
            let b = self.bytes(4, "the binary endianness int 1")?;
            let le = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            let be = u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
            if le == 1 {
                self.big_endian = false;
            } else if be == 1 {
                self.big_endian = true;
            } else {
                return Err(self.err(format!(
                    "the binary endianness int should be 1, found bytes {b:?}"
                )));
            }
            self.binary = true;
        }
        Ok(())
    }

    fn physical_names(&mut self, f: &mut FileData) -> Result<(), MeshError> {
        // Always ASCII, even in binary files.
        let n: usize = self.parse_tok("the number of physical names")?;
        for _ in 0..n {
            let dim: i32 = self.parse_tok("a physical group dimension")?;
            let tag: i32 = self.parse_tok("a physical tag")?;
            self.skip_ws_inline();
            let start = self.pos;
            while let Some(&b) = self.data.get(self.pos) {
                if b == b'\n' {
                    break;
                }
                self.pos += 1;
            }
            let raw = std::str::from_utf8(&self.data[start..self.pos])
                .map_err(|_| self.err("physical name is not UTF-8".into()))?
                .trim();
            if raw.len() < 2 || !raw.starts_with('"') || !raw.ends_with('"') {
                return Err(self.err(format!("expected a quoted physical name, found '{raw}'")));
            }
            if !(0..=3).contains(&dim) {
                return Err(self.err(format!(
                    "physical group dimension must be 0..3, found {dim}"
                )));
            }
            f.names
                .insert((dim, tag), raw[1..raw.len() - 1].to_string());
        }
        Ok(())
    }

    fn skip_ws_inline(&mut self) {
        while matches!(self.data.get(self.pos), Some(b' ' | b'\t' | b'\r')) {
            self.pos += 1;
        }
    }

    fn entities(&mut self, f: &mut FileData) -> Result<(), MeshError> {
        let mut counts = [0usize; 4];
        for (d, c) in counts.iter_mut().enumerate() {
            *c = self.count(&format!("the number of {}-dimensional entities", d), 1)?;
        }
        for (d, &n) in counts.iter().enumerate() {
            for _ in 0..n {
                let tag = self.int("an entity tag")?;
                let nbox = if d == 0 { 3 } else { 6 };
                for _ in 0..nbox {
                    self.double("an entity bounding-box coordinate")?;
                }
                let np = self.count("the number of physical tags", 1)?;
                let mut phys = Vec::with_capacity(np);
                for _ in 0..np {
                    phys.push(self.int("a physical tag")?);
                }
                if d > 0 {
                    let nb = self.count("the number of bounding entities", 1)?;
                    for _ in 0..nb {
                        self.int("a bounding entity tag")?;
                    }
                }
                f.entity_phys.insert((d as i32, tag), phys);
            }
        }
        Ok(())
    }

    fn nodes(&mut self, f: &mut FileData) -> Result<(), MeshError> {
        if f.nodes_seen {
            return Err(self.err("a second $Nodes section".into()));
        }
        f.nodes_seen = true;
        let nblocks = self.count("the number of entity blocks", 1)?;
        let total = self.count("the number of nodes", 1)?;
        self.size("the minimum node tag")?;
        self.size("the maximum node tag")?;
        f.node_tags.reserve(total);
        f.coords.reserve(total);
        for _ in 0..nblocks {
            let dim = self.int("an entity dimension (0..3)")?;
            if !(0..=3).contains(&dim) {
                return Err(self.err(format!("entity dimension must be 0..3, found {dim}")));
            }
            self.int("an entity tag")?;
            let parametric = self.int("the parametric flag (0 or 1)")?;
            if parametric != 0 && parametric != 1 {
                return Err(self.err(format!(
                    "parametric flag must be 0 or 1, found {parametric}"
                )));
            }
            let n = self.count("the number of nodes in the block", 1)?;
            let start = f.node_tags.len();
            for _ in 0..n {
                f.node_tags.push(self.size("a node tag")?);
            }
            let extra = if parametric == 1 { dim as usize } else { 0 };
            for k in 0..n {
                let mut x = [0.0; 3];
                for v in x.iter_mut() {
                    *v =
                        self.double(&format!("a coordinate of node {}", f.node_tags[start + k]))?;
                }
                for _ in 0..extra {
                    self.double("a parametric coordinate")?;
                }
                f.coords.push(x);
            }
        }
        if f.node_tags.len() != total {
            return Err(self.err(format!(
                "the header announces {total} nodes but the blocks hold {}",
                f.node_tags.len()
            )));
        }
        Ok(())
    }

    fn elements(&mut self, f: &mut FileData) -> Result<(), MeshError> {
        if f.elements_seen {
            return Err(self.err("a second $Elements section".into()));
        }
        f.elements_seen = true;
        let nblocks = self.count("the number of entity blocks", 1)?;
        let total = self.count("the number of elements", 1)?;
        self.size("the minimum element tag")?;
        self.size("the maximum element tag")?;
        let mut read = 0usize;
        for _ in 0..nblocks {
            let (line, offset) = (self.line, self.pos);
            let dim = self.int("an entity dimension (0..3)")?;
            let entity = self.int("an entity tag")?;
            let code = self.int("an element type")?;
            let Some((kind, nodes_per, tdim)) = element_type(code as i64) else {
                return Err(self.err(format!(
                    "unsupported element type {code} (supported: 1 line2, 8 line3, 2 tri3, 9 tri6, 3 quad4, 16 quad8, 4 tet4, 11 tet10, 5 hex8, 15 point)"
                )));
            };
            if tdim != dim {
                return Err(self.err(format!(
                    "element type {code} has dimension {tdim} but the block's entity has dimension {dim}"
                )));
            }
            let n = self.count("the number of elements in the block", 1)?;
            let mut tags = Vec::with_capacity(n * nodes_per);
            for _ in 0..n {
                self.size("an element tag")?;
                for _ in 0..nodes_per {
                    tags.push(self.size(&format!(
                        "a node tag ({nodes_per} per element of type {code})"
                    ))?);
                }
            }
            read += n;
            f.blocks.push(ElementBlock {
                dim,
                entity,
                kind,
                tags,
                nodes_per,
                line: if self.binary { 0 } else { line },
                offset,
            });
        }
        if read != total {
            return Err(self.err(format!(
                "the header announces {total} elements but the blocks hold {read}"
            )));
        }
        Ok(())
    }

    fn skip_section(&mut self, tok: &str) -> Result<(), MeshError> {
        let end = format!("$End{}", &tok[1..]);
        let hay = &self.data[self.pos..];
        match hay.windows(end.len()).position(|w| w == end.as_bytes()) {
            Some(i) => {
                self.line += hay[..i].iter().filter(|&&b| b == b'\n').count();
                self.pos += i + end.len();
                Ok(())
            }
            None => Err(self.err(format!("unknown section {tok} is not closed by {end}"))),
        }
    }
}

fn gmsh_to_vtk(kind: CellType, nodes: &mut [usize]) {
    if kind == CellType::Tet10 {
        nodes.swap(8, 9);
    }
}

/// Node permutation that reverses a cell's orientation (VTK order).
fn reversal(kind: CellType) -> &'static [usize] {
    use CellType::*;
    match kind {
        Tri3 => &[0, 2, 1],
        Tri6 => &[0, 2, 1, 5, 4, 3],
        Quad4 => &[0, 3, 2, 1],
        Quad8 => &[0, 3, 2, 1, 7, 6, 5, 4],
        Tet4 => &[0, 2, 1, 3],
        Tet10 => &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
        Hex8 => &[0, 3, 2, 1, 4, 7, 6, 5],
        Line2 => &[1, 0],
        Line3 => &[1, 0, 2],
    }
}

fn build(f: FileData, path: &Path) -> Result<Mesh, MeshError> {
    let perr =
        |line: usize, offset: Option<usize>, section: &str, message: String| MeshError::Parse {
            path: path.to_path_buf(),
            line,
            section: section.into(),
            message: match offset {
                Some(o) => format!("at byte offset {o}: {message}"),
                None => message,
            },
        };
    if !f.nodes_seen {
        return Err(perr(
            0,
            None,
            "$Nodes",
            "the file has no $Nodes section".into(),
        ));
    }
    if !f.elements_seen {
        return Err(perr(
            0,
            None,
            "$Elements",
            "the file has no $Elements section".into(),
        ));
    }
    let dim = f.blocks.iter().map(|b| b.dim).max().unwrap_or(0);
    if dim < 2 {
        return Err(perr(
            0,
            None,
            "$Elements",
            "no 2D or 3D elements: nothing to make cells of".into(),
        ));
    }
    let mut tag_index: HashMap<u64, usize> = HashMap::with_capacity(f.node_tags.len());
    for (i, &t) in f.node_tags.iter().enumerate() {
        if tag_index.insert(t, i).is_some() {
            return Err(perr(
                0,
                None,
                "$Nodes",
                format!("node tag {t} appears twice"),
            ));
        }
    }
    let block_where = |b: &ElementBlock| {
        // Binary blocks have no meaningful line: report the offset.
        if b.line == 0 {
            (0, Some(b.offset))
        } else {
            (b.line, None)
        }
    };
    let lookup = |b: &ElementBlock, t: u64| -> Result<usize, MeshError> {
        tag_index.get(&t).copied().ok_or_else(|| {
            let (l, o) = block_where(b);
            perr(
                l,
                o,
                "$Elements",
                format!("element block (entity {} of dimension {}) refers to node tag {t}, which $Nodes does not define", b.entity, b.dim),
            )
        })
    };
    // Nodes used by cells, in file order.
    let mut used = vec![false; f.node_tags.len()];
    for b in f.blocks.iter().filter(|b| b.dim == dim) {
        for &t in &b.tags {
            used[lookup(b, t)?] = true;
        }
    }
    let mut new_index = vec![usize::MAX; f.node_tags.len()];
    let mut mesh = Mesh::new(dim as usize);
    for (i, u) in used.iter().enumerate() {
        if *u {
            let x = f.coords[i];
            if dim == 2 && x[2] != 0.0 {
                return Err(MeshError::Invalid(format!(
                    "{}: a 2D mesh must lie in the xy plane, but node {} has z = {}",
                    path.display(),
                    f.node_tags[i],
                    x[2]
                )));
            }
            new_index[i] = mesh.add_node(x);
        }
    }
    let name = |d: i32, p: i32| {
        f.names
            .get(&(d, p))
            .cloned()
            .unwrap_or_else(|| p.to_string())
    };
    let phys = |b: &ElementBlock| {
        f.entity_phys
            .get(&(b.dim, b.entity))
            .cloned()
            .unwrap_or_default()
    };
    let mapped = |b: &ElementBlock, e: usize| -> Result<Vec<usize>, MeshError> {
        b.tags[e * b.nodes_per..(e + 1) * b.nodes_per]
            .iter()
            .map(|&t| {
                let i = lookup(b, t)?;
                if new_index[i] == usize::MAX {
                    let (l, o) = block_where(b);
                    Err(perr(
                        l,
                        o,
                        "$Elements",
                        format!(
                            "an element of dimension {} uses node tag {t}, which no {dim}D cell uses",
                            b.dim
                        ),
                    ))
                } else {
                    Ok(new_index[i])
                }
            })
            .collect()
    };
    let centre = |kind: CellType| -> [f64; 3] {
        match kind {
            CellType::Tri3 | CellType::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
            CellType::Tet4 | CellType::Tet10 => [0.25; 3],
            _ => [0.0; 3],
        }
    };
    let mut group_cells: HashMap<String, (Vec<usize>, Vec<usize>)> = HashMap::new();
    for b in f.blocks.iter().filter(|b| b.dim == dim) {
        let Some(kind) = b.kind else { continue };
        let nel = b.tags.len() / b.nodes_per;
        let groups: Vec<String> = phys(b).iter().map(|&p| name(dim, p)).collect();
        for e in 0..nel {
            let mut nodes = mapped(b, e)?;
            gmsh_to_vtk(kind, &mut nodes);
            let x: Vec<[f64; 3]> = nodes.iter().map(|&n| mesh.coords[n]).collect();
            let det = jacobian_det(kind, &x, centre(kind));
            if det.is_nan() || det == 0.0 {
                return Err(MeshError::Invalid(format!(
                    "{}: a {kind} cell (entity {}) is degenerate (zero Jacobian)",
                    path.display(),
                    b.entity
                )));
            }
            if det < 0.0 {
                nodes = reversal(kind).iter().map(|&i| nodes[i]).collect();
            }
            let c = mesh.add_cell(kind, &nodes);
            for g in &groups {
                let e = group_cells.entry(g.clone()).or_default();
                e.0.push(c);
                e.1.extend(nodes.iter().copied());
            }
        }
    }
    // Collected first: `Mesh::add_*_to_group` sorts the whole group on each call.
    for (g, (cells, nodes)) in group_cells {
        mesh.add_cells_to_group(&g, cells);
        mesh.add_nodes_to_group(&g, nodes);
    }
    for b in f.blocks.iter().filter(|b| b.dim < dim) {
        let groups: Vec<String> = phys(b).iter().map(|&p| name(b.dim, p)).collect();
        if groups.is_empty() {
            continue;
        }
        let nel = b.tags.len() / b.nodes_per;
        let mut facets = Vec::new();
        let mut nodes_all = Vec::new();
        for e in 0..nel {
            let mut nodes = mapped(b, e)?;
            nodes_all.extend(nodes.iter().copied());
            if let (true, Some(kind)) = (b.dim == dim - 1, b.kind) {
                gmsh_to_vtk(kind, &mut nodes);
                facets.push(crate::Facet { kind, nodes });
            }
        }
        if !facets.is_empty() {
            let attached = mesh.attach_facets(&facets, None).map_err(|e| {
                let (l, o) = block_where(b);
                perr(
                    l,
                    o,
                    "$Elements",
                    format!("entity {} of dimension {}: {e}", b.entity, b.dim),
                )
            })?;
            for g in &groups {
                mesh.add_facets_to_group(g, attached.iter().map(|a| a.facet.clone()));
            }
        }
        for g in &groups {
            mesh.add_nodes_to_group(g, nodes_all.iter().copied());
        }
    }
    Ok(mesh)
}
