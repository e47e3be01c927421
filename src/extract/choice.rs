//! The choice of the modes among the chains of the stabilisation chart, and why each candidate
//! was kept or rejected.
//!
//! Candidates: the chains ([`Chain`]) with at least `min_stable` stable poles, taken by
//! descending number of stable poles (ties to the lower frequency). A candidate is rejected,
//! in this order, when
//! 1. the median damping of its stable poles reaches `max_damping` ([`Reason::Damped`]);
//! 2. it repeats a kept mode: within the frequency tolerance of it, and either never present
//!    at the same orders (a chain broken and resumed) or of the same shape (MAC of the residue
//!    vectors > `mac_min`) ([`Reason::Duplicate`]).
//!
//! With a number of modes requested (`--modes N`), the first N candidates left are the modes
//! (the others: [`Reason::NotRequested`]): the choice of the earlier versions, unchanged.
//! Without it (the automatic choice), three rules more, checked before the duplicates:
//! 3. its longest run of consecutive stable orders is shorter than `min_stable`
//!    ([`Reason::ShortRun`]);
//! 4. that run starts above the low-order share of the orders, `low_order_share x max_order`
//!    ([`LOW_ORDER_SHARE`] = 2/3 by default: order 40 of 60) ([`Reason::LateStart`]): a pole
//!    that only the highest orders hold is the model's, fitting noise, not the structure's
//!    (two modes closer than their bandwidths can need half the orders to come apart: a raised
//!    `max_order` keeps them);
//! 5. the MPC of its chosen pole's residues is below `mpc_min` ([`MPC_MIN`] = 0.95)
//!    ([`Reason::Complex`]); a mode kept whose MPC falls below it in the final fit is rejected
//!    then ([`Reason::ComplexAfterFit`]) and the fit made again without it.

use faer::c64;
use serde::Serialize;

use super::excitation::EdgeNote;
use super::shapes::{mac, real_mode};
use super::stabilization::{Chain, ChartPole, Criteria};

/// Default least MPC of a mode of the automatic choice.
pub const MPC_MIN: f64 = 0.95;
/// Default share of the orders within which a mode's run of stable orders must start.
pub const LOW_ORDER_SHARE: f64 = 2.0 / 3.0;

/// The rules of the automatic choice beside the chart's [`Criteria`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Rules {
    /// Least MPC of a mode, in (0, 1].
    pub mpc_min: f64,
    /// The run of stable orders must start at or below this share of the highest order.
    pub low_order_share: f64,
    /// Highest model order.
    pub max_order: usize,
}

impl Rules {
    /// The last order at which a run of stable orders may start.
    pub fn last_start(&self) -> usize {
        ((self.low_order_share * self.max_order as f64 + 1e-9).floor() as usize).max(1)
    }
}

/// Why a candidate is not a mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Reason {
    /// Too heavily damped to be physical.
    Damped { damping_ratio: f64, max: f64 },
    /// Its longest run of consecutive stable orders is too short.
    ShortRun { length: usize, needed: usize },
    /// Its run of stable orders starts at too high an order.
    LateStart { first: usize, last_allowed: usize },
    /// Its chosen pole's shape is too complex.
    Complex { mpc: f64, min: f64 },
    /// Its shape in the final fit is too complex.
    ComplexAfterFit { mpc: f64, min: f64 },
    /// The same mode as the kept one at `of_hz`.
    Duplicate { of_hz: f64 },
    /// Beyond the number of modes requested (`rank`-th candidate of `requested`).
    NotRequested { rank: usize, requested: usize },
}

impl Reason {
    /// A word or two for the chart's marks.
    pub fn code(&self) -> &'static str {
        match self {
            Reason::Damped { .. } => "damped",
            Reason::ShortRun { .. } => "short run",
            Reason::LateStart { .. } => "high orders",
            Reason::Complex { .. } | Reason::ComplexAfterFit { .. } => "MPC",
            Reason::Duplicate { .. } => "duplicate",
            Reason::NotRequested { .. } => "beyond --modes",
        }
    }
}

impl std::fmt::Display for Reason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Reason::Damped { damping_ratio, max } => write!(
                f,
                "damping {:.1}% >= {:.1}%",
                100.0 * damping_ratio,
                100.0 * max
            ),
            Reason::ShortRun { length, needed } => write!(
                f,
                "its longest run of consecutive stable orders is {length} < {needed}"
            ),
            Reason::LateStart {
                first,
                last_allowed,
            } => write!(
                f,
                "stable only from order {first} (> {last_allowed}): a pole of the high orders"
            ),
            Reason::Complex { mpc, min } => write!(f, "MPC {mpc:.3} < {min}"),
            Reason::ComplexAfterFit { mpc, min } => {
                write!(f, "MPC {mpc:.3} < {min} in the final fit")
            }
            Reason::Duplicate { of_hz } => write!(f, "the same mode as {of_hz:.3} Hz"),
            Reason::NotRequested { rank, requested } => {
                write!(f, "candidate {rank} of {requested} requested")
            }
        }
    }
}

