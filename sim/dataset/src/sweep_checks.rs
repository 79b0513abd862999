//! Cross-checks of one sweep's files: the object truth against the per-point labels. A reader
//! that skipped them would train on fewer samples or score a smaller target without a word.

use std::path::Path;

use crate::{ObjectTruth, PointLabel};

/// Checks the objects of a sweep (ids unique and not 0, values finite) and that they agree with
/// the labels read from `labels_path`: every instance id in the labels names an object, and each
/// object's `point_count` is the number of points labelled with its id. Returns the first problem.
pub(crate) fn check_objects(
    objects: &[ObjectTruth],
    labels: &[PointLabel],
    labels_path: &Path,
) -> Result<(), String> {
    if let Some(reason) = objects.iter().find_map(ObjectTruth::problem) {
        return Err(reason);
    }
    let mut ids: Vec<u16> = objects.iter().map(|o| o.id).collect();
    ids.sort_unstable();
    if let Some(w) = ids.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!("two objects have id {}", w[0]));
    }
    let max_id = ids.last().copied().unwrap_or(0);
    let mut counts = vec![0u32; usize::from(max_id) + 1];
    let mut object_of_id: Vec<Option<&ObjectTruth>> = vec![None; counts.len()];
    for o in objects {
        object_of_id[usize::from(o.id)] = Some(o);
    }
    let labels_name = labels_path.display();
    for label in labels {
        let id = label.instance();
        match counts.get_mut(usize::from(id)) {
            Some(count) => *count += 1,
            None => return Err(unknown_instance(labels, id, &labels_name.to_string())),
        }
    }
    // Instance 0 is the static world; ids below the largest may still name no object.
    for (id, (&count, object)) in counts.iter().zip(&object_of_id).enumerate().skip(1) {
        match object {
            None if count > 0 => {
                return Err(unknown_instance(
                    labels,
                    id as u16,
                    &labels_name.to_string(),
                ));
            }
            Some(o) if o.point_count != count => {
                return Err(format!(
                    "object {} ({:?}) has point_count {}, but {labels_name} labels {count} points with its id",
                    o.id, o.name, o.point_count
                ));
            }
            _ => {}
        }
    }
    Ok(())
}

fn unknown_instance(labels: &[PointLabel], id: u16, labels_name: &str) -> String {
    let points = labels.iter().filter(|l| l.instance() == id).count();
    format!("{labels_name} labels {points} points with instance {id}, but no object has that id")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ActorClass, SemanticClass};

    fn object(id: u16, point_count: u32) -> ObjectTruth {
        ObjectTruth {
            id,
            name: format!("actor{id}"),
            class: ActorClass::Car,
            target: false,
            moving: true,
            centre_m: [1.0, 2.0, 0.7],
            size_m: [4.5, 1.8, 1.4],
            yaw_rad: 0.1,
            velocity_mps: [3.0, 0.0, 0.0],
            speed_mps: 3.0,
            heading_rad: 0.0,
            yaw_rate_radps: 0.0,
            point_count,
        }
    }

    fn labels(instances: &[u16]) -> Vec<PointLabel> {
        instances
            .iter()
            .map(|&i| match i {
                0 => PointLabel::new(SemanticClass::Road, 0),
                _ => PointLabel::new(SemanticClass::MovingCar, i),
            })
            .collect()
    }

    fn check(objects: &[ObjectTruth], instances: &[u16]) -> Result<(), String> {
        check_objects(
            objects,
            &labels(instances),
            Path::new("labels/000003.label"),
        )
    }

    #[test]
    fn labels_and_objects_that_agree_pass() {
        assert!(check(&[object(1, 2), object(3, 0)], &[0, 1, 1, 0]).is_ok());
    }

    #[test]
    fn labelled_points_with_no_objects_at_all_are_refused() {
        let err = check(&[], &[0, 2, 2]).unwrap_err();
        assert!(
            err.contains("2 points with instance 2") && err.contains("000003.label"),
            "{err}"
        );
    }

    #[test]
    fn an_instance_below_the_largest_id_without_an_object_is_refused() {
        let err = check(&[object(4, 0)], &[2]).unwrap_err();
        assert!(err.contains("instance 2"), "{err}");
    }

    #[test]
    fn a_point_count_that_differs_from_the_labels_is_refused() {
        let err = check(&[object(1, 5)], &[1, 1]).unwrap_err();
        assert!(
            err.contains("point_count 5") && err.contains("labels 2 points"),
            "{err}"
        );
    }

    #[test]
    fn duplicate_and_zero_ids_are_refused() {
        assert!(check(&[object(1, 0), object(1, 0)], &[]).is_err());
        assert!(check(&[object(0, 0)], &[]).is_err());
    }

    #[test]
    fn a_non_finite_object_value_is_refused() {
        let mut o = object(1, 0);
        o.speed_mps = f64::NAN;
        assert!(check(&[o], &[]).is_err());
    }
}
