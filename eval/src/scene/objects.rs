//! Every actor at every scan, as the whole-scene evaluation scores it: its true motion, what
//! each method estimates for the cluster holding most of its points, and the scene-flow error on
//! its points; scored as the per-target tables are (SPEC §6), broken down by class, range and
//! number of points.

use std::collections::BTreeMap;

use patchflow_dataset::ActorClass;
use serde::{Deserialize, Serialize};

use crate::methods::estimate::MotionEstimate;
use crate::methods::method::Method;
use crate::scene::metrics::{MIN_SCORED_SPEED_MPS, MethodMetrics, score_method};
use crate::scene::truth_at_scan::TruthAtScan;

/// An actor is scored at a scan when at least this many of its points lie in the height slice
/// inside the map window: fewer carry no usable patch, centroid or shape.
pub const MIN_OBJECT_POINTS: usize = 10;

/// One actor at one scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectScan {
    /// Scan number within the sequence.
    pub scan: usize,
    /// Actor id.
    pub actor: u16,
    /// Its class.
    pub class: ActorClass,
    /// Its true motion, range and sliced points (`target_points` holds the actor's points).
    pub truth: TruthAtScan,
    /// Per method with one estimate per cluster (and ZERO-FLOW): the estimate for the actor.
    pub estimates: BTreeMap<Method, Option<MotionEstimate>>,
    /// Per method: mean end-point error over the actor's sliced points, metres per sweep.
    pub point_epe_m: BTreeMap<Method, f64>,
}

/// A set of object scans the report scores together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ObjectGroup {
    /// Every moving object (true speed at least 0.5 m/s).
    Moving,
    /// Moving objects of one class.
    Class(ActorClass),
    /// Objects standing still (true speed below 0.5 m/s): their motion should come out near zero.
    Standing,
    /// Moving objects in a range bin (index into [`RANGE_BINS_M`]).
    Range(usize),
    /// Moving objects in a bin of sliced points (index into [`POINT_BINS`]).
    Points(usize),
}

/// Range bins, metres: label and upper edge.
pub const RANGE_BINS_M: [(&str, f64); 3] = [
    ("under 15 m", 15.0),
    ("15-30 m", 30.0),
    ("30 m and more", f64::INFINITY),
];

/// Bins of sliced points on the object: label and upper edge.
pub const POINT_BINS: [(&str, f64); 3] = [
    ("under 50", 50.0),
    ("50-200", 200.0),
    ("200 and more", f64::INFINITY),
];

impl ObjectGroup {
    /// Report label.
    pub fn label(self) -> String {
        match self {
            Self::Moving => "all moving".into(),
            Self::Class(class) => format!("{class:?}").to_lowercase(),
            Self::Standing => "standing".into(),
            Self::Range(bin) => RANGE_BINS_M[bin].0.into(),
            Self::Points(bin) => format!("{} points", POINT_BINS[bin].0),
        }
    }

    /// Whether an object scan belongs to the group.
    pub fn contains(self, object: &ObjectScan) -> bool {
        let moving = object.truth.speed_mps >= MIN_SCORED_SPEED_MPS;
        let bin_of = |value: f64, bins: &[(&str, f64); 3]| bins.iter().position(|b| value < b.1);
        match self {
            Self::Moving => moving,
            Self::Class(class) => moving && object.class == class,
            Self::Standing => !moving,
            Self::Range(bin) => {
                moving && object.truth.range_m.and_then(|r| bin_of(r, &RANGE_BINS_M)) == Some(bin)
            }
            Self::Points(bin) => {
                let points = object.truth.target_points.map(|n| n as f64);
                moving && points.and_then(|n| bin_of(n, &POINT_BINS)) == Some(bin)
            }
        }
    }

    /// The groups of the report: all moving, per class, standing, per range, per points.
    pub fn all() -> Vec<Self> {
        let classes = [
            ActorClass::Car,
            ActorClass::Truck,
            ActorClass::Pedestrian,
            ActorClass::Cyclist,
        ];
        let mut groups = vec![Self::Moving];
        groups.extend(classes.map(Self::Class));
        groups.push(Self::Standing);
        groups.extend((0..RANGE_BINS_M.len()).map(Self::Range));
        groups.extend((0..POINT_BINS.len()).map(Self::Points));
        groups
    }
}

/// The scores of one method on one group of object scans.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ObjectMetrics {
    /// Object scans in the group.
    pub object_scans: usize,
    /// Heading (not for ZERO-FLOW), speed, coverage and velocity EPE, as for the target.
    pub motion: MethodMetrics,
    /// Mean over the object scans of the mean point EPE, metres per sweep.
    pub point_epe_m: Option<f64>,
}

