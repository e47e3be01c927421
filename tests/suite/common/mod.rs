//! Models and helpers shared by the integration tests.
#![allow(dead_code)]

pub mod continuous;
pub mod frf;

use std::path::{Path, PathBuf};

use jointid::structure::{Observation, Structure};

#[allow(unused_imports)]
pub use jointid::model::fixtures::{paper_chain, paper_model, steel_bar};

/// Every DOF of a model, as measured points.
pub fn all_dofs(model: &Structure) -> Vec<Observation> {
    (0..model.dof_count())
        .map(|d| Observation::dof(&model.dofs, d))
        .collect()
}

/// The translations only (rotations unmeasured).
pub fn translations(model: &Structure) -> Vec<Observation> {
    all_dofs(model)
        .into_iter()
        .filter(|p| !p.direction.is_rotation())
        .collect()
}

/// Runs the binary and asserts that it succeeded, showing its stderr when not.
pub fn jointid_ok(args: &[&str]) -> std::process::Output {
    let out = jointid(args);
    assert!(
        out.status.success(),
        "jointid {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// A fresh scratch directory for one test.
pub fn scratch(prefix: &str, name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("jointid-{prefix}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the binary.
pub fn jointid(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_jointid"))
        .args(args)
        .output()
        .unwrap()
}

/// Runs the binary with its stdout on /dev/full, where every write fails (no space left), and
/// asserts that the run ends as on any other error: exit 2, the cause said, no panic. Returns
/// the run's stderr; None, saying so, where the device is absent.
pub fn stdout_refused(args: &[&str]) -> Option<String> {
    let Ok(full) = std::fs::File::create("/dev/full") else {
        eprintln!("skipped: /dev/full is absent");
        return None;
    };
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointid"))
        .args(args)
        .stdout(std::process::Stdio::from(full))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(
        err.contains("error: stdout: cannot write"),
        "{args:?}: {err}"
    );
    Some(err)
}

/// The UNESP-BERT data folder (`../shared/data/unesp-bert`), or None, saying so, where it is
/// absent (the data are never copied into the project).
pub fn unesp_dir() -> Option<std::path::PathBuf> {
    let dir =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/data/unesp-bert");
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!(
            "skipped: {} is absent (UNESP-BERT data not shared here)",
            dir.display()
        );
        None
    }
}

/// A JSON number, or a panic naming what was there instead.
pub fn number(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The `mode` number of every entry of the JSON array `v` (a report's `left_out`, or
/// `remaining.modes`).
pub fn mode_numbers(v: &serde_json::Value) -> Vec<u64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|m| m["mode"].as_u64().unwrap())
        .collect()
}

/// Every number anywhere in `v` is finite (JSON has no NaN or infinity: they would come out
/// as null or be missing, which [`number`] refuses where a value is required).
pub fn assert_finite(v: &serde_json::Value, path: &str) {
    use serde_json::Value;
    match v {
        Value::Number(n) => assert!(n.as_f64().is_some_and(f64::is_finite), "{path}: {n}"),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, x)| assert_finite(x, &format!("{path}[{i}]"))),
        Value::Object(o) => o
            .iter()
            .for_each(|(k, x)| assert_finite(x, &format!("{path}.{k}"))),
        _ => {}
    }
}

/// Every `parameters[i].value` of a report's JSON is positive and finite, and lies within a
/// factor 10^3 of `nominals[i]` unless the report marks it at a limit (`limit`: the data cannot
/// tell it from rigid or free).
pub fn assert_within_fit_range(parameters: &serde_json::Value, nominals: &[f64], label: &str) {
    let range = 1e3;
    for (p, nominal) in parameters.as_array().unwrap().iter().zip(nominals) {
        let v = number(&p["value"]);
        assert!(v.is_finite() && v > 0.0, "{label}: {p}");
        if p.get("limit").is_none() {
            assert!(v > nominal / range && v < nominal * range, "{label}: {p}");
        }
    }
}

/// The CI study (`studies/ci-bias.toml`) written as `dir/file`: `trials` trials per cell, its
/// model by absolute path, named `name`, its result CSV `csv` (relative to `dir`).
pub fn ci_study(dir: &Path, file: &str, name: &str, csv: &str, trials: usize) -> PathBuf {
    let model = std::path::absolute("models/paper-case-1.toml").unwrap();
    let text = std::fs::read_to_string("studies/ci-bias.toml")
        .unwrap()
        .replace("name = \"ci-bias\"", &format!("name = {name:?}"))
        .replace("trials = 50000", &format!("trials = {trials}"))
        .replace("\"../models/paper-case-1.toml\"", &format!("{model:?}"))
        .replace("\"../results/ci-bias.csv\"", &format!("{csv:?}"));
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    path
}

/// The names in `dir`, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Runs the binary with `args`, expects exit 2 with every one of `needles` in its error, and
/// returns the error.
pub fn refused(args: &[&str], needles: &[&str]) -> String {
    let o = jointid(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "`{n}` not in: {err}");
    }
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// `path` as UTF-8.
pub fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}
