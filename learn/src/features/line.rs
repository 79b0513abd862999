//! Bresenham's line (Bresenham 1965) on a grid: the tracing of misses for the reflection map
//! (thesis 2.1.1) and the outlines of the rendered boxes, visiting the same cells.

/// The columns and rows `((c0, c1), (r0, r1))` a traced line touched, both ends included.
pub(crate) type Touched = ((usize, usize), (usize, usize));

/// Adds a miss to every cell of Bresenham's line from cell `from` to cell `to` that lies inside
/// the `cols × rows` window (the line's last cell left out if `skip_last`); either end may lie
/// outside the window. Returns the columns and rows touched, `None` if no cell was inside.
///
/// The cells are those of the whole line, whatever part of it the window holds: a line traced
/// on a larger window and cut to a smaller one counts the same cells as one traced on the
/// smaller window, so one sweep's counts serve every window inside the one they were traced on
/// (clipping the line to the window first would move its cells near the edge).
///
/// Steep lines step cell by cell. Flat lines (at least three cells along the major axis per step
/// of the minor one) go run by run (Bresenham's run-slice form): the cells sharing a minor
/// coordinate are one loop without the error test, contiguous in memory for x-major lines.
/// Both visit exactly the cells of [`bresenham`].
pub(crate) fn add_misses(
    misses: &mut [f32],
    (cols, rows): (usize, usize),
    from: (i64, i64),
    to: (i64, i64),
    skip_last: bool,
) -> Option<Touched> {
    let line = Octant::new(from, to, cols as i64);
    let x_major = (to.0 - from.0).abs() >= (to.1 - from.1).abs();
    let sign = |a: i64, b: i64| if b >= a { 1 } else { -1 };
    let (sx, sy) = (sign(from.0, to.0), sign(from.1, to.1));
    // Cell k of the line lies at major coordinate a0 + sa·k and minor coordinate b0 + sb·m_k.
    let ((a0, sa, na), (b0, sb, nb)) = if x_major {
        ((from.0, sx, cols), (from.1, sy, rows))
    } else {
        ((from.1, sy, rows), (from.0, sx, cols))
    };
    let (ka, kb) = inside_steps(a0, sa, na as i64);
    let (ma, mb) = inside_steps(b0, sb, nb as i64);
    let (k_lo, k_hi) = if line.minor == 0 {
        if ma > 0 || mb < 0 {
            return None;
        }
        (ka.max(0), kb.min(line.major - i64::from(skip_last)))
    } else {
        let first = |m: i64| line.first_cell_of_minor_step(m);
        (
            ka.max(first(ma)).max(0),
            kb.min(first(mb + 1) - 1)
                .min(line.major - i64::from(skip_last)),
        )
    };
    if k_lo > k_hi {
        return None;
    }
    let cell = |k: i64| {
        let m = line.minor_steps_before(k);
        if x_major {
            (from.0 + sx * k, from.1 + sy * m)
        } else {
            (from.0 + sx * m, from.1 + sy * k)
        }
    };
    let index = |(x, y): (i64, i64)| y * cols as i64 + x;
    let (first_cell, last_cell) = (cell(k_lo), cell(k_hi));
    let count = k_hi + 1 - k_lo;
    let m = line.minor_steps_before(k_lo);
    if 3 * line.minor > line.major {
        let mut at = index(first_cell);
        let mut err = 2 * line.minor * (k_lo + 1) - line.major - 2 * line.major * m;
        for _ in 0..count {
            misses[at as usize] += 1.0;
            if err > 0 {
                at += line.minor_step;
                err -= 2 * line.major;
            }
            err += 2 * line.minor;
            at += line.major_step;
        }
    } else {
        // Run m holds cells first_cell_of_minor_step(m) .. first_cell_of_minor_step(m + 1) − 1;
        // track the next run's start as a quotient and remainder (no division per run).
        let mut k = k_lo;
        let mut at = index(first_cell);
        let mut next = line.next_run_starts(m);
        loop {
            let end = next.start().min(k_hi + 1);
            add_run(misses, at, line.major_step, end - k);
            if end > k_hi {
                break;
            }
            at += (end - k) * line.major_step + line.minor_step;
            k = end;
            next.advance();
        }
    }
    let (x0, x1) = (first_cell.0.min(last_cell.0), first_cell.0.max(last_cell.0));
    let (y0, y1) = (first_cell.1.min(last_cell.1), first_cell.1.max(last_cell.1));
    Some(((x0 as usize, x1 as usize), (y0 as usize, y1 as usize)))
}

