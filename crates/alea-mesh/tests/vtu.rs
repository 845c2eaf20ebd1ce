//! VTU writer: the file is parsed back with a minimal XML reader and checked against the mesh.

use std::collections::HashMap;

use alea_mesh::CellType::*;
use alea_mesh::generate::{plate_with_hole, rectangle};
use alea_mesh::{Mesh, MeshError, VtuEncoding, VtuWriter, write_pvd, write_vtm};
use base64::Engine as _;

/// A `DataArray`: its attributes and decoded values (as f64).
#[derive(Debug)]
struct Array {
    attrs: HashMap<String, String>,
    values: Vec<f64>,
}

fn attrs(tag: &str) -> HashMap<String, String> {
    let mut out = HashMap::new();
    let mut rest = tag;
    while let Some(eq) = rest.find("=\"") {
        let key = rest[..eq].rsplit(' ').next().unwrap().to_string();
        let after = &rest[eq + 2..];
        let end = after.find('"').unwrap();
        out.insert(key, after[..end].to_string());
        rest = &after[end + 1..];
    }
    out
}

/// All DataArrays in document order, with the enclosing section (PointData, CellData, ...).
fn parse(xml: &str) -> (HashMap<String, String>, Vec<(String, Array)>) {
    let piece = xml
        .find("<Piece")
        .map(|i| attrs(&xml[i..i + xml[i..].find('>').unwrap()]))
        .unwrap();
    let mut out = Vec::new();
    let mut section = String::new();
    let mut pos = 0;
    while let Some(i) = xml[pos..].find('<') {
        let start = pos + i;
        let end = start + xml[start..].find('>').unwrap();
        let tag = &xml[start + 1..end];
        let name = tag.split_whitespace().next().unwrap();
        if ["PointData", "CellData", "Points", "Cells"].contains(&name) {
            section = name.to_string();
        }
        if name == "DataArray" {
            let a = attrs(tag);
            let close = end + xml[end..].find("</DataArray>").unwrap();
            let text = xml[end + 1..close].trim();
            let values = if a["format"] == "ascii" {
                text.split_whitespace()
                    .map(|t| t.parse().unwrap())
                    .collect()
            } else {
                let bytes = base64::engine::general_purpose::STANDARD
                    .decode(text)
                    .unwrap();
                let n = u64::from_le_bytes(bytes[..8].try_into().unwrap()) as usize;
                let data = &bytes[8..];
                assert_eq!(n, data.len(), "header byte count");
                match a["type"].as_str() {
                    "Float64" => data
                        .chunks(8)
                        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
                        .collect(),
                    "Int64" => data
                        .chunks(8)
                        .map(|c| i64::from_le_bytes(c.try_into().unwrap()) as f64)
                        .collect(),
                    "Int32" => data
                        .chunks(4)
                        .map(|c| i32::from_le_bytes(c.try_into().unwrap()) as f64)
                        .collect(),
                    "UInt8" => data.iter().map(|&b| b as f64).collect(),
                    t => panic!("type {t}"),
                }
            };
            out.push((section.clone(), Array { attrs: a, values }));
            pos = close;
        } else {
            pos = end;
        }
    }
    (piece, out)
}

fn get<'a>(arrays: &'a [(String, Array)], section: &str, name: &str) -> &'a Array {
    &arrays
        .iter()
        .find(|(s, a)| s == section && a.attrs.get("Name").map(|n| n.as_str()) == Some(name))
        .unwrap_or_else(|| panic!("no {name} in {section}"))
        .1
}

fn check_structure(m: &Mesh, xml: &str) -> Vec<(String, Array)> {
    assert!(xml.starts_with("<?xml"));
    assert!(xml.trim_end().ends_with("</VTKFile>"));
    let (piece, arrays) = parse(xml);
    assert_eq!(piece["NumberOfPoints"], m.num_nodes().to_string());
    assert_eq!(piece["NumberOfCells"], m.num_cells().to_string());
    let pts = get(&arrays, "Points", "Points");
    assert_eq!(pts.attrs["NumberOfComponents"], "3");
    let flat: Vec<f64> = m.coords.iter().flat_map(|x| x.to_vec()).collect();
    assert_eq!(pts.values, flat);
    let conn = get(&arrays, "Cells", "connectivity");
    let offs = get(&arrays, "Cells", "offsets");
    let types = get(&arrays, "Cells", "types");
    assert_eq!(offs.values.len(), m.num_cells());
    assert_eq!(types.values.len(), m.num_cells());
    let mut prev = 0usize;
    for (c, kind, nodes) in m.cells() {
        let end = offs.values[c] as usize;
        let got: Vec<usize> = conn.values[prev..end].iter().map(|&v| v as usize).collect();
        assert_eq!(got, nodes);
        assert_eq!(types.values[c] as u8, kind.vtk_code());
        prev = end;
    }
    assert_eq!(prev, conn.values.len());
    arrays
}

