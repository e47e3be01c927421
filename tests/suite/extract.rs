//! Accuracy of `jointid::extract` on FRFs of lumped systems.
//!
//! The data are generated independently of the extractor (tests/common/frf.rs): each FRF line
//! is a direct complex solve of (K - w^2 M + i w C) x = e_ref; the true modes come from the
//! construction of the system (prescribed frequencies, damping ratios, mass-normalised shapes),
//! from the symmetric eigenproblem of a spring-mass chain, or from the state-space eigenproblem
//! for non-proportional damping. Noise: complex Gaussian, fixed seeds.

use crate::common::frf;

use frf::{System, add_noise, frf_set, lines, mac, prescribed, receptance, shape_at};
use jointid::extract::{BandSource, Extraction, FrfSet, Quantity, Settings, extract};

/// Frequencies within `f_tol` (relative), damping within `z_tol` (relative), MAC of the real
/// shapes against the true ones at the responses >= `mac_min`; one mode per true mode.
fn assert_modes(
    ex: &Extraction,
    sys: &frf::System,
    modes: &[usize],
    responses: &[usize],
    f_tol: f64,
    z_tol: f64,
    mac_min: f64,
) {
    let table: Vec<String> = ex
        .modes
        .iter()
        .map(|m| {
            format!(
                "{:.4} Hz {:.5} mpc {:.4}",
                m.frequency_hz, m.damping_ratio, m.mpc
            )
        })
        .collect();
    let rejected: Vec<String> = ex
        .decisions
        .iter()
        .filter_map(|d| {
            let why = d.rejected.as_ref()?;
            Some(format!("{:.4} Hz: {why}", d.frequency_hz))
        })
        .collect();
    assert_eq!(
        ex.modes.len(),
        modes.len(),
        "found {table:#?}, rejected {rejected:#?}"
    );
    for (m, &r) in ex.modes.iter().zip(modes) {
        let (f, z) = (sys.frequencies_hz[r], sys.damping[r]);
        let ef = (m.frequency_hz - f) / f;
        let ez = (m.damping_ratio - z) / z;
        let shape = shape_at(sys, r, responses);
        let mac = mac(&m.real_shape, &shape);
        eprintln!(
            "mode {r}: f {:.5} ({ef:+.2e})  zeta {:.5} ({ez:+.2e})  MAC {mac:.6}  stable {:?}",
            m.frequency_hz, m.damping_ratio, m.stable_orders
        );
        assert!(
            ef.abs() < f_tol,
            "mode {r}: frequency {} vs {f}",
            m.frequency_hz
        );
        assert!(
            ez.abs() < z_tol,
            "mode {r}: damping {} vs {z}",
            m.damping_ratio
        );
        assert!(mac >= mac_min, "mode {r}: MAC {mac}");
    }
}

/// The bench case (bench/extract_vs_sdypy.py): seven modes, 40 to 1500 Hz, seven responses in
/// velocity on lines 0.25 to 1000 Hz, 2% noise with a floor: the system, the responses and
/// the FRFs.
fn bench_case() -> (System, Vec<usize>, FrfSet) {
    let f = [40.0, 120.0, 210.0, 330.0, 480.0, 650.0, 1500.0];
    let z = [0.01, 0.02, 0.005, 0.01, 0.03, 0.002, 0.01];
    let sys = prescribed(&f, &z, 5);
    let freqs = lines(0.25, 1000.0);
    let responses: Vec<usize> = (0..7).collect();
    let h = receptance(&sys, 0, &freqs);
    let mut set = frf_set(&h, &freqs, &responses, Quantity::Velocity);
    add_noise(&mut set, 0.02, 1e-4, 11);
    (sys, responses, set)
}

#[test]
fn five_modes_with_modes_outside_the_band_noisy_velocity() {
    // Modes at 40 Hz (below the band) and 1500 Hz (above) act through the residual terms.
    let (sys, responses, set) = bench_case();
    let settings = Settings {
        band_hz: Some((80.0, 800.0)),
        ..Settings::default()
    };
    let ex = extract(&set, &settings, &|_, _| {}).unwrap();
    // No number of modes: the automatic choice, which keeps the five and nothing else.
    assert_modes(&ex, &sys, &[1, 2, 3, 4, 5], &responses, 1e-3, 0.1, 0.999);
    assert_kept_are_the_modes(&ex);
}

