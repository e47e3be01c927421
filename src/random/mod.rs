//! The random streams shared by [`crate::study`] and [`crate::simulate`], and the
//! measurement-error model they draw.
//!
//! Shape: every identified element is multiplied by (1 + e). `uniform` (the paper's
//! "random errors of maximum value +-4%"): e uniform on [-a, a], a = shape_noise, variance
//! a^2/3. `gaussian`: e normal with standard deviation a.
//!
//! Frequency: f = f_true (1 + eps), eps with standard deviation sigma_f = frequency_noise;
//! normal under `gaussian`, uniform on [-sqrt(3) sigma_f, sqrt(3) sigma_f] under `uniform`.
//! Nothing is drawn for a zero level.
//!
//! Streams: trial t of cell c draws from xoshiro256++ (Blackman & Vigna, "Scrambled linear
//! pseudorandom number generators", 2021) whose state is
//! (mix(seed), mix(c ^ K1), mix(t ^ K2), mix(seed ^ c ^ t ^ K3)), mix being the SplitMix64
//! finaliser (a bijection of u64) and K1..K3 fixed odd constants: distinct (seed, cell,
//! trial) give distinct states, and the state is never zero. A trial
//! draws, for each mode in grid order, its shape errors in ascending DOF order, then its
//! frequency error. A uniform variate takes the top 52 bits of one u64 as the mantissa of a
//! number in [1, 2): u = from_bits(0x3FF0_0000_0000_0000 | x >> 12) - 1, in [0, 1), and
//! e = a (2u - 1). Normal variates are rand_distr's `StandardNormal`. The output is thus a
//! function of (seed, cell, trial) alone, whatever the number of threads.
//!
//! [`LaneRng`] runs the streams of [`LANES`] consecutive trials side by side (structure of
//! arrays, so that uniform draws vectorise); lane l is exactly the stream of [`TrialRng`] for
//! its trial.
//!
//! Layer 1 (foundations; see the crate docs): may import, without a circle, the other foundations:
//! [`crate::stats`], [`crate::input`], [`crate::structure`], [`crate::uff`].

use std::fmt;
use std::str::FromStr;

use std::convert::Infallible;

use rand_distr::{Distribution, StandardNormal};

#[cfg(target_arch = "x86_64")]
mod avx2;

/// Number of trials drawn side by side by [`LaneRng`], and solved side by side by the study
/// engine's batched systems (`identify::ModeSystem::assemble_lanes`).
pub const LANES: usize = 8;

/// One value per lane.
pub type Lanes = [f64; LANES];

/// The noise distribution of a study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseKind {
    /// Uniform errors; shape_noise is the maximum relative error.
    Uniform,
    /// Normal errors; shape_noise is the standard deviation.
    Gaussian,
}

impl NoiseKind {
    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            NoiseKind::Uniform => "uniform",
            NoiseKind::Gaussian => "gaussian",
        }
    }

    /// Variance of the relative shape error for the level `a`.
    pub fn shape_variance(self, a: f64) -> f64 {
        match self {
            NoiseKind::Uniform => a * a / 3.0,
            NoiseKind::Gaussian => a * a,
        }
    }
}

impl fmt::Display for NoiseKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for NoiseKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "uniform" => Ok(NoiseKind::Uniform),
            "gaussian" => Ok(NoiseKind::Gaussian),
            _ => Err("it must be \"uniform\" (the paper) or \"gaussian\"".to_string()),
        }
    }
}

/// The random stream of one trial: xoshiro256++ (see the module docs).
#[derive(Debug, Clone)]
pub struct TrialRng {
    s: [u64; 4],
}

/// One step of xoshiro256++: the output of state (s0, s1, s2, s3), which advances.
#[inline(always)]
fn xoshiro_step(s0: &mut u64, s1: &mut u64, s2: &mut u64, s3: &mut u64) -> u64 {
    let result = s0.wrapping_add(*s3).rotate_left(23).wrapping_add(*s0);
    let t = *s1 << 17;
    *s2 ^= *s0;
    *s3 ^= *s1;
    *s1 ^= *s2;
    *s0 ^= *s3;
    *s2 ^= t;
    *s3 = s3.rotate_left(45);
    result
}

/// The SplitMix64 finaliser: a bijection of u64 with full avalanche.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

const K1: u64 = 0xD1B5_4A32_D192_ED03;
const K2: u64 = 0xAEF1_7502_108E_F2D9;
const K3: u64 = 0x8CB9_2BA7_2F3D_8DD7;

