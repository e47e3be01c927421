//! Property tests of the parsers and the commands on generated inputs: no panic, a rejection
//! is exit 2 with an `error:` line, an accepted input gives only finite numbers, and no file
//! is left behind by a failed run.
//!
//! Inputs are mutations of valid files (a field replaced by a generated value, a line
//! dropped or duplicated, bytes flipped) and generated flag values, made by proptest's
//! strategies, independent of the code under test. `cargo test` runs a bounded number of
//! cases (32 per property); for a long run: `PROPTEST_CASES=5000 cargo test --release --test suite fuzz::`.
//! The security surfaces (cluster scripts, merge, external models, geometry) are in
//! [`security`]; the fourth round's (levels files, lap tables, standard-error columns, solid
//! specimens) in [`surfaces`].

use crate::common;

mod security;
mod surfaces;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use proptest::prelude::*;

use crate::common::{paper_model, scratch};
use jointid::measured::MeasuredModes;

const PAPER: &str = include_str!("../../models/paper-case-1.toml");
const UNESP: &str = include_str!("../../models/unesp-bert.toml");

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|c| c.parse().ok())
        .unwrap_or(32);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Numbers a hostile user types: extremes, signs, non-numbers.
fn wild_number() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("0".to_string()),
        Just("-1".to_string()),
        Just("1e-308".to_string()),
        Just("1e308".to_string()),
        Just("nan".to_string()),
        Just("inf".to_string()),
        Just("\"x\"".to_string()),
        Just("".to_string()),
        Just("18446744073709551615".to_string()),
        (-1e12f64..1e12).prop_map(|v| format!("{v:e}")),
        (0u64..100_000).prop_map(|v| v.to_string()),
    ]
}

/// `text` with the value of one `key = value` line replaced, or a line dropped or doubled.
fn mutate_toml(text: &'static str) -> impl Strategy<Value = String> {
    let lines: Vec<&'static str> = text.lines().collect();
    let count = lines.len();
    (0..count, 0u8..3, wild_number()).prop_map(move |(i, op, value)| {
        let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        match op {
            0 => {
                if let Some((key, _)) = out[i].split_once('=') {
                    out[i] = format!("{key}= {value}");
                }
            }
            1 => {
                out.remove(i);
            }
            _ => {
                let line = out[i].clone();
                out.insert(i, line);
            }
        }
        out.join("\n")
    })
}

/// A valid measured-modes CSV of the paper model (exact modes 1-4, every DOF).
/// Every name `simulate --effect` accepts (from the registries), and one it does not.
fn effect_names() -> Vec<String> {
    jointid::simulate::effect_catalogue()
        .into_iter()
        .map(|(name, _)| name)
        .chain(["bogus".to_string()])
        .collect()
}

fn measured_csv() -> String {
    let model = paper_model(1e7, 1e4);
    let points = common::all_dofs(&model);
    let modal = jointid::modal::ModalSolution::solve(&model.assemble()).unwrap();
    let modes = jointid::simulate::exact_modes(&modal, model.rigid, &[1, 2, 3, 4], &points);
    let mut out = Vec::new();
    modes.write_csv(&mut out, &model).unwrap();
    String::from_utf8(out).unwrap()
}

fn every_value_finite(m: &MeasuredModes) -> bool {
    m.modes().iter().all(|mode| {
        mode.frequency_hz.is_finite()
            && mode.frequency_hz > 0.0
            && mode.values.iter().all(|v| v.is_finite())
    })
}

