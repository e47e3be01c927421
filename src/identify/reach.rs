//! The far ends of a parameter's reach in the frequency-only identification
//! ([`super::frequency_only`]), solved once for every mode that identifies that parameter.
//!
//! The search brackets the root between p_0 / REACH and p_0 REACH. At those ends the model is
//! far from the nominal one, where a reduced model ([`crate::modal::reduced`]) would need as
//! many enrichments as a full solve costs: they are solved in full, once per parameter and
//! end, with the pairs of every mode, and shared by the modes (each mode solved them itself
//! before, 16 full solves for 8 modes of one parameter, now 2).

use std::sync::OnceLock;

use crate::modal::{ModalError, reduced};
use crate::structure::Structure;

/// The eigenvalues of one end, solved when first asked for.
type End = OnceLock<Result<Vec<f64>, ModalError>>;

/// The eigenvalues at both ends of every identified parameter's reach, solved when first
/// asked for.
pub struct Ends<'a> {
    structure: &'a Structure,
    count: usize,
    solved: Vec<[End; 2]>,
}

impl<'a> Ends<'a> {
    /// The ends of `structure`'s parameters, each solve for its lowest `count` pairs.
    pub fn new(structure: &'a Structure, count: usize) -> Self {
        let solved = structure
            .identified()
            .iter()
            .map(|_| [OnceLock::new(), OnceLock::new()])
            .collect();
        Ends {
            structure,
            count,
            solved,
        }
    }

    /// Eigenvalue `t` with identified parameter `param` at `factor` (REACH or 1 / REACH, the
    /// larger end `high`) times its value; none when `t` is beyond the pairs solved.
    pub fn eigenvalue(
        &self,
        param: usize,
        high: bool,
        factor: f64,
        t: usize,
    ) -> Option<Result<f64, ModalError>> {
        if t >= self.count {
            return None;
        }
        let values = self.solved[param][usize::from(high)].get_or_init(|| {
            let mut values: Vec<f64> = self
                .structure
                .identified()
                .iter()
                .map(|p| p.value)
                .collect();
            values[param] *= factor;
            let mut at = self.structure.with_values(&values);
            at.reduced = None;
            reduced::full(&at, &[], self.count).map(|m| m.values().to_vec())
        });
        Some(values.clone().map(|v| v[t]))
    }
}
