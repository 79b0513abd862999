//! The benchmark's methods (SPEC §6) as a type, in their canonical order for tables and plots.
//!
//! The derived order is the report order: the four GP variants of thesis Table 4.5, the oracle
//! baselines, the self-associating baselines, the exact-GP variants, then the methods that only
//! the whole-scene evaluation reports (the GPs' per-point flow and the zero-flow baseline).

use std::fmt;
use std::str::FromStr;

use patchflow_learn::{GpKind, MergeRule};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::EvalError;

/// One method of the benchmark.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Method {
    /// SPGP, all per-point predictions merged (thesis 3.1.4, eqs. 3.35-3.37).
    SpgpAll,
    /// SPGP, only the low-variance predictions merged.
    SpgpBest,
    /// SPGP-HET, all predictions merged.
    SpgpHetAll,
    /// SPGP-HET, low-variance predictions merged.
    SpgpHetBest,
    /// SPGP-HET, all predictions merged, trained by the thesis' protocol exactly
    /// (`EstimatorParams::thesis`), beside the default's [`Self::SpgpHetAll`] (per-target
    /// tables only).
    SpgpHetAllThesis,
    /// Constant-velocity Kalman filter on the cluster centroid, association from ground truth.
    Kf,
    /// ICP between the cluster at t−1 and at t, association from ground truth.
    Icp,
    /// Kalman filters of a multi-target tracker that associates clusters itself.
    KfAuto,
    /// ICP between clusters linked by nearest predicted centroid.
    IcpAuto,
    /// The KF-AUTO tracker whose filters also measure the GP's merged heading and speed.
    GpKf,
    /// ICP-AUTO started from the GP's merged motion instead of the centroid alignment.
    GpIcp,
    /// Exact GP, all predictions merged.
    FullGpAll,
    /// Exact GP, low-variance predictions merged.
    FullGpBest,
    /// SPGP ALL where the moving classifier says the cluster moves, zero flow where not.
    SpgpAllMos,
    /// SPGP-HET ALL with the moving/static decision.
    SpgpHetAllMos,
    /// Exact GP ALL with the moving/static decision.
    FullGpAllMos,
    /// SPGP per point: each point moves with its own predicted heading and speed (scene flow only).
    SpgpPoint,
    /// SPGP-HET per point (scene flow only).
    SpgpHetPoint,
    /// Exact GP per point (scene flow only).
    FullGpPoint,
    /// Every point stands still: the scene-flow floor every method should beat on moving points.
    ZeroFlow,
}

/// How a GP method turns per-point predictions into motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GpReadout {
    /// One merged estimate per cluster, spread to its points.
    Merged(MergeRule),
    /// Each point's own heading and speed.
    PerPoint,
}

impl Method {
    /// Every method, in canonical order.
    pub const ALL: [Self; 20] = [
        Self::SpgpAll,
        Self::SpgpBest,
        Self::SpgpHetAll,
        Self::SpgpHetBest,
        Self::SpgpHetAllThesis,
        Self::Kf,
        Self::Icp,
        Self::KfAuto,
        Self::IcpAuto,
        Self::GpKf,
        Self::GpIcp,
        Self::FullGpAll,
        Self::FullGpBest,
        Self::SpgpAllMos,
        Self::SpgpHetAllMos,
        Self::FullGpAllMos,
        Self::SpgpPoint,
        Self::SpgpHetPoint,
        Self::FullGpPoint,
        Self::ZeroFlow,
    ];

