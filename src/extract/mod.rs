//! Modal parameters from measured FRFs of one reference: poles, damping, complex and real mode
//! shapes, their complexity, and the stabilisation chart that supports the choice.
//!
//! The steps, one file each:
//! 1. [`frf`]: the input ([`FrfSet`]) checked; the analysis band and its line weights (the
//!    coherence averaged over the responses when given, else 1); [`excitation`]: where the
//!    FRFs were excited, the automatic band, and its extension for the modes' margins;
//! 2. [`lscf`]: the common-denominator LSCF estimator in the z-domain with real coefficients
//!    (Guillaume et al., IMAC 2003; Peeters et al., "The PolyMAX frequency-domain method",
//!    Shock and Vibration 11, 2004), solved for every model order 1..=`max_order`; its poles
//!    (stable, positive frequency, in the band) from the companion matrix;
//! 3. [`lsfd`]: residues of those poles per order by least squares in the frequency domain,
//!    with lower and upper residual terms in the form of the FRF's quantity;
//! 4. [`stabilization`]: each pole classified stable in frequency, damping and shape against
//!    the previous order, chains of poles across orders; [`choice`]: the modes chosen among
//!    the chains by rules, each candidate with why it was kept or rejected;
//! 5. [`refine`]: the chosen poles refined by nonlinear least squares of the modal model to the
//!    FRFs (residues eliminated), then the final LSFD residues;
//! 6. [`shapes`]: real normal modes, MPC and MPD from the complex residue vectors; the FRFs of
//!    the model and a relative fit error per response.
//!
//! Around them: [`universal`] gathers the FRFs of universal files and the positions of their
//! nodes, [`csv`] writes the modes as a measured-modes CSV, [`report`] the choices as JSON
//! (all for `jointid extract`).
//!
//! Contract of [`Mode`]: frequency_hz is the undamped natural frequency |lambda| / 2 pi, the
//! damping ratio -Re(lambda) / |lambda|; the residues are receptance residues (displacement per
//! unit reference, times rad/s) whatever the quantity of the FRFs; modes ascend in frequency.
//!
//! Layer 3 (models and measurements; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`]) and, without a circle, [`crate::model`], [`crate::measured`].

pub mod choice;
pub mod csv;
pub mod excitation;
pub mod frf;
pub mod lscf;
pub mod lsfd;
pub mod refine;
pub mod report;
pub mod shapes;
pub mod stabilization;
pub mod uncertainty;
pub mod universal;

mod final_fit;
mod run;

use faer::c64;

use crate::input::{Number, SettingError};

pub use choice::{Decision, LOW_ORDER_SHARE, MPC_MIN, Reason, Rules};
pub use excitation::{BandSource, EDGE_MARGIN, EdgeNote};
pub use frf::{FrfSet, Quantity};
pub use run::extract;
pub use stabilization::{
    ChartPole, Criteria, DAMPING_TOLERANCE, FREQUENCY_TOLERANCE, MAC_MIN, MAX_DAMPING,
    StabilityClass,
};
pub use uncertainty::{ModeStd, NoiseSource};

/// Default highest model order (degree of the common denominator).
pub const MAX_ORDER: usize = 60;
/// Default least coherence (averaged over the responses) of the coherent lines of the
/// automatic band ([`excitation`]).
pub const COHERENCE_MIN: f64 = 0.8;

