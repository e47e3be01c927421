//! `diagnose` on the small independent battery (tests/fixtures/battery): right verdicts per
//! noise situation.
//!
//! Independence: every case (model.toml, measured.csv, truth.json) was made by
//! bench/battery/generate.py, a Python finite-element chain (Hermite beams, a finer mesh for
//! the effect's increment), its own effects (five of jointid's library, four outside it) and
//! its own noise (numpy PCG64 streams: the stated model, an additive floor 10x larger, noise
//! twice and half the stated, Student-t shape noise); none of it reads or calls jointid's
//! `simulate`, its noise code or its effects. Regenerate with
//! `$(bash scripts/python-env.sh) bench/battery/generate.py small`.
//!
//! What a right verdict is: truth.json's `expected.right_verdicts` (bench/battery/run.py's
//! RULES): clean -> `none`; a library effect named (when weak, `none` too); an effect outside
//! the library -> `unexplained` (when weak, `none` too); and, by the mimicry rule, a library
//! effect that the generator's own fit shows reproducing the truth's noise-free data within
//! the detection limit (bench/battery/detect.py, `mimicry`: a lap behind a soft joint spring
//! is, to the data, a joint mass).
//!
//! The goal is >= 90% right in every noise situation and clean `none` >= 95%.
//! Every test here is `#[ignore]`d (tens of seconds to minutes in an unoptimised build):
//! `.ci/run` runs them in release; by hand `cargo test --release --test suite diagnose_battery
//! -- --ignored`.
//! - `clean_and_strong_library_cases_are_right` (20 cases: per situation the 2 clean cases,
//!   the strong joint coupling and the strong joint mass) asserts every verdict right;
//! - `stated_noise_verdicts_are_those_recorded` (the 20 cases of the noise as stated) asserts
//!   every verdict equal to the one recorded in `AS_STATED`, right or wrong: a new default
//!   candidate or a changed rule that moves a verdict fails here, and the change must say why
//!   by updating the table;
//! - `verdicts_per_noise_situation_reach_their_floors` (all 100 cases) asserts the right
//!   verdicts reached today in each situation (`FLOOR`), so that a change which loses right
//!   verdicts fails; raise a floor when the diagnosis
//!   improves. bench/battery/run.sh scores the larger battery.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use jointid::diagnose::{DiagnoseSettings, Noise, PairingRule, Verdict, diagnose};
use jointid::measured::MeasuredModes;

/// Right verdicts required per noise situation (out of the situation's 20 cases): 93 of 100
/// with each model's own discrepancy (before it: 94; half_stated lost one mimic, a lap named
/// a joint mass at half the stated noise, and heavy_tailed two: a weak sensor mass ambiguous
/// with shear, a strong point mass taken for a frequency-dependent joint).
const FLOOR: [(&str, usize); 5] = [
    ("as_stated", 20),
    ("floor_x10", 20),
    ("twice_stated", 20),
    ("half_stated", 15),
    ("heavy_tailed", 18),
];
/// Clean cases (of all situations) required to be `none`.
const CLEAN_FLOOR: usize = 10;
/// The fast test's cases: clean, strong joint coupling, strong joint mass.
const FAST: [&str; 3] = [
    "-clean-none",
    "-joint_coupling-strong",
    "-joint_mass-strong",
];

