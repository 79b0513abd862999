//! Shortened training tracks for `bench --quick`: every track is kept, but only a share of its
//! sweeps is simulated, in three windows centred in the first, middle and last third of the
//! track, so the samples still cover every part of every track (the actors a track brings
//! together, at every observation direction and speed, SPEC §3). A window is the track's
//! scenario text with a smaller top-level `sweeps` and a later `start_secs`, written beside the
//! datasets so `generate` records exactly what it simulated.

use std::path::Path;

use patchflow_sim::{Scenario, ScenarioSource};

use crate::error::EvalError;
use crate::report::{create_dir, write_atomic};

/// Windows per shortened track.
const WINDOWS: u32 = 3;
/// The fewest sweeps a window keeps.
const MIN_SWEEPS: u32 = 10;

/// Scenario files for `sources` with `share` of their sweeps in [`WINDOWS`] windows each
/// (`<name>_w1.toml` …), written into `dir`; with a share of 1 (or more) the sources are
/// returned as they are.
pub(crate) fn shortened_tracks(
    sources: &[ScenarioSource],
    share: f64,
    dir: &Path,
) -> Result<Vec<ScenarioSource>, EvalError> {
    if !(share > 0.0 && share < 1.0) {
        return Ok(sources.to_vec());
    }
    create_dir(dir)?;
    let mut out = Vec::new();
    for source in sources {
        let (name, text, file) = match source {
            ScenarioSource::Embedded(name, text) => (
                (*name).to_owned(),
                (*text).to_owned(),
                format!("{name}.toml"),
            ),
            ScenarioSource::File(path) => (
                path.file_stem()
                    .map_or_else(|| "track".into(), |s| s.to_string_lossy().into_owned()),
                std::fs::read_to_string(path).map_err(|e| EvalError::io(path, e))?,
                path.display().to_string(),
            ),
        };
        let scenario =
            Scenario::from_toml(&text, &file, &name).map_err(|source| EvalError::Sim {
                out: dir.to_owned(),
                source,
            })?;
        for (k, (start_secs, sweeps)) in windows(&scenario, share).into_iter().enumerate() {
            let path = dir.join(format!("{name}_w{}.toml", k + 1));
            write_atomic(&path, windowed(&text, start_secs, sweeps).as_bytes())?;
            out.push(ScenarioSource::File(path));
        }
    }
    Ok(out)
}

/// `(start_secs, sweeps)` of each window: `share` of the sweeps split evenly, each window
/// centred in its third of the track.
fn windows(scenario: &Scenario, share: f64) -> Vec<(f64, u32)> {
    let total = scenario.sweeps;
    let per_window = ((f64::from(total) * share / f64::from(WINDOWS)).round() as u32)
        .max(MIN_SWEEPS)
        .min(total / WINDOWS);
    let part = total / WINDOWS;
    let period = scenario.lidar.period_secs();
    (0..WINDOWS)
        .map(|k| {
            let first = k * part + (part - per_window) / 2;
            (scenario.start_secs + f64::from(first) * period, per_window)
        })
        .collect()
}

/// The scenario text with its top-level `sweeps` and `start_secs` replaced by the window's.
fn windowed(text: &str, start_secs: f64, sweeps: u32) -> String {
    let header = format!(
        "sweeps = {sweeps} # a window of the full track, for bench --quick\nstart_secs = {start_secs:.3}\n"
    );
    let mut out = String::with_capacity(text.len() + header.len());
    let mut in_table = false;
    let mut written = false;
    for line in text.lines() {
        let trimmed = line.trim_start();
        if !in_table && trimmed.starts_with('[') {
            in_table = true;
            if !written {
                out.push_str(&header);
                written = true;
            }
        }
        let key = trimmed.split('=').next().map(str::trim);
        if !in_table && matches!(key, Some("sweeps" | "start_secs")) {
            if !written {
                out.push_str(&header);
                written = true;
            }
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    if !written {
        out.push_str(&header);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_replaces_the_top_level_sweeps_and_start_and_leaves_tables_alone() {
        let text = "description = \"x\"\nsweeps = 150\nstart_secs = 1.0\n[ego]\nspeed_mps = 6.0\n";
        let short = windowed(text, 2.5, 17);
        assert!(short.contains("\nsweeps = 17 #"), "{short}");
        assert!(short.contains("\nstart_secs = 2.500\n[ego]"), "{short}");
        assert_eq!(short.matches("sweeps").count(), 1);
        assert_eq!(short.matches("start_secs").count(), 1);
    }

    #[test]
    fn three_windows_share_a_third_of_the_sweeps_one_in_each_third_of_the_track() {
        let text = "sweeps = 150\n[ego]\npath_m = [[0.0, 0.0], [300.0, 0.0]]\nspeed_mps = 5.0\n";
        let scenario = Scenario::from_toml(text, "t.toml", "t").unwrap();
        let w = windows(&scenario, 1.0 / 3.0);
        assert_eq!(w.len(), 3);
        for (k, &(start, sweeps)) in w.iter().enumerate() {
            assert_eq!(sweeps, 17);
            let third = k as f64 * 5.0;
            assert!(
                start >= third && start + 1.7 <= third + 5.0,
                "window {k} at {start} s"
            );
        }
    }

    #[test]
    fn every_windowed_embedded_track_loads_with_fewer_sweeps() {
        let dir = tempfile::tempdir().unwrap();
        let sources: Vec<ScenarioSource> = patchflow_sim::EMBEDDED_SCENARIOS
            .iter()
            .filter(|(name, _)| name.starts_with("train"))
            .map(|&(name, text)| ScenarioSource::Embedded(name, text))
            .collect();
        let short = shortened_tracks(&sources, 1.0 / 3.0, dir.path()).unwrap();
        assert_eq!(short.len(), 3 * sources.len());
        let mut full_sweeps = 0;
        for source in &sources {
            let ScenarioSource::Embedded(name, text) = source else {
                panic!("embedded");
            };
            full_sweeps += Scenario::from_toml(text, "full.toml", name).unwrap().sweeps;
        }
        let mut short_sweeps = 0;
        for source in &short {
            let ScenarioSource::File(path) = source else {
                panic!("a file");
            };
            let text = std::fs::read_to_string(path).unwrap();
            short_sweeps += Scenario::from_toml(&text, "short.toml", "w")
                .unwrap()
                .sweeps;
        }
        assert!(
            3 * short_sweeps <= full_sweeps + 30,
            "{short_sweeps} of {full_sweeps}"
        );
    }
}
