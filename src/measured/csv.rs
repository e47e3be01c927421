//! The measured-modes CSV, one row per (mode, measured point):
//!
//! ```text
//! mode,frequency_hz,node,dof,value        a DOF of a node (beam chains)
//! 1,150.2,0,w,0.8812
//! mode,frequency_hz,x,dof,value           a position along the chain, m (between nodes too)
//! 1,18.8,0.176,w,0.31
//! mode,frequency_hz,label,value           a DOF label or a declared sensor's label
//! 1,150.2,7:w,0.8812
//! mode,frequency_hz,x,y,z,dof,value       coordinates in space, m, and a direction x|y|z
//! 1,150.2,0.3,0.01,0.02,z,0.8812          (the nearest DOF of an external model)
//! ```
//! `mode` is the deformable mode number r (1 = first elastic mode). A point absent for a mode
//! is not identified (the paper's NF). Every row of a mode carries the same frequency. A row may
//! leave the point and the value empty to give a frequency alone; a mode still needs at least
//! one shape row. Optional columns after `value`, in any order: `damping_ratio` and `mpc`
//! (modal phase collinearity), constant within a mode, as `jointid extract` writes them; and
//! the standard errors of the data: `frequency_std` (Hz) and `damping_std` (same unit as
//! `damping_ratio`), constant within a mode, and `value_std` on every shape row (same
//! normalisation as `value`). A standard error is finite and >= 0 (`frequency_std` > 0, and a
//! mode's `value_std` not all 0); `frequency_std` and `value_std` are given for every mode or
//! for none, `value_std` on every shape row of a mode or on none, and `damping_std` only
//! where `damping_ratio` is. Relative to what they qualify they lie in [`RELATIVE_STD`](crate::input::RELATIVE_STD):
//! `frequency_std` from 1e-12 to 1 times `frequency_hz`, a non-zero `value_std` from 1e-12 to
//! 1 times the mode's largest |value|, a non-zero `damping_std` from 1e-12 times
//! `damping_ratio` to 1.
//!
//! [`Csv`] reads it as one of the [`Format`]s; points are resolved by [`locate`]; the writer
//! ([`MeasuredModes::write_csv`]) chooses the location form the points allow.
//!
//! May import: the measured-modes model, its error, point resolution and format trait.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use super::error::MeasuredError;
use super::format::Format;
use super::locate::{Location, locate};
use super::modes::{MAX_FREQUENCY_HZ, MAX_MODE, MeasuredMode, MeasuredModes};
use crate::input::{Number, RELATIVE_STD, relative_std_in_range};
use crate::structure::{Direction, Observation, Structure};

/// Optional per-mode columns, then the optional per-row column.
const OPTIONAL: [&str; 5] = [
    "damping_ratio",
    "mpc",
    "frequency_std",
    "damping_std",
    "value_std",
];

/// A shape row read: the point, its value, its line and its standard error.
type ShapeRow = (Observation, f64, u64, Option<f64>);

struct Pending {
    frequency_hz: f64,
    first_line: u64,
    /// The per-mode optional values, in the order of [`OPTIONAL`] (the last unused).
    per_mode: [Option<f64>; 4],
    shape: BTreeMap<String, ShapeRow>,
}

/// The range of an optional column's values, for the message.
fn check_optional(name: &str, text: &str) -> Result<f64, String> {
    let v = text.parse::<f64>().ok().filter(|v| v.is_finite());
    let (ok, allowed) = match name {
        "damping_ratio" | "mpc" => (
            v.is_some_and(|v| (0.0..=1.0).contains(&v)),
            "a number from 0 to 1",
        ),
        "frequency_std" => (v.is_some_and(|v| v > 0.0), "a finite number > 0 (Hz)"),
        _ => (v.is_some_and(|v| v >= 0.0), "a finite number >= 0"),
    };
    match v {
        Some(v) if ok => Ok(v),
        _ => Err(format!(
            "{name} = `{text}` is invalid: it must be {allowed}"
        )),
    }
}

