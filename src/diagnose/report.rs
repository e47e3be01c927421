//! What a diagnosis reports: error summaries of a model against the data, per-mode joint
//! corrections with their uncertainties, candidates, the verdict. Plain data, serialisable.

use serde::Serialize;

use super::fit::{Estimate, Fitted, Noise};
use super::noise::NoiseEstimate;
use super::pairing::mac;
use crate::identify::propagation::{jacobian, propagated_std};
use crate::identify::{Identifier, Projector, Settings};
use crate::measured::MeasuredModes;
use crate::stats::chi2_sf;
use crate::structure::observe;

/// The verdict of a diagnosis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// The calibrated model explains the data within the working noise (stated, or estimated
    /// from the data); no candidate is significant.
    None,
    /// A candidate is significant and brings the residual down to the noise.
    Effect,
    /// The best candidate explains the data, but another does nearly as well (within
    /// [`super::AMBIGUITY_MARGIN`] of information criterion): the data cannot tell them apart.
    Ambiguous,
    /// The residual stays above the noise with every candidate: an effect outside the library
    /// ([`Report::pattern`] says where the residual sits).
    Unexplained,
    /// The joint whose parameters scale as (f / f_ref)^alpha is the best explanation, and no
    /// static candidate comes close: the paper's frequency-dependent joint (the candidate
    /// `frequency_dependence`; [`Report::trend`] shows the per-mode corrections).
    #[serde(rename = "frequency_dependent")]
    FrequencyDependent,
}

/// The chi^2 one measured mode carries in a fit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeChi2 {
    /// Measured mode r.
    pub mode: usize,
    /// From its frequency.
    pub frequency: f64,
    /// From its shape components.
    pub shape: f64,
}

/// A stretch of the beams where the shape residual concentrates.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Region {
    /// First abscissa of the stretch, m.
    pub x_from: f64,
    /// Last abscissa, m.
    pub x_to: f64,
    /// Its share of the shape chi^2 (all modes).
    pub share: f64,
}

/// Where the remaining misfit sits: by mode (frequency against shape) and along the beams.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidualPattern {
    /// Every mode, the largest total chi^2 first.
    pub modes: Vec<ModeChi2>,
    /// The frequencies' share of the whole chi^2.
    pub frequency_share: f64,
    /// Stretches of the sensors whose summed squared shape residual (over modes) is at least
    /// half the largest one, the largest share first.
    pub regions: Vec<Region>,
}

impl ResidualPattern {
    /// The pattern of `fitted` on `measured` under `noise` with shape floor `floor` (the
    /// residuals weighted as in the fit, module `fit`).
    pub fn of(fitted: &Fitted, measured: &MeasuredModes, noise: Noise, floor: f64) -> Self {
        let residuals = super::fit::residuals(fitted, measured);
        let mut shape = residuals.shape.iter();
        let mut modes = Vec::new();
        let mut at_x: Vec<(f64, f64)> = Vec::new();
        for (m, rf) in measured.modes().iter().zip(&residuals.frequency) {
            let mut shape_chi2 = 0.0;
            for p in &m.points {
                let Some(&(u, e)) = shape.next() else { break };
                let z2 = (e / (noise.shape * (u * u + floor * floor).sqrt())).powi(2);
                shape_chi2 += z2;
                match at_x.iter_mut().find(|(x, _)| (x - p.x).abs() <= 1e-9) {
                    Some(slot) => slot.1 += z2,
                    None => at_x.push((p.x, z2)),
                }
            }
            modes.push(ModeChi2 {
                mode: m.mode,
                frequency: (rf / noise.frequency).powi(2),
                shape: shape_chi2,
            });
        }
        let frequency_total: f64 = modes.iter().map(|m| m.frequency).sum();
        let total = frequency_total + modes.iter().map(|m| m.shape).sum::<f64>();
        modes.sort_by(|a, b| (b.frequency + b.shape).total_cmp(&(a.frequency + a.shape)));
        at_x.sort_by(|a, b| a.0.total_cmp(&b.0));
        let shape_total: f64 = at_x.iter().map(|(_, z)| z).sum();
        let largest = at_x.iter().map(|(_, z)| *z).fold(0.0, f64::max);
        let mut regions: Vec<Region> = Vec::new();
        let mut open = false;
        for &(x, z) in &at_x {
            if largest > 0.0 && z >= 0.5 * largest {
                match regions.last_mut() {
                    Some(r) if open => {
                        r.x_to = x;
                        r.share += z / shape_total;
                    }
                    _ => regions.push(Region {
                        x_from: x,
                        x_to: x,
                        share: z / shape_total,
                    }),
                }
                open = true;
            } else {
                open = false;
            }
        }
        regions.sort_by(|a, b| b.share.total_cmp(&a.share));
        ResidualPattern {
            modes,
            frequency_share: if total > 0.0 {
                frequency_total / total
            } else {
                0.0
            },
            regions,
        }
    }
}

