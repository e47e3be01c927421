//! Where the FRFs were excited: the automatic analysis band, the check of a given band, and
//! the band's extension that gives every kept mode room to its edges.
//!
//! The evidence per line, one of two kinds:
//! - with coherence (the mean over the responses, c): low coherence has two causes, a weak
//!   response (the valley between two modes, where the sensors' noise shows) or a weak input
//!   (outside the excitation's band). With the output noise smooth in frequency, the input's
//!   spectrum is, up to a constant, x = [c / (1 - c)] / sum_o |H_o|^2 (the signal-to-noise
//!   ratio of the response over the response's power), which tells them apart. A line is
//!   *coherent* when c reaches `coherence_min`, and *excited* when its c reaches
//!   [`LEVEL_COHERENCE_FLOOR`] and either its x is within [`LEVEL_RATIO`] of the input's plateau (the upper quartile of x
//!   over the coherent lines) or its c reaches [`COHERENCE_CEILING`] (near a resonance c
//!   stays at its ceiling, set by bias errors, while |H| grows: there x only bounds the input
//!   from below). Where the input rolls off (a band-limited random excitation), x falls by
//!   decades and the line is not excited, however large the response and its coherence below
//!   the ceiling;
//! - without coherence, the FRF's level above its noise: the noise of a line from the second
//!   difference of each response (|H_(k-1) - 2 H_k + H_(k+1)|^2 / 6, the variance of white
//!   noise), the signal-to-noise ratio s = sum |H|^2 / sum noise turned into the coherence it
//!   would give, s / (1 + s), and held to `coherence_min` as above.
//!
//! Both are smoothed by a running median over [`window`] lines (a narrow anti-resonance or
//! a lone line does not split or make a band). The automatic band is the widest run of
//! excited lines. A band given (`--band`) with coherence is refused when fewer than a
//! window of its lines are excited ([`ExtractError::NoExcitation`]).
//!
//! Edges: a mode within `edge_margin` half-power bandwidths (2 zeta f) of an edge of the
//! automatic band has the edge moved out to twice that margin (within the data), once; what
//! remains short is reported with the reason ([`EdgeNote`]).

use faer::c64;
use serde::Serialize;

use super::{ExtractError, FrfSet};

/// Least mean coherence of a line excited by the level rule (see the module docs).
pub const LEVEL_COHERENCE_FLOOR: f64 = 0.5;
/// How far (a factor in power) the input estimate of an excited line may fall below the
/// input's plateau (the upper quartile over the coherent lines).
pub const LEVEL_RATIO: f64 = 10.0;
/// A mean coherence at or above which a line counts as excited whatever its input estimate.
pub const COHERENCE_CEILING: f64 = 0.98;
/// Default least distance of a mode to the band's edges, in half-power bandwidths.
pub const EDGE_MARGIN: f64 = 5.0;

/// Where the analysis band came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BandSource {
    /// Given by the user (`--band`), used as given.
    Given,
    /// The widest run of lines the coherence (and the level) shows excited.
    Coherence,
    /// The widest run of lines whose FRF level stands above its noise (no coherence given).
    Level,
}

/// The odd length of the running median over `n` lines: about 1% of them, at least 5.
pub fn window(n: usize) -> usize {
    (n / 100).max(5) | 1
}

/// The running median of `v` over `w` lines (shorter at the ends, where an even count takes
/// the lower middle value).
fn running_median(v: &[f64], w: usize) -> Vec<f64> {
    let half = w / 2;
    (0..v.len())
        .map(|k| {
            let a = k.saturating_sub(half);
            let b = (k + half + 1).min(v.len());
            let mut part: Vec<f64> = v[a..b].to_vec();
            part.sort_by(f64::total_cmp);
            part[(part.len() - 1) / 2]
        })
        .collect()
}

/// The upper quartile of `v` (NaN when empty).
fn upper_quartile(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[3 * (v.len() - 1) / 4]
}

/// Which lines of `frf` were excited (see the module docs), one flag per line of the data,
/// and the smoothed evidence: the mean coherence, or the coherence-equivalent of the level.
pub struct Excitation {
    /// Excited lines.
    pub excited: Vec<bool>,
    /// The smoothed coherence (or its equivalent from the level) per line.
    pub coherence: Vec<f64>,
    /// The kind of evidence.
    pub source: BandSource,
}

/// The total power sum_o |H_o|^2 of every line.
fn power(responses: &[Vec<c64>], n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| responses.iter().map(|h| h[k].norm_sqr()).sum())
        .collect()
}

