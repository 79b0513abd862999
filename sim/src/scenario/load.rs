//! Loading a scenario file: parse (serde + toml, unknown fields rejected), fill defaults, validate,
//! and report every problem with the file, the line and a plain reason.

use std::path::Path;

use toml::de::{DeTable, DeValue};

use super::Scenario;
use super::bounds::{
    MAX_ACTORS, MAX_SCENARIO_BYTES, MAX_SWEEPS, REFLECTIVITY, TIME_SECS, check_count,
};
use super::derived_limits::derived_problems;
use super::problem::{Problem, Seg};
use crate::error::{Result, SimError};

impl Scenario {
    /// Reads, validates and resolves a scenario file; errors name the file and the line.
    pub fn from_file(path: &Path) -> Result<Self> {
        Self::from_file_at_rung(path, None)
    }

    /// Like [`Scenario::from_file`], with the realism rung replaced by `rung` if given.
    pub fn from_file_at_rung(path: &Path, rung: Option<super::Realism>) -> Result<Self> {
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
        let base = path.parent().unwrap_or(Path::new(""));
        Self::parse(&text, &path.display().to_string(), &stem, rung, base)
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
    /// `generate --realism NAME` does); knobs the file sets on their own still apply. Mesh files
    /// named by actors are read relative to the current directory.
    pub fn from_toml_at_rung(
        text: &str,
        file: &str,
        default_name: &str,
        rung: Option<super::Realism>,
    ) -> Result<Self> {
        Self::parse(text, file, default_name, rung, Path::new(""))
    }

    /// Parses, resolves and validates scenario text, reading mesh files relative to `base`.
    fn parse(
        text: &str,
        file: &str,
        default_name: &str,
        rung: Option<super::Realism>,
        base: &Path,
    ) -> Result<Self> {
        if let Some((offset, reason)) = super::array_lengths::array_length_problem(text) {
            return Err(SimError::at_offset(file, text, offset, reason));
        }
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
        if let Some(rung) = rung {
            scenario.realism = rung;
        }
        let lidar_problems = scenario.lidar.resolve_kind(&keys_of_table(text, "lidar"));
        scenario.resolve();
        let mut problems: Vec<Problem> = lidar_problems
            .into_iter()
            .map(|(field, reason)| (vec![Seg::Key("lidar"), Seg::Key(field)], reason))
            .collect();
        problems.extend(scenario.problems());
        if let Some((at, reason)) = problems.into_iter().next() {
            return Err(SimError::at_offset(file, text, locate(text, &at), reason));
        }
        scenario
            .load_meshes(base)
            .map_err(|(at, reason)| SimError::at_offset(file, text, locate(text, &at), reason))?;
        Ok(scenario)
    }

    /// Fills every optional field with its default.
    fn resolve(&mut self) {
        self.world.resolve(self.realism);
        let fleet = self.world.knobs().fleet;
        // The ego car is the sensor's own car: one fixed body on every rung.
        self.ego.resolve();
        if self.ego.name.is_empty() {
            self.ego.name = "ego".to_owned();
        }
        for (i, actor) in self.actors.iter_mut().enumerate() {
            actor.resolve_in(fleet);
            if actor.name.is_empty() {
                actor.name = format!("actor{}", i + 1);
            }
        }
        for structure in &mut self.structures {
            structure.resolve(fleet);
        }
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
                && let Err((field, reason)) = actor.trajectory()
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

/// The keys a top-level table of `text` sets (none if it is absent or the text does not parse).
fn keys_of_table(text: &str, table: &str) -> Vec<String> {
    let Ok(root) = DeTable::parse(text) else {
        return Vec::new();
    };
    let found = root.get_ref().iter().find(|(k, _)| k.get_ref() == table);
    match found.map(|(_, v)| v.get_ref()) {
        Some(DeValue::Table(t)) => t.iter().map(|(k, _)| k.get_ref().to_string()).collect(),
        _ => Vec::new(),
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
#[path = "load_tests.rs"]
mod tests;
