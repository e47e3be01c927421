//! SIGINT and SIGTERM at any moment of a run leave no temporary file, no staging folder and
//! no empty folder the run created: each command is interrupted at delays spread over its
//! run time, and what is left is checked after each.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{self, scratch};

/// Every entry under `dir` (recursively), as paths relative to it.
fn entries(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        let name = path
            .strip_prefix(dir)
            .unwrap()
            .to_string_lossy()
            .into_owned();
        if path.is_dir() {
            let inner = entries(&path);
            if inner.is_empty() {
                out.push(format!("{name}/"));
            }
            out.extend(inner.into_iter().map(|i| format!("{name}/{i}")));
        } else {
            out.push(name);
        }
    }
    out
}

/// Runs `args` in `dir` `runs` times, each interrupted by `signal` after a delay spread over
/// `span`; after each, `check` gets the exit code and what the run left (besides `keep`),
/// which is then removed.
fn interrupt(
    dir: &Path,
    args: &[&str],
    signal: &str,
    runs: u32,
    span: Duration,
    keep: &[&str],
    check: impl Fn(Option<i32>, &[String]),
) {
    for run in 0..runs {
        let delay = span * run / runs;
        let mut child = Command::new(env!("CARGO_BIN_EXE_jointid"))
            .args(args)
            .current_dir(dir)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let start = Instant::now();
        while start.elapsed() < delay {
            std::hint::spin_loop();
        }
        let _ = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status();
        let code = child.wait().unwrap().code();
        let left: Vec<String> = entries(dir)
            .into_iter()
            .filter(|e| !keep.contains(&e.as_str()))
            .collect();
        check(code, &left);
        for e in std::fs::read_dir(dir).unwrap() {
            let path = e.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if keep.contains(&name.as_str()) {
                continue;
            }
            if path.is_dir() {
                std::fs::remove_dir_all(&path).unwrap();
            } else {
                std::fs::remove_file(&path).unwrap();
            }
        }
    }
}

/// No temporary (a name starting with `.`) and no empty folder.
fn no_leftovers(code: Option<i32>, left: &[String]) {
    for e in left {
        let hidden = e.split('/').any(|part| part.starts_with('.'));
        assert!(!hidden, "exit {code:?} left the temporary {e}: {left:?}");
        assert!(
            !e.ends_with('/'),
            "exit {code:?} left the empty folder {e}: {left:?}"
        );
    }
}

#[test]
fn an_interrupted_diagnose_leaves_no_temporary_and_no_empty_plots_folder() {
    let dir = scratch("signals", "diagnose");
    let model = std::path::absolute("models/paper-case-1.toml").unwrap();
    let model = model.to_str().unwrap();
    let test = dir.join("test.csv");
    let simulate = format!(
        "simulate --model {model} --effect joint_mass=0.05 --modes 6 --frequency-noise 0.001 \
         --shape-noise 0.02 --measure w --seed 1 --out {}",
        test.display()
    );
    common::jointid_ok(&simulate.split_whitespace().collect::<Vec<_>>());
    let diagnose = format!(
        "diagnose --model {model} --measured test.csv --frequency-noise 0.001 \
         --shape-noise 0.02 --json r.json --plots plots/deep"
    );
    let args: Vec<&str> = diagnose.split_whitespace().collect();
    for signal in ["-INT", "-TERM"] {
        interrupt(
            &dir,
            &args,
            signal,
            40,
            Duration::from_millis(60),
            &["test.csv"],
            no_leftovers,
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_interrupted_export_or_study_leaves_no_staging_folder_and_no_empty_folder() {
    let dir = scratch("signals", "export");
    let model = std::path::absolute("models/paper-case-1.toml").unwrap();
    let model = model.to_str().unwrap();
    let args = ["export", model, "--out", "exported"];
    interrupt(
        &dir,
        &args,
        "-TERM",
        40,
        Duration::from_millis(20),
        &[],
        |code, left| {
            no_leftovers(code, left);
            if code != Some(0) {
                // Exported whole or not at all.
                assert!(
                    left.is_empty() || left.iter().any(|e| e.ends_with("model.toml")),
                    "{left:?}"
                );
            }
        },
    );
    common::ci_study(&dir, "s.toml", "ci-bias", "out/sub/s.csv", 2000);
    let args = ["study", "s.toml", "--quiet", "--trials-csv", "out/t.csv"];
    interrupt(
        &dir,
        &args,
        "-INT",
        20,
        Duration::from_millis(300),
        &["s.toml"],
        no_leftovers,
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_interrupted_report_leaves_its_folder_whole_or_absent() {
    let dir = scratch("signals", "report");
    let results = std::path::absolute("results/ci-bias.csv").unwrap();
    let args = ["report", results.to_str().unwrap(), "--out", "plots/deep"];
    common::jointid_ok(&[&args[..3], &[dir.join("whole").to_str().unwrap()]].concat());
    let whole = entries(&dir.join("whole"));
    std::fs::remove_dir_all(dir.join("whole")).unwrap();
    // Delays spread over the whole run (tens of milliseconds), its figures' writing among them.
    interrupt(
        &dir,
        &args,
        "-TERM",
        60,
        Duration::from_millis(120),
        &[],
        |code, left| {
            no_leftovers(code, left);
            let written: Vec<String> = left
                .iter()
                .filter_map(|e| e.strip_prefix("plots/deep/").map(str::to_string))
                .collect();
            assert!(
                left.is_empty() || written.len() == whole.len(),
                "exit {code:?} left {left:?}"
            );
        },
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