/// How one measured mode compares with its paired model mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeError {
    /// Measured mode r.
    pub mode: usize,
    /// Paired model mode (deformable numbering, 1 = first elastic).
    pub model_mode: usize,
    /// Measured frequency, Hz.
    pub frequency_measured_hz: f64,
    /// Model frequency, Hz.
    pub frequency_model_hz: f64,
    /// (model - measured) / measured, %.
    pub frequency_error_pct: f64,
    /// MAC over the measured DOFs.
    pub mac: f64,
    /// RMS of (c y_model - y_measured) over the measured DOFs, % of the largest measured
    /// component.
    pub shape_rms_pct: f64,
    /// The model shape at the measured DOFs, scaled and signed to the measured one (for
    /// plots; not in the JSON).
    #[serde(skip)]
    pub model_shape: Vec<f64>,
}

/// How a model compares with all the data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorSummary {
    /// RMS of the relative frequency errors, %.
    pub frequency_rms_pct: f64,
    /// Smallest MAC.
    pub min_mac: f64,
    /// Mean MAC.
    pub mean_mac: f64,
    /// chi^2 of the residuals under the stated noise.
    pub chi2: f64,
    /// Its degrees of freedom (data minus fitted unknowns).
    pub dof: usize,
    /// chi^2 / dof (about 1 at the noise level; below 1 where the shape floor dominates).
    pub chi2_per_dof: f64,
    /// P(chi^2_dof > chi^2): the goodness of fit.
    pub p_value: f64,
    /// The fitted parameters (joints, then effect), with standard errors.
    pub parameters: Vec<Estimate>,
    /// Mode by mode.
    pub modes: Vec<ModeError>,
}

impl ErrorSummary {
    /// The summary of a fitted (or as-given) model; its goodness of fit under the scale of
    /// `noise`.
    pub fn of(fitted: &Fitted, measured: &MeasuredModes, noise: &NoiseEstimate) -> Self {
        let y = fitted.modal.vectors();
        let modes: Vec<ModeError> = measured
            .modes()
            .iter()
            .enumerate()
            .map(|(r, m)| {
                let s = fitted.pairing.model_index[r];
                let model: Vec<f64> = m.points.iter().map(|p| p.read_column(y, s)).collect();
                let sign = if model.iter().zip(&m.values).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                let peak = m.peak();
                let ss: f64 = model
                    .iter()
                    .zip(&m.values)
                    .map(|(a, b)| (fitted.scales[r] * sign * a - b).powi(2))
                    .sum();
                let f = fitted.modal.frequency_hz(s);
                ModeError {
                    mode: m.mode,
                    model_mode: s + 1 - fitted.configured.structure.rigid,
                    frequency_measured_hz: m.frequency_hz,
                    frequency_model_hz: f,
                    frequency_error_pct: 100.0 * (f - m.frequency_hz) / m.frequency_hz,
                    mac: mac(&model, &m.values),
                    shape_rms_pct: 100.0 * (ss / m.values.len() as f64).sqrt() / peak,
                    model_shape: model.iter().map(|a| fitted.scales[r] * sign * a).collect(),
                }
            })
            .collect();
        let count = modes.len() as f64;
        ErrorSummary {
            frequency_rms_pct: (modes
                .iter()
                .map(|e| e.frequency_error_pct.powi(2))
                .sum::<f64>()
                / count)
                .sqrt(),
            min_mac: modes.iter().map(|e| e.mac).fold(f64::INFINITY, f64::min),
            mean_mac: modes.iter().map(|e| e.mac).sum::<f64>() / count,
            chi2: fitted.chi2,
            dof: fitted.dof,
            chi2_per_dof: fitted.chi2 / fitted.dof as f64,
            p_value: noise.fit_p_value(fitted.chi2, fitted.dof),
            parameters: fitted.estimates.clone(),
            modes,
        }
    }
}

