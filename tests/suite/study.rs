//! The Monte-Carlo study engine: reproducibility, the one-trial path, first-order statistics,
//! grid validation and the CI gate.

use std::path::{Path, PathBuf};
use std::process::Command;

use jointid::identify::{Identifier, Settings};
use jointid::measured::MeasuredMode;
use jointid::random::TrialRng;
use jointid::structure::Observation;
use jointid::study::predicted::noise_free_jacobian;
use jointid::study::{CellPlan, Study, StudyRun};

const MODEL: &str = include_str!("../../models/paper-case-1.toml");
const MODEL_PATH: &str = "models/paper-case-1.toml";

fn study(grid: &str, trials: usize, noise: &str) -> Study {
    let text = format!(
        "name = \"t\"\nmodel = \"{MODEL_PATH}\"\n[truth]\ndelta = {{ k1 = 2.0e6, k2 = 2.0e3 }}\n{grid}\n[monte_carlo]\ntrials = {trials}\nseed = 11\nnoise = \"{noise}\"\n[output]\ncsv = \"t.csv\"\n"
    );
    let model = jointid::model::from_toml(MODEL, Path::new(MODEL_PATH)).unwrap();
    Study::from_toml_with_model(&text, Path::new("t.toml"), model, Path::new(MODEL_PATH)).unwrap()
}

/// The identified DOFs of a cell as measured points.
fn points(run: &StudyRun, dofs: &[usize]) -> Vec<Observation> {
    dofs.iter()
        .map(|&d| Observation::dof(&run.study.model.dofs, d))
        .collect()
}

#[test]
fn every_lane_of_the_engine_is_the_one_trial_identification_bitwise() {
    for noise in ["uniform", "gaussian"] {
        let grid = "[grid]\nmodes = [1, 2, 4]\nn = [12]\nm = [6]\nnf = [7]\nweighting = [\"inverse-sqrt\"]\nshape_noise = [0.03]\nfrequency_noise = [0.002]";
        let run = StudyRun::new(study(grid, 21, noise)).unwrap();
        let cell = &run.cells[0];
        let (_, samples) = run.run_cell(cell, &|_| {});
        let plan = CellPlan::new(&run.study, &run.context, cell).unwrap();
        let identifier = Identifier::for_structure(
            &run.study.model,
            &run.context.nominal,
            Settings {
                n: 12,
                m: 6,
                weighting: cell.weighting,
            },
        )
        .unwrap();
        for trial in [0, 7, 8, 20] {
            let mut rng = TrialRng::new(run.study.seed, cell.index as u64, trial as u64);
            for (k, mode) in plan.modes.iter().enumerate() {
                let values = mode
                    .truth_shape
                    .iter()
                    .map(|&y| y * (1.0 + rng.shape_error(run.study.noise, cell.shape_noise)))
                    .collect();
                let f = 1.0 + rng.frequency_error(run.study.noise, cell.frequency_noise);
                let lambda = mode.truth_lambda * f * f;
                let measured = MeasuredMode::new(
                    mode.mode,
                    lambda.sqrt() / (2.0 * std::f64::consts::PI),
                    points(&run, &plan.identified),
                    values,
                );
                // The frequency round trip through Hz costs an ulp of lambda: compare to 1e-9.
                let z = identifier.identify(&measured).unwrap().relative.unwrap();
                for (i, p) in plan.values.iter().enumerate() {
                    let engine = samples.values[(trial * plan.modes.len() + k) * 2 + i];
                    let one = p * z[i];
                    assert!(
                        (engine - one).abs() <= 1e-9 * one.abs(),
                        "{noise}, trial {trial}, mode {}, param {i}: {engine} vs {one}",
                        mode.mode
                    );
                }
            }
        }
    }
}

