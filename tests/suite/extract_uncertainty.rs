//! Calibration of the standard errors of `jointid::extract` against the scatter of repeated
//! measurements.
//!
//! Independence: the FRFs are H1 estimates made here, as an analyser makes them, from a lumped
//! system solved line by line (tests/common/frf.rs: a complex LU solve per line, true modes from
//! the system's construction). Per line and average i: a random input X_i ~ CN(0, 1), outputs
//! Y_oi = H_o X_i + N_oi with output noise N_oi ~ CN(0, s_o^2) (s_o a stated fraction of the
//! response's peak |H_o|), then H1_o = sum Y X* / sum |X|^2 and the coherence
//! |sum Y X*|^2 / (sum |X|^2 sum |Y|^2). Nothing here calls the extractor's noise model or its
//! propagation: the check is the empirical scatter of the estimates over independent
//! realisations against the standard errors each realisation reports.
//!
//! Criteria (per mode): the mean reported standard error within 0.75-1.33 times the empirical
//! standard deviation across realisations, for the frequency, the damping ratio and the shape
//! values (the median over the mode's components of that ratio); and the 95% interval
//! (estimate +- 1.96 se) covering the truth in 85-100% of the realisations.
//! Both are ignored in the default `cargo test` (tens of seconds unoptimised) and run by
//! .ci/run in release with the long batteries: `forty_realisations_are_calibrated` (one
//! situation), and `calibration_table` (bench/extract_uncertainty.sh runs it too), which prints the full table of 40 realisations in each of four
//! situations.

use crate::common::frf::{Rng, System, frf_set, lines, prescribed, receptance, shape_at};
use faer::c64;
use jointid::extract::{Extraction, FrfSet, Quantity, Settings, extract};

/// Modes in the band and one above it (a residual), their damping ratios.
const FREQUENCIES: [f64; 4] = [40.0, 75.0, 120.0, 420.0];
const DAMPING: [f64; 4] = [0.012, 0.015, 0.010, 0.02];
const RESPONSES: [usize; 4] = [0, 1, 2, 3];
/// The system's seed: every mode well excited at the reference (|phi_0| above 0.3 of the
/// mode's largest component) and one clear largest component per mode (the second below 0.85
/// of it), so that the unit-peak normalisation of the shapes is the same in every realisation
/// (where two components tie, the estimates switch between two normalisations and their
/// scatter is not that of one quantity).
const SYSTEM_SEED: u64 = 0;

/// One measurement situation.
#[derive(Clone, Copy)]
struct Situation {
    name: &'static str,
    /// Output noise standard deviation, as a fraction of the response's peak |H|.
    noise: f64,
    /// Averages of the H1 estimate.
    averages: usize,
    /// Whether the extraction is told the averages (else it estimates from the residuals).
    told: bool,
}

/// H1 estimates and coherences of `h` (`[response][line]`), `averages` averages, output noise
/// `noise` times each response's peak.
fn h1(
    h: &[Vec<c64>],
    noise: f64,
    averages: usize,
    rng: &mut Rng,
) -> (Vec<Vec<c64>>, Vec<Vec<f64>>) {
    let peaks: Vec<f64> = h
        .iter()
        .map(|r| r.iter().map(|v| v.norm()).fold(0.0, f64::max))
        .collect();
    let lines = h[0].len();
    let mut estimate = vec![Vec::with_capacity(lines); h.len()];
    let mut coherence = vec![Vec::with_capacity(lines); h.len()];
    let mut cn = |s: f64| c64::new(rng.normal(), rng.normal()) * (s / 2f64.sqrt());
    for k in 0..lines {
        let mut sxx = 0.0;
        let mut sxy = vec![c64::new(0.0, 0.0); h.len()];
        let mut syy = vec![0.0; h.len()];
        for _ in 0..averages {
            let x = cn(1.0);
            sxx += x.norm_sqr();
            for o in 0..h.len() {
                let y = h[o][k] * x + cn(noise * peaks[o]);
                sxy[o] += y * x.conj();
                syy[o] += y.norm_sqr();
            }
        }
        for o in 0..h.len() {
            estimate[o].push(sxy[o] / sxx);
            coherence[o].push((sxy[o].norm_sqr() / (sxx * syy[o])).min(1.0));
        }
    }
    (estimate, coherence)
}

