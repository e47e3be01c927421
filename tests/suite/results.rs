//! The shipped `results/` are what the code gives today: the cheap parts are regenerated here
//! exactly as `results/regenerate.sh` makes them (same commands, same relative paths, run from
//! the project's root) into a scratch folder and compared byte for byte with the committed
//! files. A difference fails with the file's name and the command that brings `results/` up to
//! date: `bash results/regenerate.sh`.
//!
//! Regenerated: the CI gate's study (`results/ci-bias.csv`), the reports of the three shipped
//! study CSVs (`results/*/index.html` and their figures) and README's worked diagnosis
//! (`results/worked-example/`: the simulated test, the text and JSON reports, the plots).
//! Not regenerated: the paper-case studies' CSVs (the main job; their reports are checked
//! against them) and `results/unesp-bert/` (it needs the data outside the project).

use std::path::{Path, PathBuf};

use crate::common::scratch;

/// The project's root, where `results/regenerate.sh` runs.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs jointid from the project's root, as the script does, with the arguments of `line`
/// (the script's own words, split at blanks) and then `more`; asserts that it succeeded.
fn run(line: &str, more: &[&str]) -> Vec<u8> {
    let args: Vec<&str> = line
        .split_whitespace()
        .chain(more.iter().copied())
        .collect();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointid"))
        .current_dir(root())
        .args(&args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "jointid {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// A path as an argument.
fn arg(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// Every file of `dir`, by name (the figures and pages are flat folders).
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `made` has the bytes of the committed `shipped` (relative to the root).
fn assert_same(made: &[u8], shipped: &str) {
    let committed = std::fs::read(root().join(shipped))
        .unwrap_or_else(|e| panic!("{shipped}: {e}; run `bash results/regenerate.sh`"));
    assert!(
        made == committed.as_slice(),
        "{shipped} is stale: the code makes another file today; run `bash results/regenerate.sh` and commit results/"
    );
}

/// The folder `made` has the files of the committed folder `shipped`, each the same bytes.
fn assert_same_folder(made: &Path, shipped: &str) {
    assert_eq!(
        files(made),
        files(&root().join(shipped)),
        "{shipped}: other files than the code makes today; run `bash results/regenerate.sh`"
    );
    for name in files(made) {
        assert_same(
            &std::fs::read(made.join(&name)).unwrap(),
            &format!("{shipped}/{name}"),
        );
    }
}

#[test]
fn the_ci_bias_study_and_every_study_report_are_current() {
    let dir = scratch("results", "studies");
    let csv = dir.join("ci-bias.csv");
    run("study studies/ci-bias.toml --quiet --out", &[arg(&csv)]);
    assert_same(&std::fs::read(&csv).unwrap(), "results/ci-bias.csv");
    for (name, title) in [
        ("paper-case-1", "Paper case I"),
        ("paper-case-2", "Paper case II"),
        ("ci-bias", "CI bias gate"),
    ] {
        let out = dir.join(name);
        let source = format!("results/{name}.csv");
        run("report", &[&source, "--out", arg(&out), "--title", title]);
        assert_same_folder(&out, &format!("results/{name}"));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_worked_diagnosis_is_current() {
    let dir = scratch("results", "worked");
    let test = dir.join("test.csv");
    run(
        "simulate --model models/paper-case-1.toml --effect joint_mass=0.05 --modes 6 \
         --frequency-noise 0.001 --shape-noise 0.02 --measure w --seed 1 --out",
        &[arg(&test)],
    );
    assert_same(
        &std::fs::read(&test).unwrap(),
        "results/worked-example/test.csv",
    );
    // Diagnosed from the committed copy, by its relative path as the script gives it (the
    // page's title names it).
    let (json, plots) = (dir.join("report.json"), dir.join("plots"));
    let text = run(
        "diagnose --model models/paper-case-1.toml --measured results/worked-example/test.csv \
         --frequency-noise 0.001 --shape-noise 0.02",
        &["--json", arg(&json), "--plots", arg(&plots)],
    );
    assert_same(&text, "results/worked-example/report.txt");
    assert_same(
        &std::fs::read(&json).unwrap(),
        "results/worked-example/report.json",
    );
    assert_same_folder(&plots, "results/worked-example/plots");
    std::fs::remove_dir_all(&dir).unwrap();
}