    /// The name used in reports and files (`SPGP-HET-ALL`, `KF-AUTO`, `ZERO-FLOW`, …).
    pub fn name(self) -> &'static str {
        match self {
            Self::SpgpAll => "SPGP-ALL",
            Self::SpgpBest => "SPGP-BEST",
            Self::SpgpHetAll => "SPGP-HET-ALL",
            Self::SpgpHetBest => "SPGP-HET-BEST",
            Self::SpgpHetAllThesis => "SPGP-HET-ALL (thesis)",
            Self::Kf => "KF",
            Self::Icp => "ICP",
            Self::KfAuto => "KF-AUTO",
            Self::IcpAuto => "ICP-AUTO",
            Self::GpKf => "GP-KF",
            Self::GpIcp => "GP-ICP",
            Self::FullGpAll => "FULL-GP-ALL",
            Self::FullGpBest => "FULL-GP-BEST",
            Self::SpgpAllMos => "SPGP-ALL+MOS",
            Self::SpgpHetAllMos => "SPGP-HET-ALL+MOS",
            Self::FullGpAllMos => "FULL-GP-ALL+MOS",
            Self::SpgpPoint => "SPGP-POINT",
            Self::SpgpHetPoint => "SPGP-HET-POINT",
            Self::FullGpPoint => "FULL-GP-POINT",
            Self::ZeroFlow => "ZERO-FLOW",
        }
    }

    /// The GP method of an estimator kind read out one way.
    pub fn gp(kind: GpKind, readout: GpReadout) -> Self {
        use GpReadout::{Merged, PerPoint};
        match (kind, readout) {
            (GpKind::Spgp, Merged(MergeRule::All)) => Self::SpgpAll,
            (GpKind::Spgp, Merged(MergeRule::Best)) => Self::SpgpBest,
            (GpKind::Spgp, PerPoint) => Self::SpgpPoint,
            (GpKind::SpgpHet, Merged(MergeRule::All)) => Self::SpgpHetAll,
            (GpKind::SpgpHet, Merged(MergeRule::Best)) => Self::SpgpHetBest,
            (GpKind::SpgpHet, PerPoint) => Self::SpgpHetPoint,
            (GpKind::Full, Merged(MergeRule::All)) => Self::FullGpAll,
            (GpKind::Full, Merged(MergeRule::Best)) => Self::FullGpBest,
            (GpKind::Full, PerPoint) => Self::FullGpPoint,
        }
    }

    /// The GP method of an estimator kind read out as ALL where the moving classifier decides
    /// the cluster moves, zero flow where it decides it is static.
    pub fn gp_decided(kind: GpKind) -> Self {
        match kind {
            GpKind::Spgp => Self::SpgpAllMos,
            GpKind::SpgpHet => Self::SpgpHetAllMos,
            GpKind::Full => Self::FullGpAllMos,
        }
    }

    /// The per-target method of an estimator read out by `rule`: the thesis preset's SPGP-HET
    /// model gives [`Self::SpgpHetAllThesis`] for ALL and nothing for BEST (one row is kept for
    /// it); any other model [`Self::gp`].
    pub fn of_target_readout(
        estimator: &patchflow_learn::MotionEstimator,
        rule: MergeRule,
    ) -> Option<Self> {
        let kind = estimator.gp_kind();
        match (
            estimator.is_thesis_preset() && kind == GpKind::SpgpHet,
            rule,
        ) {
            (true, MergeRule::All) => Some(Self::SpgpHetAllThesis),
            (true, MergeRule::Best) => None,
            (false, _) => Some(Self::gp(kind, GpReadout::Merged(rule))),
        }
    }

    /// The three methods of one trained estimator: ALL, BEST and per point.
    pub fn of_estimator(kind: GpKind) -> [Self; 3] {
        [
            Self::gp(kind, GpReadout::Merged(MergeRule::All)),
            Self::gp(kind, GpReadout::Merged(MergeRule::Best)),
            Self::gp(kind, GpReadout::PerPoint),
        ]
    }

    /// Whether the method reports one estimate per cluster, so the per-target tables (thesis
    /// 4.4) score it: every method but the per-point GP flows and the zero-flow baseline.
    pub fn is_per_cluster(self) -> bool {
        !matches!(
            self,
            Self::SpgpPoint | Self::SpgpHetPoint | Self::FullGpPoint | Self::ZeroFlow
        )
    }

    /// Whether the method estimates a heading (the zero-flow baseline has none).
    pub fn has_heading(self) -> bool {
        self != Self::ZeroFlow
    }

    /// Whether the method takes its data association from ground truth (`KF`, `ICP`): an
    /// oracle upper bound, kept out of the scene-flow ranking (issue 27).
    pub fn is_oracle(self) -> bool {
        matches!(self, Self::Kf | Self::Icp)
    }

    /// Whether the method uses a trained model (a GP, and for `+MOS` the moving classifier).
    pub fn is_learned(self) -> bool {
        !matches!(
            self,
            Self::Kf | Self::Icp | Self::KfAuto | Self::IcpAuto | Self::ZeroFlow
        )
    }

    /// The name as report tables print it: the oracle-association methods marked as the upper
    /// bounds they are (`KF (oracle)`).
    pub fn label(self) -> String {
        if self.is_oracle() {
            format!("{} (oracle)", self.name())
        } else {
            self.name().to_owned()
        }
    }

    /// Position in [`Self::ALL`], for stable plot colours.
    pub fn slot(self) -> usize {
        self as usize
    }
}

