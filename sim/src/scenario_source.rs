//! Where a scenario comes from: a TOML file on disk or one of the embedded scenarios, as a
//! command-line argument names it.

use std::path::{Path, PathBuf};

use crate::error::{Result, SimError};
use crate::scenario::{EMBEDDED_OCCUPANCY_SCENARIOS, EMBEDDED_SCENARIOS, Realism, Scenario};

/// Where a scenario comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ScenarioSource {
    /// A TOML file on disk.
    File(PathBuf),
    /// An embedded scenario: name and text.
    Embedded(&'static str, &'static str),
}

impl ScenarioSource {
    /// Every embedded scenario.
    pub fn all_embedded() -> Vec<Self> {
        EMBEDDED_SCENARIOS
            .iter()
            .map(|&(name, text)| Self::Embedded(name, text))
            .collect()
    }

    /// The scenario a command-line argument names: the file at that path if there is one,
    /// otherwise the embedded scenario of that name (with or without `.toml`), e.g.
    /// `dgpom_tjunction`; an error names the argument when it is neither.
    pub fn from_argument(argument: &Path) -> Result<Self> {
        // A path that is there as a link (even a dangling or looping one) is a file argument:
        // reading it then says what is wrong with it, instead of "no such scenario".
        if argument.exists() || std::fs::symlink_metadata(argument).is_ok() {
            return Ok(Self::File(argument.to_owned()));
        }
        let text = argument.to_string_lossy();
        let name = text.strip_suffix(".toml").unwrap_or(&text);
        EMBEDDED_SCENARIOS
            .iter()
            .chain(&EMBEDDED_OCCUPANCY_SCENARIOS)
            .find(|(embedded, _)| *embedded == name)
            .map(|&(name, text)| Self::Embedded(name, text))
            .ok_or_else(|| {
                SimError::Options(format!(
                    "{text}: no such scenario file, nor an embedded scenario of that name"
                ))
            })
    }

    /// Loads and validates it.
    pub fn load(&self) -> Result<Scenario> {
        self.load_at_rung(None)
    }

    /// Loads and validates it with its realism rung replaced by `rung`, if given.
    pub fn load_at_rung(&self, rung: Option<Realism>) -> Result<Scenario> {
        match self {
            Self::File(path) => Scenario::from_file_at_rung(path, rung),
            Self::Embedded(name, text) => {
                Scenario::from_toml_at_rung(text, &format!("<embedded {name}.toml>"), name, rung)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_argument_names_a_file_or_else_an_embedded_scenario() {
        let source = ScenarioSource::from_argument(Path::new("dgpom_tjunction")).unwrap();
        assert!(matches!(
            source,
            ScenarioSource::Embedded("dgpom_tjunction", _)
        ));
        let source = ScenarioSource::from_argument(Path::new("situation2.toml")).unwrap();
        assert!(matches!(source, ScenarioSource::Embedded("situation2", _)));
        let err = ScenarioSource::from_argument(Path::new("no/such/scene.toml")).unwrap_err();
        assert!(err.to_string().contains("no/such/scene.toml"), "{err}");
    }

    #[test]
    fn a_symlink_loop_given_as_a_scenario_is_named_as_a_loop() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.toml"));
        std::os::unix::fs::symlink(&b, &a).unwrap();
        std::os::unix::fs::symlink(&a, &b).unwrap();
        let err = ScenarioSource::from_argument(&a)
            .unwrap()
            .load()
            .unwrap_err();
        assert!(err.to_string().contains("loop of symbolic links"), "{err}");
    }
}