#[test]
fn fields_round_trip_in_both_encodings() {
    let m = plate_with_hole(1.0, 3.0, 4, 3, 2.0, Quad8).unwrap();
    let n = m.num_nodes();
    let c = m.num_cells();
    let ps: Vec<f64> = (0..n).map(|i| i as f64 * 0.5).collect();
    let pv: Vec<f64> = (0..2 * n).map(|i| i as f64 - 3.25).collect();
    let ct: Vec<f64> = (0..3 * c).map(|i| 1e-3 * i as f64).collect();
    let ct6: Vec<f64> = (0..6 * c).map(|i| i as f64).collect();
    for enc in [VtuEncoding::Ascii, VtuEncoding::Base64] {
        let xml = VtuWriter::new(&m)
            .encoding(enc)
            .point_scalar("T", &ps)
            .point_vector("u", 2, &pv)
            .cell_tensor("sigma", 3, &ct)
            .cell_tensor("s6", 6, &ct6)
            .cell_scalar("id", &(0..c).map(|i| i as f64).collect::<Vec<_>>())
            .to_xml()
            .unwrap();
        let arrays = check_structure(&m, &xml);
        assert_eq!(get(&arrays, "PointData", "T").values, ps);
        let u = get(&arrays, "PointData", "u");
        assert_eq!(u.attrs["NumberOfComponents"], "3");
        for i in 0..n {
            assert_eq!(
                &u.values[3 * i..3 * i + 3],
                &[pv[2 * i], pv[2 * i + 1], 0.0]
            );
        }
        let s = get(&arrays, "CellData", "sigma");
        assert_eq!(s.attrs["NumberOfComponents"], "6");
        assert_eq!(s.attrs["ComponentName3"], "XY");
        for i in 0..c {
            let e = &ct[3 * i..3 * i + 3];
            assert_eq!(
                &s.values[6 * i..6 * i + 6],
                &[e[0], e[1], 0.0, e[2], 0.0, 0.0]
            );
        }
        assert_eq!(get(&arrays, "CellData", "s6").values, ct6);
        let g = get(&arrays, "CellData", "group_domain");
        assert_eq!(g.attrs["type"], "Int32");
        assert!(g.values.iter().all(|&v| v == 1.0));
    }
}

#[test]
fn group_fields_mark_membership() {
    let mut m = rectangle(2.0, 1.0, 2, 1, Tri6).unwrap();
    m.add_cells_to_group("left", [0, 1]);
    let xml = VtuWriter::new(&m)
        .encoding(VtuEncoding::Ascii)
        .to_xml()
        .unwrap();
    let arrays = check_structure(&m, &xml);
    assert_eq!(
        get(&arrays, "CellData", "group_left").values,
        [1.0, 1.0, 0.0, 0.0]
    );
    let xml = VtuWriter::new(&m).group_fields(false).to_xml().unwrap();
    assert!(!xml.contains("group_left"));
}

#[test]
fn non_finite_and_wrong_length_are_errors() {
    let m = rectangle(1.0, 1.0, 1, 1, Quad4).unwrap();
    let mut v = vec![0.0; 4];
    v[2] = f64::NAN;
    let e = VtuWriter::new(&m)
        .point_scalar("pressure", &v)
        .to_xml()
        .unwrap_err();
    assert!(
        matches!(&e, MeshError::Invalid(s) if s.contains("pressure") && s.contains("NaN")),
        "{e}"
    );
    let e = VtuWriter::new(&m)
        .cell_vector("f", 3, &[1.0, f64::INFINITY, 0.0])
        .to_xml()
        .unwrap_err();
    assert!(
        matches!(&e, MeshError::Invalid(s) if s.contains("'f'")),
        "{e}"
    );
    let e = VtuWriter::new(&m)
        .point_vector("u", 2, &[0.0; 7])
        .to_xml()
        .unwrap_err();
    assert!(
        matches!(&e, MeshError::Invalid(s) if s.contains("'u'")),
        "{e}"
    );
    assert!(
        VtuWriter::new(&m)
            .point_tensor("t", 5, &[0.0; 20])
            .to_xml()
            .is_err()
    );
}

#[test]
fn multiblock_collection_of_substructures() {
    let mut m = rectangle(2.0, 1.0, 2, 1, Quad4).unwrap();
    m.add_cells_to_group("a", [0]);
    m.add_cells_to_group("b", [1]);
    let (a, _) = m.extract(&["a"]).unwrap();
    let (b, _) = m.extract(&["b"]).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-mesh-vtm-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let vtm = dir.join("parts.vtm");
    let files = write_vtm(
        &vtm,
        &[("a", VtuWriter::new(&a)), ("sub b", VtuWriter::new(&b))],
    )
    .unwrap();
    assert_eq!(files.len(), 2);
    let text = std::fs::read_to_string(&vtm).unwrap();
    assert!(text.contains("file=\"parts/a.vtu\"") && text.contains("file=\"parts/sub_b.vtu\""));
    for (f, mesh) in files.iter().zip([&a, &b]) {
        check_structure(mesh, &std::fs::read_to_string(f).unwrap());
    }
    assert!(
        write_vtm(
            &vtm,
            &[("x", VtuWriter::new(&a)), ("x", VtuWriter::new(&b))]
        )
        .is_err()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn pvd_collection_and_duplicate_names() {
    let m = rectangle(1.0, 1.0, 1, 1, Quad4).unwrap();
    let dir = std::env::temp_dir().join(format!("alea-mesh-pvd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let pvd = dir.join("steps.pvd");
    write_pvd(&pvd, &[(0.0, "a.vtu"), (0.5, "b.vtu")]).unwrap();
    let text = std::fs::read_to_string(&pvd).unwrap();
    assert_eq!(text.matches("<DataSet ").count(), 2);
    assert!(text.contains("timestep=\"0.5\"") && text.contains("file=\"b.vtu\""));
    assert!(write_pvd(&pvd, &[(f64::NAN, "x.vtu")]).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
    // Duplicate names, including a clash with a group field.
    let twice = VtuWriter::new(&m)
        .point_scalar("p", &[0.0; 4])
        .point_scalar("p", &[0.0; 4])
        .to_xml();
    assert!(twice.is_err());
    assert!(
        VtuWriter::new(&m)
            .cell_scalar("group_domain", &[0.0])
            .to_xml()
            .is_err()
    );
    let no_groups = VtuWriter::new(&m).group_fields(false);
    assert!(
        no_groups
            .cell_scalar("group_domain", &[0.0])
            .to_xml()
            .is_ok()
    );
}
