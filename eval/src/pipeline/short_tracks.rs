//! Shortened training tracks for `bench --quick`: every track is kept (so the samples still
//! cover every observation direction and speed of SPEC §3) but only a share of its sweeps is
//! simulated: the LAST share, where a track's traffic meets the ego. A shortened track is its
//! scenario text with a smaller top-level `sweeps` and a later `start_secs`, written beside the
//! datasets so `generate` records exactly what it simulated.
//!
//! Why the last share (docs/investigations.md, "Quick training tracks"): the tracks' actors start
//! far from the ego and converge on its route, so the full tracks' importance-weighted draw
//! (thesis 3.1.2) takes 66 % of its samples, 77 % of its crossing cars and 75 % of its actors at
//! 8 m/s or more from the last third of the sweeps and 12 % (mostly pedestrians) from the first.
//! A model trained on the first third underestimated every fast target's speed (by 2.7 m/s in
//! situation 1 and 4.5 m/s in situation 4); on the last third it comes close to the full set's.

use std::path::Path;

use patchflow_sim::{Scenario, ScenarioSource};

use crate::error::EvalError;
use crate::report::{create_dir, write_atomic};

/// The fewest sweeps a shortened track keeps.
const MIN_SWEEPS: u32 = 10;

/// Scenario files for `sources` with the last `share` of their sweeps, written into `dir`; with
/// a share of 1 (or more) the sources are returned as they are.
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
            let path = dir.join(format!("{name}.toml"));
            let scenario =
                Scenario::from_toml(&text, &file, &name).map_err(|source| EvalError::Sim {
                    out: dir.to_owned(),
                    source,
                })?;
            write_atomic(&path, shorten(&text, &scenario, share).as_bytes())?;
            Ok(ScenarioSource::File(path))
        })
        .collect()
}

/// The scenario text (parsed as `scenario`) with its top-level `sweeps = N` replaced by
/// `share × N` (at least [`MIN_SWEEPS`]) and its `start_secs` moved to the first kept sweep, so
/// the kept sweeps are the track's last ones; a text that does not state its sweeps is returned
/// unchanged.
fn shorten(text: &str, scenario: &Scenario, share: f64) -> String {
    let n = scenario.sweeps;
    let kept = ((f64::from(n) * share).round() as u32).clamp(MIN_SWEEPS.min(n), n);
    let start_secs = scenario.sweep_start_secs(n - kept);
    let mut in_table = false;
    let mut out = String::with_capacity(text.len() + 120);
    let mut shortened = false;
    for line in text.lines() {
        let trimmed = line.trim_start();
        in_table |= trimmed.starts_with('[');
        let key = (!in_table)
            .then(|| trimmed.split('=').next())
            .flatten()
            .map(str::trim);
        match key {
            Some("sweeps") => {
                out.push_str(&format!(
                    "sweeps = {kept} # the last {kept} of {n} sweeps; shortened for bench --quick\n"
                ));
                out.push_str(&format!("start_secs = {start_secs:?}"));
                shortened = true;
            }
            // The original start is replaced by the one written with `sweeps`.
            Some("start_secs") => continue,
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    if shortened { out } else { text.to_owned() }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(text: &str) -> Scenario {
        Scenario::from_toml(text, "t.toml", "t").unwrap()
    }

    #[test]
    fn the_last_third_of_the_sweeps_is_kept_and_tables_are_untouched() {
        let text = "description = \"x\"\nsweeps = 150\n[ego]\npath_m = [[0.0, 0.0], [100.0, 0.0]]\nspeed_mps = 6.0\n";
        let short = shorten(text, &parsed(text), 1.0 / 3.0);
        assert!(short.contains("\nsweeps = 50 #"), "{short}");
        // 100 sweeps skipped at 10 Hz.
        assert!(short.contains("\nstart_secs = 10.0\n"), "{short}");
        assert!(
            short.ends_with("[ego]\npath_m = [[0.0, 0.0], [100.0, 0.0]]\nspeed_mps = 6.0\n"),
            "{short}"
        );
        let cut = parsed(&short);
        assert_eq!(cut.sweeps, 50);
        assert!((cut.sweep_start_secs(49) - parsed(text).sweep_start_secs(149)).abs() < 1e-9);
    }

    #[test]
    fn a_stated_start_is_moved_not_repeated() {
        let text = "start_secs = 2.0\nsweeps = 30\n[ego]\npath_m = [[0.0, 0.0], [100.0, 0.0]]\nspeed_mps = 6.0\n";
        let short = shorten(text, &parsed(text), 1.0 / 3.0);
        assert_eq!(short.matches("start_secs").count(), 1, "{short}");
        assert!((parsed(&short).start_secs - 4.0).abs() < 1e-9, "{short}");
    }

    #[test]
    fn a_short_track_keeps_at_least_ten_sweeps_and_never_gains_any() {
        let ego = "[ego]\npath_m = [[0.0, 0.0], [100.0, 0.0]]\nspeed_mps = 6.0\n";
        let twelve = format!("sweeps = 12\n{ego}");
        assert!(shorten(&twelve, &parsed(&twelve), 0.1).starts_with("sweeps = 10 #"));
        let four = format!("sweeps = 4\n{ego}");
        let short = shorten(&four, &parsed(&four), 0.1);
        assert!(short.starts_with("sweeps = 4 #") && short.contains("start_secs = 0.0"));
    }

    #[test]
    fn every_shortened_embedded_track_loads_with_its_last_sweeps() {
        let dir = tempfile::tempdir().unwrap();
        let sources: Vec<ScenarioSource> = patchflow_sim::EMBEDDED_SCENARIOS
            .iter()
            .filter(|(name, _)| name.starts_with("train"))
            .map(|&(name, text)| ScenarioSource::Embedded(name, text))
            .collect();
        let short = shortened_tracks(&sources, 1.0 / 3.0, dir.path()).unwrap();
        assert_eq!(short.len(), sources.len());
        assert_eq!(
            short.len(),
            11,
            "the nine tracks and the two crossing tracks"
        );
        for (full, short) in sources.iter().zip(&short) {
            let (ScenarioSource::Embedded(name, text), ScenarioSource::File(path)) = (full, short)
            else {
                panic!("unexpected sources");
            };
            let long = Scenario::from_toml(text, "full.toml", name).unwrap();
            let cut = std::fs::read_to_string(path).unwrap();
            let cut = Scenario::from_toml(&cut, "short.toml", name).unwrap();
            assert!(3 * cut.sweeps <= long.sweeps + 2, "{name}");
            let (end, full_end) = (
                cut.sweep_start_secs(cut.sweeps - 1),
                long.sweep_start_secs(long.sweeps - 1),
            );
            assert!(
                (end - full_end).abs() < 1e-9,
                "{name} ends at {end} s, the full track at {full_end} s"
            );
        }
    }
}
