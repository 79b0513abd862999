//! Loading a scenario file: parse (serde + toml, unknown fields rejected), fill defaults, validate,
//! and report every problem with the file, the line and a plain reason.

use std::path::Path;

use toml::de::{DeTable, DeValue};

use super::Scenario;
use crate::error::{Result, SimError};
use crate::motion::Trajectory;

/// One step of the way from the document root to a value, to find the line a problem is on.
#[derive(Debug, Clone, Copy)]
enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

/// A problem found after parsing: where it is (keys and array indices) and what it is.
type Problem = (Vec<Seg<'static>>, String);

impl Scenario {
    /// Reads, validates and resolves a scenario file; errors name the file and the line.
    pub fn from_file(path: &Path) -> Result<Self> {
        Self::from_file_at_rung(path, None)
    }

    /// Like [`Scenario::from_file`], with the realism rung replaced by `rung` if given.
    pub fn from_file_at_rung(path: &Path, rung: Option<super::Realism>) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| SimError::Io {
            path: path.to_owned(),
            source,
        })?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Self::from_toml_at_rung(&text, &path.display().to_string(), &stem, rung)
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
        Self::from_toml_at_rung(text, file, default_name, None)
    }

    /// Like [`Scenario::from_toml`], with the realism rung replaced by `rung` if given (as
    /// `generate --realism NAME` does); knobs the file sets on their own still apply.
    pub fn from_toml_at_rung(
        text: &str,
        file: &str,
        default_name: &str,
        rung: Option<super::Realism>,
    ) -> Result<Self> {
        let mut scenario: Scenario = toml::from_str(text).map_err(|e| {
            let offset = e.span().map(|s| s.start).unwrap_or(0);
            SimError::at_offset(file, text, offset, e.message().trim().to_owned())
        })?;
        if scenario.name.is_empty() {
            scenario.name = default_name.to_owned();
        }
        if let Some(rung) = rung {
            scenario.realism = rung;
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
        self.world.resolve(self.realism);
        self.sensor.resolve(self.realism);
        self.pose_error.resolve(self.realism);
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
        if !(1..=100_000).contains(&self.sweeps) {
            out.push((
                vec![Seg::Key("sweeps")],
                format!("sweeps must be 1 to 100000, got {}", self.sweeps),
            ));
        }
        if !self.start_secs.is_finite() {
            out.push((
                vec![Seg::Key("start_secs")],
                "start_secs must be finite".to_owned(),
            ));
        }
        if !(0.0..=1.0).contains(&self.ground_reflectivity) {
            out.push((
                vec![Seg::Key("ground_reflectivity")],
                format!(
                    "ground_reflectivity must be in [0, 1], got {}",
                    self.ground_reflectivity
                ),
            ));
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
        if self.actors.len() > 60_000 {
            out.push((vec![Seg::Key("actors")], "at most 60000 actors".to_owned()));
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
        let tables = [
            ("world", self.world.problems()),
            ("sensor", self.sensor.problems()),
            ("pose_error", self.pose_error.problems()),
        ];
        for (table, problems) in tables {
            for (field, reason) in problems {
                out.push((vec![Seg::Key(table), Seg::Key(field)], reason));
            }
        }
        for (i, road) in self.roads.iter().enumerate() {
            for (field, reason) in road.problems() {
                out.push((
                    vec![Seg::Key("roads"), Seg::Index(i), Seg::Key(field)],
                    reason,
                ));
            }
        }
        out
    }
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
    fn a_realism_knob_out_of_range_names_its_line_value_and_bound() {
        let (line, reason) = error_of(&format!("{BASE}[world]\nclutter = 1.0\ncamber = 0.7\n"));
        assert_eq!(line, 7);
        assert_eq!(reason, "camber = 0.7 is above 0.1");
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
