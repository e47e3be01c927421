//! The search of the frequency-only identification ([`super::frequency_only`]): the root u =
//! ln(p / p_0) of g(u) = ln lambda_t(p_0 e^u) - ln lambda_meas on [-ln REACH, ln REACH].
//!
//! The iteration: from u = 0, Newton steps u - g / g' (g' = s, the sensitivity), each kept
//! inside the bracket [a, b] that the iterates' signs shrink (a step leaving it is replaced by
//! the bracket's midpoint), until |g| < 1e-12 or b - a < 1e-13; the bracket starts as the
//! whole reach. The iteration reads the ends of the reach only for their position: their
//! values decide, before it, whether there is a root (not [`INSENSITIVE`]: the ends' ln
//! lambda differ; not out of reach: they lie on either side of the target) and on which side
//! of it g is negative (`rising`).
//!
//! Newton first ([`Order::NewtonFirst`]): for a stiffening parameter ([`stiffening`]: dK/dp
//! positive semi-definite, no mass) lambda_t(p) is non-decreasing (Courant-Fischer: K(p)
//! grows with p in the Loewner order, M stays), so g rises and the iteration runs with
//! `rising` known, the ends unsolved. It needs them only when it would bisect towards an end
//! it has not evaluated (a Newton step beyond the iterates' own bracket) or when it ends
//! without a root it can vouch for: |g| < 1e-12 at its last iterate, or a sign change between
//! two iterates, and iterates whose g spread by at least [`INSENSITIVE`] (then, g being
//! monotone, so do the ends, and they bracket the root: the checks before the iteration would
//! have passed). Otherwise the ends are solved where the iteration stands, and a mode
//! insensitive or out of reach is refused with the same error and the same frequencies of the
//! ends as before. Where the ends are not needed, the iterates are those the iteration makes
//! after the ends (same start, same `rising`, same brackets' positions): the same root, bit
//! for bit, without the two solves at the ends of the reach. On the 212k lap of bench/ these
//! were the costly ones: far from the nominal model the reduced model does not serve, and the
//! stiff end of k_shear_x was one full solve of 12 s which every mode waited for; no mode
//! needs the ends there (identify's CSV the same bytes; 63 s -> 38 s with the nominal solve
//! and its factor shared as well, docs/benchmarks.md). What the ends' full solve also did,
//! and Newton first no longer does where the iterates vouch for a root: refuse a mode out of
//! the full model's reach that the reduced pairs at the iterates reach (a mode the basis
//! misses: their eigenvalues then lie above the full model's). The root's value came from
//! those reduced pairs before as well. One exception to the bits: with no shared ends
//! ([`Ends`]) and a reduced model, an end solved in the middle of the iteration enriches the
//! probe's basis there, not before the first iterate; the later iterates then differ in their
//! last digits (the same root to the reduced model's tolerance).
//!
//! Other parameters (a mass, a coupling that is not a sum of springs) solve the ends first
//! ([`Order::EndsFirst`]), as before.
//!
//! Layer 4 (identification): imports the structure and the modal solution.

use super::frequency_error::FrequencyError;
use super::reach::{Ends, REACH};
use crate::modal::{ModalError, lambda_to_hz, reduced};
use crate::structure::{Parameter, SparseSym, Structure};

/// Smallest spread of g (ln lambda) over the reach of a mode that sees its parameter; below
/// it the mode is refused as insensitive.
pub const INSENSITIVE: f64 = 1e-6;

/// Most iterations of the search.
pub const ITERATIONS: usize = 100;

/// Relative slack of the diagonal dominance that makes a parameter stiffening: the rounding
/// of a spring's diagonal entry against its off-diagonal ones.
pub const DOMINANCE_SLACK: f64 = 1e-12;

/// When the ends of the reach are solved (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// For a stiffening parameter, only when the iteration needs them; first for the others.
    NewtonFirst,
    /// Always first.
    EndsFirst,
}

