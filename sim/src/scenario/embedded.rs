//! The shipped scenario files, embedded in the binary so `patchflow generate` works anywhere.

/// `(name, TOML text)` of every shipped scenario, sorted by name: the five evaluation situations
/// and the training tracks: the nine of SPEC §3 (`train01` … `train09`, the thesis preset's data)
/// and the training traffic of issue 24 (`train10`, `train12`: cross traffic of both directions
/// between parked cars at 10-45 m; docs/estimator.md, "Training at simulator scale").
/// (`scenarios/tiny.toml`, for tests, the `traffic_*` tracks, measured but not adopted, and the
/// `unseen_*` checks, which no model may train on, are not among them.)
pub const EMBEDDED_SCENARIOS: [(&str, &str); 16] = [
    (
        "situation1",
        include_str!("../../../scenarios/situation1.toml"),
    ),
    (
        "situation2",
        include_str!("../../../scenarios/situation2.toml"),
    ),
    (
        "situation3",
        include_str!("../../../scenarios/situation3.toml"),
    ),
    (
        "situation4",
        include_str!("../../../scenarios/situation4.toml"),
    ),
    (
        "situation5",
        include_str!("../../../scenarios/situation5.toml"),
    ),
    ("train01", include_str!("../../../scenarios/train01.toml")),
    ("train02", include_str!("../../../scenarios/train02.toml")),
    ("train03", include_str!("../../../scenarios/train03.toml")),
    ("train04", include_str!("../../../scenarios/train04.toml")),
    ("train05", include_str!("../../../scenarios/train05.toml")),
    ("train06", include_str!("../../../scenarios/train06.toml")),
    ("train07", include_str!("../../../scenarios/train07.toml")),
    ("train08", include_str!("../../../scenarios/train08.toml")),
    ("train09", include_str!("../../../scenarios/train09.toml")),
    ("train10", include_str!("../../../scenarios/train10.toml")),
    ("train12", include_str!("../../../scenarios/train12.toml")),
];

/// `(name, TOML text)` of the shipped occupancy-map scenarios (the DGPOM paper's T-junction with
/// a fixed planar scanner): evaluation run and training run. They are kept out of
/// [`EMBEDDED_SCENARIOS`], which `patchflow generate` runs when given no scenario, because that
/// folder is what `train` and `cv` read, and planar scans have no place among their sequences;
/// `patchflow generate dgpom_tjunction dgpom_tjunction_train --out DIR` makes them by name.
pub const EMBEDDED_OCCUPANCY_SCENARIOS: [(&str, &str); 2] = [
    (
        "dgpom_tjunction",
        include_str!("../../../scenarios/dgpom_tjunction.toml"),
    ),
    (
        "dgpom_tjunction_train",
        include_str!("../../../scenarios/dgpom_tjunction_train.toml"),
    ),
];
