//! The input of `jointid extract` from universal files: the FRFs of one reference (dataset 58,
//! function type 4) gathered from one or more files into an [`FrfSet`], their coherences
//! (function type 6) matched by DOF, and the positions along the beam of the response nodes from
//! a geometry (dataset 15 or 2411).
//!
//! What is checked, each failure an [`UffInputError`] naming the file and the record: one
//! reference DOF for every FRF, one frequency axis (start, step, number of points), one
//! ordinate quantity and one units label (no FRF in m/s^2/N beside one in g/N), no response DOF
//! twice, a bending DOF (translation along Y or Z, rotation about Y or Z: the beam lies along
//! X; any direction for a structure in space, [`Responses::Space`]), and every response node
//! present in the geometry. A negative direction (the sensor
//! mounted the other way round) flips the sign of its FRF so that every shape component is in
//! the positive sense of its axis.
//!
//! The quantity comes from the ordinate's specific data type of record 9 (8 displacement,
//! 11 velocity, 12 acceleration), else from its units label (`m`, `m/s`, `m/s^2` before the
//! `/` of the reference), else it must be given.

use std::path::{Path, PathBuf};

use crate::uff::{Function, FunctionType, Nodes, Record};

use super::{FrfSet, Quantity};

/// Relative tolerance of an even frequency axis stored as uneven 6-digit values
/// (see [`Function::even_abscissa`]).
pub const AXIS_TOLERANCE: f64 = 5e-6;

/// Where one response of the set came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// The file.
    pub file: PathBuf,
    /// 1-based index of its dataset in the file.
    pub record: usize,
    /// Response node.
    pub node: u64,
    /// Response direction as the file gives it (+-2, +-3 translations; +-5, +-6 rotations).
    pub direction: i32,
}

impl Channel {
    /// Whether the DOF is a rotation.
    pub fn is_rotation(&self) -> bool {
        self.direction.abs() >= 4
    }
}

/// The FRFs of the files, ready for [`super::extract`].
#[derive(Debug, Clone)]
pub struct UffFrfs {
    /// The set; response o is `channels[o]`.
    pub set: FrfSet,
    /// One per response.
    pub channels: Vec<Channel>,
    /// The reference (node, direction).
    pub reference: (u64, i32),
    /// The ordinate's units label, e.g. `m/s^2/V`.
    pub units: String,
}