#[test]
fn monte_carlo_std_agrees_with_first_order_prediction_at_small_noise() {
    let grid = "[grid]\nmodes = [1, 2, 3, 4]\nn = [10]\nm = [5]\nnf = [5]\nweighting = [\"inverse\", \"equal\"]\nshape_noise = [0.001]\nfrequency_noise = [0.0005]";
    for noise in ["uniform", "gaussian"] {
        let run = StudyRun::new(study(grid, 20_000, noise)).unwrap();
        for cell in &run.cells {
            let (result, _) = run.run_cell(cell, &|_| {});
            for row in &result.rows {
                let s = row.summary.as_ref().unwrap();
                let predicted = row.predicted_std.unwrap();
                assert!(
                    (s.std / predicted - 1.0).abs() < 0.10,
                    "{noise}, {}, mode {} param {}: MC {} vs predicted {predicted}",
                    cell.weighting,
                    row.mode,
                    row.param,
                    s.std
                );
            }
        }
    }
}

#[test]
fn first_order_jacobian_matches_central_differences() {
    let grid = "[grid]\nmodes = [1, 3]\nn = [10]\nm = [6]\nnf = [5]\nweighting = [\"inverse\"]\nshape_noise = [0.01]\nfrequency_noise = [0.001]";
    let run = StudyRun::new(study(grid, 1, "uniform")).unwrap();
    let plan = CellPlan::new(&run.study, &run.context, &run.cells[0]).unwrap();
    let identifier = Identifier::for_structure(
        &run.study.model,
        &run.context.nominal,
        Settings {
            n: 10,
            m: 6,
            weighting: run.cells[0].weighting,
        },
    )
    .unwrap();
    for mode in &plan.modes {
        let jac = noise_free_jacobian(&plan, mode).unwrap();
        let z_of = |shape: Vec<f64>, lambda: f64| {
            let measured = MeasuredMode::new(
                mode.mode,
                lambda.sqrt() / (2.0 * std::f64::consts::PI),
                points(&run, &plan.identified),
                shape,
            );
            identifier.identify(&measured).unwrap().relative.unwrap()
        };
        for j in [0, 5, 17, plan.identified.len() - 1] {
            let h = 1e-6 * mode.truth_shape.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
            let shifted = |sign: f64| {
                let mut y = mode.truth_shape.clone();
                y[j] += sign * h;
                z_of(y, mode.truth_lambda)
            };
            let (plus, minus) = (shifted(1.0), shifted(-1.0));
            for i in 0..2 {
                let fd = (plus[i] - minus[i]) / (2.0 * h);
                let scale = (0..plan.identified.len())
                    .map(|t| jac.shape[(i, t)].abs())
                    .fold(0.0, f64::max);
                assert!(
                    (fd - jac.shape[(i, j)]).abs() < 1e-5 * scale,
                    "mode {}, dof {j}, param {i}: {fd} vs {}",
                    mode.mode,
                    jac.shape[(i, j)]
                );
            }
        }
        let h = 1e-6 * mode.truth_lambda;
        let (plus, minus) = (
            z_of(mode.truth_shape.clone(), mode.truth_lambda + h),
            z_of(mode.truth_shape.clone(), mode.truth_lambda - h),
        );
        for i in 0..2 {
            let fd = (plus[i] - minus[i]) / (2.0 * h);
            assert!(
                (fd - jac.lambda[i]).abs() < 1e-5 * jac.lambda[i].abs(),
                "mode {}, lambda, param {i}: {fd} vs {}",
                mode.mode,
                jac.lambda[i]
            );
        }
    }
}

// ---- the binary ----

struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("jointid-study-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("model.toml"), MODEL).unwrap();
        Scratch(dir)
    }
    fn study_file(&self, body: &str) -> PathBuf {
        let p = self.0.join("s.toml");
        std::fs::write(&p, format!("name = \"s\"\nmodel = \"model.toml\"\n[truth]\ndelta = {{ k1 = 2.0e6, k2 = 2.0e3 }}\n{body}\n[output]\ncsv = \"out/s.csv\"\n")).unwrap();
        p
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn jointid(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_jointid"))
        .args(args)
        .output()
        .unwrap()
}

const SMALL: &str = "[grid]\nmodes = [1, 2, 3, 4]\nn = [10, 22]\nm = [5]\nnf = [0, 5, [\"3:theta\", \"9:w\"]]\nweighting = [\"inverse\"]\nshape_noise = [0.002, 0.04]\nfrequency_noise = [0.0005]\n[monte_carlo]\ntrials = 3000\nseed = 5\nnoise = \"uniform\"";

#[test]
fn output_is_byte_identical_for_one_and_two_threads() {
    let s = Scratch::new("threads");
    let file = s.study_file(SMALL);
    let mut outputs = Vec::new();
    for threads in ["1", "2"] {
        let out = s.0.join(format!("r{threads}.csv"));
        let trials = s.0.join(format!("t{threads}.csv"));
        let run = jointid(&[
            "study",
            file.to_str().unwrap(),
            "--threads",
            threads,
            "--out",
            out.to_str().unwrap(),
            "--trials-csv",
            trials.to_str().unwrap(),
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        outputs.push((
            std::fs::read(&out).unwrap(),
            std::fs::read(&trials).unwrap(),
        ));
    }
    assert_eq!(outputs[0].0, outputs[1].0, "result CSVs differ");
    assert_eq!(outputs[0].1, outputs[1].1, "trial CSVs differ");
    let text = String::from_utf8(outputs[0].0.clone()).unwrap();
    let header = text.lines().next().unwrap();
    assert!(header.starts_with("cell,mode,param,n,m,nf,weighting,shape_noise,frequency_noise,noise,introduced,trials,failures,mean,bias,relative_bias,std,rmse,median,mad,q05,q25,q75,q95,bias_se,predicted_std"));
    // 2 n x 3 nf x 2 noise levels = 12 cells, 4 modes, 2 parameters.
    assert_eq!(text.lines().count(), 1 + 12 * 8);
    assert!(!text.contains("NaN") && !text.contains("inf"));
    assert!(text.contains(",2,theta 9:w") || text.contains("3:theta 9:w"));
    let trials = String::from_utf8(outputs[0].1.clone()).unwrap();
    assert_eq!(trials.lines().count(), 1 + 12 * 3000 * 8);
}

#[test]
fn check_passes_where_the_method_is_accurate_and_fails_with_the_figures_where_it_is_not() {
    let s = Scratch::new("check");
    let gate = "[check]\nmax_abs_relative_bias = 0.05\nwhere = { n = [22], nf = [0], shape_noise = [0.002] }";
    let file = s.study_file(&format!("{SMALL}\n{gate}"));
    let run = jointid(&["check", file.to_str().unwrap()]);
    assert_eq!(
        run.status.code(),
        Some(0),
        "{}{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        String::from_utf8_lossy(&run.stdout)
            .starts_with("check passed: 8 (cell, mode, parameter) rows")
    );
    // At n = 10 the truncation bias of Delta k2 is far above 5%: the gate must fail.
    let gate = "[check]\nmax_abs_relative_bias = 0.05\nstatistic = \"median\"\nwhere = { n = [10], nf = [0], shape_noise = [0.002], params = [\"k2\"] }";
    let file = s.study_file(&format!("{SMALL}\n{gate}"));
    let run = jointid(&["check", file.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert_eq!(run.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("check FAILED"), "{stdout}");
    assert!(stdout.contains("(n = 10, m = 5, nf = 0, weighting = inverse, shape_noise = 0.002, frequency_noise = 0.0005), mode 2, k2: relative bias of the median"), "{stdout}");
    // A selection that matches nothing is an error, not a pass.
    let file = s.study_file(&format!(
        "{SMALL}\n[check]\nmax_abs_relative_bias = 0.05\nwhere = {{ n = [11] }}"
    ));
    let run = jointid(&["check", file.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&run.stderr)
            .contains("[check].where selects no (cell, mode, parameter)")
    );
}

#[test]
fn impossible_cells_are_all_listed_before_anything_runs() {
    let s = Scratch::new("cells");
    let body = "[grid]\nmodes = [1, 6]\nn = [7, 30]\nm = [2, 6]\nnf = [0, 23]\nweighting = [\"equal\"]\nshape_noise = [0.04]\nfrequency_noise = [0.0]\n[monte_carlo]\ntrials = 10\nseed = 1\nnoise = \"uniform\"";
    let file = s.study_file(body);
    let run = jointid(&["study", file.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2));
    assert!(
        stderr.contains("impossible cell(s) in the grid, nothing was computed"),
        "{stderr}"
    );
    assert!(
        stderr.contains(
            "grid.m[1] = 6: m = 6 is invalid: a basis of n = 7 has only 5 deformable rows"
        ),
        "{stderr}"
    );
    assert!(stderr.contains("grid.modes[1] = 6: mode 6 pairs with basis index 8 (1-based, after 2 rigid-body modes), beyond n = 7"), "{stderr}");
    assert!(stderr.contains("grid.nf[1] (NF = 23) with grid.n[1] = 30: 15 identified DOF(s) cannot determine the 30 components of g"), "{stderr}");
    assert!(!s.0.join("out").exists(), "nothing may be written");
}

#[test]
fn bad_study_fields_name_their_path_and_what_is_allowed() {
    let s = Scratch::new("fields");
    let cases = [
        (
            SMALL.replace(
                "weighting = [\"inverse\"]",
                "weighting = [\"inverse\", \"cubic\"]",
            ),
            "s.toml: grid.weighting[1] = \"cubic\" is invalid: `cubic` is not a weighting",
        ),
        (
            SMALL.replace("trials = 3000", "trials = 0"),
            "s.toml: monte_carlo.trials = 0 is invalid: it must be an integer from 1 to",
        ),
        (
            SMALL.replace("noise = \"uniform\"", "noise = \"laplace\""),
            "s.toml: monte_carlo.noise = \"laplace\" is invalid",
        ),
        (
            SMALL.replace("shape_noise = [0.002, 0.04]", "shape_noise = [-0.01]"),
            "s.toml: grid.shape_noise[0] = -0.01 is invalid: it must be a relative error from 0 to below 1 (100%)",
        ),
        (
            SMALL.replace("frequency_noise = [0.0005]", "frequency_noise = [1e308]"),
            "s.toml: grid.frequency_noise[0] = 1e308 is invalid: it must be a relative standard deviation from 0 to below 1",
        ),
        (
            SMALL.replace("\"9:w\"", "\"99:w\""),
            "s.toml: grid.nf[2][1] = \"99:w\" is invalid: an unidentified DOF is \"node:dof\" with node 0 to 18",
        ),
        (
            SMALL.replace("m = [5]", "m = [5]\nbogus = 1"),
            "s.toml:9: grid.bogus: unknown field `bogus`, expected one of `modes`",
        ),
    ];
    for (body, message) in cases {
        let file = s.study_file(&body);
        let run = jointid(&["study", file.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{body}");
        assert!(stderr.contains(message), "expected `{message}` in {stderr}");
    }
    let file = s.0.join("s.toml");
    std::fs::write(&file, format!("name = \"s\"\nmodel = \"model.toml\"\n[truth]\ndelta = {{ k1 = 2.0e6, k3 = 1.0 }}\n{SMALL}\n[output]\ncsv = \"o.csv\"\n")).unwrap();
    let run = jointid(&["study", file.to_str().unwrap()]);
    assert!(
        String::from_utf8_lossy(&run.stderr)
            .contains("truth.delta.k3 = 1 is invalid: the model's parameters are k1, k2")
    );
}
