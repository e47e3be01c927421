//! The layered lap from the command line: the independent 2D half-lap specimen
//! (`tests/fixtures/lap2d/`, made by `bench/lap2d/` with plane-stress solids and interface
//! springs, nothing of jointid) diagnosed from the user's point-joint model with the overlap
//! given; and bad overlaps refused with exit code 2, nothing written.

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

/// The uniform interface (k_n b = 2.5e9, k_t b = 5e8 N/m per m in the 2D model): the layered
/// lap takes chi^2 from 22500 (point joint) to about 27 on 16 degrees of freedom and finds
/// k_s within 3 standard errors of the 2D model's k_t b. Its k_n (6.5e8 +- 0.5e8) is not the
/// 2D model's 2.5e9: the beam layers' k_n also stands for what plane-stress solids do and
/// Euler-Bernoulli layers do not (checked here to stay below the truth, not asserted equal).
#[test]
fn the_independent_half_lap_is_fitted_by_the_layered_lap() {
    let dir = scratch("layered-lap", "lap2d");
    let model = dir.join("model.toml");
    std::fs::write(&model, with_overlap("uniform", "0.12")).unwrap();
    let json = dir.join("report.json");
    let measured = format!("{FIXTURES}/uniform/measured.csv");
    jointid_ok(&[
        "diagnose",
        "--model",
        s(&model),
        "--measured",
        &measured,
        "--shape-noise",
        "0.01",
        "--json",
        s(&json),
    ]);
    let report: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let lap = report["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "layered_lap")
        .expect("the layered lap is tried");
    let chi2 = number(&lap["chi2"]);
    let before = number(&report["before"]["chi2"]);
    assert!(chi2 < 50.0 && before > 1e4, "chi^2 {before} -> {chi2}");
    let p = &lap["parameters"];
    let (k_s, se) = (number(&p[1]["value"]), number(&p[1]["se"]));
    assert_eq!(p[1]["name"], "k_s");
    assert!((k_s - 5e8).abs() < 3.0 * se, "k_s {k_s:e} +- {se:e}");
    assert!(number(&p[0]["value"]) < 2.5e9);
}

#[test]
fn overlaps_longer_than_the_beams_or_not_positive_are_refused() {
    let dir = scratch("layered-lap", "bad");
    let measured = format!("{FIXTURES}/uniform/measured.csv");
    for (length, message) in [
        (
            "0.9",
            "joint[0].lap.length = 0.9 is invalid: the overlap is centred on the joint and reaches half its length into each beam: it must be at most twice the shorter of beam[0] (0.35 m) and beam[1] (0.35 m), 0.7 m",
        ),
        (
            "-0.1",
            "joint[0].lap.length = -0.1 is invalid: it must be finite and > 0 (m)",
        ),
        (
            "0",
            "joint[0].lap.length = 0 is invalid: it must be finite and > 0 (m)",
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
