//! Figures of a diagnosis (`jointid diagnose --plots DIR`):
//! - `shape_mode{r}.svg`: measured against model mode shape, joint calibrated and after;
//! - `frequency_error.svg`: frequency error per mode, joint calibrated and after;
//! - `corrections_{param}.svg`: the paper's per-mode corrections against frequency, before and
//!   after, with their standard deviations under the stated noise;
//! - `stiffness_{param}.svg`: the per-mode joint parameter (calibrated value plus the mode's
//!   correction) against frequency, with the band mean +- 2 standard deviations that a
//!   frequency-independent joint would keep to (the paper's question);
//! - `candidates.svg`: every candidate's significance (-log10 of its adjusted p-value) against the
//!   threshold of the selection.

use super::plot::{LineAxes, PlotError, Series, bars, lines, svg};
use super::study_report::{Figure, unit_of};
use crate::diagnose::report::ModeCorrection;
use crate::diagnose::{ALPHA, Report};
use crate::measured::MeasuredModes;
use crate::structure::Direction;

fn corrections_series(name: &str, list: &[ModeCorrection], param: &str) -> Series {
    let points: Vec<(&ModeCorrection, f64)> = list
        .iter()
        .filter(|c| c.param == param)
        .filter_map(|c| Some((c, c.correction?)))
        .collect();
    Series {
        name: name.to_string(),
        points: points.iter().map(|(c, v)| (c.frequency_hz, *v)).collect(),
        errors: Some(points.iter().map(|(c, _)| c.std.unwrap_or(0.0)).collect()),
        line: true,
    }
}

/// Every figure of a diagnosis of `measured` against `model`.
pub fn diagnose_figures(
    report: &Report,
    measured: &MeasuredModes,
) -> Result<Vec<Figure>, PlotError> {
    let mut out = shape_figures(report, measured)?;
    out.push(frequency_error_figure(report)?);
    out.extend(correction_figures(report)?);
    out.extend(candidates_figure(report)?);
    Ok(out)
}

/// Measured against model shape of every mode, joint calibrated and after.
fn shape_figures(report: &Report, measured: &MeasuredModes) -> Result<Vec<Figure>, PlotError> {
    let mut out = Vec::new();
    for ((m, before), after) in measured
        .modes()
        .iter()
        .zip(&report.before.modes)
        .zip(&report.after.modes)
    {
        // Translations when measured, else rotations.
        let kind = if m.points.iter().any(|p| !p.direction.is_rotation()) {
            m.points
                .iter()
                .find(|p| !p.direction.is_rotation())
                .map_or(Direction::W, |p| p.direction)
        } else {
            m.points.first().map_or(Direction::Theta, |p| p.direction)
        };
        let pick = |values: &[f64]| -> Vec<(f64, f64)> {
            let mut points: Vec<(f64, f64)> = m
                .points
                .iter()
                .zip(values)
                .filter(|(p, _)| p.direction == kind)
                .map(|(p, &v)| (p.x, v))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            points
        };
        let series = [
            Series {
                name: format!("model before (MAC {:.4})", before.mac),
                points: pick(&before.model_shape),
                errors: None,
                line: true,
            },
            Series {
                name: format!("model after (MAC {:.4})", after.mac),
                points: pick(&after.model_shape),
                errors: None,
                line: true,
            },
            Series {
                name: "measured".into(),
                points: pick(&m.values),
                errors: None,
                line: false,
            },
        ];
        let unit = format!("{kind} (scaled to the measured shape)");
        let title = format!(
            "mode {}: measured {:.2} Hz, model {:.2} Hz before, {:.2} Hz after",
            m.mode, m.frequency_hz, before.frequency_model_hz, after.frequency_model_hz
        );
        let body = svg((1000, 450), |area| {
            lines(
                area,
                &title,
                &LineAxes {
                    x_desc: "position along the chain x (m)".into(),
                    y_desc: unit.clone(),
                    log_x: false,
                    log_y: false,
                    reference: None,
                    clip_errors: false,
                },
                &series,
            )
        })?;
        out.push(Figure {
            name: format!("shape_mode{}.svg", m.mode),
            caption: format!(
                "Mode {}: measured shape against the model's, with the joint calibrated and after.",
                m.mode
            ),
            svg: body,
        });
    }
    Ok(out)
}

/// The frequency error of every mode, joint calibrated and after.
fn frequency_error_figure(report: &Report) -> Result<Figure, PlotError> {
    let error_series = |name: &str, modes: &[crate::diagnose::report::ModeError]| Series {
        name: name.into(),
        points: modes
            .iter()
            .map(|e| (e.mode as f64, e.frequency_error_pct))
            .collect(),
        errors: None,
        line: true,
    };
    let series = [
        error_series("joint calibrated", &report.before.modes),
        error_series("after", &report.after.modes),
    ];
    let noise = 100.0 * report.noise.frequency;
    let body = svg((900, 450), |area| {
        lines(
            area,
            "Frequency error per mode",
            &LineAxes {
                x_desc: "measured mode r".into(),
                y_desc: "(f model - f measured) / f measured (%)".into(),
                log_x: false,
                log_y: false,
                reference: Some((0.0, format!("0 (stated noise +-{noise} %)"))),
                clip_errors: false,
            },
            &series,
        )
    })?;
    Ok(Figure {
        name: "frequency_error.svg".into(),
        caption: "Frequency error of every mode, joint calibrated and after.".into(),
        svg: body,
    })
}