/// The verdicts of the 20 cases of the noise as stated, as jointid gives them today: all 20
/// right (the laps 014 and 015 are, to the data, joint masses: the generator's own fit shows
/// the mimicry; 012, a weak element damage, is `unexplained`: no candidate is clearly better
/// than the calibrated joint once each carries its own discrepancy; 019, a strong point mass
/// off the joint, is `partial`: a joint mass with a joint coupling removes 92% of the
/// misfit and says what remains, since a second cause is read by the classical F test (it
/// was `unexplained` while the profile likelihood ratio was read as F); 008, a weak
/// suspension, is named since the test of a spring added from zero is one-sided).
const AS_STATED: [(&str, &str); 20] = [
    ("000-as_stated-clean-none", "none"),
    ("001-as_stated-clean-none", "none"),
    ("002-as_stated-joint_coupling-weak", "effect:joint_coupling"),
    (
        "003-as_stated-joint_coupling-strong",
        "effect:joint_coupling",
    ),
    ("004-as_stated-joint_mass-weak", "none"),
    ("005-as_stated-joint_mass-strong", "effect:joint_mass"),
    ("006-as_stated-sensor_mass-weak", "none"),
    ("007-as_stated-sensor_mass-strong", "effect:sensor_mass"),
    ("008-as_stated-suspension-weak", "effect:suspension"),
    ("009-as_stated-suspension-strong", "effect:suspension"),
    ("010-as_stated-shear-weak", "none"),
    ("011-as_stated-shear-strong", "effect:shear"),
    ("012-as_stated-element_damage-weak", "unexplained"),
    ("013-as_stated-element_damage-strong", "unexplained"),
    ("014-as_stated-lap_joint-weak", "effect:joint_mass"),
    ("015-as_stated-lap_joint-strong", "effect:joint_mass"),
    ("016-as_stated-frequency_joint-weak", "none"),
    (
        "017-as_stated-frequency_joint-strong",
        "frequency_dependent",
    ),
    ("018-as_stated-point_mass-weak", "none"),
    (
        "019-as_stated-point_mass-strong",
        "partial:joint_mass + joint_coupling",
    ),
];

fn battery() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/battery")
}

/// `none`, `effect:<name>`, `ambiguous:<contenders>`, `unexplained` or `frequency_dependent`,
/// or `error: ...` when diagnose refuses.
fn verdict_word(case: &Path, truth: &serde_json::Value) -> String {
    verdict_word_with(case, truth, None)
}

/// The generating noise of a situation as the generator's truth.json describes it: relative
/// shape standard deviation, additive floor (fraction of the peak), relative frequency
/// standard deviation (bench/battery/generate.py).
fn generating_noise(situation: &str) -> Option<(f64, f64, f64)> {
    match situation {
        "as_stated" => Some((0.02, 0.02, 0.001)),
        "twice_stated" => Some((0.04, 0.02, 0.002)),
        "half_stated" => Some((0.01, 0.02, 0.0005)),
        "floor_x10" => Some((0.02, 0.2, 0.001)),
        _ => None,
    }
}

/// The measured modes with standard-error columns from the generating noise (s, floor, f):
/// value_std = s sqrt(u^2 + (floor peak)^2), frequency_std = f frequency, as a modal test that
/// reports its own uncertainty would give them.
fn with_standard_errors(measured: &MeasuredModes, (s, floor, f): (f64, f64, f64)) -> MeasuredModes {
    let modes = measured
        .modes()
        .iter()
        .map(|m| {
            let peak = m.peak();
            let mut m = m.clone();
            m.frequency_std = Some(f * m.frequency_hz);
            m.value_std = Some(
                m.values
                    .iter()
                    .map(|u| s * (u * u + (floor * peak).powi(2)).sqrt())
                    .collect(),
            );
            m
        })
        .collect();
    MeasuredModes::new(modes)
}

/// [`verdict_word`], the data carrying standard errors from `noise` when given.
fn verdict_word_with(
    case: &Path,
    truth: &serde_json::Value,
    noise: Option<(f64, f64, f64)>,
) -> String {
    let model = jointid::model::from_path(&case.join("model.toml")).expect("model.toml");
    let measured =
        MeasuredModes::from_path(&case.join("measured.csv"), &model).expect("measured.csv");
    let measured = match noise {
        Some(n) => with_standard_errors(&measured, n),
        None => measured,
    };
    let stated = &truth["noise"]["stated"];
    let settings = DiagnoseSettings {
        noise: Noise {
            frequency: stated["frequency"]
                .as_f64()
                .expect("stated frequency noise"),
            shape: stated["shape"].as_f64().expect("stated shape noise"),
        },
        pairing: PairingRule::default(),
        per_mode: None,
        extended: false,
        full_model: false,
        causes: Vec::new(),
    };
    match diagnose(&model, &measured, settings) {
        Ok(report) => match report.verdict {
            Verdict::None => "none".to_string(),
            Verdict::Effect => format!("effect:{}", report.selected.unwrap_or_default()),
            Verdict::Partial => format!("partial:{}", report.selected.unwrap_or_default()),
            Verdict::Ambiguous => format!("ambiguous:{}", report.contenders.join("|")),
            Verdict::Unexplained => "unexplained".to_string(),
            Verdict::FrequencyDependent => "frequency_dependent".to_string(),
        },
        Err(e) => format!("error: {e}"),
    }
}

