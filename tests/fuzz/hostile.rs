//! The hostile classes of issue 26, each tried with several values: outputs that are or hold
//! inputs, symlinked output folders, FIFOs and devices as inputs, huge finite values, and the
//! memory budget under a process limit. Each must end in a clear error naming the file (or a
//! valid result) with nothing the user owns changed, and never block.

use std::path::{Path, PathBuf};

use patchflow_learn::{GpModel, MotionEstimator};
use patchflow_sim::{GenerateOptions, Scenario, ScenarioSource, Shard, generate_dataset};

const TINY: &str = "sweeps = 2\n[lidar]\nchannels = 8\nazimuth_steps = 60\nblocks = 6\n\
    [ego]\npath_m = [[0.0, 0.0], [40.0, 0.0]]\nspeed_mps = 2.0\n\
    [[actors]]\nname = \"car\"\ntarget = true\npath_m = [[8.0, -6.0], [8.0, 40.0]]\nspeed_mps = 6.0\n";

fn generate(out: &Path, overwrite: bool) -> patchflow_sim::Result<()> {
    let options = GenerateOptions {
        out: out.to_owned(),
        seed: 1,
        shard: Shard::ALL,
        realism: None,
        overwrite,
    };
    let source = ScenarioSource::Embedded("tiny", TINY);
    generate_dataset(&[source], &options, &|_| {}).map(|_| ())
}

/// Every file under `dir` with its bytes, sorted.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                files.push((path.clone(), std::fs::read(&path).unwrap()));
            }
        }
    }
    files.sort();
    files
}

#[test]
fn an_output_folder_holding_foreign_files_is_never_changed() {
    for (name, text) in [
        ("manifest.json", "{\"mine\": true}"),
        ("manifest.json", "not json at all"),
        ("sequences/tiny/labels/000000.label", "user data"),
        ("sequences/tiny/notes.txt", "user notes"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
        let before = snapshot(dir.path());
        let err = generate(dir.path(), false).unwrap_err().to_string();
        assert!(err.contains(dir.path().to_str().unwrap()), "{name}: {err}");
        let after: Vec<_> = snapshot(dir.path())
            .into_iter()
            .filter(|(p, _)| !p.ends_with(".lock"))
            .collect();
        assert_eq!(after, before, "{name} was changed");
    }
}

#[test]
fn symlinked_output_folders_are_refused_and_their_targets_untouched() {
    for link in ["sequences", "sequences/tiny"] {
        let dir = tempfile::tempdir().unwrap();
        let elsewhere = tempfile::tempdir().unwrap();
        std::fs::write(elsewhere.path().join("precious.txt"), "keep").unwrap();
        let at = dir.path().join(link);
        std::fs::create_dir_all(at.parent().unwrap()).unwrap();
        std::os::unix::fs::symlink(elsewhere.path(), &at).unwrap();
        for overwrite in [false, true] {
            let err = generate(dir.path(), overwrite).unwrap_err().to_string();
            assert!(err.contains("symbolic link"), "{link}: {err}");
        }
        assert_eq!(snapshot(elsewhere.path()).len(), 1, "{link}");
    }
}

#[test]
fn fifos_and_devices_as_inputs_are_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("input");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    let mut specials = vec![PathBuf::from("/dev/zero"), PathBuf::from("/dev/null")];
    if made.is_ok_and(|s| s.success()) {
        specials.push(fifo);
    }
    for path in &specials {
        let shown = path.display().to_string();
        let err = Scenario::from_file(path).unwrap_err().to_string();
        assert!(err.contains(&shown), "{err}");
        let err = MotionEstimator::load(path).unwrap_err().to_string();
        assert!(err.contains(&shown), "{err}");
        let err = GpModel::load(path).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
        let err = patchflow_dataset::Dataset::open(path)
            .unwrap_err()
            .to_string();
        assert!(err.contains(&shown), "{err}");
    }
}

#[test]
fn huge_finite_values_in_a_scenario_are_refused_at_their_line() {
    for (from, to) in [
        ("speed_mps = 6.0", "speed_mps = 1e300"),
        ("speed_mps = 6.0", "speed_mps = 1.7e308"),
        ("[8.0, 40.0]", "[8.0, 1e300]"),
        ("[40.0, 0.0]", "[1e15, 0.0]"),
        ("channels = 8", "channels = 9223372036854775807"),
    ] {
        let text = TINY.replacen(from, to, 1);
        assert_ne!(text, TINY);
        let err = Scenario::from_toml(&text, "huge.toml", "huge")
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("huge.toml:"), "{to}: {err}");
    }
}

#[test]
fn the_memory_budget_is_read_and_names_its_limit() {
    let budget = patchflow_sim::memory_budget().expect("Linux exposes MemAvailable");
    assert!(budget.bytes > 0 && !budget.source.is_empty());
}

#[test]
fn a_scenario_that_would_fill_the_disk_is_refused_before_any_work() {
    // 100,000 sweeps of 640,000 rays: about 2.4 PB of points.
    let text = "sweeps = 100000\n[lidar]\nchannels = 64\nazimuth_steps = 10000\nblocks = 100\n\
        [ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 0.0001\n";
    let dir = tempfile::tempdir().unwrap();
    // A relative --out as well: its free space is read from the working folder.
    for out in [
        dir.path().join("data"),
        PathBuf::from("no-such-relative-folder/data"),
    ] {
        let options = GenerateOptions {
            out: out.clone(),
            seed: 1,
            shard: Shard::ALL,
            realism: None,
            overwrite: false,
        };
        let source = ScenarioSource::Embedded("vast", text);
        let err = generate_dataset(&[source], &options, &|_| {})
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(out.to_str().unwrap()) && err.contains("free") && err.contains("GB"),
            "{err}"
        );
        assert!(!out.exists(), "{}: work began", out.display());
    }
}

#[test]
fn huge_finite_values_in_a_dataset_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    generate(dir.path(), false).unwrap();
    let seq = dir.path().join("sequences/tiny");
    let objects = seq.join("objects/000001.json");
    let original = std::fs::read_to_string(&objects).unwrap();
    let read = |root: &Path| {
        patchflow_dataset::Dataset::open(root)
            .and_then(|d| d.sequence("tiny"))
            .and_then(|s| s.read_sweep(1))
            .map(|_| ())
    };
    for (field, value) in [
        ("size_m", "[4.5, 7e250, 1.5]"),
        ("yaw_rate_radps", "-3e200"),
        ("velocity_mps", "[0.0, 2e30, 0.0]"),
        ("centre_m", "[1e15, 0.0, 0.0]"),
    ] {
        let mut json: serde_json::Value = serde_json::from_str(&original).unwrap();
        json[0][field] = serde_json::from_str(value).unwrap();
        std::fs::write(&objects, json.to_string()).unwrap();
        let err = read(dir.path()).unwrap_err().to_string();
        assert!(err.contains("objects/000001.json"), "{field}: {err}");
    }
    std::fs::write(&objects, original).unwrap();
    let flow = seq.join("flow/000001.bin");
    let mut bytes = std::fs::read(&flow).unwrap();
    bytes[..4].copy_from_slice(&1e35f32.to_le_bytes());
    std::fs::write(&flow, bytes).unwrap();
    let err = read(dir.path()).unwrap_err().to_string();
    assert!(
        err.contains("flow/000001.bin") && err.contains("m/s"),
        "{err}"
    );
}
