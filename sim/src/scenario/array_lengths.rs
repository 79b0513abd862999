//! Fixed-length arrays of a scenario file checked before they are read: the deserializer would
//! drop the extra elements of `size_m = [1, 2, 3, 4]` or `path_m = [[0, 0, 5], …]` without a
//! word, so a value the user wrote would be silently ignored. Every such array is checked here
//! by key, and the first of the wrong length is reported at its own line.

use toml::de::{DeTable, DeValue};

/// How a key's array is shaped.
#[derive(Debug, Clone, Copy)]
enum Shape {
    /// Exactly this many numbers, e.g. `size_m = [l, w, h]`.
    Flat(usize, &'static str),
    /// A list of arrays of exactly this many numbers each, e.g. `path_m = [[x, y], …]`.
    Nested(usize, &'static str),
}

/// The fixed-length arrays of the scenario format, by key.
const SHAPES: [(&str, Shape); 6] = [
    ("size_m", Shape::Flat(3, "[length, width, height]")),
    ("centre_m", Shape::Flat(2, "[x, y]")),
    ("car_speed_mps", Shape::Flat(2, "[min, max]")),
    ("repeat_to_m", Shape::Flat(2, "[x, y]")),
    ("path_m", Shape::Nested(2, "[x, y]")),
    ("speed_changes", Shape::Nested(2, "[time_secs, speed_mps]")),
];

/// The byte offset and reason of the first array of the wrong length in `text`, if any (text
/// that does not parse is left to the loader's own error).
pub(super) fn array_length_problem(text: &str) -> Option<(usize, String)> {
    let root = DeTable::parse(text).ok()?;
    check_table(root.get_ref())
}

fn check_table(table: &DeTable) -> Option<(usize, String)> {
    for (key, value) in table.iter() {
        let name = key.get_ref().as_ref();
        if let (Some((_, shape)), DeValue::Array(items)) =
            (SHAPES.iter().find(|(k, _)| *k == name), value.get_ref())
        {
            match *shape {
                Shape::Flat(n, form) if items.len() != n => {
                    return Some((
                        value.span().start,
                        format!(
                            "{name} has {} values; it takes exactly {n}: {form}",
                            items.len()
                        ),
                    ));
                }
                Shape::Nested(n, form) => {
                    for (i, item) in items.iter().enumerate() {
                        if let DeValue::Array(inner) = item.get_ref()
                            && inner.len() != n
                        {
                            return Some((
                                item.span().start,
                                format!(
                                    "{name} entry {i} has {} values; each takes exactly {n}: {form}",
                                    inner.len()
                                ),
                            ));
                        }
                    }
                }
                Shape::Flat(..) => {}
            }
        }
        if let Some(found) = check_value(value.get_ref()) {
            return Some(found);
        }
    }
    None
}

fn check_value(value: &DeValue) -> Option<(usize, String)> {
    match value {
        DeValue::Table(t) => check_table(t),
        DeValue::Array(items) => items.iter().find_map(|item| check_value(item.get_ref())),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reason(text: &str) -> String {
        array_length_problem(text)
            .map(|(_, r)| r)
            .unwrap_or_default()
    }

    #[test]
    fn arrays_of_the_wrong_length_are_named_with_what_they_take() {
        let base = "[[actors]]\nspeed_mps = 1.0\n";
        let r = reason(&format!("{base}path_m = [[0, 0, 5], [100, 0, 5]]\n"));
        assert!(r.contains("path_m entry 0 has 3 values"), "{r}");
        let r = reason(&format!(
            "{base}path_m = [[0, 0], [9, 0]]\nsize_m = [1, 2, 3, 4]\n"
        ));
        assert!(r.contains("size_m has 4 values"), "{r}");
        let r = reason(&format!(
            "{base}path_m = [[0, 0], [9, 0]]\nspeed_changes = [[0.1, 1, 5]]\n"
        ));
        assert!(r.contains("speed_changes entry 0 has 3 values"), "{r}");
        assert_eq!(
            reason(&format!(
                "{base}path_m = [[0, 0], [9, 0]]\nsize_m = [1, 2, 3]\n"
            )),
            ""
        );
    }

    #[test]
    fn the_offset_points_at_the_offending_line() {
        let text = "sweeps = 2\n[[actors]]\nsize_m = [1, 2]\n";
        let (offset, _) = array_length_problem(text).unwrap();
        assert_eq!(text[..offset].matches('\n').count() + 1, 3);
    }
}