#[test]
fn three_modes_noise_free_displacement() {
    // Light to heavy damping (0.2% to 3%) and nothing outside the band: noise-free FRFs are
    // recovered to the rounding of the data.
    let f = [50.0, 140.0, 300.0];
    let z = [0.002, 0.01, 0.03];
    let sys = prescribed(&f, &z, 3);
    let freqs = lines(0.5, 400.0);
    let responses: Vec<usize> = (0..3).collect();
    let h = receptance(&sys, 0, &freqs);
    let set = frf_set(&h, &freqs, &responses, Quantity::Displacement);
    let settings = Settings {
        max_order: 24,
        ..Settings::default()
    };
    let ex = extract(&set, &settings, &|_, _| {}).unwrap();
    assert_modes(&ex, &sys, &[0, 1, 2], &responses, 1e-11, 1e-11, 1.0 - 1e-12);
}

#[test]
fn eight_modes_noisy_acceleration() {
    // Eight modes in the band, 0.2% to 3% damping, 1% noise on accelerances.
    let f = [55.0, 110.0, 180.0, 250.0, 330.0, 420.0, 510.0, 600.0];
    let z = [0.002, 0.005, 0.01, 0.03, 0.008, 0.02, 0.004, 0.015];
    let sys = prescribed(&f, &z, 8);
    let freqs = lines(0.5, 700.0);
    let responses: Vec<usize> = (0..8).collect();
    let h = receptance(&sys, 0, &freqs);
    let mut set = frf_set(&h, &freqs, &responses, Quantity::Acceleration);
    add_noise(&mut set, 0.01, 1e-4, 8);
    let settings = Settings {
        band_hz: Some((30.0, 650.0)),
        max_order: 40,
        ..Settings::default()
    };
    let ex = extract(&set, &settings, &|_, _| {}).unwrap();
    assert_modes(
        &ex,
        &sys,
        &[0, 1, 2, 3, 4, 5, 6, 7],
        &responses,
        1e-3,
        0.1,
        0.999,
    );
}

#[test]
fn close_modes_noisy_receptance() {
    // Modes at 200 and 203 Hz with 0.5% damping (half-power bandwidths 2 Hz: the peaks merge)
    // beside 120 and 310 Hz; 1% noise.
    let f = [120.0, 200.0, 203.0, 310.0];
    let z = [0.01, 0.005, 0.005, 0.02];
    let sys = prescribed(&f, &z, 4);
    let freqs = lines(0.25, 400.0);
    let responses: Vec<usize> = (0..4).collect();
    let h = receptance(&sys, 0, &freqs);
    let mut set = frf_set(&h, &freqs, &responses, Quantity::Displacement);
    add_noise(&mut set, 0.01, 1e-4, 4);
    let settings = Settings {
        band_hz: Some((80.0, 380.0)),
        max_order: 30,
        ..Settings::default()
    };
    let ex = extract(&set, &settings, &|_, _| {}).unwrap();
    assert_modes(&ex, &sys, &[0, 1, 2, 3], &responses, 1e-3, 0.1, 0.999);
}

#[test]
fn frfs_scaled_far_from_one_give_the_same_modes() {
    // The noise-free case above, its FRFs multiplied by 1e-150 .. 1e150: frequencies, damping
    // and MPC do not depend on the unit of the data.
    let sys = prescribed(&[50.0, 140.0, 300.0], &[0.002, 0.01, 0.03], 3);
    let freqs = lines(0.5, 400.0);
    let responses: Vec<usize> = (0..3).collect();
    let h = receptance(&sys, 0, &freqs);
    let settings = Settings {
        max_order: 24,
        ..Settings::default()
    };
    let base = extract(
        &frf_set(&h, &freqs, &responses, Quantity::Displacement),
        &settings,
        &|_, _| {},
    )
    .unwrap();
    for scale in [1e-150, 1e-90, 1e90, 1e150] {
        let mut set = frf_set(&h, &freqs, &responses, Quantity::Displacement);
        for r in &mut set.responses {
            for v in r.iter_mut() {
                *v *= scale;
            }
        }
        let ex =
            extract(&set, &settings, &|_, _| {}).unwrap_or_else(|e| panic!("scale {scale}: {e}"));
        assert_eq!(ex.modes.len(), base.modes.len(), "scale {scale}");
        for (a, b) in ex.modes.iter().zip(&base.modes) {
            assert!(
                (a.frequency_hz - b.frequency_hz).abs() < 1e-9 * b.frequency_hz,
                "{scale}"
            );
            assert!(
                (a.mpc - b.mpc).abs() < 1e-9,
                "scale {scale}: MPC {} vs {}",
                a.mpc,
                b.mpc
            );
        }
    }
}

