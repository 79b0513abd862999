//! No two files of one crate import each other (issue #16): a file that imports a file which
//! imports it back is one concept split in two, or two concepts tangled, and a change to either
//! ripples into both. The test reads every library and binary source file of the workspace,
//! resolves each `crate::…` and `super::…` path (names re-exported by a `lib.rs` or `mod.rs` are
//! followed to the file that defines them), and lists every pair of files that import each
//! other. Test modules (from `#[cfg(test)]` on) are left out, since a test may use its
//! neighbours' fixtures, and so are comments, whose doc links import nothing.
//!
//! The same holds one level up (issue 29): the rooms of a crate (the modules directly under its
//! `src/`, a folder with all its files or a single file) form a ladder, so no two rooms import
//! each other, directly, in either direction.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The source roots of the workspace's crates, relative to the workspace root.
const CRATE_ROOTS: [&str; 7] = [
    "sim/dataset/src",
    "sim/src",
    "learn/gp/src",
    "learn/src",
    "learn/occupancy/src",
    "eval/src",
    "eval/src/bin/patchflow",
];

/// One source file: its module path inside its crate and its text without test modules.
struct SourceFile {
    path: PathBuf,
    module: Vec<String>,
    /// Whether the file is the root of its module folder (`lib.rs`, `main.rs`, `mod.rs`).
    folder_root: bool,
    text: String,
}

fn sources(root: &Path, skip: &[PathBuf]) -> Vec<SourceFile> {
    let mut files = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("reading a source folder") {
            let path = entry.expect("a folder entry").path();
            if path.is_dir() {
                if !skip.contains(&path) {
                    stack.push(path);
                }
                continue;
            }
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            if !name.ends_with(".rs") || name.ends_with("_tests.rs") {
                continue;
            }
            let relative = path.strip_prefix(root).expect("inside the root");
            let mut module: Vec<String> = relative
                .with_extension("")
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            let folder_root = matches!(name, "lib.rs" | "main.rs" | "mod.rs");
            if folder_root {
                module.pop();
            }
            let text = std::fs::read_to_string(&path).expect("reading a source file");
            let text = match text.find("#[cfg(test)]") {
                Some(at) => &text[..at],
                None => &text,
            };
            // Comments (doc links included) name items without importing them.
            let text: String = text
                .lines()
                .map(|line| line.find("//").map_or(line, |at| &line[..at]))
                .collect::<Vec<_>>()
                .join("\n");
            files.push(SourceFile {
                path,
                module,
                folder_root,
                text,
            });
        }
    }
    files
}

/// Every path that starts at `at` in `text` (after `crate::` or `super::`), with `{…}` groups
/// expanded: `a::{b, c::d}` gives `a::b` and `a::c::d`.
fn expand(text: &str) -> Vec<Vec<String>> {
    fn path(
        chars: &[char],
        mut i: usize,
        prefix: Vec<String>,
        out: &mut Vec<Vec<String>>,
    ) -> usize {
        let mut segments = prefix;
        loop {
            while i < chars.len() && chars[i].is_whitespace() {
                i += 1;
            }
            if i < chars.len() && chars[i] == '{' {
                i += 1;
                loop {
                    i = path(chars, i, segments.clone(), out);
                    while i < chars.len() && chars[i].is_whitespace() {
                        i += 1;
                    }
                    match chars.get(i) {
                        Some(',') => i += 1,
                        Some('}') => return i + 1,
                        _ => return i,
                    }
                    while i < chars.len() && chars[i].is_whitespace() {
                        i += 1;
                    }
                    if chars.get(i) == Some(&'}') {
                        return i + 1;
                    }
                }
            }
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            if i > start {
                segments.push(chars[start..i].iter().collect());
            }
            if chars.get(i) == Some(&':') && chars.get(i + 1) == Some(&':') {
                i += 2;
                continue;
            }
            out.push(segments);
            return i;
        }
    }
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    path(&chars, 0, Vec::new(), &mut out);
    out
}