impl fmt::Display for Method {
    /// The name, honouring width and alignment (`{:>28}`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

impl FromStr for Method {
    type Err = EvalError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == text)
            .ok_or_else(|| EvalError::BadParameter {
                name: "method",
                reason: format!("unknown method '{text}'"),
            })
    }
}

impl Serialize for Method {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

/// The ten methods of the per-target tables (SPEC §6), in table order: the four GP variants
/// (thesis Table 4.5), the oracle-association baselines, the self-associating baselines, then
/// the GP-informed tracking (issue 27).
pub const CANONICAL_METHODS: [Method; 10] = [
    Method::SpgpAll,
    Method::SpgpBest,
    Method::SpgpHetAll,
    Method::SpgpHetBest,
    Method::Kf,
    Method::Icp,
    Method::KfAuto,
    Method::IcpAuto,
    Method::GpKf,
    Method::GpIcp,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_back_to_its_method() {
        for method in Method::ALL {
            assert_eq!(method.name().parse::<Method>().unwrap(), method);
        }
        assert!("my-method".parse::<Method>().is_err());
    }

    #[test]
    fn the_derived_order_is_the_canonical_table_order() {
        let mut shuffled = [
            Method::ZeroFlow,
            Method::IcpAuto,
            Method::SpgpAll,
            Method::Kf,
        ];
        shuffled.sort();
        assert_eq!(
            shuffled,
            [
                Method::SpgpAll,
                Method::Kf,
                Method::IcpAuto,
                Method::ZeroFlow
            ]
        );
        assert!(CANONICAL_METHODS.windows(2).all(|w| w[0] < w[1]));
    }

    #[test]
    fn gp_methods_are_named_after_kind_and_readout() {
        let names = Method::of_estimator(GpKind::SpgpHet).map(Method::name);
        assert_eq!(names, ["SPGP-HET-ALL", "SPGP-HET-BEST", "SPGP-HET-POINT"]);
        assert_eq!(
            Method::gp(GpKind::Full, GpReadout::Merged(MergeRule::Best)).name(),
            "FULL-GP-BEST"
        );
    }

    #[test]
    fn a_method_formats_as_its_name_padded_to_the_width_asked_for() {
        assert_eq!(
            format!("{:>8}|{:<4}|", Method::Kf, Method::Icp),
            "      KF|ICP |"
        );
    }

    #[test]
    fn only_the_truth_associated_methods_are_labelled_oracle() {
        assert_eq!(Method::Icp.label(), "ICP (oracle)");
        assert_eq!(Method::IcpAuto.label(), "ICP-AUTO");
        assert!(Method::GpKf.is_learned() && !Method::KfAuto.is_learned());
        assert_eq!(
            Method::gp_decided(GpKind::SpgpHet).name(),
            "SPGP-HET-ALL+MOS"
        );
    }

    #[test]
    fn a_method_serialises_as_its_name() {
        let json = serde_json::to_string(&Method::KfAuto).unwrap();
        assert_eq!(json, "\"KF-AUTO\"");
        assert_eq!(
            serde_json::from_str::<Method>(&json).unwrap(),
            Method::KfAuto
        );
    }
}
