//! Random edits of valid files: numbers swapped for hostile values, lines dropped or doubled,
//! bytes changed, inserted or cut, JSON values replaced, floats in binary records poisoned.
//! Each edit picks its place with an unbounded index taken modulo the file's size, so every
//! generated edit applies to any file.

use proptest::prelude::*;
use proptest::sample::select;

/// Values a hostile or careless user writes in place of a number (TOML and JSON spellings).
const NUMBERS: &[&str] = &[
    "0",
    "-0.0",
    "1",
    "-1",
    "0.5",
    "2",
    "1e-20",
    "-1e-20",
    "1e300",
    "-1e300",
    "nan",
    "inf",
    "-inf",
    "1e9",
    "1e6",
    "65535",
    "65536",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "3.5e38",
    "1e-320",
    "100000",
    "-86401",
    "2001",
    "0.1",
    "0.009",
    "512",
    "100001",
    "\"\"",
    "[]",
    "\"x\"",
    "true",
    "{}",
];

/// JSON values put in place of any node of a JSON file.
const JSON_VALUES: &[&str] = &[
    "0",
    "-1",
    "1.5",
    "1e300",
    "-1e300",
    "1e-300",
    "65536",
    "4294967296",
    "null",
    "true",
    "\"\"",
    "\"spgp\"",
    "\"spgp-het\"",
    "\"full\"",
    "\"patch\"",
    "\"gabor\"",
    "[]",
    "{}",
    "[1e300]",
    "[[0.0]]",
    "\"patchflow-dataset\"",
];

/// Floats written over a binary record.
const FLOATS: &[f32] = &[
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    -f32::MAX,
    1e30,
    0.0,
    -1.0,
    1e-40,
    65536.0,
];

/// One edit of a file.
#[derive(Debug, Clone)]
pub enum Edit {
    /// Replace the `nth` number of a text with a hostile value.
    Number(usize, &'static str),
    /// Replace the `nth` node of a JSON document with another value.
    JsonNode(usize, &'static str),
    /// Delete the `nth` line.
    DeleteLine(usize),
    /// Write the `nth` line twice.
    DuplicateLine(usize),
    /// Overwrite one byte.
    Byte(usize, u8),
    /// Insert bytes.
    Insert(usize, Vec<u8>),
    /// Cut the file at a position.
    Truncate(usize),
    /// Overwrite the 4-byte word at a position with a float.
    Float(usize, f32),
}

/// One to three edits.
pub fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        4 => (any::<usize>(), select(NUMBERS)).prop_map(|(n, v)| Edit::Number(n, v)),
        3 => (any::<usize>(), select(JSON_VALUES)).prop_map(|(n, v)| Edit::JsonNode(n, v)),
        1 => any::<usize>().prop_map(Edit::DeleteLine),
        1 => any::<usize>().prop_map(Edit::DuplicateLine),
        1 => (any::<usize>(), any::<u8>()).prop_map(|(at, b)| Edit::Byte(at, b)),
        1 => (any::<usize>(), proptest::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(at, bytes)| Edit::Insert(at, bytes)),
        1 => any::<usize>().prop_map(Edit::Truncate),
        2 => (any::<usize>(), select(FLOATS)).prop_map(|(at, v)| Edit::Float(at, v)),
    ];
    proptest::collection::vec(edit, 1..4)
}

/// Applies `edits` in order to the bytes of a file.
pub fn apply(bytes: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for edit in edits {
        out = apply_one(out, edit);
    }
    out
}

fn apply_one(mut b: Vec<u8>, edit: &Edit) -> Vec<u8> {
    let at = |i: usize, len: usize| if len == 0 { 0 } else { i % len };
    match edit {
        Edit::Number(n, value) => {
            let numbers = number_spans(&b);
            if let Some(&(start, end)) = numbers.get(at(*n, numbers.len())) {
                b.splice(start..end, value.bytes());
            }
        }
        Edit::JsonNode(n, value) => {
            if let (Ok(mut doc), Ok(new)) = (
                serde_json::from_slice::<serde_json::Value>(&b),
                serde_json::from_str::<serde_json::Value>(value),
            ) {
                let mut pointers = Vec::new();
                collect_pointers(&doc, String::new(), &mut pointers);
                let pointer = &pointers[at(*n, pointers.len())];
                if let Some(node) = doc.pointer_mut(pointer) {
                    *node = new;
                }
                b = serde_json::to_vec_pretty(&doc).unwrap_or(b);
            }
        }
        Edit::DeleteLine(n) | Edit::DuplicateLine(n) => {
            let mut lines: Vec<&[u8]> = b.split_inclusive(|&c| c == b'\n').collect();
            let k = at(*n, lines.len());
            if !lines.is_empty() {
                if matches!(edit, Edit::DeleteLine(_)) {
                    lines.remove(k);
                } else {
                    lines.insert(k, lines[k]);
                }
            }
            b = lines.concat();
        }
        Edit::Byte(i, byte) => {
            let k = at(*i, b.len());
            if let Some(c) = b.get_mut(k) {
                *c = *byte;
            }
        }
        Edit::Insert(i, bytes) => {
            let k = at(*i, b.len() + 1);
            b.splice(k..k, bytes.iter().copied());
        }
        Edit::Truncate(i) => b.truncate(at(*i, b.len() + 1)),
        Edit::Float(i, v) => {
            let words = b.len() / 4;
            if words > 0 {
                let k = 4 * at(*i, words);
                b[k..k + 4].copy_from_slice(&v.to_le_bytes());
            }
        }
    }
    b
}

/// Byte ranges of the numbers of a text: a digit (or a sign before one) not inside a word,
/// and the digits, dots, exponents and signs that follow.
fn number_spans(b: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let in_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
        let signed = b[i] == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit);
        if !in_word && (b[i].is_ascii_digit() || signed) {
            let start = i;
            i += 1;
            while i < b.len()
                && matches!(b[i], b'0'..=b'9' | b'.' | b'e' | b'E' | b'+' | b'-' | b'_')
            {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

/// JSON pointers of every node of `value`, depth first.
fn collect_pointers(value: &serde_json::Value, here: String, out: &mut Vec<String>) {
    match value {
        serde_json::Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                collect_pointers(item, format!("{here}/{i}"), out);
            }
        }
        serde_json::Value::Object(map) => {
            for (key, item) in map {
                let key = key.replace('~', "~0").replace('/', "~1");
                collect_pointers(item, format!("{here}/{key}"), out);
            }
        }
        _ => {}
    }
    out.push(here);
}

#[test]
fn number_edits_replace_whole_numbers_and_skip_names() {
    let text = b"train01 = [1.5e3, -2]\n";
    assert_eq!(number_spans(text), vec![(11, 16), (18, 20)]);
    let edited = apply(text, &[Edit::Number(1, "nan")]);
    assert_eq!(edited, b"train01 = [1.5e3, nan]\n");
}

#[test]
fn json_edits_replace_one_node() {
    let edited = apply(br#"{"a": [1, 2]}"#, &[Edit::JsonNode(1, "null")]);
    let value: serde_json::Value = serde_json::from_slice(&edited).unwrap();
    assert_eq!(value, serde_json::json!({"a": [1, null]}));
}