/// The crate-absolute paths a file refers to.
fn referenced_paths(file: &SourceFile) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    for (anchor, base) in [
        ("crate::", Vec::new()),
        ("super::", {
            let mut m = file.module.clone();
            if !file.folder_root || !m.is_empty() {
                m.pop();
            }
            m
        }),
    ] {
        let mut from = 0;
        while let Some(at) = file.text[from..].find(anchor) {
            let start = from + at;
            from = start + anchor.len();
            let before = file.text[..start].chars().last();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            for rest in expand(&file.text[from..]) {
                let mut full = base.clone();
                full.extend(rest);
                paths.push(full);
            }
        }
    }
    paths
}

/// Public items each file defines, by name (for following re-exports).
fn definitions(files: &[SourceFile]) -> BTreeMap<String, BTreeSet<usize>> {
    let mut defined: BTreeMap<String, BTreeSet<usize>> = BTreeMap::new();
    for (f, file) in files.iter().enumerate() {
        for line in file.text.lines() {
            let line = line.trim_start();
            let Some(rest) = line
                .strip_prefix("pub ")
                .or_else(|| line.strip_prefix("pub(crate) "))
            else {
                continue;
            };
            let mut words = rest.split_whitespace();
            let kind = words.next().unwrap_or("");
            if matches!(kind, "struct" | "enum" | "fn" | "trait" | "type" | "const") {
                let name: String = words
                    .next()
                    .unwrap_or("")
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                defined.entry(name).or_default().insert(f);
            }
        }
    }
    defined
}

/// The files a file imports (by index), resolving paths to the longest module prefix and names
/// re-exported by folder roots to their defining file.
fn imports(
    files: &[SourceFile],
    f: usize,
    defined: &BTreeMap<String, BTreeSet<usize>>,
) -> BTreeSet<usize> {
    let by_module: BTreeMap<&[String], usize> = files
        .iter()
        .enumerate()
        .map(|(i, s)| (s.module.as_slice(), i))
        .collect();
    let mut out = BTreeSet::new();
    for path in referenced_paths(&files[f]) {
        let Some(len) = (0..=path.len())
            .rev()
            .find(|&n| by_module.contains_key(&path[..n]))
        else {
            continue;
        };
        let mut target = by_module[&path[..len]];
        if files[target].folder_root && len < path.len() {
            // A name re-exported by lib.rs or mod.rs: its home is the file that defines it.
            match defined.get(&path[len]) {
                Some(homes) if homes.len() == 1 => target = *homes.iter().next().unwrap_or(&target),
                _ => continue,
            }
        }
        if target != f && !files[target].folder_root {
            out.insert(target);
        }
    }
    out
}

/// The room of a file: the first segment of its module path (none for the crate root).
fn room(file: &SourceFile) -> Option<&str> {
    file.module.first().map(String::as_str)
}

/// The other rooms a file imports: the first segment of each `crate::…` or `super::…` path, or
/// for a name the crate root re-exports, the room of the file that defines it.
fn room_imports(
    files: &[SourceFile],
    f: usize,
    defined: &BTreeMap<String, BTreeSet<usize>>,
) -> BTreeSet<String> {
    let rooms: BTreeSet<&str> = files.iter().filter_map(room).collect();
    let mut out = BTreeSet::new();
    for path in referenced_paths(&files[f]) {
        let Some(first) = path.first() else {
            continue;
        };
        let target = if rooms.contains(first.as_str()) {
            Some(first.as_str())
        } else {
            match defined.get(first) {
                Some(homes) if homes.len() == 1 => {
                    homes.iter().next().and_then(|&h| room(&files[h]))
                }
                _ => None,
            }
        };
        if let Some(target) = target.filter(|&t| Some(t) != room(&files[f])) {
            out.insert(target.to_owned());
        }
    }
    out
}

/// Every pair of rooms under `root` that import each other, as `a <-> b` (a before b).
fn two_way_rooms(root: &Path, skip: &[PathBuf]) -> (usize, Vec<String>) {
    let files = sources(root, skip);
    let defined = definitions(&files);
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (f, file) in files.iter().enumerate() {
        if let Some(from) = room(file) {
            edges
                .entry(from.to_owned())
                .or_default()
                .extend(room_imports(&files, f, &defined));
        }
    }
    let mut ties = Vec::new();
    for (a, targets) in &edges {
        for b in targets.iter().filter(|b| *b > a) {
            if edges.get(b).is_some_and(|back| back.contains(a)) {
                ties.push(format!("{} <-> {}", a, b));
            }
        }
    }
    (files.len(), ties)
}

