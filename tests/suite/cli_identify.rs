//! `jointid identify` end to end: a good run, and every bad input with its message, a
//! non-zero exit and no output file.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{all_dofs, paper_model};
use jointid::modal::ModalSolution;
use jointid::simulate::exact_modes;
use jointid::structure::Observation;

struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("jointid-cli-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.path(name);
        std::fs::write(&p, text).unwrap();
        p
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const MODEL: &str = include_str!("../../models/paper-case-1.toml");

fn simulated_csv(dofs: &[Observation]) -> String {
    let truth = paper_model(1.2e7, 1.2e4);
    let modes = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        2,
        &[1, 2, 3, 4],
        dofs,
    );
    let mut buf = Vec::new();
    modes.write_csv(&mut buf, &truth).unwrap();
    String::from_utf8(buf).unwrap()
}

fn identify(model: &Path, measured: &Path, extra: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_jointid"))
        .arg("identify")
        .arg("--model")
        .arg(model)
        .arg("--measured")
        .arg(measured)
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn identifies_noise_free_modes_into_a_csv() {
    let s = Scratch::new("good");
    let model = s.write("m.toml", MODEL);
    let data = s.write("d.csv", &simulated_csv(&all_dofs(&paper_model(1.0, 1.0))));
    let out = s.path("out.csv");
    let run = identify(
        &model,
        &data,
        &[
            "--n",
            "38",
            "--m",
            "7",
            "--weighting",
            "inverse",
            "--modes",
            "1,3",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "mode,param,initial,correction,corrected,relative_correction,frequency_measured_hz,frequency_model_hz,condition,resolution,identified"
    );
    assert_eq!(lines.len(), 5);
    for (line, (mode, param, delta)) in lines[1..].iter().zip([
        (1, "k1", 2.0e6),
        (1, "k2", 2.0e3),
        (3, "k1", 2.0e6),
        (3, "k2", 2.0e3),
    ]) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[0], mode.to_string());
        assert_eq!(f[1], param);
        let correction: f64 = f[3].parse().unwrap();
        assert!((correction - delta).abs() < 1e-8 * delta, "{line}");
        let relative: f64 = f[5].parse().unwrap();
        assert!((relative - 0.2).abs() < 1e-8, "{line}");
        let resolution: f64 = f[9].parse().unwrap();
        assert!(resolution > 0.5 && resolution <= 1.0, "{line}");
        assert_eq!(f[10], "yes");
    }
    // Without --out: a readable table on stdout.
    let run = identify(
        &model,
        &data,
        &["--n", "38", "--m", "7", "--weighting", "equal"],
    );
    assert!(run.status.success());
    let table = String::from_utf8(run.stdout).unwrap();
    assert!(table.lines().next().unwrap().contains("correction"));
    assert_eq!(table.lines().count(), 9);
}

fn assert_fails(name: &str, model_text: &str, csv: &str, args: &[&str], message: &str) {
    let s = Scratch::new(name);
    let model = s.write("m.toml", model_text);
    let data = s.write("d.csv", csv);
    let out = s.path("out.csv");
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["--out", out.to_str().unwrap()]);
    let run = identify(&model, &data, &all);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "{name}: should fail");
    assert!(
        stderr.contains(message),
        "{name}: expected `{message}` in:\n{stderr}"
    );
    assert!(!out.exists(), "{name}: output file left behind");
    assert_eq!(
        std::fs::read_dir(&s.0).unwrap().count(),
        2,
        "{name}: stray files"
    );
}

