//! Shortened training tracks for `bench --quick`: every track is kept (so the samples still
//! cover every observation direction and speed of SPEC §3) but only a share of its sweeps is
//! simulated. A shortened track is its scenario text with a smaller top-level `sweeps`, written
//! beside the datasets so `generate` records exactly what it simulated.

use std::path::Path;

use patchflow_sim::ScenarioSource;

use crate::error::EvalError;
use crate::report::{create_dir, write_atomic};

/// The fewest sweeps a shortened track keeps.
const MIN_SWEEPS: u64 = 10;

/// Scenario files for `sources` with `share` of their sweeps, written into `dir`; with a share of
/// 1 (or more) the sources are returned as they are.
pub(crate) fn shortened_tracks(
    sources: &[ScenarioSource],
    share: f64,
    dir: &Path,
) -> Result<Vec<ScenarioSource>, EvalError> {
    if !(share > 0.0 && share < 1.0) {
        return Ok(sources.to_vec());
    }
    create_dir(dir)?;
    sources
        .iter()
        .map(|source| {
            let (name, text) = match source {
                ScenarioSource::Embedded(name, text) => ((*name).to_owned(), (*text).to_owned()),
                ScenarioSource::File(path) => (
                    path.file_stem()
                        .map_or_else(|| "track".into(), |s| s.to_string_lossy().into_owned()),
                    std::fs::read_to_string(path).map_err(|e| EvalError::io(path, e))?,
                ),
            };
            let path = dir.join(format!("{name}.toml"));
            write_atomic(&path, shorten(&text, share).as_bytes())?;
            Ok(ScenarioSource::File(path))
        })
        .collect()
}

/// The scenario text with its top-level `sweeps = N` replaced by `share × N` (at least
/// [`MIN_SWEEPS`]); a text that does not state its sweeps is returned unchanged.
fn shorten(text: &str, share: f64) -> String {
    let mut in_table = false;
    let mut out = String::with_capacity(text.len() + 40);
    for line in text.lines() {
        let trimmed = line.trim_start();
        in_table |= trimmed.starts_with('[');
        let sweeps = (!in_table)
            .then(|| trimmed.strip_prefix("sweeps"))
            .flatten()
            .and_then(|rest| rest.trim_start().strip_prefix('='))
            .and_then(|value| value.split('#').next())
            .and_then(|value| value.trim().parse::<u64>().ok());
        match sweeps {
            Some(n) => {
                let kept = ((n as f64 * share).round() as u64).clamp(MIN_SWEEPS.min(n), n);
                out.push_str(&format!(
                    "sweeps = {kept} # {n} in the full track; shortened for bench --quick"
                ));
            }
            None => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_third_of_the_sweeps_is_kept_and_tables_are_untouched() {
        let text =
            "description = \"x\"\nsweeps = 150\n[ego]\nspeed_mps = 6.0\n[lidar]\nsweeps = 9\n";
        let short = shorten(text, 1.0 / 3.0);
        assert!(short.contains("\nsweeps = 50 #"), "{short}");
        assert!(short.ends_with("[lidar]\nsweeps = 9\n"), "{short}");
    }

    #[test]
    fn a_short_track_keeps_at_least_ten_sweeps_and_never_gains_any() {
        assert!(shorten("sweeps = 12\n", 0.1).starts_with("sweeps = 10 #"));
        assert!(shorten("sweeps = 4\n", 0.1).starts_with("sweeps = 4 #"));
    }

    #[test]
    fn every_shortened_embedded_track_loads_with_fewer_sweeps() {
        let dir = tempfile::tempdir().unwrap();
        let sources: Vec<ScenarioSource> = patchflow_sim::EMBEDDED_SCENARIOS
            .iter()
            .filter(|(name, _)| name.starts_with("train"))
            .map(|&(name, text)| ScenarioSource::Embedded(name, text))
            .collect();
        let short = shortened_tracks(&sources, 1.0 / 3.0, dir.path()).unwrap();
        assert_eq!(short.len(), 9);
        for (full, short) in sources.iter().zip(&short) {
            let (ScenarioSource::Embedded(name, text), ScenarioSource::File(path)) = (full, short)
            else {
                panic!("unexpected sources");
            };
            let long = patchflow_sim::Scenario::from_toml(text, "full.toml", name).unwrap();
            let cut = std::fs::read_to_string(path).unwrap();
            let cut = patchflow_sim::Scenario::from_toml(&cut, "short.toml", name).unwrap();
            assert!(3 * cut.sweeps <= long.sweeps + 2, "{name}");
        }
    }
}
