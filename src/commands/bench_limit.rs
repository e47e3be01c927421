//! The limit of the study kernel on this machine, per trial-mode and thread: the time of the
//! random draws alone (the engine's own generator, `LANES` trials side by side, compiled for
//! AVX2 when the CPU has it, as the engine is) plus the kernel's floating-point operations at
//! the measured peak rate of independent multiplies and adds (no FMA: the engine contracts
//! nothing, so that every instruction set gives the same bits). `jointid bench` prints the
//! engine's time per trial-mode beside it.

use std::hint::black_box;
use std::time::Instant;

use jointid::identify::{LANES, Lanes};
use jointid::random::{LaneRng, NoiseKind};
use jointid::study::CellPlan;

/// The measured parts of the limit.
pub struct Limit {
    /// Nanoseconds per trial-mode of the random draws alone.
    pub draws_ns: f64,
    /// Floating-point operations per trial-mode.
    pub flops: usize,
    /// Floating-point operations per second of one thread (independent mul and add).
    pub flop_rate: f64,
}

impl Limit {
    /// Measures the limit for `plan` (basis size `n`) over `trials` trials.
    pub fn measure(plan: &CellPlan, n: usize, trials: usize) -> Self {
        let (modes, count) = (plan.modes.len(), plan.identified.len());
        let start = Instant::now();
        black_box(draws(trials, modes, count));
        let draws_ns = start.elapsed().as_secs_f64() * 1e9 / (trials * modes) as f64;
        let iterations = 20_000_000;
        let start = Instant::now();
        black_box(flop_loop(iterations));
        let flop_rate = (iterations * CHAINS * 4 * 2) as f64 / start.elapsed().as_secs_f64();
        Self {
            draws_ns,
            flops: flops(plan, n),
            flop_rate,
        }
    }

    /// The limit, ns per trial-mode: draws plus flops at the peak rate.
    pub fn ns(&self) -> f64 {
        self.draws_ns + self.flops as f64 / self.flop_rate * 1e9
    }
}

/// Floating-point operations of one trial-mode with shape noise only and no mass term:
/// the perturbed shape (6 per identified element: the uniform variate from its bits, times
/// the level, exact * (1 + e)), the projection g = P y (2 n n_id), the assembly of eq.
/// (10)-(12) (3 m for W b, q m (2 n + 1) for W S), the QR (two norms per column, one division
/// per element, 4 m per projected column or right-hand side), the back substitution (q^2) and
/// Delta p = p z (q).
pub fn flops(plan: &CellPlan, n: usize) -> usize {
    let (id, q) = (plan.identified.len(), plan.q());
    let m = plan.modes.first().map_or(0, |p| p.system.m());
    let qr = 2 * q * (2 * m + 1) + q * m + (0..q).map(|k| (q - k) * 4 * m).sum::<usize>();
    6 * id + 2 * n * id + 3 * m + q * m * (2 * n + 1) + qr + q * q + q
}

fn draws(trials: usize, modes: usize, count: usize) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { draws_avx2(trials, modes, count) };
    }
    draws_portable(trials, modes, count)
}

/// [`draws_portable`] with the engine's AVX2 generator.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn draws_avx2(trials: usize, modes: usize, count: usize) -> f64 {
    let mut out: Vec<Lanes> = vec![[0.0; LANES]; count];
    let mut sum = [0.0; LANES];
    for first in (0..trials).step_by(LANES) {
        let mut rng = LaneRng::new(1, 0, first as u64);
        for _ in 0..modes {
            // SAFETY: AVX2 is enabled in this function, called only after the CPU was checked.
            unsafe { rng.uniform_shape_errors_avx2(0.04, &mut out) };
            for o in &out {
                for l in 0..LANES {
                    sum[l] += o[l];
                }
            }
        }
    }
    sum.iter().sum()
}

/// The draws of `trials` trials of `modes` modes, summed so that none is optimised away.
fn draws_portable(trials: usize, modes: usize, count: usize) -> f64 {
    let mut out: Vec<Lanes> = vec![[0.0; LANES]; count];
    let mut sum = [0.0; LANES];
    for first in (0..trials).step_by(LANES) {
        let mut rng = LaneRng::new(1, 0, first as u64);
        for _ in 0..modes {
            rng.shape_errors(NoiseKind::Uniform, 0.04, &mut out);
            for o in &out {
                for l in 0..LANES {
                    sum[l] += o[l];
                }
            }
        }
    }
    sum.iter().sum()
}

/// Independent accumulators: enough to cover the latency of a multiply and an add.
const CHAINS: usize = 12;

fn flop_loop(iterations: usize) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU supports AVX2, checked just above.
        return unsafe { flop_loop_avx2(iterations) };
    }
    let (c, d) = (black_box(0.999_999_9), black_box(1e-9));
    let mut x = [[1.0f64; 4]; CHAINS];
    for _ in 0..iterations {
        for e in x.iter_mut().flatten() {
            *e = *e * c + d;
        }
    }
    x.iter().flatten().sum()
}

/// x <- x c + d on `CHAINS` registers of 4 (explicit AVX instructions, so that the count of
/// multiplies and adds is the one written): one multiply and one add per element.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn flop_loop_avx2(iterations: usize) -> f64 {
    use std::arch::x86_64::{_mm256_add_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_storeu_pd};
    let c = _mm256_set1_pd(black_box(0.999_999_9));
    let d = _mm256_set1_pd(black_box(1e-9));
    let mut x = [_mm256_set1_pd(1.0); CHAINS];
    for _ in 0..iterations {
        for v in x.iter_mut() {
            *v = _mm256_add_pd(_mm256_mul_pd(*v, c), d);
        }
    }
    let mut sum = 0.0;
    for v in x {
        let mut out = [0.0; 4];
        // SAFETY: `out` has room for the 4 values stored.
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), v) };
        sum += out.iter().sum::<f64>();
    }
    sum
}