/// Whether `param` is stiffening: no mass, and the symmetric part of dK/dp diagonally
/// dominant with a non-negative diagonal (to [`DOMINANCE_SLACK`]), hence positive
/// semi-definite (Gershgorin): a sum of springs, as the joints' and the interfaces' are.
pub fn stiffening(param: &Parameter) -> bool {
    param.mass.entries().iter().all(|e| e.2 == 0.0) && dominant(&param.stiffness)
}

fn dominant(s: &SparseSym) -> bool {
    let n = s
        .entries()
        .iter()
        .map(|e| e.0.max(e.1) + 1)
        .max()
        .unwrap_or(0);
    let (mut diagonal, mut off) = (vec![0.0_f64; n], vec![0.0_f64; n]);
    for &(i, j, v) in s.entries() {
        if i == j {
            diagonal[i] += v;
        } else {
            // row i and column j of the symmetric part (A + A^T) / 2
            off[i] += 0.5 * v.abs();
            off[j] += 0.5 * v.abs();
        }
    }
    diagonal
        .iter()
        .zip(&off)
        .all(|(&d, &o)| d >= 0.0 && d >= o * (1.0 - DOMINANCE_SLACK))
}

/// A mode's eigenvalue and its sensitivity to one parameter, at a value of that parameter.
pub(super) struct Probe<'a> {
    pub structure: Structure,
    pub at: usize,
    pub param: &'a Parameter,
    pub t: usize,
}

impl Probe<'_> {
    /// (ln lambda_t, d ln lambda_t / d ln p) at p.
    /// On the structure's reduced model when it carries one, kept as the solves enrich it.
    fn at_value(&mut self, p: f64) -> Result<(f64, f64), ModalError> {
        self.structure.parameters[self.at].value = p;
        let (modal, enriched) =
            reduced::lowest_checking(&self.structure, &[], self.t + 1, Some(self.t..self.t + 1))?;
        if enriched.is_some() {
            self.structure.reduced = enriched;
        }
        let lambda = modal.values()[self.t];
        let y: Vec<f64> = modal.vectors().col(self.t).iter().copied().collect();
        let dk = quadratic(&self.param.stiffness, &y);
        let dm = quadratic(&self.param.mass, &y);
        Ok((lambda.ln(), p * (dk - lambda * dm) / lambda))
    }
}

/// y^T A y of a symmetric sparse A.
pub(super) fn quadratic(a: &SparseSym, y: &[f64]) -> f64 {
    let mut ay = vec![0.0; y.len()];
    a.apply(y, &mut ay);
    y.iter().zip(&ay).map(|(u, v)| u * v).sum()
}

/// What a refusal names: the mode, the parameter, the model's mode and the measured value.
pub(super) struct Named {
    pub mode: usize,
    pub param: String,
    pub model_mode: usize,
    pub measured_hz: f64,
}

/// The root u and the sensitivity s at the last iterate, and whether the ends were solved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Root {
    pub u: f64,
    pub s: f64,
    pub ends_solved: bool,
}

/// One mode's search (module docs).
pub(super) struct Search<'a, 'e> {
    pub probe: Probe<'a>,
    /// The ends shared by the modes, when the structure carries a usable reduced model.
    pub shared: Option<&'e Ends<'e>>,
    /// The parameter's index into [`Structure::identified`].
    pub param: usize,
    pub p0: f64,
    /// ln lambda_meas.
    pub target: f64,
    pub named: Named,
    /// `rising` once the ends were solved and admit a root.
    checked: Option<bool>,
}

impl<'a, 'e> Search<'a, 'e> {
    pub fn new(
        probe: Probe<'a>,
        shared: Option<&'e Ends<'e>>,
        param: usize,
        target: f64,
        named: Named,
    ) -> Self {
        let p0 = probe.param.value;
        Search {
            probe,
            shared,
            param,
            p0,
            target,
            named,
            checked: None,
        }
    }