struct Header {
    location: Location,
    optional: Vec<(usize, &'static str)>,
    value: usize,
}

fn header(fields: &[&str]) -> Result<Header, String> {
    let allowed = "the header must be `mode,frequency_hz,` then `node,dof`, `x,dof`, `x,y,z,dof` or `label`, then `value`, then optionally any of `damping_ratio`, `mpc`, `frequency_std`, `damping_std`, `value_std`";
    let location = match fields.get(2).copied() {
        Some("node") => Location::Node,
        Some("x") if fields.get(3) == Some(&"y") => Location::Space,
        Some("x") => Location::Position,
        Some("label") => Location::Label,
        _ => return Err(format!("{allowed}; found `{}`", fields.join(","))),
    };
    let value = 2 + location.fields().len();
    let expected_start: Vec<&str> = ["mode", "frequency_hz"]
        .iter()
        .chain(location.fields())
        .chain(&["value"])
        .copied()
        .collect();
    if fields.len() < expected_start.len() || fields[..expected_start.len()] != expected_start[..] {
        return Err(format!("{allowed}; found `{}`", fields.join(",")));
    }
    let mut optional = Vec::new();
    for (i, f) in fields.iter().enumerate().skip(expected_start.len()) {
        match OPTIONAL.iter().find(|o| *o == f) {
            Some(o) if !optional.iter().any(|(_, seen)| seen == o) => optional.push((i, *o)),
            _ => {
                return Err(format!(
                    "{allowed}; found `{}` (column `{f}`)",
                    fields.join(",")
                ));
            }
        }
    }
    Ok(Header {
        location,
        optional,
        value,
    })
}

/// The measured-modes CSV as a [`Format`].
pub struct Csv;

impl Format for Csv {
    fn name(&self) -> &'static str {
        "csv"
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["csv"]
    }

    fn signature(&self) -> &'static str {
        "a header starting `mode,frequency_hz`"
    }

    /// The first line that is neither blank nor a `#` comment starts with the field `mode`.
    fn recognises(&self, bytes: &[u8]) -> bool {
        let text = String::from_utf8_lossy(bytes);
        let text = text.trim_start_matches('\u{feff}');
        text.lines()
            .map(str::trim)
            .find(|l| !l.is_empty() && !l.starts_with('#'))
            .is_some_and(|l| l.split(',').next().map(str::trim) == Some("mode"))
    }

    fn read(
        &self,
        bytes: &[u8],
        file: &Path,
        structure: &Structure,
    ) -> Result<MeasuredModes, MeasuredError> {
        let err = |line: u64, message: String| MeasuredError::Line {
            file: file.to_path_buf(),
            line,
            message: crate::input::safe::clip_quotes(message),
        };
        let mut csv = ::csv::ReaderBuilder::new()
            .trim(::csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(bytes);
        let fields: Vec<String> = csv
            .headers()
            .map_err(|e| err(1, e.to_string()))?
            .iter()
            .map(String::from)
            .collect();
        let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
        let header = header(&fields).map_err(|m| err(1, m))?;
        let mut pending: BTreeMap<usize, Pending> = BTreeMap::new();
        for record in csv.records() {
            let record = record.map_err(|e| {
                let line = e.position().map(|p| p.line()).unwrap_or(0);
                err(line, e.to_string())
            })?;
            let line = record.position().map(|p| p.line()).unwrap_or(0);
            row(&mut pending, &record, line, &header, structure).map_err(|m| err(line, m))?;
        }
        if pending.is_empty() {
            return Err(MeasuredError::Empty {
                file: file.to_path_buf(),
            });
        }
        let modes = pending
            .into_iter()
            .map(|(mode, p)| {
                if p.shape.is_empty() {
                    return Err(err(
                        p.first_line,
                        format!(
                            "mode {mode} has no shape rows: at least one point and value is needed"
                        ),
                    ));
                }
                mode_of(mode, p).map_err(|(line, m)| err(line, m))
            })
            .collect::<Result<Vec<_>, _>>()?;
        all_or_none(&modes).map_err(|m| MeasuredError::Line {
            file: file.to_path_buf(),
            line: 1,
            message: m,
        })?;
        Ok(MeasuredModes::new(modes))
    }
}

