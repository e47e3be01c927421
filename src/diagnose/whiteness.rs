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

use super::fit::{Fitted, Noise, residuals};
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

/// The whiteness test of the shape residuals of `fitted` on `measured`, standardised by the
/// `working` noise with `floor` (a fraction of the peak).
pub fn whiteness(fitted: &Fitted, measured: &MeasuredModes, working: Noise, floor: f64) -> Whiteness {
    let res = residuals(fitted, measured);
    let mut shape = res.shape.iter();
    let (mut sum, mut sum_sq, mut pairs, mut square, mut values) = (0.0, 0.0, 0, 0.0, 0);
    for mode in measured.modes() {
        let z: Vec<(usize, f64, f64)> = mode
            .points
            .iter()
            .zip(shape.by_ref())
            .map(|(p, &(u, e))| {
                let sigma = working.shape * (u * u + floor * floor).sqrt();
                (p.direction as usize, p.x, e / sigma)
            })
            .collect();
        let mut order: Vec<usize> = (0..z.len()).collect();
        order.sort_by(|&a, &b| z[a].0.cmp(&z[b].0).then(z[a].1.total_cmp(&z[b].1)));
        for w in order.windows(2) {
            let (a, b) = (z[w[0]], z[w[1]]);
            if a.0 == b.0 {
                let p = a.2 * b.2;
                sum += p;
                sum_sq += p * p;
                pairs += 1;
            }
        }
        square += z.iter().map(|v| v.2 * v.2).sum::<f64>();
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
