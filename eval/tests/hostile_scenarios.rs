//! Scenario values that once crashed the physics library, exhausted memory or wrote non-finite
//! points (issue 13) now stop `generate` before any work, with the file, the line, the value,
//! the allowed range and the reason; scenes whose lidar would see nothing are refused.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use common::{assert_clean_failure, generate_file};

const LIDAR: &str = "sweeps = 2\n[lidar]\nchannels = 8\nazimuth_steps = 90\nblocks = 9\n";
const EGO: &str = "[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n";

/// Writes `text` as `case.toml`, runs `generate` on it and checks the failure's message.
fn refused(text: &str, must_mention: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("case.toml");
    std::fs::write(&scenario, text).unwrap();
    let out = dir.path().join("data");
    assert_clean_failure(&generate_file(&scenario, &out), must_mention);
}

#[test]
fn a_rate_of_1e_minus_20_hz_is_refused_with_line_and_range() {
    refused(
        &format!("sweeps = 2\n[lidar]\nrate_hz = 1e-20\n{EGO}"),
        &[
            "case.toml:3: rate_hz = 1e-20 is below 0.1 Hz",
            "0.1 to 100 Hz",
        ],
    );
}

#[test]
fn a_start_time_of_1e300_seconds_is_refused() {
    refused(
        &format!("start_secs = 1e300\n{LIDAR}{EGO}"),
        &["case.toml:1: start_secs = 1e300 is above 86400 s"],
    );
}

#[test]
fn a_structure_centre_of_1e300_metres_is_refused() {
    refused(
        &format!("{LIDAR}{EGO}[[structures]]\nkind = \"wall\"\ncentre_m = [1e300, 0.0]\n"),
        &["case.toml:11: centre_m = 1e300 is above 100000 m"],
    );
}

#[test]
fn a_structure_size_of_1e300_metres_is_refused() {
    refused(
        &format!(
            "{LIDAR}{EGO}[[structures]]\nkind = \"wall\"\ncentre_m = [9.0, 0.0]\nsize_m = [1e300, 1.0, 1.0]\n"
        ),
        &["case.toml:12: size_m = 1e300 is above 1000 m"],
    );
}

#[test]
fn a_row_to_a_billion_metres_is_refused_before_it_is_built() {
    refused(
        &format!(
            "{LIDAR}{EGO}[[structures]]\nkind = \"wall\"\ncentre_m = [9.0, 0.0]\nrepeat_to_m = [1e9, 0.0]\n"
        ),
        &["case.toml:12: repeat_to_m = 1e9 is above 100000 m"],
    );
}

#[test]
fn a_row_of_too_many_boxes_is_refused_by_its_count() {
    refused(
        &format!(
            "{LIDAR}{EGO}[[structures]]\nkind = \"pole\"\ncentre_m = [9.0, 0.0]\nrepeat_to_m = [90000.0, 0.0]\nspacing_m = 0.1\n"
        ),
        &["case.toml:12:", "899911 boxes", "at most 10000"],
    );
}

#[test]
fn the_largest_lidar_is_refused_with_its_memory_estimate() {
    refused(
        &format!("sweeps = 1\n[lidar]\nchannels = 512\nazimuth_steps = 100000\n{EGO}"),
        &[
            "case.toml:4:",
            "51200000 rays per sweep",
            "6.1 GB",
            "at most 4000000",
        ],
    );
}

#[test]
fn range_noise_of_1e300_metres_is_refused_instead_of_writing_non_finite_points() {
    refused(
        &format!("{LIDAR}range_noise_std_m = 1e300\n{EGO}"),
        &["case.toml:6: range_noise_std_m = 1e300 is above 1 m"],
    );
}

#[test]
fn an_empty_name_is_refused() {
    refused(
        &format!("name = \"\"\n{LIDAR}{EGO}"),
        &["case.toml:1:", "empty", "1-64"],
    );
}

#[test]
fn an_ego_driving_off_the_ground_is_refused_before_generating() {
    refused(
        &format!("{LIDAR}[ego]\npath_m = [[1900.0, 0.0], [2100.0, 0.0]]\nspeed_mps = 5.0\n"),
        &["case.toml:7:", "ground square"],
    );
}

#[test]
fn a_sensor_buried_in_a_building_gives_no_points_and_is_refused() {
    refused(
        &format!("{LIDAR}{EGO}[[structures]]\nkind = \"building\"\ncentre_m = [0.0, 0.0]\n"),
        &["sequences/case", "sweep 0 has no points"],
    );
}

/// `patchflow ARGS` under an address-space limit of `bytes`: through `prlimit --as` where the
/// machine has it, else `ulimit -v` in `sh`; `None` where neither can set it.
fn patchflow_limited(bytes: u64, args: &[&str]) -> Option<std::process::Output> {
    use std::process::Command;
    let bin = env!("CARGO_BIN_EXE_patchflow");
    let prlimit = Command::new("prlimit").arg("--version").output();
    if prlimit.is_ok_and(|o| o.status.success()) {
        let run = Command::new("prlimit")
            .arg(format!("--as={bytes}"))
            .arg(bin)
            .args(args)
            .output()
            .ok()?;
        return Some(run);
    }
    let script = format!("ulimit -v {} || exit 99; exec \"$0\" \"$@\"", bytes / 1024);
    let run = Command::new("sh")
        .args(["-c", &script, bin])
        .args(args)
        .output()
        .ok()?;
    (run.status.code() != Some(99)).then_some(run)
}

#[test]
fn a_sweep_beyond_the_address_space_limit_is_refused_naming_the_limit_never_aborting() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("wide.toml");
    // 128 × 20,000 rays: one sweep needs about 312 MB.
    std::fs::write(
        &scenario,
        format!("sweeps = 2\n[lidar]\nchannels = 128\nazimuth_steps = 20000\nblocks = 100\n{EGO}"),
    )
    .unwrap();
    let out = dir.path().join("data");
    let args = [
        "generate",
        scenario.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    // 330-370 MB once passed the check and aborted (SIGABRT) mid-sweep.
    for limit_mb in [150, 250, 330, 370] {
        let Some(run) = patchflow_limited(limit_mb << 20, &args) else {
            println!("note: no address-space limit can be set on this machine; test skipped");
            return;
        };
        assert_clean_failure(&run, &["address-space limit", "128 × 20000 rays"]);
        assert!(!out.join("sequences").exists(), "{limit_mb} MB: work began");
    }
    // A limit the tiny scene fits in (with every thread's reserve) lets it through.
    let tiny = common::tiny_scenario();
    let run = patchflow_limited(
        16 << 30,
        &[
            "generate",
            tiny.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    )
    .unwrap();
    common::assert_success(&run);
}