/// The mode read, its shape rows' standard errors checked (all or none, not all zero), its
/// damping_std only beside a damping_ratio; an error gives its line.
fn mode_of(mode: usize, p: Pending) -> Result<MeasuredMode, (u64, String)> {
    let [damping_ratio, mpc, frequency_std, damping_std] = p.per_mode;
    if damping_std.is_some() && damping_ratio.is_none() {
        return Err((
            p.first_line,
            format!(
                "mode {mode} has a damping_std but no damping_ratio: a standard error needs the value it qualifies"
            ),
        ));
    }
    let given: Vec<&ShapeRow> = p.shape.values().filter(|r| r.3.is_some()).collect();
    let mut m = if given.is_empty() {
        let (points, values) = p.shape.into_values().map(|(o, v, _, _)| (o, v)).unzip();
        MeasuredMode::new(mode, p.frequency_hz, points, values)
    } else {
        if let Some(missing) = p.shape.values().find(|r| r.3.is_none()) {
            return Err((
                missing.2,
                format!(
                    "mode {mode}, point {} has no value_std, but line {} gives one: give value_std on every shape row of a mode or on none",
                    missing.0.label, given[0].2
                ),
            ));
        }
        let peak = p.shape.values().fold(0.0_f64, |a, r| a.max(r.1.abs()));
        if let Some(row) = given.iter().filter(|_| peak > 0.0).find(|r| {
            r.3.is_some_and(|s| s != 0.0 && !relative_std_in_range(s, peak))
        }) {
            return Err((
                row.2,
                format!(
                    "value_std = {} is invalid: it must be 0 or from {} to {} times the mode's largest |value| ({})",
                    Number(row.3.unwrap_or_default()),
                    Number(RELATIVE_STD.0),
                    Number(RELATIVE_STD.1),
                    Number(peak)
                ),
            ));
        }
        if given.iter().all(|r| r.3 == Some(0.0)) {
            return Err((
                p.first_line,
                format!(
                    "mode {mode} has value_std 0 on every point: that claims an exact shape; give the measurement's standard errors or leave the column out"
                ),
            ));
        }
        let rows = p
            .shape
            .into_values()
            .map(|(o, v, _, s)| (o, v, s.unwrap_or(0.0)))
            .collect();
        MeasuredMode::with_value_std(mode, p.frequency_hz, rows)
    };
    if let (Some(zeta), Some(std)) = (damping_ratio, damping_std)
        && std != 0.0
        && !(std >= RELATIVE_STD.0 * zeta && std <= RELATIVE_STD.1)
    {
        return Err((
            p.first_line,
            format!(
                "damping_std = {} is invalid: it must be 0 or from {} times damping_ratio ({}) to 1",
                Number(std),
                Number(RELATIVE_STD.0),
                Number(zeta)
            ),
        ));
    }
    m.damping_ratio = damping_ratio;
    m.mpc = mpc;
    m.frequency_std = frequency_std;
    m.damping_std = damping_std;
    Ok(m)
}

/// frequency_std and value_std are given for every mode or for none.
fn all_or_none(modes: &[MeasuredMode]) -> Result<(), String> {
    type Has = fn(&MeasuredMode) -> bool;
    let columns: [(&str, Has); 2] = [
        ("frequency_std", |m| m.frequency_std.is_some()),
        ("value_std", |m| m.value_std.is_some()),
    ];
    for (name, has) in columns {
        let with: Vec<String> = modes
            .iter()
            .filter(|m| has(m))
            .map(|m| m.mode.to_string())
            .collect();
        if let Some(without) = modes.iter().find(|m| !has(m))
            && !with.is_empty()
        {
            return Err(format!(
                "{name} is given for mode(s) {} but not for mode {}: give it for every mode or for none",
                with.join(","),
                without.mode
            ));
        }
    }
    Ok(())
}