/// The per-mode corrections and the per-mode joint values of every parameter.
fn correction_figures(report: &Report) -> Result<Vec<Figure>, PlotError> {
    let mut out = Vec::new();
    let mut params: Vec<String> = report
        .per_mode_before
        .iter()
        .map(|c| c.param.clone())
        .collect();
    params.sort();
    params.dedup();
    for param in &params {
        let series = [
            corrections_series("joint calibrated", &report.per_mode_before, param),
            corrections_series("after", &report.per_mode_after, param),
        ];
        let title = format!(
            "Per-mode correction of {param} (paper's method, {})",
            report.per_mode_settings
        );
        let body = svg((1000, 480), |area| {
            lines(
                area,
                &title,
                &LineAxes {
                    x_desc: "measured frequency (Hz)".into(),
                    y_desc: format!("Delta {param} ({})", unit_of(param)),
                    log_x: true,
                    log_y: false,
                    reference: Some((0.0, "no correction".into())),
                    clip_errors: true,
                },
                &series,
            )
        })?;
        out.push(Figure {
            name: format!("corrections_{}.svg", param.replace('.', "_")),
            caption: format!("The paper's per-mode correction of {param} against frequency, +- one standard deviation under the stated noise (bars cut at the edge): a trend that disappears after the effect is added was the missing effect, not the joint."),
            svg: body,
        });
    }
    for param in &params {
        if let Some(figure) = stiffness_figure(report, param)? {
            out.push(figure);
        }
    }
    Ok(out)
}

/// Every candidate's (and combination's) significance against the rule's threshold (none when
/// no candidate was fitted).
fn candidates_figure(report: &Report) -> Result<Option<Figure>, PlotError> {
    let fitted: Vec<_> = report
        .candidates
        .iter()
        .filter(|c| c.criterion.is_some())
        .collect();
    if !fitted.is_empty() {
        let labels: Vec<String> = fitted.iter().map(|c| c.name.clone()).collect();
        // -log10 of the adjusted p-value, a p-value of 0 (below the smallest double) at 300.
        let values: Vec<f64> = fitted
            .iter()
            .map(|c| -c.criterion.unwrap_or(1.0).max(1e-300).log10())
            .collect();
        let critical = -ALPHA.log10();
        let label = format!("significant above {critical:.0} (p = {ALPHA})");
        let selected = report
            .selected
            .as_ref()
            .and_then(|name| labels.iter().position(|l| l == name))
            .map(|i| (i, "selected"));
        let body = svg((900, 450), |area| {
            bars(
                area,
                "Candidates and causes together: significance against the model each extends",
                "-log10 adjusted p-value",
                &labels,
                &values,
                (critical, &label),
                selected,
            )
        })?;
        return Ok(Some(Figure {
            name: "candidates.svg".into(),
            caption: format!(
                "Every candidate's significance, -log10 of its likelihood-ratio p-value (each model with its own discrepancy: F where one was estimated) adjusted for the {} hypotheses tried up to its step (Bonferroni; log scale); a combination (a + b) is tested against the model it extends (a). Above the dashed line a cause is significant; the selected model is the clearly best one, extended while a further cause is.",
                report.hypotheses
            ),
            svg: body,
        }));
    }
    Ok(None)
}

/// The per-mode value of `param` (calibrated joint-only value plus the paper's correction)
/// against frequency, with the band of a frequency-independent joint: the weighted mean of
/// the corrections +- 2 standard deviations of each mode's correction.
fn stiffness_figure(report: &Report, param: &str) -> Result<Option<Figure>, PlotError> {
    let Some(calibrated) = report
        .before
        .parameters
        .iter()
        .find(|e| e.name == param)
        .map(|e| e.value)
    else {
        return Ok(None);
    };
    let Some(flat) = report.flatness_before.iter().find(|f| f.param == param) else {
        return Ok(None);
    };
    let points: Vec<(f64, f64, f64)> = report
        .per_mode_before
        .iter()
        .filter(|c| c.param == param)
        .filter_map(|c| Some((c.frequency_hz, c.correction?, c.std?)))
        .collect();
    if points.len() < 2 {
        return Ok(None);
    }
    let level = calibrated + flat.mean;
    let band = |sign: f64| -> Vec<(f64, f64)> {
        points
            .iter()
            .map(|(f, _, s)| (*f, level + sign * 2.0 * s))
            .collect()
    };
    let series = [
        Series {
            name: "frequency-independent joint: mean + 2 std".into(),
            points: band(1.0),
            errors: None,
            line: true,
        },
        Series {
            name: "frequency-independent joint: mean - 2 std".into(),
            points: band(-1.0),
            errors: None,
            line: true,
        },
        Series {
            name: "per mode (+- 1 std)".into(),
            points: points
                .iter()
                .map(|(f, c, _)| (*f, calibrated + c))
                .collect(),
            errors: Some(points.iter().map(|(_, _, s)| *s).collect()),
            line: false,
        },
    ];
    let title = format!(
        "Per-mode {param} against frequency: slope {:.3e} +- {:.3e} per kHz",
        flat.slope_per_khz, flat.slope_se_per_khz
    );
    let body = svg((1000, 480), |area| {
        lines(
            area,
            &title,
            &LineAxes {
                x_desc: "measured frequency (Hz)".into(),
                y_desc: format!("{param} ({})", unit_of(param)),
                log_x: false,
                log_y: false,
                reference: Some((level, "weighted mean over the modes".into())),
                clip_errors: true,
            },
            &series,
        )
    })?;
    Ok(Some(Figure {
        name: format!("stiffness_{}.svg", param.replace('.', "_")),
        caption: format!(
            "The joint's {param} mode by mode (the calibrated value plus the paper's per-mode correction, joint only) against frequency. A frequency-independent joint keeps inside the band, the weighted mean +- 2 standard deviations of each mode's correction; points leaving it along a trend are the paper's frequency-dependent joint (verdict here: {})",
            serde_json::to_value(report.verdict)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default()
        ),
        svg: body,
    }))
}
