//! Properties of the surfaces added in the fourth round (part of the `fuzz` suite, same case
//! counts): mutated levels files (`amplitude`), lap tables (`[joint.lap]`), standard-error
//! columns of measured-modes CSVs (`identify`) and `solid` specimens. Each run exits 0 or 2,
//! never 101 or a signal; an accepted input writes only finite numbers (a standard error the
//! data do not determine is `NaN` by the format's definition, never inf); a refused one writes
//! nothing.

use std::path::Path;

use proptest::prelude::*;

use super::{
    exits_cleanly, identified_or_nothing_written, jointid, measured_csv, mutate_toml, names,
    wild_number,
};
use crate::common::scratch;
use crate::messages::LAP_MODEL;

/// The fuzz suite's case count, from a fixed seed: `cargo test` runs the same cases on every
/// machine (`PROPTEST_RNG_SEED` explores others).
fn config() -> ProptestConfig {
    let seed = std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(42);
    ProptestConfig {
        rng_seed: proptest::test_runner::RngSeed::Fixed(seed),
        ..super::config()
    }
}

const UNESP: &str = include_str!("../../../models/unesp-bert.toml");
const MODES: &str = include_str!("../../../results/unesp-bert/modes_0p05V.csv");

/// Four levels of the same modes at growing accelerations.
const LEVELS: &str = "model = \"model.toml\"\n\
    [[level]]\nexcitation = 0.05\nmodes = \"modes.csv\"\nacceleration = [1.0, 2.0]\n\
    [[level]]\nexcitation = 0.1\nmodes = \"modes.csv\"\nacceleration = [2.1, 4.3]\n\
    [[level]]\nexcitation = 0.2\nmodes = \"modes.csv\"\nacceleration = [4.4, 8.1]\n\
    [[level]]\nexcitation = 0.4\nmodes = \"modes.csv\"\nacceleration = [9.0, 15.5]\n";

/// `text` with one number inside an array (`[a, b]`) replaced by `value`, on line `line`.
fn in_array(text: &str, line: usize, value: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let i = line % lines.len();
    if let (Some(open), Some(comma)) = (lines[i].find('['), lines[i].find(',')) {
        lines[i] = format!("{}{value}{}", &lines[i][..=open], &lines[i][comma..]);
    }
    lines.join("\n")
}

/// No NaN or inf in a written CSV, but `NaN` in a standard-error column (`*std`, `*_se`): the
/// amplitude tables' way to say the data do not determine it.
fn finite_but_undetermined_std(path: &Path) -> Result<(), TestCaseError> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    for line in lines {
        for (i, field) in line.split(',').enumerate() {
            let lower = field.to_ascii_lowercase();
            let column = header.get(i).copied().unwrap_or("");
            let std = column.ends_with("std") || column.ends_with("_se");
            prop_assert!(
                !lower.ends_with("inf"),
                "{} in {}: {}",
                field,
                path.display(),
                line
            );
            prop_assert!(
                lower != "nan" || std,
                "{} in {}: {}",
                field,
                path.display(),
                line
            );
        }
    }
    Ok(())
}

/// The measured modes of `measured_csv` with standard errors: 1e-4 of each frequency, 1e-3 of
/// each shape value.
fn csv_with_std() -> String {
    let text = measured_csv();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let cols: Vec<&str> = header.split(',').collect();
    let at = |name: &str| cols.iter().position(|c| *c == name).unwrap();
    let (f, v) = (at("frequency_hz"), at("value"));
    let mut out = format!("{header},frequency_std,value_std\n");
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        let num = |i: usize| fields[i].parse::<f64>().unwrap();
        out += &format!(
            "{line},{:e},{:e}\n",
            1e-4 * num(f),
            1e-3 * num(v).abs().max(1e-3)
        );
    }
    out
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn levels_files_fit_or_are_refused(
        text in prop_oneof![
            mutate_toml(LEVELS),
            (0usize..30, wild_number()).prop_map(|(line, v)| in_array(LEVELS, line, &v)),
        ],
    ) {
        let dir = scratch("fuzz", "levels");
        std::fs::write(dir.join("model.toml"), UNESP).unwrap();
        std::fs::write(dir.join("modes.csv"), MODES).unwrap();
        std::fs::write(dir.join("levels.toml"), &text).unwrap();
        let out = jointid(&dir, &["amplitude", "levels.toml", "--out", "out"]);
        if exits_cleanly(&out)? {
            for name in names(&dir.join("out")).iter().filter(|n| n.ends_with(".csv")) {
                finite_but_undetermined_std(&dir.join("out").join(name))?;
            }
        } else {
            prop_assert_eq!(names(&dir), vec!["levels.toml", "model.toml", "modes.csv"]);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn lap_tables_build_or_are_refused(text in mutate_toml(LAP_MODEL)) {
        if let Ok(model) = jointid::model::from_toml(&text, Path::new("lap.toml")) {
            let mats = model.assemble();
            prop_assert!(mats.k.is_finite() && mats.m.is_finite());
            // Solved or refused as ill scaled, never a panic.
            if let Ok(modal) = jointid::modal::ModalSolution::solve(&mats) {
                prop_assert!(modal.values().iter().all(|v| v.is_finite()));
            }
        }
    }

    #[test]
    fn standard_error_columns_are_used_or_refused(
        line in 1usize..150,
        column in prop_oneof![Just("frequency_std"), Just("value_std")],
        value in wild_number(),
        from_frequency in any::<bool>(),
    ) {
        let dir = super::workdir("std");
        let text = csv_with_std();
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let index = lines[0].split(',').position(|c| c == column).unwrap();
        let i = line.min(lines.len() - 1);
        let mut fields: Vec<String> = lines[i].split(',').map(str::to_string).collect();
        fields[index] = value;
        lines[i] = fields.join(",");
        std::fs::write(dir.join("meas.csv"), lines.join("\n")).unwrap();
        let mut args = vec!["identify", "--model", "model.toml", "--measured", "meas.csv", "--out", "out.csv"];
        if from_frequency {
            args.push("--from-frequency");
        } else {
            args.extend(["--n", "10", "--m", "5", "--weighting", "inverse"]);
        }
        let out = jointid(&dir, &args);
        identified_or_nothing_written(&dir, &out)?;
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn solid_specimens_are_made_or_refused(text in mutate_toml(crate::solid::LAP)) {
        let dir = scratch("fuzz", "solid");
        std::fs::write(dir.join("lap.toml"), &text).unwrap();
        let out = jointid(&dir, &["solid", "lap.toml", "--out", "made"]);
        if exits_cleanly(&out)? {
            // What solid writes, its own reader accepts, with finite matrices.
            let model = jointid::model::from_path(&dir.join("made/model.toml"));
            prop_assert!(model.is_ok(), "{:?}", model.err());
            let mats = model.unwrap().assemble();
            prop_assert!(mats.k.is_finite() && mats.m.is_finite());
        } else {
            prop_assert_eq!(names(&dir), vec!["lap.toml".to_string()]);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