/// Adds the row on `line` to the modes read so far, or says what is wrong with it.
fn row(
    pending: &mut BTreeMap<usize, Pending>,
    record: &::csv::StringRecord,
    line: u64,
    header: &Header,
    structure: &Structure,
) -> Result<(), String> {
    let mode: usize = match record[0].parse::<usize>() {
        Ok(r) if (1..=MAX_MODE).contains(&r) => r,
        _ => {
            return Err(format!(
                "mode = `{}` is invalid: it must be an integer from 1 (the first elastic mode) to {MAX_MODE}",
                &record[0]
            ));
        }
    };
    let frequency_hz = positive(&record[1], "frequency_hz", "Hz", MAX_FREQUENCY_HZ)?;
    let mut value_std = None;
    let mut per_mode: Vec<(usize, &str, f64)> = Vec::new();
    for &(i, name) in &header.optional {
        let text = &record[i];
        if text.is_empty() {
            continue;
        }
        let v = check_optional(name, text)?;
        if name == "frequency_std" && !relative_std_in_range(v, frequency_hz) {
            return Err(format!(
                "frequency_std = {} is invalid: it must be from {} to {} times frequency_hz ({} Hz)",
                Number(v),
                Number(RELATIVE_STD.0),
                Number(RELATIVE_STD.1),
                Number(frequency_hz)
            ));
        }
        match OPTIONAL.iter().position(|o| *o == name) {
            Some(slot) if slot < 4 => per_mode.push((slot, name, v)),
            _ => value_std = Some(v),
        }
    }
    let entry = pending.entry(mode).or_insert_with(|| Pending {
        frequency_hz,
        first_line: line,
        per_mode: [None; 4],
        shape: BTreeMap::new(),
    });
    if entry.frequency_hz != frequency_hz {
        return Err(format!(
            "mode {mode} has frequency_hz = {frequency_hz} here but {} on line {}: all rows of a mode must carry the same frequency",
            entry.frequency_hz, entry.first_line
        ));
    }
    for (slot, name, b) in per_mode {
        match entry.per_mode[slot] {
            Some(a) if a != b => {
                return Err(format!(
                    "mode {mode} has {name} = {b} here but {a} above: it is one value per mode"
                ));
            }
            _ => entry.per_mode[slot] = Some(b),
        }
    }
    let location: Vec<&str> = (2..header.value).map(|i| &record[i]).collect();
    let value_text = &record[header.value];
    if location.iter().all(|f| f.is_empty()) && value_text.is_empty() {
        if let Some(v) = value_std {
            return Err(format!(
                "value_std = {v} on a row without a point and value: a standard error needs the value it qualifies"
            ));
        }
        return Ok(());
    }
    let point = locate(header.location, &location, structure)?;
    let value: f64 = match value_text.parse::<f64>() {
        Ok(v) if v.is_finite() => v,
        _ => {
            return Err(format!(
                "value = `{value_text}` is invalid: it must be a finite number"
            ));
        }
    };
    let label = point.label.clone();
    if let Some((_, _, first, _)) = entry
        .shape
        .insert(label.clone(), (point, value, line, value_std))
    {
        return Err(format!(
            "mode {mode}, point {label} is given twice (first on line {first})"
        ));
    }
    Ok(())
}

