//! The size rules of issue 29, kept true as the code and the docs grow: no source file over 400
//! lines (one concept per file; a file past that holds two) and no line of the Markdown docs over
//! 120 characters (they are read in a terminal and in diffs, where longer lines wrap or hide).

use std::path::{Path, PathBuf};

/// Longest source file, lines.
const MAX_SOURCE_LINES: usize = 400;
/// Longest line of the docs, characters.
const MAX_DOC_LINE_CHARS: usize = 120;

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the tests crate sits in the workspace")
        .to_path_buf()
}

/// Every file under `dir` whose name ends in `extension`, skipping build output and hidden folders.
/// Build output is any folder Cargo tagged as a cache (`CACHEDIR.TAG`, which it writes into every
/// target directory, whatever `CARGO_TARGET_DIR` names it), and `target`.
fn files_under(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(folder) = stack.pop() {
        for entry in std::fs::read_dir(&folder).expect("reading a folder of the workspace") {
            let path = entry.expect("a folder entry").path();
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            let name = name.unwrap_or_default();
            if path.is_dir() {
                let build_output = name == "target" || path.join("CACHEDIR.TAG").is_file();
                if !name.starts_with('.') && !build_output {
                    stack.push(path);
                }
            } else if name.ends_with(extension) {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

#[test]
fn no_source_file_is_longer_than_four_hundred_lines() {
    let root = workspace_root();
    let long: Vec<String> = files_under(&root, ".rs")
        .into_iter()
        .filter_map(|path| {
            let lines = std::fs::read_to_string(&path).ok()?.lines().count();
            (lines > MAX_SOURCE_LINES).then(|| format!("{} ({lines} lines)", path.display()))
        })
        .collect();
    assert!(long.is_empty(), "over {MAX_SOURCE_LINES} lines: {long:#?}");
}

#[test]
fn no_line_of_the_docs_is_longer_than_a_hundred_and_twenty_characters() {
    let root = workspace_root();
    let mut docs: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "CONTRIBUTING.md"]
        .iter()
        .map(|name| root.join(name))
        .collect();
    docs.extend(files_under(&root.join("docs"), ".md"));
    docs.push(root.join("scenarios/README.md"));
    assert!(
        docs.len() > 5,
        "the docs were not found under {}",
        root.display()
    );
    let mut long = Vec::new();
    for path in docs {
        let text = std::fs::read_to_string(&path).expect("reading a doc");
        for (number, line) in text.lines().enumerate() {
            let chars = line.chars().count();
            if chars > MAX_DOC_LINE_CHARS {
                long.push(format!(
                    "{}:{} ({chars} characters)",
                    path.display(),
                    number + 1
                ));
            }
        }
    }
    assert!(
        long.is_empty(),
        "over {MAX_DOC_LINE_CHARS} characters: {long:#?}"
    );
}
