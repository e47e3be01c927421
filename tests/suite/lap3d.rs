//! `diagnose` on 3D solid half-laps diagnosed with the 1D model a user writes (the model-form
//! test of the diagnosis): the verdict names the lap, alone or with shear, as `effect` or
//! `partial`, and what remains beyond the noise is said.
//!
//! Independence: every case of `tests/fixtures/lap3d/` was made by `bench/lap3d/generate.py`:
//! 20-node hexahedra and zero-thickness interface elements of its own (`bench/lap3d/fe3d.py`,
//! checked against the exact Timoshenko frequencies of the bar by `bench/lap3d/check_fe3d.py`),
//! numpy's noise (0.1% on the frequencies, 1% of each mode's peak on the shapes). Nothing of
//! jointid made them: the physics (a solid's shear and rotary inertia, the notches' stress
//! field, interfaces tied everywhere, at three bolt patches or glued, a mass on one end, a
//! monolithic bar) is another model class than the 1D chain of the diagnosis, whose model file
//! is what a user writes: two Euler-Bernoulli beams of the full section and `[joint.lap]`
//! (`model.toml`), or the same with Timoshenko beams (`timoshenko.toml`).
//!
//! Each case runs in seconds in release and a minute unoptimised, so the battery is
//! `#[ignore]`d here and run by `.ci/run` in release (`cargo test --release --test suite
//! lap3d -- --ignored --nocapture` prints its table).

use serde_json::Value;

use crate::common::{jointid_ok, mode_numbers, number, scratch};

/// The diagnosis of fixture `case` (tests/fixtures/lap3d/CASE) with the noise it was made with,
/// by the user's Euler-Bernoulli model (`model.toml`).
fn diagnose(case: &str, dir: &std::path::Path) -> Value {
    diagnose_with(case, "model", dir)
}

/// The diagnosis of fixture `case` by its model file `model`.toml.
fn diagnose_with(case: &str, model: &str, dir: &std::path::Path) -> Value {
    run_diagnose(case, model, &[], dir)
}

/// The diagnosis of fixture `case` by its model file `model`.toml with the extended library
/// of candidates (`--extended`).
fn diagnose_extended(case: &str, model: &str, dir: &std::path::Path) -> Value {
    run_diagnose(case, model, &["--extended"], dir)
}