#[test]
fn no_two_rooms_of_a_crate_import_each_other() {
    let workspace = patchflow_tests::workspace_root();
    let roots: Vec<PathBuf> = CRATE_ROOTS.iter().map(|r| workspace.join(r)).collect();
    let mut ties = Vec::new();
    let mut files_seen = 0;
    for (root, name) in roots.iter().zip(CRATE_ROOTS) {
        let skip: Vec<PathBuf> = roots.iter().filter(|r| *r != root).cloned().collect();
        let (files, pairs) = two_way_rooms(root, &skip);
        files_seen += files;
        ties.extend(pairs.into_iter().map(|pair| format!("{name}: {pair}")));
    }
    assert!(files_seen > 100, "read only {files_seen} source files");
    assert!(ties.is_empty(), "rooms importing each other: {ties:#?}");
}

#[test]
fn a_room_importing_a_room_that_imports_it_back_is_found() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let write = |path: &str, text: &str| {
        let path = dir.path().join(path);
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("a folder");
        std::fs::write(path, text).expect("a source file");
    };
    write("lib.rs", "mod bench;\nmod study;\npub use study::Plan;\n");
    write("bench/mod.rs", "mod run;\n");
    write("bench/run.rs", "use crate::study::plan::Plan;\n");
    write("study/mod.rs", "pub mod plan;\npub use plan::Plan;\n");
    write("study/plan.rs", "pub struct Plan;\n");
    let (_, ties) = two_way_rooms(dir.path(), &[]);
    assert!(ties.is_empty(), "one way only: {ties:?}");
    // The study now uses the bench through the crate root's re-export: a tie.
    write("lib.rs", "mod bench;\nmod study;\npub use bench::Run;\n");
    write("bench/mod.rs", "mod run;\npub use run::Run;\n");
    write(
        "bench/run.rs",
        "use crate::study::plan::Plan;\npub struct Run;\n",
    );
    write("study/plan.rs", "use crate::Run;\npub struct Plan;\n");
    let (_, ties) = two_way_rooms(dir.path(), &[]);
    assert_eq!(ties, ["bench <-> study"]);
}

#[test]
fn no_two_files_of_a_crate_import_each_other() {
    let workspace = patchflow_tests::workspace_root();
    let roots: Vec<PathBuf> = CRATE_ROOTS.iter().map(|r| workspace.join(r)).collect();
    let mut circles = Vec::new();
    let mut files_seen = 0;
    for root in &roots {
        let skip: Vec<PathBuf> = roots.iter().filter(|r| *r != root).cloned().collect();
        let files = sources(root, &skip);
        files_seen += files.len();
        let defined = definitions(&files);
        let edges: Vec<BTreeSet<usize>> = (0..files.len())
            .map(|f| imports(&files, f, &defined))
            .collect();
        for (a, targets) in edges.iter().enumerate() {
            for &b in targets.iter().filter(|&&b| b > a) {
                if edges[b].contains(&a) {
                    circles.push(format!(
                        "{} <-> {}",
                        files[a]
                            .path
                            .strip_prefix(&workspace)
                            .unwrap_or(&files[a].path)
                            .display(),
                        files[b]
                            .path
                            .strip_prefix(&workspace)
                            .unwrap_or(&files[b].path)
                            .display()
                    ));
                }
            }
        }
    }
    assert!(files_seen > 100, "read only {files_seen} source files");
    assert!(
        circles.is_empty(),
        "files importing each other:\n{}",
        circles.join("\n")
    );
}

#[test]
fn the_path_reader_expands_nested_groups() {
    let paths = expand("features::{sampler::{Rank, Run}, samples::Sample};");
    let joined: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        joined,
        [
            "features::sampler::Rank",
            "features::sampler::Run",
            "features::samples::Sample"
        ]
    );
}
