//! The record of a beam calibrated on a reference test (`jointid calibrate`, the paper's first
//! step): the factors by which its material values were scaled from the values the user typed,
//! with their standard errors, kept in the model file as `[beam.calibrated]` so that a
//! diagnosis can compare the joint identified on the calibrated beams with the joint the
//! typed beams would have given.
//!
//! A stiffness factor scales E of the beam, of its segments, and its shear modulus G with it
//! (E / G stays the material's); a density factor scales rho of the beam and its segments.

use super::{Beam, Chain};

/// A fitted factor and its standard error.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Factor {
    /// The factor (1: the typed value).
    pub value: f64,
    /// Its standard error.
    pub se: f64,
}

/// What a reference test changed on one beam.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BeamCalibration {
    /// The beam, 0-based in chain order.
    pub beam: usize,
    /// The factor of its stiffness (E and G).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<Factor>,
    /// The factor of its density.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub density: Option<Factor>,
    /// The reference test it was calibrated on (as the calibration named it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<String>,
}

/// Scales the material of `beam`: E (and G) by `stiffness`, rho by `density`, segments
/// included.
pub fn scale_beam(beam: &mut Beam, stiffness: f64, density: f64) {
    beam.youngs_modulus *= stiffness;
    beam.density *= density;
    if let Some(shear) = &mut beam.shear {
        shear.modulus *= stiffness;
    }
    for segment in &mut beam.segments {
        let s = &mut segment.section;
        s.youngs_modulus *= stiffness;
        s.density *= density;
        if let Some(shear) = &mut s.shear {
            shear.modulus *= stiffness;
        }
    }
}

impl Chain {
    /// The chain with the beams' values as typed before their calibration (every factor
    /// divided out; the records dropped).
    pub fn typed(&self) -> Chain {
        let mut chain = self.clone();
        for c in &self.calibration {
            let of = |f: Option<Factor>| f.map_or(1.0, |f| 1.0 / f.value);
            scale_beam(&mut chain.beams[c.beam], of(c.stiffness), of(c.density));
        }
        chain.calibration.clear();
        chain
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_chain;
    use crate::structure::Shear;

    #[test]
    fn the_typed_chain_divides_every_factor_out_of_beam_segments_and_shear() {
        let mut chain = paper_chain(1e7, 1e4);
        chain.beams[1].shear = Some(Shear {
            factor: 0.85,
            modulus: 8e10,
        });
        let mut segment = chain.beams[1].clone();
        segment.youngs_modulus = 1e11;
        chain.beams[1].segments.push(super::super::Segment {
            from: 0.0,
            to: 0.1,
            section: segment.section(),
        });
        let typed = chain.clone();
        scale_beam(&mut chain.beams[1], 1.03, 0.98);
        assert_eq!(
            chain.beams[1].segments[0].section.youngs_modulus,
            1e11 * 1.03
        );
        assert_eq!(chain.beams[1].shear.unwrap().modulus, 8e10 * 1.03);
        chain.calibration.push(BeamCalibration {
            beam: 1,
            stiffness: Some(Factor {
                value: 1.03,
                se: 0.01,
            }),
            density: Some(Factor {
                value: 0.98,
                se: 0.01,
            }),
            reference: None,
        });
        let back = chain.typed();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-15 * b;
        assert!(close(
            back.beams[1].youngs_modulus,
            typed.beams[1].youngs_modulus
        ));
        assert!(close(back.beams[1].density, typed.beams[1].density));
        assert!(close(
            back.beams[1].segments[0].section.youngs_modulus,
            1e11
        ));
        assert!(close(back.beams[1].shear.unwrap().modulus, 8e10));
        assert_eq!(back.beams[0], typed.beams[0]);
        assert!(back.calibration.is_empty());
    }
}
