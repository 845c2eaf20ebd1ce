//! ParaView output: VTK XML UnstructuredGrid (`.vtu`) files with point and cell fields, and
//! multi-block (`.vtm`) collections of several meshes (substructures), and `.pvd` collections
//! of files indexed by time or parameter.
//!
//! Hand-written rather than through `vtkio` 0.6: the format needed is small (one `Piece`,
//! `DataArray`s in `ascii` or `binary` = base64 encoding), vtkio's old dependencies warn, and
//! writing it ourselves lets us check every value (a non-finite value is an error naming the
//! field, never a silent NaN in the file).
//!
//! Layout: `byte_order="LittleEndian"`, `header_type="UInt64"`; in binary mode each array is
//! base64 of (UInt64 byte count, then the little-endian values), uncompressed. Points are
//! Float64 `[x, y, z]`; connectivity and offsets Int64; types UInt8 (node order = VTK order, as
//! in [`Mesh`]). Fields are Float64:
//! - scalars: 1 component;
//! - vectors: 3 components (2D input padded with z = 0);
//! - symmetric tensors: 6 components in ParaView's order `XX YY ZZ XY YZ XZ`, with component
//!   names; input as 3 (`xx yy xy`, 2D, zz = 0), 4 (`xx yy zz xy`, 2D with out-of-plane stress)
//!   or 6 (`xx yy zz xy yz xz`) values per entity.
//!
//! By default every cell group `g` also gives an Int32 cell field `group_g` (1 for the group's
//! cells, 0 elsewhere) so that groups can be shown with a threshold filter.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use base64::Engine as _;

use crate::{Mesh, MeshError};

/// How data arrays are encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VtuEncoding {
    /// Human-readable text.
    Ascii,
    /// Base64 of the little-endian binary values (smaller, faster to read).
    Base64,
}

#[derive(Clone, Debug)]
struct Field {
    name: String,
    ncomp: usize,
    component_names: Option<[&'static str; 6]>,
    data: Vec<f64>,
}

/// Builder of a `.vtu` file for one mesh. Field methods record errors (wrong length, bad
/// dimension) that [`VtuWriter::write`] then returns.
#[derive(Clone, Debug)]
pub struct VtuWriter<'a> {
    mesh: &'a Mesh,
    encoding: VtuEncoding,
    groups: bool,
    point: Vec<Field>,
    cell: Vec<Field>,
    error: Option<String>,
}

const TENSOR_NAMES: [&str; 6] = ["XX", "YY", "ZZ", "XY", "YZ", "XZ"];

impl<'a> VtuWriter<'a> {
    /// A writer for `mesh`, base64 encoding, with group fields.
    pub fn new(mesh: &'a Mesh) -> Self {
        VtuWriter {
            mesh,
            encoding: VtuEncoding::Base64,
            groups: true,
            point: Vec::new(),
            cell: Vec::new(),
            error: None,
        }
    }

    /// Chooses the encoding.
    pub fn encoding(mut self, e: VtuEncoding) -> Self {
        self.encoding = e;
        self
    }

    /// Whether to write the `group_<name>` cell fields (default: yes).
    pub fn group_fields(mut self, yes: bool) -> Self {
        self.groups = yes;
        self
    }

    fn fail(&mut self, msg: String) {
        if self.error.is_none() {
            self.error = Some(msg);
        }
    }

