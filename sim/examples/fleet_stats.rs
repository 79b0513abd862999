//! Prints the statistics of the fleet the `urban` and `harsh` rungs draw (`VehicleBody`): per
//! car body style and for trucks, the mean ± std and range of length, width, height and belt
//! line, and how many belt lines lie below, near and above the thesis' slice top (1.0 m).
//! `cargo run --release -p patchflow-sim --example fleet_stats [DRAWS]` (default 100,000).

use patchflow_dataset::ActorClass;
use patchflow_sim::{CarModel, VehicleBody};

fn moments(values: &[f64]) -> String {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt();
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    format!("{mean:.3} ± {std:.3} ({lo:.2}-{hi:.2})")
}

fn main() {
    let draws: u64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100_000);
    println!(
        "| vehicles | length m | width m | height m | belt line m | belt < 0.98 / 0.98-1.02 / > 1.02 m |"
    );
    println!("|---|---|---|---|---|---|");
    let kinds: [(&str, ActorClass, Option<CarModel>); 5] = [
        ("cars (no model: the whole fleet)", ActorClass::Car, None),
        ("`compact`", ActorClass::Car, Some(CarModel::Compact)),
        ("`sedan`", ActorClass::Car, Some(CarModel::Sedan)),
        ("`van`", ActorClass::Car, Some(CarModel::Van)),
        ("trucks", ActorClass::Truck, None),
    ];
    for (name, class, model) in kinds {
        let bodies: Vec<VehicleBody> = (0..draws)
            .filter_map(|i| VehicleBody::draw(class, model, i.wrapping_mul(0x9E37_79B9_7F4A_7C15)))
            .collect();
        let column =
            |f: &dyn Fn(&VehicleBody) -> f64| -> Vec<f64> { bodies.iter().map(f).collect() };
        let belts = column(&|b| b.belt_m);
        let n = belts.len() as f64;
        let share =
            |f: &dyn Fn(f64) -> bool| 100.0 * belts.iter().filter(|&&b| f(b)).count() as f64 / n;
        println!(
            "| {name} | {} | {} | {} | {} | {:.0} / {:.0} / {:.0} % |",
            moments(&column(&|b| b.size_m[0])),
            moments(&column(&|b| b.size_m[1])),
            moments(&column(&|b| b.size_m[2])),
            moments(&belts),
            share(&|b| b < 0.98),
            share(&|b| (0.98..=1.02).contains(&b)),
            share(&|b| b > 1.02),
        );
    }
}
