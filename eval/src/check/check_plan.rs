//! What `patchflow check` reads trained models on: scenarios of the user's own, each marking one
//! target, simulated once per world seed (issue 24: "the same models on unseen target shapes and
//! traffic … checked with others you have not seen").
//!
//! A world seed draws everything random in a scenario (the fleet's shapes, clutter, sensor noise),
//! so one check on several worlds is several readings of the same manoeuvre, as the README's tally
//! of the `unseen_*` checks on worlds 7-14 is.

use patchflow_sim::{Realism, ScenarioSource};

use crate::error::EvalError;

/// The checks and the worlds they are read on.
#[derive(Debug, Clone)]
pub struct CheckPlan {
    /// The scenarios, each marking its target (`target = true` on one actor).
    pub scenarios: Vec<ScenarioSource>,
    /// World seeds (`patchflow generate --seed`), each check simulated once per seed.
    pub worlds: Vec<u64>,
    /// A realism rung for every scenario; `None` keeps each file's own (`urban` if it names none).
    pub realism: Option<Realism>,
    /// Keep each world's dataset under `OUT/data/world-W` (deleted once read otherwise).
    pub keep_data: bool,
}

impl CheckPlan {
    /// The checks' names (their sequences' names), in the order given, after checking that
    /// there is at least one world, that every scenario loads and marks a target, and that no two
    /// share a name.
    pub fn check_names(&self) -> Result<Vec<String>, EvalError> {
        if self.worlds.is_empty() {
            return Err(bad("worlds", "no world seed given".into()));
        }
        if self.scenarios.is_empty() {
            return Err(bad("scenarios", "no scenario given".into()));
        }
        let mut names: Vec<String> = Vec::with_capacity(self.scenarios.len());
        for source in &self.scenarios {
            let scenario = source
                .load_at_rung(self.realism)
                .map_err(|err| bad("scenarios", err.to_string()))?;
            let targets = scenario.actors.iter().filter(|a| a.target).count();
            if targets != 1 {
                return Err(bad(
                    "scenarios",
                    format!(
                        "{}: marks {targets} targets; a check needs exactly one actor with \
                         `target = true`",
                        describe(source)
                    ),
                ));
            }
            if names.contains(&scenario.name) {
                return Err(bad(
                    "scenarios",
                    format!(
                        "{}: a second scenario named `{}` (each check needs its own name)",
                        describe(source),
                        scenario.name
                    ),
                ));
            }
            names.push(scenario.name);
        }
        Ok(names)
    }
}

/// World seeds from `7-14` (a range, both ends included), `7,9,12` (a list) or `7`.
pub fn parse_worlds(text: &str) -> Result<Vec<u64>, EvalError> {
    let seed = |part: &str| {
        part.trim().parse::<u64>().map_err(|_| {
            bad(
                "--worlds",
                format!("`{text}`: expected seeds such as `7-14`, `7,9,12` or `7`"),
            )
        })
    };
    let worlds: Vec<u64> = match text.split_once('-') {
        Some((first, last)) => {
            let (first, last) = (seed(first)?, seed(last)?);
            if last < first {
                return Err(bad(
                    "--worlds",
                    format!("`{text}`: the range ends before it starts"),
                ));
            }
            if last - first >= MAX_WORLDS as u64 {
                return Err(too_many(text));
            }
            (first..=last).collect()
        }
        None => text.split(',').map(seed).collect::<Result<_, _>>()?,
    };
    let mut sorted = worlds.clone();
    sorted.sort_unstable();
    sorted.dedup();
    if sorted.len() != worlds.len() {
        return Err(bad("--worlds", format!("`{text}`: a seed given twice")));
    }
    if worlds.len() > MAX_WORLDS {
        return Err(too_many(text));
    }
    Ok(worlds)
}

fn too_many(text: &str) -> EvalError {
    bad("--worlds", format!("`{text}`: at most {MAX_WORLDS} worlds"))
}

/// Most worlds one run reads (each costs a few minutes for twenty checks).
const MAX_WORLDS: usize = 1000;

/// How an error names a scenario: its file, or the embedded scenario's name.
fn describe(source: &ScenarioSource) -> String {
    match source {
        ScenarioSource::File(path) => path.display().to_string(),
        ScenarioSource::Embedded(name, _) => format!("<embedded {name}.toml>"),
    }
}

fn bad(name: &'static str, reason: String) -> EvalError {
    EvalError::BadParameter { name, reason }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;

    fn file(dir: &std::path::Path, name: &str, text: &str) -> ScenarioSource {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        ScenarioSource::File(path)
    }

    const TINY: &str = include_str!("../../../scenarios/tiny.toml");

    fn plan(scenarios: Vec<ScenarioSource>) -> CheckPlan {
        CheckPlan {
            scenarios,
            worlds: vec![7],
            realism: None,
            keep_data: false,
        }
    }

    #[test]
    fn worlds_are_read_as_a_range_a_list_or_one_seed() {
        assert_eq!(parse_worlds("7-14").unwrap(), (7..=14).collect::<Vec<_>>());
        assert_eq!(parse_worlds("7,9, 12").unwrap(), vec![7, 9, 12]);
        assert_eq!(parse_worlds("3").unwrap(), vec![3]);
    }

    #[test]
    fn malformed_or_repeated_worlds_are_refused_with_the_text_given() {
        for text in [
            "",
            "a",
            "7-",
            "9-7",
            "7,7",
            "1-2000",
            "0-18446744073709551615",
            "-3",
        ] {
            let err = parse_worlds(text).unwrap_err().to_string();
            assert!(
                err.contains("--worlds") && err.contains(text),
                "{text}: {err}"
            );
        }
    }

    #[test]
    fn a_scenario_without_a_target_is_refused_naming_its_file() {
        let dir = tempfile::tempdir().unwrap();
        let untargeted = TINY.replace("target = true", "target = false");
        let sources = vec![file(dir.path(), "plain.toml", &untargeted)];
        let err = plan(sources).check_names().unwrap_err().to_string();
        assert!(
            err.contains("plain.toml") && err.contains("0 targets"),
            "{err}"
        );
    }

    #[test]
    fn two_scenarios_of_one_name_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let named = format!("name = \"same\"\n{TINY}");
        let sources = vec![
            file(dir.path(), "a.toml", &named),
            file(dir.path(), "b.toml", &named),
        ];
        let err = plan(sources).check_names().unwrap_err().to_string();
        assert!(err.contains("b.toml") && err.contains("`same`"), "{err}");
    }

    #[test]
    fn the_checks_are_named_as_their_sequences_in_the_order_given() {
        let dir = tempfile::tempdir().unwrap();
        let sources = vec![
            file(dir.path(), "second.toml", TINY),
            file(dir.path(), "first.toml", TINY),
        ];
        assert_eq!(plan(sources).check_names().unwrap(), ["second", "first"]);
    }
}