/// Scores every method on the object scans of `group`; `None` for a group with no object scan.
pub fn score_objects(
    objects: &[ObjectScan],
    group: ObjectGroup,
) -> Option<BTreeMap<Method, ObjectMetrics>> {
    let members: Vec<&ObjectScan> = objects.iter().filter(|o| group.contains(o)).collect();
    if members.is_empty() {
        return None;
    }
    let truth: Vec<TruthAtScan> = members.iter().map(|o| o.truth).collect();
    let methods: std::collections::BTreeSet<Method> = members
        .iter()
        .flat_map(|o| o.estimates.keys().chain(o.point_epe_m.keys()).copied())
        .collect();
    let mut out = BTreeMap::new();
    for method in methods {
        let estimates: Vec<Option<MotionEstimate>> = members
            .iter()
            .map(|o| o.estimates.get(&method).copied().flatten())
            .collect();
        // Scoring cannot fail: truth and estimates have one entry per member.
        let Ok(mut motion) = score_method(&truth, &estimates) else {
            continue;
        };
        if !method.has_heading() {
            motion.heading_rmse_deg = None;
            motion.heading_me_deg = None;
            motion.heading_scored_scans = 0;
        }
        let epes: Vec<f64> = members
            .iter()
            .filter_map(|o| o.point_epe_m.get(&method).copied())
            .collect();
        let point_epe_m = (!epes.is_empty()).then(|| epes.iter().sum::<f64>() / epes.len() as f64);
        out.insert(
            method,
            ObjectMetrics {
                object_scans: members.len(),
                motion,
                point_epe_m,
            },
        );
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn object(class: ActorClass, speed_mps: f64, range_m: f64, points: usize) -> ObjectScan {
        let truth = TruthAtScan {
            range_m: Some(range_m),
            target_points: Some(points),
            ..TruthAtScan::from_velocity(0, [speed_mps, 0.0])
        };
        let estimates = BTreeMap::from([
            (
                Method::KfAuto,
                Some(MotionEstimate::from_velocity([0.0, speed_mps])),
            ),
            (
                Method::ZeroFlow,
                Some(MotionEstimate::from_velocity([0.0, 0.0])),
            ),
        ]);
        ObjectScan {
            scan: 0,
            actor: 1,
            class,
            truth,
            estimates,
            point_epe_m: BTreeMap::from([(Method::ZeroFlow, speed_mps * 0.1)]),
        }
    }

    #[test]
    fn groups_split_moving_objects_by_class_range_and_points_and_keep_standing_ones_apart() {
        let objects = [
            object(ActorClass::Car, 6.0, 10.0, 300),
            object(ActorClass::Pedestrian, 1.2, 20.0, 40),
            object(ActorClass::Truck, 0.0, 35.0, 500),
        ];
        let count = |g: ObjectGroup| objects.iter().filter(|o| g.contains(o)).count();
        assert_eq!(count(ObjectGroup::Moving), 2);
        assert_eq!(count(ObjectGroup::Class(ActorClass::Pedestrian)), 1);
        assert_eq!(count(ObjectGroup::Class(ActorClass::Truck)), 0);
        assert_eq!(count(ObjectGroup::Standing), 1);
        assert_eq!(count(ObjectGroup::Range(0)), 1);
        assert_eq!(count(ObjectGroup::Range(2)), 0);
        assert_eq!(count(ObjectGroup::Points(0)), 1);
        assert_eq!(ObjectGroup::Points(2).label(), "200 and more points");
    }

    #[test]
    fn zero_flow_has_a_speed_error_but_no_heading_score() {
        let objects = [
            object(ActorClass::Car, 6.0, 10.0, 300),
            object(ActorClass::Car, 4.0, 12.0, 90),
        ];
        let scores = score_objects(&objects, ObjectGroup::Moving).unwrap();
        let zero = &scores[&Method::ZeroFlow];
        assert!(zero.motion.heading_rmse_deg.is_none());
        assert!((zero.motion.speed_rmse_mps.unwrap() - (26.0f64).sqrt()).abs() < 1e-12);
        assert!((zero.point_epe_m.unwrap() - 0.5).abs() < 1e-12);
        let kf = &scores[&Method::KfAuto];
        assert!((kf.motion.heading_rmse_deg.unwrap() - 90.0).abs() < 1e-9);
        assert_eq!(kf.object_scans, 2);
        assert!(score_objects(&objects, ObjectGroup::Standing).is_none());
    }
}
