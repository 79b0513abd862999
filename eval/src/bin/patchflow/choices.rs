//! The fixed sets of names the command line accepts (`--gp`, `--feature`, `--align`, `--preset`,
//! `--readout`, `--realism`, `--kind`, the study's name), as clap value enums: a typo is refused by clap with the
//! list of valid values and a non-zero exit, before any work starts. Each converts into the
//! library's own type; the spellings are SPEC §7's.

use clap::ValueEnum;
use patchflow_eval::{GpReadout, StudyFactor};
use patchflow_learn::{Alignment, EstimatorParams, FeatureKind, GpKind, MergeRule};
use patchflow_sim::Realism;

/// A Gaussian-process kind (`--gp`, `--kind`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum GpChoice {
    /// Sparse GP with learned pseudo-inputs.
    Spgp,
    /// SPGP with one learned noise term per pseudo-input.
    SpgpHet,
    /// Exact GP.
    Full,
}

impl From<GpChoice> for GpKind {
    fn from(choice: GpChoice) -> Self {
        match choice {
            GpChoice::Spgp => Self::Spgp,
            GpChoice::SpgpHet => Self::SpgpHet,
            GpChoice::Full => Self::Full,
        }
    }
}

/// A feature vector (`--feature`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FeatureChoice {
    /// The 242 patch values.
    Patch,
    /// The 16 Gabor responses.
    Gabor,
}

impl From<FeatureChoice> for FeatureKind {
    fn from(choice: FeatureChoice) -> Self {
        match choice {
            FeatureChoice::Patch => Self::Patch,
            FeatureChoice::Gabor => Self::Gabor,
        }
    }
}

/// A patch alignment (`--align`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AlignChoice {
    /// Along the bearing to the point (heading features).
    Bearing,
    /// Along the heading the speed GP is trained on (speed features).
    Heading,
}

impl From<AlignChoice> for Alignment {
    fn from(choice: AlignChoice) -> Self {
        match choice {
            AlignChoice::Bearing => Self::Bearing,
            AlignChoice::Heading => Self::Heading,
        }
    }
}

/// A training preset (`--preset`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PresetChoice {
    /// The estimator's defaults.
    Default,
    /// The thesis' protocol exactly.
    Thesis,
}

impl From<PresetChoice> for EstimatorParams {
    fn from(choice: PresetChoice) -> Self {
        match choice {
            PresetChoice::Default => Self::default(),
            PresetChoice::Thesis => Self::thesis(),
        }
    }
}

/// How clusters move their points (`--readout`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ReadoutChoice {
    /// The merged estimate of all points.
    All,
    /// The merged estimate of the low-variance points.
    Best,
    /// Each point its own prediction.
    Point,
}

impl From<ReadoutChoice> for GpReadout {
    fn from(choice: ReadoutChoice) -> Self {
        match choice {
            ReadoutChoice::All => Self::Merged(MergeRule::All),
            ReadoutChoice::Best => Self::Merged(MergeRule::Best),
            ReadoutChoice::Point => Self::PerPoint,
        }
    }
}

/// A realism rung (`--realism`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum RealismChoice {
    /// Flat ground, box shapes, ideal sensor.
    Ideal,
    /// The default world.
    Urban,
    /// More of each imperfection.
    Harsh,
}

impl From<RealismChoice> for Realism {
    fn from(choice: RealismChoice) -> Self {
        match choice {
            RealismChoice::Ideal => Self::Ideal,
            RealismChoice::Urban => Self::Urban,
            RealismChoice::Harsh => Self::Harsh,
        }
    }
}

/// A study (`patchflow study NAME`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum StudyChoice {
    /// The realism rung.
    Realism,
    /// The lidar's turn rate.
    Rate,
    /// The lidar's channel count.
    Channels,
    /// The cell size of the maps the patches sample.
    Cell,
    /// The cell size and the lidar's rate together, pairs at the same cells per sweep.
    CellRate,
}

impl From<StudyChoice> for StudyFactor {
    fn from(choice: StudyChoice) -> Self {
        match choice {
            StudyChoice::Realism => Self::Realism,
            StudyChoice::Rate => Self::Rate,
            StudyChoice::Channels => Self::Channels,
            StudyChoice::Cell => Self::Cell,
            StudyChoice::CellRate => Self::CellRate,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_gp_choice_is_spelled_as_the_library_names_it() {
        for choice in GpChoice::value_variants() {
            let name = choice.to_possible_value().map(|v| v.get_name().to_owned());
            assert_eq!(name.as_deref(), Some(GpKind::from(*choice).name()));
        }
    }

    #[test]
    fn every_study_choice_is_spelled_as_the_library_names_it() {
        for choice in StudyChoice::value_variants() {
            let name = choice.to_possible_value().map(|v| v.get_name().to_owned());
            assert_eq!(name.as_deref(), Some(StudyFactor::from(*choice).name()));
        }
    }

    #[test]
    fn every_realism_choice_is_spelled_as_the_library_names_it() {
        for choice in RealismChoice::value_variants() {
            let name = choice.to_possible_value().map(|v| v.get_name().to_owned());
            assert_eq!(name.as_deref(), Some(Realism::from(*choice).name()));
        }
    }
}
