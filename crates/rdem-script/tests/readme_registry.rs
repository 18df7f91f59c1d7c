//! The command tables of `docs/commands.md` (the reference the README links to) are made
//! from the registries (commands, fix, compute, dump, region and variable styles): this
//! test fails when they differ, so a style added to a registry is documented and no row
//! names a style rdem does not run.
//!
//! After changing a registry row, `RDEM_BLESS=1 cargo test -p rdem-script --test
//! readme_registry` rewrites the tables in docs/commands.md.

use std::path::Path;

const BEGIN: &str = "<!-- command tables: made from the registries";
const END: &str = "<!-- end of the command tables -->";

#[test]
fn readme_tables_are_the_registries() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/commands.md");
    let readme = std::fs::read_to_string(&path).expect("docs/commands.md");
    let b = readme
        .find(BEGIN)
        .expect("docs/commands.md has the begin marker");
    let b = b + readme[b..].find('\n').expect("marker line ends") + 1;
    let e = readme
        .find(END)
        .expect("docs/commands.md has the end marker");
    let want = format!("\n{}", rdem_script::commands::readme_tables());
    if std::env::var_os("RDEM_BLESS").is_some() {
        let new = format!("{}{want}{}", &readme[..b], &readme[e..]);
        std::fs::write(&path, new).expect("write docs/commands.md");
        return;
    }
    let got = &readme[b..e];
    if got != want {
        let first = got
            .lines()
            .zip(want.lines())
            .position(|(g, w)| g != w)
            .unwrap_or(got.lines().count().min(want.lines().count()));
        panic!(
            "the command tables of docs/commands.md differ from the registries at table line {}:\n  docs:     {:?}\n  registry: {:?}\nRun RDEM_BLESS=1 cargo test -p rdem-script --test suite readme_registry",
            first + 1,
            got.lines().nth(first),
            want.lines().nth(first)
        );
    }
}

#[test]
fn every_registry_name_is_unique() {
    use rdem_script::{commands, dumps, fixes};
    let mut all: Vec<Vec<&str>> = vec![
        commands::REGISTRY.rows.iter().map(|r| r.name).collect(),
        fixes::REGISTRY.rows.iter().map(|r| r.name).collect(),
        rdem_script::computes::REGISTRY
            .rows
            .iter()
            .map(|r| r.name)
            .collect(),
        dumps::REGISTRY.rows.iter().map(|r| r.name).collect(),
        commands::region::STYLES
            .rows
            .iter()
            .map(|r| r.name)
            .collect(),
        rdem_script::variables::STYLES
            .rows
            .iter()
            .map(|r| r.name)
            .collect(),
    ];
    for names in &mut all {
        let n = names.len();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), n, "a name is listed twice: {names:?}");
    }
}