impl TrialRng {
    /// The stream of trial `trial` of cell `cell` (see the module docs).
    pub fn new(seed: u64, cell: u64, trial: u64) -> Self {
        TrialRng {
            s: [
                mix(seed),
                mix(cell ^ K1),
                mix(trial ^ K2),
                mix(seed ^ cell ^ trial ^ K3),
            ],
        }
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        let [s0, s1, s2, s3] = &mut self.s;
        xoshiro_step(s0, s1, s2, s3)
    }

    /// A uniform variate on [-1, 1).
    #[inline]
    pub fn symmetric_unit(&mut self) -> f64 {
        symmetric_unit(self.next_u64())
    }

    /// A standard normal variate.
    #[inline]
    pub fn standard_normal(&mut self) -> f64 {
        StandardNormal.sample(self)
    }

    /// A relative error of the given kind with shape level `a` (maximum or std).
    #[inline]
    pub fn shape_error(&mut self, kind: NoiseKind, a: f64) -> f64 {
        match kind {
            NoiseKind::Uniform => a * self.symmetric_unit(),
            NoiseKind::Gaussian => a * self.standard_normal(),
        }
    }

    /// A relative frequency error with standard deviation `sigma`.
    #[inline]
    pub fn frequency_error(&mut self, kind: NoiseKind, sigma: f64) -> f64 {
        match kind {
            NoiseKind::Uniform => 3f64.sqrt() * sigma * self.symmetric_unit(),
            NoiseKind::Gaussian => sigma * self.standard_normal(),
        }
    }
}

/// The uniform variate on [-1, 1) of 64 random bits (see the module docs).
#[inline(always)]
fn symmetric_unit(x: u64) -> f64 {
    let u = f64::from_bits(0x3FF0_0000_0000_0000 | (x >> 12)) - 1.0;
    2.0 * u - 1.0
}

/// The streams of `LANES` consecutive trials, side by side.
#[derive(Debug, Clone)]
pub struct LaneRng {
    s: [[u64; LANES]; 4],
}

impl LaneRng {
    /// Lane l is the stream of trial `first + l` of cell `cell`.
    pub fn new(seed: u64, cell: u64, first: u64) -> Self {
        let trials: [TrialRng; LANES] =
            std::array::from_fn(|l| TrialRng::new(seed, cell, first + l as u64));
        LaneRng {
            s: std::array::from_fn(|w| std::array::from_fn(|l| trials[l].s[w])),
        }
    }

    /// The next 64 bits of every lane (xoshiro256++, lane-wise).
    #[inline(always)]
    fn next_lanes(&mut self) -> [u64; LANES] {
        let [s0, s1, s2, s3] = &mut self.s;
        let mut out = [0; LANES];
        for l in 0..LANES {
            out[l] = xoshiro_step(&mut s0[l], &mut s1[l], &mut s2[l], &mut s3[l]);
        }
        out
    }

    /// Lane `l` alone, as a scalar stream.
    fn lane(&mut self, l: usize) -> LaneView<'_> {
        LaneView { rng: self, lane: l }
    }

    /// Relative shape errors of level `a`: `out[j][l]` is the j-th draw of lane l.
    #[inline(always)]
    pub fn shape_errors(&mut self, kind: NoiseKind, a: f64, out: &mut [Lanes]) {
        match kind {
            NoiseKind::Uniform => {
                for o in out.iter_mut() {
                    let x = self.next_lanes();
                    for l in 0..LANES {
                        o[l] = a * symmetric_unit(x[l]);
                    }
                }
            }
            NoiseKind::Gaussian => {
                for l in 0..LANES {
                    let mut lane = self.lane(l);
                    for o in out.iter_mut() {
                        o[l] = a * lane.standard_normal();
                    }
                }
            }
        }
    }

    /// One relative frequency error of standard deviation `sigma` per lane.
    #[inline(always)]
    pub fn frequency_errors(&mut self, kind: NoiseKind, sigma: f64) -> Lanes {
        std::array::from_fn(|l| {
            let mut lane = self.lane(l);
            match kind {
                NoiseKind::Uniform => 3f64.sqrt() * sigma * symmetric_unit(lane.next()),
                NoiseKind::Gaussian => sigma * lane.standard_normal(),
            }
        })
    }
}

/// One lane of a [`LaneRng`].
struct LaneView<'a> {
    rng: &'a mut LaneRng,
    lane: usize,
}

impl LaneView<'_> {
    #[inline]
    fn next(&mut self) -> u64 {
        let [s0, s1, s2, s3] = &mut self.rng.s;
        let l = self.lane;
        xoshiro_step(&mut s0[l], &mut s1[l], &mut s2[l], &mut s3[l])
    }

    fn standard_normal(&mut self) -> f64 {
        StandardNormal.sample(self)
    }
}

