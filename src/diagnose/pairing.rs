//! Pairing measured modes with model modes: by the modal assurance criterion
//! MAC(a, b) = (a . b)^2 / ((a . a)(b . b)) over the measured points, among the model modes
//! whose frequency lies within a window around the measured frequency, or by numbers the user
//! gives.
//!
//! With three or four sensors a MAC alone cannot tell modes apart: some high model mode always
//! resembles any short vector. The frequency window keeps the candidates to those a calibration
//! can reach; a measured mode with no candidate that resembles it is an error naming it, never
//! a silent pairing with whatever mode is left.

use crate::measured::MeasuredModes;
use crate::modal::ModalSolution;
use crate::optim::assignment::assign;

/// Smallest MAC accepted for a pair.
pub const MIN_MAC: f64 = 0.5;

/// Default half-width of the frequency window, relative to the measured frequency.
pub const DEFAULT_WINDOW: f64 = 0.5;

/// How measured modes are paired with model modes.
#[derive(Debug, Clone, PartialEq)]
pub struct PairingRule {
    /// Half-width of the frequency window: a model mode is a candidate for measured mode r
    /// when |f_model - f_r| <= window f_r.
    pub window: f64,
    /// Pairs given by the user: (measured mode r, model deformable mode t), 1-based. A mode
    /// listed here is paired with that model mode whatever its frequency and MAC.
    pub given: Vec<(usize, usize)>,
}

impl Default for PairingRule {
    fn default() -> Self {
        Self {
            window: DEFAULT_WINDOW,
            given: Vec::new(),
        }
    }
}

/// MAC of two vectors (0 when either is zero).
pub fn mac(a: &[f64], b: &[f64]) -> f64 {
    let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    if aa == 0.0 || bb == 0.0 {
        0.0
    } else {
        ab * ab / (aa * bb)
    }
}

/// The model mode (0-based index of the eigensolution) of every measured mode, in the order of
/// the measured modes, with its MAC.
#[derive(Debug, Clone, PartialEq)]
pub struct Pairing {
    /// Model mode index per measured mode.
    pub model_index: Vec<usize>,
    /// MAC of each pair.
    pub mac: Vec<f64>,
}

/// A model mode near a measured one, for the message of an unpaired mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Near {
    /// The model's deformable mode number (1-based).
    pub mode: usize,
    /// Its frequency, Hz.
    pub frequency_hz: f64,
    /// Its MAC with the measured mode.
    pub mac: f64,
    /// The measured mode paired with it, if another took it.
    pub taken_by: Option<usize>,
}

/// Why a measured mode has no partner.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Unpaired {
    /// No model mode in the window resembles it.
    #[error(
        "measured mode {mode} ({frequency_hz:.4} Hz) has no credible partner: no model mode within +-{pct}% of its frequency has a MAC >= {MIN_MAC} and is left free by the other measured modes ({near}); widen the window (--pairing-window), pair it by number (--pair {mode}:t), or leave the mode out",
        pct = 100.0 * window,
        near = describe(nearest)
    )]
    NoPartner {
        /// Measured mode r.
        mode: usize,
        /// Its frequency.
        frequency_hz: f64,
        /// The window used.
        window: f64,
        /// The model modes nearest in frequency.
        nearest: Vec<Near>,
    },
    /// A given pair names a mode that does not exist.
    #[error("--pair {mode}:{model_mode}: {reason}")]
    BadGiven {
        /// Measured mode r.
        mode: usize,
        /// Model mode t.
        model_mode: usize,
        /// Why.
        reason: String,
    },
}

fn describe(nearest: &[Near]) -> String {
    if nearest.is_empty() {
        return "the model has no deformable mode".into();
    }
    let list: Vec<String> = nearest
        .iter()
        .map(|n| {
            let taken = n
                .taken_by
                .map(|r| format!(", paired with measured mode {r}"))
                .unwrap_or_default();
            format!(
                "model mode {} at {:.4} Hz, MAC {:.3}{taken}",
                n.mode, n.frequency_hz, n.mac
            )
        })
        .collect();
    format!("nearest: {}", list.join("; "))
}

