//! The layered lap from the command line: the independent 2D half-lap specimen
//! (`tests/fixtures/lap2d/`, made by `bench/lap2d/` with plane-stress solids and interface
//! springs, nothing of jointid) diagnosed from the user's point-joint model with the overlap
//! given; and bad overlaps refused with exit code 2, nothing written.
//!
//! Independence: the data come from `bench/lap2d/fe2d.py`, a plane-stress finite-element model
//! in numpy/scipy (8-node quadrilaterals through the height, zero-thickness interface elements
//! of normal and tangential stiffness per area, the overlap's ends free faces, bolts as stiffer
//! interface patches and point masses), with numpy's seeded gaussian noise; the model the
//! diagnosis sees is the one a user writes first (two beams of the full section, a point
//! joint, the bolts as point masses) with the overlap's length given.

use crate::common::{jointid, jointid_ok, number, s, scratch};
use serde_json::Value;

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/lap2d");

/// The fixture's model file with the overlap (0.12 m, a half-lap) given at its joint, the
/// overlap's length written as `length`.
fn with_overlap(case: &str, length: &str) -> String {
    let text = std::fs::read_to_string(format!("{FIXTURES}/{case}/model.toml")).unwrap();
    text.replacen(
        "k2 = 1.0e3\n",
        &format!("k2 = 1.0e3\n[joint.lap]\nlength = {length}\nlayers = \"half\"\n"),
        1,
    )
}

/// `jointid diagnose` of fixture `case` with the half-lap overlap of 0.12 m given and the
/// noise options `noise`: its terminal output and its JSON report.
fn diagnosed(case: &str, noise: &[&str]) -> (String, Value) {
    let dir = scratch("layered-lap", case);
    let model = dir.join("model.toml");
    std::fs::write(&model, with_overlap(case, "0.12")).unwrap();
    let json = dir.join("report.json");
    let measured = format!("{FIXTURES}/{case}/measured.csv");
    let mut args = vec!["diagnose", "--model", s(&model), "--measured", &measured];
    args.extend_from_slice(noise);
    args.extend(["--json", s(&json)]);
    let out = jointid_ok(&args);
    let report = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    (String::from_utf8_lossy(&out.stdout).into_owned(), report)
}

/// The layered lap's row of a report's candidates.
fn layered_lap(report: &Value) -> &Value {
    report["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "layered_lap")
        .expect("the layered lap is tried")
}

/// The uniform interface (k_n b = 2.5e9, k_t b = 5e8 N/m per m in the 2D model): the layered
/// lap takes chi^2 from 22600 (point joint) to about 23 on 15 degrees of freedom and finds
/// k_s within 3 standard errors of the 2D model's k_t b. Its k_n (1.2e9 +- 0.3e9) is below
/// the 2D model's 2.5e9: the layers are Euler-Bernoulli beams, the 2D solids also shear
/// (checked here to stay below the truth, not asserted equal).
#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn the_independent_half_lap_is_fitted_by_the_layered_lap() {
    let (_, report) = diagnosed("uniform", &["--shape-noise", "0.01"]);
    let lap = layered_lap(&report);
    let chi2 = number(&lap["chi2"]);
    let before = number(&report["before"]["chi2"]);
    assert!(chi2 < 50.0 && before > 1e4, "chi^2 {before} -> {chi2}");
    let p = &lap["parameters"];
    let (k_s, se) = (number(&p[1]["value"]), number(&p[1]["se"]));
    assert_eq!(p[1]["name"], "k_s");
    assert!((k_s - 5e8).abs() < 3.0 * se, "k_s {k_s:e} +- {se:e}");
    assert!(number(&p[0]["value"]) < 2.5e9);
}

/// The test: the bolted lap (three bolts, 0.1% frequency noise, three sensors, six
/// modes). The calibrated point joint leaves 7% RMS; the diagnosis names the layered lap (k_n,
/// k_s and the notched roots' k_r fitted) and its frequency RMS error after is within 1%
/// (0.07%); the table of before and after is printed.
#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn the_bolted_lap_is_named_and_closes_the_loop() {
    let (out, report) = diagnosed(
        "bolted",
        &["--frequency-noise", "0.001", "--shape-noise", "0.01"],
    );
    eprintln!("{}", out.lines().take(14).collect::<Vec<_>>().join("\n"));
    assert!(out.starts_with("verdict: effect: layered_lap\n"), "{out}");
    for row in ["joint calibrated", "after"] {
        assert!(
            out.lines().any(|l| l.trim_start().starts_with(row)),
            "{row}"
        );
    }
    let (before, after) = (
        number(&report["before"]["frequency_rms_pct"]),
        number(&report["after"]["frequency_rms_pct"]),
    );
    assert!(before > 3.0, "the point joint leaves {before}%");
    assert!(after <= 1.0, "the layered lap leaves {after}%");
    let lap = layered_lap(&report);
    let names: Vec<&str> = lap["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["k_n", "k_s", "k_r"]);
}

