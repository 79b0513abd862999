//! Development check: learn the motion map of `<name>_train` in DATASET and score DGPOM and the
//! GPOMs on `<name>` at t = 3 … 9. `cargo run --release -p patchflow-occupancy --example
//! dgpom_check -- DATASET [NAME]`. Environment: `ITERS` (DGPOM's L-BFGS iterations, 50),
//! `NOISE_FLOOR` (all GPs), `PSEUDO` (SPGP's pseudo-inputs, all GPs), `FREE` (free-sample spacing, m), `PAST_FREE=0`, `SCANS`, `METHODS`,
//! `QUERY`, `FITS` (print every fit), `DIAG` (1 − AUC by class of query point), `ORACLE=ε` (the
//! exact T-junction lane velocities with error ε), `MIN_CELLS`, `CROSSING`, `DUMP`; for the motion
//! map alone `MM_SEED` (the subsets it draws where a kind has more cells than its half),
//! `VEL_POINTS` (cells of Υ and of ε), `CLUSTERS=1|2` (each moving cluster against its actor),
//! `CLDUMP` and `ACTORS` (every cluster, every actor near the T-junction's lanes, to stderr),
//! `LANES` (Υ's error by region of the busy intersection), `HITS` (its west street's returns).

use std::sync::Arc;
use std::time::Instant;

use patchflow_dataset::Dataset;
use patchflow_gp::MotionField;
use patchflow_occupancy::*;