/// Pairs every measured mode: the given pairs first, then the rest among the deformable model
/// modes (index >= `rigid`) within the window with a MAC >= [`MIN_MAC`], each model mode used
/// once: as many pairs as possible, and among those the largest total MAC
/// ([`crate::optim::assignment`]; a greedy choice by decreasing MAC can take the only partner
/// of another mode, which three sensors make common). `modal` holds every model mode the window can reach.
pub fn pair(
    modal: &ModalSolution,
    measured: &MeasuredModes,
    rigid: usize,
    rule: &PairingRule,
) -> Result<Pairing, Unpaired> {
    let y = modal.vectors();
    let count = measured.modes().len();
    let mac_with = |r: usize, t: usize| {
        let m = &measured.modes()[r];
        let model: Vec<f64> = m.points.iter().map(|p| p.read_column(y, t)).collect();
        mac(&m.values, &model)
    };
    let mut model_index = vec![usize::MAX; count];
    let mut used = vec![false; modal.len()];
    for &(mode, t) in &rule.given {
        let bad = |reason: String| Unpaired::BadGiven {
            mode,
            model_mode: t,
            reason,
        };
        let r = measured
            .modes()
            .iter()
            .position(|m| m.mode == mode)
            .ok_or_else(|| bad(format!("the data have no mode {mode}")))?;
        let index = (t + rigid)
            .checked_sub(1)
            .filter(|&i| t >= 1 && i < modal.len())
            .ok_or_else(|| {
                bad(format!(
                    "the model's deformable modes computed are 1 to {}",
                    modal.len() - rigid
                ))
            })?;
        if used[index] || model_index[r] != usize::MAX {
            return Err(bad("each measured and model mode may be paired once".into()));
        }
        model_index[r] = index;
        used[index] = true;
    }
    // the rest: as many pairs as the window and the MAC bar allow, of largest total MAC
    let weights: Vec<Vec<Option<f64>>> = measured
        .modes()
        .iter()
        .enumerate()
        .map(|(r, m)| {
            (0..modal.len())
                .map(|t| {
                    let free = t >= rigid && !used[t] && model_index[r] == usize::MAX;
                    let near = (modal.frequency_hz(t) - m.frequency_hz).abs()
                        <= rule.window * m.frequency_hz;
                    (free && near)
                        .then(|| mac_with(r, t))
                        .filter(|&value| value >= MIN_MAC)
                })
                .collect()
        })
        .collect();
    for (r, t) in assign(&weights).into_iter().enumerate() {
        if let Some(t) = t {
            model_index[r] = t;
            used[t] = true;
        }
    }
    if let Some(r) = model_index.iter().position(|&i| i == usize::MAX) {
        let m = &measured.modes()[r];
        let mut nearest: Vec<Near> = (rigid..modal.len())
            .map(|t| Near {
                mode: t + 1 - rigid,
                frequency_hz: modal.frequency_hz(t),
                mac: mac_with(r, t),
                taken_by: model_index
                    .iter()
                    .position(|&i| i == t)
                    .map(|q| measured.modes()[q].mode),
            })
            .collect();
        nearest.sort_by(|a, b| {
            (a.frequency_hz - m.frequency_hz)
                .abs()
                .total_cmp(&(b.frequency_hz - m.frequency_hz).abs())
        });
        nearest.truncate(3);
        return Err(Unpaired::NoPartner {
            mode: m.mode,
            frequency_hz: m.frequency_hz,
            window: rule.window,
            nearest,
        });
    }
    let mac = (0..count).map(|r| mac_with(r, model_index[r])).collect();
    Ok(Pairing { model_index, mac })
}

