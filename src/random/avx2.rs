//! The uniform shape errors of [`LaneRng`] in explicit AVX2 instructions: xoshiro256++
//! (Blackman & Vigna, "Scrambled linear pseudorandom number generators", ACM TOMS 2021) on
//! four 64-bit lanes per register, two registers per word of state, and the variate
//! e = a (2u - 1) with u = (bits >> 12 as the mantissa of [1, 2)) - 1 (see the parent
//! module). Integer steps are exact and the floating-point steps are the scalar ones, in the
//! same order, one lane per element: every draw is bitwise that of [`LaneRng::shape_errors`].
//! The compiler leaves the lane loop of the portable generator scalar (it does not turn the
//! 64-bit rotations into vector shifts), and the draws were then half of the kernel's time.

use std::arch::x86_64::{
    __m256d, __m256i, _mm256_add_epi64, _mm256_castsi256_pd, _mm256_loadu_si256, _mm256_mul_pd,
    _mm256_or_si256, _mm256_set1_epi64x, _mm256_set1_pd, _mm256_slli_epi64, _mm256_srli_epi64,
    _mm256_storeu_pd, _mm256_storeu_si256, _mm256_sub_pd, _mm256_xor_si256,
};

use super::LaneRng;
use super::{LANES, Lanes};

/// Registers per word of state (`LANES` / 4).
const HALVES: usize = LANES / 4;

impl LaneRng {
    /// [`LaneRng::shape_errors`] for uniform errors, bitwise the same draws.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub unsafe fn uniform_shape_errors_avx2(&mut self, a: f64, out: &mut [Lanes]) {
        // SAFETY: each load reads 4 u64 inside a word of 8.
        let load = |w: &[u64; LANES], h: usize| unsafe {
            _mm256_loadu_si256(w.as_ptr().add(4 * h).cast::<__m256i>())
        };
        // s[h][w]: word w of the lanes 4h .. 4h + 4.
        let mut s: [[__m256i; 4]; HALVES] =
            std::array::from_fn(|h| std::array::from_fn(|w| load(&self.s[w], h)));
        let exponent = _mm256_set1_epi64x(0x3FF0_0000_0000_0000);
        let (one, two, level) = (_mm256_set1_pd(1.0), _mm256_set1_pd(2.0), _mm256_set1_pd(a));
        for o in out.iter_mut() {
            for (state, o4) in s.iter_mut().zip(o.chunks_exact_mut(4)) {
                let [s0, s1, s2, s3] = *state;
                let sum = _mm256_add_epi64(s0, s3);
                let rotated =
                    _mm256_or_si256(_mm256_slli_epi64::<23>(sum), _mm256_srli_epi64::<41>(sum));
                let result = _mm256_add_epi64(rotated, s0);
                let t = _mm256_slli_epi64::<17>(s1);
                let s2 = _mm256_xor_si256(s2, s0);
                let s3 = _mm256_xor_si256(s3, s1);
                let s1 = _mm256_xor_si256(s1, s2);
                let s0 = _mm256_xor_si256(s0, s3);
                let s2 = _mm256_xor_si256(s2, t);
                let s3 = _mm256_or_si256(_mm256_slli_epi64::<45>(s3), _mm256_srli_epi64::<19>(s3));
                *state = [s0, s1, s2, s3];
                let mantissa = _mm256_or_si256(_mm256_srli_epi64::<12>(result), exponent);
                let u: __m256d = _mm256_sub_pd(_mm256_castsi256_pd(mantissa), one);
                let e = _mm256_mul_pd(level, _mm256_sub_pd(_mm256_mul_pd(two, u), one));
                // SAFETY: 4 f64 stored into a chunk of 4.
                unsafe { _mm256_storeu_pd(o4.as_mut_ptr(), e) };
            }
        }
        for (h, state) in s.iter().enumerate() {
            for (word, v) in self.s.iter_mut().zip(state) {
                // SAFETY: 4 u64 stored inside a word of 8.
                unsafe { _mm256_storeu_si256(word.as_mut_ptr().add(4 * h).cast(), *v) };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! Reference: the portable lane generator, itself tested against the scalar stream and
    //! xoshiro256++'s published output in the parent module.
    use super::super::NoiseKind;
    use super::*;

    #[test]
    fn avx2_draws_are_bitwise_the_portable_ones() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            println!("skipped: this CPU has no AVX2");
            return;
        }
        let (mut fast, mut portable) = (LaneRng::new(9, 2, 4096), LaneRng::new(9, 2, 4096));
        let (mut a, mut b) = (vec![[0.0; LANES]; 33], vec![[0.0; LANES]; 33]);
        for round in 0..50 {
            // SAFETY: AVX2 checked above.
            unsafe { fast.uniform_shape_errors_avx2(0.04, &mut a) };
            portable.shape_errors(NoiseKind::Uniform, 0.04, &mut b);
            for (x, y) in a.iter().zip(&b) {
                for l in 0..LANES {
                    assert_eq!(x[l].to_bits(), y[l].to_bits(), "round {round}, lane {l}");
                }
            }
        }
        assert_eq!(fast.s, portable.s);
    }
}
