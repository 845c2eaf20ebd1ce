//! Property-based fuzzing of the Gmsh reader, on a bounded budget that runs in `cargo test`
//! (proptest): the shipped fixtures (ASCII and binary, every cell kind) with random byte edits
//! (a byte replaced, a run of bytes deleted or duplicated, the file cut short), and random
//! bytes after a valid header. Whatever the bytes, `parse_msh` returns a mesh or an error - it
//! never panics, and never allocates beyond what the file's size can justify (counts are
//! checked against the bytes left, so a huge announced count is an error, not an abort).

use alea_mesh::gmsh::parse_msh;
use proptest::prelude::*;

fn fixtures() -> Vec<(String, Vec<u8>)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "msh"))
        .map(|p| {
            (
                p.file_name().unwrap().to_string_lossy().into_owned(),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect();
    v.sort();
    assert!(v.len() >= 10, "fixtures expected in {}", dir.display());
    v
}

#[derive(Clone, Debug)]
enum Edit {
    Byte(usize, u8),
    Delete(usize, usize),
    Duplicate(usize, usize),
    Truncate(usize),
    Digit(usize, u8),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Edit::Byte(i, b)),
        (any::<usize>(), 1usize..64).prop_map(|(i, n)| Edit::Delete(i, n)),
        (any::<usize>(), 1usize..64).prop_map(|(i, n)| Edit::Duplicate(i, n)),
        any::<usize>().prop_map(Edit::Truncate),
        // Counts and tags are digits: change one to another digit.
        (any::<usize>(), b'0'..=b'9').prop_map(|(i, d)| Edit::Digit(i, d)),
    ]
}

fn apply(data: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut d = data.to_vec();
    for e in edits {
        if d.is_empty() {
            break;
        }
        let at = |i: &usize, d: &Vec<u8>| i % d.len();
        match e {
            Edit::Byte(i, b) => {
                let k = at(i, &d);
                d[k] = *b;
            }
            Edit::Delete(i, n) => {
                let k = at(i, &d);
                let end = (k + n).min(d.len());
                d.drain(k..end);
            }
            Edit::Duplicate(i, n) => {
                let k = at(i, &d);
                let end = (k + n).min(d.len());
                let piece = d[k..end].to_vec();
                d.splice(k..k, piece);
            }
            Edit::Truncate(i) => {
                let k = at(i, &d);
                d.truncate(k);
            }
            Edit::Digit(i, digit) => {
                let digits: Vec<usize> = (0..d.len()).filter(|&j| d[j].is_ascii_digit()).collect();
                if !digits.is_empty() {
                    let k = digits[i % digits.len()];
                    d[k] = *digit;
                }
            }
        }
    }
    d
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn edited_fixtures_never_panic(which in any::<usize>(), edits in prop::collection::vec(edit(), 1..4)) {
        let all = fixtures();
        let (name, data) = &all[which % all.len()];
        let bytes = apply(data, &edits);
        if let Err(e) = parse_msh(&bytes, name) {
            prop_assert!(!e.to_string().is_empty());
        }
    }

    #[test]
    fn garbage_after_a_valid_header_never_panics(tail in prop::collection::vec(any::<u8>(), 0..2000),
                                                 binary in any::<bool>()) {
        let mut bytes = if binary {
            b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n".to_vec()
        } else {
            b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n".to_vec()
        };
        bytes.extend_from_slice(&tail);
        let _ = parse_msh(&bytes, "garbage.msh");
    }
}