/// Universal files that do not make one set of FRFs.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UffInputError {
    /// No dataset 58 of function type 4 in any file.
    #[error("{files}: no FRF (dataset 58 of function type 4) in the file(s)")]
    NoFrf {
        /// The files, comma separated.
        files: String,
    },
    /// An FRF of another reference.
    #[error(
        "{}: record {record}: reference node {node} direction {direction}, but record {first_record} of {} has node {first_node} direction {first_direction}; every FRF needs the same reference",
        file.display(), first_file.display()
    )]
    MixedReference {
        file: PathBuf,
        record: usize,
        node: u64,
        direction: i32,
        first_file: PathBuf,
        first_record: usize,
        first_node: u64,
        first_direction: i32,
    },
    /// An FRF on another frequency axis.
    #[error(
        "{}: record {record}: frequency axis {what}; the first FRF has {expected}: every FRF and coherence needs one axis",
        file.display()
    )]
    MixedAxis {
        file: PathBuf,
        record: usize,
        what: String,
        expected: String,
    },
    /// An abscissa that is not evenly spaced.
    #[error("{}: record {record}: the frequency axis is not evenly spaced", file.display())]
    UnevenAxis { file: PathBuf, record: usize },
    /// A function of fewer than two points: no axis at all.
    #[error(
        "{}: record {record} has {points} point(s): an FRF needs at least two frequency lines",
        file.display()
    )]
    TooFewPoints {
        file: PathBuf,
        record: usize,
        points: usize,
    },
    /// An FRF of another quantity or units.
    #[error(
        "{}: record {record}: ordinate {what}, but the first FRF has {expected}; mixed units are refused",
        file.display()
    )]
    MixedUnits {
        file: PathBuf,
        record: usize,
        what: String,
        expected: String,
    },
    /// The quantity cannot be told.
    #[error(
        "{}: record {record}: the ordinate's data type {data_type} and units {units:?} do not say displacement, velocity or acceleration; give the quantity",
        file.display()
    )]
    UnknownQuantity {
        file: PathBuf,
        record: usize,
        data_type: i32,
        units: String,
    },
    /// A response DOF given twice.
    #[error(
        "{}: record {record}: response node {node} direction {direction} is already given by record {first_record} of {}",
        file.display(), first_file.display()
    )]
    DuplicateResponse {
        file: PathBuf,
        record: usize,
        node: u64,
        direction: i32,
        first_file: PathBuf,
        first_record: usize,
    },
    /// A DOF that is not a bending DOF of a beam along X.
    #[error(
        "{}: record {record}: response node {node} direction {direction} is not a bending DOF; allowed: +-2, +-3 (translation Y, Z), +-5, +-6 (rotation about Y, Z)",
        file.display()
    )]
    NotBending {
        file: PathBuf,
        record: usize,
        node: u64,
        direction: i32,
    },
    /// A DOF that is not a direction in space.
    #[error(
        "{}: record {record}: response node {node} direction {direction} is not a direction in space; allowed: +-1, +-2, +-3 (translation X, Y, Z), +-4, +-5, +-6 (rotation about X, Y, Z)",
        file.display()
    )]
    NotInSpace {
        file: PathBuf,
        record: usize,
        node: u64,
        direction: i32,
    },
    /// A response node absent from the geometry.
    #[error(
        "{}: response node {node} (record {record} of {}) is not in the geometry; its nodes: {present}",
        geometry.display(), file.display()
    )]
    MissingNode {
        geometry: PathBuf,
        node: u64,
        file: PathBuf,
        record: usize,
        present: String,
    },
    /// A geometry without nodes.
    #[error("{}: no node coordinates (dataset 15 or 2411)", geometry.display())]
    NoGeometry { geometry: PathBuf },
    /// A node given twice at different places.
    #[error(
        "{}: node {node} is given twice, at {first:?} and at {second:?}: a node has one place; remove or renumber one of them",
        geometry.display()
    )]
    DuplicateNode {
        geometry: PathBuf,
        node: u64,
        first: [f64; 3],
        second: [f64; 3],
    },
}

/// The frequency lines of an axis (start, step, points): start + i step.
fn lines((start, step, points): (f64, f64, usize)) -> Vec<f64> {
    (0..points).map(|i| start + i as f64 * step).collect()
}

/// The frequency lines of an axis given by its values (as a universal file's uneven
/// abscissa, or a reader that computed them), evenly spaced within [`AXIS_TOLERANCE`]: the
/// lines a file with these values gives; None when they are not evenly spaced.
pub fn even_lines(x: &[f64]) -> Option<Vec<f64>> {
    crate::uff::function::even_values(x, AXIS_TOLERANCE).map(|(a, b)| lines((a, b, x.len())))
}

fn axis_of(f: &Function) -> Option<(f64, f64, usize)> {
    f.even_abscissa(AXIS_TOLERANCE)
        .map(|(a, b)| (a, b, f.len()))
}

/// The axis of a found function, or why it has none (too few points, uneven).
fn axis_or_error(x: &Found) -> Result<(f64, f64, usize), UffInputError> {
    if x.f.len() < 2 {
        return Err(UffInputError::TooFewPoints {
            file: x.file.to_path_buf(),
            record: x.record,
            points: x.f.len(),
        });
    }
    axis_of(x.f).ok_or_else(|| UffInputError::UnevenAxis {
        file: x.file.to_path_buf(),
        record: x.record,
    })
}

