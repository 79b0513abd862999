//! Loading a scenario file: parse (serde + toml, unknown fields rejected), fill defaults, validate,
//! and report every problem with the file, the line and a plain reason.

use std::path::Path;

use toml::de::{DeTable, DeValue};

use super::Scenario;
use super::bounds::{
    MAX_ACTORS, MAX_SCENARIO_BYTES, MAX_SWEEPS, REFLECTIVITY, TIME_SECS, check_count,
};
use super::derived_limits::derived_problems;
use crate::error::{Result, SimError};
use crate::motion::Trajectory;

/// One step of the way from the document root to a value, to find the line a problem is on.
#[derive(Debug, Clone, Copy)]
pub(super) enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

/// A problem found after parsing: where it is (keys and array indices) and what it is.
pub(super) type Problem = (Vec<Seg<'static>>, String);

impl Scenario {
    /// Reads, validates and resolves a scenario file; errors name the file and the line.
    pub fn from_file(path: &Path) -> Result<Self> {
        let bytes = patchflow_dataset::read_limited(path, MAX_SCENARIO_BYTES)?;
        let text = String::from_utf8(bytes).map_err(|_| SimError::Scenario {
            file: path.display().to_string(),
            line: 1,
            reason: "not UTF-8 text".to_owned(),
        })?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Self::from_toml(&text, &path.display().to_string(), &stem)
    }

    /// Parses and validates scenario text. `file` names it in errors; `default_name` is used when
    /// the text sets no `name`.
    ///
    /// ```
    /// let text = "sweeps = 3\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n";
    /// let scenario = patchflow_sim::Scenario::from_toml(text, "mini.toml", "mini").unwrap();
    /// assert_eq!(scenario.name, "mini");
    /// assert_eq!(scenario.lidar.channels, 64);
    /// ```
    pub fn from_toml(text: &str, file: &str, default_name: &str) -> Result<Self> {
        let mut scenario: Scenario = toml::from_str(text).map_err(|e| {
            let offset = e.span().map(|s| s.start).unwrap_or(0);
            SimError::at_offset(file, text, offset, e.message().trim().to_owned())
        })?;
        if scenario.name.is_empty() {
            if let Some(offset) = key_offset(text, "name") {
                let reason = "name = \"\" is empty; names are 1-64 letters, digits, '_' or '-'";
                return Err(SimError::at_offset(file, text, offset, reason));
            }
            scenario.name = default_name.to_owned();
        }
        scenario.resolve();
        if let Some((at, reason)) = scenario.problems().into_iter().next() {
            return Err(SimError::at_offset(file, text, locate(text, &at), reason));
        }
        Ok(scenario)
    }

    /// Fills every optional field with its default.
    fn resolve(&mut self) {
        self.ego.resolve();
        if self.ego.name.is_empty() {
            self.ego.name = "ego".to_owned();
        }
        for (i, actor) in self.actors.iter_mut().enumerate() {
            actor.resolve();
            if actor.name.is_empty() {
                actor.name = format!("actor{}", i + 1);
            }
        }
        for structure in &mut self.structures {
            structure.resolve();
        }
    }

    /// Every problem of the resolved scenario, in file order.
    fn problems(&self) -> Vec<Problem> {
        let mut out: Vec<Problem> = Vec::new();
        let name_ok = !self.name.is_empty()
            && self.name.len() <= 64
            && self
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !name_ok {
            out.push((
                vec![Seg::Key("name")],
                format!(
                    "name {:?} must be 1-64 letters, digits, '_' or '-' (it names a folder)",
                    self.name
                ),
            ));
        }
        let top = [
            check_count(
                "sweeps",
                self.sweeps.into(),
                1,
                MAX_SWEEPS,
                "sweeps of one sequence",
            ),
            TIME_SECS.check("start_secs", self.start_secs),
            REFLECTIVITY.check("ground_reflectivity", self.ground_reflectivity),
            check_count(
                "actors",
                self.actors.len() as u64,
                0,
                MAX_ACTORS,
                "listed actors",
            ),
        ];
        for (field, reason) in top.into_iter().flatten() {
            out.push((vec![Seg::Key(field)], reason));
        }
        for (field, reason) in self.lidar.problems() {
            out.push((vec![Seg::Key("lidar"), Seg::Key(field)], reason));
        }
        if self.ego.class != patchflow_dataset::ActorClass::Car {
            out.push((
                vec![Seg::Key("ego"), Seg::Key("class")],
                "the ego vehicle must be a car".to_owned(),
            ));
        }
        let movers = std::iter::once((vec![Seg::Key("ego")], &self.ego)).chain(
            self.actors
                .iter()
                .enumerate()
                .map(|(i, a)| (vec![Seg::Key("actors"), Seg::Index(i)], a)),
        );
        for (at, actor) in movers {
            let mut problems = actor.problems();
            if problems.is_empty()
                && let Err((field, reason)) = Trajectory::from_config(actor)
            {
                problems.push((field, reason));
            }
            for (field, reason) in problems {
                let mut path = at.clone();
                path.push(Seg::Key(field));
                out.push((path, format!("{}: {reason}", actor.name)));
            }
        }
        let targets: Vec<usize> = (0..self.actors.len())
            .filter(|&i| self.actors[i].target)
            .collect();
        if targets.len() > 1 {
            out.push((
                vec![
                    Seg::Key("actors"),
                    Seg::Index(targets[1]),
                    Seg::Key("target"),
                ],
                "only one actor may be the target".to_owned(),
            ));
        }
        if self.ego.target {
            out.push((
                vec![Seg::Key("ego"), Seg::Key("target")],
                "the ego car cannot be the target".to_owned(),
            ));
        }
        for (i, actor) in self.actors.iter().enumerate() {
            if self.actors[..i].iter().any(|a| a.name == actor.name) {
                out.push((
                    vec![Seg::Key("actors"), Seg::Index(i), Seg::Key("name")],
                    format!("actor name {:?} is used twice", actor.name),
                ));
            }
        }
        for (i, structure) in self.structures.iter().enumerate() {
            for (field, reason) in structure.problems() {
                out.push((
                    vec![Seg::Key("structures"), Seg::Index(i), Seg::Key(field)],
                    reason,
                ));
            }
        }
        for (field, reason) in self.traffic.problems() {
            out.push((vec![Seg::Key("traffic"), Seg::Key(field)], reason));
        }
        // Sizes derived from several fields, once each field is within its own bounds.
        if out.is_empty() {
            out.extend(derived_problems(self));
        }
        out
    }

    /// Checks a scenario built in code (not read from a file) as a file would be checked; the
    /// first problem is reported with the field's path.
    pub fn validate(&self) -> Result<()> {
        match self.problems().into_iter().next() {
            None => Ok(()),
            Some((at, reason)) => Err(SimError::Options(format!(
                "scenario {:?}: {}: {reason}",
                self.name,
                path_text(&at)
            ))),
        }
    }
}

/// `lidar.rate_hz`, `actors[2].path_m`: where a problem is, for scenarios without a file.
fn path_text(path: &[Seg]) -> String {
    let mut out = String::new();
    for seg in path {
        match seg {
            Seg::Key(k) if out.is_empty() => out.push_str(k),
            Seg::Key(k) => out.push_str(&format!(".{k}")),
            Seg::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// Byte offset of the top-level `key` in `text`, if the text sets it.
fn key_offset(text: &str, key: &str) -> Option<usize> {
    let root = DeTable::parse(text).ok()?;
    root.get_ref()
        .iter()
        .find(|(k, _)| k.get_ref() == key)
        .map(|(k, _)| k.span().start)
}

/// Byte offset of the value at `path` in `text`: the deepest part of the path that exists
/// (a field left to its default points at its table).
fn locate(text: &str, path: &[Seg]) -> usize {
    let Ok(root) = DeTable::parse(text) else {
        return 0;
    };
    let mut offset = 0;
    let mut table: Option<&DeTable> = Some(root.get_ref());
    let mut value: Option<&toml::Spanned<DeValue>> = None;
    for seg in path {
        let next = match (*seg, table, value) {
            (Seg::Key(key), Some(t), _) => t
                .iter()
                .find(|(k, _)| k.get_ref() == key)
                .map(|(k, v)| (k.span().start, v)),
            (Seg::Index(i), _, Some(v)) => match v.get_ref() {
                DeValue::Array(items) => items.get(i).map(|item| (item.span().start, item)),
                _ => None,
            },
            _ => None,
        };
        let Some((start, v)) = next else { break };
        offset = start;
        value = Some(v);
        table = match v.get_ref() {
            DeValue::Table(t) => Some(t),
            _ => None,
        };
    }
    offset
}

#[cfg(test)]
mod tests {
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
}
