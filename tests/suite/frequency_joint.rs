//! The frequency-dependent joint recovered by `diagnose` from data made independently of the
//! candidate: each mode r of paper case I solved densely with every joint parameter at
//! p_j0 (f_r / f_ref)^alpha_j by a fixed-point loop written here (f_ref the geometric mean of
//! the modes' frequencies), its shape read at the 19 translations (`simulate` of that one
//! structure, without noise). Noise, where added, is drawn here (fixed seed).
//!
//! Exact recovery of (k1, k2, alpha) on noise-free data; one alpha shared against one per
//! parameter selected by the data; recovery within 3 standard errors on noisy data.

use crate::common::{paper_model, steel_bar, translations};
use jointid::diagnose::{DiagnoseSettings, Noise, PairingRule, Report, Verdict, diagnose};
use jointid::measured::{MeasuredMode, MeasuredModes};
use jointid::modal::{DENSE_MAX_DOFS, ModalSolution};
use jointid::model::{Chain, Joint};
use jointid::simulate::{Errors, simulate};
use jointid::structure::Structure;
use jointid::study::NoiseKind;

const K: [f64; 2] = [1e7, 1e4];
const NOISE: Noise = Noise {
    frequency: 0.001,
    shape: 0.02,
};

/// The first six elastic modes of paper case I with k_j(f) = K_j (f / f_ref)^alpha_j, each
/// at its own frequency (fixed point, |change| < 1e-13), f_ref the geometric mean of the six.
/// Noise: relative gaussian `noise` (frequency, shape) from a fixed LCG + Box-Muller.
fn data(alpha: [f64; 2], noise: Option<Noise>) -> MeasuredModes {
    data_of(&paper_model(K[0], K[1]), alpha, noise)
}

/// As [`data`], of `model` (a chain joined by the paper's joint at `K`).
fn data_of(model: &Structure, alpha: [f64; 2], noise: Option<Noise>) -> MeasuredModes {
    let points = translations(model);
    let quiet = Errors {
        shape: 0.0,
        frequency: 0.0,
        kind: NoiseKind::Gaussian,
        seed: 1,
    };
    let at = |f: f64, f_ref: f64| {
        model.with_values(&[
            K[0] * (f / f_ref).powf(alpha[0]),
            K[1] * (f / f_ref).powf(alpha[1]),
        ])
    };
    let nominal = ModalSolution::solve(&model.assemble()).unwrap();
    let mut f: Vec<f64> = (0..6).map(|r| nominal.frequency_hz(r + 2)).collect();
    // The reference depends on the frequencies: iterate the whole set to its fixed point.
    for _ in 0..200 {
        let f_ref = (f.iter().map(|v| v.ln()).sum::<f64>() / 6.0).exp();
        let next: Vec<f64> = (0..6)
            .map(|r| {
                let modal = ModalSolution::solve(&at(f[r], f_ref).assemble()).unwrap();
                modal.frequency_hz(r + 2)
            })
            .collect();
        let change = next
            .iter()
            .zip(&f)
            .map(|(a, b)| (a / b).ln().abs())
            .fold(0.0, f64::max);
        f = next;
        if change < 1e-13 {
            break;
        }
    }
    let f_ref = (f.iter().map(|v| v.ln()).sum::<f64>() / 6.0).exp();
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut gauss = move || {
        let mut u = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let (a, b) = (u(), u());
        (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos()
    };
    let modes = (0..6)
        .map(|r| {
            let one = simulate(&at(f[r], f_ref), &[], &[r + 1], &points, quiet).unwrap();
            let m = &one.modes()[0];
            let (sf, ss) = noise.map_or((0.0, 0.0), |n| (n.frequency, n.shape));
            let peak = m.peak();
            let values = m
                .values
                .iter()
                .map(|v| v + ss * (v * v + (0.02 * peak).powi(2)).sqrt() * gauss())
                .collect();
            MeasuredMode::new(r + 1, f[r] * (1.0 + sf * gauss()), m.points.clone(), values)
        })
        .collect();
    MeasuredModes::new(modes)
}

fn run(measured: &MeasuredModes) -> Report {
    run_on(&paper_model(K[0], K[1]), measured)
}

fn run_on(model: &Structure, measured: &MeasuredModes) -> Report {
    let settings = DiagnoseSettings {
        noise: NOISE,
        pairing: PairingRule::default(),
        per_mode: None,
        extended: false,
        full_model: false,
        causes: Vec::new(),
    };
    diagnose(model, measured, settings).unwrap()
}

/// (value, se) of the after model's parameter `name`.
fn after(r: &Report, name: &str) -> (f64, f64) {
    let e = r
        .after
        .parameters
        .iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("{name} in {:?}", r.after.parameters));
    (e.value, e.se)
}