mod diagnose;
use diagnose::{cluster_quality, diagnose, lane_regions};

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let Some(dir) = args.get(1) else {
        return Err("usage: dgpom_check DATASET [NAME]".into());
    };
    let dataset = Dataset::open(std::path::Path::new(dir))?;
    let name = args.get(2).map_or("dgpom_tjunction", String::as_str);
    let seq = OccupancySequence::load(&dataset.sequence(name)?)?;
    let train = OccupancySequence::load(&dataset.sequence(&format!("{name}_train"))?)?;
    let start = Instant::now();
    let mut mm = MotionMapParams::default();
    if let Ok(v) = std::env::var("VEL_POINTS") {
        mm.velocity_points = v.parse()?;
        mm.error_points = mm.velocity_points;
    }
    if let Ok(v) = std::env::var("MM_SEED") {
        mm.seed = v.parse()?;
    }
    if let Ok(v) = std::env::var("MIN_CELLS") {
        mm.clusters.min_cells = v.parse()?;
    }
    let map = MotionMap::learn(&train, &mm)?;
    println!(
        "motion map in {:.2} s: {}",
        start.elapsed().as_secs_f64(),
        map.summary
    );
    println!("accuracy: {:?}", map.accuracy);
    let kinds = |k: ClusterKind| map.clusters.iter().filter(|c| c.kind == k).count();
    println!(
        "clusters: {} arrived, {} vacated, {} stationary; paired {}",
        kinds(ClusterKind::Arrived),
        kinds(ClusterKind::Vacated),
        kinds(ClusterKind::Stationary),
        map.clusters
            .iter()
            .filter(|c| c.association == Association::Paired)
            .count()
    );
    for y in [
        2.0, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0, 6.5, 7.0, 7.5, 8.0, 9.0, 10.0, 11.0,
    ] {
        let v: Vec<String> = [0.0, 5.0, 10.0, 15.0, 20.0, 25.0, 30.0]
            .iter()
            .map(|&x| {
                let v = map.velocity_mps([x, y]);
                format!("{:+.2},{:+.2}|{:.2}", v[0], v[1], map.error_mps([x, y]))
            })
            .collect();
        println!("y {y:5.1}: {}", v.join("  "));
    }
    if std::env::var("HITS").is_ok() {
        // The returns beyond x = −20 m near the west street, scans 100-105, and the actors there.
        let by_scan = train.truth.actors_by_scan();
        for (k, (scan, (_, actors))) in train
            .scans
            .iter()
            .zip(by_scan.iter())
            .enumerate()
            .skip(100)
            .take(6)
        {
            let hits: Vec<String> = scan
                .beams
                .iter()
                .filter(|b| b.hit && b.end_m[0] < -20.0 && b.end_m[1].abs() < 6.0)
                .map(|b| format!("({:.1},{:.1})", b.end_m[0], b.end_m[1]))
                .collect();
            println!("scan {k}: hits {}", hits.join(" "));
            for a in actors {
                if a.centre_m[0] < -20.0 && a.centre_m[1].abs() < 6.0 {
                    println!(
                        "   actor {} at ({:.1},{:.1})",
                        a.name, a.centre_m[0], a.centre_m[1]
                    );
                }
            }
        }
    }
    if std::env::var("LANES").is_ok() {
        lane_regions(&map, &train);
    }
    if std::env::var("CLUSTERS").is_ok() {
        cluster_quality(&map, &train);
    }
    if std::env::var("CLDUMP").is_ok() {
        for c in &map.clusters {
            eprintln!(
                "CL {} {:?} {:.2} {:.2} {:.2} {:.2} {}",
                c.scan,
                c.kind,
                c.centroid_m[0],
                c.centroid_m[1],
                c.velocity_mps[0],
                c.velocity_mps[1],
                c.cells_m.len()
            );
        }
    }
    if std::env::var("ACTORS").is_ok() {
        for (k, (t, actors)) in train.truth.actors_by_scan().iter().enumerate() {
            for a in actors {
                let b = OrientedBox::of_object(a);
                if b.centre_m[0] < -5.0 || b.centre_m[0] > 35.0 {
                    continue;
                }
                eprintln!(
                    "ACT scan {k} t {t:.1} x {:.2}..{:.2} y {:.2}..{:.2} v {:+.1}",
                    b.centre_m[0] - b.half_extents_m[0],
                    b.centre_m[0] + b.half_extents_m[0],
                    b.centre_m[1] - b.half_extents_m[1],
                    b.centre_m[1] + b.half_extents_m[1],
                    a.velocity_mps[0]
                );
            }
        }
    }
    if std::env::var("CROSSING").is_ok() {
        // The busy intersection: each lane's Υ at 20, 10 and 5 m before the centre and beyond.
        for (lane, points) in [
            (
                "east  y=-2.5 (+8)",
                [[-20.0, -2.5], [-10.0, -2.5], [-5.0, -2.5], [10.0, -2.5]],
            ),
            (
                "west  y=+2.5 (-6)",
                [[20.0, 2.5], [10.0, 2.5], [5.0, 2.5], [-10.0, 2.5]],
            ),
            (
                "north x=+2.5 (+7)",
                [[2.5, -20.0], [2.5, -10.0], [2.5, -5.0], [2.5, 10.0]],
            ),
            (
                "south x=-2.5 (-9)",
                [[-2.5, 20.0], [-2.5, 10.0], [-2.5, 5.0], [-2.5, -10.0]],
            ),
            (
                "block (0)",
                [[20.0, 20.0], [-20.0, -20.0], [20.0, -20.0], [-20.0, 20.0]],
            ),
        ] {
            let v: Vec<String> = points
                .iter()
                .map(|&p| {
                    let v = map.velocity_mps(p);
                    format!("{:+.2},{:+.2}|{:.2}", v[0], v[1], map.error_mps(p))
                })
                .collect();
            println!("{lane}: {}", v.join("  "));
        }
        return Ok(());
    }
    if std::env::var("DUMP").is_ok() {
        dump(&map);
        return Ok(());
    }
    let mut map = map;
    if let Ok(eps) = std::env::var("ORACLE") {
        // The exact lane velocities (T-junction), error `eps` everywhere.
        let eps: f64 = eps.parse()?;
        let nodes = map.raster.nodes();
        let vx = |p: &[f64; 2]| match p[1] {
            y if (3.5..=5.5).contains(&y) => 2.0,
            y if (6.5..=8.5).contains(&y) => -1.0,
            _ => 0.0,
        };
        map.raster.values = vec![
            nodes.iter().map(vx).collect(),
            vec![0.0; nodes.len()],
            vec![eps; nodes.len()],
        ];
    }
    let map = Arc::new(map);
    let samples = SampleParams {
        past_free: std::env::var("PAST_FREE").map_or(true, |v| v != "0"),
        free_spacing_m: std::env::var("FREE").map_or(Ok(3.0), |v| v.parse())?,
        ..SampleParams::default()
    };
    let solver = GpSolver {
        noise_floor: std::env::var("NOISE_FLOOR")
            .map_or(Ok(GpSolver::default().noise_floor), |v| v.parse())?,
        pseudo_inputs: std::env::var("PSEUDO")
            .map_or(Ok(GpSolver::default().pseudo_inputs), |v| v.parse())?,
        ..GpSolver::default()
    };
    // GPOM_ITERS: the GPOMs' iteration limit on both paths (default theirs: 25 exact, 50 SPGP).
    let gpom_default = GpomMethod::space(samples.clone());
    let gpom_iters: Option<usize> = std::env::var("GPOM_ITERS")
        .ok()
        .map(|v| v.parse())
        .transpose()?;
    let (gpom_iters, gpom_exact_iters) = gpom_iters.map_or(
        (gpom_default.max_iters, gpom_default.exact_max_iters),
        |n| (n, n),
    );
    let methods: Vec<Box<dyn MapMethod>> = vec![
        Box::new(DgpomMethod::new(
            DgpomParams {
                solver,
                samples: samples.clone(),
                max_iters: std::env::var("ITERS").map_or(Ok(50), |v| v.parse())?,
                ..DgpomParams::default()
            },
            map,
        )),
        Box::new(GpomMethod {
            solver,
            max_iters: gpom_iters,
            exact_max_iters: gpom_exact_iters,
            ..GpomMethod::space(samples.clone())
        }),
        Box::new(GpomMethod {
            solver,
            max_iters: gpom_iters,
            exact_max_iters: gpom_exact_iters,
            ..GpomMethod::space_time(samples)
        }),
    ];
    // METHODS=DGPOM,GPOM-RD keeps only those; QUERY=5,6 only those query times.
    let only = std::env::var("METHODS").ok();
    let refs: Vec<&dyn MapMethod> = methods
        .iter()
        .map(|m| m.as_ref())
        .filter(|m| {
            only.as_ref()
                .is_none_or(|o| o.split(',').any(|n| n == m.id().name()))
        })
        .collect();
    let mut params = OccupancyParams::default();
    if let Ok(q) = std::env::var("QUERY") {
        params.query_scans = q
            .split(',')
            .map(str::parse)
            .collect::<std::result::Result<_, _>>()?;
        params.figure_scans.clear();
    }
    if let Ok(n) = std::env::var("SCANS") {
        params.scans_per_map = n.parse()?;
    }
    if std::env::var("DIAG").is_ok() {
        params.figure_scans = params.query_scans.clone();
    }
    let scores = evaluate_sequence(&seq, &refs, &params, &|_, _| {})?;
    if std::env::var("DIAG").is_ok() {
        for fig in &scores.figures {
            diagnose(&seq, fig);
        }
    }
    for (name, m) in &scores.methods {
        let aucs: Vec<String> = m
            .auc_by_query_scan
            .values()
            .map(|a| format!("{:.4}", a.unwrap_or(f64::NAN)))
            .collect();
        if std::env::var("FITS").is_ok() {
            for line in &m.summaries {
                println!("    {line}");
            }
        }
        println!(
            "{name:>9}: {}  {:.2} s/map  {}",
            aucs.join(" "),
            m.mean_seconds_per_map(),
            m.summaries.last().cloned().unwrap_or_default()
        );
        println!(
            "           s/map {:?}  CPU s/map {:?}",
            m.seconds_per_map
                .iter()
                .map(|s| format!("{s:.2}"))
                .collect::<Vec<_>>(),
            m.cpu_seconds_per_map
                .iter()
                .map(|s| format!("{:.2}", s.unwrap_or(f64::NAN)))
                .collect::<Vec<_>>()
        );
    }
    Ok(())
}

fn dump(map: &MotionMap) {
    for c in &map.clusters {
        if c.kind != ClusterKind::Stationary && c.centroid_m[1] > 5.5 {
            println!(
                "scan {:3} {:?} {:?} n {:2} at ({:5.1}, {:4.1}) v ({:+.2}, {:+.2})",
                c.scan,
                c.kind,
                c.association,
                c.cells_m.len(),
                c.centroid_m[0],
                c.centroid_m[1],
                c.velocity_mps[0],
                c.velocity_mps[1]
            );
        }
    }
}
