//! Pairing measured modes with model modes by the modal assurance criterion,
//! MAC(a, b) = (a . b)^2 / ((a . a)(b . b)), over the measured DOFs.

use crate::measured::MeasuredModes;
use crate::modal::ModalSolution;

/// Smallest MAC accepted for a pair.
pub const MIN_MAC: f64 = 0.5;

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

/// A measured mode no model mode resembles.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "measured mode {mode} pairs with no model mode: its best MAC is {best_mac:.3} (model mode {best_mode}, below {MIN_MAC}); check the mode's shape rows and numbering, or leave it out"
)]
pub struct Unpaired {
    /// Measured mode r.
    pub mode: usize,
    /// Best MAC found.
    pub best_mac: f64,
    /// The model's deformable mode number with that MAC.
    pub best_mode: usize,
}

/// Pairs greedily by decreasing MAC among the deformable model modes (index >= `rigid`), each
/// model mode used once.
pub fn pair(
    modal: &ModalSolution,
    measured: &MeasuredModes,
    rigid: usize,
) -> Result<Pairing, Unpaired> {
    let y = modal.vectors();
    let macs: Vec<Vec<f64>> = measured
        .modes()
        .iter()
        .map(|m| {
            (rigid..modal.len())
                .map(|t| {
                    mac(
                        &m.values,
                        &m.points
                            .iter()
                            .map(|p| p.read_column(y, t))
                            .collect::<Vec<_>>(),
                    )
                })
                .collect()
        })
        .collect();
    let mut candidates: Vec<(usize, usize)> = (0..macs.len())
        .flat_map(|r| (0..macs[r].len()).map(move |t| (r, t)))
        .collect();
    candidates.sort_by(|a, b| macs[b.0][b.1].total_cmp(&macs[a.0][a.1]).then(a.cmp(b)));
    let mut model_index = vec![usize::MAX; macs.len()];
    let mut used = vec![false; modal.len()];
    for (r, t) in candidates {
        if model_index[r] == usize::MAX && !used[t] && macs[r][t] >= MIN_MAC {
            model_index[r] = t + rigid;
            used[t] = true;
        }
    }
    for (r, &index) in model_index.iter().enumerate() {
        if index == usize::MAX {
            let (best, &best_mac) = macs[r]
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1))
                .expect("a model has deformable modes");
            return Err(Unpaired {
                mode: measured.modes()[r].mode,
                best_mac,
                best_mode: best + 1,
            });
        }
    }
    let mac = model_index
        .iter()
        .zip(&macs)
        .map(|(&i, m)| m[i - rigid])
        .collect();
    Ok(Pairing { model_index, mac })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::measured::MeasuredModes;
    use crate::model::fixtures::paper_model;
    use crate::simulate::exact_modes;
    use crate::structure::Observation;

    #[test]
    fn exact_modes_pair_with_themselves_and_a_swap_is_found() {
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let dofs: Vec<Observation> = (0..38)
            .step_by(2)
            .map(|d| Observation::dof(&model.dofs, d))
            .collect();
        let exact = exact_modes(&modal, 2, &[1, 2, 3, 4], &dofs);
        let p = pair(&modal, &exact, 2).unwrap();
        assert_eq!(p.model_index, vec![2, 3, 4, 5]);
        assert!(p.mac.iter().all(|&m| (m - 1.0).abs() < 1e-12));
        // Mislabel modes 2 and 3 (a swap in the test report): pairing follows the shapes.
        let mut modes = exact.modes().to_vec();
        modes[1].mode = 3;
        modes[2].mode = 2;
        let swapped = pair(&modal, &MeasuredModes::new(modes), 2).unwrap();
        assert_eq!(swapped.model_index, vec![2, 4, 3, 5]);
    }

    #[test]
    fn a_shape_like_no_mode_is_unpaired() {
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        // A pseudo-random pattern over all 38 DOFs resembles no mode (with few DOFs, some high
        // mode always does).
        let all: Vec<Observation> = (0..38).map(|d| Observation::dof(&model.dofs, d)).collect();
        let mut modes = exact_modes(&modal, 2, &[1], &all).modes().to_vec();
        modes[0].values = (0..38).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let err = pair(&modal, &MeasuredModes::new(modes), 2).unwrap_err();
        assert_eq!(err.mode, 1);
        assert!(err.best_mac < MIN_MAC);
        assert!(
            err.to_string()
                .starts_with("measured mode 1 pairs with no model mode")
        );
    }

    #[test]
    fn mac_is_scale_and_sign_invariant() {
        assert!((mac(&[1.0, 2.0], &[-3.0, -6.0]) - 1.0).abs() < 1e-15);
        assert_eq!(mac(&[1.0, 0.0], &[0.0, 1.0]), 0.0);
    }
}