/// The coherence-equivalent of the level over the noise, per line (see the module docs).
fn level_coherence(responses: &[Vec<c64>], n: usize) -> Vec<f64> {
    let power = power(responses, n);
    (0..n)
        .map(|k| {
            let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
            let noise: f64 = responses
                .iter()
                .map(|h| (h[a] - 2.0 * h[k] + h[b]).norm_sqr() / 6.0)
                .sum();
            let snr = power[k] / noise;
            if snr.is_finite() {
                snr / (1.0 + snr)
            } else {
                1.0
            }
        })
        .collect()
}

/// The excited lines of `frf` (validated) at coherence threshold `coherence_min`.
pub fn excitation(frf: &FrfSet, coherence_min: f64) -> Excitation {
    let n = frf.frequencies_hz.len();
    let w = window(n);
    let Some(coherence) = &frf.coherence else {
        let c = running_median(&level_coherence(&frf.responses, n), w);
        return Excitation {
            excited: c.iter().map(|&c| c >= coherence_min).collect(),
            coherence: c,
            source: BandSource::Level,
        };
    };
    let mean: Vec<f64> = (0..n)
        .map(|k| coherence.iter().map(|r| r[k]).sum::<f64>() / coherence.len() as f64)
        .collect();
    let power = power(&frf.responses, n);
    let log_input: Vec<f64> = mean
        .iter()
        .zip(&power)
        .map(|(&c, &p)| {
            let c = c.clamp(1e-12, 1.0 - 1e-12);
            (c / (1.0 - c) / p).log10()
        })
        .collect();
    let c = running_median(&mean, w);
    let x = running_median(&log_input, w);
    let plateau = upper_quartile(
        (0..n)
            .filter(|&k| c[k] >= coherence_min && x[k].is_finite())
            .map(|k| x[k])
            .collect(),
    );
    let floor = LEVEL_COHERENCE_FLOOR.min(coherence_min);
    let excited = (0..n)
        .map(|k| {
            c[k] >= floor
                && (c[k] >= COHERENCE_CEILING.max(coherence_min)
                    || x[k] >= plateau - LEVEL_RATIO.log10())
        })
        .collect();
    Excitation {
        excited,
        coherence: c,
        source: BandSource::Coherence,
    }
}

/// The widest run of excited lines above 0 Hz (ties: the lower), as (first, last) line.
pub fn widest_run(f: &[f64], excited: &[bool]) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for k in 0..=excited.len() {
        let on = k < excited.len() && excited[k] && f[k] > 0.0;
        match (on, start) {
            (true, None) => start = Some(k),
            (false, Some(a)) => {
                let b = k - 1;
                let wider = best.is_none_or(|(p, q)| f[b] - f[a] > f[q] - f[p]);
                if b > a && wider {
                    best = Some((a, b));
                }
                start = None;
            }
            _ => {}
        }
    }
    best
}

/// Why an edge of the band stays closer to a mode than the margin.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum EdgeNote {
    /// The band was given (`--band`): it is used as given.
    BandGiven,
    /// The data end there.
    DataEnd {
        /// The last (or first) line above 0 Hz of the data.
        edge_hz: f64,
    },
    /// The band was already extended once; the mode moved or a new one appeared at the edge.
    ExtendedOnce,
}

/// The band moved out so that every (frequency, damping ratio) of `modes` lies `margin`
/// half-power bandwidths inside it, asking twice that (within the data `data`), or None when
/// every mode already has its margin.
pub fn extended(
    (lo, hi): (f64, f64),
    modes: &[(f64, f64)],
    margin: f64,
    data: (f64, f64),
) -> Option<(f64, f64)> {
    let (mut new_lo, mut new_hi) = (lo, hi);
    for &(f, zeta) in modes {
        let bandwidth = 2.0 * zeta * f;
        if f - lo < margin * bandwidth {
            new_lo = new_lo.min(f - 2.0 * margin * bandwidth);
        }
        if hi - f < margin * bandwidth {
            new_hi = new_hi.max(f + 2.0 * margin * bandwidth);
        }
    }
    let (new_lo, new_hi) = (new_lo.max(data.0), new_hi.min(data.1));
    (new_lo < lo || new_hi > hi).then_some((new_lo, new_hi))
}

