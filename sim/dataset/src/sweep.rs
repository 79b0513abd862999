//! One lidar sweep: points in the sensor frame with per-point labels, flow and timing, plus object truth.

use crate::{MAX_OBJECT_SPEED_MPS, MAX_POINTS_PER_SWEEP, ObjectTruth, PointLabel, Pose};

/// Largest intensity a point may carry (they are reflectivities near 0 to 1, or 0 to 255).
const MAX_INTENSITY: f64 = 1e6;
/// Latest a point may fire after its sweep's reference time, seconds (a turn takes 0.1 s).
pub(crate) const MAX_TIME_IN_SWEEP_SECS: f64 = 3600.0;

/// One labelled sweep as stored on disk (SPEC §4).
///
/// The per-point arrays are parallel: index `i` of each describes the same point. Points are in
/// the sensor frame at the sweep's reference time (`stamp_secs`) with the ego's own motion removed,
/// as in KITTI odometry; moving actors keep their rolling-shutter smear.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Sweep {
    /// Sweep number within its sequence (file name `NNNNNN`).
    pub index: u32,
    /// Reference time of the sweep, seconds since the sequence started (`times.txt`).
    pub stamp_secs: f64,
    /// Pose of the sensor at the reference time (`poses.txt`): the truth.
    pub world_from_sensor: Pose,
    /// The ego's own estimate of that pose (`poses_estimated.txt`), which the points were
    /// ego-motion-compensated with; `None` when the dataset has none (then it is the truth).
    pub estimated_world_from_sensor: Option<Pose>,
    /// x, y, z in the sensor frame (KITTI axes: x forward, y left, z up), metres.
    pub points_in_sensor: Vec<[f32; 3]>,
    /// Return intensity in [0, 1].
    pub intensities: Vec<f32>,
    /// SemanticKITTI label per point.
    pub labels: Vec<PointLabel>,
    /// True velocity of the hit surface point, world frame, m/s.
    pub flow_in_world_mps: Vec<[f32; 3]>,
    /// Seconds since the sweep started at which the point was measured.
    pub time_in_sweep_secs: Vec<f32>,
    /// Channel (ring) of each point, 0 = the lowest beam (`ring/NNNNNN.bin`, uint16); empty when
    /// the dataset has no ring files.
    pub rings: Vec<u16>,
    /// Ground truth of every actor at the reference time.
    pub objects: Vec<ObjectTruth>,
}

impl Sweep {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.points_in_sensor.len()
    }

    /// True if the sweep has no points.
    pub fn is_empty(&self) -> bool {
        self.points_in_sensor.is_empty()
    }

    /// Checks that all per-point arrays have one entry per point; returns the first mismatch.
    pub fn check_lengths(&self) -> Result<(), String> {
        let n = self.len();
        for (name, len) in [
            ("intensities", self.intensities.len()),
            ("labels", self.labels.len()),
            ("flow", self.flow_in_world_mps.len()),
            ("time", self.time_in_sweep_secs.len()),
            (
                "ring",
                if self.rings.is_empty() {
                    n
                } else {
                    self.rings.len()
                },
            ),
        ] {
            if len != n {
                return Err(format!("{name} has {len} entries for {n} points"));
            }
        }
        Ok(())
    }

    /// The pose the ego itself believes it had (what perception and estimators should use, as
    /// a real car only knows its estimate): the estimate if the dataset has one, else the truth.
    pub fn estimated_pose(&self) -> Pose {
        self.estimated_world_from_sensor
            .unwrap_or(self.world_from_sensor)
    }

    /// Checks that the sweep fits the format's limits and every value is finite (a NaN or an
    /// infinity on disk is a silently wrong result for every reader); returns the first problem.
    pub fn check_values(&self) -> Result<(), String> {
        if self.len() > MAX_POINTS_PER_SWEEP {
            return Err(format!(
                "{} points; a sweep holds at most {MAX_POINTS_PER_SWEEP}",
                self.len()
            ));
        }
        // Finite, and within physical sense: a 1e38 m/s flow is finite in f32 but no truth.
        fn first_bad(
            name: &str,
            values: impl Iterator<Item = f32>,
            per: usize,
            (limit, unit): (f64, &str),
        ) -> Option<String> {
            let mut values = values;
            let bad = |v: &f32| !v.is_finite() || f64::from(v.abs()) > limit;
            values.position(|v| bad(&v)).map(|k| {
                format!(
                    "{name} of point {} is not finite or beyond ±{limit} {unit}",
                    k / per
                )
            })
        }
        let problem = first_bad(
            "a coordinate",
            self.points_in_sensor.iter().flatten().copied(),
            3,
            (crate::MAX_COORDINATE_M, "m"),
        )
        .or_else(|| {
            let intensities = self.intensities.iter().copied();
            first_bad("the intensity", intensities, 1, (MAX_INTENSITY, ""))
        })
        .or_else(|| {
            first_bad(
                "the flow",
                self.flow_in_world_mps.iter().flatten().copied(),
                3,
                (MAX_OBJECT_SPEED_MPS, "m/s"),
            )
        })
        .or_else(|| {
            let times = self.time_in_sweep_secs.iter().copied();
            first_bad("the time", times, 1, (MAX_TIME_IN_SWEEP_SECS, "s"))
        })
        .or_else(|| self.objects.iter().find_map(ObjectTruth::problem));
        match problem {
            Some(reason) => Err(reason),
            None => Ok(()),
        }
    }

    /// Point `i` transformed into the world frame.
    pub fn point_in_world(&self, i: usize) -> nalgebra::Point3<f64> {
        let [x, y, z] = self.points_in_sensor[i];
        self.world_from_sensor * nalgebra::Point3::new(f64::from(x), f64::from(y), f64::from(z))
    }

    /// The object marked `target`, if any.
    pub fn target(&self) -> Option<&ObjectTruth> {
        self.objects.iter().find(|o| o.target)
    }
}
