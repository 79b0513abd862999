//! A `[lidar]` table with `kind = "planar"`: the planar range scanner's defaults, and the
//! spinner-only fields it fixes (one channel at 0° elevation, one column per beam, each scan cast
//! at one instant). Resolved planar tables state those fixed values, so they read back equal.

use super::{ElevationSpacing, LidarConfig, SensorKind};

/// Field of view of a planar scanner unless the file says otherwise, degrees (SICK LMS291).
pub const PLANAR_FOV_DEG: f64 = 180.0;
/// Beams of a planar scanner unless the file says otherwise (SICK LMS291 at 1°).
pub const PLANAR_BEAMS: u32 = 181;
/// Range of a planar scanner unless the file says otherwise, metres (SICK LMS291).
pub const PLANAR_MAX_RANGE_M: f64 = 80.0;
/// Mount height of a planar scanner unless the file says otherwise, metres: below a car's roof,
/// where a scanner on a small robot sits (the spinning lidar's 1.73 m would look over the cars).
pub const PLANAR_MOUNT_HEIGHT_M: f64 = 0.5;

impl LidarConfig {
    /// Resolves the sensor kind. `keys_in_file` are the keys the scenario's `[lidar]` table sets.
    /// A planar scanner gets its defaults for the fields the file leaves out and the fixed values
    /// of the spinner-only fields; a spinning lidar keeps everything. Returns the fields that
    /// contradict the kind (a spinner-only field set to another value on a planar scanner, or a
    /// planar field on a spinning lidar), each with the reason.
    pub(crate) fn resolve_kind(&mut self, keys_in_file: &[String]) -> Vec<(&'static str, String)> {
        let set = |key: &str| keys_in_file.iter().any(|k| k == key);
        match self.kind {
            SensorKind::Spinning => ["fov_deg", "beams"]
                .into_iter()
                .filter(|key| set(key))
                .map(|key| {
                    let reason =
                        format!("{key} applies to a planar scanner only (add kind = \"planar\")");
                    (key, reason)
                })
                .collect(),
            SensorKind::Planar => {
                self.fov_deg.get_or_insert(PLANAR_FOV_DEG);
                let beams = *self.beams.get_or_insert(PLANAR_BEAMS);
                if !set("max_range_m") {
                    self.max_range_m = PLANAR_MAX_RANGE_M;
                }
                if !set("mount_height_m") {
                    self.mount_height_m = PLANAR_MOUNT_HEIGHT_M;
                }
                let fixed = LidarConfig {
                    channels: 1,
                    upper_deg: 0.0,
                    lower_deg: 0.0,
                    spacing: ElevationSpacing::Uniform,
                    azimuth_steps: beams,
                    rolling_shutter: false,
                    blocks: 1,
                    ..self.clone()
                };
                let differs = [
                    ("channels", self.channels != fixed.channels),
                    ("upper_deg", self.upper_deg != fixed.upper_deg),
                    ("lower_deg", self.lower_deg != fixed.lower_deg),
                    ("spacing", self.spacing != fixed.spacing),
                    ("azimuth_steps", self.azimuth_steps != fixed.azimuth_steps),
                    (
                        "rolling_shutter",
                        self.rolling_shutter != fixed.rolling_shutter,
                    ),
                    ("blocks", self.blocks != fixed.blocks),
                ];
                let problems = differs
                    .into_iter()
                    .filter(|&(key, differs)| differs && set(key))
                    .map(|(key, _)| {
                        let reason = format!(
                            "{key} applies to the spinning lidar only: a planar scanner has one channel at 0° elevation, one column per beam (`beams`) and casts each scan at one instant"
                        );
                        (key, reason)
                    })
                    .collect();
                *self = fixed;
                problems
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn planar(
        keys: &[&str],
        edit: impl FnOnce(&mut LidarConfig),
    ) -> (LidarConfig, Vec<&'static str>) {
        let mut config = LidarConfig {
            kind: SensorKind::Planar,
            ..LidarConfig::default()
        };
        edit(&mut config);
        let keys: Vec<String> = keys.iter().map(|k| (*k).to_owned()).collect();
        let problems = config.resolve_kind(&keys);
        (config, problems.into_iter().map(|(k, _)| k).collect())
    }

    #[test]
    fn a_bare_planar_table_resolves_to_a_sick_lms291_like_scanner() {
        let (config, problems) = planar(&["kind"], |_| {});
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!((config.fov_deg, config.beams), (Some(180.0), Some(181)));
        assert_eq!(
            (config.channels, config.azimuth_steps, config.blocks),
            (1, 181, 1)
        );
        assert_eq!((config.max_range_m, config.mount_height_m), (80.0, 0.5));
        assert!(!config.rolling_shutter);
        assert!(config.problems().is_empty());
    }

    #[test]
    fn a_spinner_only_field_on_a_planar_scanner_is_a_problem_naming_it() {
        let (_, problems) = planar(&["kind", "channels"], |c| c.channels = 16);
        assert_eq!(problems, ["channels"]);
    }

    #[test]
    fn a_resolved_planar_table_resolves_again_without_problems() {
        let (once, _) = planar(&["kind", "beams"], |c| c.beams = Some(70));
        let mut again = once.clone();
        let every_key: Vec<String> = [
            "kind",
            "channels",
            "upper_deg",
            "lower_deg",
            "spacing",
            "azimuth_steps",
            "rolling_shutter",
            "blocks",
            "fov_deg",
            "beams",
            "max_range_m",
            "mount_height_m",
        ]
        .iter()
        .map(|k| (*k).to_owned())
        .collect();
        assert!(again.resolve_kind(&every_key).is_empty());
        assert_eq!(again, once);
    }

    #[test]
    fn planar_fields_on_a_spinning_lidar_are_a_problem() {
        let mut config = LidarConfig {
            beams: Some(70),
            ..LidarConfig::default()
        };
        let problems = config.resolve_kind(&["beams".to_owned()]);
        assert_eq!(problems.len(), 1);
        assert_eq!(problems[0].0, "beams");
    }
}
