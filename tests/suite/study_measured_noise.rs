//! A study's noise taken from a measured file's standard errors (`noise = "measured"`).
//!
//! Independence: the measured files are written here by hand, with standard errors chosen
//! proportional to the values (sigma_i = a |v_i|), so the relative error a study must draw is
//! known in closed form (a, and frequency_std / frequency_hz), not taken from the code under
//! test. The engine is then held to a stated-noise study of those levels: bit for bit on one
//! mode, and through the first-order prediction on two modes of different levels.

use std::path::Path;

use jointid::study::{Study, StudyRun};

const MODEL: &str = include_str!("../../models/paper-case-1.toml");
const MODEL_PATH: &str = "models/paper-case-1.toml";

/// Shape rows of the measured file: (node, direction, value). The values need not be the
/// model's shape: only their errors relative to them are used.
const ROWS: [(usize, &str, f64); 5] = [
    (2, "w", 0.31),
    (5, "w", -0.72),
    (9, "w", 1.0),
    (12, "theta", 4.2),
    (16, "w", 0.55),
];

/// A measured file of `modes` = (mode, frequency Hz, relative frequency error, relative shape
/// error a); the peak row has value_std 0, as an extracted mode's.
fn measured_csv(modes: &[(usize, f64, f64, f64)]) -> String {
    let mut text = String::from("mode,frequency_hz,node,dof,value,frequency_std,value_std\n");
    for &(mode, f, rel_f, a) in modes {
        for (node, dof, v) in ROWS {
            let std = if v == 1.0 { 0.0 } else { a * v.abs() };
            text.push_str(&format!(
                "{mode},{f},{node},{dof},{v},{},{std}\n",
                rel_f * f
            ));
        }
    }
    text
}

fn study_text(grid: &str, trials: usize, monte_carlo: &str) -> String {
    format!(
        "name = \"t\"\nmodel = \"{MODEL_PATH}\"\n[truth]\ndelta = {{ k1 = 2.0e6, k2 = 2.0e3 }}\n{grid}\n[monte_carlo]\ntrials = {trials}\nseed = 5\n{monte_carlo}\n[output]\ncsv = \"t.csv\"\n"
    )
}

/// The study of `text`, the file `t.toml` in `dir` beside the measured file `m.csv`.
fn study_in(dir: &Path, text: &str) -> Result<Study, String> {
    let model = jointid::model::from_toml(MODEL, Path::new(MODEL_PATH)).unwrap();
    Study::from_toml_with_model(text, &dir.join("t.toml"), model, Path::new(MODEL_PATH))
        .map_err(|e| e.to_string())
}

const MEASURED: &str = "noise = \"measured\"\nmeasured = \"m.csv\"";

#[test]
fn measured_levels_are_the_files_relative_errors() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.csv"),
        measured_csv(&[(1, 150.0, 0.001, 0.02), (2, 600.0, 0.0004, 0.05)]),
    )
    .unwrap();
    let grid = "[grid]\nmodes = [1, 2]\nn = [10]\nm = [5]\nnf = [5]\nweighting = [\"inverse\"]\nshape_noise = [1.0, 2.0]\nfrequency_noise = [1.0]";
    let study = study_in(dir.path(), &study_text(grid, 10, MEASURED)).unwrap();
    assert_eq!(study.noise_name(), "measured");
    let m = study.measured_noise.as_ref().unwrap();
    for (r, a, rel_f) in [(1, 0.02, 0.001), (2, 0.05, 0.0004)] {
        let e = m.of(r).unwrap();
        assert!((e.shape / a - 1.0).abs() < 1e-12, "mode {r}: {}", e.shape);
        assert!((e.frequency / rel_f - 1.0).abs() < 1e-12, "mode {r}");
    }
    // The grid's levels multiply them, mode by mode.
    let run = StudyRun::new(study).unwrap();
    let plan = jointid::study::CellPlan::new(&run.study, &run.context, &run.cells[1]).unwrap();
    assert_eq!(run.cells[1].shape_noise, 2.0);
    assert!((plan.modes[0].shape_noise / 0.04 - 1.0).abs() < 1e-12);
    assert!((plan.modes[1].shape_noise / 0.10 - 1.0).abs() < 1e-12);
    assert!((plan.modes[1].frequency_noise / 0.0004 - 1.0).abs() < 1e-12);
}

#[test]
fn one_mode_under_its_measured_noise_is_the_stated_normal_noise_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.csv"),
        measured_csv(&[(3, 900.0, 0.0007, 0.015)]),
    )
    .unwrap();
    let grid = |shape: f64, freq: f64| {
        format!(
            "[grid]\nmodes = [3]\nn = [10]\nm = [5]\nnf = [5]\nweighting = [\"inverse-sqrt\"]\nshape_noise = [{shape}]\nfrequency_noise = [{freq}]"
        )
    };
    let measured = study_in(dir.path(), &study_text(&grid(1.0, 1.0), 64, MEASURED)).unwrap();
    let e = *measured.measured_noise.as_ref().unwrap().of(3).unwrap();
    let stated = study_in(
        dir.path(),
        &study_text(&grid(e.shape, e.frequency), 64, "noise = \"gaussian\""),
    )
    .unwrap();
    let (a, b) = (
        StudyRun::new(measured).unwrap(),
        StudyRun::new(stated).unwrap(),
    );
    let (ra, _) = a.run_cell(&a.cells[0], &|_| {});
    let (rb, _) = b.run_cell(&b.cells[0], &|_| {});
    assert_eq!(ra.rows, rb.rows);
}

