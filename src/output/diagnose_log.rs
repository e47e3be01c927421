//! The lines of `jointid diagnose`'s log on stderr: one per step of the diagnosis
//! ([`crate::diagnose::progress`]), behind the seconds since the start.

use crate::diagnose::{Pass, Step};

/// The line of `step` of pass `pass`, `seconds` into the run.
pub fn line(seconds: f64, pass: Pass, step: &Step) -> String {
    let pass = match pass {
        Pass::Calibration => "calibration".to_string(),
        Pass::Candidates => "candidates".to_string(),
        Pass::Together(n) => format!("{n} causes together"),
    };
    let what = match step {
        Step::Calibrated { chi2, iterations } => {
            format!("joint calibrated: chi^2 {chi2:.1} after {iterations} iterations")
        }
        Step::Iteration {
            candidate,
            variant,
            iteration,
            chi2,
        } => {
            let variant = variant.map(|v| format!(" ({v})")).unwrap_or_default();
            format!("{candidate}{variant} iteration {iteration}: chi^2 {chi2:.1}")
        }
        Step::Fitted {
            candidate,
            outcome: Ok(deviance),
        } => format!("{candidate} fitted: deviance {deviance:.1}"),
        Step::Fitted {
            candidate,
            outcome: Err(reason),
        } => format!("{candidate} not fitted: {reason}"),
        Step::Noise(e) => {
            let (f, a) = (e.working.frequency, e.working.shape);
            if e.from_data {
                format!(
                    "yardstick: the data's own standard errors (RMS frequency {f:.3e}, shape {a:.3e})"
                )
            } else if e.stated_kept {
                format!(
                    "yardstick: the stated noise kept (frequency {f:.3e}, shape {a:.3e}): no model's residuals pass the checks"
                )
            } else {
                format!(
                    "yardstick estimated from the residuals of {}: frequency {f:.3e}, shape {a:.3e}",
                    e.from_model
                )
            }
        }
    };
    format!("diagnose [{seconds:8.1} s] {pass}: {what}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_names_the_time_the_pass_and_the_step() {
        assert_eq!(
            line(
                12.345,
                Pass::Candidates,
                &Step::Iteration {
                    candidate: "frequency_dependence",
                    variant: Some("one alpha"),
                    iteration: 3,
                    chi2: 212.44,
                }
            ),
            "diagnose [    12.3 s] candidates: frequency_dependence (one alpha) iteration 3: chi^2 212.4"
        );
        assert_eq!(
            line(
                1.0,
                Pass::Calibration,
                &Step::Iteration {
                    candidate: "sensor_mass",
                    variant: None,
                    iteration: 1,
                    chi2: 9.96,
                }
            ),
            "diagnose [     1.0 s] calibration: sensor_mass iteration 1: chi^2 10.0"
        );
        let why = crate::diagnose::candidate::CandidateError::Undetermined(
            "the data do not determine it".into(),
        );
        assert_eq!(
            line(
                0.0,
                Pass::Together(2),
                &Step::Fitted {
                    candidate: "joint_mass",
                    outcome: Err(&why),
                }
            ),
            "diagnose [     0.0 s] 2 causes together: joint_mass not fitted: the data do not determine it"
        );
    }
}
