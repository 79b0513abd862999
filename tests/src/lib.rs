//! Shared fixtures of patchflow's cross-crate tests. The tests themselves sit beside this folder,
//! one behaviour per file, declared as `[[test]]` targets in `tests/Cargo.toml`.

/// The workspace root, for tests that read `scenarios/`.
pub fn workspace_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}
