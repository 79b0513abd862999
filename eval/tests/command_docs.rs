//! Every subcommand `patchflow --help` lists is documented on docs/commands.md (its synopsis line
//! and its row of the table of what each is for), so a command cannot be added unseen.

#![allow(clippy::unwrap_used)] // test code: a panic is a failed test with its location

mod common;

use common::{assert_success, patchflow};

/// The subcommands of `patchflow --help`, without `help`.
fn subcommands() -> Vec<String> {
    let output = patchflow(&["--help"]);
    assert_success(&output);
    let text = String::from_utf8(output.stdout).unwrap();
    let listed = text
        .split("Commands:")
        .nth(1)
        .and_then(|rest| rest.split("\n\n").next())
        .unwrap();
    listed
        .lines()
        .filter_map(|line| line.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_owned)
        .collect()
}

#[test]
fn every_subcommand_has_a_synopsis_line_and_a_row_on_the_commands_page() {
    let page = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/commands.md"),
    )
    .unwrap();
    let names = subcommands();
    assert!(names.len() >= 13, "{names:?}");
    for name in names {
        assert!(
            page.contains(&format!("\npatchflow {name} ")),
            "docs/commands.md has no synopsis line for `{name}`"
        );
        assert!(
            page.contains(&format!("| `{name}` |")),
            "docs/commands.md has no row for `{name}`"
        );
    }
}
