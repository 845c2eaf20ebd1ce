//! The sections of a `.msh` 4.1 file: `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`,
//! `$Elements`, and skipping any other section. The same code reads ASCII and binary files (the
//! [`Reader`]'s items switch on the encoding).

use super::reader::Reader;
use super::{ElementBlock, FileData};
use crate::{CellType, MeshError};

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
    pub(super) fn mesh_format(&mut self) -> Result<(), MeshError> {
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

    pub(super) fn physical_names(&mut self, f: &mut FileData) -> Result<(), MeshError> {
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

    pub(super) fn entities(&mut self, f: &mut FileData) -> Result<(), MeshError> {
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

    pub(super) fn nodes(&mut self, f: &mut FileData) -> Result<(), MeshError> {
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

    pub(super) fn elements(&mut self, f: &mut FileData) -> Result<(), MeshError> {
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

    pub(super) fn skip_section(&mut self, tok: &str) -> Result<(), MeshError> {
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
