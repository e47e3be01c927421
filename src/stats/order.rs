//! Order statistics of large samples without comparison sorts: a least-significant-digit
//! radix sort in IEEE 754 total order, and selection of single order statistics.
//!
//! The study's statistics need each column of a cell (up to millions of corrections) in
//! ascending order: its quantiles are order statistics and its sums run over the sorted
//! values, so the sorted array itself is part of the output's definition. Under
//! `f64::total_cmp` two values compare equal only when their bits are equal, so the sorted
//! array is unique: any correct sort gives bitwise the array of `sort_by(f64::total_cmp)`.
//! The radix sort here gets it in six linear passes instead of N log N comparisons.
//!
//! Method: each f64 is mapped to a u64 key whose unsigned order is the total order (the sign
//! bit of a non-negative value is set, every bit of a negative value is flipped; the map of
//! IEEE 754-2008 sec. 5.10 totalOrder, as in `f64::total_cmp`), the keys are sorted by six
//! stable counting passes of 11 bits (Knuth, *The Art of Computer Programming* vol. 3,
//! sec. 5.2.5, radix sorting; all six histograms from one read of the keys), passes whose
//! digit is the same for every key are skipped, and the keys are mapped back.
//!
//! The median absolute deviation needs two order statistics of |x - median| only: they are
//! merged from the sorted sample ([`median_deviation_sorted`], half a pass) or, for samples
//! with NaN, selected (`select_nth_unstable_by`, expected linear time), never sorted.

/// Bits per radix digit.
const DIGIT: u32 = 11;
/// Buckets per digit.
const BUCKETS: usize = 1 << DIGIT;
/// Digits per 64-bit key.
const PASSES: usize = 64usize.div_ceil(DIGIT as usize);
/// Below this length a comparison sort is faster than six counting passes.
const SMALL: usize = 256;

/// The u64 whose unsigned order is the total order of `x`.
#[inline(always)]
fn key(x: f64) -> u64 {
    let bits = x.to_bits();
    bits ^ ((((bits as i64) >> 63) as u64) | (1 << 63))
}

/// The f64 of a key made by [`key`].
#[inline(always)]
fn value(k: u64) -> f64 {
    let mask = if k >> 63 == 1 { 1 << 63 } else { u64::MAX };
    f64::from_bits(k ^ mask)
}

/// Sorts `values` ascending in total order (`f64::total_cmp`: -NaN < -inf < ... < -0 < +0 <
/// ... < +inf < +NaN); the result is bitwise that of `values.sort_by(f64::total_cmp)`.
pub fn sort_total(values: &mut [f64]) {
    if values.len() <= SMALL {
        values.sort_unstable_by(f64::total_cmp);
        return;
    }
    let mut keys: Vec<u64> = values.iter().map(|&x| key(x)).collect();
    let mut spare = vec![0u64; keys.len()];
    let mut counts = vec![[0usize; BUCKETS]; PASSES];
    for &k in &keys {
        for (pass, c) in counts.iter_mut().enumerate() {
            c[digit(k, pass)] += 1;
        }
    }
    for (pass, c) in counts.iter_mut().enumerate() {
        if c.contains(&keys.len()) {
            continue;
        }
        let mut start = 0;
        for slot in c.iter_mut() {
            let count = *slot;
            *slot = start;
            start += count;
        }
        for &k in &keys {
            let d = digit(k, pass);
            spare[c[d]] = k;
            c[d] += 1;
        }
        std::mem::swap(&mut keys, &mut spare);
    }
    for (x, &k) in values.iter_mut().zip(&keys) {
        *x = value(k);
    }
}

#[inline(always)]
fn digit(k: u64, pass: usize) -> usize {
    ((k >> (pass as u32 * DIGIT)) as usize) & (BUCKETS - 1)
}

/// The type-7 quantile `p` in [0, 1] of a non-empty sample in any order, by selection:
/// exactly the value [`super::quantile_sorted`] gives on the sorted sample. `values` is
/// reordered.
pub fn quantile_select(values: &mut [f64], p: f64) -> f64 {
    let n = values.len();
    let h = (n - 1) as f64 * p;
    let lo = h.floor() as usize;
    let (_, &mut below, above) = values.select_nth_unstable_by(lo, f64::total_cmp);
    // The (lo + 1)-th order statistic is the least of what lies above the lo-th.
    let above = above
        .iter()
        .copied()
        .min_by(f64::total_cmp)
        .unwrap_or(below);
    below + (h - lo as f64) * (above - below)
}