impl MeasuredModes {
    /// Writes the modes in the file format above: by label where every point is a sensor the
    /// model declares, by node where every point is a node's DOF, by position where every
    /// point lies on a chain, by label otherwise.
    pub fn write_csv<W: std::io::Write>(
        &self,
        out: W,
        structure: &Structure,
    ) -> Result<(), ::csv::Error> {
        let points = self.points();
        let node_of = |o: &Observation| o.single_dof().and_then(|d| structure.dofs.get(d).node);
        let declared = |o: &Observation| structure.sensors.iter().any(|s| s == o);
        let location = if !structure.sensors.is_empty() && points.iter().all(declared) {
            Location::Label
        } else if points.iter().all(|o| node_of(o).is_some()) {
            Location::Node
        } else if !structure.dofs.lines().is_empty()
            && points
                .iter()
                .all(|o| matches!(o.direction, Direction::W | Direction::Theta))
        {
            Location::Position
        } else {
            Location::Label
        };
        let any = |has: fn(&MeasuredMode) -> bool| self.modes().iter().any(has);
        let damping = any(|m| m.damping_ratio.is_some());
        let mpc = any(|m| m.mpc.is_some());
        let frequency_std = any(|m| m.frequency_std.is_some());
        let damping_std = any(|m| m.damping_std.is_some());
        let value_std = any(|m| m.value_std.is_some());
        let mut w = ::csv::Writer::from_writer(out);
        let mut head: Vec<&str> = vec!["mode", "frequency_hz"];
        head.extend(location.fields());
        head.push("value");
        if damping {
            head.push("damping_ratio");
        }
        if mpc {
            head.push("mpc");
        }
        for (on, name) in [
            (frequency_std, "frequency_std"),
            (damping_std, "damping_std"),
            (value_std, "value_std"),
        ] {
            if on {
                head.push(name);
            }
        }
        w.write_record(&head)?;
        // Field by field from one scratch string: no allocation per row (a 212,562-DOF
        // model's modes are millions of rows).
        let mut text = String::new();
        let mut number = |w: &mut ::csv::Writer<W>, v: Option<f64>| {
            text.clear();
            if let Some(v) = v {
                write!(text, "{v}").expect("formatting into a string");
            }
            w.write_field(&text)
        };
        for m in self.modes() {
            let (mode, frequency) = (m.mode.to_string(), m.frequency_hz.to_string());
            for (j, (o, &v)) in m.points.iter().zip(&m.values).enumerate() {
                w.write_field(&mode)?;
                w.write_field(&frequency)?;
                match location {
                    Location::Node => {
                        match node_of(o) {
                            Some(n) => w.write_field(n.to_string())?,
                            None => w.write_field("")?,
                        }
                        w.write_field(o.direction.name())?;
                    }
                    Location::Position => {
                        number(&mut w, Some(o.x))?;
                        w.write_field(o.direction.name())?;
                    }
                    Location::Space => {
                        let at = o.single_dof().map(|d| structure.dofs.get(d).position);
                        for c in at.unwrap_or([f64::NAN; 3]) {
                            number(&mut w, Some(c))?;
                        }
                        w.write_field(o.direction.name())?;
                    }
                    Location::Label => w.write_field(&o.label)?,
                }
                number(&mut w, Some(v))?;
                if damping {
                    number(&mut w, m.damping_ratio)?;
                }
                if mpc {
                    number(&mut w, m.mpc)?;
                }
                if frequency_std {
                    number(&mut w, m.frequency_std)?;
                }
                if damping_std {
                    number(&mut w, m.damping_std)?;
                }
                if value_std {
                    number(&mut w, m.value_std.as_ref().map(|s| s[j]))?;
                }
                w.write_record(None::<&[u8]>)?;
            }
        }
        w.flush()?;
        Ok(())
    }
}

