//! Single-link agglomerative clustering of the sliced end points on x, y (thesis 2.2.1).
//!
//! Cutting the single-link hierarchy at distance d gives exactly the connected components of the
//! graph that links every two points at most d apart, so we compute those instead of the O(N²)
//! SLINK: hash the points into cells of side d/√2 (points in one cell are linked; linked points
//! lie at most two cells apart), test only pairs of neighbouring cells until one pair links them,
//! and join with union-find. O(N log N) for bounded point density.

/// A partition of points into clusters with deterministic ids: cluster 0 holds point 0, and ids
/// follow the smallest member index.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Clusters {
    cluster_of: Vec<usize>,
    members: Vec<Vec<usize>>,
}

impl Clusters {
    /// Single-link clusters of `points_xy` cut at `max_gap_m`: two points share a cluster iff a
    /// chain of points with consecutive distances ≤ `max_gap_m` joins them.
    pub fn single_link(points_xy: &[[f64; 2]], max_gap_m: f64) -> Self {
        let mut sets = UnionFind::new(points_xy.len());
        let gap2 = max_gap_m * max_gap_m;
        // Cells of side d/√2: two points in one cell are less than d apart, so a cell is joined
        // without a single test; linked points lie at most two cells apart.
        // Shrunk by 1e-9 so rounding cannot link a same-cell pair just over d.
        let side = max_gap_m / std::f64::consts::SQRT_2 * (1.0 - 1e-9);
        let cell_of = |p: &[f64; 2]| ((p[0] / side).floor() as i64, (p[1] / side).floor() as i64);
        let mut keyed: Vec<((i64, i64), usize)> = points_xy
            .iter()
            .enumerate()
            .map(|(i, p)| (cell_of(p), i))
            .collect();
        keyed.sort_unstable();
        // Runs of equal keys: one run per occupied cell.
        let mut runs: Vec<((i64, i64), usize, usize)> = Vec::new();
        for (pos, (key, _)) in keyed.iter().enumerate() {
            match runs.last_mut() {
                Some((k, _, end)) if k == key => *end = pos + 1,
                _ => runs.push((*key, pos, pos + 1)),
            }
        }
        let close = |a: usize, b: usize| {
            let (p, q) = (points_xy[a], points_xy[b]);
            (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) <= gap2
        };
        for &(_, start, end) in &runs {
            for k in start + 1..end {
                sets.union(keyed[start].1, keyed[k].1);
            }
        }
        // Half of the 5 × 5 neighbourhood; the other half sees this cell from its side. One close
        // pair joins two cells, since each cell is already one set.
        const HALF: [(i64, i64); 12] = [
            (1, 0),
            (2, 0),
            (-2, 1),
            (-1, 1),
            (0, 1),
            (1, 1),
            (2, 1),
            (-2, 2),
            (-1, 2),
            (0, 2),
            (1, 2),
            (2, 2),
        ];
        for &((cx, cy), start, end) in &runs {
            let own = &keyed[start..end];
            for (dx, dy) in HALF {
                let key = (cx + dx, cy + dy);
                let Ok(n) = runs.binary_search_by(|r| r.0.cmp(&key)) else {
                    continue;
                };
                let other = &keyed[runs[n].1..runs[n].2];
                if sets.find(own[0].1) == sets.find(other[0].1) {
                    continue;
                }
                let linked = own
                    .iter()
                    .any(|&(_, a)| other.iter().any(|&(_, b)| close(a, b)));
                if linked {
                    sets.union(own[0].1, other[0].1);
                }
            }
        }
        Self::from_roots((0..points_xy.len()).map(|i| sets.find(i)).collect())
    }

    /// Relabels root ids so ids follow the smallest member index.
    fn from_roots(roots: Vec<usize>) -> Self {
        let mut id_of_root = vec![usize::MAX; roots.len()];
        let mut cluster_of = Vec::with_capacity(roots.len());
        let mut members: Vec<Vec<usize>> = Vec::new();
        for (i, root) in roots.into_iter().enumerate() {
            if id_of_root[root] == usize::MAX {
                id_of_root[root] = members.len();
                members.push(Vec::new());
            }
            cluster_of.push(id_of_root[root]);
            members[id_of_root[root]].push(i);
        }
        Self {
            cluster_of,
            members,
        }
    }

