//! Regressions of the fuzzing findings: every input below once panicked, hung, overwrote an
//! input, left a file behind or printed nonsense with exit 0. Each now ends with exit 2, a
//! message naming the file, field or flag, the value and what is allowed, and nothing
//! written. The inputs are written by hand here (independent of the code under test); the
//! measured file comes from `jointid simulate`, whose own checks are tested elsewhere.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::scratch;

const PAPER: &str = include_str!("../../models/paper-case-1.toml");

const ONE_BEAM: &str = "[[beam]]\nlength = 0.5\nelements = 10\nyoungs_modulus = 2.1e11\ndensity = 7850.0\narea = 2.4e-3\nsecond_moment = 3.2e-7\n";

const STUDY: &str = "name = \"s\"\nmodel = \"model.toml\"\n[truth]\ndelta = { k1 = 2.0e6, k2 = 2.0e3 }\n[grid]\nmodes = [1, 2]\nn = [10]\nm = [5]\nnf = [0]\nweighting = [\"inverse\"]\nshape_noise = [0.01]\nfrequency_noise = [0.0]\n[monte_carlo]\ntrials = 20\nseed = 1\nnoise = \"uniform\"\n[output]\ncsv = \"out.csv\"\n";

fn jointid(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_jointid"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Exit 2, the message in stderr, no panic.
fn refused(out: &Output, message: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(message),
        "expected `{message}` in: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A directory with the paper model, a one-beam model and measured modes of the paper model.
fn setup(name: &str) -> PathBuf {
    let dir = scratch("reliability", name);
    std::fs::write(dir.join("model.toml"), PAPER).unwrap();
    std::fs::write(dir.join("one.toml"), ONE_BEAM).unwrap();
    let out = jointid(
        &dir,
        &[
            "simulate",
            "--model",
            "model.toml",
            "--modes",
            "4",
            "--out",
            "meas.csv",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    dir
}

#[test]
fn a_model_without_parameters_is_refused_by_every_command() {
    let dir = setup("one-beam");
    let out = jointid(
        &dir,
        &[
            "simulate", "--model", "one.toml", "--modes", "3", "--out", "one.csv",
        ],
    );
    assert!(out.status.success());
    refused(
        &jointid(
            &dir,
            &[
                "identify",
                "--model",
                "one.toml",
                "--measured",
                "one.csv",
                "--n",
                "8",
                "--m",
                "4",
                "--weighting",
                "inverse",
            ],
        ),
        "the model identifies no parameter",
    );
    refused(
        &jointid(
            &dir,
            &["diagnose", "--model", "one.toml", "--measured", "one.csv"],
        ),
        "one.csv: the model identifies no joint parameter",
    );
    std::fs::write(dir.join("s.toml"), STUDY.replace("model.toml", "one.toml")).unwrap();
    refused(&jointid(&dir, &["study", "s.toml"]), "s.toml: model = \"");
    assert!(!dir.join("out.csv").exists());
}

#[test]
fn per_mode_settings_that_cannot_hold_a_mode_are_refused_before_the_fit() {
    let dir = setup("per-mode");
    for (n, m, message) in [
        (
            "5",
            "2",
            "mode 4 pairs with basis index 6 (1-based, after 2 rigid-body modes), beyond n = 5",
        ),
        ("0", "0", "n = 0 is invalid: it must be from 3 to 38"),
    ] {
        let args = [
            "diagnose",
            "--model",
            "model.toml",
            "--measured",
            "meas.csv",
            "--n",
            n,
            "--m",
            m,
        ];
        refused(&jointid(&dir, &args), message);
    }
    // Two shape rows on one mode: the default per-mode basis is small; no panic, a report.
    let text = std::fs::read_to_string(dir.join("meas.csv")).unwrap();
    let mut kept = 0;
    let two: String = text
        .lines()
        .filter(|l| {
            if !l.starts_with("2,") {
                return true;
            }
            kept += 1;
            kept <= 2
        })
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(dir.join("two.csv"), two).unwrap();
    let out = jointid(
        &dir,
        &["diagnose", "--model", "model.toml", "--measured", "two.csv"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_mechanism_is_refused_instead_of_zero_frequencies() {
    let dir = setup("mechanism");
    let tiny = PAPER
        .replace("k1 = 1.0e7", "k1 = 1e-308")
        .replace("k2 = 1.0e4", "k2 = 1e-308");
    std::fs::write(dir.join("tiny.toml"), tiny).unwrap();
    let message = "deformable mode 1 has frequency";
    refused(
        &jointid(
            &dir,
            &[
                "simulate",
                "--model",
                "tiny.toml",
                "--modes",
                "4",
                "--out",
                "t.csv",
            ],
        ),
        message,
    );
    refused(
        &jointid(
            &dir,
            &[
                "identify",
                "--model",
                "tiny.toml",
                "--measured",
                "meas.csv",
                "--n",
                "10",
                "--m",
                "5",
                "--weighting",
                "inverse",
            ],
        ),
        message,
    );
    std::fs::write(
        dir.join("s.toml"),
        STUDY.replace("k1 = 2.0e6", "k1 = -9.99999999e6"),
    )
    .unwrap();
    refused(
        &jointid(&dir, &["study", "s.toml"]),
        "the modified (truth.delta) model",
    );
    assert_eq!(
        listing(&dir),
        ["meas.csv", "model.toml", "one.toml", "s.toml", "tiny.toml"]
    );
}

#[test]
fn effect_sizes_outside_their_physical_range_are_refused() {
    let dir = setup("effects");
    for (effect, message) in [
        (
            "element_damage=1.5",
            "element_damage = 1.5 is invalid: the lost fraction of EI is 1.5; it must be from 0 to below 1",
        ),
        (
            "sensor_mass=-0.01",
            "sensor_mass = -0.01 is invalid: sensor_mass.m = ",
        ),
        (
            "suspension=-1",
            "suspension = -1 is invalid: suspension.k = ",
        ),
        ("joint_coupling=1e300", "joint_coupling = 1e300 is invalid"),
    ] {
        refused(
            &jointid(
                &dir,
                &[
                    "simulate",
                    "--model",
                    "model.toml",
                    "--modes",
                    "4",
                    "--effect",
                    effect,
                    "--out",
                    "e.csv",
                ],
            ),
            message,
        );
    }
    assert!(!dir.join("e.csv").exists());
}

#[test]
fn an_output_never_replaces_an_input_or_a_special_file() {
    let dir = setup("outputs");
    let before = std::fs::read(dir.join("model.toml")).unwrap();
    std::fs::create_dir(dir.join("sub")).unwrap();
    refused(
        &jointid(
            &dir,
            &[
                "simulate",
                "--model",
                "model.toml",
                "--modes",
                "4",
                "--out",
                "./sub/../model.toml",
            ],
        ),
        "refused as output: it is the input model.toml",
    );
    refused(
        &jointid(
            &dir,
            &[
                "identify",
                "--model",
                "model.toml",
                "--measured",
                "meas.csv",
                "--n",
                "10",
                "--m",
                "5",
                "--weighting",
                "inverse",
                "--out",
                "meas.csv",
            ],
        ),
        "meas.csv: refused as output: it is the input meas.csv",
    );
    refused(
        &jointid(
            &dir,
            &[
                "diagnose",
                "--model",
                "model.toml",
                "--measured",
                "meas.csv",
                "--json",
                "model.toml",
            ],
        ),
        "model.toml: refused as output: it is the input model.toml",
    );
    std::fs::write(dir.join("s.toml"), STUDY).unwrap();
    refused(
        &jointid(&dir, &["study", "s.toml", "--out", "s.toml"]),
        "it is the input s.toml",
    );
    std::fs::write(
        dir.join("s2.toml"),
        STUDY.replace("csv = \"out.csv\"", "csv = \"s2.toml\""),
    )
    .unwrap();
    refused(
        &jointid(&dir, &["study", "s2.toml"]),
        "s2.toml: refused as output: it is the input s2.toml",
    );
    refused(
        &jointid(
            &dir,
            &["study", "s.toml", "--out", "x.csv", "--trials-csv", "x.csv"],
        ),
        "x.csv and x.csv are the same file",
    );
    std::fs::create_dir(dir.join("adir")).unwrap();
    refused(
        &jointid(
            &dir,
            &[
                "simulate",
                "--model",
                "model.toml",
                "--modes",
                "4",
                "--out",
                "adir",
            ],
        ),
        "adir: refused as output: it exists and is not a regular file",
    );
    if Path::new("/dev/full").exists() {
        refused(
            &jointid(
                &dir,
                &[
                    "simulate",
                    "--model",
                    "model.toml",
                    "--modes",
                    "4",
                    "--out",
                    "/dev/full",
                ],
            ),
            "/dev/full: refused as output: it exists and is not a regular file",
        );
    }
    assert_eq!(std::fs::read(dir.join("model.toml")).unwrap(), before);
    assert_eq!(
        listing(&dir),
        [
            "adir",
            "meas.csv",
            "model.toml",
            "one.toml",
            "s.toml",
            "s2.toml",
            "sub"
        ]
    );
}

#[test]
fn nothing_is_computed_or_left_when_a_run_cannot_finish() {
    let dir = setup("leftovers");
    std::fs::write(dir.join("s.toml"), STUDY).unwrap();
    refused(
        &jointid(&dir, &["check", "s.toml"]),
        "s.toml: there is no [check] table",
    );
    let gated = format!("{STUDY}[check]\nmax_abs_relative_bias = 0.1\n[check.where]\nn = [99]\n");
    std::fs::write(dir.join("g.toml"), gated).unwrap();
    refused(
        &jointid(&dir, &["check", "g.toml"]),
        "g.toml: [check].where selects no (cell, mode, parameter) of the grid",
    );
    // The results cannot be written: the trials CSV, complete by then, is not left either.
    refused(
        &jointid(
            &dir,
            &[
                "study",
                "s.toml",
                "--trials-csv",
                "tr.csv",
                "--out",
                "/proc/self/x/o.csv",
            ],
        ),
        "cannot",
    );
    // The figures cannot be written: the JSON is not left either.
    refused(
        &jointid(
            &dir,
            &[
                "diagnose",
                "--model",
                "model.toml",
                "--measured",
                "meas.csv",
                "--json",
                "d.json",
                "--plots",
                "/proc/self/x",
            ],
        ),
        "/proc/self/x",
    );
    assert_eq!(
        listing(&dir),
        ["g.toml", "meas.csv", "model.toml", "one.toml", "s.toml"]
    );
}

#[test]
fn flags_out_of_range_name_the_flag_and_the_range() {
    let dir = setup("flags");
    std::fs::write(dir.join("s.toml"), STUDY).unwrap();
    refused(
        &jointid(&dir, &["study", "s.toml", "--threads", "100000"]),
        "--threads 100000 is invalid: it must be from 1 to",
    );
    refused(
        &jointid(&dir, &["study", "s.toml", "--threads", "0"]),
        "--threads 0 is invalid",
    );
    refused(
        &jointid(&dir, &["bench", "--trials", "100000000000"]),
        "--trials 100000000000 is invalid: it must be from 1 to 10000000",
    );
    refused(
        &jointid(&dir, &["bench", "--trials", "10", "--repeat", "0"]),
        "--repeat 0 is invalid",
    );
    assert!(!dir.join("out.csv").exists());
}

#[cfg(unix)]
#[test]
fn an_interrupted_study_leaves_no_temporary() {
    let dir = setup("signal");
    std::fs::write(
        dir.join("big.toml"),
        STUDY.replace("trials = 20", "trials = 10000000"),
    )
    .unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_jointid"))
        .current_dir(&dir)
        .args([
            "study",
            "big.toml",
            "--trials-csv",
            "tr.csv",
            "--quiet",
            "--threads",
            "1",
        ])
        .spawn()
        .unwrap();
    // Wait until the temporary of the trials exists, then interrupt.
    let started = std::time::Instant::now();
    while !listing(&dir).iter().any(|n| n.ends_with(".tmp")) {
        assert!(started.elapsed().as_secs() < 120, "no temporary appeared");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(130));
    assert_eq!(
        listing(&dir),
        ["big.toml", "meas.csv", "model.toml", "one.toml"]
    );
}

/// `bench` with its stdout on /dev/full: its figures cannot be printed, an error (exit 2,
/// the cause said), not a panic.
#[test]
fn a_bench_whose_stdout_is_full_exits_2_not_101() {
    crate::common::stdout_refused(&["bench", "--trials", "10", "--repeat", "1"]);
}
