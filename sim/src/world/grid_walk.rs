//! The 2-D grid walk both grids of a street world cast rays with (the ground's blocks and cells,
//! the piece grid's cells): the cells a ray crosses, in order, each with the span of `t` the ray
//! spends over it (Amanatides and Woo's traversal).

/// Walks the cells of a grid (`size` cells of `cell` metres from the local origin) that the 2-D
/// ray `origin + t·dir` crosses for `t` in `span`, in order, calling `visit(i, j, t_in, t_out)`
/// until it returns true; returns whether it did.
pub(crate) fn walk_cells(
    origin: [f32; 2],
    dir: [f32; 2],
    cell: f32,
    size: [usize; 2],
    span: (f32, f32),
    mut visit: impl FnMut(usize, usize, f32, f32) -> bool,
) -> bool {
    let (mut t, t_end) = span;
    // Per axis: the cell index, its step, the `t` of the next cell boundary and between two.
    // A cell index below 0 is clamped (truncation is the floor there), one past the end wraps
    // to a huge index that fails the size test.
    let axis = |a: usize| {
        let start = origin[a] + dir[a] * t;
        let c = ((start / cell).max(0.0) as usize).min(size[a] - 1);
        if dir[a] > 1e-12 {
            (
                c,
                1usize,
                ((c + 1) as f32 * cell - origin[a]) / dir[a],
                cell / dir[a],
            )
        } else if dir[a] < -1e-12 {
            (
                c,
                usize::MAX,
                (c as f32 * cell - origin[a]) / dir[a],
                -cell / dir[a],
            )
        } else {
            (c, 0, f32::INFINITY, f32::INFINITY)
        }
    };
    let (mut i, step_i, mut next_x, delta_x) = axis(0);
    let (mut j, step_j, mut next_y, delta_y) = axis(1);
    loop {
        // Ties step along x.
        if next_y < next_x {
            if visit(i, j, t, next_y.min(t_end)) {
                return true;
            }
            if next_y >= t_end {
                return false;
            }
            t = next_y;
            next_y += delta_y;
            j = j.wrapping_add(step_j);
            if j >= size[1] {
                return false;
            }
        } else {
            if visit(i, j, t, next_x.min(t_end)) {
                return true;
            }
            if next_x >= t_end {
                return false;
            }
            t = next_x;
            next_x += delta_x;
            i = i.wrapping_add(step_i);
            if i >= size[0] {
                return false;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_diagonal_ray_visits_the_cells_it_crosses_in_order() {
        let mut visited = Vec::new();
        walk_cells(
            [0.5, 0.2],
            [0.8, 0.6],
            1.0,
            [4, 4],
            (0.0, 10.0),
            |i, j, ta, tb| {
                assert!(ta <= tb);
                visited.push((i, j));
                false
            },
        );
        assert_eq!(visited, [(0, 0), (1, 0), (1, 1), (2, 1), (2, 2), (3, 2)]);
    }
}
