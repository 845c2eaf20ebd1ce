//! Property-based fuzzing of the study parsers, on a bounded budget that runs in `cargo test`
//! (proptest; about a second in release): whatever the input, parsing and building never panic
//! or overflow the stack - they return a value or an error.
//!
//! - expressions: token soups of the grammar's own pieces (numbers, names, operators,
//!   parentheses, commas, functions) and arbitrary strings; a parsed expression evaluates
//!   without panicking at any point;
//! - study files: the shipped plate study with up to four random edits (a character replaced,
//!   a token inserted, a line deleted or duplicated), then `Study::from_source` (TOML, schema,
//!   parameters, limits, mesh, model, quantities, methods).

use alea_study::Source;
use alea_study::expr::Expr;
use alea_study::runner::Study;
use proptest::prelude::*;

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

const TOKENS: &[&str] = &[
    "1", "0", "2.5", "1e308", "1e-308", "3.", ".5", "1e", "x", "y", "a", "pi", "_b", "+", "-", "*",
    "/", "^", "(", ")", ",", " ", "sin(", "exp(", "min(", "pow(", "atan2(", "ln(", "sqrt(", "$",
    "é", "\n", "((((", "))))", "----", "^^", "1e999",
];

fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(TOKENS), 0..60).prop_map(|v| v.concat())
}

proptest! {
    #![proptest_config(config(2000))]

    #[test]
    fn expressions_never_panic(text in prop_oneof![token_soup(), ".{0,80}"],
                               vals in prop::array::uniform3(prop::num::f64::ANY)) {
        if let Ok(e) = Expr::parse(&text, &["x", "y", "a"]) {
            let _ = e.eval(&vals);
            let _ = e.uses(2);
        }
    }
}

const PLATE: &str = include_str!("../../../examples/plate-random-E.toml");

const INSERTS: &[&str] = &[
    "[",
    "]",
    "{",
    "}",
    "=",
    "\"",
    ",",
    "#",
    "\n",
    "[[method]]\n",
    "[[quantity]]\n",
    "[statistics]\n",
    "-1",
    "0",
    "1e400",
    "nan",
    "inf",
    "true",
    "\"x\"",
    "9999999999999999999",
    "[[parameter]]\nname = \"E\"\n",
    "[[substructure]]\n",
    "[[interface]]\n",
    "[0, 0]",
    "((((((((((",
    "kind = \"tet10\"\n",
    "law = \"beta\"\n",
    "design = \"grid\"\n",
];

#[derive(Clone, Debug)]
enum Edit {
    Replace(usize, char),
    Insert(usize, &'static str),
    DeleteLine(usize),
    DuplicateLine(usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), prop::char::range(' ', '~')).prop_map(|(i, c)| Edit::Replace(i, c)),
        (any::<usize>(), prop::sample::select(INSERTS)).prop_map(|(i, s)| Edit::Insert(i, s)),
        any::<usize>().prop_map(Edit::DeleteLine),
        any::<usize>().prop_map(Edit::DuplicateLine),
    ]
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut t = text.to_string();
    for e in edits {
        match e {
            Edit::Replace(i, c) => {
                let chars: Vec<char> = t.chars().collect();
                if chars.is_empty() {
                    continue;
                }
                let k = i % chars.len();
                t = chars
                    .iter()
                    .enumerate()
                    .map(|(j, &x)| if j == k { *c } else { x })
                    .collect();
            }
            Edit::Insert(i, s) => {
                let k = i % (t.len() + 1);
                let k = (0..=k).rev().find(|&k| t.is_char_boundary(k)).unwrap_or(0);
                t.insert_str(k, s);
            }
            Edit::DeleteLine(i) | Edit::DuplicateLine(i) => {
                let mut lines: Vec<&str> = t.lines().collect();
                if lines.is_empty() {
                    continue;
                }
                let k = i % lines.len();
                if matches!(e, Edit::DeleteLine(_)) {
                    lines.remove(k);
                } else {
                    lines.insert(k, lines[k]);
                }
                t = lines.join("\n");
            }
        }
    }
    t
}

proptest! {
    #![proptest_config(config(1000))]

    #[test]
    fn study_files_never_panic(edits in prop::collection::vec(edit(), 1..5)) {
        let text = apply(PLATE, &edits);
        match Study::from_source(Source::from_text("fuzz.toml", &text)) {
            Ok(study) => {
                prop_assert!(!study.all_points().is_empty());
            }
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(!msg.is_empty());
                prop_assert!((2..=5).contains(&e.exit_code()), "{msg}");
            }
        }
    }
}

#[test]
fn deeply_nested_toml_is_an_error_not_a_stack_overflow() {
    for n in [1_000, 100_000] {
        let arrays = format!("{PLATE}\nextra = {}1{}\n", "[".repeat(n), "]".repeat(n));
        let tables = format!("{PLATE}\nextra = {}1{}\n", "{a = ".repeat(n), "}".repeat(n));
        for text in [arrays, tables] {
            let r = std::thread::Builder::new()
                .stack_size(2 << 20)
                .spawn(move || {
                    Study::from_source(Source::from_text("deep.toml", &text)).map(|_| ())
                })
                .unwrap()
                .join()
                .expect("no stack overflow");
            assert_eq!(r.unwrap_err().exit_code(), 2);
        }
    }
}