#[test]
fn every_bad_input_is_explained_and_leaves_no_file() {
    let good = simulated_csv(&all_dofs(&paper_model(1.0, 1.0)));
    let w_only = simulated_csv(&common::translations(&paper_model(1.0, 1.0)));
    let std_args = ["--n", "10", "--m", "5", "--weighting", "inverse"];
    let header = "mode,frequency_hz,node,dof,value\n";
    assert_fails(
        "length",
        &MODEL.replacen("length = 0.30", "length = -0.3", 1),
        &good,
        &std_args,
        "m.toml: beam[1].length = -0.3 is invalid: it must be finite and > 0 (m)",
    );
    assert_fails(
        "unknown-key",
        &MODEL.replacen("density", "densty", 1),
        &good,
        &std_args,
        "beam[0].densty: unknown field `densty`",
    );
    assert_fails(
        "dof",
        MODEL,
        &format!("{header}1,150,0,phi,1\n"),
        &std_args,
        "d.csv:2: dof = `phi` is invalid: it must be `w` or `theta`",
    );
    assert_fails(
        "node",
        MODEL,
        &format!("{header}1,150,19,w,1\n"),
        &std_args,
        "d.csv:2: node = `19` is invalid: the model has nodes 0 to 18",
    );
    assert_fails(
        "duplicate",
        MODEL,
        &format!("{header}1,150,0,w,1\n1,150,0,w,1\n"),
        &std_args,
        "d.csv:3: mode 1, point 0:w is given twice (first on line 2)",
    );
    assert_fails(
        "frequencies",
        MODEL,
        &format!("{header}1,150,0,w,1\n1,152,1,w,1\n"),
        &std_args,
        "d.csv:3: mode 1 has frequency_hz = 152 here but 150 on line 2",
    );
    assert_fails(
        "nonfinite",
        MODEL,
        &format!("{header}1,150,0,w,nan\n"),
        &std_args,
        "d.csv:2: value = `nan` is invalid",
    );
    assert_fails(
        "no-shape",
        MODEL,
        &format!("{header}1,150,,,\n"),
        &std_args,
        "d.csv:2: mode 1 has no shape rows",
    );
    assert_fails(
        "underdetermined",
        MODEL,
        &w_only,
        &["--n", "20", "--m", "5", "--weighting", "inverse"],
        "mode 1: 19 identified DOF(s) cannot determine the 20 components of g",
    );
    assert_fails(
        "m-large",
        MODEL,
        &good,
        &["--n", "10", "--m", "9", "--weighting", "inverse"],
        "m = 9 is invalid: a basis of n = 10 has only 8 deformable rows",
    );
    assert_fails(
        "m-small",
        MODEL,
        &good,
        &["--n", "10", "--m", "1", "--weighting", "inverse"],
        "m = 1 is invalid: it must be at least the number of parameters q = 2",
    );
    assert_fails(
        "n-large",
        MODEL,
        &good,
        &["--n", "39", "--m", "5", "--weighting", "inverse"],
        "--n 39 is invalid: it must be from 3 to 38",
    );
    assert_fails(
        "beyond-basis",
        MODEL,
        &good,
        &["--n", "5", "--m", "2", "--weighting", "inverse"],
        "mode 4 pairs with basis index 6 (1-based, after 2 rigid-body modes), beyond n = 5: increase n",
    );
    assert_fails(
        "missing-mode",
        MODEL,
        &good,
        &[
            "--n",
            "10",
            "--m",
            "5",
            "--weighting",
            "inverse",
            "--modes",
            "1,7",
        ],
        "--modes 1,7 is invalid: it asks for mode 7, which the measured modes do not hold",
    );
    assert_fails(
        "weighting",
        MODEL,
        &good,
        &["--n", "10", "--m", "5", "--weighting", "cubic"],
        "`cubic` is not a weighting: use equal, inverse or inverse-sqrt",
    );
    assert_fails(
        "no-model",
        "",
        &good,
        &std_args,
        "m.toml: beam = 0 beam(s) is invalid: a chain has 1 to 9 [[beam]] tables",
    );
}

/// Three sensors on a free-free lap beam (the independent 2D specimen of tests/fixtures/lap2d):
/// the paper's system cannot be formed, each mode's frequency gives one parameter.
#[test]
fn three_sensors_identify_one_parameter_per_mode_from_its_frequency() {
    let dir = Scratch::new("from-frequency");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/lap2d/bolted");
    let from_frequency = |noise: &str, out: &Path| {
        identify(
            &fixture.join("model.toml"),
            &fixture.join("measured.csv"),
            &[
                "--from-frequency",
                "--frequency-noise",
                noise,
                "--out",
                common::s(out),
            ],
        )
    };
    let out = dir.path("freq.csv");
    let run = from_frequency("0.001", &out);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12, "6 modes x (k1, k2)");
    for mode in 1..=6 {
        let of: Vec<&Vec<&str>> = rows.iter().filter(|r| r[0] == mode.to_string()).collect();
        let how: Vec<&str> = of.iter().map(|r| r[col("identified")]).collect();
        assert_eq!(
            how.iter().filter(|h| **h == "frequency").count(),
            1,
            "mode {mode}: {how:?}"
        );
        assert_eq!(
            how.iter().filter(|h| **h == "held").count(),
            1,
            "mode {mode}: {how:?}"
        );
        let own = of
            .iter()
            .find(|r| r[col("identified")] == "frequency")
            .unwrap();
        let std: f64 = own[col("relative_correction_std")].parse().unwrap();
        assert!(std > 0.0 && std.is_finite(), "mode {mode}: std {std}");
    }
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("note: mode 1: k2 from the frequency alone (--from-frequency)"),
        "{stderr}"
    );
    // without --from-frequency the paper's settings are required; a bad noise is refused
    let missing = identify(
        &fixture.join("model.toml"),
        &fixture.join("measured.csv"),
        &[],
    );
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("--n <N>"));
    let bad = from_frequency("2", &dir.path("no.csv"));
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains(
        "--frequency-noise 2 is invalid: a relative standard deviation from 1e-12 to below 1"
    ));
    assert!(!dir.path("no.csv").exists());
}