/// Settings of the extraction; [`Settings::default`] gives the documented defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Analysis band (Hz), used as given; default: the widest run of excited lines, extended
    /// for the modes' margins (see [`excitation`]).
    pub band_hz: Option<(f64, f64)>,
    /// Highest model order, >= 2; default [`MAX_ORDER`].
    pub max_order: usize,
    /// Number of modes wanted: the candidates with the most stable poles; default: the
    /// automatic choice ([`choice`]).
    pub n_modes: Option<usize>,
    /// Least number of stable poles of a physical chain; default
    /// [`stabilization::min_stable_default`] of `max_order`.
    pub min_stable: Option<usize>,
    /// Relative frequency tolerance of stability, in (0, 1); default [`FREQUENCY_TOLERANCE`].
    pub frequency_tolerance: f64,
    /// Relative damping tolerance of stability, in (0, 1); default [`DAMPING_TOLERANCE`].
    pub damping_tolerance: f64,
    /// Least MAC of stability in shape, in (0, 1); default [`MAC_MIN`].
    pub mac_min: f64,
    /// Largest damping ratio of a physical pole, in (0, 1]; default [`MAX_DAMPING`].
    pub max_damping: f64,
    /// Least mean coherence of the lines that set the input's plateau of the automatic band
    /// (without coherence: of the level's equivalent; see [`excitation`]), in [0, 1]; default
    /// [`COHERENCE_MIN`].
    pub coherence_min: f64,
    /// Least MPC of a mode of the automatic choice, in (0, 1]; default [`MPC_MIN`].
    pub mpc_min: f64,
    /// A mode of the automatic choice must be stable from an order at or below this share of
    /// `max_order`, in (0, 1]; default [`LOW_ORDER_SHARE`].
    pub low_order_share: f64,
    /// Least distance of a mode to the edges of the automatic band, in half-power bandwidths
    /// (2 zeta f), finite and >= 0; default [`EDGE_MARGIN`].
    pub edge_margin: f64,
    /// Terms of each residual expansion (see [`lsfd`]): 0 (every mode in the band), 1 (the
    /// classical mass-like lower and stiffness-like upper residual) or 2; default 2.
    pub residual_terms: usize,
    /// Refine the chosen poles by nonlinear least squares ([`refine`]); default true.
    pub refine: bool,
    /// Number of averages of the H1 estimates: with the coherence it gives the noise of every
    /// line, and so the standard errors ([`uncertainty`]); >= 2; default: none, the noise then
    /// comes from the residuals of the fit.
    pub averages: Option<usize>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            band_hz: None,
            max_order: MAX_ORDER,
            n_modes: None,
            min_stable: None,
            frequency_tolerance: FREQUENCY_TOLERANCE,
            damping_tolerance: DAMPING_TOLERANCE,
            mac_min: MAC_MIN,
            max_damping: MAX_DAMPING,
            coherence_min: COHERENCE_MIN,
            mpc_min: MPC_MIN,
            low_order_share: LOW_ORDER_SHARE,
            edge_margin: EDGE_MARGIN,
            residual_terms: 2,
            refine: true,
            averages: None,
        }
    }
}

impl Settings {
    /// Checks every setting against the range its field's docs give; [`extract`] does too.
    pub fn check(&self) -> Result<(), SettingError> {
        let invalid = |setting, value: &dyn std::fmt::Display, allowed| {
            Err(SettingError::new(setting, value, allowed))
        };
        let open_unit = |v: f64| v > 0.0 && v < 1.0;
        if self.n_modes == Some(0) {
            return invalid("n_modes", &0, "at least one mode is needed");
        }
        if self.max_order < 2 {
            return invalid("max_order", &self.max_order, "it must be an integer >= 2");
        }
        if let Some(m) = self.min_stable
            && (m == 0 || m > self.max_order)
        {
            return invalid("min_stable", &m, "it must be an integer in 1..=max_order");
        }
        for (setting, value) in [
            ("frequency_tolerance", self.frequency_tolerance),
            ("damping_tolerance", self.damping_tolerance),
            ("mac_min", self.mac_min),
        ] {
            if !open_unit(value) {
                return invalid(setting, &Number(value), "it must be in (0, 1)");
            }
        }
        if !(self.max_damping > 0.0 && self.max_damping <= 1.0) {
            return invalid(
                "max_damping",
                &Number(self.max_damping),
                "it must be in (0, 1]",
            );
        }
        if self.residual_terms > 2 {
            return invalid(
                "residual_terms",
                &self.residual_terms,
                "it must be 0, 1 or 2",
            );
        }
        if let Some(n @ (0 | 1)) = self.averages {
            return invalid(
                "averages",
                &n,
                "it must be an integer >= 2 (one average has no coherence)",
            );
        }
        if !(0.0..=1.0).contains(&self.coherence_min) {
            return invalid("coherence_min", &self.coherence_min, "it must be in [0, 1]");
        }
        for (setting, value) in [
            ("mpc_min", self.mpc_min),
            ("low_order_share", self.low_order_share),
        ] {
            if !(value > 0.0 && value <= 1.0) {
                return invalid(setting, &Number(value), "it must be in (0, 1]");
            }
        }
        if !(self.edge_margin.is_finite() && self.edge_margin >= 0.0) {
            return invalid(
                "edge_margin",
                &Number(self.edge_margin),
                "it must be a finite number >= 0 (half-power bandwidths)",
            );
        }
        Ok(())
    }
}

