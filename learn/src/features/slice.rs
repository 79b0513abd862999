//! The height slice (thesis 2.1.1): the parts of the beams and the end points between 0.5 m and
//! 1.0 m above the ground, projected onto the ground plane.

use patchflow_dataset::Sweep;

use crate::{FeatureParams, LearnError, Result};

/// The part of one beam inside the height slice, projected to the ground plane (world x, y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlicedBeam {
    /// Where the beam enters the slice (or the sensor, if it starts inside).
    pub start_xy: [f64; 2],
    /// Where it leaves the slice, or its end point.
    pub end_xy: [f64; 2],
    /// True if the end point lies in the slice: the end cell is a hit, the rest misses.
    pub hit: bool,
}

/// An end point inside the slice: world x, y and its index among the sweep's points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlicedPoint {
    /// World x, metres.
    pub x_m: f64,
    /// World y, metres.
    pub y_m: f64,
    /// Index into the sweep's per-point arrays.
    pub index: usize,
}

/// One sweep cut to the height slice.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightSlice {
    /// Sensor position at the sweep's reference time, world x, y.
    pub sensor_xy: [f64; 2],
    /// Every beam that crosses or ends in the slice, in point order.
    pub beams: Vec<SlicedBeam>,
    /// Every end point in the slice, in point order.
    pub points: Vec<SlicedPoint>,
}

impl HeightSlice {
    /// Cuts a sweep: heights are world z (ground at z = 0), beams run from the sensor origin to
    /// each end point. A non-finite point is an error.
    pub fn cut(sweep: &Sweep, params: &FeatureParams) -> Result<Self> {
        let origin = sweep.world_from_sensor.translation.vector;
        let rotation = sweep.world_from_sensor.rotation.to_rotation_matrix();
        let (zmin, zmax) = (params.slice_min_m, params.slice_max_m);
        let mut beams = Vec::new();
        let mut points = Vec::new();
        for (index, p) in sweep.points_in_sensor.iter().enumerate() {
            if !p.iter().all(|v| v.is_finite()) {
                return Err(LearnError::DegenerateData(format!(
                    "sweep {}: point {index} is not finite",
                    sweep.index
                )));
            }
            let end = rotation
                * nalgebra::Vector3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
                + origin;
            let Some((t0, t1)) = clip_to_slab(origin.z, end.z, zmin, zmax) else {
                continue;
            };
            let at = |t: f64| {
                [
                    origin.x + t * (end.x - origin.x),
                    origin.y + t * (end.y - origin.y),
                ]
            };
            let hit = (zmin..=zmax).contains(&end.z);
            beams.push(SlicedBeam {
                start_xy: at(t0),
                end_xy: at(t1),
                hit,
            });
            if hit {
                points.push(SlicedPoint {
                    x_m: end.x,
                    y_m: end.y,
                    index,
                });
            }
        }
        Ok(Self {
            sensor_xy: [origin.x, origin.y],
            beams,
            points,
        })
    }
}

/// The parameter interval `[t0, t1] ⊆ [0, 1]` where `z0 + t·(z1 − z0)` lies in `[zmin, zmax]`.
fn clip_to_slab(z0: f64, z1: f64, zmin: f64, zmax: f64) -> Option<(f64, f64)> {
    let dz = z1 - z0;
    if dz.abs() < 1e-12 {
        return (zmin..=zmax).contains(&z0).then_some((0.0, 1.0));
    }
    let (ta, tb) = ((zmin - z0) / dz, (zmax - z0) / dz);
    let (lo, hi) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
    (lo <= hi).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Translation3, UnitQuaternion};
    use patchflow_dataset::{PointLabel, Pose};

    fn sweep_with(points: Vec<[f32; 3]>) -> Sweep {
        let n = points.len();
        Sweep {
            world_from_sensor: Pose::from_parts(
                Translation3::new(5.0, -2.0, 1.73),
                UnitQuaternion::identity(),
            ),
            points_in_sensor: points,
            intensities: vec![0.5; n],
            labels: vec![PointLabel::default(); n],
            flow_in_world_mps: vec![[0.0; 3]; n],
            time_in_sweep_secs: vec![0.0; n],
            ..Sweep::default()
        }
    }

    #[test]
    fn a_beam_ending_in_the_slice_is_cut_where_it_enters_and_kept_as_a_hit() {
        // End 10 m ahead at z = 0.73 (world): enters the slice (z = 1.0) at 73 % of the way.
        let slice = HeightSlice::cut(
            &sweep_with(vec![[10.0, 0.0, -1.0]]),
            &FeatureParams::default(),
        )
        .unwrap();
        assert_eq!(slice.beams.len(), 1);
        let beam = slice.beams[0];
        assert!(beam.hit);
        assert!((beam.start_xy[0] - (5.0 + 7.3)).abs() < 1e-6, "{beam:?}");
        assert!((beam.end_xy[0] - 15.0).abs() < 1e-6);
        assert_eq!(slice.points[0].index, 0);
    }

    #[test]
    fn a_ground_beam_keeps_only_its_passage_through_the_slice_as_misses() {
        // End on the ground 17.3 m ahead: inside the slice between 7.3 m and 12.3 m.
        let slice = HeightSlice::cut(
            &sweep_with(vec![[17.3, 0.0, -1.73]]),
            &FeatureParams::default(),
        )
        .unwrap();
        let beam = slice.beams[0];
        assert!(!beam.hit && slice.points.is_empty());
        assert!((beam.start_xy[0] - 12.3).abs() < 1e-5 && (beam.end_xy[0] - 17.3).abs() < 1e-5);
    }

    #[test]
    fn beams_above_the_slice_are_dropped() {
        let slice = HeightSlice::cut(
            &sweep_with(vec![[20.0, 0.0, 0.5]]),
            &FeatureParams::default(),
        )
        .unwrap();
        assert!(slice.beams.is_empty() && slice.points.is_empty());
    }

    #[test]
    fn a_non_finite_point_is_an_error() {
        let err = HeightSlice::cut(
            &sweep_with(vec![[f32::NAN, 0.0, 0.0]]),
            &FeatureParams::default(),
        );
        assert!(err.is_err());
    }
}