fn positive(text: &str, name: &str, unit: &str, max: f64) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= max => Ok(v),
        _ => Err(format!(
            "{name} = `{text}` is invalid: it must be a number > 0 and at most {max:e} ({unit})"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    fn read_with(text: &str, structure: &Structure) -> Result<MeasuredModes, String> {
        MeasuredModes::from_reader(text.as_bytes(), Path::new("d.csv"), structure)
            .map_err(|e| e.to_string())
    }

    fn read(text: &str) -> Result<MeasuredModes, String> {
        read_with(text, &paper_model(1e7, 1e4))
    }

    fn dofs(m: &MeasuredMode) -> Vec<usize> {
        m.points.iter().map(|p| p.single_dof().unwrap()).collect()
    }

    #[test]
    fn reads_modes_sorted_with_their_dofs() {
        let m = read("mode,frequency_hz,node,dof,value\n2,400,3,theta,1.5\n1,150.2,0,theta,-3.1\n1,150.2,0,w,0.88\n2,400,,,\n").unwrap();
        assert_eq!(m.modes().len(), 2);
        let first = &m.modes()[0];
        assert_eq!((first.mode, first.frequency_hz), (1, 150.2));
        assert_eq!(dofs(first), vec![0, 1]);
        assert_eq!(first.values, vec![0.88, -3.1]);
        assert_eq!(first.points[1].label, "0:theta");
        assert_eq!(dofs(m.get(2).unwrap()), vec![7]);
    }

    #[test]
    fn a_position_on_a_node_reads_that_node_and_between_nodes_interpolates() {
        let by_node =
            read("mode,frequency_hz,node,dof,value\n1,150,3,w,0.5\n1,150,3,theta,2\n").unwrap();
        // Node 3 of the 0.2 m / 7-element first beam sits at x = 3 * 0.2 / 7.
        let x = 3.0 * 0.2 / 7.0;
        let by_x = read(&format!(
            "mode,frequency_hz,x,dof,value\n1,150,{x},w,0.5\n1,150,{x},theta,2\n"
        ))
        .unwrap();
        assert_eq!(by_node.modes()[0].points, by_x.modes()[0].points);
        let between = read("mode,frequency_hz,x,dof,value\n1,150,0.1,w,0.5\n").unwrap();
        let p = &between.modes()[0].points[0];
        assert_eq!(p.label, "x=0.1:w");
        assert_eq!(p.terms.len(), 4);
        // Interpolation reproduces a rigid motion w = 1 + 2 x exactly.
        let rigid: Vec<f64> = (0..38)
            .map(|d| {
                let node = d / 2;
                let xn = if node < 8 {
                    node as f64 * 0.2 / 7.0
                } else {
                    0.2 + (node - 8) as f64 * 0.03
                };
                if d % 2 == 0 { 1.0 + 2.0 * xn } else { 2.0 }
            })
            .collect();
        assert!((p.read(&rigid) - 1.2).abs() < 1e-14);
    }

    #[test]
    fn labels_and_optional_columns_are_read() {
        let m = read("mode,frequency_hz,label,value,damping_ratio,mpc\n1,150,5:theta,1.5,0.01,0.99\n1,150,2:w,1,0.01,\n").unwrap();
        let mode = &m.modes()[0];
        assert_eq!(dofs(mode), vec![4, 11]);
        assert_eq!((mode.damping_ratio, mode.mpc), (Some(0.01), Some(0.99)));
        let e = read("mode,frequency_hz,label,value,damping_ratio\n1,150,5:theta,1.5,0.01\n1,150,2:w,1,0.02\n").unwrap_err();
        assert_eq!(
            e,
            "d.csv:3: mode 1 has damping_ratio = 0.02 here but 0.01 above: it is one value per mode"
        );
        let e = read("mode,frequency_hz,label,value\n1,150,bolt,1.5\n").unwrap_err();
        assert_eq!(
            e,
            "d.csv:2: label = `bolt` is invalid: it is neither a DOF of the model nor a declared sensor"
        );
    }

    #[test]
    fn each_bad_line_names_its_line_and_what_is_allowed() {
        let h = "mode,frequency_hz,node,dof,value\n";
        let cases = [
            (
                "1,150,0,phi,1.0\n",
                "d.csv:2: dof = `phi` is invalid: it must be `w` or `theta` (or x, y, z, rx, ry, rz for an external model)",
            ),
            (
                "1,150,19,w,1.0\n",
                "d.csv:2: node = `19` is invalid: the model has nodes 0 to 18",
            ),
            (
                "1,150,0,w,1.0\n1,150,0,w,2.0\n",
                "d.csv:3: mode 1, point 0:w is given twice (first on line 2)",
            ),
            (
                "1,150,0,w,1.0\n1,151,1,w,2.0\n",
                "d.csv:3: mode 1 has frequency_hz = 151 here but 150 on line 2: all rows of a mode must carry the same frequency",
            ),
            (
                "1,150,0,w,inf\n",
                "d.csv:2: value = `inf` is invalid: it must be a finite number",
            ),
            (
                "1,NaN,0,w,1\n",
                "d.csv:2: frequency_hz = `NaN` is invalid: it must be a number > 0 and at most 1e9 (Hz)",
            ),
            (
                "1,1e200,0,w,1\n",
                "d.csv:2: frequency_hz = `1e200` is invalid: it must be a number > 0 and at most 1e9 (Hz)",
            ),
            (
                "0,150,0,w,1\n",
                "d.csv:2: mode = `0` is invalid: it must be an integer from 1 (the first elastic mode) to 100000",
            ),
            (
                "18446744073709551615,150,0,w,1\n",
                "d.csv:2: mode = `18446744073709551615` is invalid: it must be an integer from 1 (the first elastic mode) to 100000",
            ),
            (
                "1,150,0,w,1\n2,300,,,\n",
                "d.csv:3: mode 2 has no shape rows: at least one point and value is needed",
            ),
        ];
        for (body, message) in cases {
            assert_eq!(
                read(&format!("{h}{body}")).unwrap_err(),
                message,
                "for {body:?}"
            );
        }
        assert!(
            read("mode,freq,node,dof,value\n")
                .unwrap_err()
                .starts_with("d.csv:1: the header must be")
        );
        assert!(
            read("mode,frequency_hz,node,dof,value,colour\n")
                .unwrap_err()
                .ends_with("(column `colour`)")
        );
        assert_eq!(
            read(h).unwrap_err(),
            "d.csv: no measured mode (only a header, or an empty file)"
        );
        assert!(
            read(&format!("{h}1,150,0,w\n"))
                .unwrap_err()
                .starts_with("d.csv:2: ")
        );
        assert_eq!(
            read("mode,frequency_hz,x,dof,value\n1,150,0.6,w,1\n").unwrap_err(),
            "d.csv:2: x = 0.6 m is outside the chain, which spans 0 to 0.5 m"
        );
    }

    /// The standard-error columns: read with their points, and every misuse refused naming
    /// the line and the column.
    #[test]
    fn standard_errors_are_read_and_checked() {
        let h =
            "mode,frequency_hz,node,dof,value,damping_ratio,frequency_std,damping_std,value_std\n";
        let m = read(&format!(
            "{h}1,150,3,w,0.5,0.01,0.02,0.001,0.004\n1,150,0,w,1,0.01,0.02,0.001,0\n"
        ))
        .unwrap();
        let mode = &m.modes()[0];
        assert_eq!(dofs(mode), vec![0, 6]);
        assert_eq!(mode.value_std, Some(vec![0.0, 0.004]));
        assert_eq!(
            (mode.frequency_std, mode.damping_std),
            (Some(0.02), Some(0.001))
        );
        assert!(m.has_std());
        let cases = [
            (
                "1,150,0,w,1,0.01,0.02,0.001,-0.1\n",
                "d.csv:2: value_std = `-0.1` is invalid: it must be a finite number >= 0",
            ),
            (
                "1,150,0,w,1,0.01,NaN,0.001,0.1\n",
                "d.csv:2: frequency_std = `NaN` is invalid: it must be a finite number > 0 (Hz)",
            ),
            (
                "1,150,0,w,1,0.01,0,0.001,0.1\n",
                "d.csv:2: frequency_std = `0` is invalid: it must be a finite number > 0 (Hz)",
            ),
            (
                "1,150,0,w,1,0.01,0.02,inf,0.1\n",
                "d.csv:2: damping_std = `inf` is invalid: it must be a finite number >= 0",
            ),
            (
                "1,150,0,w,1,0.01,0.02,0.001,0.1\n1,150,3,w,0.5,0.01,0.02,0.001,\n",
                "d.csv:3: mode 1, point 3:w has no value_std, but line 2 gives one: give value_std on every shape row of a mode or on none",
            ),
            (
                "1,150,0,w,1,,0.02,0.001,0.1\n",
                "d.csv:2: mode 1 has a damping_std but no damping_ratio: a standard error needs the value it qualifies",
            ),
            (
                "1,150,0,w,1,0.01,0.02,0.001,0.1\n1,150,,,,0.01,0.02,0.001,0.1\n",
                "d.csv:3: value_std = 0.1 on a row without a point and value: a standard error needs the value it qualifies",
            ),
            (
                "1,150,0,w,1,0.01,0.02,0.001,0\n",
                "d.csv:2: mode 1 has value_std 0 on every point: that claims an exact shape; give the measurement's standard errors or leave the column out",
            ),
            (
                "1,150,0,w,1,0.01,0.02,0.001,0.1\n2,400,0,w,1,0.01,,,0.1\n",
                "d.csv:1: frequency_std is given for mode(s) 1 but not for mode 2: give it for every mode or for none",
            ),
            // Relative to what they qualify, within 1e-12 to 1: beyond, the propagated errors
            // were inf, and a chi^2 weighted by them inf or NaN, with exit 0.
            (
                "1,150,0,w,1,0.01,1e308,0.001,0.1\n",
                "d.csv:2: frequency_std = 1e308 is invalid: it must be from 1e-12 to 1 times frequency_hz (150 Hz)",
            ),
            (
                "1,150,0,w,1,0.01,1e-300,0.001,0.1\n",
                "d.csv:2: frequency_std = 1e-300 is invalid: it must be from 1e-12 to 1 times frequency_hz (150 Hz)",
            ),
            (
                "1,150,0,w,1,0.01,0.02,0.001,0.1\n1,150,3,w,0.5,0.01,0.02,0.001,1e-300\n",
                "d.csv:3: value_std = 1e-300 is invalid: it must be 0 or from 1e-12 to 1 times the mode's largest |value| (1)",
            ),
            (
                "1,150,0,w,1,0.01,0.02,0.001,1e308\n",
                "d.csv:2: value_std = 1e308 is invalid: it must be 0 or from 1e-12 to 1 times the mode's largest |value| (1)",
            ),
            (
                "1,150,0,w,1,0.01,0.02,2,0.1\n",
                "d.csv:2: damping_std = 2 is invalid: it must be 0 or from 1e-12 times damping_ratio (0.01) to 1",
            ),
        ];
        for (body, message) in cases {
            assert_eq!(
                read(&format!("{h}{body}")).unwrap_err(),
                message,
                "for {body:?}"
            );
        }
    }

    /// A file not named *.csv is read as CSV when its content is; otherwise the error lists
    /// the formats.
    #[test]
    fn the_csv_is_chosen_by_its_name_or_its_header() {
        assert!(Csv.recognises(b"\xef\xbb\xbf# from the rig\n\n mode , frequency_hz,x\n"));
        assert!(!Csv.recognises(b"{\"modes\": []}"));
        assert!(!Csv.recognises(b""));
        let text = "mode,frequency_hz,node,dof,value\n1,150,0,w,1\n";
        let model = paper_model(1e7, 1e4);
        let from = |name: &str, text: &str| {
            MeasuredModes::from_reader(text.as_bytes(), Path::new(name), &model)
                .map_err(|e| e.to_string())
        };
        assert_eq!(from("d.txt", text), read(text));
        // The extension wins over the content: a CSV's own message.
        let e = from("d.CSV", "{}").unwrap_err();
        assert!(e.starts_with("d.CSV:1: the header must be"), "{e}");
        assert_eq!(
            from("d.json", "{}").unwrap_err(),
            "d.json: the format of these measured modes is not known: the formats known are csv \
             (*.csv, or a header starting `mode,frequency_hz`)"
        );
    }

    #[test]
    fn write_then_read_round_trips_in_every_location_form() {
        let model = paper_model(1e7, 1e4);
        let on_nodes: Vec<Observation> = [0, 5, 36]
            .iter()
            .map(|&d| Observation::dof(&model.dofs, d))
            .collect();
        let between = vec![
            model.dofs.at_x(0.1, Direction::W).unwrap(),
            model.dofs.at_x(0.45, Direction::Theta).unwrap(),
        ];
        for points in [on_nodes, between] {
            let mut mode = MeasuredMode::new(3, 812.25, points, vec![0.1, -1e-7, 3.0]);
            mode.values.truncate(mode.points.len());
            mode.damping_ratio = Some(0.0125);
            let without = MeasuredModes::new(vec![mode.clone()]);
            mode.frequency_std = Some(0.25);
            mode.value_std = Some((0..mode.points.len()).map(|j| 0.01 * j as f64).collect());
            let m = MeasuredModes::new(vec![mode]);
            let mut buf = Vec::new();
            without.write_csv(&mut buf, &model).unwrap();
            assert!(!std::str::from_utf8(&buf).unwrap().contains("_std"));
            let mut buf = Vec::new();
            m.write_csv(&mut buf, &model).unwrap();
            assert_eq!(read(std::str::from_utf8(&buf).unwrap()).unwrap(), m);
        }
    }
}
