//! What `generate` checks before it writes into a dataset folder: a `manifest.json` there is one
//! of ours (another file of that name is replaced only with `--overwrite`), and no sequence folder
//! is a symbolic link or leads out of the dataset, so regenerating never touches files elsewhere.

use std::path::Path;

use patchflow_dataset::{FORMAT_NAME, read_limited};

use crate::error::{Result, SimError};

/// Refuses to replace `root/manifest.json` unless it is a patchflow dataset manifest or
/// `overwrite` is set.
pub(crate) fn check_manifest_is_ours(root: &Path, overwrite: bool) -> Result<()> {
    let path = root.join("manifest.json");
    let Ok(meta) = std::fs::symlink_metadata(&path) else {
        return Ok(());
    };
    let ours = meta.is_file()
        && read_limited(&path, 64 << 20).is_ok_and(|bytes| {
            serde_json::from_slice::<serde_json::Map<String, serde_json::Value>>(&bytes)
                .is_ok_and(|map| map.get("format").and_then(|f| f.as_str()) == Some(FORMAT_NAME))
        });
    match (ours, overwrite, meta.is_file()) {
        (true, _, _) => Ok(()),
        (false, true, true) => Ok(()),
        (false, _, false) => Err(SimError::Options(format!(
            "{}: not a regular file (a link, folder or special file); refusing to replace it",
            path.display()
        ))),
        (false, false, true) => Err(SimError::Options(format!(
            "{}: a manifest.json that is not a patchflow dataset's is already there; refusing to replace it (pass --overwrite to replace it, or write to another folder)",
            path.display()
        ))),
    }
}

/// Refuses a sequence folder `root/sequences/name` (or `root/sequences`) that is a symbolic
/// link or resolves outside `root`.
pub(crate) fn check_sequence_folder(root: &Path, name: &str) -> Result<()> {
    let sequences = root.join("sequences");
    for path in [sequences.clone(), sequences.join(name)] {
        let Ok(meta) = std::fs::symlink_metadata(&path) else {
            return Ok(());
        };
        if meta.file_type().is_symlink() || !meta.is_dir() {
            return Err(SimError::Options(format!(
                "{}: a symbolic link or file, not a folder of this dataset; refusing to write or delete through it",
                path.display()
            )));
        }
        let io = |source| SimError::Io {
            path: path.clone(),
            source,
        };
        let (resolved, base) = (
            std::fs::canonicalize(&path).map_err(io)?,
            std::fs::canonicalize(root).map_err(io)?,
        );
        if !resolved.starts_with(&base) {
            return Err(SimError::Options(format!(
                "{}: leads to {} outside the dataset folder; refusing to write or delete there",
                path.display(),
                resolved.display()
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_foreign_manifest_is_kept_unless_overwrite_is_given() {
        let dir = tempfile::tempdir().unwrap();
        assert!(check_manifest_is_ours(dir.path(), false).is_ok());
        std::fs::write(dir.path().join("manifest.json"), r#"{"app": "other"}"#).unwrap();
        let err = check_manifest_is_ours(dir.path(), false).unwrap_err();
        assert!(
            err.to_string().contains("not a patchflow dataset's"),
            "{err}"
        );
        assert!(check_manifest_is_ours(dir.path(), true).is_ok());
        let ours = format!(r#"{{"format": "{FORMAT_NAME}", "version": 1, "sequences": []}}"#);
        std::fs::write(dir.path().join("manifest.json"), ours).unwrap();
        assert!(check_manifest_is_ours(dir.path(), false).is_ok());
    }

    #[test]
    fn a_symlinked_sequence_folder_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("sequences")).unwrap();
        std::os::unix::fs::symlink(elsewhere.path(), dir.path().join("sequences/s")).unwrap();
        let err = check_sequence_folder(dir.path(), "s").unwrap_err();
        assert!(err.to_string().contains("symbolic link"), "{err}");
        assert!(check_sequence_folder(dir.path(), "t").is_ok());
    }

    const TINY: &str = "sweeps = 2\n[lidar]\nchannels = 8\nazimuth_steps = 60\nblocks = 6\n\
        [ego]\npath_m = [[0.0, 0.0], [40.0, 0.0]]\nspeed_mps = 2.0\n\
        [[actors]]\nname = \"car\"\ntarget = true\npath_m = [[8.0, -6.0], [8.0, 40.0]]\nspeed_mps = 6.0\n";

    fn generate(out: &Path, seed: u64, overwrite: bool) -> Result<()> {
        let options = crate::GenerateOptions {
            out: out.to_owned(),
            seed,
            shard: crate::Shard::ALL,
            realism: None,
            overwrite,
        };
        let source = crate::ScenarioSource::Embedded("tiny", TINY);
        crate::generate_dataset(&[source], &options, &|_| {}).map(|_| ())
    }

    #[test]
    fn overwrite_removes_only_what_generate_wrote_and_never_follows_a_link() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("D");
        generate(&out, 1, false).unwrap();
        let mine = out.join("sequences/tiny/my_notes.txt");
        std::fs::write(&mine, "keep me").unwrap();
        generate(&out, 2, true).unwrap();
        assert_eq!(std::fs::read_to_string(&mine).unwrap(), "keep me");
        // A sequence folder that is a link elsewhere: refused even with --overwrite.
        let elsewhere = dir.path().join("elsewhere");
        std::fs::create_dir_all(elsewhere.join("velodyne")).unwrap();
        std::fs::write(elsewhere.join("velodyne/000000.bin"), "precious").unwrap();
        std::fs::remove_dir_all(out.join("sequences/tiny")).unwrap();
        std::os::unix::fs::symlink(&elsewhere, out.join("sequences/tiny")).unwrap();
        let err = generate(&out, 3, true).unwrap_err();
        assert!(err.to_string().contains("symbolic link"), "{err}");
        assert!(elsewhere.join("velodyne/000000.bin").exists());
    }

    #[test]
    fn files_no_run_wrote_are_refused_even_with_overwrite() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("D");
        std::fs::create_dir_all(out.join("sequences/tiny/labels")).unwrap();
        std::fs::write(out.join("sequences/tiny/labels/000000.label"), "x").unwrap();
        let err = generate(&out, 1, true).unwrap_err();
        assert!(err.to_string().contains("no patchflow run wrote"), "{err}");
        assert!(out.join("sequences/tiny/labels/000000.label").exists());
    }

    #[test]
    fn an_unrelated_manifest_is_not_replaced_by_generate() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("manifest.json"), "{\"mine\": 1}").unwrap();
        let err = generate(dir.path(), 1, false).unwrap_err();
        assert!(err.to_string().contains("not a patchflow"), "{err}");
        let kept = std::fs::read_to_string(dir.path().join("manifest.json")).unwrap();
        assert_eq!(kept, "{\"mine\": 1}");
    }
}
