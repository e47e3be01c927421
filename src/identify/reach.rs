//! The far ends of a parameter's reach in the frequency-only identification
//! ([`super::frequency_only`]), solved once for every mode that identifies that parameter.
//!
//! The search brackets the root between p_0 / REACH and p_0 REACH, and reads at its ends only
//! on which side of the measured eigenvalue the mode lies (the bracket), and whether it moves
//! at all (insensitive): the Newton steps inside start from p_0 whatever the ends' values.
//! Each end is solved once per parameter, with the pairs of every mode, and shared by the
//! modes (each mode solved them itself before, 16 full solves for 8 modes of one parameter,
//! now 2), and only when a mode's search needs them ([`super::root`]: for a stiffening
//! parameter, where its Newton steps cannot vouch for a root).
//!
//! First on the structure's reduced model ([`crate::modal::reduced`]), as it is: at these
//! ends the model is far from the nominal one, where the enrichment to the reduced model's
//! tolerance would cost as much as a full solve, but a side needs far less. A reduced
//! eigenvalue is a Rayleigh-Ritz value, at or above the full model's: below the target (by
//! more than [`ROUNDING`] in ln lambda) the full one is below too; above it, the side is
//! taken when the pair's error estimate e (the relative error of its eigenvalue) is at most
//! [`MARGIN`] times its distance to the target in ln lambda. An end whose side is not
//! certain is solved in full (on the 212k lap of bench/, the stiff end of k_shear_x for all
//! eight modes, whose soft end the reduced model settled: one full solve where there were
//! two); when the ends do not make a bracket (a mode out of reach, or
//! insensitive: the caller's messages quote the ends' frequencies), both are, as before.

use std::sync::OnceLock;

use crate::modal::{ModalError, reduced};
use crate::structure::Structure;

/// Widest factor on the parameter the search allows, each way.
pub const REACH: f64 = 1e4;

/// Largest error estimate of a reduced end above the target, as a fraction of its distance
/// to the target in ln lambda. The estimate is no bound: on the small lap of the tests the
/// stiff end's error was 1.0-1.1 times it, once 500 times (5e-9 against 1e-11), the soft
/// end's up to 40 times; a hundredfold margin, where the ends lie 1e-3 to 1 away in ln
/// lambda and their estimates below 1e-5.
pub const MARGIN: f64 = 0.01;

/// Distance in ln lambda below the target from which a reduced end's side is certain (the
/// rounding of the reduced pencil's eigenvalues lies far below it).
pub const ROUNDING: f64 = 1e-9;

/// Smallest |ln lambda_high - ln lambda_low| of a bracket taken from the reduced ends: ten
/// times the caller's threshold of an insensitive mode (1e-6).
pub const SPREAD: f64 = 1e-5;

/// ln lambda_t at both ends of a parameter's reach, and where they come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// At p_0 / REACH.
    pub low: f64,
    /// At p_0 REACH.
    pub high: f64,
    /// Whether either end is from the reduced model (else both from the full one).
    pub reduced: bool,
}

/// The eigenvalues of one end (and, on the reduced model, their error estimates), solved
/// when first asked for.
type End<T> = OnceLock<Result<T, ModalError>>;

/// A reduced end: none when the structure carries no usable reduction.
type Estimated = Option<(Vec<f64>, Vec<f64>)>;

/// The eigenvalues at both ends of every identified parameter's reach, solved when first
/// asked for.
pub struct Ends<'a> {
    structure: &'a Structure,
    count: usize,
    full: Vec<[End<Vec<f64>>; 2]>,
    estimated: Vec<[End<Estimated>; 2]>,
}

impl<'a> Ends<'a> {
    /// The ends of `structure`'s parameters, each solve for its lowest `count` pairs.
    pub fn new(structure: &'a Structure, count: usize) -> Self {
        let params = structure.identified().len();
        Ends {
            structure,
            count,
            full: (0..params).map(|_| Default::default()).collect(),
            estimated: (0..params).map(|_| Default::default()).collect(),
        }
    }

    /// ln lambda_t at the low and the high end of identified parameter `param`'s reach, to be
    /// compared with `target` (the measured ln lambda): each end from the reduced model when
    /// that settles its side, else from the full model; both from the full model when they
    /// make no bracket with a reduced end among them (module docs); none when `t` is beyond
    /// the pairs solved.
    pub fn bracket(
        &self,
        param: usize,
        t: usize,
        target: f64,
    ) -> Option<Result<Bracket, ModalError>> {
        (t < self.count).then(|| self.bracket_of(param, t, target))
    }

    fn bracket_of(&self, param: usize, t: usize, target: f64) -> Result<Bracket, ModalError> {
        let full = |high: bool| -> Result<f64, ModalError> { Ok(self.full(param, high)?[t].ln()) };
        let (reduced_low, reduced_high) = (
            self.side(param, false, t, target)?,
            self.side(param, true, t, target)?,
        );
        let low = reduced_low.map_or_else(|| full(false), Ok)?;
        let high = reduced_high.map_or_else(|| full(true), Ok)?;
        let reduced = reduced_low.is_some() || reduced_high.is_some();
        let bracket =
            (low - target).signum() != (high - target).signum() && (high - low).abs() >= SPREAD;
        if reduced && !bracket {
            return Ok(Bracket {
                low: full(false)?,
                high: full(true)?,
                reduced: false,
            });
        }
        Ok(Bracket { low, high, reduced })
    }

    /// ln lambda_t at one end from the reduced model, when that settles its side of `target`.
    fn side(
        &self,
        param: usize,
        high: bool,
        t: usize,
        target: f64,
    ) -> Result<Option<f64>, ModalError> {
        let Some((values, estimates)) = self.estimated(param, high)? else {
            return Ok(None);
        };
        let g = values[t].ln() - target;
        let certain = g < -ROUNDING || (g > 0.0 && estimates[t] <= MARGIN * g);
        Ok(certain.then_some(g + target))
    }

    /// `structure` with identified parameter `param` at the end `high` of its reach.
    fn at_end(&self, param: usize, high: bool) -> Structure {
        let mut values: Vec<f64> = self
            .structure
            .identified()
            .iter()
            .map(|p| p.value)
            .collect();
        values[param] *= if high { REACH } else { 1.0 / REACH };
        self.structure.with_values(&values)
    }

    fn full(&self, param: usize, high: bool) -> Result<&Vec<f64>, ModalError> {
        self.full[param][usize::from(high)]
            .get_or_init(|| {
                let mut at = self.at_end(param, high);
                at.reduced = None;
                reduced::full(&at, &[], self.count).map(|m| m.values().to_vec())
            })
            .as_ref()
            .map_err(Clone::clone)
    }

    fn estimated(&self, param: usize, high: bool) -> Result<&Estimated, ModalError> {
        self.estimated[param][usize::from(high)]
            .get_or_init(|| {
                let at = self.at_end(param, high);
                Ok(reduced::estimated(&at, &[], self.count)?.map(|m| {
                    let e = reduced::residuals(&m).to_vec();
                    (m.values().to_vec(), e)
                }))
            })
            .as_ref()
            .map_err(Clone::clone)
    }
}
