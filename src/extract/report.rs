//! The choices of an extraction as a JSON report (`jointid extract --report`): the band and
//! where it came from, the rules, every candidate mode with why it was kept or rejected.
//! The fields are listed in docs/formats.md.

use serde::Serialize;

use super::Extraction;
use super::choice::Decision;
use super::excitation::BandSource;

/// Version of the report's layout; raised when a field changes meaning or goes.
pub const VERSION: u32 = 1;

/// The band of the report.
#[derive(Debug, Serialize)]
pub struct BandReport {
    /// Lower and upper edges (Hz).
    pub hz: (f64, f64),
    /// Where it came from.
    pub source: BandSource,
    /// The automatic band before its extension for the modes' margins, when extended.
    pub extended_from: Option<(f64, f64)>,
}

/// The thresholds of the chart and of the choice.
#[derive(Debug, Serialize)]
pub struct RulesReport {
    pub frequency_tolerance: f64,
    pub damping_tolerance: f64,
    pub mac_min: f64,
    pub max_damping: f64,
    pub min_stable: usize,
    pub max_order: usize,
    /// Whether the automatic rules applied (no number of modes requested).
    pub automatic: bool,
    pub mpc_min: f64,
    pub low_order_share: f64,
    /// The last order at which a mode's run of stable orders may start.
    pub last_start: usize,
    /// Least distance of a mode to the band's edges (half-power bandwidths).
    pub edge_margin: f64,
}

/// The whole report.
#[derive(Debug, Serialize)]
pub struct Report<'a> {
    pub version: u32,
    pub band: BandReport,
    pub rules: RulesReport,
    /// Every candidate: the kept ones first (`mode` 1, 2, ...), then the rejected ones.
    pub candidates: &'a [Decision],
    /// Chains with fewer than `min_stable` stable poles (not candidates).
    pub weak_chains: usize,
}

impl<'a> Report<'a> {
    /// The report of `ex`.
    pub fn of(ex: &'a Extraction) -> Self {
        let c = &ex.criteria;
        Report {
            version: VERSION,
            band: BandReport {
                hz: ex.band_hz,
                source: ex.band_source,
                extended_from: ex.extended_from,
            },
            rules: RulesReport {
                frequency_tolerance: c.frequency_tolerance,
                damping_tolerance: c.damping_tolerance,
                mac_min: c.mac_min,
                max_damping: c.max_damping,
                min_stable: c.min_stable,
                max_order: ex.max_order,
                automatic: ex.requested.is_none(),
                mpc_min: ex.rules.mpc_min,
                low_order_share: ex.rules.low_order_share,
                last_start: ex.rules.last_start(),
                edge_margin: ex.edge_margin,
            },
            candidates: &ex.decisions,
            weak_chains: ex.weak_chains,
        }
    }

    /// Writes the report as pretty JSON.
    pub fn write(&self, w: &mut dyn std::io::Write) -> std::io::Result<()> {
        serde_json::to_writer_pretty(&mut *w, self).map_err(std::io::Error::other)?;
        writeln!(w)
    }
}