/// Same number of points, start within 1e-6 of a step, step within 1e-6 relative.
fn same_axis(a: (f64, f64, usize), b: (f64, f64, usize)) -> bool {
    let step = a.1.abs();
    a.2 == b.2 && (a.0 - b.0).abs() <= 1e-6 * step && (a.1 - b.1).abs() <= 1e-6 * step
}

/// The quantity of an FRF's ordinate (see the module docs).
fn quantity_of(f: &Function) -> Option<Quantity> {
    match f.ordinate_axis.data_type {
        8 => return Some(Quantity::Displacement),
        11 => return Some(Quantity::Velocity),
        12 => return Some(Quantity::Acceleration),
        _ => {}
    }
    let units = f.ordinate_axis.units.replace(' ', "");
    let numerator = units.split('/').next().unwrap_or("");
    let per_second = units.split('/').nth(1).unwrap_or("");
    match (numerator, per_second) {
        ("m", "s^2" | "s2" | "s**2") => Some(Quantity::Acceleration),
        ("m", "s") => Some(Quantity::Velocity),
        ("m", _) => Some(Quantity::Displacement),
        _ => None,
    }
}

/// A function record found in one of the files.
struct Found<'a> {
    file: &'a Path,
    /// 1-based index of the record in its file.
    record: usize,
    f: &'a Function,
}

/// The FRFs and the coherences of `files`, in file and record order.
fn gather(files: &[(PathBuf, Vec<Record>)]) -> (Vec<Found<'_>>, Vec<Found<'_>>) {
    let mut frf: Vec<Found> = Vec::new();
    let mut coherence: Vec<Found> = Vec::new();
    for (file, records) in files {
        for (i, r) in records.iter().enumerate() {
            if let Record::Function(f) = r {
                let found = Found {
                    file,
                    record: i + 1,
                    f,
                };
                match f.function_type {
                    FunctionType::Frf => frf.push(found),
                    FunctionType::Coherence => coherence.push(found),
                    _ => {}
                }
            }
        }
    }
    (frf, coherence)
}

/// What the first FRF sets and every other function must share.
struct Frame<'a> {
    first: &'a Found<'a>,
    /// The abscissa: start (Hz), step (Hz), points.
    axis: (f64, f64, usize),
    /// The reference DOF (node, direction).
    reference: (u64, i32),
    /// The ordinate units.
    units: String,
    /// The quantity the first FRF declares.
    quantity: Option<Quantity>,
    /// The response directions allowed.
    responses: Responses,
}