    fn add(&mut self, on_points: bool, name: &str, per: usize, data: &[f64], kind: Shape) {
        let count = if on_points {
            self.mesh.num_nodes()
        } else {
            self.mesh.num_cells()
        };
        let place = if on_points { "point" } else { "cell" };
        if data.len() != count * per {
            self.fail(format!(
                "{place} field '{name}' has {} values, expected {count} x {per}",
                data.len()
            ));
            return;
        }
        let (ncomp, names, out): (usize, Option<[&'static str; 6]>, Vec<f64>) = match kind {
            Shape::Scalar => (1, None, data.to_vec()),
            Shape::Vector => {
                let mut v = Vec::with_capacity(3 * count);
                for e in data.chunks(per) {
                    v.extend_from_slice(e);
                    v.extend(std::iter::repeat_n(0.0, 3 - per));
                }
                (3, None, v)
            }
            Shape::SymTensor => {
                let mut v = Vec::with_capacity(6 * count);
                for e in data.chunks(per) {
                    let t = match per {
                        3 => [e[0], e[1], 0.0, e[2], 0.0, 0.0],
                        4 => [e[0], e[1], e[2], e[3], 0.0, 0.0],
                        _ => [e[0], e[1], e[2], e[3], e[4], e[5]],
                    };
                    v.extend_from_slice(&t);
                }
                (6, Some(TENSOR_NAMES), v)
            }
        };
        let taken = if on_points { &self.point } else { &self.cell };
        if taken.iter().any(|f| f.name == name)
            || (!on_points
                && self.groups
                && name
                    .strip_prefix("group_")
                    .is_some_and(|g| self.mesh.cell_groups.contains_key(g)))
        {
            self.fail(format!("{place} field '{name}' is given twice"));
            return;
        }
        let f = Field {
            name: name.to_string(),
            ncomp,
            component_names: names,
            data: out,
        };
        if on_points {
            self.point.push(f)
        } else {
            self.cell.push(f)
        }
    }

    fn vector(mut self, on_points: bool, name: &str, dim: usize, data: &[f64]) -> Self {
        if dim == 2 || dim == 3 {
            self.add(on_points, name, dim, data, Shape::Vector);
        } else {
            self.fail(format!(
                "vector field '{name}': dimension must be 2 or 3, got {dim}"
            ));
        }
        self
    }

    fn tensor(mut self, on_points: bool, name: &str, ncomp: usize, data: &[f64]) -> Self {
        if matches!(ncomp, 3 | 4 | 6) {
            self.add(on_points, name, ncomp, data, Shape::SymTensor);
        } else {
            self.fail(format!(
                "tensor field '{name}': 3 (xx yy xy), 4 (xx yy zz xy) or 6 (xx yy zz xy yz xz) components per entity, got {ncomp}"
            ));
        }
        self
    }

    /// A scalar per node.
    pub fn point_scalar(mut self, name: &str, data: &[f64]) -> Self {
        self.add(true, name, 1, data, Shape::Scalar);
        self
    }

    /// A vector per node: `dim` (2 or 3) values per node, node after node.
    pub fn point_vector(self, name: &str, dim: usize, data: &[f64]) -> Self {
        self.vector(true, name, dim, data)
    }

    /// A symmetric tensor per node: `ncomp` = 3, 4 or 6 values per node (see the module doc).
    pub fn point_tensor(self, name: &str, ncomp: usize, data: &[f64]) -> Self {
        self.tensor(true, name, ncomp, data)
    }

    /// A scalar per cell.
    pub fn cell_scalar(mut self, name: &str, data: &[f64]) -> Self {
        self.add(false, name, 1, data, Shape::Scalar);
        self
    }

    /// A vector per cell: `dim` (2 or 3) values per cell.
    pub fn cell_vector(self, name: &str, dim: usize, data: &[f64]) -> Self {
        self.vector(false, name, dim, data)
    }

    /// A symmetric tensor per cell: `ncomp` = 3, 4 or 6 values per cell (see the module doc).
    pub fn cell_tensor(self, name: &str, ncomp: usize, data: &[f64]) -> Self {
        self.tensor(false, name, ncomp, data)
    }

    /// The file's text.
    ///
    /// # Errors
    /// [`MeshError::Invalid`] for a field of the wrong length or with a non-finite value (named),
    /// or a mesh whose cells refer to missing nodes.
    pub fn to_xml(&self) -> Result<String, MeshError> {
        if let Some(e) = &self.error {
            return Err(MeshError::Invalid(e.clone()));
        }
        self.mesh.validate()?;
        for (place, fields) in [("point", &self.point), ("cell", &self.cell)] {
            for f in fields {
                if let Some(i) = f.data.iter().position(|v| !v.is_finite()) {
                    return Err(MeshError::Invalid(format!(
                        "{place} field '{}': value {} (entity {}, component {}) is {}",
                        f.name,
                        i,
                        i / f.ncomp,
                        i % f.ncomp,
                        f.data[i]
                    )));
                }
            }
        }
        for x in &self.mesh.coords {
            if x.iter().any(|v| !v.is_finite()) {
                return Err(MeshError::Invalid(format!(
                    "node coordinates {x:?} are not finite"
                )));
            }
        }
        let m = self.mesh;
        let mut s = String::new();
        s.push_str("<?xml version=\"1.0\"?>\n");
        s.push_str("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
        s.push_str("  <UnstructuredGrid>\n");
        let _ = writeln!(
            s,
            "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
            m.num_nodes(),
            m.num_cells()
        );
        s.push_str("      <PointData>\n");
        for f in &self.point {
            self.float_array(&mut s, f);
        }
        s.push_str("      </PointData>\n      <CellData>\n");
        for f in &self.cell {
            self.float_array(&mut s, f);
        }
        if self.groups {
            for (name, cells) in &m.cell_groups {
                let mut v = vec![0i64; m.num_cells()];
                for &c in cells {
                    if c < v.len() {
                        v[c] = 1;
                    }
                }
                self.int_array(&mut s, &format!("group_{name}"), "Int32", &v);
            }
        }
        s.push_str("      </CellData>\n      <Points>\n");
        let pts: Vec<f64> = m.coords.iter().flat_map(|x| x.iter().copied()).collect();
        self.float_array(
            &mut s,
            &Field {
                name: "Points".into(),
                ncomp: 3,
                component_names: None,
                data: pts,
            },
        );
        s.push_str("      </Points>\n      <Cells>\n");
        let mut conn = Vec::new();
        let mut offsets = Vec::with_capacity(m.num_cells());
        let mut types = Vec::with_capacity(m.num_cells());
        for (_, kind, nodes) in m.cells() {
            conn.extend(nodes.iter().map(|&n| n as i64));
            offsets.push(conn.len() as i64);
            types.push(kind.vtk_code() as i64);
        }
        self.int_array(&mut s, "connectivity", "Int64", &conn);
        self.int_array(&mut s, "offsets", "Int64", &offsets);
        self.int_array(&mut s, "types", "UInt8", &types);
        s.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
        Ok(s)
    }

    /// Writes the file.
    ///
    /// # Errors
    /// As [`VtuWriter::to_xml`], and [`MeshError::Io`] if the file cannot be written.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<(), MeshError> {
        let path = path.as_ref();
        let xml = self.to_xml()?;
        crate::atomic::write_bytes_atomic(path, xml.as_bytes()).map_err(|source| MeshError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    fn format(&self) -> &'static str {
        match self.encoding {
            VtuEncoding::Ascii => "ascii",
            VtuEncoding::Base64 => "binary",
        }
    }

    fn float_array(&self, s: &mut String, f: &Field) {
        let _ = write!(
            s,
            "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\"",
            xml_escape(&f.name),
            f.ncomp
        );
        if let Some(names) = f.component_names {
            for (i, n) in names.iter().enumerate() {
                let _ = write!(s, " ComponentName{i}=\"{n}\"");
            }
        }
        let _ = writeln!(s, " format=\"{}\">", self.format());
        match self.encoding {
            VtuEncoding::Ascii => {
                for chunk in f.data.chunks(f.ncomp.max(1) * 4) {
                    s.push_str("          ");
                    for v in chunk {
                        // `{:e}`-free shortest round-trip representation.
                        let _ = write!(s, "{v:?} ");
                    }
                    s.push('\n');
                }
            }
            VtuEncoding::Base64 => {
                let mut bytes = Vec::with_capacity(8 + 8 * f.data.len());
                bytes.extend_from_slice(&((8 * f.data.len()) as u64).to_le_bytes());
                for v in &f.data {
                    bytes.extend_from_slice(&v.to_le_bytes());
                }
                push_base64(s, &bytes);
            }
        }
        s.push_str("        </DataArray>\n");
    }

    fn int_array(&self, s: &mut String, name: &str, ty: &str, v: &[i64]) {
        let _ = writeln!(
            s,
            "        <DataArray type=\"{ty}\" Name=\"{}\" format=\"{}\">",
            xml_escape(name),
            self.format()
        );
        match self.encoding {
            VtuEncoding::Ascii => {
                for chunk in v.chunks(16) {
                    s.push_str("          ");
                    for x in chunk {
                        let _ = write!(s, "{x} ");
                    }
                    s.push('\n');
                }
            }
            VtuEncoding::Base64 => {
                let size = match ty {
                    "UInt8" => 1,
                    "Int32" => 4,
                    _ => 8,
                };
                let mut bytes = Vec::with_capacity(8 + size * v.len());
                bytes.extend_from_slice(&((size * v.len()) as u64).to_le_bytes());
                for &x in v {
                    match size {
                        1 => bytes.push(x as u8),
                        4 => bytes.extend_from_slice(&(x as i32).to_le_bytes()),
                        _ => bytes.extend_from_slice(&x.to_le_bytes()),
                    }
                }
                push_base64(s, &bytes);
            }
        }
        s.push_str("        </DataArray>\n");
    }
}

#[derive(Clone, Copy)]
enum Shape {
    Scalar,
    Vector,
    SymTensor,
}

fn push_base64(s: &mut String, bytes: &[u8]) {
    s.push_str("          ");
    s.push_str(&base64::engine::general_purpose::STANDARD.encode(bytes));
    s.push('\n');
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A file-name-safe version of a part name.
fn safe_name(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes several meshes (e.g. substructures) as one ParaView multi-block data set: each part
/// to `<dir>/<stem>/<part>.vtu` and the collection to `path` (`<dir>/<stem>.vtm`), which refers to
/// them by relative paths. Returns the paths of the `.vtu` files written.
///
/// # Errors
/// Any error of the parts' writers; [`MeshError::Invalid`] for duplicate part names;
/// [`MeshError::Io`] on a file system failure.
pub fn write_vtm(
    path: impl AsRef<Path>,
    parts: &[(&str, VtuWriter<'_>)],
) -> Result<Vec<PathBuf>, MeshError> {
    let path = path.as_ref();
    let io = |p: &Path| {
        let p = p.to_path_buf();
        move |source| MeshError::Io { path: p, source }
    };
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "parts".into());
    let dir = path.parent().unwrap_or(Path::new("")).join(&stem);
    std::fs::create_dir_all(&dir).map_err(io(&dir))?;
    let mut names = std::collections::BTreeSet::new();
    let mut written = Vec::new();
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <vtkMultiBlockDataSet>\n",
    );
    for (i, (name, w)) in parts.iter().enumerate() {
        let file = format!("{}.vtu", safe_name(name));
        if !names.insert(file.clone()) {
            return Err(MeshError::Invalid(format!(
                "two parts would be written to the same file {file}"
            )));
        }
        let p = dir.join(&file);
        w.write(&p)?;
        written.push(p);
        let _ = writeln!(
            xml,
            "    <DataSet index=\"{i}\" name=\"{}\" file=\"{}/{}\"/>",
            xml_escape(name),
            xml_escape(&stem),
            xml_escape(&file)
        );
    }
    xml.push_str("  </vtkMultiBlockDataSet>\n</VTKFile>\n");
    crate::atomic::write_bytes_atomic(path, xml.as_bytes()).map_err(io(path))?;
    Ok(written)
}

/// Writes a ParaView collection (`.pvd`) of data sets indexed by a time or parameter value,
/// e.g. one `.vtu` or `.vtm` per load step or per run: `entries` are `(value, file)` with `file`
/// relative to the `.pvd` file's directory.
///
/// # Errors
/// [`MeshError::Invalid`] for a non-finite value; [`MeshError::Io`] if the file cannot be
/// written.
pub fn write_pvd(path: impl AsRef<Path>, entries: &[(f64, &str)]) -> Result<(), MeshError> {
    let path = path.as_ref();
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for (t, file) in entries {
        if !t.is_finite() {
            return Err(MeshError::Invalid(format!(
                "pvd entry '{file}' has a non-finite time value {t}"
            )));
        }
        let _ = writeln!(
            xml,
            "    <DataSet timestep=\"{t:?}\" part=\"0\" file=\"{}\"/>",
            xml_escape(file)
        );
    }
    xml.push_str("  </Collection>\n</VTKFile>\n");
    crate::atomic::write_bytes_atomic(path, xml.as_bytes()).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })
}
