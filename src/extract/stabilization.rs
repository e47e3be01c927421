//! The stabilisation chart and its chains of poles.
//!
//! Classification: the poles of order n are matched one-to-one with those of order n - 1,
//! nearest first in |s_n - s_(n-1)| / |s_(n-1)| (a pole keeps the previous pole nearest to it
//! unless a nearer pole of order n took it). Against its match a pole is
//! - stable in frequency when |f_n - f_(n-1)| / f_(n-1) < `frequency_tolerance`
//!   ([`FREQUENCY_TOLERANCE`] = 1% by default),
//! - stable in damping when |zeta_n - zeta_(n-1)| / zeta_(n-1) < `damping_tolerance`
//!   ([`DAMPING_TOLERANCE`] = 5%),
//! - stable in shape when the MAC of their LSFD residue vectors > `mac_min` ([`MAC_MIN`] = 0.98).
//!
//! Chains: a pole stable in frequency continues the chain of its match; any other pole starts
//! a chain. A pole stable in all three is *stable*. A chain's pole is its stable pole of
//! median frequency; it carries its stable orders, their longest run of consecutive orders
//! and the median damping of its stable poles ([`Chain`]). Which chains are modes:
//! [`super::choice`] (candidates: at least `min_stable` stable poles, [`min_stable_default`]:
//! 20% of the orders, at least 5).

use faer::c64;

use super::shapes::mac;

/// Default relative tolerance on the frequency between consecutive orders.
pub const FREQUENCY_TOLERANCE: f64 = 0.01;
/// Default relative tolerance on the damping ratio between consecutive orders.
pub const DAMPING_TOLERANCE: f64 = 0.05;
/// Default lower bound of the MAC of the residue vectors between consecutive orders.
pub const MAC_MIN: f64 = 0.98;
/// Default upper bound of the damping ratio of a physical pole.
pub const MAX_DAMPING: f64 = 0.2;

/// The default least number of stable poles of a physical chain for `orders` orders.
pub fn min_stable_default(orders: usize) -> usize {
    (orders / 5).max(5)
}

/// Stability class of a pole, for the chart's markers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StabilityClass {
    /// Not stable in frequency.
    New,
    /// Stable in frequency only.
    Frequency,
    /// Stable in frequency and damping, not in shape.
    Damping,
    /// Stable in frequency and shape, not in damping.
    Shape,
    /// Stable in frequency, damping and shape.
    Stable,
}

/// One pole of one model order.
#[derive(Debug, Clone)]
pub struct ChartPole {
    /// Model order (degree of the denominator).
    pub order: usize,
    /// The pole (rad/s).
    pub pole: c64,
    /// Undamped natural frequency |pole| / 2 pi (Hz).
    pub frequency_hz: f64,
    /// Damping ratio -Re(pole) / |pole|.
    pub damping_ratio: f64,
    /// Stable in frequency against its match at the previous order.
    pub stable_frequency: bool,
    /// Stable in damping.
    pub stable_damping: bool,
    /// Stable in shape.
    pub stable_shape: bool,
    /// The chain it belongs to.
    pub chain: usize,
    /// Whether this is the pole chosen for a mode.
    pub selected: bool,
}

impl ChartPole {
    /// The class of the pole.
    pub fn class(&self) -> StabilityClass {
        match (
            self.stable_frequency,
            self.stable_damping,
            self.stable_shape,
        ) {
            (false, _, _) => StabilityClass::New,
            (true, true, true) => StabilityClass::Stable,
            (true, true, false) => StabilityClass::Damping,
            (true, false, true) => StabilityClass::Shape,
            (true, false, false) => StabilityClass::Frequency,
        }
    }

    /// Stable in frequency, damping and shape.
    pub fn is_stable(&self) -> bool {
        self.class() == StabilityClass::Stable
    }
}

/// The thresholds of the classification and of the choice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criteria {
    /// Relative frequency tolerance.
    pub frequency_tolerance: f64,
    /// Relative damping tolerance.
    pub damping_tolerance: f64,
    /// Least MAC of the residue vectors.
    pub mac_min: f64,
    /// Least number of stable poles of a physical chain.
    pub min_stable: usize,
    /// Largest damping ratio of a physical pole.
    pub max_damping: f64,
}

/// The poles of one order with their residue vectors.
pub struct OrderPoles {
    /// Model order.
    pub order: usize,
    /// Poles (positive frequency, stable, in the band).
    pub poles: Vec<c64>,
    /// Residue vector of every pole.
    pub residues: Vec<Vec<c64>>,
}

fn frequency(s: c64) -> f64 {
    s.norm() / (2.0 * std::f64::consts::PI)
}

fn damping(s: c64) -> f64 {
    -s.re / s.norm()
}