/// The paper's per-mode correction of one joint parameter on one mode (eq. (13)) on a
/// calibrated model, with its standard deviation from the stated noise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeCorrection {
    /// Measured mode r.
    pub mode: usize,
    /// Measured frequency, Hz.
    pub frequency_hz: f64,
    /// Parameter name.
    pub param: String,
    /// Delta p_i / p_i (None when S_r is rank deficient).
    pub relative: Option<f64>,
    /// Delta p_i.
    pub correction: Option<f64>,
    /// Standard deviation of Delta p_i, first order.
    pub std: Option<f64>,
    /// Whether p_i + Delta p_i stays positive. The per-mode step is linear in Delta p: a
    /// correction that would make a stiffness zero or negative is beyond its reach, a sign
    /// that the mode disagrees with the model in more than the joint; it is shown as the
    /// paper's method gives it, marked.
    pub physical: Option<bool>,
}

/// Whether the per-mode corrections of one parameter are consistent with a constant.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Flatness {
    /// Parameter name.
    pub param: String,
    /// Weighted mean of Delta p_i over the modes.
    pub mean: f64,
    /// chi^2 of the deviations from that mean (dof = modes - 1).
    pub chi2: f64,
    /// Its degrees of freedom.
    pub dof: usize,
    /// P(chi^2_dof > chi2): small when the corrections really change from mode to mode.
    pub p_value: f64,
    /// Weighted least-squares slope of Delta p_i against the mode's frequency, per kHz.
    pub slope_per_khz: f64,
    /// Standard error of the slope: a slope beyond 3 of them is a trend with frequency.
    pub slope_se_per_khz: f64,
    /// chi^2 of the deviations from the weighted straight line in frequency (dof = modes - 2).
    pub line_chi2: f64,
    /// P(chi^2_{modes - 2} > line_chi2) (1 with two modes): small when a straight line does
    /// not carry the corrections either.
    pub line_p_value: f64,
}

/// The per-mode corrections of every joint parameter on the calibrated `fitted` model.
pub fn per_mode_corrections(
    fitted: &Fitted,
    measured: &MeasuredModes,
    noise: Noise,
    settings: Settings,
) -> Vec<ModeCorrection> {
    let structure = &fitted.configured.structure;
    let params = structure.identified();
    let values: Vec<f64> = params.iter().map(|p| p.value).collect();
    let Ok(identifier) = Identifier::new(&fitted.modal, params.clone(), structure.rigid, settings)
    else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for (r, m) in measured.modes().iter().enumerate() {
        let s = fitted.pairing.model_index[r];
        let outcome = identifier.identify_paired(m, s).ok();
        // A mode paired beyond the basis (fewer sensors than the mode's index) has no
        // per-mode system: its correction is absent, not a panic.
        let std = Projector::new(&observe(identifier.basis(), &m.points))
            .ok()
            .filter(|_| s < settings.n)
            .and_then(|projector| {
                let jac = jacobian(
                    &projector,
                    &identifier.mode_system(s),
                    &m.values,
                    m.lambda(),
                )?;
                let shape_variance = noise.shape * noise.shape;
                Some(propagated_std(
                    &jac,
                    &m.values,
                    m.lambda(),
                    &values,
                    shape_variance,
                    noise.frequency * noise.frequency,
                ))
            });
        for (i, p) in params.iter().enumerate() {
            let relative = outcome
                .as_ref()
                .and_then(|o| o.relative.as_ref().ok())
                .map(|z| z[i]);
            out.push(ModeCorrection {
                mode: m.mode,
                frequency_hz: m.frequency_hz,
                param: p.name.clone(),
                relative,
                correction: relative.map(|z| z * p.value),
                std: std.as_ref().map(|s| s[i]),
                physical: relative.map(|z| 1.0 + z > 0.0),
            });
        }
    }
    out
}

