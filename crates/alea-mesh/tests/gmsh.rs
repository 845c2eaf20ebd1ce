//! Gmsh reader: committed fixtures (made by Gmsh 4.15 with `tests/fixtures/make_fixtures.py`)
//! must give the same meshes as the structured generators up to node numbering; malformed files
//! must give a `Parse` error naming the section (and line), never a panic.

mod common;

use std::collections::{BTreeSet, HashMap};
use std::path::PathBuf;

use alea_mesh::CellType::{self, *};
use alea_mesh::generate::{box_mesh, rectangle};
use alea_mesh::gmsh::parse_msh;
use alea_mesh::{Mesh, MeshError, read_msh};
use common::*;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn key(x: [f64; 3]) -> [i64; 3] {
    x.map(|v| (v * 1e6).round() as i64)
}

/// Map from the generator's node indices to the read mesh's, by coordinates (1e-6).
fn node_map(gen_mesh: &Mesh, read: &Mesh) -> Vec<usize> {
    assert_eq!(gen_mesh.num_nodes(), read.num_nodes(), "node counts");
    let index: HashMap<[i64; 3], usize> = read
        .coords
        .iter()
        .enumerate()
        .map(|(i, &x)| (key(x), i))
        .collect();
    assert_eq!(
        index.len(),
        read.num_nodes(),
        "read mesh has coincident nodes"
    );
    gen_mesh
        .coords
        .iter()
        .map(|&x| {
            *index
                .get(&key(x))
                .unwrap_or_else(|| panic!("no read node at {x:?}"))
        })
        .collect()
}

fn cell_set(m: &Mesh, map: Option<&[usize]>) -> BTreeSet<(CellType, Vec<usize>)> {
    m.cells()
        .map(|(_, k, n)| {
            let mut v: Vec<usize> = n.iter().map(|&i| map.map_or(i, |m| m[i])).collect();
            v.sort_unstable();
            (k, v)
        })
        .collect()
}

fn facet_set(m: &Mesh, name: &str, map: Option<&[usize]>) -> BTreeSet<Vec<usize>> {
    m.facet_group(name)
        .unwrap()
        .iter()
        .map(|f| {
            let mut v: Vec<usize> = f.nodes.iter().map(|&i| map.map_or(i, |m| m[i])).collect();
            v.sort_unstable();
            v
        })
        .collect()
}

/// The read mesh equals the generated one up to node numbering: nodes, cells, groups.
fn assert_same(read: &Mesh, expected: &Mesh, exact_cells: bool) {
    read.validate().unwrap();
    assert_eq!(read.dim, expected.dim);
    assert_positive_jacobians(read);
    assert_conforming(read);
    assert_eq!(read.num_cells(), expected.num_cells());
    let map = node_map(expected, read);
    if exact_cells {
        assert_eq!(cell_set(expected, Some(&map)), cell_set(read, None));
    }
    assert!((read.measure() - expected.measure()).abs() < 1e-9);
    assert_eq!(read.cell_group("domain").unwrap().len(), read.num_cells());
    let b = boundary_set(read);
    for name in expected.facet_groups.keys() {
        if exact_cells {
            assert_eq!(
                facet_set(expected, name, Some(&map)),
                facet_set(read, name, None),
                "facet group {name}"
            );
        } else {
            // Gmsh splits the faces along other diagonals: same count, same nodes (below).
            assert_eq!(
                expected.facet_group(name).unwrap().len(),
                read.facet_group(name).unwrap().len()
            );
        }
        for f in read.facet_group(name).unwrap() {
            assert!(
                b.contains(&f.nodes),
                "facet {:?} of {name} not outward",
                f.nodes
            );
        }
        let mut nodes: Vec<usize> = expected.node_groups[name].iter().map(|&i| map[i]).collect();
        nodes.sort_unstable();
        assert_eq!(read.node_groups[name], nodes, "node group {name}");
    }
}

