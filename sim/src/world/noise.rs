//! Seeded 2-D value noise: a lattice of hashed values in [−1, 1], smoothly interpolated, summed
//! over octaves. Stable across platforms (integer hashing only), so the procedural world is the
//! same on every machine for the same seed.

use crate::seed::mix;

/// Value noise with a given wavelength and octave count, seeded.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ValueNoise {
    seed: u64,
    inverse_wavelength: f64,
    octaves: u32,
}

impl ValueNoise {
    /// Noise whose coarsest octave has features `wavelength_m` apart.
    pub(crate) fn new(seed: u64, wavelength_m: f64, octaves: u32) -> Self {
        Self {
            seed,
            inverse_wavelength: 1.0 / wavelength_m.max(1e-6),
            octaves: octaves.max(1),
        }
    }

    /// The noise at `(x, y)`, in [−1, 1] (octaves halve in amplitude and wavelength).
    pub(crate) fn at(&self, x: f64, y: f64) -> f64 {
        let (mut sum, mut amplitude, mut norm, mut scale) =
            (0.0, 1.0, 0.0, self.inverse_wavelength);
        for octave in 0..self.octaves {
            sum += amplitude * lattice(self.seed ^ u64::from(octave), x * scale, y * scale);
            norm += amplitude;
            amplitude *= 0.5;
            scale *= 2.0;
        }
        sum / norm
    }
}

/// One octave: bilinear interpolation, with a smoothstep, of hashed lattice values.
fn lattice(seed: u64, x: f64, y: f64) -> f64 {
    let (fx, fy) = (x.floor(), y.floor());
    let (i, j) = (fx as i64, fy as i64);
    let (u, v) = (smooth(x - fx), smooth(y - fy));
    let value = |di: i64, dj: i64| {
        let h = mix(seed ^ mix((i + di) as u64 ^ mix((j + dj) as u64 ^ 0xA5A5)));
        (h >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    let bottom = value(0, 0) * (1.0 - u) + value(1, 0) * u;
    let top = value(0, 1) * (1.0 - u) + value(1, 1) * u;
    bottom * (1.0 - v) + top * v
}

fn smooth(t: f64) -> f64 {
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_stays_in_its_range_and_is_continuous() {
        let noise = ValueNoise::new(3, 10.0, 3);
        let mut previous = noise.at(0.0, 0.0);
        for k in 1..5000 {
            let x = f64::from(k) * 0.01;
            let value = noise.at(x, 0.5 * x);
            assert!((-1.0..=1.0).contains(&value), "{value}");
            assert!((value - previous).abs() < 0.05, "jump at {x}");
            previous = value;
        }
    }

    #[test]
    fn another_seed_gives_another_field() {
        let (a, b) = (ValueNoise::new(1, 5.0, 2), ValueNoise::new(2, 5.0, 2));
        let differs =
            (0..100).any(|k| (a.at(f64::from(k), 3.0) - b.at(f64::from(k), 3.0)).abs() > 0.1);
        assert!(differs);
    }
}