    /// Number of clusters.
    pub fn len(&self) -> usize {
        self.members.len()
    }

    /// True if there are no points.
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }

    /// Cluster id of point `i`.
    pub fn cluster_of(&self, i: usize) -> usize {
        self.cluster_of[i]
    }

    /// Cluster id of every point.
    pub fn ids(&self) -> &[usize] {
        &self.cluster_of
    }

    /// Point indices of cluster `c`, ascending.
    pub fn members(&self, c: usize) -> &[usize] {
        &self.members[c]
    }

    /// Every cluster's members, by id.
    pub fn iter(&self) -> impl Iterator<Item = &[usize]> {
        self.members.iter().map(Vec::as_slice)
    }
}

/// Disjoint sets with path halving and union by size.
struct UnionFind {
    parent: Vec<usize>,
    size: Vec<usize>,
}

impl UnionFind {
    fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
            size: vec![1; n],
        }
    }

    fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    fn union(&mut self, a: usize, b: usize) {
        let (mut ra, mut rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        if self.size[ra] < self.size[rb] {
            std::mem::swap(&mut ra, &mut rb);
        }
        self.parent[rb] = ra;
        self.size[ra] += self.size[rb];
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The textbook algorithm (thesis 2.2.1): start with singletons, repeatedly merge the two
    /// clusters with the smallest single-link distance while it is at most `gap`. O(N³).
    fn brute_force_single_link(points: &[[f64; 2]], gap: f64) -> Clusters {
        let d2 = |a: usize, b: usize| {
            (points[a][0] - points[b][0]).powi(2) + (points[a][1] - points[b][1]).powi(2)
        };
        let mut clusters: Vec<Vec<usize>> = (0..points.len()).map(|i| vec![i]).collect();
        loop {
            let mut best: Option<(f64, usize, usize)> = None;
            for i in 0..clusters.len() {
                for j in i + 1..clusters.len() {
                    let link = clusters[i]
                        .iter()
                        .flat_map(|&a| clusters[j].iter().map(move |&b| (a, b)))
                        .map(|(a, b)| d2(a, b))
                        .fold(f64::INFINITY, f64::min);
                    if best.is_none_or(|(d, _, _)| link < d) {
                        best = Some((link, i, j));
                    }
                }
            }
            match best {
                Some((d, i, j)) if d <= gap * gap => {
                    let merged = clusters.remove(j);
                    clusters[i].extend(merged);
                }
                _ => break,
            }
        }
        let mut roots = vec![0; points.len()];
        for c in &clusters {
            let root = *c.iter().min().unwrap_or(&0);
            for &i in c {
                roots[i] = root;
            }
        }
        Clusters::from_roots(roots)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn grid_hashing_matches_brute_force_single_link(
            points in prop::collection::vec((-3.0f64..3.0, -3.0f64..3.0), 0..40),
            gap in 0.1f64..1.5,
        ) {
            let points: Vec<[f64; 2]> = points.into_iter().map(|(x, y)| [x, y]).collect();
            prop_assert_eq!(Clusters::single_link(&points, gap), brute_force_single_link(&points, gap));
        }
    }

    #[test]
    fn a_car_beside_a_wall_is_its_own_cluster() {
        let mut points: Vec<[f64; 2]> = (0..100).map(|k| [f64::from(k) * 0.1, 0.0]).collect();
        points.extend((0..30).map(|k| [2.0 + f64::from(k) * 0.15, 1.2]));
        let clusters = Clusters::single_link(&points, 0.5);
        assert_eq!(clusters.len(), 2);
        assert_eq!(clusters.members(1).len(), 30);
        assert_eq!(clusters.cluster_of(100), 1);
    }

    #[test]
    fn a_chain_of_close_points_forms_one_long_cluster() {
        let points: Vec<[f64; 2]> = (0..50).map(|k| [f64::from(k) * 0.49, 0.0]).collect();
        assert_eq!(Clusters::single_link(&points, 0.5).len(), 1);
        assert_eq!(Clusters::single_link(&points, 0.48).len(), 50);
    }
}