/// The steps `k` (any integers) with `p0 + s·k` in `[0, n)`, as an inclusive range.
fn inside_steps(p0: i64, s: i64, n: i64) -> (i64, i64) {
    if s > 0 {
        (-p0, n - 1 - p0)
    } else {
        (p0 - (n - 1), p0)
    }
}

/// Where the runs of a flat line start: cell `ceil((2·major·m − major + 1) / (2·minor))` for
/// minor step m ≥ 1, kept as quotient and remainder.
struct RunStarts {
    q: i64,
    r: i64,
    d: i64,
    q_step: i64,
    r_step: i64,
}

impl RunStarts {
    /// The first cell of the current run (of minor step m + 1).
    fn start(&self) -> i64 {
        if self.d == 0 {
            i64::MAX
        } else {
            self.q + i64::from(self.r > 0)
        }
    }

    /// On to the next minor step.
    fn advance(&mut self) {
        self.q += self.q_step;
        self.r += self.r_step;
        if self.r >= self.d {
            self.q += 1;
            self.r -= self.d;
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
    /// The first cell (from 0) at minor step `m`: 0 for m ≤ 0; past the line for m > minor.
    fn first_cell_of_minor_step(&self, m: i64) -> i64 {
        if m <= 0 {
            return 0;
        }
        let (n, d) = (2 * self.major * m - self.major + 1, 2 * self.minor);
        (n + d - 1).div_euclid(d)
    }

    /// The minor steps the line has taken before cell `k` (0 ≤ k ≤ major).
    fn minor_steps_before(&self, k: i64) -> i64 {
        if self.major == 0 {
            0
        } else {
            (2 * self.minor * k + self.major - 1).div_euclid(2 * self.major)
        }
    }

    /// The run starts after minor step `m`: cell by cell, the start of step m + 1, m + 2, ….
    fn next_run_starts(&self, m: i64) -> RunStarts {
        let d = 2 * self.minor;
        if d == 0 {
            return RunStarts {
                q: 0,
                r: 0,
                d: 0,
                q_step: 0,
                r_step: 0,
            };
        }
        let n = 2 * self.major * (m + 1) - self.major + 1;
        RunStarts {
            q: n.div_euclid(d),
            r: n.rem_euclid(d),
            d,
            q_step: (2 * self.major).div_euclid(d),
            r_step: (2 * self.major).rem_euclid(d),
        }
    }

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
            add_misses(&mut traced, (cols, cols), from, to, false);
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
            add_misses(&mut traced, (cols, cols), from, to, skip_last);
            let mut drawn = vec![0f32; cols * cols];
            bresenham(from.0, from.1, to.0, to.1, |x, y, last| {
                if !(last && skip_last) {
                    drawn[y as usize * cols + x as usize] += 1.0;
                }
            });
            prop_assert_eq!(traced, drawn);
        }

        #[test]
        fn a_line_with_ends_outside_the_window_counts_the_drawn_cells_inside_it(
            from in (-60i64..60, -60i64..60),
            to in (-60i64..60, -60i64..60),
            (cols, rows) in (1usize..25, 1usize..25),
            skip_last: bool,
        ) {
            let mut traced = vec![0f32; cols * rows];
            let touched = add_misses(&mut traced, (cols, rows), from, to, skip_last);
            let mut drawn = vec![0f32; cols * rows];
            let (mut c, mut r) = ((usize::MAX, 0), (usize::MAX, 0));
            bresenham(from.0, from.1, to.0, to.1, |x, y, last| {
                let inside = (0..cols as i64).contains(&x) && (0..rows as i64).contains(&y);
                if inside && !(last && skip_last) {
                    drawn[y as usize * cols + x as usize] += 1.0;
                    c = (c.0.min(x as usize), c.1.max(x as usize));
                    r = (r.0.min(y as usize), r.1.max(y as usize));
                }
            });
            prop_assert_eq!(traced, drawn);
            prop_assert_eq!(touched, (c.0 != usize::MAX).then_some((c, r)));
        }
    }
}