#[test]
fn two_d_fixtures_equal_rectangle() {
    for (name, kind) in [
        ("q4", Quad4),
        ("t3", Tri3),
        ("t6", Tri6),
        ("q8", Quad8),
        ("cw_q4", Quad4),
        ("sparse_t6", Tri6),
        ("param_q8", Quad8),
    ] {
        for enc in ["ascii", "bin"] {
            let file = format!("square_{name}_{enc}.msh");
            let read = read_msh(fixture(&file)).unwrap_or_else(|e| panic!("{file}: {e}"));
            let expected = rectangle(2.0, 1.0, 4, 2, kind).unwrap();
            assert_same(&read, &expected, true);
            // Extra groups: a physical point and an unnamed physical curve (tag 12) on y = 1.
            let origin = read.node_groups["origin"].clone();
            assert_eq!(origin.len(), 1);
            assert_eq!(read.coords[origin[0]], [0.0, 0.0, 0.0]);
            assert_eq!(facet_set(&read, "12", None), facet_set(&read, "ymax", None));
            assert_eq!(read.node_groups["12"], read.node_groups["ymax"]);
            // The cell group also has a node group of its nodes: all of them.
            assert_eq!(read.node_groups["domain"].len(), read.num_nodes());
        }
    }
}

#[test]
fn three_d_fixtures_equal_box() {
    for (name, kind, exact) in [
        ("hex8", Hex8, true),
        ("tet4", Tet4, false),
        ("tet10", Tet10, false),
    ] {
        for enc in ["ascii", "bin"] {
            let file = format!("box_{name}_{enc}.msh");
            let read = read_msh(fixture(&file)).unwrap_or_else(|e| panic!("{file}: {e}"));
            let expected = box_mesh([1.0, 1.0, 2.0], [2, 2, 3], kind).unwrap();
            assert_same(&read, &expected, exact);
            assert_eq!(read.cell_types_present(), [kind]);
        }
    }
}

#[test]
fn tet10_mid_edge_nodes_are_in_vtk_order() {
    let m = read_msh(fixture("box_tet10_ascii.msh")).unwrap();
    const EDGES: [(usize, usize); 6] = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)];
    for (_, _, n) in m.cells() {
        for (k, (a, b)) in EDGES.iter().enumerate() {
            let (xa, xb, xm) = (m.coords[n[*a]], m.coords[n[*b]], m.coords[n[4 + k]]);
            for d in 0..3 {
                assert!(
                    (0.5 * (xa[d] + xb[d]) - xm[d]).abs() < 1e-9,
                    "node {} not on edge {a}-{b}",
                    4 + k
                );
            }
        }
    }
}

#[test]
fn clockwise_surface_is_reoriented() {
    // The fixture's elements are clockwise in the file (checked here from the raw text).
    let text = std::fs::read_to_string(fixture("square_cw_q4_ascii.msh")).unwrap();
    let plain = std::fs::read_to_string(fixture("square_q4_ascii.msh")).unwrap();
    assert_ne!(text, plain);
    let m = read_msh(fixture("square_cw_q4_ascii.msh")).unwrap();
    for c in 0..m.num_cells() {
        assert!(m.cell_min_jacobian(c) > 0.0);
    }
}

fn parse_err(bytes: &[u8]) -> (usize, String, String) {
    match parse_msh(bytes, "bad.msh") {
        Err(MeshError::Parse {
            line,
            section,
            message,
            ..
        }) => (line, section, message),
        Err(e) => panic!("expected a parse error, got {e}"),
        Ok(_) => panic!("expected a parse error, got a mesh"),
    }
}

/// 1-based number of the first line of `text` that starts with `prefix` after line `after`.
fn line_of(text: &str, after: &str, prefix: &str) -> usize {
    let start = text.lines().position(|l| l == after).unwrap();
    start
        + 1
        + text
            .lines()
            .skip(start)
            .position(|l| l.starts_with(prefix))
            .unwrap()
}

/// The line following the first line starting with `prefix`.
fn lines_after(text: &str, prefix: &str) -> String {
    let mut it = text.lines().skip_while(|l| !l.starts_with(prefix));
    it.next();
    it.next().unwrap().to_string()
}