/// A measured mode numbered beyond the model's elastic modes, identified from its frequency
/// alone. The model is the lap fixture's with one element per interval: nodes at 0, 0.235
/// (sensor), 0.31 (mass) and 0.35 m on the first beam, 0.35, 0.39 (mass) and 0.7 m on the
/// second, 7 nodes x 2 = 14 DOFs, 2 rigid-body modes, so 12 elastic modes (counted here from
/// the file, not by the code under test). Measured mode 6 renumbered 13 has no model mode to
/// pair with: refused naming the mode and the count, exit 2, nothing written. Renumbered 12
/// (the last elastic mode) it is accepted.
#[test]
fn a_mode_beyond_the_models_elastic_modes_is_refused_from_its_frequency() {
    let dir = Scratch::new("beyond-model");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/lap2d/bolted");
    let model_text = std::fs::read_to_string(fixture.join("model.toml"))
        .unwrap()
        .replace("elements = 70", "elements = 1");
    let model = dir.write("model.toml", &model_text);
    let measured_text = std::fs::read_to_string(fixture.join("measured.csv")).unwrap();
    let renumbered = |mode: &str| {
        let text = measured_text.replace("\n6,", &format!("\n{mode},"));
        assert_ne!(text, measured_text);
        dir.write(&format!("measured{mode}.csv"), &text)
    };
    let out = dir.path("freq.csv");
    let run = identify(
        &model,
        &renumbered("13"),
        &["--from-frequency", "--out", common::s(&out)],
    );
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(
            "measured13.csv: mode 13 is beyond the model: it has 12 elastic modes (14 DOFs, 2 rigid-body modes)"
        ),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!out.exists(), "nothing is written");
    let run = identify(
        &model,
        &renumbered("12"),
        &["--from-frequency", "--out", common::s(&out)],
    );
    assert!(
        !String::from_utf8_lossy(&run.stderr).contains("beyond the model"),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_ne!(run.status.code(), Some(101));
}

/// Runs identify into `dir/out.csv` and expects exit 2, every needle in a message under 200
/// characters, and no file written.
fn refused_into(dir: &Scratch, model: &Path, data: &Path, args: &[&str], needles: &[&str]) {
    let out = dir.path("out.csv");
    let mut all = args.to_vec();
    all.extend(["--out", common::s(&out)]);
    let run = identify(model, data, &all);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{args:?}: {stderr}");
    for n in needles {
        assert!(stderr.contains(n), "{args:?}: `{n}` not in {stderr}");
    }
    // the scratch folder's path is the test's, not the message's
    let message = stderr.trim().replace(&format!("{}/", dir.0.display()), "");
    assert!(
        message.len() < 200,
        "{} characters: {message}",
        message.len()
    );
    assert!(!out.exists(), "{args:?}: {} written", out.display());
}

