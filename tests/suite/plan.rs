//! `jointid plan`: bad input refused with the flag, the value and what is allowed (exit 2,
//! nothing written); the plan's predicted spreads against the Monte-Carlo spreads of the study
//! it writes; the free-free lap beam with three sensors said rank-deficient, with the sensor
//! that completes it.
//!
//! Independence of the test data: the Monte-Carlo spreads come from the study engine
//! (`jointid::study`: noisy shapes and frequencies drawn, the identification run trial by
//! trial, the sample standard deviation), which shares with the plan only the per-mode
//! estimator; the plan's spreads are its first-order propagation. The derivative itself is
//! checked against central differences of the estimator in `src/plan/spread.rs`. The lap beam
//! is `tests/fixtures/plan/lap-free.toml` (a half-lap bar as `tests/fixtures/lap2d`, its
//! overlap off the middle).
//!
//! The first order holds while the spread is small beside the correction's own scale: the
//! comparison covers every determinate (mode, parameter) whose predicted relative std is below
//! [`LINEAR`]; beyond, the Monte-Carlo spread is heavier-tailed (docs/planning.md).

use std::path::Path;

use jointid::output::plan::{StudyFile, StudyGrid, study_toml};
use jointid::plan::{
    Kind, Objective, Plan, Request, SettingsChoice, Sites, Status, plan, request::parse_counts,
};
use jointid::random::NoiseKind;
use jointid::study::{Study, StudyRun};

const PAPER: &str = "models/paper-case-1.toml";
const LAP: &str = "tests/fixtures/plan/lap-free.toml";

