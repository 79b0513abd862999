//! The part of one beam inside the height slice (thesis 2.1.1), as the reflection maps trace it.

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

#[cfg(test)]
impl SlicedBeam {
    /// A beam part from `start_xy` to `end_xy` (the tests' hand-made beams).
    pub(crate) fn new(start_xy: [f64; 2], end_xy: [f64; 2], hit: bool) -> Self {
        Self {
            start_xy,
            end_xy,
            hit,
        }
    }
}
