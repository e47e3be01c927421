//! The reference specimen of a calibration, derived from the jointed model the user wrote:
//!
//! - `monolithic`: the same beams without their joints, made of one piece. Every point joint
//!   is rigid: the two beams it joins become one beam whose sections are theirs, stepped where
//!   they were (each keeps its segments), meshed no coarser than the finer of the two, with a
//!   node where the joint was. The overlap a point joint declares (`[joint.lap]`) is dropped
//!   with it: its beams' lap segments stay, as the monolithic specimen of a lap keeps its
//!   geometry. Supports, masses, sensors and extra nodes stay where they are along the chain.
//! - `beam:K`: beam K alone (1-based, chain order), with what lies on it (supports, masses,
//!   sensors and extra nodes from its start to its end), its abscissae counted from its start.
//!
//! A joint that is itself a layered lap (`kind = "lap"`) has no monolithic specimen here: its
//! layers tied rigidly are another geometry. Nothing of the specimen is identified: supports'
//! springs and masses keep their values.

use std::str::FromStr;

use super::CalibrateError;
use crate::model::chain::{Beam, Chain, Segment};

/// Which test the reference modes come from (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Specimen {
    /// The chain in one piece, every joint rigid.
    Monolithic,
    /// One beam alone, 0-based.
    Beam(usize),
}

impl FromStr for Specimen {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let allowed = "it must be `monolithic` or `beam:K` (K = 1, 2, ...: one beam alone)";
        if s == "monolithic" {
            return Ok(Specimen::Monolithic);
        }
        match s.strip_prefix("beam:").map(str::parse::<usize>) {
            Some(Ok(k)) if k >= 1 => Ok(Specimen::Beam(k - 1)),
            _ => Err(format!(
                "\"{}\": {allowed}",
                s.chars().take(40).collect::<String>()
            )),
        }
    }
}

impl std::fmt::Display for Specimen {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Specimen::Monolithic => write!(f, "monolithic"),
            Specimen::Beam(b) => write!(f, "beam:{}", b + 1),
        }
    }
}

/// The beams of `chain` that make `specimen` (0-based).
pub fn beams_of(chain: &Chain, specimen: Specimen) -> Vec<usize> {
    match specimen {
        Specimen::Monolithic => (0..chain.beams.len()).collect(),
        Specimen::Beam(b) => vec![b],
    }
}

/// The chain of `specimen` made of `chain`'s beams (module docs).
pub fn specimen_chain(chain: &Chain, specimen: Specimen) -> Result<Chain, CalibrateError> {
    let mut out = match specimen {
        Specimen::Beam(b) => alone(chain, b)?,
        Specimen::Monolithic => monolithic(chain)?,
    };
    for support in &mut out.supports {
        support.identify = [false; 2];
    }
    for mass in &mut out.masses {
        mass.identify = false;
    }
    out.calibration.clear();
    Ok(out)
}

/// Beam `b` alone, with what lies on it.
fn alone(chain: &Chain, b: usize) -> Result<Chain, CalibrateError> {
    if b >= chain.beams.len() {
        return Err(CalibrateError::NoSuchBeam {
            beam: b + 1,
            beams: chain.beams.len(),
        });
    }
    let start = chain.beam_start(b);
    let end = start + chain.beams[b].length;
    let tol = 1e-9 * chain.length();
    let on = |x: f64| x >= start - tol && x <= end + tol;
    let local = |x: f64| (x - start).clamp(0.0, end - start);
    let mut out = Chain::free(vec![chain.beams[b].clone()], Vec::new());
    out.supports = chain.supports.iter().filter(|s| on(s.x)).cloned().collect();
    out.masses = chain.masses.iter().filter(|m| on(m.x)).cloned().collect();
    out.sensors = chain.sensors.iter().filter(|s| on(s.x)).cloned().collect();
    out.nodes_at = chain.nodes_at.iter().copied().filter(|&x| on(x)).collect();
    for s in &mut out.supports {
        s.x = local(s.x);
    }
    for m in &mut out.masses {
        m.x = local(m.x);
    }
    for s in &mut out.sensors {
        s.x = local(s.x);
    }
    for x in &mut out.nodes_at {
        *x = local(*x);
    }
    Ok(out)
}

/// The chain in one piece: every joint rigid.
fn monolithic(chain: &Chain) -> Result<Chain, CalibrateError> {
    if let Some(j) = chain
        .joints
        .iter()
        .position(|j| j.lap.is_some_and(|l| l.active))
    {
        return Err(CalibrateError::LapJoint { joint: j + 1 });
    }
    let mut beams = chain.beams.iter();
    let first = beams.next().expect("a chain has a beam").clone();
    let one = beams.fold(first, |a, b| joined(&a, b));
    let mut out = chain.clone();
    out.nodes_at
        .extend((1..chain.beams.len()).map(|b| chain.beam_start(b)));
    out.beams = vec![one];
    out.joints.clear();
    Ok(out)
}