fn root(path: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

fn request(sensors: &str, modes: &[usize], shape: f64, frequency: f64) -> Request {
    Request {
        sites: Sites::Nodes,
        counts: parse_counts(sensors).unwrap(),
        modes: modes.to_vec(),
        frequency_noise: frequency,
        shape_noise: shape,
        noise: NoiseKind::Gaussian,
        fixed: Vec::new(),
        objective: Objective::Worst,
        settings: SettingsChoice::Chosen,
    }
}

#[test]
fn bad_input_names_the_flag_the_value_and_what_is_allowed_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("plan.json");
    let study = dir.path().join("plan-study.toml");
    let base = |extra: &[&str]| {
        let mut args: Vec<String> = [
            "plan",
            "--model",
            root(PAPER).to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--study",
            study.to_str().unwrap(),
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let mut defaults = vec![
            ("--sites", "0,0.2,0.5"),
            ("--sensors", "3"),
            ("--modes", "1,2"),
            ("--frequency-noise", "0.001"),
            ("--shape-noise", "0.01"),
        ];
        for pair in extra.chunks(2) {
            defaults.retain(|(k, _)| *k != pair[0]);
            args.extend([pair[0].to_string(), pair[1].to_string()]);
        }
        for (k, v) in defaults {
            args.extend([k.to_string(), v.to_string()]);
        }
        args
    };
    let cases: [(&[&str], &str); 8] = [
        (
            &["--sensors", "4"],
            "--sensors 4 is invalid: it must be from 1 to 3, the candidate sites",
        ),
        (
            &["--fixed", "3:w"],
            "--fixed 3:w is invalid: a fixed sensor must be one of the 3 candidate sites (DOF 3:w is not)",
        ),
        (
            &["--modes", "1,40"],
            "--modes 40 is invalid: the model has 36 elastic modes: a mode must be from 1 to 36",
        ),
        (
            &["--shape-noise", "0"],
            "--shape-noise 0 is invalid: it must be > 0 (a relative standard deviation; the plan weighs the noise of the frequency against that of the shape)",
        ),
        (
            &["--frequency-noise", "-0.001"],
            "--frequency-noise -0.001 is invalid: it must be > 0 (a relative standard deviation; the plan weighs the noise of the frequency against that of the shape)",
        ),
        (
            &["--modes", "1,1"],
            "--modes 1 is invalid: each mode may be listed once",
        ),
        (
            &["--n", "7", "--m", "3", "--weighting", "inverse"],
            "--sensors 3 is invalid: the held n = 7 needs at least 7 sensors (eq. (15) projects on n basis vectors): place more, or hold a smaller n",
        ),
        (
            &["--objective", "best"],
            "--objective best is invalid: it must be worst, mean or det",
        ),
    ];
    for (extra, message) in cases {
        let args = base(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let run = crate::common::jointid(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr.trim(), format!("error: {message}"), "{args:?}");
        assert!(!out.exists() && !study.exists(), "{args:?} wrote a file");
    }
}

#[test]
fn three_sensors_on_the_free_free_lap_are_rank_deficient_and_one_more_completes_them() {
    let model = jointid::model::from_path(&root(LAP)).unwrap();
    let p = plan(&model, &request("3", &[1, 2], 0.01, 0.001)).unwrap();
    // The model's own three sensors (x = 0, 0.235, 0.7): no basis of a free-free beam with
    // q = 2 fits three readings (n >= 2 rigid + 2 = 4), so every mode is undetermined; one
    // more sensor is the fewest that can complete it.
    let own = p.model_layout.as_ref().unwrap();
    assert_eq!(own.sites.len(), 3);
    assert_eq!(own.evaluation.score.undetermined, 2);
    assert!(
        own.evaluation
            .modes
            .iter()
            .all(|m| m.status == Status::TooFewSensors
                && m.fallback.as_ref().is_some_and(|f| f.relative_std > 0.0))
    );
    let addition = own.addition.as_ref().unwrap();
    assert_eq!(addition.added.len(), 1);
    assert!(addition.fewest);
    assert_eq!(addition.evaluation.score.undetermined, 0);
    // The same of every three-sensor layout the plan makes.
    for l in &p.counts[0].layouts {
        assert_eq!(l.evaluation.score.undetermined, 2, "{:?}", l.kind);
        assert_eq!(l.addition.as_ref().unwrap().added.len(), 1);
    }
}

#[test]
fn the_chosen_layout_is_never_worse_than_the_references_on_the_objective() {
    let model = jointid::model::from_path(&root(PAPER)).unwrap();
    let p = plan(&model, &request("4-5", &[1, 2], 0.01, 0.001)).unwrap();
    for c in &p.counts {
        let chosen = &c.layouts[0];
        assert_eq!(chosen.kind, Kind::Chosen);
        for other in &c.layouts[1..] {
            assert!(
                !other.evaluation.score.better(&chosen.evaluation.score),
                "{} sensors: {:?} {:?} beats the chosen {:?}",
                c.sensors,
                other.kind,
                other.evaluation.score,
                chosen.evaluation.score
            );
        }
        assert_eq!(
            chosen.evaluation.score.undetermined, 0,
            "{} sensors",
            c.sensors
        );
    }
}

/// Per grid of a study, per (mode, parameter) row: the mode and the Monte-Carlo std.
type GridRows = Vec<Vec<(usize, Option<f64>)>>;

/// The plan's study run by the study engine: per grid, (mode, parameter) -> Monte-Carlo std.
fn monte_carlo(p: &Plan, model: &str, trials: usize) -> (Vec<StudyGrid>, GridRows) {
    let dir = tempfile::tempdir().unwrap();
    let model_path = root(model);
    let model_struct = jointid::model::from_path(&model_path).unwrap();
    let labels: Vec<String> = model_struct
        .dofs
        .dofs()
        .iter()
        .map(|d| d.label.clone())
        .collect();
    let (text, grids) = study_toml(
        p,
        &StudyFile {
            name: "confirm",
            model: &model_path,
            labels: &labels,
            noise: "gaussian",
            shape_noise: SHAPE,
            frequency_noise: FREQUENCY,
            trials,
            seed: 7,
            csv: "confirm.csv",
        },
    );
    let file = dir.path().join("confirm.toml");
    std::fs::write(&file, text).unwrap();
    let run = StudyRun::new(Study::from_path(&file).unwrap()).unwrap();
    let per_cell = run
        .cells
        .iter()
        .map(|cell| {
            let (result, _) = run.run_cell(cell, &|_| {});
            result
                .rows
                .iter()
                .map(|r| (r.mode, r.summary.as_ref().map(|s| s.std)))
                .collect()
        })
        .collect();
    (grids, per_cell)
}

const SHAPE: f64 = 0.002;
/// The predicted relative std below which the first order is held to the Monte-Carlo.
const LINEAR: f64 = 1.0;
const FREQUENCY: f64 = 0.0005;

/// Predicted against Monte-Carlo, within 15%, for every determinate mode and parameter of every
/// layout the study holds; returns the number compared.
fn confirm(model: &str, sensors: &str, modes: &[usize]) -> usize {
    let structure = jointid::model::from_path(&root(model)).unwrap();
    let p = plan(&structure, &request(sensors, modes, SHAPE, FREQUENCY)).unwrap();
    let (grids, mc) = monte_carlo(&p, model, 20_000);
    let mut compared = 0;
    for (grid, rows) in grids.iter().zip(&mc) {
        let layout = match grid.sensors {
            Some(n) => p
                .counts
                .iter()
                .find(|c| c.sensors == n)
                .unwrap()
                .layouts
                .iter()
                .find(|l| l.kind.name() == grid.kind)
                .unwrap(),
            None => p.model_layout.as_ref().unwrap(),
        };
        let q = p.parameters.len();
        let mc_worst = rows
            .iter()
            .enumerate()
            .map(|(r, (_, std))| std.unwrap_or(f64::INFINITY) / p.values[r % q])
            .fold(0.0, f64::max);
        // The figures of docs/planning.md (`-- --include-ignored --nocapture`).
        println!(
            "{model}: {} sensors, {:>6}: worst relative std predicted {:.4}, Monte-Carlo {:.4}",
            layout.sites.len(),
            grid.kind,
            layout.evaluation.score.value,
            mc_worst
        );
        for (k, m) in layout.evaluation.modes.iter().enumerate() {
            let Some(rel) = &m.relative_std else { continue };
            for i in (0..q).filter(|&i| rel[i] < LINEAR) {
                let predicted = rel[i] * p.values[i];
                let (mode, got) = rows[k * q + i];
                assert_eq!(mode, m.mode);
                let ratio = got.unwrap() / predicted;
                assert!(
                    (ratio - 1.0).abs() < 0.15,
                    "{model}, {} {}, mode {mode} {}: Monte-Carlo {:e} vs predicted {predicted:e}",
                    layout.sites.len(),
                    grid.kind,
                    p.parameters[i],
                    got.unwrap()
                );
                compared += 1;
                println!(
                    "  mode {mode} {:>4}: predicted {predicted:.4e}, Monte-Carlo {:.4e}, ratio {ratio:.3}",
                    p.parameters[i],
                    got.unwrap()
                );
            }
        }
    }
    compared
}

#[test]
#[ignore = "Monte-Carlo of every layout: seconds in release (.ci/run)"]
fn predicted_spread_matches_monte_carlo_on_the_paper_beam() {
    // 3 sensors: no basis fits (nothing to compare, the plan says so); 4, 6 and 9: compared.
    let structure = jointid::model::from_path(&root(PAPER)).unwrap();
    let p = plan(&structure, &request("3", &[1, 2], SHAPE, FREQUENCY)).unwrap();
    assert!(
        p.counts[0]
            .layouts
            .iter()
            .all(|l| l.evaluation.score.undetermined == 2)
    );
    let compared: usize = ["4", "6", "9"]
        .iter()
        .map(|n| confirm(PAPER, n, if *n == "4" { &[1, 2] } else { &[1, 2, 3, 4] }))
        .sum();
    assert!(compared >= 30, "{compared}");
}

#[test]
#[ignore = "Monte-Carlo of every layout: seconds in release (.ci/run)"]
fn predicted_spread_matches_monte_carlo_on_the_free_free_lap() {
    // 3 sensors leave every mode undetermined (the test above): the study holds the 4-sensor
    // layouts.
    let compared = confirm(LAP, "3-4", &[1, 2]);
    assert!(compared >= 8, "{compared}");
}

/// Every subset of `k` of `0..n`, in lexicographic order.
fn subsets(n: usize, k: usize) -> Vec<Vec<usize>> {
    if k == 0 {
        return vec![Vec::new()];
    }
    (k - 1..n)
        .flat_map(|last| {
            subsets(last, k - 1).into_iter().map(move |mut s| {
                s.push(last);
                s
            })
        })
        .collect()
}

#[test]
fn the_search_finds_the_best_of_every_layout_on_a_small_set_of_sites() {
    // Ten sites of the paper's beam, four sensors: all 210 layouts judged one by one (each a
    // plan with exactly its four sites) against the search's choice. Single exchanges end in a
    // local optimum: here 1.0% above the best layout (docs/planning.md); held within 2%.
    let model = jointid::model::from_path(&root(PAPER)).unwrap();
    let xs = [
        0.0,
        0.0571428571428571,
        0.1142857142857143,
        0.2,
        0.26,
        0.29,
        0.35,
        0.41,
        0.44,
        0.5,
    ];
    let with_sites = |sites: Vec<f64>| Request {
        sites: Sites::Positions(sites),
        ..request("4", &[1, 2], 0.01, 0.001)
    };
    let chosen = plan(&model, &with_sites(xs.to_vec())).unwrap();
    let chosen = &chosen.counts[0].layouts[0].evaluation.score;
    let best = subsets(xs.len(), 4)
        .into_iter()
        .map(|s| {
            let p = plan(&model, &with_sites(s.iter().map(|&i| xs[i]).collect())).unwrap();
            p.counts[0].layouts[0].evaluation.score.value
        })
        .fold(f64::INFINITY, f64::min);
    assert_eq!(chosen.undetermined, 0);
    assert!(
        chosen.value <= best * 1.02,
        "search {} vs exhaustive {best}",
        chosen.value
    );
}

#[test]
fn a_fixed_sensor_stays_in_every_layout_and_the_files_are_written_together() {
    let dir = tempfile::tempdir().unwrap();
    let (out, study, figure) = (
        dir.path().join("plan.json"),
        dir.path().join("confirm.toml"),
        dir.path().join("plan.svg"),
    );
    let model = root(PAPER);
    let run = crate::common::jointid_ok(&[
        "plan",
        "--model",
        model.to_str().unwrap(),
        "--sensors",
        "4-5",
        "--modes",
        "1,2",
        "--fixed",
        "0.5",
        "--frequency-noise",
        "0.001",
        "--shape-noise",
        "0.01",
        "--out",
        out.to_str().unwrap(),
        "--study",
        study.to_str().unwrap(),
        "--figure",
        figure.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(stdout.matches("[[sensor]]").count(), 9, "{stdout}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let fixed = json["plan"]["fixed"][0].as_u64().unwrap();
    assert_eq!(json["plan"]["candidates"][fixed as usize]["x"], 0.5);
    for count in json["plan"]["counts"].as_array().unwrap() {
        for layout in count["layouts"].as_array().unwrap() {
            let sites = layout["sites"].as_array().unwrap();
            assert!(sites.iter().any(|s| s.as_u64() == Some(fixed)), "{layout}");
        }
    }
    // The study reads back, one grid per layout of the plan (all determinate here).
    let s = Study::from_path(&study).unwrap();
    assert_eq!(s.grids.len(), json["study_grids"].as_array().unwrap().len());
    assert_eq!(s.grids.len(), 6);
    assert!(std::fs::read_to_string(&figure).unwrap().contains("<svg"));
}

#[test]
fn each_objective_is_the_summary_it_names_of_the_modes_spreads() {
    // Recomputed here from the per-mode covariances the plan returns: the largest std, the
    // mean std, and the geometric mean of det(C_r)^(1/2q) (2 x 2 determinants by hand).
    let model = jointid::model::from_path(&root(PAPER)).unwrap();
    for objective in [Objective::Worst, Objective::Mean, Objective::Det] {
        let p = plan(
            &model,
            &Request {
                objective,
                ..request("5", &[1, 2, 3], 0.01, 0.001)
            },
        )
        .unwrap();
        let e = &p.counts[0].layouts[0].evaluation;
        assert_eq!(e.score.undetermined, 0);
        let stds: Vec<f64> = e
            .modes
            .iter()
            .flat_map(|m| m.relative_std.clone().unwrap())
            .collect();
        let want = match objective {
            Objective::Worst => stds.iter().copied().fold(0.0, f64::max),
            Objective::Mean => stds.iter().sum::<f64>() / stds.len() as f64,
            Objective::Det => {
                let logs: f64 = e
                    .modes
                    .iter()
                    .map(|m| {
                        let c = m.covariance.as_ref().unwrap();
                        (c[0] * c[3] - c[1] * c[2]).ln() / 4.0
                    })
                    .sum();
                (logs / e.modes.len() as f64).exp()
            }
        };
        let got = e.score.value;
        assert!(
            (got - want).abs() <= 1e-9 * want,
            "{objective}: {got} vs {want}"
        );
        for m in &e.modes {
            let c = m.covariance.as_ref().unwrap();
            let s = m.relative_std.as_ref().unwrap();
            assert!((c[0].sqrt() - s[0]).abs() <= 1e-12 * s[0] && c[1] == c[2]);
        }
    }
}
