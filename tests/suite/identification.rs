//! The per-mode identification (eq. (5)-(16)) on simulated data of the paper's system.

use crate::common::{all_dofs, paper_model, translations};
use jointid::identify::{Identifier, Projector, Settings, Weighting};
use jointid::modal::ModalSolution;
use jointid::simulate::exact_modes;
use jointid::structure::{Observation, Structure, observe};

fn identifier(model: &Structure, n: usize, m: usize, weighting: Weighting) -> Identifier {
    let modal = ModalSolution::solve(&model.assemble()).unwrap();
    Identifier::for_structure(model, &modal, Settings { n, m, weighting }).unwrap()
}

/// Worst relative error of the identified corrections against `delta` over `modes`.
fn worst_error(
    nominal: &Structure,
    delta: [f64; 2],
    dofs: &[Observation],
    n: usize,
    m: usize,
    w: Weighting,
    modes: &[usize],
) -> f64 {
    let truth = nominal.with_delta(&delta);
    let measured = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        2,
        modes,
        dofs,
    );
    let id = identifier(nominal, n, m, w);
    let mut worst = 0.0_f64;
    for mode in measured.modes() {
        let z = id.identify(mode).unwrap().relative.unwrap();
        for (i, p) in id.parameters().iter().enumerate() {
            worst = worst.max((p.value * z[i] - delta[i]).abs() / delta[i].abs());
        }
    }
    worst
}

#[test]
fn exact_recovery_with_every_dof_and_the_full_basis() {
    // n = N, noise-free: eq. (7) holds exactly and (8) is exact for k1, k2, so every mode
    // recovers the introduced modification whatever m and W. The floor is the eigenvector
    // accuracy of the dense solver (about eps * lambda_max / gap, 2e-9 along the rigid-body
    // modes for mode 1), amplified by the stiffest rows: mode 1 of case I sits at 2-6e-9 for
    // m from 3 to 20, and at 1.0e-8 with m = 2 (no redundancy) or 2.0e-8 with all 36 rows
    // equally weighted (rows of modes up to 700 kHz). m = 3..20 is the tested range.
    let cases = [
        (paper_model(1.0e7, 1.0e4), [2.0e6, 2.0e3]),
        (paper_model(1.84e8, 1.65e5), [2.0e7, 2.0e4]),
        (paper_model(1.84e8, 1.65e5), [-5.0e7, 3.0e4]),
    ];
    for (nominal, delta) in &cases {
        let dofs = all_dofs(nominal);
        for m in [3, 7, 20] {
            for w in Weighting::ALL {
                let err = worst_error(nominal, *delta, &dofs, 38, m, w, &[1, 2, 3, 4, 5, 6]);
                assert!(err < 1e-8, "m {m}, {w}: error {err:e}");
            }
        }
    }
}

#[test]
fn error_falls_as_the_basis_grows_with_partial_shapes() {
    // The paper's conclusion 1: with the rotations unmeasured (NF = 19) and no noise, the
    // truncation error of g_r falls as n grows.
    let nominal = paper_model(1.0e7, 1.0e4);
    let dofs = translations(&nominal);
    // The fall is a trend, not monotone at every step: at n = 10 mode 2's k2 error jumps to
    // 8% (from 4% at n = 7) before falling again. So: every error of the large bases is
    // below every error of the small ones, and the largest basis gains a factor of 5 at least.
    let errors: Vec<f64> = [7, 10, 13, 16, 19]
        .iter()
        .map(|&n| {
            worst_error(
                &nominal,
                [2.0e6, 2.0e3],
                &dofs,
                n,
                5,
                Weighting::Inverse,
                &[1, 2, 3, 4],
            )
        })
        .collect();
    let small = errors[..2].iter().cloned().fold(f64::INFINITY, f64::min);
    let large = errors[2..].iter().cloned().fold(0.0, f64::max);
    assert!(large < small, "{errors:?}");
    assert!(errors[4] < errors[0] / 5.0, "{errors:?}");
}