/// Beam `b` made one piece with the end of `a` (module docs).
fn joined(a: &Beam, b: &Beam) -> Beam {
    let at = a.length;
    let length = at + b.length;
    let h = a.element_length().min(b.element_length());
    let mut own: Vec<&Segment> = b.segments.iter().collect();
    own.sort_by(|x, y| x.from.total_cmp(&y.from));
    let mut segments = a.segments.clone();
    let mut cursor = 0.0;
    let plain = |from: f64, to: f64, segments: &mut Vec<Segment>| {
        if to > from {
            segments.push(Segment {
                from: at + from,
                to: at + to,
                section: b.section(),
            });
        }
    };
    for g in own {
        plain(cursor, g.from, &mut segments);
        segments.push(Segment {
            from: at + g.from,
            to: at + g.to,
            section: g.section,
        });
        cursor = g.to;
    }
    plain(cursor, b.length, &mut segments);
    let mut out = a.clone();
    out.length = length;
    out.elements = ((length / h) * (1.0 - 1e-9)).ceil().max(1.0) as usize;
    out.segments = segments;
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::fixtures::{paper_chain, steel_bar};

    fn elastic_hz(chain: &Chain, count: usize) -> Vec<f64> {
        let s = chain.build();
        let modal = ModalSolution::solve(&s.assemble()).unwrap();
        (s.rigid..s.rigid + count)
            .map(|i| modal.frequency_hz(i))
            .collect()
    }

    #[test]
    fn the_monolithic_specimen_of_equal_bars_is_the_bar_of_their_length() {
        // Two 0.25 m bars of 10 elements, joined rigidly: the 0.5 m bar of 20.
        let chain = Chain::free(
            vec![steel_bar(0.25, 10), steel_bar(0.25, 10)],
            vec![crate::model::Joint::identified(1e7, 1e4)],
        );
        let one = specimen_chain(&chain, Specimen::Monolithic).unwrap();
        let bar = Chain::free(vec![steel_bar(0.5, 20)], Vec::new());
        let (a, b) = (elastic_hz(&one, 5), elastic_hz(&bar, 5));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-10 * y, "{a:?} vs {b:?}");
        }
        assert!(one.build().identified().is_empty());
    }

    #[test]
    fn a_stiffer_second_beam_stiffens_its_part_of_the_monolithic_specimen() {
        let mut chain = paper_chain(1e7, 1e4);
        chain.beams[1].youngs_modulus *= 1.5;
        let one = specimen_chain(&chain, Specimen::Monolithic).unwrap();
        assert_eq!(one.beams.len(), 1);
        let s = &one.beams[0].segments;
        assert_eq!(s.len(), 1);
        assert!((s[0].from - 0.2).abs() < 1e-15 && (s[0].to - 0.5).abs() < 1e-15);
        assert_eq!(s[0].section.youngs_modulus, chain.beams[1].youngs_modulus);
        // The paper's beams have elements of 0.2/7 and 0.3/10: the finer rules.
        assert_eq!(one.beams[0].elements, 18);
    }

    #[test]
    fn one_beam_alone_keeps_what_lies_on_it_counted_from_its_start() {
        let mut chain = paper_chain(1e7, 1e4);
        chain.sensors = vec![
            crate::model::chain::Sensor {
                x: 0.1,
                direction: crate::structure::Direction::W,
                label: None,
                mass: 0.0,
            },
            crate::model::chain::Sensor {
                x: 0.35,
                direction: crate::structure::Direction::W,
                label: Some("tip".into()),
                mass: 0.01,
            },
        ];
        let second = specimen_chain(&chain, Specimen::Beam(1)).unwrap();
        assert_eq!(second.beams, vec![chain.beams[1].clone()]);
        assert_eq!(second.sensors.len(), 1);
        assert!((second.sensors[0].x - 0.15).abs() < 1e-15);
        assert!(matches!(
            specimen_chain(&chain, Specimen::Beam(2)),
            Err(CalibrateError::NoSuchBeam { beam: 3, beams: 2 })
        ));
    }

    #[test]
    fn specimens_parse_and_print_back() {
        for s in ["monolithic", "beam:1", "beam:7"] {
            assert_eq!(s.parse::<Specimen>().unwrap().to_string(), s);
        }
        for s in ["beam:0", "beam:", "beam:-1", "Monolithic", ""] {
            assert!(s.parse::<Specimen>().is_err(), "{s}");
        }
    }
}
