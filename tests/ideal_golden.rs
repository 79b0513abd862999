//! The `ideal` realism rung reproduces the world of the first release byte for byte (SPEC §3a):
//! `scenarios/tiny.toml` and three sweeps of `situation5`, generated with seed 7 and
//! `realism = "ideal"`, must give exactly the bytes recorded (as FNV-1a digests) on the code
//! before the realism ladder existed (commit 04754b4). Files that only describe the run
//! (`scenario.toml`, `sequence.json`, `manifest.json`) and files added later (`ring/`,
//! `poses_estimated.txt`) are not compared; every file that existed then is.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

use std::path::Path;

use patchflow_sim::{GenerateOptions, ScenarioSource, Shard, generate_dataset};

/// Put in front of each scenario text: selects the rung under test.
const RUNG: &str = "realism = \"ideal\"\n";

/// FNV-1a over a file's bytes: stable across platforms, no dependency.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xCBF2_9CE4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3)
    })
}

/// `(path under the sequence folder, digest)` of every file the first release wrote for a
/// sequence, except the run description files.
fn digests(sequence: &Path) -> Vec<(String, u64)> {
    let mut out = Vec::new();
    for folder in ["velodyne", "labels", "flow", "time", "objects"] {
        let mut names: Vec<_> = std::fs::read_dir(sequence.join(folder))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        for name in names {
            let bytes = std::fs::read(sequence.join(folder).join(&name)).unwrap();
            out.push((format!("{folder}/{name}"), fnv1a(&bytes)));
        }
    }
    for name in ["poses.txt", "times.txt", "calib.txt"] {
        let bytes = std::fs::read(sequence.join(name)).unwrap();
        out.push((name.to_owned(), fnv1a(&bytes)));
    }
    out
}

fn generate(name: &str, text: &str) -> Vec<(String, u64)> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join(format!("{name}.toml"));
    std::fs::write(&file, format!("{RUNG}{text}")).unwrap();
    let options = GenerateOptions {
        out: dir.path().join("data"),
        seed: 7,
        shard: Shard::ALL,
        realism: None,
        overwrite: false,
    };
    generate_dataset(&[ScenarioSource::File(file)], &options, &|_| {}).unwrap();
    digests(&dir.path().join("data/sequences").join(name))
}

fn assert_digests(got: &[(String, u64)], recorded: &[(&str, u64)]) {
    let printed: Vec<String> = got
        .iter()
        .map(|(p, d)| format!("(\"{p}\", 0x{d:016X}),"))
        .collect();
    println!("{}", printed.join("\n"));
    let got: Vec<(&str, u64)> = got.iter().map(|(p, d)| (p.as_str(), *d)).collect();
    assert_eq!(got, recorded);
}

#[test]
fn the_ideal_rung_writes_the_tiny_scene_of_the_first_release_byte_for_byte() {
    let text =
        std::fs::read_to_string(patchflow_tests::workspace_root().join("scenarios/tiny.toml"))
            .unwrap();
    assert_digests(&generate("tiny", &text), TINY_SEED7);
}

#[test]
fn the_ideal_rung_writes_three_sweeps_of_situation5_of_the_first_release_byte_for_byte() {
    let text = std::fs::read_to_string(
        patchflow_tests::workspace_root().join("scenarios/situation5.toml"),
    )
    .unwrap()
    .replace("sweeps = 90", "sweeps = 3");
    assert_digests(&generate("situation5", &text), SITUATION5_SEED7);
}

const TINY_SEED7: &[(&str, u64)] = &[
    ("velodyne/000000.bin", 0x5F18C43E45901B8D),
    ("velodyne/000001.bin", 0x87C55C81C81B8530),
    ("velodyne/000002.bin", 0x9E13AEA1D9622ABE),
    ("labels/000000.label", 0x452F05CACBB6F1B5),
    ("labels/000001.label", 0x3AEC6ABA145ADC58),
    ("labels/000002.label", 0x19A03E3E4FA25B4A),
    ("flow/000000.bin", 0xD680246979F942B1),
    ("flow/000001.bin", 0x89D8D96479F01354),
    ("flow/000002.bin", 0x7621EE5B043DE0B0),
    ("time/000000.bin", 0x0909BEF0BAEACC3D),
    ("time/000001.bin", 0x0909BEF0BAEACC3D),
    ("time/000002.bin", 0x0909BEF0BAEACC3D),
    ("objects/000000.json", 0x967D33584F8378EB),
    ("objects/000001.json", 0xC475808C3C61B3CD),
    ("objects/000002.json", 0x122465B864FB4322),
    ("poses.txt", 0x9D5F77B02BF329AB),
    ("times.txt", 0xF94116A7EB5E4983),
    ("calib.txt", 0x0FBC08B71029AE26),
];

const SITUATION5_SEED7: &[(&str, u64)] = &[
    ("velodyne/000000.bin", 0xCEA0125F633587C3),
    ("velodyne/000001.bin", 0x5226520D06B416B3),
    ("velodyne/000002.bin", 0xBAE426184479E5B9),
    ("labels/000000.label", 0x7E4755BF369A717A),
    ("labels/000001.label", 0xBE2626ADA383BE20),
    ("labels/000002.label", 0x4CED9EEB17F2B738),
    ("flow/000000.bin", 0xFE9EF076A6307FC5),
    ("flow/000001.bin", 0x0E5D4AF8150D2675),
    ("flow/000002.bin", 0x725C9360A6510925),
    ("time/000000.bin", 0x679EC6998F528190),
    ("time/000001.bin", 0xCF5A1429CC0E043D),
    ("time/000002.bin", 0x7845182A56F737D2),
    ("objects/000000.json", 0x2BE3E11690AAC0C9),
    ("objects/000001.json", 0xD22BCBCBC5B8D935),
    ("objects/000002.json", 0xFFBE18C0CB2E41A1),
    ("poses.txt", 0x5BC87CFA802899D6),
    ("times.txt", 0xF94116A7EB5E4983),
    ("calib.txt", 0x0FBC08B71029AE26),
];
