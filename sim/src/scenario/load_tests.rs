//! Tests of scenario loading: every kind of problem is reported with the file and its line.

use super::*;

const BASE: &str = "sweeps = 3\n[ego]\npath_m = [[0.0, 0.0], [80.0, 0.0]]\nspeed_mps = 5.0\n";

fn error_of(text: &str) -> (usize, String) {
    match Scenario::from_toml(text, "bad.toml", "bad") {
        Err(SimError::Scenario { file, line, reason }) => {
            assert_eq!(file, "bad.toml");
            (line, reason)
        }
        other => panic!("expected a scenario error, got {other:?}"),
    }
}

fn with_actor(body: &str) -> String {
    format!("{BASE}\n[[actors]]\nname = \"a\"\n{body}\n")
}

#[test]
fn a_minimal_scenario_gets_every_default() {
    let s = Scenario::from_toml(BASE, "ok.toml", "ok").unwrap();
    assert_eq!(s.lidar.azimuth_steps, 1800);
    assert_eq!(s.ego.turn_radius_m, Some(8.0));
    assert_eq!(s.ego.size_m, Some([4.7, 1.8, 1.45]));
}

#[test]
fn an_unknown_field_is_rejected_with_its_line() {
    let (line, reason) = error_of(&format!("{BASE}colour = \"red\"\n"));
    assert_eq!(line, 5);
    assert!(reason.contains("colour"), "{reason}");
}

#[test]
fn a_negative_speed_is_rejected_with_its_line() {
    let (line, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = -3.0",
    ));
    assert_eq!(line, 9);
    assert!(reason.contains("speed"), "{reason}");
}

#[test]
fn an_astronomical_speed_is_named_in_a_few_characters() {
    let (line, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = 7e280",
    ));
    assert_eq!(line, 9);
    assert!(reason.contains("got 7e280"), "{reason}");
    assert!(reason.len() < 100, "{reason}");
}

#[test]
fn a_path_with_one_point_is_rejected_with_its_line() {
    let (line, reason) = error_of(&with_actor("path_m = [[0.0, 5.0]]\nspeed_mps = 3.0"));
    assert_eq!(line, 8);
    assert!(reason.contains("two points"), "{reason}");
}

#[test]
fn a_nan_is_rejected_with_its_line() {
    let (line, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0], [nan, 5.0]]\nspeed_mps = 3.0",
    ));
    assert_eq!(line, 8);
    assert!(reason.contains("finite"), "{reason}");
}

#[test]
fn a_turn_radius_below_the_class_minimum_is_rejected_with_its_line() {
    let (line, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0], [50.0, 5.0], [50.0, 50.0]]\nspeed_mps = 3.0\nturn_radius_m = 3.0",
    ));
    assert_eq!(line, 10);
    assert!(reason.contains("minimum"), "{reason}");
}

#[test]
fn a_corner_too_tight_for_its_radius_is_rejected_at_the_path() {
    let (line, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0], [10.0, 5.0], [10.0, 50.0]]\nspeed_mps = 3.0\nturn_radius_m = 20.0",
    ));
    assert_eq!(line, 8);
    assert!(reason.contains("corner"), "{reason}");
}

#[test]
fn a_bad_lidar_value_points_at_the_lidar_table() {
    let (line, reason) = error_of(&format!("{BASE}[lidar]\nchannels = 16\nrate_hz = 0.0\n"));
    assert_eq!(line, 7);
    assert!(reason.contains("rate_hz"), "{reason}");
}

#[test]
fn a_syntax_error_names_its_line() {
    let (line, _) = error_of("sweeps = 3\n[ego\n");
    assert_eq!(line, 2);
}

#[test]
fn two_targets_are_rejected() {
    let text = format!(
        "{}\n[[actors]]\nname = \"b\"\ntarget = true\npath_m = [[0.0, 9.0], [50.0, 9.0]]\nspeed_mps = 3.0\n",
        with_actor("target = true\npath_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = 3.0")
    );
    let (line, reason) = error_of(&text);
    assert_eq!(line, 14);
    assert!(reason.contains("one actor"), "{reason}");
}

#[test]
fn the_resolved_scenario_reads_back_equal() {
    let s = Scenario::from_toml(
        &with_actor("path_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = 3.0"),
        "ok.toml",
        "ok",
    )
    .unwrap();
    let back = Scenario::from_toml(&s.to_toml(), "resolved.toml", "x").unwrap();
    assert_eq!(back, s);
}

#[test]
fn an_empty_name_is_refused_at_its_line() {
    let (line, reason) = error_of(&format!("name = \"\"\n{BASE}"));
    assert_eq!(line, 1);
    assert!(reason.contains("empty"), "{reason}");
}

#[test]
fn a_finite_but_huge_start_time_is_refused_with_its_range() {
    let (line, reason) = error_of(&format!("start_secs = 1e300\n{BASE}"));
    assert_eq!(line, 1);
    assert!(reason.contains("1e300 is above 86400 s"), "{reason}");
}