/// The highest frequency the window can reach from the measured modes, Hz: the model must be
/// solved up to it.
pub fn reach_hz(measured: &MeasuredModes, rule: &PairingRule) -> f64 {
    measured
        .modes()
        .iter()
        .map(|m| m.frequency_hz * (1.0 + rule.window))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::MeasuredModes;
    use crate::model::fixtures::paper_model;
    use crate::simulate::exact_modes;
    use crate::structure::Observation;

    fn points(model: &crate::structure::Structure, dofs: &[usize]) -> Vec<Observation> {
        dofs.iter()
            .map(|&d| Observation::dof(&model.dofs, d))
            .collect()
    }

    #[test]
    fn exact_modes_pair_with_themselves_and_a_swap_is_found() {
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let dofs: Vec<usize> = (0..38).step_by(2).collect();
        let exact = exact_modes(&modal, 2, &[1, 2, 3, 4], &points(&model, &dofs));
        let rule = PairingRule::default();
        let p = pair(&modal, &exact, 2, &rule).unwrap();
        assert_eq!(p.model_index, vec![2, 3, 4, 5]);
        assert!(p.mac.iter().all(|&m| (m - 1.0).abs() < 1e-12));
        // Two modes whose frequencies were swapped in the test report: with a window wide
        // enough to reach both, the shapes decide.
        let mut modes = exact.modes().to_vec();
        let (f1, f2) = (modes[1].frequency_hz, modes[2].frequency_hz);
        modes[1].frequency_hz = f2;
        modes[2].frequency_hz = f1;
        let wide = PairingRule {
            window: 3.0,
            ..rule.clone()
        };
        let swapped = pair(&modal, &MeasuredModes::new(modes.clone()), 2, &wide).unwrap();
        assert_eq!(swapped.model_index, vec![2, 3, 4, 5]);
        // Given pairs override.
        let given = PairingRule {
            given: vec![(2, 3), (3, 2)],
            ..wide
        };
        let forced = pair(&modal, &MeasuredModes::new(modes), 2, &given).unwrap();
        assert_eq!(forced.model_index, vec![2, 4, 3, 5]);
    }

    #[test]
    fn three_sensors_cannot_pair_a_mode_with_a_high_model_mode() {
        // A fine mesh and three sensors: many high model modes resemble any three-component
        // vector; the window keeps the pairing to the right mode.
        let mut chain = crate::model::fixtures::paper_chain(1e7, 1e4);
        for beam in &mut chain.beams {
            beam.elements = (beam.length / 0.005).round() as usize;
        }
        let model = chain.build();
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let sensors: Vec<Observation> = [0.02, 0.27, 0.48]
            .iter()
            .map(|&x| model.dofs.at_x(x, crate::structure::Direction::W).unwrap())
            .collect();
        // The test's structure: the joint 30% stiffer than the model's, shapes with 2% errors.
        let truth = model.with_delta(&[3e6, 3e3]);
        let errors = crate::simulate::Errors {
            shape: 0.02,
            frequency: 0.0,
            kind: crate::study::NoiseKind::Gaussian,
            seed: 5,
        };
        let exact = crate::simulate::measured_modes(
            &ModalSolution::solve(&truth.assemble()).unwrap(),
            2,
            &[1, 2, 3, 4, 5, 6],
            &sensors,
            errors,
        );
        // Modes 3 to 6 each have some other model mode with a MAC above 0.99 on three sensors.
        let lookalikes = (0..6)
            .filter(|&r| {
                let m = &exact.modes()[r];
                (2..modal.len()).filter(|&t| t != r + 2).any(|t| {
                    let model: Vec<f64> = m
                        .points
                        .iter()
                        .map(|p| p.read_column(modal.vectors(), t))
                        .collect();
                    mac(&m.values, &model) > 0.99
                })
            })
            .count();
        assert!(lookalikes >= 3, "{lookalikes}");
        // By MAC alone (no window) some mode pairs wrongly; within the window none does.
        let anywhere = PairingRule {
            window: f64::INFINITY,
            ..PairingRule::default()
        };
        let by_mac = pair(&modal, &exact, 2, &anywhere).unwrap();
        assert_ne!(by_mac.model_index, vec![2, 3, 4, 5, 6, 7]);
        let p = pair(&modal, &exact, 2, &PairingRule::default()).unwrap();
        assert_eq!(p.model_index, vec![2, 3, 4, 5, 6, 7]);
    }

    #[test]
    fn a_mode_with_no_partner_in_the_window_is_named() {
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let dofs: Vec<usize> = (0..38).collect();
        let mut modes = exact_modes(&modal, 2, &[1], &points(&model, &dofs))
            .modes()
            .to_vec();
        // A shape like no mode.
        modes[0].values = (0..38).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let err = pair(
            &modal,
            &MeasuredModes::new(modes),
            2,
            &PairingRule::default(),
        )
        .unwrap_err();
        let text = err.to_string();
        assert!(
            text.starts_with("measured mode 1 (150.0539 Hz) has no credible partner: no model mode within +-50% of its frequency has a MAC >= 0.5 and is left free by the other measured modes (nearest: model mode 1 at 150.0539 Hz, MAC "),
            "{text}"
        );
        let bad = PairingRule {
            given: vec![(1, 99)],
            ..PairingRule::default()
        };
        let exact = exact_modes(&modal, 2, &[1], &points(&model, &dofs));
        assert_eq!(
            pair(&modal, &exact, 2, &bad).unwrap_err().to_string(),
            "--pair 1:99: the model's deformable modes computed are 1 to 36"
        );
    }

    #[test]
    fn mac_is_scale_and_sign_invariant() {
        assert!((mac(&[1.0, 2.0], &[-3.0, -6.0]) - 1.0).abs() < 1e-15);
        assert_eq!(mac(&[1.0, 0.0], &[0.0, 1.0]), 0.0);
    }
}
