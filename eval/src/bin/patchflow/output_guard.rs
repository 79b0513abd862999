//! The one check every subcommand runs before it writes: its output never is, contains or lies
//! inside one of its inputs (after resolving symbolic links, `..` and relative paths), and an
//! output that exists is of the kind the command writes (a folder or a file), so nothing a user
//! owns is overwritten and no command fails after minutes of work on an unusable `--out`.

use std::path::{Component, Path, PathBuf};

/// What a command writes at its `--out`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// One file (a model, a CSV, a figure).
    File,
    /// A folder of files (a report, a dataset).
    Folder,
}

/// One path a command reads, with the option that named it (`--data`, `--model`, …).
#[derive(Debug, Clone, Copy)]
pub struct Input<'a> {
    /// The option or argument, for the message.
    pub option: &'a str,
    /// The path as given.
    pub path: &'a Path,
}

impl<'a> Input<'a> {
    /// An input named by `option`.
    pub fn new(option: &'a str, path: &'a Path) -> Self {
        Self { option, path }
    }
}

/// Refuses `output` (given as `--out`, written as `kind`) when it is, contains or lies inside one
/// of `inputs`, or when it exists as the other kind; the error names both paths.
pub fn check_output(output: &Path, kind: OutputKind, inputs: &[Input<'_>]) -> anyhow::Result<()> {
    check_kind(output, kind)?;
    let out = resolve(output)?;
    for input in inputs {
        let Ok(inp) = resolve(input.path) else {
            continue; // an input that cannot be resolved is reported when it is read
        };
        let relation = if out == inp {
            "is"
        } else if inp.starts_with(&out) {
            "contains"
        } else if out.starts_with(&inp) {
            "lies inside"
        } else {
            continue;
        };
        anyhow::bail!(
            "--out {} {relation} the input {} {}: a command never writes over what it reads; choose another output",
            output.display(),
            input.option,
            input.path.display()
        );
    }
    Ok(())
}

/// Refuses an existing output of the wrong kind, in words.
fn check_kind(output: &Path, kind: OutputKind) -> anyhow::Result<()> {
    let Ok(meta) = std::fs::metadata(output) else {
        return Ok(());
    };
    match kind {
        OutputKind::Folder if !meta.is_dir() => anyhow::bail!(
            "--out {} is an existing file, not a folder: this command writes a folder of files there; remove the file or choose another path",
            output.display()
        ),
        OutputKind::File if meta.is_dir() => anyhow::bail!(
            "--out {} is an existing folder: this command writes one file; name a file inside it",
            output.display()
        ),
        OutputKind::File if !meta.is_file() => anyhow::bail!(
            "--out {} is not a regular file (a pipe, device or socket): this command writes a regular file",
            output.display()
        ),
        _ => Ok(()),
    }
}

/// The absolute path `path` stands for, symbolic links resolved: the canonical form of its
/// deepest existing ancestor with the rest appended (`..` in the rest taken lexically).
pub fn resolve(path: &Path) -> anyhow::Result<PathBuf> {
    let absolute = match path.is_absolute() {
        true => path.to_owned(),
        false => std::env::current_dir()?.join(path),
    };
    let mut rest = Vec::new();
    let mut existing = absolute.as_path();
    loop {
        match std::fs::canonicalize(existing) {
            Ok(mut resolved) => {
                for part in rest.iter().rev() {
                    match part {
                        Component::ParentDir => {
                            resolved.pop();
                        }
                        Component::Normal(name) => resolved.push(name),
                        _ => {}
                    }
                }
                return Ok(resolved);
            }
            Err(err) => {
                if err.raw_os_error() == Some(40) {
                    anyhow::bail!(
                        "{}: a loop of symbolic links (ELOOP): the path never reaches a file",
                        path.display()
                    );
                }
                let (Some(parent), Some(last)) =
                    (existing.parent(), existing.components().next_back())
                else {
                    return Ok(absolute);
                };
                rest.push(last);
                existing = parent;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(output: &Path, kind: OutputKind, input: &Path) -> String {
        let inputs = [Input::new("--data", input)];
        match check_output(output, kind, &inputs) {
            Ok(()) => String::new(),
            Err(err) => err.to_string(),
        }
    }

    #[test]
    fn an_output_equal_to_inside_or_around_an_input_is_refused_naming_both() {
        let dir = tempfile::tempdir().expect("temp dir");
        let data = dir.path().join("D");
        std::fs::create_dir_all(data.join("sequences")).expect("mkdir");
        std::fs::write(data.join("manifest.json"), "{}").expect("writes");
        let msg = refused(&data, OutputKind::Folder, &data);
        assert!(
            msg.contains(" is the input --data") && msg.contains("D"),
            "{msg}"
        );
        let msg = refused(&data.join("manifest.json"), OutputKind::File, &data);
        assert!(msg.contains("lies inside"), "{msg}");
        let msg = refused(&data.join("new/deeper"), OutputKind::Folder, &data);
        assert!(msg.contains("lies inside"), "{msg}");
        let msg = refused(dir.path(), OutputKind::Folder, &data);
        assert!(msg.contains("contains"), "{msg}");
        let msg = refused(&data.join("sequences/../x.csv"), OutputKind::File, &data);
        assert!(msg.contains("lies inside"), "{msg}");
        assert_eq!(
            refused(&dir.path().join("E"), OutputKind::Folder, &data),
            ""
        );
    }

    #[test]
    fn a_symlinked_output_is_compared_by_where_it_leads() {
        let dir = tempfile::tempdir().expect("temp dir");
        let csv = dir.path().join("x.csv");
        std::fs::write(&csv, "a,b\n1,2\n").expect("writes");
        let link = dir.path().join("link.csv");
        std::os::unix::fs::symlink(&csv, &link).expect("symlink");
        assert!(refused(&link, OutputKind::File, &csv).contains(" is the input"));
        let folder = dir.path().join("f");
        std::fs::create_dir(&folder).expect("mkdir");
        let folder_link = dir.path().join("g");
        std::os::unix::fs::symlink(&folder, &folder_link).expect("symlink");
        let msg = refused(&folder_link.join("new.json"), OutputKind::File, &folder);
        assert!(msg.contains("lies inside"), "{msg}");
    }

    #[test]
    fn an_existing_output_of_the_wrong_kind_is_named_in_words() {
        let dir = tempfile::tempdir().expect("temp dir");
        let file = dir.path().join("report");
        std::fs::write(&file, "x").expect("writes");
        let msg = refused(&file, OutputKind::Folder, Path::new("/nonexistent-input"));
        assert!(msg.contains("is an existing file, not a folder"), "{msg}");
        let msg = refused(
            dir.path(),
            OutputKind::File,
            Path::new("/nonexistent-input"),
        );
        assert!(msg.contains("is an existing folder"), "{msg}");
    }

    #[test]
    fn a_symlink_loop_is_named_as_a_loop() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (a, b) = (dir.path().join("a"), dir.path().join("b"));
        std::os::unix::fs::symlink(&b, &a).expect("symlink");
        std::os::unix::fs::symlink(&a, &b).expect("symlink");
        let err = resolve(&a).expect_err("a loop");
        assert!(err.to_string().contains("loop"), "{err}");
    }
}