/// The FRFs of bench/extract_vs_sdypy.py (the case of the first test above, drawn by the same
/// generator: tests/common/frf.rs is its Rust twin, independent of the extractor) with neither
/// a band nor a number of modes: the band is the data's (no coherence: the level stands above
/// the noise on every line) and the automatic choice keeps the six true modes below the last
/// line (1000 Hz) and nothing else; every rejected candidate says why. (With the bench's band
/// 80-800 Hz, the first test above: the five true modes in it.)
#[test]
fn without_a_band_the_automatic_choice_keeps_the_six_true_modes_of_the_bench_case() {
    let (sys, responses, set) = bench_case();
    let ex = extract(&set, &Settings::default(), &|_, _| {}).unwrap();
    assert_eq!(ex.band_source, BandSource::Level);
    assert_eq!(ex.band_hz, (0.25, 1000.0));
    assert_modes(&ex, &sys, &[0, 1, 2, 3, 4, 5], &responses, 1e-3, 0.1, 0.999);
    assert_kept_are_the_modes(&ex);
}

/// The decisions number the kept candidates 1..=modes, and every other one says why not.
fn assert_kept_are_the_modes(ex: &Extraction) {
    let kept: Vec<usize> = ex.decisions.iter().filter_map(|d| d.mode).collect();
    assert_eq!(kept, (1..=ex.modes.len()).collect::<Vec<_>>());
    for d in &ex.decisions {
        assert_eq!(d.mode.is_some(), d.rejected.is_none(), "{d:?}");
    }
}

/// A mode near where the excitation stops: the coherence is 0.99 below 150 Hz and 0.05 above,
/// and the mode at 146 Hz (1% damping, half-power bandwidth 2.92 Hz) would sit 1.4 bandwidths
/// from the edge of the excited band. The band is moved out to 10 bandwidths above it, and
/// the mode keeps its margin of 5 there; the band before the move is reported.
#[test]
fn a_mode_at_the_edge_of_the_excited_band_moves_the_edge_out() {
    let f = [60.0, 146.0, 260.0];
    let z = [0.01, 0.01, 0.01];
    let sys = prescribed(&f, &z, 3);
    let freqs = lines(0.25, 300.0);
    let responses: Vec<usize> = (0..3).collect();
    let h = receptance(&sys, 0, &freqs);
    let mut set = frf_set(&h, &freqs, &responses, Quantity::Displacement);
    let coherence: Vec<f64> = freqs
        .iter()
        .map(|&x| if x < 150.0 { 0.99 } else { 0.05 })
        .collect();
    set.coherence = Some(vec![coherence; 3]);
    let settings = Settings {
        max_order: 24,
        ..Settings::default()
    };
    let ex = extract(&set, &settings, &|_, _| {}).unwrap();
    let (lo, hi) = ex.extended_from.expect("the band was extended");
    assert!(lo <= 1.0 && (148.0..150.0).contains(&hi), "{lo} {hi}");
    let top = 146.0 * (1.0 + 2.0 * 5.0 * 2.0 * 0.01);
    assert!((ex.band_hz.1 - top).abs() < 0.1, "{:?}", ex.band_hz);
    assert_eq!(ex.modes.len(), 2);
    let d = &ex.decisions[1];
    assert_eq!(d.mode, Some(2));
    assert!((d.frequency_hz - 146.0).abs() < 0.01, "{d:?}");
    assert!(d.margins.1 >= 5.0 && d.edge.is_none(), "{d:?}");
}
