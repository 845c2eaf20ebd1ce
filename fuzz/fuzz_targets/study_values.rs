//! The study-file loader past TOML parsing (structure-aware): a shipped study file, parsed,
//! gets up to eight edits chosen by the fuzzer - a value replaced (integers, floats including
//! NaN, infinities and extremes, strings from the study files' own vocabulary or arbitrary,
//! booleans, arrays, tables), a key removed, a known key added to a table, an entry of an array
//! of tables duplicated or removed - and is written back as valid TOML, so that every case
//! reaches the schema, the parameters, the limits, the mesh, the model, the quantities and the
//! methods (`Study::from_source`). Any outcome but a panic is fine: a study or an error.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use alea_study::Source;
use alea_study::runner::Study;
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use toml::{Table, Value};

/// Shipped study files that load in well under a second.
const SEEDS: &[&str] = &[
    "plate-random-E.toml",
    "blade-root-simple.toml",
    "turbine-2d-wear.toml",
    "turbine-2d-wear-adaptive.toml",
    "turbine-2d-wear-goal.toml",
    "hertz-line-contact.toml",
    "block-on-plane-3d.toml",
];

struct Corpus {
    dir: PathBuf,
    files: Vec<(String, Table)>,
    keys: Vec<String>,
    strings: Vec<String>,
}

fn corpus() -> &'static Corpus {
    static C: OnceLock<Corpus> = OnceLock::new();
    C.get_or_init(|| {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../examples");
        let mut files = Vec::new();
        let (mut keys, mut strings) = (Vec::new(), Vec::new());
        for name in SEEDS {
            let text = std::fs::read_to_string(dir.join(name)).expect("shipped study file");
            let table: Table = toml::from_str(&text).expect("shipped study files parse");
            collect(&Value::Table(table.clone()), &mut keys, &mut strings);
            files.push((name.to_string(), table));
        }
        keys.sort();
        keys.dedup();
        strings.sort();
        strings.dedup();
        Corpus {
            dir,
            files,
            keys,
            strings,
        }
    })
}

/// Every key and string value of a document (the vocabulary of the edits).
fn collect(v: &Value, keys: &mut Vec<String>, strings: &mut Vec<String>) {
    match v {
        Value::Table(t) => {
            for (k, v) in t {
                keys.push(k.clone());
                collect(v, keys, strings);
            }
        }
        Value::Array(a) => a.iter().for_each(|v| collect(v, keys, strings)),
        Value::String(s) => strings.push(s.clone()),
        _ => {}
    }
}

/// A step of a path into a document.
#[derive(Clone, Debug)]
enum Step {
    Key(String),
    Index(usize),
}

/// Every path to a value of the document (tables and arrays included).
fn paths(v: &Value, here: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match v {
        Value::Table(t) => {
            for (k, v) in t {
                here.push(Step::Key(k.clone()));
                out.push(here.clone());
                paths(v, here, out);
                here.pop();
            }
        }
        Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                here.push(Step::Index(i));
                out.push(here.clone());
                paths(v, here, out);
                here.pop();
            }
        }
        _ => {}
    }
}

fn get_mut<'v>(v: &'v mut Value, path: &[Step]) -> Option<&'v mut Value> {
    let mut cur = v;
    for s in path {
        cur = match (s, cur) {
            (Step::Key(k), Value::Table(t)) => t.get_mut(k)?,
            (Step::Index(i), Value::Array(a)) => a.get_mut(*i)?,
            _ => return None,
        };
    }
    Some(cur)
}

/// A value chosen by the fuzzer.
#[derive(Arbitrary, Debug)]
enum NewValue {
    Int(i64),
    SmallInt(i8),
    Float(f64),
    Special(u8),
    Word(u16),
    Text(String),
    Bool(bool),
    Array(Vec<Scalar>),
    EmptyTable,
}

#[derive(Arbitrary, Debug)]
enum Scalar {
    Float(f64),
    Int(i16),
    Word(u16),
}