/// Flatness of the per-mode corrections of every parameter.
pub fn flatness(corrections: &[ModeCorrection]) -> Vec<Flatness> {
    let mut names: Vec<&str> = corrections.iter().map(|c| c.param.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    names
        .into_iter()
        .filter_map(|name| {
            let points: Vec<(f64, f64, f64)> = corrections
                .iter()
                .filter(|c| c.param == name)
                .filter_map(|c| {
                    Some((
                        c.frequency_hz / 1000.0,
                        c.correction?,
                        c.std.filter(|s| *s > 0.0)?,
                    ))
                })
                .collect();
            if points.len() < 2 {
                return None;
            }
            let wsum: f64 = points.iter().map(|(_, _, s)| 1.0 / (s * s)).sum();
            let mean = points.iter().map(|(_, x, s)| x / (s * s)).sum::<f64>() / wsum;
            let chi2: f64 = points
                .iter()
                .map(|(_, x, s)| ((x - mean) / s).powi(2))
                .sum();
            let fbar = points.iter().map(|(f, _, s)| f / (s * s)).sum::<f64>() / wsum;
            let sxx: f64 = points
                .iter()
                .map(|(f, _, s)| (f - fbar).powi(2) / (s * s))
                .sum();
            let sxy: f64 = points
                .iter()
                .map(|(f, x, s)| (f - fbar) * (x - mean) / (s * s))
                .sum();
            let dof = points.len() - 1;
            let (slope, slope_se) = if sxx > 0.0 {
                (sxy / sxx, 1.0 / sxx.sqrt())
            } else {
                (0.0, f64::INFINITY)
            };
            let line_chi2 = (chi2 - slope * slope * sxx).max(0.0);
            Some(Flatness {
                param: name.to_string(),
                mean,
                chi2,
                dof,
                p_value: chi2_sf(chi2, dof as f64),
                slope_per_khz: slope,
                slope_se_per_khz: slope_se,
                line_chi2,
                line_p_value: if dof > 1 {
                    chi2_sf(line_chi2, (dof - 1) as f64)
                } else {
                    1.0
                },
            })
        })
        .collect()
}

/// One candidate's fit, or why it failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CandidateReport {
    /// Candidate name.
    pub name: String,
    /// The effect's fitted parameters (joints are in `summary`).
    pub parameters: Vec<Estimate>,
    /// Fitted size in the unit of `jointid simulate --effect` (see `describe`).
    pub size: Option<f64>,
    /// Standard error of the size.
    pub size_se: Option<f64>,
    /// What the effect is and what its size means.
    pub describe: String,
    /// chi^2 with the candidate.
    pub chi2: Option<f64>,
    /// Degrees of freedom with the candidate.
    pub dof: Option<usize>,
    /// Likelihood-ratio statistic chi^2(joint only) - chi^2(with candidate).
    pub lrt: Option<f64>,
    /// The criterion: the likelihood-ratio p-value P(chi^2_k > lrt), Bonferroni-adjusted for
    /// the number of candidates tried (smaller is more significant).
    pub criterion: Option<f64>,
    /// Goodness of fit with the candidate, P(chi^2_dof > chi^2).
    pub fit_p_value: Option<f64>,
    /// Lack of fit of the frequencies alone under the working noise, P(chi^2_dof > chi^2_f)
    /// (module `noise`).
    pub frequency_p_value: Option<f64>,
    /// Structure of the shape residuals along the structure, P(N(0, 1) > Z) (module
    /// `whiteness`): small when neighbouring residuals share their sign.
    pub whiteness_p_value: Option<f64>,
    /// The fit's summary with the candidate.
    #[serde(skip)]
    pub summary: Option<ErrorSummary>,
    /// Why the fit failed, if it did.
    pub error: Option<String>,
    /// Why the fitted size is not physically plausible (the candidate is then excluded from
    /// the selection), if it is not.
    pub excluded: Option<String>,
}