#[test]
fn a_row_too_long_to_build_is_refused_by_its_count() {
    let (line, reason) = error_of(&format!(
        "{BASE}[[structures]]\nkind = \"pole\"\ncentre_m = [0.0, 9.0]\nrepeat_to_m = [50000.0, 9.0]\nspacing_m = 0.1\n"
    ));
    assert_eq!(line, 8);
    assert!(reason.contains("500001 boxes"), "{reason}");
}

#[test]
fn too_many_rays_per_sweep_are_refused_with_the_memory_they_need() {
    let (line, reason) = error_of(&format!(
        "{BASE}[lidar]\nchannels = 512\nazimuth_steps = 100000\nblocks = 10\n"
    ));
    assert_eq!(line, 7);
    assert!(
        reason.contains("51200000 rays") && reason.contains("6.1 GB"),
        "{reason}"
    );
}

#[test]
fn an_ego_leaving_the_ground_is_refused() {
    let text = "sweeps = 3\n[ego]\npath_m = [[1990.0, 0.0], [2050.0, 0.0]]\nspeed_mps = 5.0\n";
    let (line, reason) = error_of(text);
    assert_eq!(line, 3);
    assert!(reason.contains("ground square"), "{reason}");
}

#[test]
fn an_actor_driving_beyond_the_world_during_a_long_run_is_refused() {
    let (_, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = 40.0\nstart_secs = -80000.0",
    ));
    assert!(reason.contains("within the world"), "{reason}");
}

#[test]
fn a_scenario_built_in_code_is_checked_too() {
    let mut s = Scenario::from_toml(BASE, "ok.toml", "ok").unwrap();
    s.lidar.rate_hz = 1e-20;
    let err = s.validate().unwrap_err().to_string();
    assert!(
        err.contains("lidar.rate_hz") && err.contains("below 0.1 Hz"),
        "{err}"
    );
}

#[test]
fn a_realism_knob_out_of_range_names_its_line_value_and_bound() {
    let (line, reason) = error_of(&format!("{BASE}[world]\nclutter = 1.0\ncamber = 0.7\n"));
    assert_eq!(line, 7);
    assert!(
        reason.starts_with("camber = 0.7 is above 0.1 (allowed 0 to 0.1: "),
        "{reason}"
    );
}

#[test]
fn an_unknown_rung_is_rejected_with_its_line() {
    let (line, reason) = error_of(&format!("realism = \"perfect\"\n{BASE}"));
    assert_eq!(line, 1);
    assert!(reason.contains("perfect"), "{reason}");
}

#[test]
fn the_default_rung_is_urban_and_a_knob_set_alone_overrides_it() {
    let s = Scenario::from_toml(
        &format!("{BASE}[sensor]\nmixed_pixels = 0.0\n"),
        "ok.toml",
        "ok",
    )
    .unwrap();
    assert_eq!(s.realism, super::super::Realism::Urban);
    assert_eq!(s.sensor.knobs().mixed_pixels, 0.0);
    assert_eq!(s.world.knobs().camber, 0.02);
    let ideal =
        Scenario::from_toml_at_rung(BASE, "ok.toml", "ok", Some(super::super::Realism::Ideal))
            .unwrap();
    assert!(ideal.world.knobs().flat_ground() && ideal.pose_error.knobs().exact());
}

#[test]
fn a_spinner_only_field_in_a_planar_table_points_at_its_line() {
    let (line, reason) = error_of(&format!(
        "{BASE}[lidar]\nkind = \"planar\"\nbeams = 70\nblocks = 10\n"
    ));
    assert_eq!(line, 8);
    assert!(reason.contains("blocks"), "{reason}");
}

#[test]
fn a_resolved_planar_scenario_reads_back_equal() {
    let text = format!("{BASE}[lidar]\nkind = \"planar\"\nbeams = 70\nmax_range_m = 20.0\n");
    let s = Scenario::from_toml(&text, "ok.toml", "ok").unwrap();
    assert_eq!((s.lidar.channels, s.lidar.azimuth_steps), (1, 70));
    let back = Scenario::from_toml(&s.to_toml(), "resolved.toml", "x").unwrap();
    assert_eq!(back, s);
}

#[test]
fn a_path_point_of_three_values_is_rejected_with_its_line() {
    let (line, reason) = error_of(&with_actor(
        "path_m = [[0.0, 5.0, 5.0], [50.0, 5.0, 5.0]]\nspeed_mps = 3.0",
    ));
    assert_eq!(line, 8);
    assert!(reason.contains("path_m entry 0 has 3 values"), "{reason}");
}

#[test]
fn a_car_model_on_a_pedestrian_is_rejected_with_its_line() {
    let (line, reason) = error_of(&with_actor(
        "class = \"pedestrian\"\nmodel = \"van\"\npath_m = [[0.0, 5.0], [50.0, 5.0]]\nspeed_mps = 1.0",
    ));
    assert_eq!(line, 9);
    assert!(
        reason.contains("car body style") && reason.contains("pedestrian"),
        "{reason}"
    );
}
