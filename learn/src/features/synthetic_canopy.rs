//! Tree crowns for synthetic sweeps: foliage above the ground that returns some of the rays
//! entering it and lets the rest through to the ground or whatever lies behind.

use nalgebra::Vector3;

/// A tree canopy: a vertical cylinder of foliage above the ground, trunk left out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SyntheticCanopy {
    /// Centre, world x, y.
    pub centre_xy: [f64; 2],
    /// Radius, metres.
    pub radius_m: f64,
    /// Lowest leaves above the ground at the centre, metres.
    pub bottom_m: f64,
    /// Top of the crown above the ground at the centre, metres.
    pub top_m: f64,
    /// Share of the rays entering the crown that return from its surface (the rest pass through).
    pub density: f64,
}

impl SyntheticCanopy {
    /// A street tree: 3 m crown radius from 2.5 m to 7 m, returning 60 % of the rays.
    pub fn street_tree(centre_xy: [f64; 2]) -> Self {
        Self {
            centre_xy,
            radius_m: 3.0,
            bottom_m: 2.5,
            top_m: 7.0,
            density: 0.6,
        }
    }

    /// Where the ray `o + t·d` enters the crown standing on `floor_m`, if it does.
    pub(crate) fn entry(&self, o: &Vector3<f64>, d: &Vector3<f64>, floor_m: f64) -> Option<f64> {
        let (ox, oy) = (o.x - self.centre_xy[0], o.y - self.centre_xy[1]);
        let a = d.x * d.x + d.y * d.y;
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        if a > 1e-12 {
            let b = ox * d.x + oy * d.y;
            let c = ox * ox + oy * oy - self.radius_m * self.radius_m;
            let disc = b * b - a * c;
            if disc < 0.0 {
                return None;
            }
            let root = disc.sqrt();
            t0 = t0.max((-b - root) / a);
            t1 = t1.min((-b + root) / a);
        } else if ox * ox + oy * oy > self.radius_m * self.radius_m {
            return None;
        }
        let (lo, hi) = (floor_m + self.bottom_m, floor_m + self.top_m);
        if d.z.abs() > 1e-12 {
            let (a, b) = ((lo - o.z) / d.z, (hi - o.z) / d.z);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        } else if o.z < lo || o.z > hi {
            return None;
        }
        (t0 <= t1 && t1 > 0.0).then_some(t0)
    }
}
