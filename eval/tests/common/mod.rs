//! Shared helpers of the CLI tests: run the release binary, check a clean failure, make a tiny dataset.

#![allow(clippy::unwrap_used, dead_code)] // test code; each test file uses some of the helpers

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `patchflow` with `args`.
pub fn patchflow(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_patchflow"))
        .args(args)
        .output()
        .unwrap()
}

/// Standard error as text.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Exit 1, no panic, and every text of `must_mention` in the message.
pub fn assert_clean_failure(output: &Output, must_mention: &[&str]) {
    let err = stderr(output);
    assert_eq!(
        output.status.code(),
        Some(1),
        "exit status {:?}, stderr: {err}",
        output.status
    );
    assert!(!err.contains("panicked"), "panic: {err}");
    for text in must_mention {
        assert!(err.contains(text), "stderr lacks {text:?}: {err}");
    }
}

/// Exit 0, or the message.
pub fn assert_success(output: &Output) {
    assert!(output.status.success(), "{}", stderr(output));
}

/// The shipped test scene (`scenarios/tiny.toml`: 3 sweeps, a crossing target).
pub fn tiny_scenario() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/tiny.toml")
}

/// Generates the scenario file `scenario` into `out` with the default seed.
pub fn generate_file(scenario: &Path, out: &Path) -> Output {
    patchflow(&[
        "generate",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

/// Generates the scenario file `scenario` with `seed` into `out`.
pub fn generate_seeded(scenario: &Path, out: &Path, seed: u64) -> Output {
    let seed = seed.to_string();
    patchflow(&[
        "generate",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--seed",
        &seed,
    ])
}

/// Generates `scenarios/tiny.toml` with `seed` into `out`.
pub fn generate_tiny(out: &Path, seed: u64) -> Output {
    generate_seeded(&tiny_scenario(), out, seed)
}

/// Runs `evaluate` with `model` on `data`, writing the report to `out`.
pub fn evaluate(model: &Path, data: &Path, out: &Path) -> Output {
    patchflow(&[
        "evaluate",
        "--model",
        model.to_str().unwrap(),
        "--data",
        data.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ])
}

/// Trains a small SPGP model on `data` into `model`.
pub fn train_small(data: &Path, model: &Path) -> Output {
    train_small_with(data, model, &[])
}

/// [`train_small`] with more arguments (`--preset thesis`).
pub fn train_small_with(data: &Path, model: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "train",
        "--data",
        data.to_str().unwrap(),
        "--out",
        model.to_str().unwrap(),
        "--gp",
        "spgp",
        "--samples",
        "40",
        "--pseudo",
        "5",
    ];
    args.extend_from_slice(extra);
    patchflow(&args)
}

/// Every file under `root` with its bytes, sorted by path.
pub fn files(root: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![root.to_owned()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                out.push((
                    path.strip_prefix(root).unwrap().to_owned(),
                    std::fs::read(&path).unwrap(),
                ));
            }
        }
    }
    out.sort();
    out
}