#[test]
fn malformed_ascii_files_name_line_and_section() {
    let text = std::fs::read_to_string(fixture("square_q4_ascii.msh")).unwrap();
    // Truncated inside $Nodes.
    let cut = text.find("$Nodes").unwrap() + 40;
    let (_, section, msg) = parse_err(&text.as_bytes()[..cut]);
    assert_eq!(section, "$Nodes");
    assert!(msg.contains("file"), "{msg}");
    // A garbage token in an element line.
    let elem_line = line_of(&text, "$Elements", "2 1 3 ");
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let header = lines[elem_line - 1].clone();
    let target = elem_line; // the first element of that block, 0-based index = elem_line
    lines[target] = lines[target].replacen(' ', " x7 ", 1);
    let (line, section, msg) = parse_err(lines.join("\n").as_bytes());
    assert_eq!(
        (line, section.as_str()),
        (target + 1, "$Elements"),
        "{msg} / {header}"
    );
    assert!(msg.contains("node tag") && msg.contains("x7"), "{msg}");
    // Wrong node count in the $Nodes header.
    let nodes_hdr = line_of(&text, "$Nodes", "");
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let parts: Vec<&str> = lines[nodes_hdr].split(' ').collect();
    let n: usize = parts[1].parse().unwrap();
    lines[nodes_hdr] = format!("{} {} {} {}", parts[0], n + 1, parts[2], parts[3]);
    let (_, section, msg) = parse_err(lines.join("\n").as_bytes());
    assert_eq!(section, "$Nodes");
    assert!(msg.contains("announces"), "{msg}");
    // Unknown element type 99.
    let bad = text.replacen("\n2 1 3 ", "\n2 1 99 ", 1);
    assert_ne!(bad, text);
    let (line, section, msg) = parse_err(bad.as_bytes());
    assert_eq!(section, "$Elements");
    assert!(msg.contains("99") && line > 0, "{msg}");
    // Missing $EndNodes.
    let bad = text.replacen("$EndNodes\n", "", 1);
    let (_, section, msg) = parse_err(bad.as_bytes());
    assert_eq!(section, "$Nodes");
    assert!(
        msg.contains("$EndNodes") && msg.contains("$Elements"),
        "{msg}"
    );
    // Non-numeric coordinate.
    let bad = text.replacen("\n0 0 0\n", "\n0 zero 0\n", 1);
    let (_, section, msg) = parse_err(bad.as_bytes());
    assert_eq!(section, "$Nodes");
    assert!(msg.contains("coordinate") && msg.contains("zero"), "{msg}");
    // Old format version.
    let (_, section, msg) = parse_err(text.replacen("4.1 0 8", "2.2 0 8", 1).as_bytes());
    assert_eq!(section, "$MeshFormat");
    assert!(msg.contains("2.2"), "{msg}");
    // An element referring to a node tag that $Nodes does not define.
    let first = lines_after(&text, "2 1 3 ");
    let cut = first.trim_end().rfind(' ').unwrap();
    let bad = text.replacen(&first, &format!("{} 999", &first[..cut]), 1);
    let (_, section, msg) = parse_err(bad.as_bytes());
    assert_eq!(section, "$Elements");
    assert!(msg.contains("999"), "{msg}");
    // No file.
    assert!(matches!(
        read_msh(fixture("missing.msh")),
        Err(MeshError::Io { .. })
    ));
}

#[test]
fn malformed_binary_files_name_offset_and_section() {
    let data = std::fs::read(fixture("square_q8_bin.msh")).unwrap();
    let nodes = data.windows(6).position(|w| w == b"$Nodes").unwrap();
    let (line, section, msg) = parse_err(&data[..nodes + 100]);
    assert_eq!((line, section.as_str()), (0, "$Nodes"));
    assert!(
        msg.contains("byte offset") && msg.contains("end of file"),
        "{msg}"
    );
    // Element type of the first element block set to 99 (binary int after dim and tag).
    let el = data.windows(9).position(|w| w == b"$Elements").unwrap() + 10 + 32;
    let mut bad = data.clone();
    bad[el + 8..el + 12].copy_from_slice(&99i32.to_le_bytes());
    let (line, section, msg) = parse_err(&bad);
    assert_eq!((line, section.as_str()), (0, "$Elements"));
    assert!(msg.contains("99"), "{msg}");
}