fn jointid(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_jointid"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Exit 0, or exit 2 with an error line; never a panic.
fn exits_cleanly(out: &Output) -> Result<bool, TestCaseError> {
    let stderr = String::from_utf8_lossy(&out.stderr);
    prop_assert!(!stderr.contains("panicked"), "{}", stderr);
    match out.status.code() {
        Some(0) => Ok(true),
        Some(2) => {
            prop_assert!(stderr.contains("error: "), "{}", stderr);
            Ok(false)
        }
        other => Err(TestCaseError::fail(format!("exit {other:?}: {stderr}"))),
    }
}

/// No NaN or inf in a written CSV.
fn finite_csv(path: &Path) -> Result<(), TestCaseError> {
    let text = std::fs::read_to_string(path).unwrap();
    for line in text.lines().skip(1) {
        for field in line.split(',') {
            let lower = field.to_ascii_lowercase();
            prop_assert!(
                !(lower == "nan" || lower.ends_with("inf")),
                "{} in {}",
                field,
                line
            );
        }
    }
    Ok(())
}

/// An identify run in `dir` on its meas.csv and model.toml: out.csv written with no NaN or
/// inf, or exit 2 with nothing written.
fn identified_or_nothing_written(dir: &Path, out: &Output) -> Result<(), TestCaseError> {
    if exits_cleanly(out)? {
        finite_csv(&dir.join("out.csv"))
    } else {
        prop_assert_eq!(
            names(dir),
            vec!["meas.csv".to_string(), "model.toml".to_string()]
        );
        Ok(())
    }
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn workdir(name: &str) -> PathBuf {
    let dir = scratch("fuzz", name);
    std::fs::write(dir.join("model.toml"), PAPER).unwrap();
    std::fs::write(dir.join("meas.csv"), measured_csv()).unwrap();
    dir
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn model_files_parse_or_are_refused(text in prop_oneof![mutate_toml(PAPER), mutate_toml(UNESP)]) {
        if let Ok(model) = jointid::model::from_toml(&text, Path::new("m.toml")) {
            // An accepted model assembles into finite matrices.
            let mats = model.assemble();
            prop_assert!(mats.k.is_finite() && mats.m.is_finite());
        }
    }

    #[test]
    fn measured_files_parse_or_are_refused(
        line in 1usize..150,
        field in 0usize..5,
        value in wild_number(),
        flip in proptest::option::of((0usize..4000, any::<u8>())),
    ) {
        let model = paper_model(1e7, 1e4);
        let text = measured_csv();
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let i = line.min(lines.len() - 1);
        let mut fields: Vec<String> = lines[i].split(',').map(str::to_string).collect();
        let f = field.min(fields.len() - 1);
        fields[f] = value;
        lines[i] = fields.join(",");
        let mut bytes = lines.join("\n").into_bytes();
        if let Some((at, b)) = flip {
            let at = at % bytes.len();
            bytes[at] = b;
        }
        if let Ok(m) = MeasuredModes::from_reader(&bytes[..], Path::new("m.csv"), &model) {
            prop_assert!(every_value_finite(&m));
        }
    }

    #[test]
    fn universal_files_parse_or_are_refused(
        at in 0usize..3000,
        byte in any::<u8>(),
        cut in proptest::option::of(0usize..3000),
    ) {
        let mut text = format!(
            "    -1\n   151\n{}\n    -1\n    -1\n    15\n         1         0         0         1  0.0000000E+00  0.0000000E+00  0.0000000E+00\n         2         0         0         1  1.0000000E-01  0.0000000E+00  0.0000000E+00\n    -1\n",
            "fuzz"
        )
        .into_bytes();
        let at = at % text.len();
        text[at] = byte;
        if let Some(cut) = cut {
            text.truncate(cut % (text.len() + 1));
        }
        let _ = jointid::uff::read(&text, Path::new("f.uff"));
    }

    #[test]
    fn identify_on_generated_flags(
        n in 0usize..45,
        m in 0usize..45,
        weighting in prop_oneof![Just("equal"), Just("inverse"), Just("inverse-sqrt"), Just("cubic")],
        modes in proptest::collection::vec(0usize..8, 0..4),
        params in prop_oneof![Just(None), Just(Some("k2")), Just(Some("auto")), Just(Some("k9"))],
    ) {
        let dir = workdir("identify");
        let (n, m) = (n.to_string(), m.to_string());
        let mut args = vec![
            "identify", "--model", "model.toml", "--measured", "meas.csv", "--n", &n, "--m", &m,
            "--weighting", weighting, "--out", "out.csv",
        ];
        let list: Vec<String> = modes.iter().map(|m| m.to_string()).collect();
        let list = list.join(",");
        if !modes.is_empty() {
            args.extend(["--modes", &list]);
        }
        if let Some(p) = params {
            args.extend(["--params", p]);
        }
        let out = jointid(&dir, &args);
        identified_or_nothing_written(&dir, &out)?;
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn simulate_on_generated_flags(
        modes in 0usize..40,
        shape in prop_oneof![Just(0.0), Just(1e-160), Just(0.02), Just(0.99), Just(1.5), Just(-0.1)],
        effect in prop_oneof![
            Just(None),
            (prop::sample::select(effect_names()), -2.0f64..2.0).prop_map(Some),
        ],
    ) {
        let dir = workdir("simulate");
        let (modes, shape) = (modes.to_string(), shape.to_string());
        let mut args = vec![
            "simulate", "--model", "model.toml", "--modes", &modes, "--shape-noise", &shape,
            "--out", "out.csv",
        ];
        let effect = effect.map(|(name, size)| format!("{name}={size}"));
        if let Some(e) = &effect {
            args.extend(["--effect", e]);
        }
        let out = jointid(&dir, &args);
        if exits_cleanly(&out)? {
            finite_csv(&dir.join("out.csv"))?;
            // What simulate writes, its own reader accepts.
            let model = jointid::model::from_path(&dir.join("model.toml")).unwrap();
            let read = MeasuredModes::from_path(&dir.join("out.csv"), &model);
            prop_assert!(read.is_ok(), "{:?}", read.err());
        } else {
            prop_assert_eq!(names(&dir), vec!["meas.csv".to_string(), "model.toml".to_string()]);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn study_files_run_or_are_refused(text in mutate_toml(STUDY)) {
        let dir = workdir("study");
        std::fs::write(dir.join("s.toml"), &text).unwrap();
        let out = jointid(&dir, &["study", "s.toml", "--quiet"]);
        if exits_cleanly(&out)? {
            let written: Vec<String> = names(&dir).into_iter().filter(|n| n.ends_with(".csv") && n != "meas.csv").collect();
            for name in written {
                finite_csv(&dir.join(name))?;
            }
        } else {
            prop_assert_eq!(
                names(&dir),
                vec!["meas.csv".to_string(), "model.toml".to_string(), "s.toml".to_string()]
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

const STUDY: &str = "name = \"s\"\nmodel = \"model.toml\"\n[truth]\ndelta = { k1 = 2.0e6, k2 = 2.0e3 }\n[grid]\nmodes = [1, 2]\nn = [10]\nm = [5]\nnf = [0]\nweighting = [\"inverse\"]\nshape_noise = [0.01]\nfrequency_noise = [0.0]\n[monte_carlo]\ntrials = 20\nseed = 1\nnoise = \"uniform\"\n[output]\ncsv = \"out.csv\"\n";