/// Refuses a band given with coherence in which fewer than a [`window`] of lines are excited.
pub fn check_given(
    frf: &FrfSet,
    lines: &[usize],
    (lo, hi): (f64, f64),
    coherence_min: f64,
) -> Result<(), ExtractError> {
    if frf.coherence.is_none() {
        return Ok(());
    }
    let e = excitation(frf, coherence_min);
    let count = lines.iter().filter(|&&k| e.excited[k]).count();
    if count >= window(frf.frequencies_hz.len()).min(lines.len()) {
        return Ok(());
    }
    let best = lines
        .iter()
        .map(|&k| e.coherence[k])
        .fold(0.0_f64, f64::max);
    Err(ExtractError::NoExcitation {
        lo,
        hi,
        best,
        threshold: coherence_min,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::extract::Quantity;

    /// A single-mode accelerance on 0..200 Hz (0.25 Hz lines) measured with an input of unit
    /// level below `cut` Hz and 1e-4 above, and a white output noise: the coherence
    /// |H|^2 u / (|H|^2 u + n), at most 0.995 (the bias near the resonance). It falls to 0.7 in
    /// the valley above the mode, where the response is weak.
    fn set(cut: f64) -> FrfSet {
        let f: Vec<f64> = (0..801).map(|k| k as f64 * 0.25).collect();
        let h: Vec<c64> = f
            .iter()
            .map(|&x| {
                let r = x / 40.0;
                c64::new(1.0 - r * r, 0.04 * r).inv() * (0.3 + r * r)
            })
            .collect();
        let valley = h.iter().map(|v| v.norm_sqr()).fold(f64::INFINITY, f64::min);
        let noise = valley * 0.3 / 0.7;
        let coherence: Vec<f64> = f
            .iter()
            .zip(&h)
            .map(|(&x, v)| {
                let u = if x < cut { 1.0 } else { 1e-4 };
                let s = v.norm_sqr() * u;
                (s / (s + noise)).min(0.995)
            })
            .collect();
        FrfSet {
            frequencies_hz: f,
            responses: vec![h],
            coherence: Some(vec![coherence]),
            quantity: Quantity::Acceleration,
        }
    }

    #[test]
    fn the_band_ends_where_the_coherence_shows_no_input() {
        let frf = set(150.0);
        let e = excitation(&frf, 0.8);
        let (a, b) = widest_run(&frf.frequencies_hz, &e.excited).unwrap();
        let f = &frf.frequencies_hz;
        // The valley stays in: its low coherence comes with a low response.
        let low = (0..f.len())
            .filter(|&k| f[k] < 150.0)
            .map(|k| frf.coherence.as_ref().unwrap()[0][k]);
        assert!(low.fold(1.0, f64::min) < 0.75);
        assert!(
            f[a] <= 1.5 && (148.0..=150.0).contains(&f[b]),
            "{} {}",
            f[a],
            f[b]
        );
    }

    #[test]
    fn a_band_without_excitation_is_refused() {
        let frf = set(150.0);
        let lines: Vec<usize> = (640..=760).collect();
        let got = check_given(&frf, &lines, (160.0, 190.0), 0.8).unwrap_err();
        assert_eq!(
            got.to_string(),
            "band 160..190 Hz shows no excitation: its smoothed mean coherence reaches 0.003 \
             (0.8 needed) and the level does not explain it; give a band the input covered"
        );
        let lines: Vec<usize> = (40..=400).collect();
        assert_eq!(check_given(&frf, &lines, (10.0, 100.0), 0.8), Ok(()));
    }

    #[test]
    fn data_without_coherent_lines_have_no_automatic_band() {
        let mut frf = set(150.0);
        frf.coherence = Some(vec![vec![0.3; frf.frequencies_hz.len()]]);
        let got = crate::extract::frf::band(&frf, &crate::extract::Settings::default());
        assert_eq!(
            got.unwrap_err().to_string(),
            "no frequency band shows excitation: the mean coherence, smoothed over 1% of the \
             lines, reaches 0.3 at best (0.8 needed); give the band explicitly or lower the \
             coherence threshold"
        );
    }

    #[test]
    fn edges_move_out_for_a_mode_near_them_within_the_data() {
        // 20 Hz, 1%: a bandwidth of 0.4 Hz; 5 of them is 2 Hz, so 21 Hz is too near.
        let modes = [(20.0, 0.01), (80.0, 0.01)];
        assert_eq!(
            extended((19.0, 100.0), &modes, 5.0, (0.25, 200.0)),
            Some((16.0, 100.0))
        );
        assert_eq!(extended((10.0, 100.0), &modes, 5.0, (0.25, 200.0)), None);
        assert_eq!(
            extended((10.0, 81.0), &modes, 5.0, (0.25, 82.0)),
            Some((10.0, 82.0))
        );
    }

    #[test]
    fn the_running_median_ignores_a_lone_line() {
        let v = [1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 9.0, 1.0];
        assert_eq!(
            running_median(&v, 3),
            [1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]
        );
    }
}