fn all_cases() -> Vec<PathBuf> {
    let mut cases: Vec<PathBuf> = std::fs::read_dir(battery())
        .expect("tests/fixtures/battery")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.join("truth.json").exists())
        .collect();
    cases.sort();
    assert_eq!(cases.len(), 100, "the small battery has 100 cases");
    cases
}

fn truth_of(case: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(case.join("truth.json")).expect("truth.json"))
        .expect("truth.json parses")
}

/// Whether `word` is right for `truth`: listed in its `right_verdicts`, or `partial` (a cause
/// named, a misfit beyond the noise remaining) where `unexplained` is right (an effect outside
/// the library: a partial explanation says that something remains).
fn is_right(word: &str, truth: &serde_json::Value) -> bool {
    let listed = |w: &str| {
        truth["expected"]["right_verdicts"]
            .as_array()
            .expect("right_verdicts")
            .iter()
            .any(|v| v.as_str() == Some(w))
    };
    listed(word) || (word.starts_with("partial:") && listed("unexplained"))
}

#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn clean_and_strong_library_cases_are_right() {
    let cases: Vec<PathBuf> = all_cases()
        .into_iter()
        .filter(|c| {
            let name = c.file_name().unwrap().to_string_lossy().to_string();
            FAST.iter().any(|f| name.ends_with(f))
        })
        .collect();
    assert_eq!(cases.len(), 20, "4 cases per noise situation");
    let wrong: Vec<String> = verdicts(&cases)
        .into_iter()
        .filter(|(_, word, truth)| !is_right(word, truth))
        .map(|(name, word, _)| format!("{name} -> {word}"))
        .collect();
    assert!(wrong.is_empty(), "wrong verdicts:\n{}", wrong.join("\n"));
}

/// Every case's verdict, diagnosed in parallel (the cases are independent).
fn verdicts(cases: &[PathBuf]) -> Vec<(String, String, serde_json::Value)> {
    use rayon::prelude::*;
    cases
        .par_iter()
        .map(|case| {
            let truth = truth_of(case);
            let name = case.file_name().unwrap().to_string_lossy().to_string();
            (name, verdict_word(case, &truth), truth)
        })
        .collect()
}

#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn stated_noise_verdicts_are_those_recorded() {
    let cases: Vec<PathBuf> = all_cases()
        .into_iter()
        .filter(|c| c.to_string_lossy().contains("-as_stated-"))
        .collect();
    assert_eq!(cases.len(), AS_STATED.len());
    let found = verdicts(&cases);
    let changed: Vec<String> = found
        .iter()
        .zip(AS_STATED)
        .filter(|((name, word, _), (case, recorded))| name != case || word != recorded)
        .map(|((name, word, _), (_, recorded))| format!("{name}: {recorded} -> {word}"))
        .collect();
    assert!(
        changed.is_empty(),
        "verdicts on the independent battery changed (a change of the candidate library or of the rules of module decide does this: if intended, update AS_STATED and say why):\n{}",
        changed.join("\n")
    );
    let right = found.iter().filter(|(_, w, t)| is_right(w, t)).count();
    let floor = FLOOR[0].1;
    assert!(right >= floor, "{right}/20 right, floor {floor}");
}

/// Right verdicts per situation when the data carry standard errors (the generating noise),
/// the stated noise being the as-stated one whatever the truth: `(situation, right, cases)`.
fn with_data_errors(filter: impl Fn(&str) -> bool) -> Vec<(String, usize, usize, Vec<String>)> {
    use rayon::prelude::*;
    let cases: Vec<PathBuf> = all_cases()
        .into_iter()
        .filter(|c| filter(&c.file_name().unwrap().to_string_lossy()))
        .collect();
    let found: Vec<(String, String, bool)> = cases
        .par_iter()
        .filter_map(|case| {
            let truth = truth_of(case);
            let situation = truth["noise"]["situation"].as_str().unwrap().to_string();
            let noise = generating_noise(&situation)?;
            let word = verdict_word_with(case, &truth, Some(noise));
            let name = case.file_name().unwrap().to_string_lossy().to_string();
            Some((
                situation,
                format!("{name} -> {word}"),
                is_right(&word, &truth),
            ))
        })
        .collect();
    let mut table: BTreeMap<String, (usize, usize, Vec<String>)> = BTreeMap::new();
    for (situation, line, ok) in found {
        let e = table.entry(situation).or_default();
        e.0 += usize::from(ok);
        e.1 += 1;
        if !ok {
            e.2.push(line);
        }
    }
    table
        .into_iter()
        .map(|(s, (r, n, w))| (s, r, n, w))
        .collect()
}