#[test]
fn truncations_and_byte_flips_never_panic() {
    for file in [
        "square_t6_ascii.msh",
        "square_t6_bin.msh",
        "box_tet10_bin.msh",
    ] {
        let data = std::fs::read(fixture(file)).unwrap();
        let step = (data.len() / 700).max(1);
        for cut in (0..data.len()).step_by(step) {
            let _ = parse_msh(&data[..cut], file);
        }
        let mut state = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..400 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let mut bad = data.clone();
            let i = (state % data.len() as u64) as usize;
            bad[i] = (state >> 32) as u8;
            let _ = parse_msh(&bad, file);
        }
    }
}

#[test]
fn curved_t6_plate_with_hole_from_gmsh() {
    let m = read_msh(fixture("plate_hole_t6.msh")).unwrap();
    m.validate().unwrap();
    assert_positive_jacobians(&m);
    assert_conforming(&m);
    assert_groups_outward(&m);
    assert_eq!(m.cell_types_present(), [Tri6]);
    let exact = 16.0 - std::f64::consts::PI / 4.0;
    assert!((m.measure() / exact - 1.0).abs() < 1e-5, "{}", m.measure());
    for x in group_coords(&m, "hole") {
        assert!((x[0].hypot(x[1]) - 1.0).abs() < 1e-9);
    }
    for (g, d, v) in [
        ("xsym", 0, 0.0),
        ("ysym", 1, 0.0),
        ("right", 0, 4.0),
        ("top", 1, 4.0),
    ] {
        for x in group_coords(&m, g) {
            assert!((x[d] - v).abs() < 1e-9, "{g}: {x:?}");
        }
    }
    // Every boundary facet is in exactly one group.
    let total: usize = m.facet_groups.values().map(|v| v.len()).sum();
    assert_eq!(total, m.boundary_facets().len());
}

#[test]
fn unknown_sections_are_skipped() {
    let text = std::fs::read_to_string(fixture("square_t6_ascii.msh")).unwrap();
    let plain = parse_msh(text.as_bytes(), "a.msh").unwrap();
    let extra = text.replacen(
        "$EndMeshFormat\n",
        "$EndMeshFormat\n$Comments\nnot a $Nodes section\n$EndComments\n",
        1,
    ) + "$NodeData\n1\n\"u\"\n1\n0.0\n3\n0\n1\n1\n1 0.5\n$EndNodeData\n";
    let m = parse_msh(extra.as_bytes(), "b.msh").unwrap();
    assert_eq!(m.coords, plain.coords);
    assert_eq!(m.num_cells(), plain.num_cells());
    assert_eq!(m.facet_groups, plain.facet_groups);
    // An unknown section that is never closed is an error.
    let (_, section, msg) = parse_err((text.clone() + "$Periodic\n1\n").as_bytes());
    assert_eq!(section, "$Periodic");
    assert!(msg.contains("$EndPeriodic"), "{msg}");
}

#[test]
fn two_d_mesh_must_lie_in_the_xy_plane() {
    let text = std::fs::read_to_string(fixture("square_q4_ascii.msh")).unwrap();
    let bad = text.replacen("\n2 1 0\n", "\n2 1 0.5\n", 1);
    assert_ne!(bad, text);
    let e = parse_msh(bad.as_bytes(), "z.msh").unwrap_err();
    assert!(
        matches!(&e, MeshError::Invalid(m) if m.contains("xy plane")),
        "{e}"
    );
}