/// One identified mode.
#[derive(Debug, Clone)]
pub struct Mode {
    /// Undamped natural frequency (Hz).
    pub frequency_hz: f64,
    /// Damping ratio (fraction of critical).
    pub damping_ratio: f64,
    /// The pole lambda (rad/s), positive imaginary part.
    pub pole: c64,
    /// Receptance residue per response.
    pub residues: Vec<c64>,
    /// The residues scaled so that the largest component is 1 + 0i.
    pub complex_shape: Vec<c64>,
    /// The real normal mode, largest component +1 (see [`shapes`]).
    pub real_shape: Vec<f64>,
    /// Modal phase collinearity, in [0, 1] (1: real mode).
    pub mpc: f64,
    /// Mean phase deviation (degrees), in [0, 90] (0: real mode).
    pub mpd_deg: f64,
    /// First and last model order at which its chain was stable.
    pub stable_orders: (usize, usize),
    /// Number of stable poles of its chain.
    pub stable_count: usize,
    /// Standard errors of the frequency, the damping ratio and the real shape
    /// ([`uncertainty`]).
    pub std: ModeStd,
}

/// Everything the extraction found.
#[derive(Debug, Clone)]
pub struct Extraction {
    /// The modes, ascending in frequency.
    pub modes: Vec<Mode>,
    /// Every pole of every order with its stability flags; the chosen ones `selected`.
    pub chart: Vec<ChartPole>,
    /// The thresholds the chart and the choice used.
    pub criteria: Criteria,
    /// The rules of the automatic choice.
    pub rules: Rules,
    /// The number of modes requested; None: the automatic choice.
    pub requested: Option<usize>,
    /// The least distance of a mode to the band's edges asked for (half-power bandwidths).
    pub edge_margin: f64,
    /// Every candidate (chain with `min_stable` or more stable poles): the kept ones first,
    /// by mode number, then the rejected ones, each with why.
    pub decisions: Vec<Decision>,
    /// Number of chains with fewer than `min_stable` stable poles (not candidates).
    pub weak_chains: usize,
    /// Highest model order computed.
    pub max_order: usize,
    /// The analysis band (Hz).
    pub band_hz: (f64, f64),
    /// Where it came from.
    pub band_source: BandSource,
    /// The automatic band before it was extended for the modes' margins, when it was.
    pub extended_from: Option<(f64, f64)>,
    /// The frequency lines of the band (Hz).
    pub frequencies_hz: Vec<f64>,
    /// Their indices on the axis of the [`FrfSet`].
    pub lines: Vec<usize>,
    /// The FRFs of the identified model on those lines, `[response][line]`.
    pub synthesized: Vec<Vec<c64>>,
    /// Relative fit error per response: ||H - H_model|| / ||H|| over the band.
    pub fit_error: Vec<f64>,
    /// Lower residual coefficients [L_1, L_2] per response (see [`lsfd`] for their form per
    /// quantity; 0 when not fitted).
    pub lower_residual: Vec<[f64; 2]>,
    /// Upper residual coefficients [U_1, U_2] per response.
    pub upper_residual: Vec<[f64; 2]>,
    /// Mean coherence per response over the band, when coherence was given.
    pub mean_coherence: Option<Vec<f64>>,
    /// Whether the poles were refined (false when off, or when the refinement left the band or
    /// merged poles and the chart's poles were kept).
    pub refined: bool,
    /// Where the noise behind the modes' standard errors came from.
    pub noise: NoiseSource,
}

