//! The input of the extraction: a set of FRFs of one reference, its checks, and the analysis
//! band (the lines the estimators see, with their weights).

use faer::c64;

use super::excitation::{self, BandSource};
use super::{ExtractError, Settings};

/// The response quantity of the FRFs, per unit of the reference (force or voltage).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Receptance (m/N).
    Displacement,
    /// Mobility ((m/s)/N).
    Velocity,
    /// Accelerance ((m/s^2)/N).
    Acceleration,
}

impl Quantity {
    /// The power p of (i omega) that turns a receptance into this quantity: H = (i omega)^p H_d.
    pub fn power(self) -> i32 {
        match self {
            Quantity::Displacement => 0,
            Quantity::Velocity => 1,
            Quantity::Acceleration => 2,
        }
    }

    /// The name used in files and messages.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Displacement => "displacement",
            Quantity::Velocity => "velocity",
            Quantity::Acceleration => "acceleration",
        }
    }
}

/// FRFs of one reference to several responses, on one evenly spaced frequency axis.
#[derive(Debug, Clone)]
pub struct FrfSet {
    /// Frequency lines (Hz), ascending, evenly spaced, >= 0.
    pub frequencies_hz: Vec<f64>,
    /// One FRF per response channel, one value per line.
    pub responses: Vec<Vec<c64>>,
    /// Ordinary coherence per response and line, in [0, 1], when measured.
    pub coherence: Option<Vec<Vec<f64>>>,
    /// The response quantity.
    pub quantity: Quantity,
}

/// Relative tolerance on the frequency step: line k must lie within this fraction of a step
/// of f_0 + k df (files that print frequencies with a few digits stay accepted).
pub const SPACING_TOLERANCE: f64 = 1e-3;

impl FrfSet {
    /// Checks the shape and values of the set: see [`ExtractError`] for every failure.
    pub fn validate(&self) -> Result<(), ExtractError> {
        let f = &self.frequencies_hz;
        let n = f.len();
        if n < 2 {
            return Err(ExtractError::TooFewLines {
                lines: n,
                needed: 2,
                max_order: 0,
            });
        }
        if self.responses.is_empty() {
            return Err(ExtractError::NoResponses);
        }
        for (index, &value) in f.iter().enumerate() {
            if !value.is_finite() || value < 0.0 {
                return Err(ExtractError::BadFrequency { index, value });
            }
            if index > 0 && value <= f[index - 1] {
                return Err(ExtractError::NotAscending {
                    index,
                    value,
                    previous: f[index - 1],
                });
            }
        }
        let step = (f[n - 1] - f[0]) / (n - 1) as f64;
        let tolerance = SPACING_TOLERANCE * step;
        for (index, &value) in f.iter().enumerate() {
            let expected = f[0] + index as f64 * step;
            if (value - expected).abs() > tolerance {
                return Err(ExtractError::UnevenSpacing {
                    index,
                    value,
                    expected,
                    step,
                    tolerance,
                });
            }
        }
        for (response, h) in self.responses.iter().enumerate() {
            if h.len() != n {
                return Err(ExtractError::LengthMismatch {
                    response,
                    len: h.len(),
                    expected: n,
                });
            }
            if let Some(index) = h
                .iter()
                .position(|v| !v.re.is_finite() || !v.im.is_finite())
            {
                return Err(ExtractError::NonFinite {
                    response,
                    index,
                    frequency_hz: f[index],
                    re: h[index].re,
                    im: h[index].im,
                });
            }
        }
        if let Some(coherence) = &self.coherence {
            if coherence.len() != self.responses.len() {
                return Err(ExtractError::CoherenceCount {
                    count: coherence.len(),
                    expected: self.responses.len(),
                });
            }
            for (response, c) in coherence.iter().enumerate() {
                if c.len() != n {
                    return Err(ExtractError::CoherenceLength {
                        response,
                        len: c.len(),
                        expected: n,
                    });
                }
                if let Some(index) = c.iter().position(|v| !(0.0..=1.0).contains(v)) {
                    return Err(ExtractError::CoherenceRange {
                        response,
                        index,
                        frequency_hz: f[index],
                        value: c[index],
                    });
                }
            }
        }
        Ok(())
    }
}

/// The lines the estimators see.
#[derive(Debug, Clone)]
pub struct Band {
    /// Band edges (Hz).
    pub lo: f64,
    /// Upper edge (Hz).
    pub hi: f64,
    /// Indices of the lines in the band (0 Hz excluded: the residual terms are singular there).
    pub lines: Vec<usize>,
    /// Weight per line of the band: the coherence averaged over the responses, or 1.
    pub weights: Vec<f64>,
    /// Where the band came from.
    pub source: BandSource,
}

/// The analysis band: `settings.band_hz` when given (refused with coherence when the
/// coherence shows no excitation in it, [`excitation::check_given`]); else the widest run of
/// excited lines ([`excitation`]: the coherence and the level, or the level alone).
pub fn band(frf: &FrfSet, settings: &Settings) -> Result<Band, ExtractError> {
    let f = &frf.frequencies_hz;
    let (data_lo, data_hi) = (f[0], f[f.len() - 1]);
    let step = (data_hi - data_lo) / (f.len() - 1) as f64;
    let slack = SPACING_TOLERANCE * step;
    let (lo, hi, source) = match settings.band_hz {
        Some((lo, hi)) => {
            if !(lo.is_finite() && hi.is_finite() && lo < hi)
                || lo < data_lo - slack
                || hi > data_hi + slack
            {
                return Err(ExtractError::BadBand {
                    lo,
                    hi,
                    data_lo,
                    data_hi,
                });
            }
            (lo, hi, BandSource::Given)
        }
        None => {
            let e = excitation::excitation(frf, settings.coherence_min);
            match excitation::widest_run(f, &e.excited) {
                Some((a, b)) => (f[a], f[b], e.source),
                None if e.source == BandSource::Level => (data_lo, data_hi, e.source),
                None => {
                    return Err(ExtractError::NoCoherentBand {
                        threshold: settings.coherence_min,
                        best: e.coherence.iter().copied().fold(0.0, f64::max),
                    });
                }
            }
        }
    };
    let band = band_of(frf, (lo, hi), source);
    if source == BandSource::Given {
        excitation::check_given(frf, &band.lines, (lo, hi), settings.coherence_min)?;
    }
    Ok(band)
}

/// The band `lo`..`hi` (Hz, within the data, checked) of `frf`: its lines above 0 Hz and their
/// weights (the mean coherence, or 1).
pub fn band_of(frf: &FrfSet, (lo, hi): (f64, f64), source: BandSource) -> Band {
    let f = &frf.frequencies_hz;
    let step = (f[f.len() - 1] - f[0]) / (f.len() - 1) as f64;
    let slack = SPACING_TOLERANCE * step;
    let lines: Vec<usize> = (0..f.len())
        .filter(|&k| f[k] > 0.0 && f[k] >= lo - slack && f[k] <= hi + slack)
        .collect();
    let weights = lines
        .iter()
        .map(|&k| {
            frf.coherence.as_ref().map_or(1.0, |c| {
                c.iter().map(|r| r[k]).sum::<f64>() / c.len() as f64
            })
        })
        .collect();
    Band {
        lo,
        hi,
        lines,
        weights,
        source,
    }
}