const SPECIAL: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    2.0,
    1e-300,
    1e300,
    f64::MIN_POSITIVE,
    f64::MAX,
    f64::MIN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    f64::NAN,
    1e6,
    1e9,
    1e-9,
];

impl NewValue {
    fn value(&self, c: &Corpus) -> Value {
        let word = |w: u16| Value::String(c.strings[w as usize % c.strings.len()].clone());
        match self {
            NewValue::Int(i) => Value::Integer(*i),
            NewValue::SmallInt(i) => Value::Integer(i64::from(*i)),
            NewValue::Float(x) => Value::Float(*x),
            NewValue::Special(k) => Value::Float(SPECIAL[*k as usize % SPECIAL.len()]),
            NewValue::Word(w) => word(*w),
            NewValue::Text(s) => Value::String(s.clone()),
            NewValue::Bool(b) => Value::Boolean(*b),
            NewValue::Array(v) => Value::Array(
                v.iter()
                    .take(16)
                    .map(|s| match s {
                        Scalar::Float(x) => Value::Float(*x),
                        Scalar::Int(i) => Value::Integer(i64::from(*i)),
                        Scalar::Word(w) => word(*w),
                    })
                    .collect(),
            ),
            NewValue::EmptyTable => Value::Table(Table::new()),
        }
    }
}

/// An edit of the document.
#[derive(Arbitrary, Debug)]
enum Edit {
    /// Replace the value at a path.
    Set { path: u16, value: NewValue },
    /// Remove the value at a path.
    Remove { path: u16 },
    /// Add a key of the vocabulary to the table at a path (or the document).
    Add {
        path: u16,
        key: u16,
        value: NewValue,
    },
    /// Duplicate an entry of an array.
    Duplicate { path: u16 },
}

#[derive(Arbitrary, Debug)]
struct Input {
    file: u8,
    edits: Vec<Edit>,
}

fn apply(doc: &mut Value, edit: &Edit, c: &Corpus) {
    let mut all = Vec::new();
    paths(doc, &mut Vec::new(), &mut all);
    if all.is_empty() {
        return;
    }
    let pick = |p: u16| all[p as usize % all.len()].clone();
    match edit {
        Edit::Set { path, value } => {
            if let Some(v) = get_mut(doc, &pick(*path)) {
                *v = value.value(c);
            }
        }
        Edit::Remove { path } => {
            let p = pick(*path);
            let (last, parent) = p.split_last().expect("paths are not empty");
            match (get_mut(doc, parent), last) {
                (Some(Value::Table(t)), Step::Key(k)) => {
                    t.remove(k);
                }
                (Some(Value::Array(a)), Step::Index(i)) if *i < a.len() => {
                    a.remove(*i);
                }
                _ => {}
            }
        }
        Edit::Add { path, key, value } => {
            let k = c.keys[*key as usize % c.keys.len()].clone();
            let target = match get_mut(doc, &pick(*path)) {
                Some(Value::Table(_)) => pick(*path),
                _ => Vec::new(),
            };
            if let Some(Value::Table(t)) = get_mut(doc, &target) {
                t.insert(k, value.value(c));
            }
        }
        Edit::Duplicate { path } => {
            let p = pick(*path);
            let (last, parent) = p.split_last().expect("paths are not empty");
            if let (Some(Value::Array(a)), Step::Index(i)) = (get_mut(doc, parent), last)
                && *i < a.len()
                && a.len() < 64
            {
                let copy = a[*i].clone();
                a.push(copy);
            }
        }
    }
}

fuzz_target!(|input: Input| {
    let c = corpus();
    let (name, table) = &c.files[input.file as usize % c.files.len()];
    let mut doc = Value::Table(table.clone());
    for edit in input.edits.iter().take(8) {
        apply(&mut doc, edit, c);
    }
    let Value::Table(t) = doc else { return };
    // Values TOML cannot write (a key of an inline table after a table, ...) are not cases.
    let Ok(text) = toml::to_string(&t) else {
        return;
    };
    let source = Source {
        path: c.dir.join(name),
        text,
    };
    let _ = Study::from_source(source);
});