/// rand_core's generator trait over a `next` of 64 bits, for rand_distr's distributions.
macro_rules! try_rng_from_u64 {
    ($t:ty, $next:ident) => {
        impl rand_core::TryRng for $t {
            type Error = Infallible;

            #[inline]
            fn try_next_u32(&mut self) -> Result<u32, Infallible> {
                Ok((self.$next() >> 32) as u32)
            }

            #[inline]
            fn try_next_u64(&mut self) -> Result<u64, Infallible> {
                Ok(self.$next())
            }

            fn try_fill_bytes(&mut self, dst: &mut [u8]) -> Result<(), Infallible> {
                for chunk in dst.chunks_mut(8) {
                    chunk.copy_from_slice(&self.$next().to_le_bytes()[..chunk.len()]);
                }
                Ok(())
            }
        }
    };
}

try_rng_from_u64!(TrialRng, next_u64);
try_rng_from_u64!(LaneView<'_>, next);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xoshiro256plusplus_reference_output() {
        // Reference: the authors' xoshiro256plusplus.c from state {1, 2, 3, 4} gives
        // 41943041, 58720359, 3588806011781223, 3591011842654386.
        let mut r = TrialRng { s: [1, 2, 3, 4] };
        let out: Vec<u64> = (0..4).map(|_| r.next_u64()).collect();
        assert_eq!(
            out,
            vec![41943041, 58720359, 3588806011781223, 3591011842654386]
        );
    }

    #[test]
    fn lane_l_is_the_scalar_stream_of_its_trial() {
        for kind in [NoiseKind::Uniform, NoiseKind::Gaussian] {
            let mut lanes = LaneRng::new(3, 5, 100);
            let mut shape = vec![[0.0; LANES]; 7];
            let mut draws = Vec::new();
            for _ in 0..2 {
                lanes.shape_errors(kind, 0.04, &mut shape);
                draws.push((shape.clone(), lanes.frequency_errors(kind, 0.01)));
            }
            for l in 0..LANES {
                let mut scalar = TrialRng::new(3, 5, 100 + l as u64);
                for (shape, freq) in &draws {
                    for row in shape {
                        assert_eq!(
                            row[l].to_bits(),
                            scalar.shape_error(kind, 0.04).to_bits(),
                            "{kind}, lane {l}"
                        );
                    }
                    assert_eq!(
                        freq[l].to_bits(),
                        scalar.frequency_error(kind, 0.01).to_bits()
                    );
                }
            }
        }
    }

    #[test]
    fn streams_depend_on_seed_cell_and_trial_only() {
        let draw = |s, c, t| {
            let mut r = TrialRng::new(s, c, t);
            (0..4).map(|_| r.symmetric_unit()).collect::<Vec<_>>()
        };
        assert_eq!(draw(1, 2, 3), draw(1, 2, 3));
        assert_ne!(draw(1, 2, 3), draw(1, 2, 4));
        assert_ne!(draw(1, 2, 3), draw(1, 3, 3));
        assert_ne!(draw(1, 2, 3), draw(2, 2, 3));
    }

    #[test]
    fn error_distributions_have_their_stated_moments() {
        let mut r = TrialRng::new(7, 0, 0);
        let n = 200_000;
        for kind in [NoiseKind::Uniform, NoiseKind::Gaussian] {
            let x: Vec<f64> = (0..n).map(|_| r.shape_error(kind, 0.04)).collect();
            let mean = x.iter().sum::<f64>() / n as f64;
            let var = x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1) as f64;
            assert!(
                mean.abs() < 5.0 * (kind.shape_variance(0.04) / n as f64).sqrt(),
                "{kind}: mean {mean}"
            );
            assert!(
                (var / kind.shape_variance(0.04) - 1.0).abs() < 0.02,
                "{kind}: var {var}"
            );
            let f: Vec<f64> = (0..n).map(|_| r.frequency_error(kind, 0.01)).collect();
            let fvar = f.iter().map(|v| v * v).sum::<f64>() / n as f64;
            assert!(
                (fvar / 1e-4 - 1.0).abs() < 0.02,
                "{kind}: frequency var {fvar}"
            );
        }
        let mut r = TrialRng::new(1, 1, 1);
        assert!(
            (0..10_000)
                .map(|_| r.shape_error(NoiseKind::Uniform, 0.04))
                .all(|e| e.abs() <= 0.04)
        );
    }
}
