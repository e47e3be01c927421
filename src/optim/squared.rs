//! The squared extrapolation of a slow fixed-point iteration x -> F(x) (Varadhan & Roland,
//! "Simple and globally convergent methods for accelerating the convergence of any EM
//! algorithm", Scand. J. Stat. 35, 2008: their scheme S3). From x0, x1 = F(x0), x2 = F(x1):
//!
//! ```text
//!   r = x1 - x0,   v = x2 - 2 x1 + x0,   alpha = -|r| / |v|   (at most -1)
//!   x' = x0 - 2 alpha r + alpha^2 v
//! ```
//!
//! For a linear map of contraction rate c along r the iteration's error falls by c per step;
//! x' lands on the fixed point in one step (alpha = -1 / (1 - c)). alpha = -1 gives x' = x2,
//! the plain iteration's two steps: the extrapolation never goes less far than they do. The
//! caller checks the objective at x' and keeps the plain step where it is worse (the method's
//! global convergence). Every component is kept at or above its lower bound (variances: 0).

/// Largest |alpha|: a step of 64 times the plain one is far past where a linearisation of F
/// can be trusted.
pub const MAX_STEP: f64 = 64.0;

/// x' of the module docs from `x0`, `x1` = F(x0), `x2` = F(x1), every component at least
/// `floor`; None where the two steps do not differ (v = 0: a fixed point, or a linear map of
/// rate 0) or a component is not finite.
pub fn extrapolate(x0: &[f64], x1: &[f64], x2: &[f64], floor: f64) -> Option<Vec<f64>> {
    let r: Vec<f64> = x1.iter().zip(x0).map(|(a, b)| a - b).collect();
    let v: Vec<f64> = x2
        .iter()
        .zip(x1)
        .zip(x0)
        .map(|((c, b), a)| c - 2.0 * b + a)
        .collect();
    let norm = |u: &[f64]| u.iter().map(|e| e * e).sum::<f64>().sqrt();
    let (nr, nv) = (norm(&r), norm(&v));
    if !nr.is_finite() || !nv.is_finite() || nv <= 0.0 {
        return None;
    }
    let alpha = (-nr / nv).clamp(-MAX_STEP, -1.0);
    Some(
        x0.iter()
            .zip(&r)
            .zip(&v)
            .map(|((a, r), v)| (a - 2.0 * alpha * r + alpha * alpha * v).max(floor))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A linear contraction x -> p + c (x - p) is solved in one step where 1 / (1 - c) is
    /// within [`MAX_STEP`]; beyond, the step stops at that many plain steps' length.
    #[test]
    fn a_linear_contraction_is_solved_in_one_step() {
        let p = [0.3, -1.2];
        for c in [0.1, 0.5, 0.93, 0.98] {
            let f = |x: &[f64]| -> Vec<f64> {
                x.iter().zip(&p).map(|(x, p)| p + c * (x - p)).collect()
            };
            let x0 = vec![2.0, 4.0];
            let x1 = f(&x0);
            let x2 = f(&x1);
            let x = extrapolate(&x0, &x1, &x2, f64::NEG_INFINITY).unwrap();
            for (a, b) in x.iter().zip(&p) {
                assert!(
                    (a - b).abs() < 1e-12 * (1.0 + b.abs()),
                    "c {c}: {a} against {b}"
                );
            }
        }
        let f = |x: f64| 0.99 * x;
        let x = extrapolate(&[1.0], &[f(1.0)], &[f(f(1.0))], f64::NEG_INFINITY).unwrap()[0];
        // x0 - 2 alpha r + alpha^2 v with alpha = -64, r = -0.01, v = 1e-4.
        let capped = 1.0 - 2.0 * 64.0 * 0.01 + 64.0 * 64.0 * 1e-4;
        assert!((x - capped).abs() < 1e-9, "{x} against {capped}");
    }

    /// A map that overshoots its fixed point (rate c < 0: |alpha| < 1) takes the plain two
    /// steps, never a shorter one; the floor holds; no step where the map stands still.
    #[test]
    fn the_step_is_never_shorter_than_two_plain_ones_and_keeps_the_floor() {
        let f = |x: f64| 0.4 - 0.5 * (x - 0.4);
        let (x0, x1) = (1.0, f(1.0));
        let x = extrapolate(&[x0], &[x1], &[f(x1)], 0.0).unwrap()[0];
        assert!((x - f(x1)).abs() < 1e-15, "{x} against {}", f(x1));
        // Towards a fixed point below the floor: the floor.
        let g = |x: f64| -0.5 + 0.9 * (x + 0.5);
        let (y1, y2) = (g(0.2), g(g(0.2)));
        assert_eq!(extrapolate(&[0.2], &[y1], &[y2], 0.0).unwrap(), vec![0.0]);
        assert!(extrapolate(&[0.2, 1.0], &[0.2, 1.0], &[0.2, 1.0], 0.0).is_none());
        assert!(extrapolate(&[0.0], &[1.0], &[f64::NAN], 0.0).is_none());
    }
}
