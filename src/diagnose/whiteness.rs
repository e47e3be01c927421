//! Structure in the shape residuals along the structure: the lack-of-fit test that does not
//! stand on the noise level.
//!
//! Measurement noise is independent from one sensor to the next; what a wrong model leaves in
//! a mode shape is a difference of smooth shapes, so neighbouring residuals share its sign.
//! With z_j the residuals of one mode, one direction, in the order of the sensors along the
//! structure (x), each divided by its working standard deviation, the lag-one products
//! p_j = z_j z_{j+1} have mean zero under independent errors of mean zero, whatever their
//! variances, and are uncorrelated with one another (E[z_1 z_2 z_2 z_3] = 0). Summed over every
//! mode and direction, the self-normalised statistic
//!
//! ```text
//!   Z = sum p_j / sqrt(sum p_j^2)
//! ```
//!
//! is asymptotically standard normal, for a misstated noise level, a misstated floor and
//! heavy-tailed errors alike (the scale of z cancels); it is large and positive when the
//! residuals are smooth along the structure. The test is one-sided: P = P(N(0, 1) > Z).
//! Residuals of a fitted model are slightly anti-correlated (the fit removes smooth
//! components), which makes the test conservative.
//!
//! Residuals far below the working noise (noise-free data fitted exactly) carry nothing to
//! test: P = 1.

use serde::Serialize;

use super::along;
use super::fit::{Noise, Residuals};
use crate::measured::MeasuredModes;
use crate::stats::chi2_sf;

/// Below this mean square of the standardised residuals there is nothing to test.
const NOTHING_TO_TEST: f64 = 1e-6;

/// The whiteness test of one fit's shape residuals.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Whiteness {
    /// The statistic Z (standard normal under white residuals).
    pub statistic: f64,
    /// Neighbouring pairs it sums over.
    pub pairs: usize,
    /// P(N(0, 1) > Z).
    pub p_value: f64,
}

/// The whiteness test of the shape residuals `res` of `measured` (as [`super::residuals`] gives
/// them), standardised by the `working` noise with `floor` (a fraction of the peak).
pub fn of_residuals(
    res: &Residuals,
    measured: &MeasuredModes,
    working: Noise,
    floor: f64,
) -> Whiteness {
    let sequences: Vec<Vec<f64>> = along::of_residuals(res, measured)
        .iter()
        .map(|s| {
            s.u.iter()
                .zip(&s.e)
                .map(|(u, e)| e / (working.shape * (u * u + floor * floor).sqrt()))
                .collect()
        })
        .collect();
    of_sequences(&sequences)
}

/// The test on standardised residuals, each sequence in the order along the structure.
pub fn of_sequences(sequences: &[Vec<f64>]) -> Whiteness {
    let (mut sum, mut sum_sq, mut pairs, mut square, mut values) = (0.0, 0.0, 0, 0.0, 0);
    for z in sequences {
        for w in z.windows(2) {
            let p = w[0] * w[1];
            sum += p;
            sum_sq += p * p;
            pairs += 1;
        }
        square += z.iter().map(|v| v * v).sum::<f64>();
        values += z.len();
    }
    if pairs == 0 || sum_sq == 0.0 || square < NOTHING_TO_TEST * values as f64 {
        return Whiteness {
            statistic: 0.0,
            pairs,
            p_value: 1.0,
        };
    }
    let statistic = sum / sum_sq.sqrt();
    let two_sided = chi2_sf(statistic * statistic, 1.0);
    let p_value = if statistic > 0.0 {
        0.5 * two_sided
    } else {
        1.0 - 0.5 * two_sided
    };
    Whiteness {
        statistic,
        pairs,
        p_value,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::TrialRng;
    use rand_distr::{Distribution, StandardNormal, StudentT};

    /// Sequences of 6 modes x 20 sensors drawn from `draw`.
    fn sequences(mut draw: impl FnMut() -> f64) -> Vec<Vec<f64>> {
        (0..6).map(|_| (0..20).map(|_| draw()).collect()).collect()
    }

    /// Under independent errors P is uniform: about 1% of 2000 draws fall below 0.01, for
    /// Gaussian errors of any scale and for Student-t (3 dof) errors whose variance changes
    /// along the sequence (a misstated floor).
    #[test]
    fn independent_errors_are_white_whatever_their_scale_and_tails() {
        let mut rng = TrialRng::new(7, 0, 0);
        let t3 = StudentT::new(3.0).unwrap();
        let (mut gauss, mut heavy) = (0, 0);
        for _ in 0..2000 {
            let g = sequences(|| {
                5.0 * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng)
            });
            gauss += usize::from(of_sequences(&g).p_value < 0.01);
            let mut j = 0;
            let h = sequences(|| {
                j += 1;
                (1.0 + (j % 20) as f64) * t3.sample(&mut rng)
            });
            heavy += usize::from(of_sequences(&h).p_value < 0.01);
        }
        // Binomial(2000, 0.01): mean 20, sd 4.5; within 3 sd (both draw 13 with these seeds:
        // the self-normalised statistic is slightly conservative at 114 pairs).
        assert!((7..=33).contains(&gauss), "{gauss} of 2000 below 0.01");
        assert!((7..=33).contains(&heavy), "{heavy} of 2000 below 0.01");
    }

    /// A smooth misfit (half a sine along the beam, the size of the noise) under the noise is
    /// found; the same misfit shuffled along the beam is not.
    #[test]
    fn a_smooth_misfit_is_not_white() {
        let mut rng = TrialRng::new(8, 0, 0);
        let smooth: Vec<Vec<f64>> = (0..6)
            .map(|r| {
                (0..20)
                    .map(|j| {
                        let x = f64::from(j) / 19.0;
                        (std::f64::consts::PI * x * (r + 1) as f64 / 2.0).sin()
                            + 0.5
                                * <StandardNormal as Distribution<f64>>::sample(
                                    &StandardNormal,
                                    &mut rng,
                                )
                    })
                    .collect()
            })
            .collect();
        let found = of_sequences(&smooth);
        assert!(found.p_value < 1e-6, "{found:?}");
        assert_eq!(found.pairs, 6 * 19);
        let shuffled: Vec<Vec<f64>> = smooth
            .iter()
            .map(|z| (0..20).map(|j| z[(j * 7) % 20]).collect())
            .collect();
        assert!(of_sequences(&shuffled).p_value > 1e-3);
    }

    /// The statistic does not depend on the noise scale, and residuals far below the noise
    /// (an exact fit) carry nothing to test.
    #[test]
    fn scale_free_and_nothing_to_test_on_an_exact_fit() {
        let z = vec![vec![0.3, -1.2, 0.8, 0.9, -0.1, 1.4, 0.2]];
        let scaled: Vec<Vec<f64>> = z
            .iter()
            .map(|s| s.iter().map(|v| 40.0 * v).collect())
            .collect();
        let (a, b) = (of_sequences(&z), of_sequences(&scaled));
        assert!((a.statistic - b.statistic).abs() < 1e-12);
        let tiny: Vec<Vec<f64>> = vec![vec![1e-5, 2e-5, 3e-5, 4e-5]];
        assert_eq!(of_sequences(&tiny).p_value, 1.0);
    }
}