/// A candidate chain and what became of it. Kept modes carry their final frequency, damping
/// and MPC; rejected ones those of their chosen pole on the chart.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Decision {
    /// Index of the chain's chosen pole in the chart.
    #[serde(skip)]
    pub pole: usize,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Damping ratio.
    pub damping_ratio: f64,
    /// MPC of the shape.
    pub mpc: f64,
    /// First and last order at which the chain is stable.
    pub stable_orders: (usize, usize),
    /// Number of stable poles of the chain.
    pub stable_count: usize,
    /// Its longest run of consecutive stable orders: (first order, number of orders).
    pub run: (usize, usize),
    /// Distances to the band's lower and upper edges in half-power bandwidths (2 zeta f).
    pub margins: (f64, f64),
    /// The mode number (1-based, ascending frequency) when kept.
    pub mode: Option<usize>,
    /// Why it was rejected; None when kept.
    pub rejected: Option<Reason>,
    /// For a kept mode nearer an edge than the margin: why the band gives it no more.
    pub edge: Option<EdgeNote>,
}

/// The rule-by-rule verdict of the automatic choice on one candidate (rules 1, 3, 4, 5 of the
/// module docs); None when it passes.
fn automatic_reason(chain: &Chain, mpc: f64, criteria: &Criteria, rules: &Rules) -> Option<Reason> {
    if chain.median_damping >= criteria.max_damping {
        return Some(Reason::Damped {
            damping_ratio: chain.median_damping,
            max: criteria.max_damping,
        });
    }
    if chain.run.1 < criteria.min_stable {
        return Some(Reason::ShortRun {
            length: chain.run.1,
            needed: criteria.min_stable,
        });
    }
    if chain.run.0 > rules.last_start() {
        return Some(Reason::LateStart {
            first: chain.run.0,
            last_allowed: rules.last_start(),
        });
    }
    (mpc < rules.mpc_min).then_some(Reason::Complex {
        mpc,
        min: rules.mpc_min,
    })
}

/// Chooses the modes among `chains` (see the module docs), marks their poles `selected` in
/// `chart` and returns a decision per candidate, the kept ones by ascending frequency first
/// (numbered), then the rejected ones by descending number of stable poles. `residues[i]`:
/// the residue vector of chart pole i. `n_modes`: the number requested, if any.
pub fn choose(
    chart: &mut [ChartPole],
    chains: &[Chain],
    residues: &[&[c64]],
    criteria: &Criteria,
    rules: &Rules,
    n_modes: Option<usize>,
) -> Vec<Decision> {
    let mut candidates: Vec<&Chain> = chains
        .iter()
        .filter(|c| c.stable_count >= criteria.min_stable)
        .collect();
    candidates.sort_by(|a, b| {
        b.stable_count.cmp(&a.stable_count).then(
            chart[a.pole]
                .frequency_hz
                .total_cmp(&chart[b.pole].frequency_hz),
        )
    });
    let mut kept: Vec<&Chain> = Vec::new();
    let mut decisions: Vec<Decision> = Vec::new();
    for chain in candidates {
        let pole = &chart[chain.pole];
        let mpc = real_mode(residues[chain.pole]).mpc;
        let reason = match n_modes {
            None => automatic_reason(chain, mpc, criteria, rules),
            Some(_) => (chain.median_damping >= criteria.max_damping).then_some(Reason::Damped {
                damping_ratio: chain.median_damping,
                max: criteria.max_damping,
            }),
        }
        .or_else(|| {
            duplicate_of(chain, &kept, chart, residues, criteria)
                .map(|of_hz| Reason::Duplicate { of_hz })
        })
        .or_else(|| match n_modes {
            Some(n) if kept.len() >= n => Some(Reason::NotRequested {
                rank: kept.len() + 1,
                requested: n,
            }),
            _ => None,
        });
        if reason.is_none() {
            kept.push(chain);
        }
        decisions.push(Decision {
            pole: chain.pole,
            frequency_hz: pole.frequency_hz,
            damping_ratio: pole.damping_ratio,
            mpc,
            stable_orders: chain.orders,
            stable_count: chain.stable_count,
            run: chain.run,
            margins: (f64::NAN, f64::NAN),
            mode: None,
            rejected: reason,
            edge: None,
        });
    }
    number_kept(chart, decisions)
}