/// A whole diagnosis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// none, effect, ambiguous, unexplained or frequency-dependent.
    pub verdict: Verdict,
    /// The selected candidate, when the verdict is `effect` (when `ambiguous`: the best of
    /// the contenders, whose fit is `after`).
    pub selected: Option<String>,
    /// When `ambiguous`: every candidate within the margin of the best, best first.
    pub contenders: Vec<String>,
    /// When `unexplained` or `frequency-dependent`: where the misfit of the joint-only fit
    /// sits, under the working noise.
    pub pattern: Option<ResidualPattern>,
    /// When `unexplained` or `frequency-dependent`: the per-mode corrections (before) that
    /// trend with frequency.
    pub trend: Vec<Flatness>,
    /// The statistical criterion, in words.
    pub criterion: String,
    /// The stated noise.
    pub noise: Noise,
    /// The noise estimated from the data, beside the stated; the selection used its working
    /// noise.
    pub noise_estimate: super::noise::NoiseEstimate,
    /// Pairing remarks: modes paired with another model mode than their number.
    pub warnings: Vec<String>,
    /// The model as given (joints uncalibrated).
    pub initial: ErrorSummary,
    /// The invariant joint calibrated on every mode, no effect.
    pub before: ErrorSummary,
    /// With the selected effect (equal to `before` when none is selected).
    pub after: ErrorSummary,
    /// Every candidate.
    pub candidates: Vec<CandidateReport>,
    /// The paper's per-mode corrections on the `before` model.
    pub per_mode_before: Vec<ModeCorrection>,
    /// The same on the `after` model.
    pub per_mode_after: Vec<ModeCorrection>,
    /// Flatness of the per-mode corrections before.
    pub flatness_before: Vec<Flatness>,
    /// Flatness after.
    pub flatness_after: Vec<Flatness>,
    /// The per-mode identification settings (n, m, weighting).
    pub per_mode_settings: String,
    /// The shape-noise floor used in the weights.
    pub shape_floor: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn correction(mode: usize, f_hz: f64, value: f64, std: f64) -> ModeCorrection {
        ModeCorrection {
            mode,
            frequency_hz: f_hz,
            param: "k1".into(),
            relative: Some(value),
            correction: Some(value),
            std: Some(std),
            physical: Some(true),
        }
    }

    #[test]
    fn corrections_on_a_line_have_its_slope_and_no_chi2_about_it() {
        // 2 + 3 f (f in kHz) at 0.5, 1, 2, 4 kHz, std 0.1.
        let list: Vec<ModeCorrection> = [0.5, 1.0, 2.0, 4.0]
            .iter()
            .enumerate()
            .map(|(r, f)| correction(r + 1, 1000.0 * f, 2.0 + 3.0 * f, 0.1))
            .collect();
        let f = &flatness(&list)[0];
        assert!((f.slope_per_khz - 3.0).abs() < 1e-12, "{f:?}");
        assert!(f.line_chi2 < 1e-18, "{f:?}");
        assert!((f.line_p_value - 1.0).abs() < 1e-12);
        // Mean 2 + 3 * 1.875 = 7.625; chi^2 about it sum (3 (f - 1.875) / 0.1)^2.
        assert!((f.mean - 7.625).abs() < 1e-12);
        let expected: f64 = [0.5, 1.0, 2.0, 4.0]
            .iter()
            .map(|x: &f64| (30.0 * (x - 1.875)).powi(2))
            .sum();
        assert!((f.chi2 - expected).abs() < 1e-9 * expected);
    }

    #[test]
    fn a_zigzag_about_a_constant_has_no_slope_and_all_its_chi2_about_the_line() {
        // +1, -1, -1, +1 about 5 at symmetric frequencies: slope 0, chi^2 4 about both.
        let list = vec![
            correction(1, 1000.0, 6.0, 1.0),
            correction(2, 2000.0, 4.0, 1.0),
            correction(3, 3000.0, 4.0, 1.0),
            correction(4, 4000.0, 6.0, 1.0),
        ];
        let f = &flatness(&list)[0];
        assert!(f.slope_per_khz.abs() < 1e-12);
        assert!((f.chi2 - 4.0).abs() < 1e-12 && (f.line_chi2 - 4.0).abs() < 1e-12);
        assert!((f.line_p_value - chi2_sf(4.0, 2.0)).abs() < 1e-15);
    }
}
