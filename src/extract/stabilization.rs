//! The stabilisation chart and the automatic choice of the physical poles.
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
//! a chain. A pole stable in all three is *stable*.
//!
//! Choice (the rule): a chain is physical when it holds at least `min_stable` stable poles
//! ([`min_stable_default`]: 20% of the orders, at least 5) and the median damping of its
//! stable poles is below `max_damping`. Its pole is the stable pole of median frequency.
//! Two physical chains within the frequency tolerance are one mode when they never share an
//! order (a chain broken and resumed) or when their shapes agree (MAC > `mac_min`: one pole
//! split in two): the chain with more stable poles stays. Close modes (distinct shapes,
//! present at the same orders) stay apart. With a requested number of modes, the chains with
//! the most stable poles are kept; the modes are returned by ascending frequency.

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

/// A chain chosen as a physical mode.
#[derive(Debug, Clone)]
pub struct Chosen {
    /// Index of the chosen pole in the chart.
    pub pole: usize,
    /// Number of stable poles of the chain.
    pub stable_count: usize,
    /// First and last order at which the chain is stable.
    pub orders: (usize, usize),
}

/// Chooses the physical poles (see the module docs) and marks them in `chart`. `residues[i]` is
/// the residue vector of chart pole i. `n_modes`: the number of modes wanted, if fixed.
pub fn choose(
    chart: &mut [ChartPole],
    residues: &[&[c64]],
    criteria: &Criteria,
    n_modes: Option<usize>,
) -> Vec<Chosen> {
    let chains = chart.iter().map(|p| p.chain + 1).max().unwrap_or(0);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); chains];
    for (i, p) in chart.iter().enumerate() {
        if p.is_stable() {
            members[p.chain].push(i);
        }
    }
    let mut candidates: Vec<(Chosen, Vec<usize>)> = Vec::new();
    for stable in members {
        if stable.len() < criteria.min_stable {
            continue;
        }
        let mut by_damping: Vec<f64> = stable.iter().map(|&i| chart[i].damping_ratio).collect();
        by_damping.sort_by(f64::total_cmp);
        if by_damping[by_damping.len() / 2] >= criteria.max_damping {
            continue;
        }
        let mut by_frequency = stable.clone();
        by_frequency.sort_by(|&a, &b| chart[a].frequency_hz.total_cmp(&chart[b].frequency_hz));
        let pole = by_frequency[by_frequency.len() / 2];
        let orders = (
            stable.iter().map(|&i| chart[i].order).min().unwrap_or(0),
            stable.iter().map(|&i| chart[i].order).max().unwrap_or(0),
        );
        candidates.push((
            Chosen {
                pole,
                stable_count: stable.len(),
                orders,
            },
            stable.iter().map(|&i| chart[i].order).collect(),
        ));
    }
    // Most stable poles first; ties to the lower frequency.
    candidates.sort_by(|a, b| {
        b.0.stable_count.cmp(&a.0.stable_count).then(
            chart[a.0.pole]
                .frequency_hz
                .total_cmp(&chart[b.0.pole].frequency_hz),
        )
    });
    let mut kept: Vec<(Chosen, Vec<usize>)> = Vec::new();
    for (c, orders) in candidates {
        let f = chart[c.pole].frequency_hz;
        let duplicate = kept.iter().any(|(k, k_orders)| {
            let fk = chart[k.pole].frequency_hz;
            let near = (f - fk).abs() < criteria.frequency_tolerance * fk;
            let disjoint = !orders.iter().any(|o| k_orders.contains(o));
            let same_shape = mac(residues[c.pole], residues[k.pole]) > criteria.mac_min;
            near && (disjoint || same_shape)
        });
        if !duplicate {
            kept.push((c, orders));
        }
    }
    if let Some(n) = n_modes {
        kept.truncate(n);
    }
    let mut chosen: Vec<Chosen> = kept.into_iter().map(|(c, _)| c).collect();
    chosen.sort_by(|a, b| {
        chart[a.pole]
            .frequency_hz
            .total_cmp(&chart[b.pole].frequency_hz)
    });
    for c in &chosen {
        chart[c.pole].selected = true;
    }
    chosen
}