impl Frame<'_> {
    /// The function's abscissa must be the first FRF's.
    fn check_axis(&self, x: &Found) -> Result<(), UffInputError> {
        let describe =
            |a: (f64, f64, usize)| format!("{} points from {} Hz by {} Hz", a.2, a.0, a.1);
        let here = axis_or_error(x)?;
        if same_axis(self.axis, here) {
            Ok(())
        } else {
            Err(UffInputError::MixedAxis {
                file: x.file.to_path_buf(),
                record: x.record,
                what: describe(here),
                expected: describe(self.axis),
            })
        }
    }

    /// The channel of FRF `x`, after checking it against the first FRF (reference, axis,
    /// units) and the `channels` before it (a bending DOF not measured twice).
    fn channel(&self, x: &Found, channels: &[Channel]) -> Result<Channel, UffInputError> {
        let (f, first) = (x.f, self.first);
        let here = (f.reference.node, f.reference.direction);
        if here != self.reference {
            return Err(UffInputError::MixedReference {
                file: x.file.to_path_buf(),
                record: x.record,
                node: here.0,
                direction: here.1,
                first_file: first.file.to_path_buf(),
                first_record: first.record,
                first_node: self.reference.0,
                first_direction: self.reference.1,
            });
        }
        self.check_axis(x)?;
        if f.ordinate_axis.units != self.units || quantity_of(f) != self.quantity {
            return Err(UffInputError::MixedUnits {
                file: x.file.to_path_buf(),
                record: x.record,
                what: format!(
                    "{:?} (data type {})",
                    f.ordinate_axis.units, f.ordinate_axis.data_type
                ),
                expected: format!(
                    "{:?} (data type {})",
                    self.units, first.f.ordinate_axis.data_type
                ),
            });
        }
        let (node, direction) = (f.response.node, f.response.direction);
        if self.responses == Responses::Space && !(1..=6).contains(&direction.abs()) {
            return Err(UffInputError::NotInSpace {
                file: x.file.to_path_buf(),
                record: x.record,
                node,
                direction,
            });
        }
        if self.responses == Responses::Bending && !matches!(direction.abs(), 2 | 3 | 5 | 6) {
            return Err(UffInputError::NotBending {
                file: x.file.to_path_buf(),
                record: x.record,
                node,
                direction,
            });
        }
        if let Some(c) = channels
            .iter()
            .find(|c| c.node == node && c.direction.abs() == direction.abs())
        {
            return Err(UffInputError::DuplicateResponse {
                file: x.file.to_path_buf(),
                record: x.record,
                node,
                direction,
                first_file: c.file.clone(),
                first_record: c.record,
            });
        }
        Ok(Channel {
            file: x.file.to_path_buf(),
            record: x.record,
            node,
            direction,
        })
    }

    /// The coherence of every channel (same response and reference DOF), or None when some
    /// channel has none.
    fn coherence(
        &self,
        coherence: &[Found],
        channels: &[Channel],
    ) -> Result<Option<Vec<Vec<f64>>>, UffInputError> {
        let mut matched = Vec::with_capacity(channels.len());
        for c in channels {
            let hit = coherence.iter().find(|x| {
                x.f.response.node == c.node
                    && x.f.response.direction == c.direction
                    && (x.f.reference.node, x.f.reference.direction) == self.reference
            });
            match hit {
                Some(x) => {
                    self.check_axis(x)?;
                    matched.push(
                        x.f.ordinate
                            .to_complex()
                            .iter()
                            .map(|v| v.re)
                            .collect::<Vec<f64>>(),
                    );
                }
                None => break,
            }
        }
        Ok((matched.len() == channels.len()).then_some(matched))
    }
}

/// Gathers the FRFs of `files` (path and records, in the order given). `quantity` overrides
/// the one the files declare.
pub fn frfs(
    files: &[(PathBuf, Vec<Record>)],
    quantity: Option<Quantity>,
) -> Result<UffFrfs, UffInputError> {
    frfs_of(files, quantity, Responses::Bending)
}

/// Which response directions a set may have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Responses {
    /// The bending DOFs of a beam along X: +-2, +-3, +-5, +-6.
    Bending,
    /// Any direction of a structure in space: +-1 to +-6 (translations X, Y, Z, rotations
    /// about them).
    Space,
}