/// Classifies every pole of every order (see the module docs). Returns the chart's poles, in
/// order of `orders` and of the poles within.
pub fn classify(orders: &[OrderPoles], criteria: &Criteria) -> Vec<ChartPole> {
    let mut out: Vec<ChartPole> = Vec::new();
    let mut next_chain = 0;
    let mut previous: Option<(usize, &OrderPoles)> = None; // (first index in out, order)
    for current in orders {
        let start = out.len();
        let mut matched: Vec<Option<usize>> = vec![None; current.poles.len()];
        if let Some((_, prev)) = previous {
            let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
            for (j, &s) in current.poles.iter().enumerate() {
                for (i, &q) in prev.poles.iter().enumerate() {
                    pairs.push(((s - q).norm() / q.norm(), j, i));
                }
            }
            pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
            let mut taken = vec![false; prev.poles.len()];
            for (_, j, i) in pairs {
                if matched[j].is_none() && !taken[i] {
                    matched[j] = Some(i);
                    taken[i] = true;
                }
            }
        }
        for (j, &s) in current.poles.iter().enumerate() {
            let (f, z) = (frequency(s), damping(s));
            let mut pole = ChartPole {
                order: current.order,
                pole: s,
                frequency_hz: f,
                damping_ratio: z,
                stable_frequency: false,
                stable_damping: false,
                stable_shape: false,
                chain: 0,
                selected: false,
            };
            if let (Some(i), Some((prev_start, prev))) = (matched[j], previous) {
                let q = prev.poles[i];
                let (fq, zq) = (frequency(q), damping(q));
                pole.stable_frequency = (f - fq).abs() < criteria.frequency_tolerance * fq;
                pole.stable_damping = (z - zq).abs() < criteria.damping_tolerance * zq;
                pole.stable_shape = mac(&current.residues[j], &prev.residues[i]) > criteria.mac_min;
                if pole.stable_frequency {
                    pole.chain = out[prev_start + i].chain;
                }
            }
            if !pole.stable_frequency {
                pole.chain = next_chain;
                next_chain += 1;
            }
            out.push(pole);
        }
        previous = Some((start, current));
    }
    out
}

/// A chain of poles with the stable poles it holds (see the module docs).
#[derive(Debug, Clone)]
pub struct Chain {
    /// Index in the chart of its stable pole of median frequency.
    pub pole: usize,
    /// Number of stable poles of the chain.
    pub stable_count: usize,
    /// First and last order at which the chain is stable.
    pub orders: (usize, usize),
    /// The orders at which it is stable, ascending.
    pub stable_orders: Vec<usize>,
    /// Its longest run of consecutive stable orders: (first order, number of orders).
    pub run: (usize, usize),
    /// Median damping ratio of its stable poles.
    pub median_damping: f64,
}

/// The longest run of consecutive integers in the ascending `orders`: (first, length); the
/// first such run on ties, (0, 0) when empty.
pub fn longest_run(orders: &[usize]) -> (usize, usize) {
    let mut best = (0, 0);
    let mut start = 0;
    for i in 0..orders.len() {
        if i > 0 && orders[i] != orders[i - 1] + 1 {
            start = i;
        }
        let length = i - start + 1;
        if length > best.1 {
            best = (orders[start], length);
        }
    }
    best
}

/// Every chain of the chart holding at least one stable pole, in order of chain number.
pub fn chains(chart: &[ChartPole]) -> Vec<Chain> {
    let count = chart.iter().map(|p| p.chain + 1).max().unwrap_or(0);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, p) in chart.iter().enumerate() {
        if p.is_stable() {
            members[p.chain].push(i);
        }
    }
    members
        .into_iter()
        .filter(|stable| !stable.is_empty())
        .map(|stable| {
            let mut by_damping: Vec<f64> = stable.iter().map(|&i| chart[i].damping_ratio).collect();
            by_damping.sort_by(f64::total_cmp);
            let mut by_frequency = stable.clone();
            by_frequency.sort_by(|&a, &b| chart[a].frequency_hz.total_cmp(&chart[b].frequency_hz));
            let stable_orders: Vec<usize> = stable.iter().map(|&i| chart[i].order).collect();
            Chain {
                pole: by_frequency[by_frequency.len() / 2],
                stable_count: stable.len(),
                orders: (stable_orders[0], stable_orders[stable_orders.len() - 1]),
                run: longest_run(&stable_orders),
                stable_orders,
                median_damping: by_damping[by_damping.len() / 2],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_run_of_orders_is_the_first_of_the_longest() {
        assert_eq!(longest_run(&[]), (0, 0));
        assert_eq!(longest_run(&[7]), (7, 1));
        assert_eq!(longest_run(&[3, 4, 5, 9, 10, 11, 12, 20]), (9, 4));
        assert_eq!(longest_run(&[3, 4, 8, 9]), (3, 2));
    }
}