/// The median of |x - median| of an ascending sample (type 7, exactly the value of
/// [`quantile_select`] on the deviations), by merging instead of selecting: below the median
/// the deviations grow walking down the sorted sample and above it walking up (subtraction
/// and |.| are monotone under rounding), so the two walks merged from the median outward give
/// the deviations in ascending order, and only the first half is walked. Samples with NaN or
/// an infinite median go through selection.
pub fn median_deviation_sorted(sorted: &[f64], median: f64) -> f64 {
    let n = sorted.len();
    let not_nan = |x: &f64| !x.is_nan();
    if n == 0 || !median.is_finite() || !not_nan(&sorted[0]) || !not_nan(&sorted[n - 1]) {
        let mut deviations: Vec<f64> = sorted.iter().map(|x| (x - median).abs()).collect();
        return quantile_select(&mut deviations, 0.5);
    }
    let h = (n - 1) as f64 * 0.5;
    let lo = h.floor() as usize;
    let hi = (lo + 1).min(n - 1);
    // Below: indices < split (x < median), walked down; above: split.., walked up.
    let split = sorted.partition_point(|&x| x < median);
    let (mut down, mut up) = (split, split);
    let mut next = || {
        let below = (down > 0).then(|| (sorted[down - 1] - median).abs());
        let above = (up < n).then(|| (sorted[up] - median).abs());
        match (below, above) {
            (Some(b), Some(a)) if b < a => {
                down -= 1;
                b
            }
            (_, Some(a)) => {
                up += 1;
                a
            }
            (Some(b), None) => {
                down -= 1;
                b
            }
            (None, None) => unreachable!("at most n deviations are taken"),
        }
    };
    let mut below = 0.0;
    for _ in 0..=lo {
        below = next();
    }
    let above = if hi > lo { next() } else { below };
    below + (h - lo as f64) * (above - below)
}

#[cfg(test)]
mod tests {
    //! Reference: the standard library's comparison sort in total order, an independent
    //! implementation; inputs from a fixed-seed splitmix64 stream of raw bit patterns (every
    //! sign, exponent, subnormal, zero, infinity and NaN) and of values with many ties.
    use super::*;
    use crate::stats::quantile_sorted;

    fn splitmix(state: &mut u64) -> u64 {
        *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    fn samples() -> Vec<Vec<f64>> {
        let mut s = 7;
        let raw: Vec<f64> = (0..5000)
            .map(|_| f64::from_bits(splitmix(&mut s)))
            .collect();
        let mut special = raw.clone();
        special.extend([
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
            f64::MIN_POSITIVE / 4.0,
            -f64::MIN_POSITIVE / 4.0,
        ]);
        let ties: Vec<f64> = (0..3001)
            .map(|_| (splitmix(&mut s) % 17) as f64 - 8.0)
            .collect();
        let smooth: Vec<f64> = (0..4099)
            .map(|_| (splitmix(&mut s) >> 11) as f64 / (1u64 << 53) as f64 * 2.0e6 - 1.0e5)
            .collect();
        let constant = vec![2.5; 1000];
        let small: Vec<f64> = raw[..100].to_vec();
        vec![
            raw,
            special,
            ties,
            smooth,
            constant,
            small,
            vec![],
            vec![1.0],
        ]
    }

    #[test]
    fn key_order_is_the_total_order() {
        for v in samples() {
            for w in v.windows(2) {
                assert_eq!(
                    key(w[0]).cmp(&key(w[1])),
                    w[0].total_cmp(&w[1]),
                    "{:e} {:e}",
                    w[0],
                    w[1]
                );
                assert_eq!(value(key(w[0])).to_bits(), w[0].to_bits());
            }
        }
    }

    #[test]
    fn radix_sort_is_bitwise_the_comparison_sort() {
        for v in samples() {
            let mut expected = v.clone();
            expected.sort_by(f64::total_cmp);
            let mut got = v.clone();
            sort_total(&mut got);
            assert_eq!(bits(&got), bits(&expected), "length {}", v.len());
        }
    }

    #[test]
    fn merged_median_deviation_is_the_selected_one() {
        for v in samples().into_iter().filter(|v| !v.is_empty()) {
            let mut sorted = v.clone();
            sorted.sort_by(f64::total_cmp);
            for w in 1..=sorted.len().min(9) {
                // Every prefix length up to 9 (odd and even N), then the whole sample.
                for s in [&sorted[..w], &sorted[..]] {
                    let median = quantile_sorted(s, 0.5);
                    let mut deviations: Vec<f64> = s.iter().map(|x| (x - median).abs()).collect();
                    let expected = quantile_select(&mut deviations, 0.5);
                    let got = median_deviation_sorted(s, median);
                    assert_eq!(got.to_bits(), expected.to_bits(), "N {}", s.len());
                }
            }
        }
    }

    #[test]
    fn selected_quantiles_are_the_sorted_ones() {
        for v in samples().into_iter().filter(|v| !v.is_empty()) {
            let mut sorted = v.clone();
            sorted.sort_by(f64::total_cmp);
            for p in [0.0, 0.05, 0.25, 0.5, 0.75, 0.95, 1.0, 1.0 / 3.0] {
                let mut work = v.clone();
                let got = quantile_select(&mut work, p);
                let expected = quantile_sorted(&sorted, p);
                assert_eq!(
                    got.to_bits(),
                    expected.to_bits(),
                    "p {p}, length {}: {got:e} vs {expected:e}",
                    v.len()
                );
            }
        }
    }
}
