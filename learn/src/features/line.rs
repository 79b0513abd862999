//! Bresenham's line (Bresenham 1965) on a grid: the tracing of misses for the reflection map
//! (thesis 2.1.1) and the outlines of the rendered boxes, visiting the same cells.

/// Adds a miss to every cell of Bresenham's line between two cells inside the window (the last
/// one left out if `skip_last`): the hot loop.
///
/// Steep lines step cell by cell. Flat lines (at least three cells along the major axis per step
/// of the minor one) go run by run (Bresenham's run-slice form): the cells sharing a minor
/// coordinate are one loop without the error test, contiguous in memory for x-major lines.
/// Both visit exactly the cells of [`bresenham`].
pub(crate) fn add_misses(
    misses: &mut [f32],
    cols: usize,
    from: (i64, i64),
    to: (i64, i64),
    skip_last: bool,
) {
    let line = Octant::new(from, to, cols as i64);
    let start = from.1 * cols as i64 + from.0;
    let count = line.major + 1 - i64::from(skip_last);
    if 3 * line.minor > line.major {
        let mut index = start;
        let mut err = 2 * line.minor - line.major;
        for _ in 0..count {
            misses[index as usize] += 1.0;
            if err > 0 {
                index += line.minor_step;
                err -= 2 * line.major;
            }
            err += 2 * line.minor;
            index += line.major_step;
        }
        return;
    }
    // The loop above takes its m-th minor step (m ≥ 1) before cell
    // k_m = ceil((2·major·m − major + 1) / (2·minor)); track that quotient and remainder.
    let d = (2 * line.minor).max(1);
    let (q_step, r_step) = (2 * line.major / d, 2 * line.major % d);
    let (mut q, mut r) = ((line.major + 1) / d, (line.major + 1) % d);
    let (mut k, mut run_start) = (0, start);
    for m in 0..=line.minor {
        let next = if m == line.minor {
            count
        } else {
            (q + i64::from(r > 0)).min(count)
        };
        add_run(
            misses,
            run_start + k * line.major_step,
            line.major_step,
            next - k,
        );
        k = next;
        run_start += line.minor_step;
        q += q_step;
        r += r_step;
        if r >= d {
            q += 1;
            r -= d;
        }
    }
}

/// Adds a miss to `len` cells from `first` on, `step` apart.
fn add_run(misses: &mut [f32], first: i64, step: i64, len: i64) {
    if len <= 0 {
        return;
    }
    let cells = match step {
        1 => &mut misses[first as usize..(first + len) as usize],
        -1 => &mut misses[(first + 1 - len) as usize..=first as usize],
        _ => {
            let mut index = first;
            for _ in 0..len {
                misses[index as usize] += 1.0;
                index += step;
            }
            return;
        }
    };
    cells.iter_mut().for_each(|v| *v += 1.0);
}

/// A line's steps split into the major axis (one step per cell) and the minor axis.
struct Octant {
    major: i64,
    minor: i64,
    major_step: i64,
    minor_step: i64,
}

impl Octant {
    /// `stride` is the step of one row: the row length for cell indices, or any value above the
    /// column count to decode `(x, y)` pairs.
    fn new(from: (i64, i64), to: (i64, i64), stride: i64) -> Self {
        let (dx, dy) = ((to.0 - from.0).abs(), (to.1 - from.1).abs());
        let sx = if to.0 >= from.0 { 1 } else { -1 };
        let sy = if to.1 >= from.1 { stride } else { -stride };
        if dx >= dy {
            Self {
                major: dx,
                minor: dy,
                major_step: sx,
                minor_step: sy,
            }
        } else {
            Self {
                major: dy,
                minor: dx,
                major_step: sy,
                minor_step: sx,
            }
        }
    }
}

/// Bresenham's line from cell `(x0, y0)` to `(x1, y1)`, both included; `visit(x, y, is_last)`.
/// Visits the same cells as the tracing loop of the reflection map.
pub(crate) fn bresenham(x0: i64, y0: i64, x1: i64, y1: i64, mut visit: impl FnMut(i64, i64, bool)) {
    let line = Octant::new((x0, y0), (x1, y1), 1 << 32);
    let (mut x, mut y) = (x0, y0);
    let mut err = 2 * line.minor - line.major;
    let split = |step: i64| {
        if step.abs() >= 1 << 32 {
            (0, step.signum())
        } else {
            (step, 0)
        }
    };
    let (major, minor) = (split(line.major_step), split(line.minor_step));
    for k in 0..=line.major {
        visit(x, y, k == line.major);
        if err > 0 {
            x += minor.0;
            y += minor.1;
            err -= 2 * line.major;
        }
        err += 2 * line.minor;
        x += major.0;
        y += major.1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn bresenham_visits_a_connected_line_between_both_ends() {
        let mut cells = Vec::new();
        bresenham(0, 0, 5, -3, |x, y, _| cells.push((x, y)));
        assert_eq!(cells.first(), Some(&(0, 0)));
        assert_eq!(cells.last(), Some(&(5, -3)));
        assert!(
            cells
                .windows(2)
                .all(|w| (w[1].0 - w[0].0).abs() <= 1 && (w[1].1 - w[0].1).abs() <= 1)
        );
        assert_eq!(cells.len(), 6);
    }

    #[test]
    fn the_tracing_loop_visits_the_cells_of_the_drawn_line() {
        let cols = 40usize;
        for (from, to) in [
            ((3, 4), (30, 11)),
            ((35, 2), (1, 30)),
            ((20, 20), (20, 20)),
            ((5, 38), (9, 0)),
        ] {
            let mut traced = vec![0f32; cols * cols];
            add_misses(&mut traced, cols, from, to, false);
            let mut drawn = vec![0f32; cols * cols];
            bresenham(from.0, from.1, to.0, to.1, |x, y, _| {
                drawn[y as usize * cols + x as usize] += 1.0
            });
            assert_eq!(traced, drawn, "{from:?} -> {to:?}");
            assert_eq!(drawn[to.1 as usize * cols + to.0 as usize], 1.0);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        #[test]
        fn the_tracing_loop_visits_the_drawn_cells_for_every_line(
            from in (0i64..30, 0i64..30),
            to in (0i64..30, 0i64..30),
            skip_last: bool,
        ) {
            let cols = 30usize;
            let mut traced = vec![0f32; cols * cols];
            add_misses(&mut traced, cols, from, to, skip_last);
            let mut drawn = vec![0f32; cols * cols];
            bresenham(from.0, from.1, to.0, to.1, |x, y, last| {
                if !(last && skip_last) {
                    drawn[y as usize * cols + x as usize] += 1.0;
                }
            });
            prop_assert_eq!(traced, drawn);
        }
    }
}