/// The kept decisions first, by ascending frequency and numbered, their poles marked in
/// `chart`; then the rejected ones in their order.
pub fn number_kept(chart: &mut [ChartPole], decisions: Vec<Decision>) -> Vec<Decision> {
    let (mut kept, rejected): (Vec<Decision>, Vec<Decision>) =
        decisions.into_iter().partition(|d| d.rejected.is_none());
    kept.sort_by(|a, b| a.frequency_hz.total_cmp(&b.frequency_hz));
    for p in chart.iter_mut() {
        p.selected = false;
    }
    for (r, d) in kept.iter_mut().enumerate() {
        d.mode = Some(r + 1);
        chart[d.pole].selected = true;
    }
    kept.extend(rejected.into_iter().map(|d| Decision { mode: None, ..d }));
    kept
}

/// The frequency of the kept chain `chain` repeats (see the module docs), if any.
fn duplicate_of(
    chain: &Chain,
    kept: &[&Chain],
    chart: &[ChartPole],
    residues: &[&[c64]],
    criteria: &Criteria,
) -> Option<f64> {
    let f = chart[chain.pole].frequency_hz;
    kept.iter()
        .find(|k| {
            let fk = chart[k.pole].frequency_hz;
            let near = (f - fk).abs() < criteria.frequency_tolerance * fk;
            let disjoint = !chain
                .stable_orders
                .iter()
                .any(|o| k.stable_orders.contains(o));
            let same_shape = mac(residues[chain.pole], residues[k.pole]) > criteria.mac_min;
            near && (disjoint || same_shape)
        })
        .map(|k| chart[k.pole].frequency_hz)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pole(frequency_hz: f64) -> ChartPole {
        let w = 2.0 * std::f64::consts::PI * frequency_hz;
        ChartPole {
            order: 1,
            pole: c64::new(-0.01 * w, w),
            frequency_hz,
            damping_ratio: 0.01,
            stable_frequency: true,
            stable_damping: true,
            stable_shape: true,
            chain: 0,
            selected: false,
        }
    }

    fn chain(pole: usize, orders: std::ops::RangeInclusive<usize>) -> Chain {
        let stable_orders: Vec<usize> = orders.collect();
        Chain {
            pole,
            stable_count: stable_orders.len(),
            orders: (stable_orders[0], stable_orders[stable_orders.len() - 1]),
            run: (stable_orders[0], stable_orders.len()),
            stable_orders,
            median_damping: 0.01,
        }
    }

    /// Four candidates at 60 orders: a real mode stable from order 5 (A, 100 Hz), a pole of
    /// the high orders (B, 150 Hz, from 45), a complex one (C, 200 Hz) and A again, broken
    /// off and resumed at other orders (D).
    #[test]
    fn each_rule_rejects_its_candidate_and_a_requested_count_keeps_the_old_choice() {
        let real = [c64::new(1.0, 0.0), c64::new(-0.5, 0.0), c64::new(0.2, 0.0)];
        let complex = [c64::new(1.0, 0.0), c64::new(0.0, 1.0), c64::new(-0.7, -0.7)];
        let residues: Vec<&[c64]> = vec![&real, &real, &complex, &real];
        let chains = [
            chain(0, 5..=60),
            chain(1, 45..=60),
            chain(2, 10..=50),
            chain(3, 1..=4),
        ];
        let mut chart = vec![pole(100.0), pole(150.0), pole(200.0), pole(100.2)];
        let criteria = Criteria {
            frequency_tolerance: 0.01,
            damping_tolerance: 0.05,
            mac_min: 0.98,
            min_stable: 4,
            max_damping: 0.2,
        };
        let rules = Rules {
            mpc_min: MPC_MIN,
            low_order_share: LOW_ORDER_SHARE,
            max_order: 60,
        };
        let got = choose(&mut chart, &chains, &residues, &criteria, &rules, None);
        let reasons: Vec<(f64, Option<Reason>)> = got
            .iter()
            .map(|d| (d.frequency_hz, d.rejected.clone()))
            .collect();
        assert_eq!(
            reasons,
            [
                (100.0, None),
                (
                    200.0,
                    Some(Reason::Complex {
                        mpc: real_mode(&complex).mpc,
                        min: 0.95
                    })
                ),
                (
                    150.0,
                    Some(Reason::LateStart {
                        first: 45,
                        last_allowed: 40
                    })
                ),
                (100.2, Some(Reason::Duplicate { of_hz: 100.0 })),
            ]
        );
        assert_eq!(got[0].mode, Some(1));
        assert!(chart[0].selected && !chart[1].selected && !chart[2].selected);
        // Two requested: the two with the most stable poles, whatever their MPC.
        let got = choose(&mut chart, &chains, &residues, &criteria, &rules, Some(2));
        let kept: Vec<f64> = got
            .iter()
            .filter(|d| d.mode.is_some())
            .map(|d| d.frequency_hz)
            .collect();
        assert_eq!(kept, [100.0, 200.0]);
        assert_eq!(
            got[2].rejected,
            Some(Reason::NotRequested {
                rank: 3,
                requested: 2
            })
        );
        assert!(chart[2].selected && !chart[1].selected);
    }
}
