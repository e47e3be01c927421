//! The settings of a diagnosis, checked where they are set.

use super::fit::Noise;
use super::pairing::PairingRule;
use crate::identify::Settings;
use crate::input::SettingError;

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
}

impl DiagnoseSettings {
    /// Checks every setting against its range: `frequency_noise` and `shape_noise` (the stated
    /// noise) in (0, 1), `pairing_window` in (0, [`LARGEST_WINDOW`]].
    pub fn check(&self) -> Result<(), SettingError> {
        let noise = "the stated noise is a relative standard deviation, above 0 and below 1";
        for (setting, value) in [
            ("frequency_noise", self.noise.frequency),
            ("shape_noise", self.noise.shape),
        ] {
            if !(value.is_finite() && value > 0.0 && value < 1.0) {
                return Err(SettingError::new(setting, value, noise));
            }
        }
        let window = self.pairing.window;
        if !(window.is_finite() && window > 0.0 && window <= LARGEST_WINDOW) {
            return Err(SettingError::new(
                "pairing_window",
                window,
                "it is a relative half-width above 0 and at most 10",
            ));
        }
        Ok(())
    }
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
        }
    }

    #[test]
    fn settings_out_of_range_are_refused_with_the_range() {
        assert!(settings(0.001, 0.02, 0.5).check().is_ok());
        assert!(settings(0.999, 0.999, LARGEST_WINDOW).check().is_ok());
        for (s, setting, value) in [
            (settings(0.0, 0.02, 0.5), "frequency_noise", "0"),
            (settings(0.001, 1.0, 0.5), "shape_noise", "1"),
            (settings(f64::NAN, 0.02, 0.5), "frequency_noise", "NaN"),
            (settings(0.001, 0.02, 0.0), "pairing_window", "0"),
            (settings(0.001, 0.02, 10.5), "pairing_window", "10.5"),
        ] {
            let e = s.check().unwrap_err();
            assert_eq!((e.setting, e.value.as_str()), (setting, value), "{e}");
        }
        assert_eq!(
            settings(-0.1, 0.02, 0.5).check().unwrap_err().to_string(),
            "frequency_noise = -0.1 is invalid: the stated noise is a relative standard deviation, above 0 and below 1"
        );
    }
}