/// A two-triangle binary file written by hand: `$Entities` with one surface in physical group 7
/// ("plate") and one curve in group 8 (unnamed), in the given endianness and size_t width.
fn handmade_binary(big_endian: bool, size_t: usize) -> Vec<u8> {
    let mut b: Vec<u8> = Vec::new();
    let int = |b: &mut Vec<u8>, v: i32| {
        b.extend(if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    let size = |b: &mut Vec<u8>, v: u64| {
        let bytes = if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        };
        if big_endian {
            b.extend(&bytes[8 - size_t..]);
        } else {
            b.extend(&bytes[..size_t]);
        }
    };
    let dbl = |b: &mut Vec<u8>, v: f64| {
        b.extend(if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    b.extend(format!("$MeshFormat\n4.1 1 {size_t}\n").as_bytes());
    int(&mut b, 1);
    b.extend(b"\n$EndMeshFormat\n$PhysicalNames\n1\n2 7 \"plate\"\n$EndPhysicalNames\n$Entities\n");
    for n in [0u64, 1, 1, 0] {
        size(&mut b, n);
    }
    // Curve 3: bounding box, 1 physical tag (8), 0 bounding points.
    int(&mut b, 3);
    for v in [0.0, 0.0, 0.0, 1.0, 0.0, 0.0] {
        dbl(&mut b, v);
    }
    size(&mut b, 1);
    int(&mut b, 8);
    size(&mut b, 0);
    // Surface 5: 1 physical tag (7), 1 bounding curve (3).
    int(&mut b, 5);
    for v in [0.0, 0.0, 0.0, 1.0, 1.0, 0.0] {
        dbl(&mut b, v);
    }
    size(&mut b, 1);
    int(&mut b, 7);
    size(&mut b, 1);
    int(&mut b, 3);
    b.extend(b"\n$EndEntities\n$Nodes\n");
    for v in [1u64, 4, 10, 40] {
        size(&mut b, v);
    }
    int(&mut b, 2);
    int(&mut b, 5);
    int(&mut b, 0);
    size(&mut b, 4);
    for t in [10u64, 20, 30, 40] {
        size(&mut b, t);
    }
    for x in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
        dbl(&mut b, x[0]);
        dbl(&mut b, x[1]);
        dbl(&mut b, 0.0);
    }
    b.extend(b"\n$EndNodes\n$Elements\n");
    for v in [2u64, 3, 1, 3] {
        size(&mut b, v);
    }
    // Two clockwise triangles on surface 5, one line on curve 3 (reversed: inward).
    int(&mut b, 2);
    int(&mut b, 5);
    int(&mut b, 2);
    size(&mut b, 2);
    for e in [[1u64, 10, 30, 20], [2, 10, 40, 30]] {
        for v in e {
            size(&mut b, v);
        }
    }
    int(&mut b, 1);
    int(&mut b, 3);
    int(&mut b, 1);
    size(&mut b, 1);
    for v in [3u64, 20, 10] {
        size(&mut b, v);
    }
    b.extend(b"\n$EndElements\n");
    b
}

#[test]
fn binary_endianness_and_size_t_width() {
    let reference = handmade_binary(false, 8);
    let m = parse_msh(&reference, "le.msh").unwrap();
    assert_eq!(m.num_cells(), 2);
    assert_positive_jacobians(&m);
    assert!((m.measure() - 1.0).abs() < 1e-15);
    assert_eq!(m.cell_group("plate").unwrap(), [0, 1]);
    // The bottom edge, given inward (1,0)->(0,0), is re-oriented outward: (0,0)->(1,0).
    let f = &m.facet_group("8").unwrap()[0];
    assert_eq!(
        [m.coords[f.nodes[0]], m.coords[f.nodes[1]]],
        [[0.0; 3], [1.0, 0.0, 0.0]]
    );
    assert_eq!(m.node_groups["8"].len(), 2);
    for (be, st) in [(true, 8), (false, 4), (true, 4)] {
        let other = parse_msh(&handmade_binary(be, st), "x.msh").unwrap();
        assert_eq!(other.coords, m.coords);
        assert_eq!(other.cell_groups, m.cell_groups);
        assert_eq!(other.facet_groups, m.facet_groups);
        assert_eq!(other.node_groups, m.node_groups);
        for c in 0..2 {
            assert_eq!(other.cell_nodes(c), m.cell_nodes(c));
        }
    }
}