    /// The root, the ends solved in `order` (module docs).
    pub fn run(mut self, order: Order) -> Result<Root, FrequencyError> {
        let newton_first = order == Order::NewtonFirst && stiffening(self.probe.param);
        let rising = if newton_first { true } else { self.ends()? };
        let fresh = self.probe.structure.clone();
        if let Some(root) = self.iterate(rising)? {
            return Ok(root);
        }
        // The ends found g falling where it was taken as rising (a parameter stiffening only
        // to the rounding): the iteration again from the start, as it runs after the ends.
        self.probe.structure = fresh;
        let rising = self.ends()?;
        Ok(self.iterate(rising)?.expect("the ends are solved"))
    }

    /// Whether g rises over the reach, from the ends' values; the refusal they call for.
    fn ends(&mut self) -> Result<bool, FrequencyError> {
        if let Some(rising) = self.checked {
            return Ok(rising);
        }
        let span = REACH.ln();
        let bracket = self
            .shared
            .and_then(|e| e.bracket(self.param, self.probe.t, self.target));
        let (g_lo, g_hi) = match bracket {
            Some(b) => {
                let b = b?;
                (b.low, b.high)
            }
            None => (
                self.probe.at_value(self.p0 * (-span).exp())?.0,
                self.probe.at_value(self.p0 * span.exp())?.0,
            ),
        };
        let (g_lo, g_hi) = (g_lo - self.target, g_hi - self.target);
        let named = &self.named;
        if (g_hi - g_lo).abs() < INSENSITIVE {
            return Err(FrequencyError::Insensitive {
                mode: named.mode,
                param: named.param.clone(),
                sensitivity: (g_hi - g_lo) / (2.0 * span),
            });
        }
        if g_lo.signum() == g_hi.signum() {
            return Err(FrequencyError::OutOfReach {
                mode: named.mode,
                param: named.param.clone(),
                model_mode: named.model_mode,
                measured_hz: named.measured_hz,
                low_hz: lambda_to_hz((g_lo + self.target).exp()),
                high_hz: lambda_to_hz((g_hi + self.target).exp()),
            });
        }
        let rising = g_hi > g_lo;
        self.checked = Some(rising);
        Ok(rising)
    }

    /// The bracketed Newton iteration of the module docs with g rising or falling as
    /// `rising`; the ends solved where it cannot vouch for its root; none when they found g
    /// the other way.
    fn iterate(&mut self, rising: bool) -> Result<Option<Root>, FrequencyError> {
        let span = REACH.ln();
        // the bracket [a, b] with g(a) of the sign of g at the low end; whether each bound is
        // an iterate (else an end of the reach)
        let (mut a, mut b) = (-span, span);
        let (mut a_seen, mut b_seen) = (false, false);
        let (mut g_min, mut g_max) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut u: f64 = 0.0;
        let mut s = 0.0;
        let mut vouched = false;
        for _ in 0..ITERATIONS {
            let (g, slope) = self.probe.at_value(self.p0 * u.exp())?;
            let g = g - self.target;
            s = slope;
            (g_min, g_max) = (g_min.min(g), g_max.max(g));
            if g.abs() < 1e-12 || b - a < 1e-13 {
                vouched = g.abs() < 1e-12 || (a_seen && b_seen);
                break;
            }
            if (g < 0.0) == rising {
                (a, a_seen) = (u, true);
            } else {
                (b, b_seen) = (u, true);
            }
            let newton = u - g / slope;
            u = if slope.is_finite() && slope != 0.0 && newton > a && newton < b {
                newton
            } else {
                // a bisection towards an end not evaluated: whether the root is there at all
                if !(a_seen && b_seen) && self.ends()? != rising {
                    return Ok(None);
                }
                0.5 * (a + b)
            };
        }
        let vouched = vouched && g_max - g_min >= INSENSITIVE;
        if !vouched && self.ends()? != rising {
            return Ok(None);
        }
        Ok(Some(Root {
            u,
            s,
            ends_solved: self.checked.is_some(),
        }))
    }
}