/// [`frfs`] with the response directions `responses` allows.
pub fn frfs_of(
    files: &[(PathBuf, Vec<Record>)],
    quantity: Option<Quantity>,
    responses: Responses,
) -> Result<UffFrfs, UffInputError> {
    let (frf, coherence) = gather(files);
    let Some(first) = frf.first() else {
        return Err(UffInputError::NoFrf {
            files: files
                .iter()
                .map(|(p, _)| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        });
    };
    let axis = axis_or_error(first)?;
    let first_quantity = quantity_of(first.f);
    let quantity = match quantity.or(first_quantity) {
        Some(q) => q,
        None => {
            return Err(UffInputError::UnknownQuantity {
                file: first.file.to_path_buf(),
                record: first.record,
                data_type: first.f.ordinate_axis.data_type,
                units: first.f.ordinate_axis.units.clone(),
            });
        }
    };
    let frame = Frame {
        first,
        axis,
        reference: (first.f.reference.node, first.f.reference.direction),
        units: first.f.ordinate_axis.units.clone(),
        quantity: first_quantity,
        responses,
    };
    let mut channels: Vec<Channel> = Vec::new();
    let mut responses = Vec::new();
    for x in &frf {
        let channel = frame.channel(x, &channels)?;
        let sign = if channel.direction < 0 { -1.0 } else { 1.0 };
        responses.push(x.f.ordinate.to_complex().iter().map(|v| v * sign).collect());
        channels.push(channel);
    }
    let coherence = frame.coherence(&coherence, &channels)?;
    let frequencies_hz = lines(axis);
    Ok(UffFrfs {
        set: FrfSet {
            frequencies_hz,
            responses,
            coherence,
            quantity,
        },
        channels,
        reference: frame.reference,
        units: frame.units,
    })
}

/// The labels of `nodes` for a message: at most the first 20, then how many in all.
fn listed(nodes: &[&crate::uff::Node]) -> String {
    let mut labels: Vec<String> = nodes.iter().take(20).map(|n| n.label.to_string()).collect();
    if nodes.len() > 20 {
        labels.push(format!("... ({} in all)", nodes.len()));
    }
    labels.join(", ")
}

/// The X coordinate of each channel's node in the geometry `nodes` (read from `geometry`).
pub fn positions(
    channels: &[Channel],
    nodes: &[Nodes],
    geometry: &Path,
) -> Result<Vec<f64>, UffInputError> {
    Ok(coordinates(channels, nodes, geometry)?
        .into_iter()
        .map(|c| c[0])
        .collect())
}

/// The coordinates (X, Y, Z, as the geometry gives them) of each channel's node in the
/// geometry `nodes` (read from `geometry`).
pub fn coordinates(
    channels: &[Channel],
    nodes: &[Nodes],
    geometry: &Path,
) -> Result<Vec<[f64; 3]>, UffInputError> {
    let all: Vec<_> = nodes.iter().flat_map(|n| &n.nodes).collect();
    if all.is_empty() {
        return Err(UffInputError::NoGeometry {
            geometry: geometry.to_path_buf(),
        });
    }
    let mut seen: std::collections::HashMap<u64, [f64; 3]> = std::collections::HashMap::new();
    for n in &all {
        let first = *seen.entry(n.label).or_insert(n.coordinates);
        if first != n.coordinates {
            return Err(UffInputError::DuplicateNode {
                geometry: geometry.to_path_buf(),
                node: n.label,
                first,
                second: n.coordinates,
            });
        }
    }
    channels
        .iter()
        .map(|c| {
            all.iter()
                .find(|n| n.label == c.node)
                .map(|n| n.coordinates)
                .ok_or_else(|| UffInputError::MissingNode {
                    geometry: geometry.to_path_buf(),
                    node: c.node,
                    file: c.file.clone(),
                    record: c.record,
                    present: listed(&all),
                })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use faer::c64;

    use super::*;
    use crate::uff::{Abscissa, Axis, Dof, Encoding, Precision, Values};

    fn axis(data_type: i32, units: &str) -> Axis {
        Axis {
            data_type,
            length_exponent: 0,
            force_exponent: 0,
            temperature_exponent: 0,
            label: "NONE".into(),
            units: units.into(),
        }
    }

    /// A 4-point function of `kind` at response (node, direction) to node 100 direction 2.
    fn function(
        kind: FunctionType,
        node: u64,
        direction: i32,
        data_type: i32,
        units: &str,
    ) -> Record {
        Record::Function(Function {
            id_lines: Default::default(),
            function_type: kind,
            function_id: 1,
            version: 1,
            load_case: 0,
            response: Dof {
                entity: "NONE".into(),
                node,
                direction,
            },
            reference: Dof {
                entity: "NONE".into(),
                node: 100,
                direction: 2,
            },
            precision: Precision::Double,
            abscissa: Abscissa::Even {
                start: 0.0,
                step: 0.5,
            },
            z_value: 0.0,
            abscissa_axis: axis(18, "Hz"),
            ordinate_axis: axis(data_type, units),
            denominator_axis: axis(13, "N"),
            z_axis: axis(0, "NONE"),
            ordinate: if kind == FunctionType::Coherence {
                Values::Real(vec![0.9; 4])
            } else {
                Values::Complex((0..4).map(|k| c64::new(k as f64, 1.0)).collect())
            },
            encoding: Encoding::Ascii,
        })
    }

    fn file(records: Vec<Record>) -> Vec<(PathBuf, Vec<Record>)> {
        vec![(PathBuf::from("f.uff"), records)]
    }

    /// In space every direction of +-1..+-6 is a response; on a beam only the bending ones.
    #[test]
    fn responses_in_space_take_every_direction() {
        let records = || {
            vec![
                function(FunctionType::Frf, 1, 1, 12, "m/s^2/N"),
                function(FunctionType::Frf, 2, -4, 12, "m/s^2/N"),
            ]
        };
        let u = frfs_of(&file(records()), None, Responses::Space).unwrap();
        let directions: Vec<i32> = u.channels.iter().map(|c| c.direction).collect();
        assert_eq!(directions, [1, -4]);
        assert!(matches!(
            frfs_of(&file(records()), None, Responses::Bending).unwrap_err(),
            UffInputError::NotBending { direction: 1, .. }
        ));
        let seven = vec![function(FunctionType::Frf, 1, 7, 12, "m/s^2/N")];
        assert_eq!(
            frfs_of(&file(seven), None, Responses::Space)
                .unwrap_err()
                .to_string(),
            "f.uff: record 1: response node 1 direction 7 is not a direction in space; allowed: +-1, +-2, +-3 (translation X, Y, Z), +-4, +-5, +-6 (rotation about X, Y, Z)"
        );
    }

    #[test]
    fn frfs_signs_quantity_and_coherence() {
        let records = vec![
            function(FunctionType::Frf, 1, 2, 0, "m/s^2/N"),
            function(FunctionType::Frf, 2, -2, 0, "m/s^2/N"),
            function(FunctionType::Coherence, 1, 2, 0, "NONE"),
            function(FunctionType::Coherence, 2, -2, 0, "NONE"),
        ];
        let u = frfs(&file(records), None).unwrap();
        assert_eq!(u.set.quantity, Quantity::Acceleration);
        assert_eq!(u.set.frequencies_hz, vec![0.0, 0.5, 1.0, 1.5]);
        assert_eq!(u.set.responses[0][3], c64::new(3.0, 1.0));
        assert_eq!(u.set.responses[1][3], c64::new(-3.0, -1.0));
        assert_eq!(u.set.coherence, Some(vec![vec![0.9; 4]; 2]));
        assert_eq!(u.reference, (100, 2));
        // Data type 11 wins over the units label; a given quantity over both.
        let v = frfs(
            &file(vec![function(FunctionType::Frf, 1, 3, 11, "x")]),
            None,
        )
        .unwrap();
        assert_eq!(v.set.quantity, Quantity::Velocity);
        assert_eq!(v.set.coherence, None);
        let d = frfs(
            &file(vec![function(FunctionType::Frf, 1, 3, 11, "x")]),
            Some(Quantity::Displacement),
        )
        .unwrap();
        assert_eq!(d.set.quantity, Quantity::Displacement);
    }

    #[test]
    fn refusals_name_the_record() {
        let err = |records| frfs(&file(records), None).unwrap_err();
        // A record of no point has no axis to be uneven: it says so.
        for abscissa in [
            Abscissa::Uneven(Vec::new()),
            Abscissa::Even {
                start: 0.0,
                step: 0.5,
            },
        ] {
            let mut empty = function(FunctionType::Frf, 1, 2, 12, "m/s^2/N");
            if let Record::Function(f) = &mut empty {
                f.abscissa = abscissa;
                f.ordinate = Values::Complex(Vec::new());
            }
            assert_eq!(
                err(vec![empty]).to_string(),
                "f.uff: record 1 has 0 point(s): an FRF needs at least two frequency lines"
            );
        }
        assert!(matches!(
            err(vec![function(FunctionType::Coherence, 1, 2, 0, "NONE")]),
            UffInputError::NoFrf { .. }
        ));
        assert!(matches!(
            err(vec![function(FunctionType::Frf, 1, 2, 0, "V/N")]),
            UffInputError::UnknownQuantity { record: 1, .. }
        ));
        assert!(matches!(
            err(vec![
                function(FunctionType::Frf, 1, 2, 12, "m/s^2/N"),
                function(FunctionType::Frf, 2, 2, 12, "g/N"),
            ]),
            UffInputError::MixedUnits { record: 2, .. }
        ));
        assert!(matches!(
            err(vec![
                function(FunctionType::Frf, 1, 2, 12, "m/s^2/N"),
                function(FunctionType::Frf, 1, -2, 12, "m/s^2/N"),
            ]),
            UffInputError::DuplicateResponse {
                record: 2,
                first_record: 1,
                ..
            }
        ));
        assert!(matches!(
            err(vec![function(FunctionType::Frf, 1, 1, 12, "m/s^2/N")]),
            UffInputError::NotBending { direction: 1, .. }
        ));
        let mut other = function(FunctionType::Frf, 2, 2, 12, "m/s^2/N");
        if let Record::Function(f) = &mut other {
            f.reference.node = 7;
        }
        assert!(matches!(
            err(vec![
                function(FunctionType::Frf, 1, 2, 12, "m/s^2/N"),
                other
            ]),
            UffInputError::MixedReference {
                record: 2,
                node: 7,
                ..
            }
        ));
        let mut other = function(FunctionType::Frf, 2, 2, 12, "m/s^2/N");
        if let Record::Function(f) = &mut other {
            f.abscissa = Abscissa::Even {
                start: 0.0,
                step: 0.25,
            };
        }
        assert!(matches!(
            err(vec![
                function(FunctionType::Frf, 1, 2, 12, "m/s^2/N"),
                other
            ]),
            UffInputError::MixedAxis { record: 2, .. }
        ));
    }

    #[test]
    fn positions_from_the_geometry() {
        let u = frfs(
            &file(vec![
                function(FunctionType::Frf, 4, 2, 12, "m/s^2/N"),
                function(FunctionType::Frf, 1, 2, 12, "m/s^2/N"),
            ]),
            None,
        )
        .unwrap();
        let node = |label, x| crate::uff::Node {
            label,
            definition_cs: 0,
            displacement_cs: 0,
            color: 0,
            coordinates: [x, 0.0, 0.0],
        };
        let nodes = vec![Nodes {
            format: crate::uff::NodeFormat::Single15,
            nodes: vec![node(1, 0.5), node(4, 0.028)],
        }];
        let g = Path::new("g.uff");
        assert_eq!(positions(&u.channels, &nodes, g).unwrap(), vec![0.028, 0.5]);
        let missing = vec![Nodes {
            format: crate::uff::NodeFormat::Single15,
            nodes: vec![node(1, 0.5)],
        }];
        let e = positions(&u.channels, &missing, g).unwrap_err();
        assert_eq!(
            e.to_string(),
            "g.uff: response node 4 (record 1 of f.uff) is not in the geometry; its nodes: 1"
        );
        assert!(matches!(
            positions(&u.channels, &[], g),
            Err(UffInputError::NoGeometry { .. })
        ));
        // A node given twice: at the same place it is one node, at another it is refused.
        let twice = |x| {
            vec![Nodes {
                format: crate::uff::NodeFormat::Single15,
                nodes: vec![node(1, 0.5), node(4, 0.028), node(1, x)],
            }]
        };
        assert_eq!(
            positions(&u.channels, &twice(0.5), g).unwrap(),
            vec![0.028, 0.5]
        );
        assert_eq!(
            positions(&u.channels, &twice(0.7), g)
                .unwrap_err()
                .to_string(),
            "g.uff: node 1 is given twice, at [0.5, 0.0, 0.0] and at [0.7, 0.0, 0.0]: a node has one place; remove or renumber one of them"
        );
    }
}