#[test]
fn sensitivity_columns_match_central_differences_of_the_projected_equations() {
    // Column i of S_r is d/d(ln p_i) of the projected equations Y^T K(p) Y g_r (eq. (6)-(10)):
    // checked against a central difference through the full assembly of K.
    let nominal = paper_model(1.0e7, 1.0e4);
    let id = identifier(&nominal, 12, 6, Weighting::Equal);
    let truth = nominal.with_delta(&[2.0e6, 2.0e3]);
    let measured = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        2,
        &[1, 2, 3, 4],
        &translations(&nominal),
    );
    let y = id.basis();
    for mode in measured.modes() {
        let s_r = id.basis_index(mode.mode).unwrap();
        let mut g = vec![0.0; 12];
        Projector::new(&observe(y, &mode.points))
            .unwrap()
            .project(&mode.values, &mut g);
        let system = id.mode_system(s_r);
        let (m, q) = (system.m(), system.q());
        let (mut s, mut b) = (vec![0.0; m * q], vec![0.0; m]);
        system.assemble(&g, mode.lambda(), &mut s, &mut b);
        let yg: Vec<f64> = (0..y.nrows())
            .map(|d| (0..12).map(|t| y[(d, t)] * g[t]).sum())
            .collect();
        for (i, p) in id.parameters().iter().enumerate() {
            let h = 1e-4;
            let projected = |sign: f64| {
                let mut delta = [0.0; 2];
                delta[i] = sign * h * p.value;
                let k = nominal.with_delta(&delta).assemble().k.to_dense();
                let kyg: Vec<f64> = (0..k.nrows())
                    .map(|a| (0..k.ncols()).map(|c| k[(a, c)] * yg[c]).sum())
                    .collect();
                system
                    .rows()
                    .rows
                    .iter()
                    .map(|&row| (0..k.nrows()).map(|a| y[(a, row)] * kyg[a]).sum::<f64>())
                    .collect::<Vec<f64>>()
            };
            let (plus, minus) = (projected(1.0), projected(-1.0));
            let scale = (0..m).map(|k| s[i * m + k].abs()).fold(0.0, f64::max);
            for k in 0..m {
                let fd = (plus[k] - minus[k]) / (2.0 * h);
                assert!(
                    (fd - s[i * m + k]).abs() < 1e-6 * scale,
                    "mode {}, param {}, row {k}: {fd} vs {}",
                    mode.mode,
                    p.name,
                    s[i * m + k]
                );
            }
        }
    }
}

#[test]
fn noisy_modes_are_identified_but_not_exactly() {
    // A guard against a method that returns the introduced values whatever the data: a 1%
    // distortion of one shape element moves the corrections.
    let nominal = paper_model(1.0e7, 1.0e4);
    let truth = nominal.with_delta(&[2.0e6, 2.0e3]);
    let measured = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        2,
        &[2],
        &all_dofs(&nominal),
    );
    let id = identifier(&nominal, 38, 7, Weighting::Inverse);
    let mut mode = measured.modes()[0].clone();
    let exact = id.identify(&mode).unwrap().relative.unwrap();
    mode.values[10] *= 1.01;
    let noisy = id.identify(&mode).unwrap().relative.unwrap();
    assert!((exact[0] - 0.2).abs() < 1e-8);
    assert!((noisy[0] - exact[0]).abs() > 1e-6, "{noisy:?} vs {exact:?}");
}

/// The standard deviations identify reports from the data's own standard errors, against the
/// scatter of the corrections over repeated noisy measurements. Independence: the noise is
/// drawn here (tests/suite/common/frf.rs's SplitMix64 stream, Gaussian, per component the
/// value_std given, per frequency the frequency_std), not by jointid's simulate; the reported
/// deviation is the first-order propagation of those errors through the weighted projection
/// and eq. (13). Per mode and parameter the empirical sd over 400 realisations is within 15%
/// of the mean reported one (the noise is small: first order holds).
#[test]
fn reported_deviations_match_the_scatter_under_the_datas_errors() {
    use crate::common::frf::Rng;
    let nominal = paper_model(1.0e7, 1.0e4);
    let truth = nominal.with_delta(&[2.0e6, 2.0e3]);
    let dofs = translations(&nominal);
    let exact = exact_modes(
        &ModalSolution::solve(&truth.assemble()).unwrap(),
        2,
        &[1, 2, 3],
        &dofs,
    );
    let id = identifier(&nominal, 10, 5, Weighting::Inverse);
    let mut rng = Rng::new(7);
    let realisations = 400;
    for exact_mode in exact.modes() {
        let peak = exact_mode.peak();
        // Errors of 0.2% of each value plus 0.05% of the peak; 1e-4 of the frequency.
        let value_std: Vec<f64> = exact_mode
            .values
            .iter()
            .map(|v| 0.002 * v.abs() + 0.0005 * peak)
            .collect();
        let frequency_std = 1e-4 * exact_mode.frequency_hz;
        let mut samples: Vec<Vec<f64>> = vec![Vec::new(); 2];
        let mut reported: Vec<f64> = vec![0.0; 2];
        for _ in 0..realisations {
            let mut mode = exact_mode.clone();
            for (v, s) in mode.values.iter_mut().zip(&value_std) {
                *v += s * rng.normal();
            }
            mode.frequency_hz += frequency_std * rng.normal();
            mode.value_std = Some(value_std.clone());
            mode.frequency_std = Some(frequency_std);
            let outcome = id.identify(&mode).unwrap();
            let z = outcome.relative.unwrap();
            let std = outcome.std.expect("the data carry standard errors");
            for i in 0..2 {
                samples[i].push(z[i]);
                reported[i] += std[i] / realisations as f64;
            }
        }
        for i in 0..2 {
            let n = samples[i].len() as f64;
            let mean = samples[i].iter().sum::<f64>() / n;
            let sd =
                (samples[i].iter().map(|z| (z - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
            let ratio = reported[i] / sd;
            assert!(
                (0.85..=1.15).contains(&ratio),
                "mode {} parameter {i}: reported {:.3e}, scatter {sd:.3e} (ratio {ratio:.3})",
                exact_mode.mode,
                reported[i]
            );
        }
    }
}