/// With its own standard errors the data need no stated noise: in the mis-stated situations
/// (noise twice or half the stated, an additive floor ten times the stated) the clean and the
/// strong library cases are all right.
#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn data_standard_errors_make_a_misstated_noise_harmless() {
    let rows = with_data_errors(|name| {
        !name.contains("-as_stated-") && FAST.iter().any(|f| name.ends_with(f))
    });
    assert_eq!(rows.iter().map(|r| r.2).sum::<usize>(), 12);
    for (situation, right, n, wrong) in rows {
        assert_eq!(
            right,
            n,
            "{situation}: wrong verdicts:\n{}",
            wrong.join("\n")
        );
    }
}

/// The whole battery with the data's standard errors (release: a minute), per situation.
#[test]
#[ignore = "80 cases: run with --release -- --ignored --nocapture"]
fn data_standard_errors_per_situation() {
    for (situation, right, n, wrong) in with_data_errors(|_| true) {
        println!("{situation}: {right}/{n} right with the data's standard errors");
        for w in wrong {
            println!("  {w}");
        }
    }
}

#[test]
#[ignore = "all 100 cases, the longest battery: .ci/run runs it in release (seconds there)"]
fn verdicts_per_noise_situation_reach_their_floors() {
    let cases = all_cases();
    // situation -> (right, cases); clean -> (none, cases)
    let mut right: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    let mut clean = (0, 0);
    let mut lines = Vec::new();
    for case in &cases {
        let truth = truth_of(case);
        let word = verdict_word(case, &truth);
        let ok = is_right(&word, &truth);
        let situation = truth["noise"]["situation"].as_str().unwrap().to_string();
        let entry = right.entry(situation).or_default();
        entry.0 += usize::from(ok);
        entry.1 += 1;
        if truth["effect"]["name"].is_null() {
            clean.0 += usize::from(word == "none");
            clean.1 += 1;
        }
        lines.push(format!(
            "{} -> {word}{}",
            case.file_name().unwrap().to_string_lossy(),
            if ok { "" } else { "  (wrong)" }
        ));
    }
    let table: Vec<String> = right
        .iter()
        .map(|(s, (r, n))| format!("{s}: {r}/{n} right"))
        .collect();
    let all = format!(
        "{}\n{}\nclean -> none: {}/{}",
        lines.join("\n"),
        table.join("\n"),
        clean.0,
        clean.1
    );
    println!("{all}");
    for (situation, floor) in FLOOR {
        let (r, n) = right.get(situation).copied().unwrap_or((0, 0));
        assert_eq!(n, 20, "{situation}: 20 cases\n{all}");
        assert!(
            r >= floor,
            "{situation}: {r}/{n} right, floor {floor}\n{all}"
        );
    }
    assert!(
        clean.0 >= CLEAN_FLOOR,
        "clean -> none {}/{}, floor {CLEAN_FLOOR}\n{all}",
        clean.0,
        clean.1
    );
}

/// Three cases of the large battery (tests/fixtures/battery-large, made by the same
/// independent generator): a weak sensor mass or suspension under noise half the stated. The
/// shape residuals show the noise at about 0.45x the stated; the effect's noncentrality at the
/// true noise is 64. Each is named: the candidates' information criteria are read under the
/// yardstick the best model's residuals give, the scale their significance was read on. Read
/// under the stated noise, every lead shrank to a fifth and a mimic (joint coupling, joint
/// mass, shear) stayed within the margin: `ambiguous`.
#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn weak_effects_under_half_the_stated_noise_are_told_apart_on_the_scale_the_data_show() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/battery-large");
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/fixtures/battery-large")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.join("truth.json").exists())
        .collect();
    cases.sort();
    assert_eq!(cases.len(), 3);
    for (name, word, truth) in verdicts(&cases) {
        let effect = truth["effect"]["name"].as_str().expect("effect name");
        assert_eq!(word, format!("effect:{effect}"), "{name}");
    }
}
