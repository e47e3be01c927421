//! The settings of a diagnosis, checked where they are set.

use super::candidate::{Tier, registry};
use super::fit::Noise;
use super::pairing::PairingRule;
use crate::identify::Settings;
use crate::input::{Number, RELATIVE_STD, SettingError};

/// Largest relative half-width of the pairing window.
pub const LARGEST_WINDOW: f64 = 10.0;

/// Settings of a diagnosis.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagnoseSettings {
    /// The stated measurement noise: relative standard deviations in (0, 1).
    pub noise: Noise,
    /// How measured modes pair with model modes (window in (0, [`LARGEST_WINDOW`]]).
    pub pairing: PairingRule,
    /// The paper's per-mode identification (None: n = the fewest identified DOFs of a mode,
    /// at most N; m = min(n - 2, 6); inverse weighting).
    pub per_mode: Option<Settings>,
    /// Also search the richer candidates (the extended tier).
    pub extended: bool,
    /// Solve every eigenproblem on the full model, never on a reduced one (a check of the
    /// reduced model's results; module [`super::reduce`]).
    pub full_model: bool,
    /// Combinations of causes to try from the start beside the candidates alone (each the
    /// names of candidates that combine, at least two, none twice).
    pub causes: Vec<Vec<String>>,
}

impl DiagnoseSettings {
    /// Checks every setting against its range: `frequency_noise` and `shape_noise` (the stated
    /// noise) from 1e-12 ([`RELATIVE_STD`]) to below 1, `pairing_window` in
    /// (0, [`LARGEST_WINDOW`]].
    pub fn check(&self) -> Result<(), SettingError> {
        let noise = "the stated noise is a relative standard deviation, from 1e-12 to below 1";
        for (setting, value) in [
            ("frequency_noise", self.noise.frequency),
            ("shape_noise", self.noise.shape),
        ] {
            if !(value.is_finite() && value >= RELATIVE_STD.0 && value < 1.0) {
                return Err(SettingError::new(setting, Number(value), noise));
            }
        }
        for combination in &self.causes {
            check_causes(combination)?;
        }
        let window = self.pairing.window;
        if !(window.is_finite() && window > 0.0 && window <= LARGEST_WINDOW) {
            return Err(SettingError::new(
                "pairing_window",
                Number(window),
                "it is a relative half-width above 0 and at most 10",
            ));
        }
        Ok(())
    }
}

/// Refuses a combination of causes that names fewer than two, one twice, or one that is no
/// candidate that combines (the effects of the library and the layered lap).
fn check_causes(combination: &[String]) -> Result<(), SettingError> {
    let value = combination.join("+");
    let combining: Vec<&'static str> = registry()
        .iter()
        .filter(|c| c.part().is_some() && c.tier() != Tier::Outside)
        .map(|c| c.name())
        .collect();
    let allowed = format!(
        "two or more of {} joined by '+', each once",
        combining.join(", ")
    );
    if combination.len() < 2 {
        return Err(SettingError::new("causes", &value, &allowed));
    }
    for (i, name) in combination.iter().enumerate() {
        if !combining.contains(&name.as_str()) {
            return Err(SettingError::new(
                "causes",
                &value,
                format!("{name} is no candidate that combines; {allowed}"),
            ));
        }
        if combination[..i].contains(name) {
            return Err(SettingError::new(
                "causes",
                &value,
                format!("{name} is named twice; {allowed}"),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(frequency: f64, shape: f64, window: f64) -> DiagnoseSettings {
        DiagnoseSettings {
            noise: Noise { frequency, shape },
            pairing: PairingRule {
                window,
                given: Vec::new(),
            },
            per_mode: None,
            extended: false,
            full_model: false,
            causes: Vec::new(),
        }
    }

    #[test]
    fn settings_out_of_range_are_refused_with_the_range() {
        assert!(settings(0.001, 0.02, 0.5).check().is_ok());
        assert!(settings(0.999, 0.999, LARGEST_WINDOW).check().is_ok());
        assert!(settings(1e-12, 1e-12, 0.5).check().is_ok());
        for (s, setting, value) in [
            (settings(0.0, 0.02, 0.5), "frequency_noise", "0"),
            (settings(0.001, 1.0, 0.5), "shape_noise", "1"),
            (settings(f64::NAN, 0.02, 0.5), "frequency_noise", "NaN"),
            // Below 1e-12 the chi^2 of any residual overflows (it was inf or NaN, exit 0).
            (settings(0.001, 1e-300, 0.5), "shape_noise", "1e-300"),
            (settings(1e-13, 0.02, 0.5), "frequency_noise", "1e-13"),
            (settings(0.001, 0.02, 0.0), "pairing_window", "0"),
            (settings(0.001, 0.02, 10.5), "pairing_window", "10.5"),
        ] {
            let e = s.check().unwrap_err();
            assert_eq!((e.setting, e.value.as_str()), (setting, value), "{e}");
        }
        let with = |causes: &[&str]| DiagnoseSettings {
            causes: vec![causes.iter().map(|c| c.to_string()).collect()],
            ..settings(0.001, 0.02, 0.5)
        };
        assert!(with(&["layered_lap", "shear"]).check().is_ok());
        for (causes, reason) in [
            (&["shear", "shear"][..], "shear is named twice"),
            (&["shear", "glue"][..], "glue is no candidate that combines"),
            (&["shear"][..], "two or more of"),
            (
                &["shear", "local_stiffness"][..],
                "local_stiffness is no candidate",
            ),
        ] {
            let e = with(causes).check().unwrap_err();
            assert_eq!(e.setting, "causes");
            assert_eq!(e.value, causes.join("+"));
            assert!(e.to_string().contains(reason), "{e}");
        }
        assert_eq!(
            settings(-0.1, 0.02, 0.5).check().unwrap_err().to_string(),
            "frequency_noise = -0.1 is invalid: the stated noise is a relative standard deviation, from 1e-12 to below 1"
        );
    }
}
