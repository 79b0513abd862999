//! `DIAG=1` of the development check: where each method's ROC AUC is lost at a query time.

use patchflow_occupancy::{MapFigure, OccupancySequence, OrientedBox};

/// Where each method's AUC is lost at one query time: 1 − AUC split over classes of occupied
/// points (static, actor seen by the query scan, actor hidden) and of free points (next to an
/// actor, crossed by a beam of the query scan, not crossed).
pub fn diagnose(seq: &OccupancySequence, fig: &MapFigure) {
    let t = fig.scan.stamp_secs;
    let statics = seq.truth.static_boxes();
    let boxes = seq.truth.boxes_at(t);
    let actors = &boxes[statics.len()..];
    let h = seq.scan_height_m();
    let hits: Vec<[f64; 2]> = fig
        .scan
        .beams
        .iter()
        .filter(|b| b.hit)
        .map(|b| b.end_m)
        .collect();
    let near = |p: [f64; 2], q: [f64; 2], r: f64| (p[0] - q[0]).hypot(p[1] - q[1]) <= r;
    let crossed = |p: [f64; 2]| {
        fig.scan.beams.iter().any(|b| {
            let (dx, dy) = (b.end_m[0] - b.start_m[0], b.end_m[1] - b.start_m[1]);
            let len2 = dx * dx + dy * dy;
            let u = ((p[0] - b.start_m[0]) * dx + (p[1] - b.start_m[1]) * dy) / len2;
            let u_end = if b.hit { 1.0 - 0.5 / len2.sqrt() } else { 1.0 };
            if !(0.0..=u_end).contains(&u) {
                return false;
            }
            let q = [b.start_m[0] + u * dx, b.start_m[1] + u * dy];
            near(p, q, 0.35)
        })
    };
    let inflated = |b: &OrientedBox, m: f64| OrientedBox {
        half_extents_m: [b.half_extents_m[0] + m, b.half_extents_m[1] + m],
        ..*b
    };
    let class: Vec<usize> = fig
        .grid
        .points_m
        .iter()
        .zip(&fig.truth)
        .map(|(&p, &occ)| {
            if occ {
                if statics.iter().any(|b| b.contains(p, h)) {
                    0
                } else if hits.iter().any(|&q| near(p, q, 0.75)) {
                    1
                } else {
                    2
                }
            } else if actors.iter().any(|b| inflated(b, 1.0).contains(p, h)) {
                3
            } else if crossed(p) {
                4
            } else {
                5
            }
        })
        .collect();
    let names = [
        "static",
        "car seen",
        "car hidden",
        "free by car",
        "free crossed",
        "free unseen",
    ];
    let counts: Vec<usize> = (0..6)
        .map(|c| class.iter().filter(|&&k| k == c).count())
        .collect();
    println!(
        "t {t}: counts {:?}",
        names.iter().zip(&counts).collect::<Vec<_>>()
    );
    for (id, map) in &fig.maps {
        let p = &map.probability;
        let occ: Vec<usize> = (0..p.len()).filter(|&i| fig.truth[i]).collect();
        let free: Vec<usize> = (0..p.len()).filter(|&i| !fig.truth[i]).collect();
        let (no, nf) = (occ.len() as f64, free.len() as f64);
        let mut loss = [0.0; 6];
        for &i in &occ {
            for &j in &free {
                let l = if p[j] > p[i] {
                    1.0
                } else if p[j] == p[i] {
                    0.5
                } else {
                    0.0
                };
                loss[class[i]] += l / (no * nf);
                loss[class[j]] += l / (no * nf);
            }
        }
        let mean_p = |c: usize| {
            let v: Vec<f64> = (0..p.len())
                .filter(|&i| class[i] == c)
                .map(|i| p[i])
                .collect();
            v.iter().sum::<f64>() / v.len().max(1) as f64
        };
        println!(
            "  {:>9}: 1-AUC {:.4} | by occupied {:.4} {:.4} {:.4} | by free {:.4} {:.4} {:.4} | mean p {}",
            id.name(),
            (loss[0] + loss[1] + loss[2] + loss[3] + loss[4] + loss[5]) / 2.0,
            loss[0],
            loss[1],
            loss[2],
            loss[3],
            loss[4],
            loss[5],
            (0..6)
                .map(|c| format!("{:.2}", mean_p(c)))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
}

/// `CLUSTERS=1`: each moving cluster's velocity against the actor it lies on (the actor box,
/// grown by 0.75 m, holding most of its cells; none: truth 0), summarised by association.
pub fn cluster_quality(map: &patchflow_occupancy::MotionMap, train: &OccupancySequence) {
    use patchflow_occupancy::ClusterKind;
    let by_scan = train.truth.actors_by_scan();
    let h = train.scan_height_m();
    let mut stats: std::collections::BTreeMap<String, (usize, f64, usize, usize)> =
        Default::default();
    let mut ratio: std::collections::BTreeMap<String, (usize, f64)> = Default::default();
    for c in &map.clusters {
        if c.kind == ClusterKind::Stationary {
            continue;
        }
        let scan = if c.kind == ClusterKind::Arrived {
            c.scan
        } else {
            c.scan.saturating_sub(1)
        };
        let Some((_, actors)) = by_scan.get(scan) else {
            continue;
        };
        let best = actors
            .iter()
            .map(|a| {
                let b = OrientedBox::of_object(a);
                let b = OrientedBox {
                    half_extents_m: [b.half_extents_m[0] + 0.75, b.half_extents_m[1] + 0.75],
                    ..b
                };
                (c.cells_m.iter().filter(|&&p| b.contains(p, h)).count(), a)
            })
            .max_by_key(|(n, _)| *n);
        let truth = match best {
            Some((n, a)) if n > 0 => [a.velocity_mps[0], a.velocity_mps[1]],
            _ => [0.0, 0.0],
        };
        let none = best.is_none_or(|(n, _)| n == 0);
        let err = (c.velocity_mps[0] - truth[0]).hypot(c.velocity_mps[1] - truth[1]);
        if err > 3.0 && std::env::var("CLUSTERS").is_ok_and(|v| v == "2") {
            println!(
                "  off: scan {} {:?} {} cells at ({:.1}, {:.1}) v ({:+.2}, {:+.2}) truth ({:+.2}, {:+.2})",
                c.scan,
                c.kind,
                c.cells_m.len(),
                c.centroid_m[0],
                c.centroid_m[1],
                c.velocity_mps[0],
                c.velocity_mps[1],
                truth[0],
                truth[1]
            );
        }
        let key = format!("{:?}/{:?}", c.association, c.kind);
        let tn = truth[0].hypot(truth[1]);
        if tn > 1.0 {
            let r = ratio.entry(key.clone()).or_default();
            r.0 += 1;
            r.1 += (c.velocity_mps[0] * truth[0] + c.velocity_mps[1] * truth[1]) / (tn * tn);
        }
        let e = stats.entry(key).or_default();
        e.0 += 1;
        e.1 += err * err;
        e.2 += usize::from(err > 3.0);
        e.3 += usize::from(none);
    }
    for (k, (n, r)) in &ratio {
        println!(
            "{k:>28}: mean (v · t) / |t|² {:.2} over {n} clusters on a moving actor",
            r / *n.max(&1) as f64
        );
    }
    for (k, (n, sq, bad, none)) in stats {
        println!(
            "{k:>28}: {n:4} clusters, RMSE {:.2} m/s, {bad} off by > 3 m/s, {none} on no actor",
            (sq / n.max(1) as f64).sqrt()
        );
    }
}

/// `LANES=1`: Υ's error on the training run's lane cells, by region of a four-way intersection
/// centred at the origin (the crossing square |x|, |y| < `HALF`, and the four arms).
pub fn lane_regions(map: &patchflow_occupancy::MotionMap, train: &OccupancySequence) {
    use patchflow_occupancy::MotionField;
    const HALF: f64 = 4.0;
    let cell = 0.5;
    let h = train.scan_height_m();
    let mut lanes: std::collections::BTreeMap<(i64, i64), ([f64; 2], usize)> = Default::default();
    for (_, actors) in train.truth.actors_by_scan() {
        for a in actors {
            let b = OrientedBox::of_object(a);
            let reach = b.half_extents_m[0].hypot(b.half_extents_m[1]);
            let lo = (
                ((b.centre_m[0] - reach) / cell).floor() as i64,
                ((b.centre_m[1] - reach) / cell).floor() as i64,
            );
            let hi = (
                ((b.centre_m[0] + reach) / cell).floor() as i64,
                ((b.centre_m[1] + reach) / cell).floor() as i64,
            );
            for c in lo.0..=hi.0 {
                for r in lo.1..=hi.1 {
                    let p = [(c as f64 + 0.5) * cell, (r as f64 + 0.5) * cell];
                    if b.contains(p, h) {
                        let e = lanes.entry((c, r)).or_insert(([0.0; 2], 0));
                        e.0[0] += a.velocity_mps[0];
                        e.0[1] += a.velocity_mps[1];
                        e.1 += 1;
                    }
                }
            }
        }
    }
    // Cells the run's beams crossed or hit (as `MotionAccuracy` scores only observed cells).
    let mut observed: std::collections::BTreeSet<(i64, i64)> = Default::default();
    for scan in &train.scans {
        for b in &scan.beams {
            let (dx, dy) = (b.end_m[0] - b.start_m[0], b.end_m[1] - b.start_m[1]);
            let steps = (dx.hypot(dy) / 0.25).ceil() as usize;
            for k in 0..=steps {
                let u = k as f64 / steps.max(1) as f64;
                let p = [b.start_m[0] + u * dx, b.start_m[1] + u * dy];
                observed.insert(((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64));
            }
        }
    }
    // region -> (n, sq err, sum |truth|, sum |Υ|, sum of Υ·t̂ / |t|)
    let mut stats: std::collections::BTreeMap<String, (usize, f64, f64, f64, f64)> =
        Default::default();
    for (&(c, r), (sum, n)) in &lanes {
        let p = [(c as f64 + 0.5) * cell, (r as f64 + 0.5) * cell];
        if !observed.contains(&(c, r)) {
            continue;
        }
        let t = [sum[0] / *n as f64, sum[1] / *n as f64];
        let v = map.velocity_mps(p);
        let region = if p[0].abs() < HALF && p[1].abs() < HALF {
            "crossing".to_string()
        } else if p[0].abs() < 10.0 && p[1].abs() < 10.0 {
            "square".to_string()
        } else {
            let arm = if p[0] < -10.0 {
                "west"
            } else if p[0] > 10.0 {
                "east"
            } else if p[1] > 10.0 {
                "north"
            } else {
                "south"
            };
            let lane = if arm == "west" || arm == "east" {
                if p[1] < 0.0 { "y<0" } else { "y>0" }
            } else if p[0] < 0.0 {
                "x<0"
            } else {
                "x>0"
            };
            let far = if p[0].abs().max(p[1].abs()) > 30.0 {
                "far"
            } else {
                "near"
            };
            format!("{arm} {lane} {far}")
        };
        let tn = t[0].hypot(t[1]);
        let e = stats.entry(region).or_default();
        e.0 += 1;
        e.1 += (v[0] - t[0]).powi(2) + (v[1] - t[1]).powi(2);
        e.2 += tn;
        e.3 += v[0].hypot(v[1]);
        e.4 += if tn > 0.1 {
            (v[0] * t[0] + v[1] * t[1]) / tn
        } else {
            0.0
        };
    }
    for (k, (n, sq, t, v, along)) in stats {
        let n_f = n.max(1) as f64;
        println!(
            "  {k:>18}: {n:5} cells, RMSE {:.2}, |truth| {:.2}, |Υ| {:.2}, Υ along truth {:.2}",
            (sq / n_f).sqrt(),
            t / n_f,
            v / n_f,
            along / n_f
        );
    }
}