/// The true FRFs (accelerance) of the system on its lines.
fn truth() -> (System, FrfSet) {
    let sys = prescribed(&FREQUENCIES, &DAMPING, SYSTEM_SEED);
    let f = lines(0.25, 160.0);
    let rec = receptance(&sys, 0, &f);
    let set = frf_set(&rec, &f, &RESPONSES, Quantity::Acceleration);
    (sys, set)
}

fn settings(averages: Option<usize>) -> Settings {
    Settings {
        band_hz: Some((20.0, 150.0)),
        max_order: 40,
        n_modes: Some(3),
        averages,
        ..Settings::default()
    }
}

/// Estimates and standard errors of one realisation: per mode (f, se), (zeta, se) and per
/// shape component (value, se).
struct Realisation {
    modes: Vec<[(f64, f64); 2]>,
    shapes: Vec<Vec<(f64, f64)>>,
}

fn realise(clean: &FrfSet, situation: Situation, seed: u64) -> Realisation {
    let mut rng = Rng::new(seed);
    let (responses, coherence) = h1(
        &clean.responses,
        situation.noise,
        situation.averages,
        &mut rng,
    );
    let set = FrfSet {
        responses,
        coherence: Some(coherence),
        ..clean.clone()
    };
    let told = situation.told.then_some(situation.averages);
    let ex: Extraction = extract(&set, &settings(told), &|_, _| {}).expect("extraction");
    Realisation {
        modes: ex
            .modes
            .iter()
            .map(|m| {
                [
                    (m.frequency_hz, m.std.frequency_hz),
                    (m.damping_ratio, m.std.damping_ratio),
                ]
            })
            .collect(),
        shapes: ex
            .modes
            .iter()
            .map(|m| {
                m.real_shape
                    .iter()
                    .copied()
                    .zip(m.std.shape.iter().copied())
                    .collect()
            })
            .collect(),
    }
}

/// Ratio of the mean reported se to the empirical sd, and the coverage of the 95% interval.
#[derive(Debug, Clone, Copy)]
struct Calibration {
    ratio: f64,
    coverage: f64,
}

