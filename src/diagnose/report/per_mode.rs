//! The paper's per-mode corrections (eq. (13)) of the joint on a calibrated model, with their
//! first-order standard deviations, and whether they are constant across the modes (the
//! paper's question: does the joint's stiffness change with frequency?). A mode whose shape
//! components cannot carry eq. (10)-(13) (fewer sensors than the basis, a rank-deficient
//! S_r) gets the one parameter it is most sensitive to from its frequency alone
//! ([`crate::identify::frequency_only`]), the others held: the question is then still
//! answered for any number of sensors. The sub-basis of n pairs is solved again where the
//! fitted model's solution holds fewer (a sparse model's fit computes the pairs it needs).

use rayon::prelude::*;
use serde::Serialize;

use crate::diagnose::fit::{Fitted, Noise};
pub use crate::identify::frequency_only::Source;
use crate::identify::frequency_only::{self, Choice};
use crate::identify::propagation::{jacobian, propagated_std};
use crate::identify::reach::Ends;
use crate::identify::{Identifier, Projector, Settings, Weighting};
use crate::measured::{MeasuredMode, MeasuredModes};
use crate::modal::reduced;
use crate::stats::chi2_sf;
use crate::structure::{Structure, observe};

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
    /// What determined it.
    pub source: Source,
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

/// The per-mode corrections of every joint parameter on the calibrated `fitted` model. A
/// mode read from a model of its own ([`Fitted::own`]: the joint at the mode's frequency) is
/// corrected on that model, relative to the joint's value there.
pub fn per_mode_corrections(
    fitted: &Fitted,
    measured: &MeasuredModes,
    noise: Noise,
    settings: Settings,
) -> Vec<ModeCorrection> {
    let identifier_of = |r: usize| {
        let structure = fitted.structure_of(r);
        let params = structure.identified();
        let modal = fitted.modal_of(r);
        // The sub-basis of n pairs: a sparse solution may hold fewer (the pairs the fit
        // needed), solved again for n.
        let wider;
        let modal = if modal.len() < settings.n && modal.len() < modal.dof_count() {
            wider = reduced::lowest(structure, &[], settings.n).ok()?;
            &wider
        } else {
            modal
        };
        Identifier::new(modal, params, structure.rigid, settings).ok()
    };
    let shared = if fitted.own.is_empty() {
        match identifier_of(0) {
            Some(i) => Some(i),
            None => return Vec::new(),
        }
    } else {
        None
    };
    // The ends of the frequency-only search's reach, solved once for the modes of one model.
    let reach = fitted.pairing.model_index.iter().max().map_or(0, |s| s + 1);
    let ends = fitted
        .own
        .is_empty()
        .then(|| Ends::new(&fitted.configured.structure, reach));
    // Modes in parallel: each may solve its structure several times (its own model, the
    // frequency-only identification's Newton steps).
    let correct = |(r, m): (usize, &MeasuredMode)| -> Vec<ModeCorrection> {
        let own = if shared.is_none() {
            identifier_of(r)
        } else {
            None
        };
        let Some(identifier) = shared.as_ref().or(own.as_ref()) else {
            return Vec::new();
        };
        let params = fitted.structure_of(r).identified();
        let values: Vec<f64> = params.iter().map(|p| p.value).collect();
        let s = fitted.pairing.model_index[r];
        let outcome = identifier.identify_paired(m, s).ok();
        let relatives = outcome
            .as_ref()
            .and_then(|o| o.relative.as_ref().ok())
            .cloned();
        if relatives.is_none()
            && let Ok(f) = frequency_only::identify_within(
                fitted.structure_of(r),
                s,
                m.mode,
                m.frequency_hz,
                Some(noise.frequency),
                Choice::MostSensitive,
                ends.as_ref().filter(|_| fitted.own.is_empty()),
            )
        {
            return from_frequency(m, &params, &f);
        }
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
        params
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let relative = relatives.as_ref().map(|z| z[i]);
                ModeCorrection {
                    mode: m.mode,
                    frequency_hz: m.frequency_hz,
                    param: p.name.clone(),
                    relative,
                    correction: relative.map(|z| z * p.value),
                    std: std.as_ref().map(|s| s[i]),
                    physical: relative.map(|z| 1.0 + z > 0.0),
                    source: Source::Shape,
                }
            })
            .collect()
    };
    each_mode(
        measured,
        fitted.configured.structure.reduced.is_some(),
        correct,
    )
}

/// `correct` of every measured mode, in parallel, or one mode after another when `in_turn`:
/// on a model solved through a reduced model (a large one), a mode's frequency search may
/// solve the full model at its reach's far ends, and two such solves at once hold two factors
/// beside the reduced model's own (on the 516,516-DOF lap of bench/, 21 GB where one at a
/// time stays near 10).
fn each_mode(
    measured: &MeasuredModes,
    in_turn: bool,
    correct: impl Fn((usize, &MeasuredMode)) -> Vec<ModeCorrection> + Sync + Send,
) -> Vec<ModeCorrection> {
    if in_turn {
        return measured
            .modes()
            .iter()
            .enumerate()
            .flat_map(correct)
            .collect();
    }
    measured
        .modes()
        .par_iter()
        .enumerate()
        .flat_map_iter(correct)
        .collect()
}

/// The corrections of mode `m` identified from its frequency alone (`f`): its one parameter,
/// the others held.
fn from_frequency(
    m: &MeasuredMode,
    params: &[crate::structure::Parameter],
    f: &frequency_only::FrequencyOutcome,
) -> Vec<ModeCorrection> {
    params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let own = i == f.param;
            ModeCorrection {
                mode: m.mode,
                frequency_hz: m.frequency_hz,
                param: p.name.clone(),
                relative: own.then_some(f.relative),
                correction: own.then_some(f.relative * p.value),
                std: f.std.filter(|_| own).map(|sd| sd * p.value),
                physical: own.then_some(true),
                source: if own { Source::Frequency } else { Source::Held },
            }
        })
        .collect()
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

/// The per-mode settings of a diagnosis when none are given: n = the fewest measured DOFs of
/// a mode (at least the rigid-body modes plus 2, at most the model's DOFs), m = min(n - rigid,
/// 6), inverse weighting.
pub fn default_settings(model: &Structure, measured: &MeasuredModes) -> Settings {
    let fewest = measured
        .modes()
        .iter()
        .map(|m| m.points.len())
        .min()
        .unwrap_or(0);
    let rigid = model.rigid;
    let n = fewest.min(model.dof_count()).max(rigid + 2);
    Settings {
        n,
        m: (n - rigid).min(6),
        weighting: Weighting::Inverse,
    }
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
            source: Source::Shape,
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