#[test]
fn overlaps_longer_than_the_beams_shorter_than_the_mesh_resolves_or_not_positive_are_refused() {
    let dir = scratch("layered-lap", "bad");
    let measured = format!("{FIXTURES}/uniform/measured.csv");
    for (length, message) in [
        (
            "0.9",
            "joint[0].lap.length = 0.9 is invalid: a centred overlap reaches half its length into each beam: at most twice the shorter of beam[0] (0.35 m) and beam[1] (0.35 m), 0.7 m",
        ),
        (
            "-0.1",
            "joint[0].lap.length = -0.1 is invalid: it must be finite and > 0 (m)",
        ),
        (
            "0",
            "joint[0].lap.length = 0 is invalid: it must be finite and > 0 (m)",
        ),
        (
            // Shorter than the mesh resolves (1e-9 of the chain's 0.7 m): the notched
            // layers' roots would merge into the joint's node.
            "1e-12",
            "joint[0].lap.length = 1e-12 is invalid: the mesh tells abscissae apart to 1e-9 of the chain's length (0.7 m): the overlap must be longer than 2.8e-9 m",
        ),
    ] {
        let model = dir.join("model.toml");
        std::fs::write(&model, with_overlap("uniform", length)).unwrap();
        let json = dir.join("report.json");
        let out = jointid(&[
            "diagnose",
            "--model",
            s(&model),
            "--measured",
            &measured,
            "--json",
            s(&json),
        ]);
        assert_eq!(out.status.code(), Some(2), "{length}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains(&format!("{}: {message}", model.display())),
            "{stderr}"
        );
        assert!(!json.exists(), "nothing is written");
    }
}

/// The diagnosis of a sparse model (the 284-DOF chain, its layered lap more) is the same to
/// the bit on one, two and three threads, terminal output and JSON report: its candidates are
/// fitted in parallel, and its eigensolutions and eigenpair derivatives split their work into
/// blocks that do not depend on the number of threads.
#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn the_diagnosis_is_the_same_on_any_number_of_threads() {
    let dir = scratch("layered-lap", "threads");
    let model = dir.join("model.toml");
    std::fs::write(&model, with_overlap("uniform", "0.12")).unwrap();
    let measured = format!("{FIXTURES}/uniform/measured.csv");
    let run = |threads: &str| {
        let json = dir.join(format!("report-{threads}.json"));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_jointid"))
            .env("RAYON_NUM_THREADS", threads)
            .args(["diagnose", "--model", s(&model), "--measured", &measured])
            .args(["--shape-noise", "0.01", "--json", s(&json)])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (out.stdout, std::fs::read(&json).unwrap())
    };
    let one = run("1");
    for threads in ["2", "3"] {
        assert!(run(threads) == one, "{threads} threads differ from one");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A lapped chain whose overlap the user guessed otherwise than the specimen's, diagnosed with
/// `--extended`: the search of the local candidates (a stiffness of one element, a region at
/// the joint) took the point joint's k2 to 4e158, where the eigensolver's Lanczos vectors went
/// dependent and its refinement indexed a column that did not exist (exit 101). The joints are
/// now held between free and rigid; the diagnosis ends with a verdict. (The data are the
/// chain's own lap of 0.08 m, `jointid simulate`: this tests the search, not the physics.)
#[test]
#[ignore = "a lapped 5 mm chain searched with --extended: 14 s in release, .ci/run runs it there"]
fn a_lapped_chain_diagnosed_with_extended_candidates_ends_with_a_verdict() {
    let dir = scratch("layered-lap", "extended");
    let chain = |joint: &str, lap: &str| {
        let beam = "[[beam]]\nlength = 0.6\nelements = 120\nyoungs_modulus = 7.0e10\ndensity = 2700.0\narea = 1.5e-4\nsecond_moment = 4.5e-10\n";
        let sensors = "[[sensor]]\nx = 0.0\nlabel = \"a1\"\n[[sensor]]\nx = 0.444\nlabel = \"a2\"\n[[sensor]]\nx = 1.2\nlabel = \"a3\"\n";
        format!("{beam}{beam}[[joint]]\n{joint}[joint.lap]\n{lap}{sensors}")
    };
    let truth = dir.join("truth.toml");
    let model = dir.join("model.toml");
    std::fs::write(
        &truth,
        chain(
            "kind = \"lap\"\n",
            "length = 0.08\nk_n = 1.0e10\nk_s = 1.0e8\n",
        ),
    )
    .unwrap();
    std::fs::write(
        &model,
        chain(
            "k1 = 1.0e9\nk2 = 1.0e5\n",
            "length = 0.12\nlayers = \"half\"\n",
        ),
    )
    .unwrap();
    let measured = dir.join("measured.csv");
    jointid_ok(&[
        "simulate",
        "--model",
        s(&truth),
        "--modes",
        "6",
        "--measure",
        "sensors",
        "--shape-noise",
        "0.01",
        "--frequency-noise",
        "0.001",
        "--seed",
        "1",
        "--out",
        s(&measured),
    ]);
    let json = dir.join("report.json");
    jointid_ok(&[
        "diagnose",
        "--model",
        s(&model),
        "--measured",
        s(&measured),
        "--frequency-noise",
        "0.002",
        "--shape-noise",
        "0.05",
        "--extended",
        "--quiet",
        "--json",
        s(&json),
    ]);
    let r: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(r["verdict"].is_string(), "{r}");
    // Every joint parameter of every model within its range: finite, positive.
    for c in r["candidates"].as_array().unwrap() {
        for p in c["parameters"].as_array().unwrap() {
            assert!(p["value"].as_f64().is_some_and(f64::is_finite), "{p}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
