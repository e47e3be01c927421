//! The memory a study needs at its peak, known before it runs: cells run one after the
//! other, and one cell holds every trial's corrections (8 bytes per trial, mode and
//! parameter, plus a failure flag per trial and mode) and, while its statistics are
//! computed, a few columns of one value per trial.

use super::Study;

/// Columns of one value per trial that the statistics of a cell hold beside its samples.
const STATISTICS_COLUMNS: u64 = 3;

/// Peak bytes of a run of `study`.
pub fn peak_bytes(study: &Study) -> u64 {
    let trials = study.trials as u64;
    let modes = study.modes.len() as u64;
    let q = study.model.identified().len() as u64;
    trials * modes * (8 * q + 1) + STATISTICS_COLUMNS * 8 * trials
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn a_nine_beam_twenty_mode_study_of_1e7_trials_needs_about_26_gb() {
        // 8 joints (16 parameters), 20 modes: the fuzzing finding of 25.6 GB of samples.
        let beam = "[[beam]]\nlength = 0.2\nelements = 4\nyoungs_modulus = 2.1e11\ndensity = 7850.0\narea = 2.4e-3\nsecond_moment = 3.2e-7\n";
        let joint = "[[joint]]\nk1 = 1.0e7\nk2 = 1.0e4\n";
        let mut model = String::new();
        for b in 0..9 {
            if b > 0 {
                model.push_str(joint);
            }
            model.push_str(beam);
        }
        let structure = crate::model::from_toml(&model, Path::new("m.toml")).unwrap();
        let deltas: Vec<String> = structure
            .identified()
            .iter()
            .map(|p| format!("\"{}\" = 1.0", p.name))
            .collect();
        let modes: Vec<String> = (1..=20).map(|m| m.to_string()).collect();
        let text = format!(
            "name = \"big\"\nmodel = \"m.toml\"\n[truth]\ndelta = {{ {} }}\n[grid]\nmodes = [{}]\nn = [40]\nm = [20]\nnf = [0]\nweighting = [\"inverse\"]\nshape_noise = [0.01]\nfrequency_noise = [0.0]\n[monte_carlo]\ntrials = 10000000\nseed = 1\nnoise = \"uniform\"\n[output]\ncsv = \"o.csv\"\n",
            deltas.join(", "),
            modes.join(", ")
        );
        let study =
            Study::from_toml_with_model(&text, Path::new("s.toml"), structure, Path::new("m.toml"))
                .unwrap();
        assert_eq!(study.model.identified().len(), 16);
        let expected = 10_000_000u64 * 20 * (8 * 16 + 1) + 3 * 8 * 10_000_000;
        assert_eq!(peak_bytes(&study), expected);
        assert!((25.6e9..26.1e9).contains(&(expected as f64)));
    }
}