#[test]
fn a_mode_listed_twice_is_refused_as_a_parameter_listed_twice_is() {
    let s = Scratch::new("twice");
    let model = s.write("m.toml", MODEL);
    let data = s.write("d.csv", &simulated_csv(&all_dofs(&paper_model(1.0, 1.0))));
    let paper = ["--n", "38", "--m", "7", "--weighting", "inverse"];
    for extra in [&["--modes", "1,1"][..], &["--modes", "1,3,1"]] {
        for settings in [&paper[..], &["--from-frequency"]] {
            let args: Vec<&str> = settings.iter().chain(extra).copied().collect();
            refused_into(
                &s,
                &model,
                &data,
                &args,
                &["--modes", "is invalid: it lists mode 1 twice"],
            );
        }
    }
    refused_into(
        &s,
        &model,
        &data,
        &["--from-frequency", "--params", "k2,k2"],
        &["--params k2,k2 is invalid: it lists k2 twice"],
    );
    // `auto` chooses the parameters itself: it is not one more name to recommend
    for value in ["auto,k1", "k2,auto"] {
        let args = ["--from-frequency", "--params", value];
        refused_into(
            &s,
            &model,
            &data,
            &args,
            &[&format!("--params {value} is invalid"), "alone"],
        );
        let run = identify(&model, &data, &args);
        assert!(!String::from_utf8_lossy(&run.stderr).contains("or give `auto`"));
    }
}

#[test]
fn a_model_with_every_parameter_fixed_is_refused_with_or_without_from_frequency() {
    let s = Scratch::new("all-fixed");
    let fixed = MODEL.replacen(
        "k2 = 1.0e4    # rotational stiffness, N m/rad",
        "k2 = 1.0e4\nfixed = [\"k1\", \"k2\"]",
        1,
    );
    assert_ne!(fixed, MODEL);
    let model = s.write("m.toml", &fixed);
    let data = s.write("d.csv", &simulated_csv(&all_dofs(&paper_model(1.0, 1.0))));
    let message = "m.toml: the model identifies no parameter";
    for args in [
        &["--from-frequency"][..],
        &["--from-frequency", "--frequency-noise", "0.001"],
        &["--n", "38", "--m", "7", "--weighting", "inverse"],
    ] {
        refused_into(&s, &model, &data, args, &[message]);
    }
}

/// A mode whose frequency lies beyond what its parameter reaches (three times the lap's sixth
/// frequency: no joint stiffness gets the model there) is written as identify writes a mode it
/// cannot stand behind: its rows with empty corrections and condition, a warning with the
/// reason, the other modes identified; never `inf` in the CSV.
#[test]
fn a_mode_beyond_its_parameters_reach_is_written_without_corrections_or_inf() {
    let dir = Scratch::new("beyond-reach");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/lap2d/bolted");
    let measured = std::fs::read_to_string(fixture.join("measured.csv")).unwrap();
    let far = measured.replace("974.2194316", "2922.658");
    assert_ne!(far, measured);
    let data = dir.write("measured.csv", &far);
    let out = dir.path("freq.csv");
    let run = identify(
        &fixture.join("model.toml"),
        &data,
        &["--from-frequency", "--out", common::s(&out)],
    );
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: mode 6: 2922.6580 Hz is beyond the reach of"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(!text.contains("inf"), "{text}");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12, "6 modes x (k1, k2)");
    for row in &rows {
        let empty =
            ["correction", "relative_correction", "condition"].map(|c| row[col(c)].is_empty());
        if row[0] == "6" {
            assert_eq!(empty, [true; 3], "{row:?}");
        } else {
            assert_eq!(empty, [false; 3], "{row:?}");
        }
    }
}

#[test]
fn a_huge_frequency_noise_is_echoed_compactly() {
    let s = Scratch::new("huge-noise");
    let model = s.write("m.toml", MODEL);
    let data = s.write("d.csv", &simulated_csv(&all_dofs(&paper_model(1.0, 1.0))));
    refused_into(
        &s,
        &model,
        &data,
        &["--from-frequency", "--frequency-noise", "1e308"],
        &["--frequency-noise 1e308 is invalid"],
    );
}

/// `text` (a measured-modes CSV) with every shape value times `scale`: the same shapes in
/// another unit.
fn scaled_values(text: &str, scale: f64) -> String {
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let value = header.split(',').position(|h| h == "value").unwrap();
    let mut out = format!("{header}\n");
    for line in lines {
        let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
        if let Ok(v) = fields[value].parse::<f64>() {
            fields[value] = format!("{:e}", v * scale);
        }
        out += &fields.join(",");
        out.push('\n');
    }
    out
}