/// Why the extraction failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExtractError {
    /// No response FRF.
    #[error("no response FRFs were given; at least one is needed")]
    NoResponses,
    /// A frequency is negative or not finite.
    #[error(
        "frequency line {index} is {} Hz; frequencies must be finite and >= 0",
        Number(*value)
    )]
    BadFrequency { index: usize, value: f64 },
    /// Frequencies do not ascend.
    #[error(
        "frequencies must ascend: line {index} is {} Hz after {} Hz",
        Number(*value), Number(*previous)
    )]
    NotAscending {
        index: usize,
        value: f64,
        previous: f64,
    },
    /// Frequencies are not evenly spaced.
    #[error(
        "frequencies must be evenly spaced: line {index} is {} Hz, expected {} Hz \
         (step {} Hz, tolerance {} Hz)",
        Number(*value), Number(*expected), Number(*step), Number(*tolerance)
    )]
    UnevenSpacing {
        index: usize,
        value: f64,
        expected: f64,
        step: f64,
        tolerance: f64,
    },
    /// A response has another length than the frequency axis.
    #[error(
        "response {response} has {len} values for {expected} frequency lines; one per line is needed"
    )]
    LengthMismatch {
        response: usize,
        len: usize,
        expected: usize,
    },
    /// A value is NaN or infinite.
    #[error(
        "response {response} at line {index} ({frequency_hz} Hz) is {re} + {im}i; FRF values must be finite"
    )]
    NonFinite {
        response: usize,
        index: usize,
        frequency_hz: f64,
        re: f64,
        im: f64,
    },
    /// A response is zero over the whole band.
    #[error(
        "response {response} is zero over the band {}..{} Hz; it carries no mode",
        Number(*lo), Number(*hi)
    )]
    ZeroResponse { response: usize, lo: f64, hi: f64 },
    /// Coherence given for another number of responses.
    #[error("coherence is given for {count} responses, but there are {expected}")]
    CoherenceCount { count: usize, expected: usize },
    /// A coherence has another length than the frequency axis.
    #[error("coherence of response {response} has {len} values for {expected} frequency lines")]
    CoherenceLength {
        response: usize,
        len: usize,
        expected: usize,
    },
    /// A coherence value outside [0, 1].
    #[error(
        "coherence of response {response} at line {index} ({frequency_hz} Hz) is {value}; it must be in [0, 1]"
    )]
    CoherenceRange {
        response: usize,
        index: usize,
        frequency_hz: f64,
        value: f64,
    },
    /// No line shows excitation for the automatic band.
    #[error(
        "no frequency band shows excitation: the mean coherence, smoothed over 1% of the lines, \
         reaches {} at best ({threshold} needed); give the band explicitly or lower the \
         coherence threshold",
        Number((best * 1000.0).round() / 1000.0)
    )]
    NoCoherentBand { threshold: f64, best: f64 },
    /// A band given where the coherence shows no excitation.
    #[error(
        "band {}..{} Hz shows no excitation: its smoothed mean coherence reaches {} ({} \
         needed) and the level does not explain it; give a band the input covered",
        Number(*lo), Number(*hi), Number((best * 1000.0).round() / 1000.0), Number(*threshold)
    )]
    NoExcitation {
        lo: f64,
        hi: f64,
        best: f64,
        threshold: f64,
    },
    /// The band asked for is empty or outside the data.
    #[error(
        "band {}..{} Hz is invalid: it needs {} <= lo < hi <= {} Hz (the FRF's lines)",
        Number(*lo), Number(*hi), Number(*data_lo), Number(*data_hi)
    )]
    BadBand {
        lo: f64,
        hi: f64,
        data_lo: f64,
        data_hi: f64,
    },
    /// Too few lines for the model order.
    #[error(
        "the band holds {lines} frequency lines above 0 Hz; model order {max_order} needs at least {needed}"
    )]
    TooFewLines {
        lines: usize,
        needed: usize,
        max_order: usize,
    },
    /// A setting out of its range ([`Settings::check`]).
    #[error("setting {0}")]
    Setting(SettingError),
    /// No chain of poles qualified as physical.
    #[error(
        "no mode found in {lo}..{hi} Hz: no chain of poles was stable (frequency, damping and \
         shape) at {min_stable} or more of the orders 1..={max_order}; the band may hold no \
         resonance, or a higher max order is needed"
    )]
    NoModes {
        lo: f64,
        hi: f64,
        min_stable: usize,
        max_order: usize,
    },
    /// A number of averages was given for FRFs without coherence.
    #[error(
        "{averages} averages were given, but the FRFs carry no coherence: the noise of each line          comes from the coherence and the number of averages together (without coherence it is          estimated from the residuals of the fit; leave the averages out)"
    )]
    AveragesWithoutCoherence { averages: usize },
    /// Fewer physical chains than modes requested.
    #[error(
        "{requested} modes were requested but only {found} chains of poles were stable at \
         {min_stable} or more orders in {lo}..{hi} Hz"
    )]
    TooFewModes {
        requested: usize,
        found: usize,
        min_stable: usize,
        lo: f64,
        hi: f64,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_are_checked_against_their_ranges() {
        assert_eq!(Settings::default().check(), Ok(()));
        let check = |settings: Settings| settings.check().unwrap_err().to_string();
        assert_eq!(
            check(Settings {
                n_modes: Some(0),
                ..Settings::default()
            }),
            "n_modes = 0 is invalid: at least one mode is needed"
        );
        assert_eq!(
            check(Settings {
                max_order: 1,
                ..Settings::default()
            }),
            "max_order = 1 is invalid: it must be an integer >= 2"
        );
        assert_eq!(
            check(Settings {
                mac_min: 1.0,
                ..Settings::default()
            }),
            "mac_min = 1 is invalid: it must be in (0, 1)"
        );
        assert_eq!(
            check(Settings {
                mpc_min: 0.0,
                ..Settings::default()
            }),
            "mpc_min = 0 is invalid: it must be in (0, 1]"
        );
        assert_eq!(
            check(Settings {
                low_order_share: 1.5,
                ..Settings::default()
            }),
            "low_order_share = 1.5 is invalid: it must be in (0, 1]"
        );
        assert_eq!(
            check(Settings {
                edge_margin: f64::INFINITY,
                ..Settings::default()
            }),
            "edge_margin = inf is invalid: it must be a finite number >= 0 (half-power bandwidths)"
        );
    }
}