/// The frequency-dependent joint's candidate report.
fn candidate(r: &Report) -> &jointid::diagnose::CandidateReport {
    r.candidates
        .iter()
        .find(|c| c.name == "frequency_dependence")
        .unwrap()
}

#[test]
fn a_shared_alpha_is_recovered_exactly_from_noise_free_data() {
    let r = run(&data([0.1, 0.1], None));
    assert_eq!(r.verdict, Verdict::FrequencyDependent, "{:?}", r.candidates);
    assert_eq!(r.selected.as_deref(), Some("frequency_dependence"));
    let (alpha, _) = after(&r, "frequency_dependence.alpha");
    assert!((alpha - 0.1).abs() < 1e-6, "alpha {alpha}");
    for (name, k) in ["k1", "k2"].iter().zip(K) {
        let (v, _) = after(&r, name);
        assert!((v / k - 1.0).abs() < 1e-6, "{name} {v}");
    }
    assert!(
        r.after.frequency_rms_pct < 1e-6,
        "{}",
        r.after.frequency_rms_pct
    );
    assert!(
        r.before.frequency_rms_pct > 0.1,
        "{}",
        r.before.frequency_rms_pct
    );
}

#[test]
fn one_alpha_per_parameter_is_selected_when_the_alphas_differ() {
    let r = run(&data([0.2, 0.05], None));
    assert_eq!(r.verdict, Verdict::FrequencyDependent);
    for (name, a) in [("k1", 0.2), ("k2", 0.05)] {
        let (v, _) = after(&r, &format!("frequency_dependence.alpha.{name}"));
        assert!((v - a).abs() < 1e-5, "alpha {name} {v}");
    }
    let fd = candidate(&r);
    assert!(
        fd.describe.contains("the data support one per parameter"),
        "{}",
        fd.describe
    );
}

#[test]
fn noisy_data_give_the_truth_within_three_standard_errors() {
    let r = run(&data([0.1, 0.1], Some(NOISE)));
    assert_eq!(r.verdict, Verdict::FrequencyDependent);
    let fd = candidate(&r);
    assert!(
        fd.describe.contains("the data support one shared"),
        "{}",
        fd.describe
    );
    let (alpha, se) = after(&r, "frequency_dependence.alpha");
    assert!((alpha - 0.1).abs() < 3.0 * se, "alpha {alpha} +- {se}");
    for (name, k) in ["k1", "k2"].iter().zip(K) {
        let (v, se) = after(&r, name);
        assert!((v - k).abs() < 3.0 * se, "{name} {v} +- {se}");
    }
    assert!(
        r.after.frequency_rms_pct < 0.3,
        "{}",
        r.after.frequency_rms_pct
    );
}

/// The same recovery on a model the sparse solver takes (paper case I at four times the
/// elements, 140 DOFs): the per-mode corrections solve the sub-basis of n pairs they need
/// (n = 70 sensors here, more than any fit computes; before, they were left out).
#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn a_shared_alpha_is_recovered_exactly_on_a_model_solved_sparsely() {
    let model = Chain::free(
        vec![steel_bar(0.2, 28), steel_bar(0.3, 40)],
        vec![Joint::identified(K[0], K[1])],
    )
    .build();
    assert!(model.dof_count() > DENSE_MAX_DOFS);
    let r = run_on(&model, &data_of(&model, [0.1, 0.1], None));
    assert_eq!(r.verdict, Verdict::FrequencyDependent, "{:?}", r.candidates);
    let (alpha, _) = after(&r, "frequency_dependence.alpha");
    assert!((alpha - 0.1).abs() < 1e-6, "alpha {alpha}");
    for (name, k) in ["k1", "k2"].iter().zip(K) {
        let (v, _) = after(&r, name);
        assert!((v / k - 1.0).abs() < 1e-6, "{name} {v}");
    }
    // Every mode corrected on its own model's full basis, each of both parameters.
    let shaped = r
        .per_mode_after
        .iter()
        .filter(|c| c.relative.is_some())
        .count();
    assert_eq!(shaped, 6 * 2, "{:?}", r.per_mode_after);
}
