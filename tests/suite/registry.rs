//! The registries are the one list of what a user can name: the candidate table of
//! docs/diagnosis.md is generated from them (this test fails when that copy is stale; `JOINTID_BLESS=1 cargo
//! test --test suite registry::` rewrites it), names are unique, and the command line accepts exactly
//! the registered names.

use jointid::diagnose::{Tier, catalogue, registry};
use jointid::output::catalogue::markdown;
use jointid::simulate::{NOT_EFFECTS, effect_catalogue};

const BEGIN: &str = "<!-- registry:begin -->\n";
const END: &str = "<!-- registry:end -->";

#[test]
fn the_documented_candidate_table_is_the_registry() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/diagnosis.md");
    let readme = std::fs::read_to_string(&path).expect("docs/diagnosis.md");
    let start = readme
        .find(BEGIN)
        .expect("docs/diagnosis.md has the registry:begin marker")
        + BEGIN.len();
    let end = readme[start..]
        .find(END)
        .expect("docs/diagnosis.md has the registry:end marker")
        + start;
    let table = markdown(&catalogue(&NOT_EFFECTS));
    if readme[start..end] != table {
        if std::env::var_os("JOINTID_BLESS").is_some() {
            let blessed = format!("{}{table}{}", &readme[..start], &readme[end..]);
            std::fs::write(&path, blessed).expect("docs/diagnosis.md written");
        } else {
            panic!(
                "the candidate table of docs/diagnosis.md disagrees with the registry; rewrite it with JOINTID_BLESS=1 cargo test --test suite registry::, or paste:\n{table}"
            );
        }
    }
}

#[test]
fn names_are_unique_and_every_effect_is_simulated_or_searched() {
    let entries = catalogue(&NOT_EFFECTS);
    let mut names: Vec<&str> = entries.iter().map(|e| e.name).collect();
    names.sort_unstable();
    let count = names.len();
    names.dedup();
    assert_eq!(names.len(), count, "a name is registered twice");
    // simulate accepts every registered effect and nothing else.
    let simulated: Vec<String> = effect_catalogue().into_iter().map(|(n, _)| n).collect();
    let expected: Vec<&str> = entries
        .iter()
        .filter(|e| e.simulate)
        .map(|e| e.name)
        .collect();
    let mut sorted: Vec<&str> = simulated.iter().map(String::as_str).collect();
    sorted.sort_unstable();
    let mut expected_sorted = expected.clone();
    expected_sorted.sort_unstable();
    assert_eq!(sorted, expected_sorted);
    // Every candidate is searched by default or with --extended; outside effects only simulate.
    for c in registry() {
        assert_ne!(c.tier(), Tier::Outside, "{}", c.name());
    }
    for e in entries.iter().filter(|e| e.tier == Tier::Outside) {
        assert!(e.simulate, "{} is neither searched nor simulated", e.name);
    }
}

#[test]
fn the_command_line_lists_the_registered_names() {
    let help = |command: &str| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointid"))
            .args([command, "--help"])
            .output()
            .expect("jointid runs");
        String::from_utf8(out.stdout).expect("utf-8")
    };
    let simulate = help("simulate");
    for (name, _) in effect_catalogue() {
        assert!(simulate.contains(&name), "simulate --help lacks {name}");
    }
    let diagnose = help("diagnose");
    for c in registry().iter().filter(|c| c.tier() == Tier::Extended) {
        assert!(
            diagnose.contains(c.name()),
            "diagnose --help lacks {}",
            c.name()
        );
    }
}