fn calibration(samples: &[(f64, f64)], truth: f64) -> Calibration {
    let n = samples.len() as f64;
    let mean = samples.iter().map(|s| s.0).sum::<f64>() / n;
    let sd = (samples.iter().map(|s| (s.0 - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let se = samples.iter().map(|s| s.1).sum::<f64>() / n;
    let covered = samples
        .iter()
        .filter(|s| (s.0 - truth).abs() <= 1.96 * s.1)
        .count();
    Calibration {
        ratio: se / sd,
        coverage: covered as f64 / n,
    }
}

/// Per mode: frequency, damping, and the shape (median ratio over the non-peak components,
/// pooled coverage).
fn table(situation: Situation, realisations: usize) -> Vec<[Calibration; 3]> {
    let (sys, clean) = truth();
    let runs: Vec<Realisation> = (0..realisations)
        .map(|i| realise(&clean, situation, 1000 + i as u64))
        .collect();
    (0..3)
        .map(|r| {
            let mut true_shape = shape_at(&sys, r, &RESPONSES);
            let peak = (0..true_shape.len())
                .max_by(|&a, &b| true_shape[a].abs().total_cmp(&true_shape[b].abs()))
                .unwrap();
            let at = true_shape[peak];
            true_shape.iter_mut().for_each(|v| *v /= at);
            let of = |q: usize| runs.iter().map(|x| x.modes[r][q]).collect::<Vec<_>>();
            let f = calibration(&of(0), sys.frequencies_hz[r]);
            let z = calibration(&of(1), sys.damping[r]);
            let mut ratios = Vec::new();
            let (mut covered, mut total) = (0.0, 0.0);
            for (j, &t) in true_shape.iter().enumerate() {
                if j == peak {
                    continue;
                }
                let samples: Vec<(f64, f64)> = runs.iter().map(|x| x.shapes[r][j]).collect();
                let c = calibration(&samples, t);
                ratios.push(c.ratio);
                covered += c.coverage * samples.len() as f64;
                total += samples.len() as f64;
            }
            ratios.sort_by(f64::total_cmp);
            let shape = Calibration {
                ratio: ratios[ratios.len() / 2],
                coverage: covered / total,
            };
            [f, z, shape]
        })
        .collect()
}

fn assert_calibrated(situation: Situation, rows: &[[Calibration; 3]]) {
    for (r, row) in rows.iter().enumerate() {
        for (what, c) in ["frequency", "damping", "shape"].iter().zip(row) {
            assert!(
                (0.75..=1.33).contains(&c.ratio) && c.coverage >= 0.85,
                "{}: mode {} {what}: se / sd {:.3}, coverage {:.2}",
                situation.name,
                r + 1,
                c.ratio,
                c.coverage
            );
        }
    }
}

const COHERENCE: Situation = Situation {
    name: "coherence, 2% noise, 20 averages",
    noise: 0.02,
    averages: 20,
    told: true,
};

/// The other situations of the full table.
const OTHERS: [Situation; 3] = [
    Situation {
        name: "coherence, 5% noise, 10 averages",
        noise: 0.05,
        averages: 10,
        told: true,
    },
    Situation {
        name: "coherence, 1% noise, 54 averages",
        noise: 0.01,
        averages: 54,
        told: true,
    },
    Situation {
        name: "residuals, 2% noise, 20 averages",
        noise: 0.02,
        averages: 20,
        told: false,
    },
];

#[test]
#[ignore = "long unoptimised: .ci/run runs it in release"]
fn forty_realisations_are_calibrated() {
    let rows = table(COHERENCE, 40);
    assert_calibrated(COHERENCE, &rows);
}

#[test]
#[ignore = "the full calibration table, 40 realisations per situation: bench/extract_uncertainty.sh"]
fn calibration_table() {
    let situations = std::iter::once(COHERENCE).chain(OTHERS);
    println!(
        "| situation | mode | frequency se/sd | coverage | damping se/sd | coverage | shape se/sd (median) | coverage |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for s in situations {
        let rows = table(s, 40);
        assert_calibrated(s, &rows);
        for (r, row) in rows.iter().enumerate() {
            println!(
                "| {} | {} | {:.2} | {:.0}% | {:.2} | {:.0}% | {:.2} | {:.0}% |",
                s.name,
                r + 1,
                row[0].ratio,
                100.0 * row[0].coverage,
                row[1].ratio,
                100.0 * row[1].coverage,
                row[2].ratio,
                100.0 * row[2].coverage
            );
        }
    }
}

/// A coherence of 1 on every line (an export rounded to 1, or noise-free data) says the noise
/// is below what the file resolves, not zero: the standard errors come from the residuals then,
/// finite and positive, and the extraction says so (they were exactly 0, which identify and
/// diagnose refuse).
#[test]
fn a_coherence_of_one_everywhere_gives_standard_errors_from_the_residuals() {
    let (_, clean) = truth();
    let mut set = clean.clone();
    crate::common::frf::add_noise(&mut set, 0.01, 0.0, 7);
    set.coherence = Some(vec![
        vec![1.0; set.frequencies_hz.len()];
        set.responses.len()
    ]);
    let ex = extract(&set, &settings(Some(20)), &|_, _| {}).expect("extraction");
    assert_eq!(
        ex.noise,
        jointid::extract::NoiseSource::ResidualsCoherenceOne { response: 0 }
    );
    for m in &ex.modes {
        assert!(m.std.frequency_hz > 0.0 && m.std.frequency_hz.is_finite());
        assert!(m.std.damping_ratio > 0.0 && m.std.damping_ratio.is_finite());
        let moving = m.std.shape.iter().filter(|s| **s > 0.0).count();
        assert_eq!(moving, m.std.shape.len() - 1, "{:?}", m.std.shape);
    }
}