/// `jointid diagnose` on fixture `case` by its model file `model`.toml, with the noise the
/// fixtures were made with and the flags `extra`: its JSON report.
fn run_diagnose(case: &str, model: &str, extra: &[&str], dir: &std::path::Path) -> Value {
    let fixture = format!("tests/fixtures/lap3d/{case}");
    let json = dir.join(format!("{case}-{model}{}.json", extra.concat()));
    let (model_file, measured) = (
        format!("{fixture}/{model}.toml"),
        format!("{fixture}/measured.csv"),
    );
    let mut args = vec![
        "diagnose",
        "--model",
        &model_file,
        "--measured",
        &measured,
        "--frequency-noise",
        "0.001",
        "--shape-noise",
        "0.01",
        "--quiet",
        "--json",
        json.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    jointid_ok(&args);
    serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap()
}

/// The causes the report names.
fn causes(r: &Value) -> Vec<String> {
    r["causes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap().to_string())
        .collect()
}

/// One line of the table the test prints.
fn line(case: &str, r: &Value) -> String {
    format!(
        "{case:14} {:12} {:34} before {:6.2}%  after {:6.2}%",
        r["verdict"].as_str().unwrap(),
        r["selected"].as_str().unwrap_or("-"),
        number(&r["before"]["frequency_rms_pct"]),
        number(&r["after"]["frequency_rms_pct"]),
    )
}

/// The lapped cases: uniform, bolted and glued interfaces at 3 and 9 sensors.
const LAPPED: [&str; 6] = [
    "uniform-3",
    "uniform-9",
    "bolts-3",
    "bolts-9",
    "glued-3",
    "glued-9",
];

/// Asserts that report `r` of `case` names the lap as `effect` or `partial`, alone or with
/// shear; its verdict and causes.
fn lap_named(case: &str, r: &Value) -> (String, Vec<String>) {
    lap_named_with(case, r, &["shear"])
}

/// Asserts that report `r` of `case` names the lap as `effect` or `partial`, alone or with
/// causes among `others`; its verdict and causes.
fn lap_named_with(case: &str, r: &Value, others: &[&str]) -> (String, Vec<String>) {
    let verdict = r["verdict"].as_str().unwrap().to_string();
    assert!(
        verdict == "effect" || verdict == "partial",
        "{case}: {verdict}"
    );
    let named = causes(r);
    assert_eq!(named[0], "layered_lap", "{case}: {named:?}");
    assert!(
        named[1..].iter().all(|c| others.contains(&c.as_str())),
        "{case}: {named:?}"
    );
    (verdict, named)
}

#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn a_solid_lap_is_named_as_a_lap_by_the_users_beam_model() {
    let dir = scratch("lap3d", "laps");
    for case in LAPPED {
        let r = diagnose(case, &dir);
        eprintln!("{}", line(case, &r));
        // The lap, alone or with shear (a glued interface too: a lap at its stiff end, never
        // refused).
        let (verdict, _) = lap_named(case, &r);
        // It removes most of the point joint's frequency error, to within 1%. The bolted lap
        // on nine sensors needs shear beside it (0.46% measured; the lap alone left 1.35%):
        // shear is found there because its flexibility is held non-negative, so its test is
        // one-sided (p = 0.0007, 0.009 after the 12 hypotheses; two-sided it was 0.017).
        let (before, after) = (
            number(&r["before"]["frequency_rms_pct"]),
            number(&r["after"]["frequency_rms_pct"]),
        );
        assert!(after < 0.25 * before, "{case}: {before}% -> {after}%");
        assert!(after <= 1.0, "{case}: after {after}%");
        if verdict == "partial" {
            let remaining = &r["remaining"];
            assert!(number(&remaining["removed"]) > 0.9, "{case}: {remaining}");
            assert!(r["discrepancy"]["frequency"].as_f64().is_some());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The bolted lap of a stubbier specimen (a 25.4 x 19.05 mm section, 0.7112 m long, a 0.12065
/// m overlap: `stubby-bolts-3` and `-9`). Shear is a larger share of what the user's
/// Euler-Bernoulli model misses: the lap alone leaves 2.0% on three sensors, the lap with
/// shear 0.39%. That second cause was not significant while the profile likelihood ratio of
/// six frequencies was read as F on their few degrees of freedom; it is by the classical F
/// statistic (`stats::improvement`). On nine sensors one sits 5 um from the joint, no node of
/// its own (module `mesh`): the model was refused as unsolvable.
#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn a_stubby_bolted_lap_is_named_with_its_shear_by_the_users_beam_model() {
    let dir = scratch("lap3d", "stubby");
    for case in ["stubby-bolts-3", "stubby-bolts-9"] {
        let r = diagnose(case, &dir);
        eprintln!("{}", line(case, &r));
        // Shear beside the lap; on nine sensors a suspension's springs then stand in for the
        // bolts' distribution (as with Timoshenko beams on the fixtures' bolted lap).
        let (_, named) = lap_named_with(case, &r, &["shear", "suspension"]);
        assert_eq!(named[..2], ["layered_lap", "shear"], "{case}");
        assert!(number(&r["after"]["frequency_rms_pct"]) <= 1.0, "{case}");
        let r = diagnose_with(case, "timoshenko", &dir);
        eprintln!("{} (Timoshenko)", line(case, &r));
        lap_named_with(case, &r, &["shear", "suspension"]);
        assert!(number(&r["after"]["frequency_rms_pct"]) <= 1.0, "{case}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A third specimen with a softer interface (`soft-*`: k_n, k_t a tenth of the fixtures').
/// Its lap's fit has several minima along k_s: from the start of least chi^2 with only the
/// shape scales fitted, three bolts on nine sensors ended with 5.3% RMS in the frequencies
/// (k_s a quarter of the interface's), where a start from the bonded side reaches the
/// interface (module `layered_lap`). With the interface uniform, the first mode lies 41%
/// below the user's starting point joint, beyond the pairing's window: it was set aside, and
/// when the calibrated joint paired it again, the sixth mode lost its partner on the way and
/// the first stayed out. The fundamental is kept now, the sixth set aside in its place.
#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn a_softer_interface_and_a_starting_joint_far_off_still_give_the_lap() {
    let dir = scratch("lap3d", "soft");
    let r = diagnose("soft-bolts-9", &dir);
    eprintln!("{}", line("soft-bolts-9", &r));
    lap_named("soft-bolts-9", &r);
    assert!(number(&r["after"]["frequency_rms_pct"]) <= 1.0);
    // The 1D lap's uniform interface stands for three patches: its k_s is the interface's
    // mean over the overlap, 2.286e9 N/m per m (within 4% measured).
    let k_s = after_parameter(&r, "k_s");
    assert!((k_s / 2.286e9 - 1.0).abs() < 0.25, "k_s = {k_s}");
    // With Timoshenko beams the lap alone (4.0% from the best start alone, 0.43% now).
    let r = diagnose_with("soft-bolts-9", "timoshenko", &dir);
    eprintln!("{} (Timoshenko)", line("soft-bolts-9", &r));
    lap_named("soft-bolts-9", &r);
    assert!(number(&r["after"]["frequency_rms_pct"]) <= 1.0);
    let r = diagnose("soft-uniform-6", &dir);
    eprintln!("{}", line("soft-uniform-6", &r));
    let left = mode_numbers(&r["left_out"]);
    // The fundamental is kept; one mode at most is set aside (the sixth, MAC 0.47 with the
    // calibrated point joint).
    assert!(!left.contains(&1) && left.len() <= 1, "{}", r["left_out"]);
    lap_named("soft-uniform-6", &r);
    assert!(number(&r["after"]["frequency_rms_pct"]) <= 1.0);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The soft uniform lap on nine sensors (`soft-uniform-9`): the lap's minimum lies between
/// whole decades of k_s, a third of its natural scale. From starts a decade apart the fit ended
/// at a fifth of the interface's k_s (2.3% RMS left with Euler-Bernoulli beams, 0.88% with
/// Timoshenko's); the half-decade start next to it reaches it (module `layered_lap`).
#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn a_soft_interface_between_the_decades_of_the_starts_is_reached() {
    let dir = scratch("lap3d", "soft-between");
    for model in ["model", "timoshenko"] {
        let r = diagnose_with("soft-uniform-9", model, &dir);
        eprintln!("{} ({model})", line("soft-uniform-9", &r));
        // A joints' coupling stiffness (joint_coupling) may be named beside the lap and shear.
        lap_named_with("soft-uniform-9", &r, &["shear", "joint_coupling"]);
        assert!(number(&r["after"]["frequency_rms_pct"]) <= 1.0);
        // The interface's k_t over the overlap: 2.54e8 N/m per m (within 2% measured).
        let k_s = after_parameter(&r, "k_s");
        assert!((k_s / 2.54e8 - 1.0).abs() < 0.25, "{model}: k_s = {k_s}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn a_monolithic_bar_and_an_unmodelled_end_mass_are_answered_not_refused() {
    let dir = scratch("lap3d", "others");
    for case in ["monolithic-3", "monolithic-9"] {
        let r = diagnose(case, &dir);
        eprintln!("{}", line(case, &r));
        // The bar's only misfit is the user's Euler-Bernoulli beams: none, or shear, or a
        // rigid joint; never an error (the joint runs stiff: a limit, not a refusal).
        let verdict = r["verdict"].as_str().unwrap();
        assert!(
            verdict == "none" || (verdict == "effect" && causes(&r) == ["shear"]),
            "{case}: {verdict} {:?}",
            causes(&r)
        );
        assert!(number(&r["after"]["frequency_rms_pct"]) < 0.2, "{case}");
    }
    for case in ["tipmass-3", "tipmass-9"] {
        let r = diagnose(case, &dir);
        eprintln!("{}", line(case, &r));
        // A 20 g mass on one end that the model lacks: the lap, with a mass at the sensors
        // (the end one among them), and a misfit beyond the noise said to remain: the
        // library's sensor mass loads every sensor alike, so the shapes miss. On three
        // sensors neither the lap nor the mass is significant alone (a frequency-dependent
        // joint mimics both, 0.62% RMS); the pair is (0.13%).
        let verdict = r["verdict"].as_str().unwrap();
        assert_eq!(verdict, "partial", "{case}");
        assert!(r["remaining"].is_object(), "{case}");
        assert_eq!(causes(&r), ["layered_lap", "sensor_mass"], "{case}");
        assert!(number(&r["after"]["frequency_rms_pct"]) < 0.2, "{case}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn with_timoshenko_beams_the_lap_alone_brings_the_frequencies_within_1_percent() {
    let dir = scratch("lap3d", "timoshenko");
    for case in LAPPED {
        let r = diagnose_with(case, "timoshenko", &dir);
        eprintln!("{} (Timoshenko)", line(case, &r));
        // The beams' own shear and rotary inertia declared, the lap is what the data name,
        // alone or with a correction of the declared shear. On nine sensors of the bolted
        // lap the uniform interface of the 1D lap leaves the first mode 1.2% low (the three
        // patches: the noise-free test below), twelve times its noise: a suspension's
        // springs stand in for that (the solid is free), as a second cause.
        let others: &[&str] = if case == "bolts-9" {
            &["shear", "suspension"]
        } else {
            &["shear"]
        };
        lap_named_with(case, &r, others);
        let after = number(&r["after"]["frequency_rms_pct"]);
        // Within 0.5% (0.04-0.37% measured): the 3D lap's axial motion in its sixth mode is
        // the beams' bars' (module `layered` of the chain).
        assert!(after <= 0.5, "{case}: after {after}%");
    }
    for case in ["monolithic-3", "monolithic-9"] {
        let r = diagnose_with(case, "timoshenko", &dir);
        eprintln!("{} (Timoshenko)", line(case, &r));
        let verdict = r["verdict"].as_str().unwrap();
        assert!(
            verdict == "none" || (verdict == "effect" && causes(&r) == ["shear"]),
            "{case}: {verdict} {:?}",
            causes(&r)
        );
        assert!(number(&r["after"]["frequency_rms_pct"]) < 0.2, "{case}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The parameter `name` of the report's after model.
fn after_parameter(r: &Value, name: &str) -> f64 {
    let p = r["after"]["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == name)
        .unwrap_or_else(|| panic!("no {name} in {}", r["after"]["parameters"]));
    number(&p["value"])
}

#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn on_noise_free_data_the_timoshenko_lap_is_the_solid_lap_but_for_the_bolts_distribution() {
    // The exact-* fixtures: the solid's modes without noise, so what the fit leaves is the 1D
    // model's form error alone.
    let dir = scratch("lap3d", "exact");
    for case in ["exact-uniform-9", "exact-glued-9", "exact-bolts-9"] {
        let r = diagnose_with(case, "timoshenko", &dir);
        eprintln!("{} (Timoshenko)", line(case, &r));
        lap_named(case, &r);
        let after = number(&r["after"]["frequency_rms_pct"]);
        let errors: Vec<f64> = r["after"]["modes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| number(&m["frequency_error_pct"]))
            .collect();
        if case == "exact-bolts-9" {
            // Three bolt patches, a uniform interface in the 1D lap: the first mode, whose
            // curvature is largest over the overlap, is where that shows (-1.2%).
            assert!(after <= 1.0, "{case}: after {after}%");
            let worst = (0..errors.len())
                .max_by(|&a, &b| errors[a].abs().total_cmp(&errors[b].abs()))
                .unwrap();
            assert_eq!(worst, 0, "{case}: {errors:?}");
        } else {
            // An interface over the whole overlap, or none (glued): the layered lap is the
            // solid to a tenth of a percent.
            assert!(after <= 0.1, "{case}: after {after}% {errors:?}");
        }
        if case == "exact-uniform-9" {
            // The interface's slip stiffness is the solid's: k_t b = 2.54e9 N/m per m.
            let k_s = after_parameter(&r, "k_s");
            assert!((k_s / 2.54e9 - 1.0).abs() < 0.05, "{case}: k_s {k_s:e}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
#[ignore = "seconds per case in release, a minute unoptimised: .ci/run runs it in release"]
fn with_the_extended_library_the_unmodelled_end_mass_is_named_and_weighed() {
    // The 20 g spread over the end face at x = 0.6 m (the chain's second end), which the
    // model file does not have: the extended library's end masses, with the lap.
    let dir = scratch("lap3d", "extended");
    for case in ["tipmass-3", "tipmass-9"] {
        for model in ["model", "timoshenko"] {
            let r = diagnose_extended(case, model, &dir);
            eprintln!("{} ({model}, --extended)", line(case, &r));
            // With the user's Euler-Bernoulli beams, shear may come third.
            let mut named = causes(&r);
            named.sort();
            let with_shear = model == "model" && named == ["end_mass", "layered_lap", "shear"];
            assert!(
                named == ["end_mass", "layered_lap"] || with_shear,
                "{case} {model}: {named:?}"
            );
            let verdict = r["verdict"].as_str().unwrap();
            assert!(
                verdict == "effect" || verdict == "partial",
                "{case} {model}: {verdict}"
            );
            let mass = after_parameter(&r, "end_mass.end2.m");
            assert!(
                (mass / 0.020 - 1.0).abs() < 0.05,
                "{case} {model}: {mass} kg"
            );
            let other = after_parameter(&r, "end_mass.end1.m");
            assert!(other < 0.002, "{case} {model}: {other} kg at the first end");
            if model == "timoshenko" {
                // The beams' shear declared, the lap and the mass are the whole misfit.
                let after = number(&r["after"]["frequency_rms_pct"]);
                assert!(after <= 0.15, "{case}: after {after}%");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