#[cfg(test)]
mod tests {
    //! Newton first against the ends first: the same roots and the same refusals, the ends
    //! left unsolved where the iteration vouches for its root.

    use super::*;
    use crate::identify::frequency_only::{Choice, FrequencyOutcome, identify_ordered};
    use crate::modal::reduced;
    use crate::model::fixtures::{paper_model, steel_bar};
    use crate::model::{Chain, Joint};

    type Ordered = Result<(FrequencyOutcome, bool), FrequencyError>;

    /// Mode `t` of `structure` identified at `factor` times its frequency, both ways.
    fn both(structure: &Structure, t: usize, factor: f64, choice: Choice) -> (Ordered, Ordered) {
        let f = reduced::lowest(structure, &[], t + 1)
            .unwrap()
            .frequency_hz(t)
            * factor;
        let mode = t + 1 - structure.rigid;
        let run =
            |order| identify_ordered(structure, t, mode, (f, Some(1e-3)), choice, None, order);
        (run(Order::NewtonFirst), run(Order::EndsFirst))
    }

    #[test]
    fn springs_are_stiffening_and_a_mass_or_a_negative_coupling_is_not() {
        let model = paper_model(1e7, 1e4);
        assert!(model.identified().iter().all(stiffening));
        let mut massive = model.identified()[1].clone();
        massive.mass = SparseSym::spring(0, 1, 1e-3);
        assert!(!stiffening(&massive));
        let mut coupled = model.identified()[1].clone();
        coupled.stiffness.add(0, 1, 1.0);
        assert!(!stiffening(&coupled), "row 0 no longer dominant");
    }

    #[test]
    fn newton_first_finds_the_same_root_as_the_ends_first_without_the_ends() {
        let model = paper_model(1e7, 1e4);
        let mut unsolved = 0;
        for t in model.rigid..model.rigid + 4 {
            for factor in [0.98, 0.999, 1.0005, 1.01] {
                for choice in [Choice::MostSensitive, Choice::Named(0), Choice::Named(1)] {
                    let (first, before) = both(&model, t, factor, choice);
                    let case = format!("pair {t}, x {factor}, {choice:?}");
                    match (first, before) {
                        (Ok((a, solved)), Ok((b, true))) => {
                            assert_eq!(a, b, "{case}");
                            unsolved += usize::from(!solved);
                        }
                        (Err(a), Err(b)) => assert_eq!(a, b, "{case}"),
                        other => panic!("{case}: {other:?}"),
                    }
                }
            }
        }
        assert!(unsolved >= 24, "only {unsolved} roots without the ends");
    }

    #[test]
    fn newton_first_refuses_a_mode_out_of_reach_or_insensitive_with_the_ends_values() {
        // mode 1 far above what k2 reaches (13 times k2 gives 3 times its frequency)
        let model = paper_model(1e7, 1e4);
        let (first, before) = both(&model, model.rigid, 20.0, Choice::Named(1));
        match (&first, &before) {
            (
                Err(
                    a @ FrequencyError::OutOfReach {
                        low_hz, high_hz, ..
                    },
                ),
                Err(b),
            ) => {
                assert_eq!(a, b);
                assert!(low_hz < high_hz, "{a}");
            }
            other => panic!("{other:?}"),
        }
        // two equal halves: the antisymmetric mode 2 does not see the rotational spring
        let halves = Chain::free(
            vec![steel_bar(0.25, 20), steel_bar(0.25, 20)],
            vec![Joint::identified(1e13, 1e5)],
        )
        .build();
        let (first, before) = both(&halves, halves.rigid + 1, 1.01, Choice::Named(1));
        match (&first, &before) {
            (Err(a @ FrequencyError::Insensitive { .. }), Err(b)) => assert_eq!(a, b),
            other => panic!("{other:?}"),
        }
    }
}