#[test]
fn two_modes_of_different_measured_levels_scatter_as_predicted() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.csv"),
        measured_csv(&[(1, 150.0, 0.0002, 0.001), (2, 600.0, 0.0008, 0.004)]),
    )
    .unwrap();
    let grid = "[grid]\nmodes = [1, 2]\nn = [10]\nm = [5]\nnf = [5]\nweighting = [\"inverse\"]\nshape_noise = [1.0]\nfrequency_noise = [1.0]";
    let run =
        StudyRun::new(study_in(dir.path(), &study_text(grid, 20_000, MEASURED)).unwrap()).unwrap();
    let (result, _) = run.run_cell(&run.cells[0], &|_| {});
    // The same study stated at mode 1's levels predicts mode 1's spread and not mode 2's.
    let stated_grid = "[grid]\nmodes = [1, 2]\nn = [10]\nm = [5]\nnf = [5]\nweighting = [\"inverse\"]\nshape_noise = [0.001]\nfrequency_noise = [0.0002]";
    let stated = StudyRun::new(
        study_in(
            dir.path(),
            &study_text(stated_grid, 1, "noise = \"gaussian\""),
        )
        .unwrap(),
    )
    .unwrap();
    let (reference, _) = stated.run_cell(&stated.cells[0], &|_| {});
    for (row, r) in result.rows.iter().zip(&reference.rows) {
        let s = row.summary.as_ref().unwrap();
        let predicted = row.predicted_std.unwrap();
        assert!(
            (s.std / predicted - 1.0).abs() < 0.10,
            "mode {} param {}: MC {} vs predicted {predicted}",
            row.mode,
            row.param,
            s.std
        );
        // First order: the spread is linear in the noise, 4x on mode 2.
        let ratio = predicted / r.predicted_std.unwrap();
        let want = if row.mode == 1 { 1.0 } else { 4.0 };
        assert!(
            (ratio / want - 1.0).abs() < 1e-9,
            "mode {}: {ratio}",
            row.mode
        );
    }
}

#[test]
fn measured_noise_input_errors_name_the_field_and_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "[grid]\nmodes = [1, 2]\nn = [10]\nm = [5]\nnf = [5]\nweighting = [\"inverse\"]\nshape_noise = [0.5]\nfrequency_noise = [0.5]";
    let cases: [(&str, Option<String>, &[&str]); 5] = [
        (
            "noise = \"measured\"",
            None,
            &["monte_carlo.noise = \"measured\"", "needs `measured ="],
        ),
        (
            "noise = \"gaussian\"\nmeasured = \"m.csv\"",
            None,
            &[
                "monte_carlo.measured = \"m.csv\"",
                "only under noise = \"measured\"",
            ],
        ),
        (
            MEASURED,
            Some("mode,frequency_hz,node,dof,value\n1,150,2,w,0.3\n2,600,2,w,0.3\n".into()),
            &[
                "monte_carlo.measured",
                "mode 1 of the file carries no standard errors",
            ],
        ),
        (
            MEASURED,
            Some(measured_csv(&[(1, 150.0, 0.001, 0.02)])),
            &["monte_carlo.measured", "the file has no mode 2"],
        ),
        (
            "noise = \"pink\"",
            None,
            &["monte_carlo.noise = \"pink\"", "or \"measured\""],
        ),
    ];
    for (monte_carlo, file, wanted) in cases {
        let _ = std::fs::remove_file(dir.path().join("m.csv"));
        if let Some(text) = &file {
            std::fs::write(dir.path().join("m.csv"), text).unwrap();
        }
        let e = study_in(dir.path(), &study_text(grid, 10, monte_carlo)).unwrap_err();
        for w in wanted {
            assert!(e.contains(w), "{monte_carlo}: `{w}` not in {e}");
        }
    }
    // Factors that would make a relative error of 100% or more.
    std::fs::write(
        dir.path().join("m.csv"),
        measured_csv(&[(1, 150.0, 0.001, 0.02), (2, 600.0, 0.0004, 0.25)]),
    )
    .unwrap();
    let e = study_in(
        dir.path(),
        &study_text(
            &grid.replace("[0.5]\nfreq", "[2.0, 4.0]\nfreq"),
            10,
            MEASURED,
        ),
    )
    .unwrap_err();
    assert!(
        e.contains("grid.shape_noise[1] = 4 is invalid") && e.contains("mode 2's measured"),
        "{e}"
    );
    // A missing file is named with the field.
    let _ = std::fs::remove_file(dir.path().join("m.csv"));
    let e = study_in(dir.path(), &study_text(grid, 10, MEASURED)).unwrap_err();
    assert!(
        e.contains("monte_carlo.measured") && e.contains("m.csv"),
        "{e}"
    );
}
