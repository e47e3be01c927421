//! What a plan is asked: the candidate sites, how many sensors, the modes to be measured and
//! their expected noise, the sensors already fixed, the objective and the method's settings.
//! Each setting is checked where it is parsed or against the model; an error names the
//! setting, the value and what is allowed ([`SettingError`]).

use std::fmt;

use serde::Serialize;

use crate::identify::Settings;
use crate::input::SettingError;
use crate::random::NoiseKind;

/// Where sensors may go.
#[derive(Debug, Clone, PartialEq)]
pub enum Sites {
    /// The transverse DOF (`w`) of every node.
    Nodes,
    /// The `w` DOF of the node at each of these abscissae, m.
    Positions(Vec<f64>),
    /// These DOF labels (any direction, an external model's labels).
    Labels(Vec<String>),
}

impl Sites {
    /// `nodes`, a comma-separated list of abscissae (m) or of DOF labels.
    pub fn parse(text: &str) -> Result<Sites, SettingError> {
        let text = text.trim();
        if text == "nodes" {
            return Ok(Sites::Nodes);
        }
        let items: Vec<&str> = text.split(',').map(str::trim).collect();
        if items.iter().any(|s| s.is_empty()) {
            return Err(SettingError::new(
                "sites",
                format!("\"{text}\""),
                "it must be `nodes`, a comma-separated list of positions (m) or of DOF labels",
            ));
        }
        match items
            .iter()
            .map(|s| s.parse::<f64>())
            .collect::<Result<Vec<f64>, _>>()
        {
            Ok(x) => Ok(Sites::Positions(x)),
            Err(_) => Ok(Sites::Labels(items.iter().map(|s| s.to_string()).collect())),
        }
    }
}

/// The scalar summary of the spreads that the search minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// The largest relative standard deviation over every determinate (mode, parameter).
    Worst,
    /// Their mean.
    Mean,
    /// The geometric mean over the determinate modes of det(C_r)^(1/2q), C_r the covariance
    /// of the mode's relative corrections (D-optimality, mode by mode).
    Det,
}

impl Objective {
    /// Every objective, in the order of the help.
    pub const ALL: [Objective; 3] = [Objective::Worst, Objective::Mean, Objective::Det];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Objective::Worst => "worst",
            Objective::Mean => "mean",
            Objective::Det => "det",
        }
    }

    /// The objective named `text`.
    pub fn parse(text: &str) -> Result<Objective, SettingError> {
        Objective::ALL
            .into_iter()
            .find(|o| o.name() == text)
            .ok_or_else(|| SettingError::new("objective", text, "it must be worst, mean or det"))
    }
}

impl fmt::Display for Objective {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The counts of sensors to place: `6` or a range `4-6`.
pub fn parse_counts(text: &str) -> Result<Vec<usize>, SettingError> {
    let bad = || {
        SettingError::new(
            "sensors",
            text,
            "it must be a count of sensors (`6`) or a range (`4-6`), from 1",
        )
    };
    let number = |s: &str| s.trim().parse::<usize>().ok().filter(|&n| n >= 1);
    match text.split_once('-') {
        None => number(text).map(|n| vec![n]).ok_or_else(bad),
        Some((a, b)) => match (number(a), number(b)) {
            (Some(a), Some(b)) if a <= b => Ok((a..=b).collect()),
            _ => Err(bad()),
        },
    }
}

/// The method's settings: held as given, or chosen with each layout among every n, m and
/// weighting the layout allows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SettingsChoice {
    /// Held.
    Given(Settings),
    /// Chosen with the layout.
    Chosen,
}

/// A planning request, before it meets the model.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// Candidate sites.
    pub sites: Sites,
    /// The counts of sensors to place, ascending.
    pub counts: Vec<usize>,
    /// The deformable modes to be measured (1-based).
    pub modes: Vec<usize>,
    /// Relative standard deviation of the measured frequencies (> 0).
    pub frequency_noise: f64,
    /// Relative error of every shape component (> 0): the standard deviation under a
    /// gaussian noise, the half-width under a uniform one (as a study reads it).
    pub shape_noise: f64,
    /// The noise distribution (as a study's `monte_carlo.noise`).
    pub noise: NoiseKind,
    /// Sensors that stay: positions (m) or DOF labels, each a candidate.
    pub fixed: Vec<String>,
    /// The objective.
    pub objective: Objective,
    /// n, m and the weighting.
    pub settings: SettingsChoice,
}

impl Request {
    /// The noise levels checked: finite and > 0.
    pub fn check_noise(&self) -> Result<(), SettingError> {
        for (name, value) in [
            ("frequency_noise", self.frequency_noise),
            ("shape_noise", self.shape_noise),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(SettingError::new(
                    name,
                    value,
                    "it must be > 0 (a relative standard deviation; the plan weighs the noise of the frequency against that of the shape)",
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sites_counts_and_objectives_parse_or_say_what_is_allowed() {
        assert_eq!(Sites::parse("nodes").unwrap(), Sites::Nodes);
        assert_eq!(
            Sites::parse("0, 0.35,0.7").unwrap(),
            Sites::Positions(vec![0.0, 0.35, 0.7])
        );
        assert_eq!(
            Sites::parse("3:w,7:w").unwrap(),
            Sites::Labels(vec!["3:w".into(), "7:w".into()])
        );
        assert_eq!(parse_counts("6").unwrap(), vec![6]);
        assert_eq!(parse_counts("3-5").unwrap(), vec![3, 4, 5]);
        for bad in ["0", "5-3", "x", "2-"] {
            assert_eq!(
                parse_counts(bad).unwrap_err().to_string(),
                format!(
                    "sensors = {bad} is invalid: it must be a count of sensors (`6`) or a range (`4-6`), from 1"
                )
            );
        }
        assert_eq!(
            Objective::parse("best").unwrap_err().to_string(),
            "objective = best is invalid: it must be worst, mean or det"
        );
        assert_eq!(Objective::parse("det").unwrap(), Objective::Det);
    }
}