/// The shapes' unit does not change what identify reports: the same noise-free modes with
/// every shape value times 1e150 (cond(W S) was inf and the resolution NaN) or 1e-200 (the
/// resolution was 0 instead of 1) give the corrections, conditions and resolutions of the
/// unscaled data, to a relative 1e-9.
#[test]
fn the_shapes_unit_changes_neither_condition_nor_resolution() {
    let s = Scratch::new("shape-unit");
    let model = s.write("m.toml", MODEL);
    let csv = simulated_csv(&all_dofs(&paper_model(1.0, 1.0)));
    let run = |name: &str, text: &str| -> Vec<Vec<f64>> {
        let data = s.write(&format!("{name}.csv"), text);
        let out = s.path(&format!("{name}-out.csv"));
        let args = [
            "--n",
            "38",
            "--m",
            "7",
            "--weighting",
            "inverse",
            "--out",
            out.to_str().unwrap(),
        ];
        let o = identify(&model, &data, &args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = std::fs::read_to_string(&out).unwrap();
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let cols = ["correction", "condition", "resolution"]
            .map(|c| header.iter().position(|h| *h == c).unwrap());
        lines
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                cols.iter().map(|&c| f[c].parse().unwrap()).collect()
            })
            .collect()
    };
    let reference = run("unit", &csv);
    assert_eq!(reference.len(), 8, "4 modes x 2 parameters");
    for scale in [1e150, 1e-200] {
        let rows = run(&format!("{scale:e}"), &scaled_values(&csv, scale));
        assert_eq!(rows.len(), reference.len());
        for (row, want) in rows.iter().zip(&reference) {
            for (v, w) in row.iter().zip(want) {
                assert!(
                    w.is_finite() && (v - w).abs() <= 1e-9 * w.abs(),
                    "x{scale:e}: {row:?} against {want:?}"
                );
            }
        }
    }
}

/// Standard errors and stated noise outside their documented relative range (1e-12 to 1 of
/// what they qualify, docs/formats.md): a `frequency_std` of 1e308 (the propagated errors
/// were inf), a `value_std` of 1e-300 on one row, `--frequency-noise 1e-300` to identify and
/// `--shape-noise 1e-300` to diagnose (chi^2 inf or NaN with exit 0). Each is refused with exit
/// 2, naming the file and line or the flag, and the value; nothing is written.
#[test]
fn standard_errors_outside_their_relative_range_are_refused() {
    let s = Scratch::new("std-range");
    let model = s.write("m.toml", MODEL);
    let csv = simulated_csv(&all_dofs(&paper_model(1.0, 1.0)));
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    let rows: Vec<&str> = lines.collect();
    let with_std = |frequency_std: &str, tiny_row: usize| {
        let mut text = format!("{header},frequency_std,value_std\n");
        for (i, row) in rows.iter().enumerate() {
            let value_std = if i == tiny_row { "1e-300" } else { "0.01" };
            text += &format!("{row},{frequency_std},{value_std}\n");
        }
        text
    };
    let out = s.path("out.csv");
    let cases = [
        (
            with_std("1e308", usize::MAX),
            vec![],
            "d.csv:2: frequency_std = 1e308 is invalid: it must be from 1e-12 to 1 times frequency_hz",
        ),
        (
            with_std("0.01", 3),
            vec![],
            "d.csv:5: value_std = 1e-300 is invalid: it must be 0 or from 1e-12 to 1 times the mode's largest |value|",
        ),
        (
            csv.clone(),
            vec!["--frequency-noise", "1e-300"],
            "--frequency-noise 1e-300 is invalid: a relative standard deviation from 1e-12 to below 1",
        ),
    ];
    for (text, extra, needle) in cases {
        let data = s.write("d.csv", &text);
        let mut args = vec!["--n", "38", "--m", "7", "--weighting", "inverse"];
        args.extend(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = identify(&model, &data, &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(needle), "`{needle}` not in: {err}");
        assert!(err.len() < 200, "{err}");
        assert!(!out.exists(), "{needle}: nothing is written");
    }
    let data = s.write("d.csv", &csv);
    let json = s.path("report.json");
    let err = common::refused(
        &[
            "diagnose",
            "--model",
            common::s(&model),
            "--measured",
            common::s(&data),
            "--shape-noise",
            "1e-300",
            "--json",
            common::s(&json),
        ],
        &[
            "--shape-noise 1e-300 is invalid: the stated noise is a relative standard deviation, from 1e-12 to below 1",
        ],
    );
    assert!(err.len() < 200, "{err}");
    assert!(!json.exists());
}
