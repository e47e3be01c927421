//! The catalogue of everything a user can name (the diagnosis's candidates, simulate's
//! effects) as a Markdown table, for docs/diagnosis.md: generated from the registries, never
//! kept by hand (tests/suite/registry.rs compares the documented copy with it).

use crate::diagnose::candidate::Entry;
use crate::model::effects::Tier;

/// The Markdown table of `entries`: name, the diagnosis's tier, whether simulate accepts it,
/// what it is and what its size means.
pub fn markdown(entries: &[Entry]) -> String {
    let mut out = String::from(
        "| name | diagnose searches it | `simulate --effect` | what it is; its size |\n|---|---|---|---|\n",
    );
    for e in entries {
        let tier = match e.tier {
            Tier::Default => "always",
            Tier::Extended => "with `--extended`",
            Tier::Outside => "never",
        };
        let simulate = if e.simulate { "yes" } else { "no" };
        out.push_str(&format!(
            "| `{}` | {tier} | {simulate} | {} |\n",
            e.name,
            e.describe.replace('|', "\\|")
        ));
    }
    out
}
